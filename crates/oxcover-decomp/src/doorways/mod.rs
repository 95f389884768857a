//! Room segmentation by doorways: a room ends where its wall has a gap.
//! The default of `oxcover segment`.
//!
//! 0. **Blocks** (`blocks.rs`): a map at least twice as fine as 0.1 m is
//!    segmented on blocks of cells 0.1 m or so across (a block free where
//!    all its cells are, so that no wall is lost); the free cells take
//!    their block's room, or, beside walls and in gaps narrower than a
//!    block, the room of the cells they join, grown breadth first. Doors
//!    are 0.7 m wide and more: seven blocks. The steps below run on the
//!    blocks: on the ipa plans at 5 cm two to three times faster than on
//!    the cells, mean IoU 0.003 (plain) and 0.012 (furnished) lower, per
//!    plan up to 0.057 lower and up to 0.045 higher.
//! 1. **Furniture**: obstacles standing alone, under 2 m², at least 0.3 m
//!    across both ways and filling half their bounding box. Doorways are
//!    looked for on the floor as if it were not there (a block beside a
//!    door would hide the door): the clearance of every cell of the floor
//!    and the medial axis, as in [`crate::voronoi_rooms`].
//! 2. **Doorways** (`lines.rs`): at every axis cell no wider than half a
//!    door, the critical line (the segment between its two nearest obstacle
//!    points on opposite sides, after the survey's critical points) is a
//!    cut where at least one of its ends is a wall end in line with it: the
//!    obstacle runs on along the line for 0.8 m as a thin wall (at most a
//!    metre thick), or for a few cells up to another wall (a door beside a
//!    corner). A gap between two wall ends, or between a wall end and the
//!    face of another wall, is cut whatever the clearance of the spaces it
//!    joins: a door wider than its corridor is still a door. The sides of a
//!    corridor cross the line at a right angle: no cut; nor where a wall
//!    across the line's end thins into one in line (a room's wall meeting
//!    a short piece of corridor wall between two doors).
//! 3. **Walls continued** (`extensions.rs`): a thin wall that ends in the
//!    open is continued straight on to the wall ahead (up to 4.5 m), and a
//!    wall's tip joined to the nearest other tip ahead of both tips, where
//!    the space on one side of the cut is wider than the cut (a room's open
//!    side, not a corridor's cross-section). Furniture is no wall here
//!    either, and neither is a wall across the end that thins into one.
//! 4. **Rooms** (`merge.rs`): the free space minus the cuts falls into
//!    regions. Two regions stay apart where the widest cut between them is
//!    narrow beside the wider space (half width at most 0.7 of its
//!    clearance) and, for a continued wall, the smaller is at least 4 m².
//!    Pieces of passage between cuts (under 2 m², much of their border
//!    cut) join the neighbour across their widest cut; regions below the
//!    smallest room join the neighbour they share the longest border with;
//!    pockets cut off by furniture join the nearest room; the cut cells go
//!    back to the rooms beside them.
//!
//! **Labels** are numbered top-left first: rooms of at least the smallest
//! area ([`RoomParams::min_area_m2`](crate::rooms::RoomParams::min_area_m2)) in row-major order of their first cell,
//! then the smaller free regions, in the same order. The same grid and
//! parameters give the same labels at every thread count.
//!
//! Measured on the ten plans of the ipa room-segmentation benchmark
//! (`cargo xtask segmentation`, `docs/segmentation.md`): IoU 0.977 plain,
//! 0.936 furnished (no plan below 0.868), against 0.597 / 0.560 for
//! [`crate::voronoi_rooms`];
//! every generated plan of `tests/doorways_generated.rs` (rooms, doors of
//! 0.7-1.6 m on both sides of a corridor and between rooms, furniture).
//!
//! Written for this workspace after the critical lines of Bormann et al.
//! 2016 ("Room segmentation: survey, implementation, and analysis"), with
//! this departure: a critical line is a door by the walls at its ends, not
//! by a local minimum of the clearance along the axis (which misses doors
//! wider than the corridor they open into), and no merging heuristic on
//! room shape follows.

