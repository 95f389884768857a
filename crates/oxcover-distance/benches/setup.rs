//! Benchmark setup shared by the criterion bench and `cargo xtask bench`
//! (which includes this file by path), so timings and cells-touched counts are
//! measured on the same maps, sources and targets.

#![allow(dead_code, reason = "each includer uses a different subset")]

use std::path::PathBuf;

use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::random::random_density;
use oxcover_grid::{Cell, Grid, components4};

/// Manhattan distance of the "near" targets from the source.
pub(crate) const NEAR: usize = 64;
/// Manhattan distance of the "far" targets: a quarter of the map's shorter side
/// (at least twice [`NEAR`]).
pub(crate) fn far(free: &Grid<bool>) -> usize {
    (free.width().min(free.height()) / 4).max(2 * NEAR)
}

/// Block side of the CFCIDT block map.
pub(crate) const BLOCK: usize = 16;

/// The benchmark maps: a 4096² random grid with 20 % obstacles (seed 1), then
/// real maps from `../shared/maps` when present.
pub(crate) fn maps() -> Vec<(String, Grid<bool>)> {
    let mut out = vec![(
        "random4096_20pct".to_string(),
        random_density(4096, 4096, 0.2, 1).free_mask(),
    )];
    // The workspace root holds Cargo.lock; `../shared/maps` sits beside it.
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let root = here
        .ancestors()
        .find(|d| d.join("Cargo.lock").exists())
        .map_or(here.clone(), PathBuf::from);
    let shared = root.join("../shared/maps");
    for rel in [
        "movingai/mazes/maze512-1-0.map",
        "movingai/rooms/64room_000.map",
        "movingai/mapf/orz900d.map",
        "ros/nav2/nav2_bringup_maps/warehouse.yaml",
        "ros/f1tenth/maps/levinelobby.yaml",
    ] {
        let p = shared.join(rel);
        if let Ok(m) = read_map(&p, &ReadOptions::default()) {
            let name = p
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            out.push((name, m.free_mask()));
        }
    }
    out
}

/// The source: the free cell of the largest component nearest the map centre.
pub(crate) fn central_source(free: &Grid<bool>) -> (Cell, usize) {
    let comps = components4(free);
    let Some(big) = comps.largest() else {
        return (Cell::new(0, 0), 0);
    };
    let centre = Cell::new(free.height() / 2, free.width() / 2);
    let src = free
        .true_cells()
        .filter(|&c| comps.labels[c] == big)
        .min_by_key(|&c| (c.manhattan(centre), c))
        .unwrap_or(centre);
    (src, comps.sizes[big as usize - 1])
}

/// Targets: a handful of cells at Manhattan distance `near` from the source.
pub(crate) fn near_targets(free: &Grid<bool>, src: Cell, near: usize) -> Vec<Cell> {
    let mut t: Vec<Cell> = free
        .true_cells()
        .filter(|&c| c.manhattan(src) == near)
        .collect();
    t.truncate(4);
    t
}
