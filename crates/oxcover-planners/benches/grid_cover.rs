//! Grid_Cover benchmarks: the fast implementation against the literal
//! reference in the same run, and its scaling from 16² to 256² cells on random
//! grids with 20 % obstacles, plus real maps (bundled, and `../shared/maps`
//! when present).
//!
//! Run: `cargo bench -p oxcover-planners --bench grid_cover`; `cargo xtask bench`
//! runs it and writes the figures into `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::random::random_density;
use oxcover_grid::{Cell, CoarseGrid, Grid, components4};
use oxcover_planners::grid_cover::{grid_cover, grid_cover_reference};

/// The largest free region of a map and its first cell.
fn region(free: &Grid<bool>) -> (Grid<bool>, Cell) {
    let comps = components4(free);
    let big = comps.largest().unwrap_or(1);
    let mask = comps.labels.map(|&l| l == big);
    let start = mask.true_cells().next().unwrap_or_default();
    (mask, start)
}

/// Side lengths of the scaling curve.
const SIDES: [usize; 5] = [16, 32, 64, 128, 256];

fn scaling(c: &mut Criterion) {
    let mut g = c.benchmark_group("grid_cover");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in SIDES {
        let (mask, start) = region(&random_density(n, n, 0.2, 7).free_mask());
        let coarse = CoarseGrid::new(&mask, 1);
        g.throughput(Throughput::Elements(mask.count_true() as u64));
        let id = format!("random{n}");
        g.bench_with_input(BenchmarkId::new("fast", &id), &start, |b, &s| {
            b.iter(|| black_box(grid_cover(&coarse, s)))
        });
        if n <= 32 {
            g.bench_with_input(BenchmarkId::new("reference", &id), &start, |b, &s| {
                b.iter(|| black_box(grid_cover_reference(&mask, s)));
            });
        }
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    for rel in [
        "fixtures/maps/navigation_tutorials/lse_arena.yaml",
        "fixtures/maps/movingai/room-32-32-4.map",
        "../shared/maps/movingai/mapf/room-64-64-8.map",
        "../shared/maps/movingai/mapf/maze-128-128-2.map",
    ] {
        let Ok(map) = read_map(&root.join(rel), &ReadOptions::default()) else {
            continue;
        };
        let (mask, start) = region(&map.free_mask());
        let coarse = CoarseGrid::new(&mask, 1);
        g.throughput(Throughput::Elements(mask.count_true() as u64));
        let id = PathBuf::from(rel)
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        g.bench_with_input(BenchmarkId::new("fast", &id), &start, |b, &s| {
            b.iter(|| black_box(grid_cover(&coarse, s)))
        });
        if mask.count_true() <= 1200 {
            g.bench_with_input(BenchmarkId::new("reference", &id), &start, |b, &s| {
                b.iter(|| black_box(grid_cover_reference(&mask, s)));
            });
        }
    }
    g.finish();
}

criterion_group!(benches, scaling);
criterion_main!(benches);