mod blocks;
mod extensions;
mod lines;
mod merge;
#[cfg(test)]
mod tests;

use std::collections::VecDeque;

use rayon::prelude::*;

use oxcover_grid::edt::boundary_distance_sq4;
use oxcover_grid::{Cell, Dir4, Grid, components4};

use crate::rooms::{
    Door, RoomParams, Rooms, doors, grow, label_runs, label_the_rest, merge_small_regions,
};
use crate::voronoi_rooms::axis_cells_in;

use blocks::{block_side, doorways_blocked};
use lines::{
    ISLAND_M2, ISLAND_THICK_M, JAMB_RUN_M, MIN_DOOR_M, THINS_OUT_M, WALL_HALF_M, critical_line,
    cut_cells_of, jamb, on_furniture, rings,
};

/// A point in grid coordinates (x = column, y = row).
type Pt = (f64, f64);

/// A doorway cut: its ends and its half width (cells).
#[derive(Clone, Copy, Debug)]
struct Cut {
    a: Pt,
    b: Pt,
    half: f64,
    /// Whether it continues a wall across an opening (else a doorway).
    extension: bool,
}

/// The cuts, the free cells each crosses, and every cell on a cut.
struct CutSet {
    cuts: Vec<Cut>,
    cells: Vec<Vec<Cell>>,
    on_cut: Grid<bool>,
}

/// Segments the free cells of `free` into rooms at their doorways (see the
/// module docs).
#[must_use]
pub fn doorways(free: &Grid<bool>, params: &RoomParams) -> Rooms {
    // Work on the free cells' bounding box and a cell round it: nothing
    // outside it is free, so nothing there can change a label.
    let (w, h) = (free.width(), free.height());
    let Some((r0, r1, c0, c1)) = free.bounding_box(|&f| f) else {
        return relabel(Grid::new(w, h, 0), 1.0);
    };
    let (r0, c0) = (r0.saturating_sub(1), c0.saturating_sub(1));
    let (r1, c1) = ((r1 + 1).min(h), (c1 + 1).min(w));
    // A fine map: on blocks of cells, the window read in place.
    let k = block_side(params.resolution);
    if k >= 2 {
        return doorways_blocked(free, (r0, r1, c0, c1), k, params);
    }
    if (r0, c0, r1, c1) == (0, 0, h, w) {
        return doorways_in(free, params, 0, true);
    }
    let iw = c1 - c0;
    let rows = free.as_slice().chunks(w).skip(r0).take(r1 - r0);
    let inner: Vec<bool> = rows.flat_map(|row| &row[c0..c1]).copied().collect();
    let Some(inner) = Grid::from_vec(iw, r1 - r0, inner) else {
        return doorways_in(free, params, 0, true);
    };
    let part = doorways_in(&inner, params, 0, true);
    let mut labels = Grid::new(w, h, 0u32);
    let out = labels.as_mut_slice().chunks_mut(w).skip(r0);
    for (to, from) in out.zip(part.labels.as_slice().chunks(iw)) {
        to[c0..c1].copy_from_slice(from);
    }
    let shift = |c: Cell| Cell::new(c.row + r0, c.col + c0);
    Rooms {
        labels,
        doors: part
            .doors
            .into_iter()
            .map(|d| Door {
                rooms: d.rooms,
                cells: d.cells.into_iter().map(shift).collect(),
                centre: shift(d.centre),
            })
            .collect(),
        ..part
    }
}

