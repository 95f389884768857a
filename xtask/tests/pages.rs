//! The committed reproduction pages are what their commands write: each
//! test runs the experiment (seeded) and compares the page, wall-clock
//! times masked (`xtask::reproduce::stable`). Pages are generated, never
//! edited by hand; after a deliberate change, run the command and commit.
//! (`lee2011` has the same test in its module; the pages on
//! `../shared/maps` are not checked here, as CI has no shared maps.)

use xtask::reproduce::{
    demir2018, pavlicek2002_camera, same_page, siamantas2010, siamantas2010_tracking,
};

#[test]
fn siamantas2010_page_is_what_the_command_writes() {
    let page = siamantas2010::generate(None).unwrap();
    if let Err(e) = same_page("siamantas2010", &page, &[], siamantas2010::TIME_LINES) {
        panic!("{e}");
    }
}

#[test]
fn demir2018_page_is_what_the_command_writes() {
    let page = demir2018::generate(None).unwrap();
    if let Err(e) = same_page("demir2018", &page, demir2018::TIME_COLUMNS, &[]) {
        panic!("{e}");
    }
}

#[test]
fn siamantas2010_tracking_page_is_what_the_command_writes() {
    let page = siamantas2010_tracking::generate(None).unwrap();
    if let Err(e) = same_page("siamantas2010_tracking", &page, &[], &[]) {
        panic!("{e}");
    }
}

#[test]
fn pavlicek2002_camera_page_is_what_the_command_writes() {
    let page = pavlicek2002_camera::generate(None).unwrap();
    if let Err(e) = same_page("pavlicek2002-camera", &page, &[], &[]) {
        panic!("{e}");
    }
}
