//! A fine map segmented on blocks of cells: the doorways are looked for on
//! a grid of [`WORK_RES_M`] cells (a block free where all its cells are),
//! and the fine free cells take the label of their block, or, where their
//! block is not free (beside walls, in narrow gaps), of the labelled cells
//! they connect to, grown breadth first. Not in the survey (Bormann et al.
//! 2016): its methods run on the map's own cells.

use std::collections::{BTreeMap, VecDeque};

use oxcover_grid::{Cell, Grid, Window};

use rayon::prelude::*;

use super::{doorways_in, merge, numbered, relabel};
use crate::rooms::{RoomParams, Rooms, door_list, grow, merge_small_regions};

/// The cell size (m) doorways are looked for at: a map at least twice as
/// fine is segmented on blocks of `⌊WORK_RES_M / resolution⌋²` cells
/// (doors of 0.7 m and more are seven blocks across and more; thin walls
/// stay: a block holding any obstacle is one).
pub(super) const WORK_RES_M: f64 = 0.1;

/// Most cells per block side (a map finer than a millimetre and a half
/// is searched on blocks finer than 0.1 m).
const MOST_SIDE: usize = 64;

/// Cells per block side for a map of `resolution` (1: no blocks).
pub(super) fn block_side(resolution: f64) -> usize {
    if resolution.is_finite() && resolution > 0.0 {
        ((WORK_RES_M / resolution) * (1.0 + 1e-9))
            .floor()
            .clamp(1.0, MOST_SIDE as f64) as usize
    } else {
        1
    }
}

/// The row-major indices of the 4-neighbours of index `i` in a `w × h`
/// grid: above, left, right, below (`None` off the grid).
fn beside(i: usize, w: usize, h: usize) -> [Option<usize>; 4] {
    let (r, c) = (i / w, i % w);
    [
        (r > 0).then(|| i - w),
        (c > 0).then(|| i - 1),
        (c + 1 < w).then_some(i + 1),
        (r + 1 < h).then_some(i + w),
    ]
}