/// [`doorways`] on the whole of `free`, whose obstacles are grown by up to
/// `grown` cells (a grid of blocks, [`blocks`]: a block holding any
/// obstacle is one), which the furniture's thickness allows for; the
/// doors between the rooms found where `find_doors`.
fn doorways_in(free: &Grid<bool>, params: &RoomParams, grown: usize, find_doors: bool) -> Rooms {
    let (w, h) = (free.width(), free.height());
    let res = params.resolution;
    let valid = res.is_finite() && res > 0.0;
    let per_metre = if valid { 1.0 / res } else { 0.0 };
    let door_half = params.door_width_m / 2.0 * per_metre;
    let min_cells = (params.min_area_m2 * per_metre * per_metre).max(1.0);
    let (run, wall_half) = (
        (JAMB_RUN_M * per_metre).max(1.0),
        (WALL_HALF_M * per_metre).max(1.0),
    );
    let thin_margin = THINS_OUT_M * per_metre;
    let blocked = free.map(|&f| !f);
    let edges = edge_cells(free);
    let rings = rings(door_half);
    let narrowest_door = (MIN_DOOR_M / 2.0 * per_metre).max(1.5);
    // The walls continued across openings beside the furniture, the
    // clearance and the doorways (each the same whatever the thread
    // count).
    let ((furniture, d4, cuts), extended) = rayon::join(
        || {
            let furniture = furniture(
                &blocked,
                &edges,
                ISLAND_M2 * per_metre * per_metre,
                (ISLAND_THICK_M * per_metre).round().max(2.0) as usize + grown,
            );
            // Doorways are looked for on the floor as if the furniture
            // were not there (a block beside a door would hide it): the
            // free cells and the clearance without it.
            let floor = free.zip_map(&furniture, |&f, &b| f || b);
            let d4 = boundary_distance_sq4(&floor.map(|&f| !f), true);
            let clearance = |c: Cell| (d4[c] as f64).sqrt() / 2.0;
            // Critical lines of the narrow axis cells, kept where a wall
            // ends in line. (In parallel, in the axis cells' row-major
            // order whatever the thread count.)
            let (lo4, hi4) = (
                (4.0 * narrowest_door * narrowest_door).floor() as u64,
                (4.0 * door_half * door_half).ceil() as u64,
            );
            let narrow_axis: Vec<Cell> = axis_cells_in(&floor, &d4, lo4..=hi4)
                .into_iter()
                .filter(|&c| (narrowest_door..=door_half).contains(&clearance(c)))
                .collect();
            let cuts: Vec<Cut> = narrow_axis
                .par_iter()
                .filter_map(|&c| critical_line(&floor, &rings, c, clearance(c)))
                .filter(|cut| {
                    !on_furniture(&furniture, cut.b, cut.a)
                        && !on_furniture(&furniture, cut.a, cut.b)
                        && (jamb(free, &furniture, cut.b, cut.a, run, wall_half, thin_margin)
                            || jamb(free, &furniture, cut.a, cut.b, run, wall_half, thin_margin))
                })
                .collect();
            (furniture, d4, cuts)
        },
        || extensions::extension_cuts(free, &edges, door_half, per_metre, wall_half),
    );
    let mut cuts = cuts;
    // (A block of furniture is no wall to continue, nor one to meet.)
    cuts.extend(extended.into_iter().filter(|cut| {
        !on_furniture(&furniture, cut.b, cut.a) && !on_furniture(&furniture, cut.a, cut.b)
    }));
    let cells: Vec<Vec<Cell>> = cuts.iter().map(|cut| cut_cells_of(free, cut)).collect();
    let mut on_cut = Grid::new(w, h, false);
    for &c in cells.iter().flatten() {
        on_cut[c] = true;
    }
    let cuts = CutSet {
        cuts,
        cells,
        on_cut,
    };
    let open = free.zip_map(&cuts.on_cut, |&f, &cut| f && !cut);
    let regions = components4(&open);
    let mut labels = regions.labels;
    let count = regions.sizes.len();
    // Each region's widest clearance.
    let mut widest = vec![0u64; count + 1];
    let cells = open
        .as_slice()
        .iter()
        .zip(labels.as_slice())
        .zip(d4.as_slice());
    for ((_, &l), &d) in cells.filter(|((o, _), _)| **o) {
        widest[l as usize] = widest[l as usize].max(d);
    }
    let peak: Vec<f64> = widest.iter().map(|&d| (d as f64).sqrt() / 2.0).collect();
    merge::join_regions(
        free,
        &open,
        &cuts,
        &mut labels,
        &regions.sizes,
        peak,
        per_metre,
    );
    // The cuts go back to the rooms beside them.
    // (Only labelled cells beside an unlabelled free one can label any.)
    let mut queue: VecDeque<Cell> = cuts
        .cells
        .iter()
        .flatten()
        .flat_map(|&c| Dir4::ALL.into_iter().filter_map(move |d| free.step(c, d)))
        .filter(|&n| labels[n] != 0)
        .collect();
    grow(free, &mut labels, &mut queue);
    label_the_rest(free, &mut labels, count as u32 + 1);
    merge_small_regions(&mut labels, min_cells);
    merge::join_pockets(&mut labels, min_cells);
    if find_doors {
        relabel(labels, min_cells)
    } else {
        let (size, first) = sizes(&labels);
        numbered(labels, &size, &first, min_cells, |_| Vec::new())
    }
}

