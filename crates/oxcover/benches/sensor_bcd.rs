//! The sensor-based planner `sensor-bcd` (Demir 2018) on three `demir2018`
//! worlds (`fixtures/worlds/demir2018`: one polygon, the concave obstacle,
//! the flat), default settings (0.2 m robot, 0.25 m tool, 180 rays), the
//! whole online run: every scan, follow step and route. The offline
//! `boustrophedon` planner, given the world's whole raster (2.5 cm cells),
//! runs in the same group as the reference: the ratio is what not knowing
//! the map costs in computation.
//!
//! Run: `cargo bench -p oxcover --bench sensor_bcd`; `cargo xtask
//! bench --only sensor_bcd` runs it and writes the figures into
//! `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use oxcover::grid::{DiscRobot, Point};
use oxcover::planners::{CoverageProblem, Start, find};
use oxcover::world::sensor_bcd::{Config, explore};
use oxcover::world::{World, WorldGeometry};

/// Worlds measured.
pub const WORLDS: [&str; 3] = ["fig05_polygon", "fig14_concave", "floor_plan"];

fn sensor_bcd(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/worlds/demir2018");
    let cfg = Config::default();
    let robot = DiscRobot::new(cfg.robot_radius, cfg.tool_radius).expect("valid radii");
    let mut g = c.benchmark_group("sensor_bcd");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(8));
    for name in WORLDS {
        let world = World::read(&dir.join(format!("{name}.ron"))).expect("bundled world");
        let start = world.start.expect("the world names a start");
        let geometry = WorldGeometry::new(&world);
        g.bench_function(format!("sensor-bcd/{name}"), |b| {
            b.iter(|| black_box(explore(&geometry, start, &cfg).expect("explored")));
        });
        let map = world.rasterise();
        let problem = CoverageProblem::new(&map, robot, Start::At(Point::new(start.x, start.y)))
            .expect("problem");
        let input = problem.input(0);
        let planner = find("boustrophedon").expect("registered");
        g.bench_function(format!("boustrophedon/{name}"), |b| {
            b.iter(|| black_box(planner.plan(&input)));
        });
    }
    g.finish();
}

criterion_group!(benches, sensor_bcd);
criterion_main!(benches);
