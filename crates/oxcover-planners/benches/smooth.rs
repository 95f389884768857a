//! The `smooth` planner (Lee 2011) on the three bundled `lee2011` rooms
//! (`fixtures/maps/lee2011`, 122×102 cells at 0.05 m), body radius 0.17 m
//! and brush radius 0.16 m as in the reproduction, planner call only (the
//! coverage problem and the coverage grid are built once, outside the
//! timing). `dtc`, the simplest planner of the workspace, and `bsa`, the
//! seed's comparison, run in the same group.
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

criterion_group!(benches, smooth);
criterion_main!(benches);