/// Each row's obstacle cells beside a free one (4-neighbours; columns in
/// order): where walls and furniture are looked for. (Rows in parallel,
/// each a mask of whole rows or'ed side by side, then read.)
fn edge_cells(free: &Grid<bool>) -> Vec<Vec<u32>> {
    let (w, h) = (free.width(), free.height());
    let cells = free.as_slice();
    (0..h)
        .into_par_iter()
        .map_init(
            || vec![false; w],
            |near, r| {
                let row = &cells[r * w..(r + 1) * w];
                near.fill(false);
                for (n, pair) in near.iter_mut().skip(1).zip(row.windows(2)) {
                    *n |= pair[0];
                }
                for (n, pair) in near.iter_mut().zip(row.windows(2)) {
                    *n |= pair[1];
                }
                for other in [r.checked_sub(1), (r + 1 < h).then_some(r + 1)]
                    .into_iter()
                    .flatten()
                {
                    for (n, &f) in near.iter_mut().zip(&cells[other * w..(other + 1) * w]) {
                        *n |= f;
                    }
                }
                row.iter()
                    .zip(near.iter())
                    .enumerate()
                    .filter(|&(_, (&f, &n))| !f && n)
                    .map(|(c, _)| c as u32)
                    .collect()
            },
        )
        .collect()
}

/// The cells of the furniture among the obstacles of `blocked`: those
/// that stand alone (not touching the grid's edge), under `most` cells,
/// at least `thick` cells across both ways and filling half their bounding
/// box at least (a block, not a scanned wall's broken piece).
///
/// Every island has a cell beside a free one, so only those (`edges`, as
/// [`edge_cells`] lists them) start a search, and a search gives up (the
/// island is no furniture) at `most` cells, at the grid's edge or at a
/// cell an earlier search gave up on:
/// the large obstacles (the walls, the world outside) are never filled
/// whole.
fn furniture(blocked: &Grid<bool>, edges: &[Vec<u32>], most: f64, thick: usize) -> Grid<bool> {
    /// A cell's state: not yet searched, in no furniture, furniture.
    const NEW: u8 = 0;
    const NONE: u8 = 1;
    const BLOCK: u8 = 2;
    let (w, h) = (blocked.width(), blocked.height());
    let b = blocked.as_slice();
    let mut state = vec![NEW; b.len()];
    let (mut island, mut stack) = (Vec::new(), Vec::new());
    let starts = edges
        .iter()
        .enumerate()
        .flat_map(|(r, row)| row.iter().map(move |&c| r * w + c as usize));
    for start in starts {
        if state[start] != NEW {
            continue;
        }
        island.clear();
        stack.clear();
        stack.push(start);
        state[start] = BLOCK;
        let mut alone = true;
        while let Some(i) = stack.pop() {
            island.push(i);
            let (r, c) = (i / w, i % w);
            if r == 0 || c == 0 || r + 1 == h || c + 1 == w || island.len() as f64 >= most {
                alone = false;
                break;
            }
            for n in [i - 1, i + 1, i - w, i + w] {
                if b[n] {
                    match state[n] {
                        NEW => {
                            state[n] = BLOCK;
                            stack.push(n);
                        }
                        NONE => {
                            alone = false;
                        }
                        _ => {}
                    }
                }
            }
            if !alone {
                break;
            }
        }
        let keep = alone && {
            let (mut r0, mut r1, mut c0, mut c1) = (usize::MAX, 0, usize::MAX, 0);
            for &i in &island {
                let (r, c) = (i / w, i % w);
                (r0, r1, c0, c1) = (r0.min(r), r1.max(r + 1), c0.min(c), c1.max(c + 1));
            }
            let (bh, bw) = (r1 - r0, c1 - c0);
            bh.min(bw) >= thick && 2 * island.len() >= bh * bw
        };
        if !keep {
            for &i in island.iter().chain(&stack) {
                state[i] = NONE;
            }
        }
    }
    Grid::from_vec(w, h, state.into_iter().map(|s| s == BLOCK).collect())
        .unwrap_or_else(|| Grid::new(w, h, false))
}

