//! The `smooth` planner (Lee 2011) on the three bundled `lee2011` rooms
//! (`fixtures/maps/lee2011`, 122×102 cells at 0.05 m), body radius 0.17 m
//! and brush radius 0.16 m as in the reproduction, planner call only (the
//! coverage problem and the coverage grid are built once, outside the
//! timing). `dtc`, the simplest planner of the workspace, and `bsa`, the
//! seed's comparison, run in the same group.
//!
//! A second group, `smooth_large`, times `smooth` against `bsa` on the
//! acceptance maps where `smooth` is slowest (`cargo xtask acceptance`'s two
//! settings): `warehouse.yaml` (1006×1674 at 0.03 m) and the ipa `lab_b.png`
//! (1237×672 at 0.05 m) with robot and tool radius 0.3 m, and
//! `maze512-2-0.map` (512×512) with the contract's default radii, from the
//! largest region as there (planner call only). They come
//! from `../shared/maps`; a map that is missing is skipped with a note.
//!
//! Run: `cargo bench -p oxcover-planners --bench smooth`; `cargo xtask bench
//! --only smooth` runs it and writes the figures into `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use oxcover_grid::DiscRobot;
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_planners::{CoverageProblem, Start, find};

/// Planners measured, the reference first.
const PLANNERS: [&str; 3] = ["dtc", "bsa", "smooth"];

fn smooth(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/maps/lee2011");
    let robot = DiscRobot::new(0.17, 0.16).expect("valid radii");
    let mut g = c.benchmark_group("smooth");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    for room in ["living", "office", "workshop"] {
        let map =
            read_map(&dir.join(format!("{room}.yaml")), &ReadOptions::new()).expect("bundled map");
        let problem = CoverageProblem::new(&map, robot, Start::First).expect("problem");
        let input = problem.input(0);
        for name in PLANNERS {
            let planner = find(name).expect("registered");
            g.bench_function(format!("{name}/{room}"), |b| {
                b.iter(|| black_box(planner.plan(&input)));
            });
        }
    }
    g.finish();
}

/// Robot and tool radius (m), or `None` for the contract's defaults.
type Radii = Option<(f64, f64)>;

/// The acceptance maps of the second group: (name, path under
/// `../shared/maps`, resolution for an image, radii).
pub const LARGE: [(&str, &str, f64, Radii); 3] = [
    (
        "warehouse",
        "ros/nav2/nav2_bringup_maps/warehouse.yaml",
        0.05,
        Some((0.3, 0.3)),
    ),
    ("lab_b", "ipa-floorplans/lab_b.png", 0.05, Some((0.3, 0.3))),
    ("maze512-2-0", "movingai/mazes/maze512-2-0.map", 1.0, None),
];

fn smooth_large(c: &mut Criterion) {
    let shared = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/maps");
    let mut g = c.benchmark_group("smooth_large");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(10));
    for (name, rel, resolution, radii) in LARGE {
        let path = shared.join(rel);
        if !path.exists() {
            eprintln!("{} not found: smooth_large/{name} skipped", path.display());
            continue;
        }
        let opts = ReadOptions {
            resolution,
            ..ReadOptions::default()
        };
        let map = read_map(&path, &opts).expect("shared map");
        let robot = match radii {
            Some((r, t)) => DiscRobot::new(r, t).expect("valid radii"),
            None => DiscRobot::cell_sized(map.resolution()),
        };
        let problem = CoverageProblem::new(&map, robot, Start::LargestRegion).expect("problem");
        let input = problem.input(0);
        for planner in ["bsa", "smooth"] {
            let p = find(planner).expect("registered");
            g.bench_function(format!("{planner}/{name}"), |b| {
                b.iter(|| black_box(p.plan(&input)));
            });
        }
    }
    g.finish();
}

criterion_group!(benches, smooth, smooth_large);
criterion_main!(benches);
