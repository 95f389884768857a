//! Room segmentation on the ten plain floor plans of the ipa room
//! segmentation benchmark (`../shared/maps/ipa-rooms`, 0.05 m per pixel,
//! grey above 250 free): `doorways`, the default of `oxcover segment`,
//! against `voronoi`, the default before it, in the same run. The plans are
//! LGPL and not bundled: without `../shared/maps` the bench says so and
//! measures nothing.
//!
//! Run: `cargo bench -p oxcover-decomp --bench segmentation`; `cargo xtask
//! bench --only segmentation` runs it and writes the figures into
//! `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use oxcover_decomp::{RoomParams, doorways, voronoi};
use oxcover_grid::io::{ReadOptions, Thresholds, read_map};

/// The plans, as `cargo xtask segmentation` scores them.
pub const PLANS: [&str; 10] = [
    "Freiburg52_scan",
    "Freiburg79_scan",
    "lab_b_scan",
    "lab_d_scan",
    "lab_intel",
    "office_a",
    "office_c",
    "office_e",
    "office_g",
    "office_i",
];

fn segmentation(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/maps/ipa-rooms");
    // Grey above 250 free: occupancy (255 - v) / 255 below 4.5 / 255.
    let cut = 4.5 / 255.0;
    let opts = ReadOptions::default()
        .resolution(0.05)
        .thresholds(Thresholds {
            occupied_thresh: cut,
            free_thresh: cut,
            ..Thresholds::default()
        });
    let params = RoomParams::indoor(0.05);
    let mut g = c.benchmark_group("segmentation");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    for plan in PLANS {
        let path = dir.join(format!("{plan}.png"));
        let Ok(map) = read_map(&path, &opts) else {
            eprintln!("{} not found: segmentation bench skipped", path.display());
            return;
        };
        let free = map.free_mask();
        g.bench_function(format!("voronoi_{plan}"), |b| {
            b.iter(|| black_box(voronoi(&free, &params)));
        });
        g.bench_function(format!("doorways_{plan}"), |b| {
            b.iter(|| black_box(doorways(&free, &params)));
        });
    }
    g.finish();
}

criterion_group!(benches, segmentation);
criterion_main!(benches);