/// [`super::doorways`] of the free cells of `free`, all inside `window`,
/// on blocks of `k × k` cells (`k` at least 2) laid from the window's
/// top-left corner.
pub(super) fn doorways_blocked(
    free: &Grid<bool>,
    (r0, r1, c0, c1): Window,
    k: usize,
    params: &RoomParams,
) -> Rooms {
    let (w, h) = (free.width(), free.height());
    let (bw, bh) = ((c1 - c0).div_ceil(k), (r1 - r0).div_ceil(k));
    // Each block's free cells; a block is free where all its k × k cells
    // are (a block cut by the window's edge is not).
    let cells = free.as_slice();
    let mut count = vec![0u32; bw * bh];
    // (Block rows in parallel: the same counts at any thread count.)
    count.par_chunks_mut(bw).enumerate().for_each(|(br, out)| {
        for r in r0 + br * k..(r0 + (br + 1) * k).min(r1) {
            let row = &cells[r * w + c0..r * w + c1];
            let tail = if k == 2 {
                // (The common case, 5 cm cells, with pairs the compiler
                // can add side by side.)
                let pairs = row.chunks_exact(2);
                let tail = pairs.remainder();
                for (n, pair) in out.iter_mut().zip(pairs) {
                    *n += u32::from(pair[0]) + u32::from(pair[1]);
                }
                tail
            } else {
                let runs = row.chunks_exact(k);
                let tail = runs.remainder();
                for (n, run) in out.iter_mut().zip(runs) {
                    *n += run.iter().map(|&f| u32::from(f)).sum::<u32>();
                }
                tail
            };
            if let Some(n) = out.get_mut(row.len() / k) {
                *n += tail.iter().map(|&f| u32::from(f)).sum::<u32>();
            }
        }
    });
    let full = (k * k) as u32;
    let blocks = Grid::from_vec(bw, bh, count.iter().map(|&n| n == full).collect())
        .unwrap_or_else(|| Grid::new(0, 0, false));
    let coarse = RoomParams {
        resolution: params.resolution * k as f64,
        ..*params
    };
    // The rooms of the blocks; beside them, the fine labels' memory made
    // ready (written once, so that the pages are in place when the labels
    // are spread) and the blocks that hold some free cells, not all.
    let (part, (mut labels, mixed)) = rayon::join(
        || doorways_in(&blocks, &coarse, 1, false),
        || {
            let mut labels = Grid::new(w, h, 0u32);
            std::hint::black_box(labels.as_mut_slice()).fill(0);
            let mixed: Vec<usize> = (0..bw * bh)
                .filter(|&b| count[b] > 0 && count[b] < full)
                .collect();
            (labels, mixed)
        },
    );
    let block_labels = part.labels.as_slice();
    let cells_of = |b: usize| {
        let (r, c) = (r0 + (b / bw) * k, c0 + (b % bw) * k);
        (r..(r + k).min(r1)).flat_map(move |r| (c..(c + k).min(c1)).map(move |c| r * w + c))
    };
    let blocks_rooms = part.areas.len();
    let pack = |lo: u32, hi: u32| (u64::from(lo) << 32) | u64::from(hi);
    // The fine labels, and beside them what the free blocks alone tell.
    let ((), (mut size, mut at, mut range)) = rayon::join(
        || {
            // The cells of a free block take its label. Each block row's labels cell by cell, copied into each of
            // its rows (block rows in parallel).
            labels.as_mut_slice()[r0 * w..r1 * w]
                .par_chunks_mut(k * w)
                .enumerate()
                .for_each(|(br, rows)| {
                    let b = br * bw;
                    let mut spread = vec![0u32; c1 - c0];
                    for (j, run) in spread.chunks_mut(k).enumerate() {
                        let l = if count[b + j] == full {
                            block_labels[b + j]
                        } else {
                            0
                        };
                        run.fill(l);
                    }
                    for row in rows.chunks_mut(w) {
                        row[c0..c1].copy_from_slice(&spread);
                    }
                });
            let out = labels.as_mut_slice();
            // The free cells of the other blocks that hold any: those
            // beside a labelled cell take its label (the first of above,
            // left, right, below), then the rest are grown into breadth
            // first from them.
            let mut seeds = Vec::new();
            for &b in &mixed {
                for i in cells_of(b) {
                    if !cells[i] {
                        continue;
                    }
                    if let Some(l) = beside(i, w, h)
                        .into_iter()
                        .flatten()
                        .map(|n| out[n])
                        .find(|&l| l != 0)
                    {
                        seeds.push((i, l));
                    }
                }
            }
            let mut queue: VecDeque<Cell> = VecDeque::with_capacity(seeds.len());
            for (i, l) in seeds {
                out[i] = l;
                queue.push_back(Cell::new(i / w, i % w));
            }
            grow(free, &mut labels, &mut queue);
        },
        || {
            // Each room's size and first cell from its free blocks (its
            // cells in the others follow), and the least and greatest
            // room in each block, packed high and low in one word, 0 for
            // none. (Block by block in row-major order: the first block
            // of a room is its top-left one.)
            let mut size = vec![0usize; blocks_rooms + 1];
            let mut at = vec![usize::MAX; blocks_rooms + 1];
            let mut range = vec![0u64; bw * bh];
            for br in 0..bh {
                for bc in (0..bw).filter(|&bc| count[br * bw + bc] == full) {
                    let b = br * bw + bc;
                    let l = block_labels[b] as usize;
                    size[l] += full as usize;
                    if at[l] == usize::MAX {
                        at[l] = (r0 + br * k) * w + c0 + bc * k;
                    }
                    range[b] = pack(l as u32, l as u32);
                }
            }
            (size, at, range)
        },
    );
    let per_metre = 1.0 / params.resolution;
    let min_cells = (params.min_area_m2 * per_metre * per_metre).max(1.0);
    let mut unreached = false;
    for &b in &mixed {
        let (mut lo, mut hi) = (u32::MAX, 0);
        for i in cells_of(b) {
            let l = labels.as_slice()[i];
            if l != 0 {
                size[l as usize] += 1;
                at[l as usize] = at[l as usize].min(i);
                (lo, hi) = (lo.min(l), hi.max(l));
            } else if cells[i] {
                unreached = true;
            }
        }
        if hi > 0 {
            range[b] = pack(lo, hi);
        }
    }
    if unreached {
        // Free cells no labelled one reaches: regions of their own, merged
        // as the fine segmentation merges its small ones, then numbered as
        // it numbers them.
        let mut next = blocks_rooms as u32 + 1;
        for &b in &mixed {
            for i in cells_of(b) {
                if cells[i] && labels.as_slice()[i] == 0 {
                    let c = Cell::new(i / w, i % w);
                    labels[c] = next;
                    next += 1;
                    grow(free, &mut labels, &mut VecDeque::from([c]));
                }
            }
        }
        merge_small_regions(&mut labels, min_cells);
        merge::join_pockets(&mut labels, min_cells);
        return relabel(labels, min_cells);
    }
    let mut first: Vec<u32> = (1..=blocks_rooms as u32)
        .filter(|&l| size[l as usize] > 0)
        .collect();
    first.sort_by_key(|&l| at[l as usize]);
    // Two rooms touch only in a block of two rooms or where a block meets
    // one of other rooms: only there are the cells' neighbours read (bands
    // of block rows in parallel, their pairs in band order).
    let touches = |br: usize, bc: usize| {
        let b = br * bw + bc;
        let here = range[b];
        let some = |r: u64| r as u32 > 0;
        some(here)
            && ((here >> 32) as u32 != here as u32 || {
                let other = |n: usize| some(range[n]) && range[n] != here;
                (br > 0 && other(b - bw))
                    || (bc > 0 && other(b - 1))
                    || (bc + 1 < bw && other(b + 1))
                    || (br + 1 < bh && other(b + bw))
            })
    };
    numbered(labels, &size, &first, min_cells, |labels| {
        let s = labels.as_slice();
        let bands: Vec<Vec<(u32, u32, usize, usize)>> = (0..bh)
            .into_par_iter()
            .map(|br| {
                let mut pairs = Vec::new();
                for i in (0..bw)
                    .filter(|&bc| touches(br, bc))
                    .flat_map(|bc| cells_of(br * bw + bc))
                {
                    let a = s[i];
                    if a == 0 {
                        continue;
                    }
                    for n in beside(i, w, h).into_iter().flatten() {
                        let b = s[n];
                        if b != 0 && b != a {
                            pairs.push((a.min(b), a.max(b), i, n));
                        }
                    }
                }
                pairs
            })
            .collect();
        let mut touching: BTreeMap<(u32, u32), Vec<Cell>> = BTreeMap::new();
        for (a, b, i, n) in bands.into_iter().flatten() {
            let cells = touching.entry((a, b)).or_default();
            cells.push(Cell::new(i / w, i % w));
            cells.push(Cell::new(n / w, n % w));
        }
        door_list(touching)
    })
}
