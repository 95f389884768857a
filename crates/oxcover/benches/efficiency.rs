//! The whole plan pipeline on the largest ipa floor plan (`lab_b.png`,
//! 1237×672 px at 0.05 m/px), robot and tool radius 0.3 m, start in the
//! largest region, boundary pass on: everything `oxcover plan` does before
//! writing (problem, room units, planner, boundary pass, metrics). Issue
//! 15's planning-time target is about this figure. The reference in the same
//! run is `boustrophedon` with rooms off, the best planner of the workspace
//! before issue 15. The map is LGPL and not bundled: without
//! `../shared/maps` the bench says so and measures nothing.
//!
//! Group `efficiency_intel` times `lanes` with rooms on against the same
//! reference on `intel_map.png` (586×587 px, planned as one region): the
//! map whose transit table (one search per loop or chain end) weighed most.
//!
//! Run: `cargo bench -p oxcover --bench efficiency`; `cargo xtask bench
//! --only efficiency` runs it and writes the figures into `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use oxcover::grid::DiscRobot;
use oxcover::grid::io::{ReadOptions, read_map};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::Start;

/// (bench name, planner, rooms), the reference first.
pub const RUNS: [(&str, &str, bool); 4] = [
    ("boustrophedon-rooms-off", "boustrophedon", false),
    ("lanes-rooms-off", "lanes", false),
    ("lanes-rooms-on", "lanes", true),
    ("boustrophedon-rooms-on", "boustrophedon", true),
];

/// The runs of group `efficiency_intel`, the reference first.
pub const INTEL_RUNS: [(&str, &str, bool); 2] = [
    ("boustrophedon-rooms-off", "boustrophedon", false),
    ("lanes-rooms-on", "lanes", true),
];

fn efficiency(c: &mut Criterion) {
    group(c, "efficiency", "lab_b.png", &RUNS);
    group(c, "efficiency_intel", "intel_map.png", &INTEL_RUNS);
}

/// Times `runs` on the ipa floor plan `file` as criterion group `name`.
fn group(c: &mut Criterion, name: &str, file: &str, runs: &[(&str, &str, bool)]) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/maps/ipa-floorplans")
        .join(file);
    let opts = ReadOptions {
        resolution: 0.05,
        ..ReadOptions::default()
    };
    let Ok(map) = read_map(&path, &opts) else {
        eprintln!("{} not found: {name} bench skipped", path.display());
        return;
    };
    let robot = DiscRobot::new(0.3, 0.3).expect("valid radii");
    let mut g = c.benchmark_group(name);
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(6));
    for &(name, planner, rooms) in runs {
        let req = PlanRequest::new(planner, map.resolution())
            .expect("registered")
            .robot(robot)
            .start(Start::LargestRegion)
            .rooms(rooms);
        g.bench_function(name, |b| b.iter(|| black_box(plan(&map, &req))));
    }
    g.finish();
}

criterion_group!(benches, efficiency);
criterion_main!(benches);
