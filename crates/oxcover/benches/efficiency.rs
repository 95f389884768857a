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
//! Group `efficiency_zone` times `lanes` with rooms on on `lab_b.png`
//! for the whole map (the reference) and for a zone, the rectangle of a
//! tenth of the map's extent at its centre (`--zones`): planning a zone
//! costs the zone, not the map.
//!
//! Run: `cargo bench -p oxcover --bench efficiency`; `cargo xtask bench
//! --only efficiency` runs it, group `efficiency_zone` four times more,
//! and writes the figures into `docs/benchmarks.md` (the zone's ratio in
//! each run and their median; the target met where every run meets it).

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
use oxcover::targets::{Areas, Targets};

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
    zone_group(c);
}

/// The zone of group `efficiency_zone`: the rectangle of `ZONE_SHARE` of
/// the map's extent, centred on it.
pub const ZONE_SHARE: f64 = 0.1;

fn zone_group(c: &mut Criterion) {
    let Some(map) = floor_plan("lab_b.png") else {
        return;
    };
    let (lo, hi) = map.frame().bounds();
    let k = ZONE_SHARE.sqrt() / 2.0;
    let (cx, cy) = ((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0);
    let (dx, dy) = ((hi.x - lo.x) * k, (hi.y - lo.y) * k);
    let zone = geo::Polygon::new(
        geo::LineString::from(vec![
            (cx - dx, cy - dy),
            (cx + dx, cy - dy),
            (cx + dx, cy + dy),
            (cx - dx, cy + dy),
            (cx - dx, cy - dy),
        ]),
        Vec::new(),
    );
    let whole = PlanRequest::new("lanes", map.resolution())
        .expect("registered")
        .robot(DiscRobot::new(0.3, 0.3).expect("valid radii"))
        .start(Start::LargestRegion);
    let zoned = whole.clone().targets(Targets {
        zones: Some(Areas {
            polygons: vec![zone],
            lines: Vec::new(),
        }),
        ..Targets::default()
    });
    let mut g = c.benchmark_group("efficiency_zone");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(6));
    g.bench_function("lanes-whole-map", |b| {
        b.iter(|| black_box(plan(&map, &whole)))
    });
    g.bench_function("lanes-zone", |b| b.iter(|| black_box(plan(&map, &zoned))));
    g.finish();
}

/// The ipa floor plan `file` at 0.05 m/px, if `../shared/maps` is there.
fn floor_plan(file: &str) -> Option<oxcover::grid::OccupancyGrid> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/maps/ipa-floorplans")
        .join(file);
    let opts = ReadOptions {
        resolution: 0.05,
        ..ReadOptions::default()
    };
    let map = read_map(&path, &opts).ok();
    if map.is_none() {
        eprintln!("{} not found: bench skipped", path.display());
    }
    map
}

/// Times `runs` on the ipa floor plan `file` as criterion group `name`.
fn group(c: &mut Criterion, name: &str, file: &str, runs: &[(&str, &str, bool)]) {
    let Some(map) = floor_plan(file) else {
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
