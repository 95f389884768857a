//! Pinned paths: every planner on every bundled map gives the same path file,
//! byte for byte, as when the pins were taken (`fixtures/golden/paths.tsv`).
//!
//! A refactor must leave these unchanged; a change that is meant to alter a
//! path re-pins with `OXCOVER_BLESS=1 cargo test --release -p oxcover --test
//! golden_paths` and says in its commit which paths changed and why.
//!
//! Each row: map, radii, planner, then either the FNV-1a 64 hash and byte
//! length of the CSV that `oxcover plan --out` writes, or `refused` with the
//! planner's reason (e.g. `optimal` on a wide map).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use oxcover::grid::io::{ReadOptions, read_map};
use oxcover::grid::{DiscRobot, OccupancyGrid};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::registry;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// FNV-1a, 64 bits: a stable hash with no dependency.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The bundled maps and the radii they are planned with: the contract's
/// defaults on the small grids, a 0.15 m robot and tool on the ROS maps.
fn cases() -> Vec<(&'static str, Option<(f64, f64)>)> {
    vec![
        ("movingai/maze-32-32-2.map", None),
        ("movingai/room-32-32-4.map", None),
        ("lee2011/office.yaml", Some((0.17, 0.16))),
        ("nav2/turtlebot3_world.yaml", Some((0.1, 0.1))),
        ("navigation_tutorials/lse_arena.yaml", Some((0.15, 0.15))),
        ("turtlebot_simulator/simple_rooms.yaml", Some((0.15, 0.15))),
        ("nobleo/basement.yaml", Some((0.15, 0.15))),
    ]
}

fn row(name: &str, map: &OccupancyGrid, radii: Option<(f64, f64)>, planner: &str) -> String {
    let mut req = PlanRequest::new(planner, map.resolution())
        .expect("registered")
        .rooms(false);
    if let Some((r, t)) = radii {
        req = req.robot(DiscRobot::new(r, t).expect("valid radii"));
    }
    let radii = radii.map_or_else(|| "default".to_string(), |(r, t)| format!("{r}/{t}"));
    let what = match plan(map, &req) {
        Ok(out) => {
            let csv = oxcover::path::to_csv(&out.points);
            format!("{:016x}\t{}", fnv1a(csv.as_bytes()), csv.len())
        }
        Err(e) => format!("refused\t{e}"),
    };
    format!("{name}\t{radii}\t{planner}\t{what}")
}

#[test]
fn every_planner_on_every_bundled_map_gives_the_pinned_path() {
    let pins = root().join("fixtures/golden/paths.tsv");
    let mut got = String::new();
    for (name, radii) in cases() {
        let map = read_map(
            &root().join("fixtures/maps").join(name),
            &ReadOptions::new(),
        )
        .expect("bundled map");
        for p in registry() {
            // Quadratic in the map: pinned on the small grids only.
            if p.name() == "full-dtc" && map.width() * map.height() > 4096 {
                continue;
            }
            let _ = writeln!(got, "{}", row(name, &map, radii, p.name()));
        }
    }
    if std::env::var_os("OXCOVER_BLESS").is_some() {
        std::fs::create_dir_all(pins.parent().expect("folder")).expect("fixtures/golden");
        std::fs::write(&pins, &got).expect("write pins");
        return;
    }
    let want = std::fs::read_to_string(&pins).expect("fixtures/golden/paths.tsv");
    let (want, got): (Vec<&str>, Vec<&str>) = (want.lines().collect(), got.lines().collect());
    let changed: Vec<String> = want
        .iter()
        .zip(&got)
        .filter(|(w, g)| w != g)
        .map(|(w, g)| format!("  pinned {w}\n  now    {g}"))
        .collect();
    assert!(
        changed.is_empty() && want.len() == got.len(),
        "{} of {} paths changed ({} pinned rows, {} now):\n{}",
        changed.len(),
        want.len(),
        want.len(),
        got.len(),
        changed.join("\n")
    );
}
