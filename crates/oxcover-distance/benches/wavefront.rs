//! Wavefront benchmarks: the Lee workspace against a plain `VecDeque` BFS in the
//! same run, on a 4096² random grid (20 % obstacles) and on real maps from
//! `../shared/maps` (skipped when absent); nearest-target queries by full
//! wavefront, CIDT and CFCIDT.
//!
//! Run: `cargo bench -p oxcover-distance --bench wavefront`; `cargo xtask bench`
//! runs it and writes the figures into `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

mod setup;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use oxcover_distance::reference::bfs_distances;
use oxcover_distance::{BlockMap, CoarseToFine, Wavefront, cidt};
use oxcover_grid::Grid;
use setup::{BLOCK, NEAR, central_source, far, maps, near_targets};

fn full_wavefront(c: &mut Criterion) {
    let mut g = c.benchmark_group("full_wavefront");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(6))
        .warm_up_time(Duration::from_secs(1));
    for (name, free) in maps() {
        let (src, reachable) = central_source(&free);
        g.throughput(Throughput::Elements(reachable as u64));
        let mut wave = Wavefront::new(&free);
        g.bench_with_input(BenchmarkId::new("lee", &name), &src, |b, &s| {
            b.iter(|| black_box(wave.propagate(&[s])));
        });
        g.bench_with_input(BenchmarkId::new("vecdeque", &name), &src, |b, &s| {
            b.iter(|| black_box(bfs_distances(&free, s)));
        });
        g.bench_with_input(BenchmarkId::new("lee_build", &name), &free, |b, f| {
            b.iter(|| black_box(Wavefront::new(f)));
        });
    }
    g.finish();
}

fn nearest_target(c: &mut Criterion) {
    for (group_name, near) in [("nearest_target", None), ("far_target", Some(()))] {
        let mut g = c.benchmark_group(group_name);
        g.sample_size(10)
            .measurement_time(Duration::from_secs(4))
            .warm_up_time(Duration::from_secs(1));
        for (name, free) in maps() {
            let (src, _) = central_source(&free);
            let dist = if near.is_none() { NEAR } else { far(&free) };
            let targets = near_targets(&free, src, dist);
            let mut is_target = Grid::new(free.width(), free.height(), false);
            for &t in &targets {
                is_target[t] = true;
            }
            let mut wave = Wavefront::new(&free);
            g.bench_with_input(BenchmarkId::new("full", &name), &src, |b, &s| {
                b.iter(|| {
                    wave.propagate(&[s]);
                    black_box(targets.iter().filter_map(|&t| wave.distance(t)).min())
                });
            });
            g.bench_with_input(BenchmarkId::new("cidt", &name), &src, |b, &s| {
                b.iter(|| black_box(cidt(&mut wave, &[s], |c| is_target[c]).map(|n| n.distance)));
            });
            let mut blocks = BlockMap::new(&free, BLOCK);
            for &t in &targets {
                blocks.set_target(t, true);
            }
            let mut cf = CoarseToFine::new();
            g.bench_with_input(BenchmarkId::new("cfcidt", &name), &src, |b, &s| {
                b.iter(|| black_box(cf.nearest(&blocks, s).map(|f| f.distance)));
            });
            g.bench_with_input(BenchmarkId::new("corridor", &name), &src, |b, &s| {
                b.iter(|| black_box(cf.corridor_nearest(&blocks, s).map(|f| f.distance)));
            });
        }
        g.finish();
    }
}

criterion_group!(benches, full_wavefront, nearest_target);
criterion_main!(benches);
