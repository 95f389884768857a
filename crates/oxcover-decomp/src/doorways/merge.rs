//! Regions between the cuts joined into rooms: what a wide cut joins stays
//! one room, pieces of passage between cuts join a neighbour, pockets of
//! floor cut off by furniture join the nearest room.

use std::collections::{BTreeMap, VecDeque};

use oxcover_grid::{Cell, Dir4, Grid};

use super::CutSet;
use crate::rooms::label_counts;

/// Largest share of the wider space's clearance a cut's half width may
/// have to keep two regions apart.
const NARROW: f64 = 0.7;

/// Smallest room (m²) a wall's continuation alone keeps apart.
const EXT_MIN_M2: f64 = 4.0;

/// Largest piece (m²) of passage between cuts that joins a neighbour.
const PIECE_M2: f64 = 2.0;

/// Least share of a piece's border that is cut.
const PIECE_CUT: f64 = 0.4;

/// Joins the regions of `labels` (components of `open`, of `sizes` cells,
/// widest clearance `peak`) that a cut of `cuts` does not keep apart.
pub(super) fn join_regions(
    free: &Grid<bool>,
    open: &Grid<bool>,
    cuts: &CutSet,
    labels: &mut Grid<u32>,
    sizes: &[usize],
    mut peak: Vec<f64>,
    per_metre: f64,
) {
    let count = sizes.len();
    // The regions each cut joins, and the widest cut between each pair.
    let mut pairs: BTreeMap<(u32, u32), (f64, bool)> = BTreeMap::new();
    for (cut, cells) in cuts.cuts.iter().zip(&cuts.cells) {
        let mut beside: Vec<u32> = Vec::new();
        for &c in cells {
            for d in Dir4::ALL {
                if let Some(n) = free.step(c, d) {
                    let l = labels[n];
                    if l != 0 && !beside.contains(&l) {
                        beside.push(l);
                    }
                }
            }
        }
        beside.sort_unstable();
        for (i, &x) in beside.iter().enumerate() {
            for &y in &beside[i + 1..] {
                let e = pairs.entry((x, y)).or_insert((0.0, true));
                *e = (e.0.max(cut.half), e.1 && cut.extension);
            }
        }
    }
    // Keep apart only what a narrow cut joins (beside the wider space):
    // the widest cuts first, each pair judged on the rooms as merged so far.
    let mut parent: Vec<u32> = (0..=count as u32).collect();
    let find = |p: &mut Vec<u32>, mut u: u32| {
        while p[u as usize] != u {
            let g = p[p[u as usize] as usize];
            p[u as usize] = g;
            u = g;
        }
        u
    };
    let mut area = vec![0usize; count + 1];
    for (i, &n) in sizes.iter().enumerate() {
        area[i + 1] = n;
    }
    let ext_min = EXT_MIN_M2 * per_metre * per_metre;
    let mut order: Vec<((u32, u32), (f64, bool))> = pairs.into_iter().collect();
    order.sort_by(|x, y| y.1.0.total_cmp(&x.1.0).then(x.0.cmp(&y.0)));
    for &((x, y), (half, extension)) in &order {
        let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
        if rx == ry {
            continue;
        }
        let wider = peak[rx as usize].max(peak[ry as usize]);
        let smaller = area[rx as usize].min(area[ry as usize]) as f64;
        let join = half > NARROW * wider || (extension && smaller < ext_min);
        if join {
            let (keep, gone) = (rx.min(ry), rx.max(ry));
            parent[gone as usize] = keep;
            peak[keep as usize] = wider;
            area[keep as usize] += area[gone as usize];
        }
    }
    // Pieces of passage between cuts (a doorway cut twice, the corner
    // between a door and a wall's continuation) join the neighbour across
    // their widest cut: the smallest pieces first.
    let piece_min = PIECE_M2 * per_metre * per_metre;
    // Each region's border cells, and those of them beside a cut.
    let mut border = vec![(0usize, 0usize); count + 1];
    let (w, h) = (free.width(), free.height());
    let (on_cut, open_at) = (cuts.on_cut.as_slice(), open.as_slice());
    // (A cell is on its region's border where a neighbour is not open:
    // off the grid, not free, or on a cut.)
    for r in 0..h {
        for c in 0..w {
            let i = r * w + c;
            if !open_at[i] {
                continue;
            }
            let beside = [
                (r > 0).then(|| i - w),
                (c > 0).then(|| i - 1),
                (c + 1 < w).then_some(i + 1),
                (r + 1 < h).then_some(i + w),
            ];
            if beside.iter().all(|n| n.is_some_and(|n| open_at[n])) {
                continue;
            }
            let cut = beside.iter().flatten().any(|&n| on_cut[n]);
            let b = &mut border[labels.as_slice()[i] as usize];
            b.0 += 1;
            b.1 += usize::from(cut);
        }
    }
    for l in 1..=count as u32 {
        let r = find(&mut parent, l);
        if r != l {
            let (e, c) = border[l as usize];
            border[r as usize].0 += e;
            border[r as usize].1 += c;
        }
    }
    let is_piece = |r: u32, area: &[usize], border: &[(usize, usize)]| {
        let (edge, cut) = border[r as usize];
        (area[r as usize] as f64) < piece_min && cut as f64 >= PIECE_CUT * edge as f64
    };
    let mut roots: Vec<u32> = (1..=count as u32)
        .filter(|&r| find(&mut parent, r) == r && is_piece(r, &area, &border))
        .collect();
    roots.sort_by_key(|&r| (area[r as usize], r));
    for r in roots {
        let r = find(&mut parent, r);
        let mut across: BTreeMap<u32, f64> = BTreeMap::new();
        for &((x, y), (half, _)) in &order {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry && (rx == r || ry == r) {
                let other = if rx == r { ry } else { rx };
                let e = across.entry(other).or_insert(0.0);
                *e = e.max(half);
            }
        }
        if across.len() < 2 || !is_piece(r, &area, &border) {
            continue;
        }
        let Some((&to, _)) = across
            .iter()
            .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(a.0)))
        else {
            continue;
        };
        let (keep, gone) = (r.min(to), r.max(to));
        parent[gone as usize] = keep;
        peak[keep as usize] = peak[r as usize].max(peak[to as usize]);
        area[keep as usize] = area[r as usize] + area[to as usize];
        let (a, b) = (border[r as usize], border[to as usize]);
        border[keep as usize] = (a.0 + b.0, a.1 + b.1);
    }
    let root: Vec<u32> = (0..=count as u32)
        .map(|l| if l == 0 { 0 } else { find(&mut parent, l) })
        .collect();
    for l in labels.as_mut_slice() {
        *l = root[*l as usize];
    }
}

