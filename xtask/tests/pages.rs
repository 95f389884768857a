//! The committed reproduction pages are what their commands write: each
//! test runs the experiment (seeded) and compares the page, wall-clock
//! times masked (`xtask::reproduce::stable`). Pages are generated, never
//! edited by hand; after a deliberate change, run the command and commit.
//! (`lee2011` has the same test in its module.) The pages made on
//! `../shared/maps` (`zhang2008`'s MovingAI rooms, `pavlicek2002`,
//! `floorplans`) are checked where those maps are, and skipped, saying so,
//! where they are not (CI's fresh clone has no `../shared`).

use xtask::reproduce::{
    demir2018, pavlicek2002, pavlicek2002_camera, same_page, siamantas2010, siamantas2010_tracking,
    zhang2008,
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

/// Whether `../shared/maps` is there; says so when it is not.
fn shared_maps(page: &str) -> bool {
    let there = xtask::shared_maps().is_some();
    if !there {
        eprintln!("{page}: not checked, ../shared/maps is not there");
    }
    there
}

#[test]
fn zhang2008_page_is_what_the_command_writes() {
    if !shared_maps("zhang2008") {
        return;
    }
    let page = zhang2008::generate(None).unwrap();
    if let Err(e) = same_page("zhang2008", &page, &[], &[]) {
        panic!("{e}");
    }
}

#[test]
fn pavlicek2002_page_is_what_the_command_writes() {
    if !shared_maps("pavlicek2002") {
        return;
    }
    let page = pavlicek2002::generate(None).unwrap();
    if let Err(e) = same_page("pavlicek2002", &page, &[], &[]) {
        panic!("{e}");
    }
}

#[test]
fn floorplans_page_is_what_the_command_writes() {
    if !shared_maps("floorplans") {
        return;
    }
    let page = pavlicek2002::generate_floorplans(None).unwrap();
    if let Err(e) = same_page("floorplans", &page, &["plan ms"], &[]) {
        panic!("{e}");
    }
}

/// `docs/lanes.svg` is what `cargo xtask diagram` draws, and every box
/// names a file that exists.
#[test]
fn the_lanes_picture_is_what_the_command_draws() {
    let root = xtask::root();
    let committed = std::fs::read_to_string(root.join("docs/lanes.svg")).unwrap();
    assert_eq!(
        committed,
        xtask::diagram::lanes_svg(),
        "run `cargo xtask diagram` and commit docs/lanes.svg"
    );
    for f in xtask::diagram::files() {
        let path = root.join("crates/oxcover-planners/src").join(f);
        assert!(path.is_file(), "the picture names {f}, which is gone");
    }
}

/// `docs/efficiency.md` reads as reference: no paragraph (a line outside
/// a table) longer than about 600 characters, and no story of how a
/// figure moved (that belongs in commit messages).
#[test]
fn the_efficiency_page_reads_as_reference() {
    let page = std::fs::read_to_string(xtask::root().join("docs/efficiency.md")).unwrap();
    for line in page.lines().filter(|l| !l.starts_with('|')) {
        assert!(
            line.chars().count() <= 650,
            "a paragraph of {} characters: {}",
            line.chars().count(),
            &line[..line.char_indices().nth(80).map_or(line.len(), |(i, _)| i)]
        );
    }
    for history in [
        "measured when introduced",
        "a later session",
        "not kept",
        "round,",
    ] {
        assert!(!page.contains(history), "history on the page: `{history}`");
    }
}
