//! Every planner of issue 4 on the largest floor plan of
//! `../shared/maps/ipa-floorplans` (`lab_b.png`, 1237×672 px at 0.05 m/px),
//! robot and tool radius 0.3 m (coverage cells of 12×12 px), planner call
//! only (the coverage problem and the coverage grid are built once, outside
//! the timing). `dtc`, the simplest planner of the workspace, runs in the same
//! group as the reference. The map is LGPL and not bundled: without
//! `../shared/maps` the bench says so and measures nothing.
//!
//! Run: `cargo bench -p oxcover-planners --bench floorplan`; `cargo xtask
//! bench` runs it and writes the figures into `docs/benchmarks.md`.

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
const PLANNERS: [&str; 7] = [
    "dtc",
    "stc",
    "spiral-stc",
    "bsa",
    "boustrophedon",
    "trapezoidal",
    "border-expansion",
];

fn floorplan(c: &mut Criterion) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/maps/ipa-floorplans/lab_b.png");
    let opts = ReadOptions {
        resolution: 0.05,
        ..ReadOptions::default()
    };
    let Ok(map) = read_map(&path, &opts) else {
        eprintln!("{} not found: floorplan bench skipped", path.display());
        return;
    };
    let robot = DiscRobot::new(0.3, 0.3).expect("valid radii");
    // Start in the largest admissible region (the default start may be a speck).
    let problem = CoverageProblem::new(&map, robot, Start::LargestRegion).expect("problem");
    let input = problem.input(0);
    let mut g = c.benchmark_group("floorplan");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    for name in PLANNERS {
        let planner = find(name).expect("registered");
        g.bench_function(name, |b| b.iter(|| black_box(planner.plan(&input))));
    }
    // Border expansion's parts: the exact distance transform, then the roads.
    let blocked = problem.plannable().map(|&p| !p);
    g.bench_function("parts/edt", |b| {
        b.iter(|| black_box(oxcover_grid::edt::boundary_distance_sq4(&blocked, true)));
    });
    g.bench_function("parts/border-expansion-roads", |b| {
        b.iter(|| {
            black_box(oxcover_decomp::border_expansion(
                problem.plannable(),
                problem.block() as f64,
            ))
        });
    });
    g.finish();
}

criterion_group!(benches, floorplan);
criterion_main!(benches);