/// Gives each region smaller than `min_cells` that no free cell joins to
/// another (a pocket of floor inside a ring of chairs, behind a table)
/// the label of the nearest larger region, across whatever lies between.
pub(super) fn join_pockets(labels: &mut Grid<u32>, min_cells: f64) {
    let size = label_counts(labels.as_slice());
    let top = size.len().saturating_sub(1);
    // (A label merged away holds no cell: no pocket.)
    let small = |l: u32| l != 0 && size[l as usize] > 0 && (size[l as usize] as f64) < min_cells;
    if !(1..=top as u32).any(small) {
        return;
    }
    let mut cells: Vec<Vec<Cell>> = vec![Vec::new(); top + 1];
    let w = labels.width();
    for (i, &l) in labels.as_slice().iter().enumerate() {
        if small(l) {
            cells[l as usize].push(Cell::new(i / w, i % w));
        }
    }
    for l in 1..=top as u32 {
        let Some(&start) = cells[l as usize].first() else {
            continue;
        };
        // Breadth first from the pocket, over every cell, to the first
        // cell of a larger region.
        let mut seen = std::collections::BTreeSet::from([start]);
        let mut queue = VecDeque::from([start]);
        let mut found = None;
        while let Some(c) = queue.pop_front() {
            let m = labels[c];
            if m != 0 && m != l && !small(m) {
                found = Some(m);
                break;
            }
            for d in Dir4::ALL {
                if let Some(n) = labels.step(c, d) {
                    if seen.insert(n) {
                        queue.push_back(n);
                    }
                }
            }
        }
        if let Some(to) = found {
            for &c in &cells[l as usize] {
                labels[c] = to;
            }
        }
    }
}