/// `labels` renumbered top-left first: rooms of at least `min_cells` in
/// row-major order of their first cell, then the smaller free regions;
/// with their areas and doors.
fn relabel(labels: Grid<u32>, min_cells: f64) -> Rooms {
    let (size, first) = sizes(&labels);
    numbered(labels, &size, &first, min_cells, doors)
}

/// Each label's size (by label), and the labels in row-major order of
/// their first cell.
fn sizes(labels: &Grid<u32>) -> (Vec<usize>, Vec<u32>) {
    let mut size: Vec<usize> = Vec::new();
    let mut first: Vec<u32> = Vec::new();
    // (A run of equal labels at a time, as `label_counts`.)
    for (l, run) in label_runs(labels.as_slice()).filter(|&(l, _)| l != 0) {
        let l = l as usize;
        if l >= size.len() {
            size.resize(l + 1, 0);
        }
        if size[l] == 0 {
            first.push(l as u32);
        }
        size[l] += run;
    }
    (size, first)
}

/// [`relabel`] given each label's cells (`size`, by label) and the labels
/// in row-major order of their first cell (`first`); `doors_of` finds the
/// doors of the labels as renumbered.
fn numbered(
    mut labels: Grid<u32>,
    size: &[usize],
    first: &[u32],
    min_cells: f64,
    doors_of: impl FnOnce(&Grid<u32>) -> Vec<Door>,
) -> Rooms {
    let big = |l: &u32| size[*l as usize] as f64 >= min_cells;
    let order: Vec<u32> = first
        .iter()
        .filter(|l| big(l))
        .chain(first.iter().filter(|l| !big(l)))
        .copied()
        .collect();
    let seeded = first.iter().filter(|l| big(l)).count();
    let mut fresh = vec![0u32; size.len()];
    for (i, &l) in order.iter().enumerate() {
        fresh[l as usize] = i as u32 + 1;
    }
    let areas: Vec<usize> = order.iter().map(|&l| size[l as usize]).collect();
    // (Labels already in order, as the blocks' are, stay as they are.)
    // (Rows in parallel.)
    if order.iter().enumerate().any(|(i, &l)| l != i as u32 + 1) {
        let w = labels.width().max(1);
        labels.as_mut_slice().par_chunks_mut(w).for_each(|row| {
            for l in row.iter_mut().filter(|l| **l != 0) {
                *l = fresh[*l as usize];
            }
        });
    }
    let doors = doors_of(&labels);
    Rooms {
        seeded,
        labels,
        areas,
        doors,
    }
}
