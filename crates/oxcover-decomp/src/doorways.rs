//! Room segmentation by doorways: a room ends where its wall has a gap.
//!
//! 1. The clearance of every free cell and the medial axis of the free
//!    space, as in [`crate::voronoi_rooms`].
//! 2. **Critical lines**: at every axis cell no wider than half a door, the
//!    segment between its two nearest obstacle points on opposite sides
//!    (the survey's critical line through a critical point).
//! 3. **Doorways**: a critical line is a doorway cut where at least one of
//!    its ends is a wall end in line with it: beyond that end the obstacle
//!    runs on along the line for [`JAMB_RUN_M`], as a thin wall (free
//!    space beside it within [`WALL_HALF_M`]). A gap between two wall ends
//!    (a door in a wall), or between a wall end and the face of another wall
//!    (a door in a wall junction), is cut whatever the clearance of the
//!    spaces it joins: a door wider than the corridor it opens into is
//!    still a door. The sides of a corridor or a room cross the line at a
//!    right angle, or end in the outside: no cut.
//! 4. **Rooms**: the free space minus the cuts falls into regions. Two
//!    regions a cut joins stay one room where the cut is not narrow beside
//!    the wider of the two spaces (its half width above [`NARROW`] of that
//!    space's clearance): the entrance of a side corridor, a wide opening
//!    into a hall. Regions below the smallest room join the neighbour they
//!    share the longest border with; the cuts go back to the rooms beside
//!    them (breadth first).
//!
//! Labels are numbered top-left first: rooms of at least the smallest area
//! in row-major order of their first cell, then the smaller free regions.
//!
//! Written for this workspace after the critical lines of Bormann et al.
//! 2016 ("Room segmentation: survey, implementation, and analysis"), with
//! this departure: a critical line is a door by the walls at its ends, not
//! by the clearance along the axis (a local minimum there misses doors
//! wider than the corridor they open into) and no merging heuristic on
//! room shape follows.

use std::collections::{BTreeMap, VecDeque};

use rayon::prelude::*;

use oxcover_grid::edt::boundary_distance_sq4;
use oxcover_grid::traverse::traverse;
use oxcover_grid::{Cell, Dir4, Grid, components4};

use crate::rooms::{Door, RoomParams, Rooms, doors, grow, label_the_rest, merge_small_regions};
use crate::voronoi_rooms::axis_cells_in;

/// How far (m) the wall must run on in line beyond a doorway's end.
const JAMB_RUN_M: f64 = 0.8;

/// Cells of thin wall a jamb needs before it may meet another wall (a door
/// beside a corner).
const JUNCTION_CELLS: usize = 3;

/// Half the thickness (m) of the thickest wall taken for a jamb.
const WALL_HALF_M: f64 = 0.5;

/// Narrowest doorway (m): narrower gaps (between chairs, behind a table)
/// are no doors.
const MIN_DOOR_M: f64 = 0.1;

/// Largest share of the wider space's clearance a cut's half width may
/// have to keep two regions apart.
const NARROW: f64 = 0.7;

/// Longest opening (m) closed by continuing a wall to the wall ahead.
const EXTENSION_M: f64 = 4.5;

/// How long (m) a wall must run behind its end to be continued, and how
/// far the wall it meets must run on beside the meeting point.
const EXT_WALL_M: f64 = 1.0;

/// Smallest room (m²) a wall's continuation alone keeps apart.
const EXT_MIN_M2: f64 = 4.0;

/// Largest piece (m²) of passage between cuts that joins a neighbour.
const PIECE_M2: f64 = 2.0;

/// Least share of a piece's border that is cut.
const PIECE_CUT: f64 = 0.4;

/// Least angle between a critical line's two ends seen from its axis
/// cell: the two nearest obstacle points lie on opposite sides.
const OPPOSITE_COS: f64 = -0.8;

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

/// Segments the free cells of `free` into rooms at their doorways (see the
/// module docs).
#[must_use]
pub fn doorways(free: &Grid<bool>, params: &RoomParams) -> Rooms {
    // Work on the free cells' bounding box and a cell round it: nothing
    // outside it is free, so nothing there can change a label.
    let (w, h) = (free.width(), free.height());
    let (mut r0, mut r1, mut c0, mut c1) = (h, 0, w, 0);
    for (r, row) in free.as_slice().chunks(w.max(1)).enumerate() {
        if let (Some(a), Some(b)) = (row.iter().position(|&f| f), row.iter().rposition(|&f| f)) {
            (r0, r1) = (r0.min(r), r1.max(r + 1));
            (c0, c1) = (c0.min(a), c1.max(b + 1));
        }
    }
    if r0 >= r1 {
        return relabel(Grid::new(w, h, 0), 1.0);
    }
    let (r0, c0) = (r0.saturating_sub(1), c0.saturating_sub(1));
    let (r1, c1) = ((r1 + 1).min(h), (c1 + 1).min(w));
    if (r0, c0, r1, c1) == (0, 0, h, w) {
        return doorways_in(free, params);
    }
    let iw = c1 - c0;
    let rows = free.as_slice().chunks(w).skip(r0).take(r1 - r0);
    let inner: Vec<bool> = rows.flat_map(|row| &row[c0..c1]).copied().collect();
    let Some(inner) = Grid::from_vec(iw, r1 - r0, inner) else {
        return doorways_in(free, params);
    };
    let part = doorways_in(&inner, params);
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

/// [`doorways`] on the whole of `free`.
fn doorways_in(free: &Grid<bool>, params: &RoomParams) -> Rooms {
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
    let blocked = free.map(|&f| !f);
    let d4 = boundary_distance_sq4(&blocked, true);
    let clearance = |c: Cell| (d4[c] as f64).sqrt() / 2.0;
    let rings = rings(door_half);
    let narrowest_door = (MIN_DOOR_M / 2.0 * per_metre).max(1.5);
    // Critical lines of the narrow axis cells, kept where a wall ends in line.
    // (In parallel, in the axis cells' row-major order whatever the thread
    // count.)
    let (lo4, hi4) = (
        (4.0 * narrowest_door * narrowest_door).floor() as u64,
        (4.0 * door_half * door_half).ceil() as u64,
    );
    let narrow_axis: Vec<Cell> = axis_cells_in(free, &d4, lo4..=hi4)
        .into_iter()
        .filter(|&c| (narrowest_door..=door_half).contains(&clearance(c)))
        .collect();
    let cuts: Vec<Cut> = narrow_axis
        .par_iter()
        .filter_map(|&c| critical_line(free, &rings, c, clearance(c)))
        .filter(|cut| {
            jamb(free, cut.b, cut.a, run, wall_half) || jamb(free, cut.a, cut.b, run, wall_half)
        })
        .collect();
    let mut cuts = cuts;
    cuts.extend(extension_cuts(free, door_half, per_metre, wall_half));
    let cut_cells: Vec<Vec<Cell>> = cuts.iter().map(|cut| cut_cells_of(free, cut)).collect();
    let mut on_cut = Grid::new(w, h, false);
    for &c in cut_cells.iter().flatten() {
        on_cut[c] = true;
    }
    let open = Grid::from_fn(w, h, |c| free[c] && !on_cut[c]);
    let regions = components4(&open);
    let mut labels = regions.labels;
    let count = regions.sizes.len();
    // Each region's widest clearance.
    let mut peak = vec![0.0f64; count + 1];
    for c in open.true_cells() {
        let l = labels[c] as usize;
        peak[l] = peak[l].max(clearance(c));
    }
    // The regions each cut joins, and the widest cut between each pair.
    let mut pairs: BTreeMap<(u32, u32), (f64, bool)> = BTreeMap::new();
    for (cut, cells) in cuts.iter().zip(&cut_cells) {
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
    for (i, &n) in regions.sizes.iter().enumerate() {
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
    for c in open.true_cells() {
        let (mut edge, mut cut) = (false, false);
        for d in Dir4::ALL {
            match free.step(c, d) {
                Some(n) if on_cut[n] => (edge, cut) = (true, true),
                Some(n) if free[n] => {}
                _ => edge = true,
            }
        }
        let b = &mut border[labels[c] as usize];
        b.0 += usize::from(edge);
        b.1 += usize::from(cut);
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
    for l in labels.as_mut_slice() {
        if *l != 0 {
            *l = find(&mut parent, *l);
        }
    }
    // The cuts go back to the rooms beside them.
    // (Only labelled cells beside an unlabelled free one can label any.)
    let mut queue: VecDeque<Cell> = cut_cells
        .iter()
        .flatten()
        .flat_map(|&c| Dir4::ALL.into_iter().filter_map(move |d| free.step(c, d)))
        .filter(|&n| labels[n] != 0)
        .collect();
    grow(free, &mut labels, &mut queue);
    label_the_rest(free, &mut labels, count as u32 + 1);
    merge_small_regions(&mut labels, min_cells);
    join_pockets(&mut labels, min_cells);
    relabel(labels, min_cells)
}

/// For each whole clearance `R` up to `most`, the offsets of the cells
/// whose square may hold a point at a distance between `R` and `R + 2.5`
/// from a cell's centre: where [`critical_line`] looks for the nearest
/// obstacle points of a cell of clearance in `R..R + 1` (nothing is nearer
/// than the clearance).
fn rings(most: f64) -> Vec<Vec<(isize, isize)>> {
    let top = most.max(0.0).ceil() as usize + 1;
    (0..=top)
        .map(|big_r| {
            let (lo, hi) = (big_r as f64 - 0.75, big_r as f64 + 2.5 + 0.75);
            let k = hi.ceil() as isize;
            (-k..=k)
                .flat_map(|dr| (-k..=k).map(move |dc| (dr, dc)))
                .filter(|&(dr, dc)| {
                    let d = (dr as f64).hypot(dc as f64);
                    d >= lo && d <= hi
                })
                .collect()
        })
        .collect()
}

/// The critical line through axis cell `c` of clearance `r`: the segment
/// between its two nearest obstacle points on opposite sides, if it has
/// two such.
fn critical_line(free: &Grid<bool>, rings: &[Vec<(isize, isize)>], c: Cell, r: f64) -> Option<Cut> {
    let centre = (c.col as f64 + 0.5, c.row as f64 + 0.5);
    let ring = rings.get(r.floor() as usize)?;
    let mut near: Vec<(Pt, f64)> = Vec::new();
    for &(dr, dc) in ring {
        let (row, col) = (c.row as isize + dr, c.col as isize + dc);
        let inside =
            row >= 0 && col >= 0 && (row as usize) < free.height() && (col as usize) < free.width();
        if inside && free[Cell::new(row as usize, col as usize)] {
            continue;
        }
        // The point of the cell's square nearest the centre.
        let q = (
            centre.0.clamp(col as f64, col as f64 + 1.0),
            centre.1.clamp(row as f64, row as f64 + 1.0),
        );
        let d = (q.0 - centre.0).hypot(q.1 - centre.1);
        if d <= r + 1.5 {
            near.push((q, d));
        }
    }
    // The pair farthest apart in angle, nearest first on ties.
    let mut best: Option<(f64, Pt, Pt)> = None;
    for (i, &(p, dp)) in near.iter().enumerate() {
        for &(q, dq) in &near[i + 1..] {
            let (ux, uy) = (p.0 - centre.0, p.1 - centre.1);
            let (vx, vy) = (q.0 - centre.0, q.1 - centre.1);
            let cos = (ux * vx + uy * vy) / (dp * dq).max(1e-9);
            if cos > OPPOSITE_COS {
                continue;
            }
            if best.is_none_or(|b| cos < b.0 - 1e-9) {
                best = Some((cos, p, q));
            }
        }
    }
    let (_, a, b) = best?;
    Some(Cut {
        a,
        b,
        half: r,
        extension: false,
    })
}

/// Whether beyond `end` (coming from `from`) the obstacle runs on in line
/// as a thin wall for `run` cells, or for [`JUNCTION_CELLS`] up to another
/// wall it meets: every point along the line past `end` is in a non-free
/// cell (or beside one, a cell's tolerance) of a wall at most
/// `2 · wall_half` cells thick, free space on both its sides.
fn jamb(free: &Grid<bool>, from: Pt, end: Pt, run: f64, wall_half: f64) -> bool {
    let (dx, dy) = (end.0 - from.0, end.1 - from.1);
    let len = dx.hypot(dy);
    if len < 1e-9 {
        return false;
    }
    let (ux, uy) = (dx / len, dy / len);
    let (nx, ny) = (-uy, ux);
    let blocked_at = |x: f64, y: f64| {
        let (col, row) = (x.floor(), y.floor());
        col < 0.0
            || row < 0.0
            || col as usize >= free.width()
            || row as usize >= free.height()
            || !free[Cell::new(row as usize, col as usize)]
    };
    let free_at = |x: f64, y: f64| !blocked_at(x, y);
    let steps = run.ceil().max(1.0) as usize;
    for k in 0..steps {
        let t = k as f64 + 0.5;
        let (x, y) = (end.0 + ux * t, end.1 + uy * t);
        let on_wall = blocked_at(x, y)
            || blocked_at(x + nx * 0.7, y + ny * 0.7)
            || blocked_at(x - nx * 0.7, y - ny * 0.7);
        if !on_wall {
            return false;
        }
        // A thin wall: free on both sides, at most two half thicknesses
        // apart.
        let most = (2.0 * wall_half).ceil().max(1.0) as usize;
        let reach = |sx: f64, sy: f64| {
            (0..=most).find(|&j| {
                let j = j as f64;
                free_at(x + sx * j, y + sy * j)
            })
        };
        match (reach(nx, ny), reach(-nx, -ny)) {
            (Some(p), Some(q)) if (p + q) as f64 <= 2.0 * wall_half + 1.0 => {}
            // The wall meets another (a corner, a junction): a jamb if it
            // ran thin for a few cells first.
            _ => return k >= JUNCTION_CELLS,
        }
    }
    true
}

/// Cuts that continue a wall across an opening wider than a door: from
/// each cell that ends a thin wall running along a grid axis for
/// [`EXT_WALL_M`] behind it, straight on over free cells to the first
/// obstacle, where that lies between a door's width and [`EXTENSION_M`]
/// ahead and is the face of a wall that runs on beside the meeting point
/// for [`EXT_WALL_M`] on one side at least.
fn extension_cuts(free: &Grid<bool>, door_half: f64, per_metre: f64, wall_half: f64) -> Vec<Cut> {
    let (w, h) = (free.width() as isize, free.height() as isize);
    let is_free = |x: isize, y: isize| {
        x >= 0 && y >= 0 && x < w && y < h && free[Cell::new(y as usize, x as usize)]
    };
    let behind = (EXT_WALL_M * per_metre).ceil().max(1.0) as isize;
    let most = (2.0 * wall_half).ceil().max(1.0) as isize;
    let (shortest, longest) = (
        (2.0 * door_half).floor() as isize,
        (EXTENSION_M * per_metre).floor() as isize,
    );
    // Free on both sides across a wall at most two half thicknesses
    // thick: the obstacle cells through (x, y) along (nx, ny), with a free
    // cell at both ends (not where they meet the grid's edge).
    let thin = |x: isize, y: isize, (nx, ny): (isize, isize)| {
        let mut run = 1;
        for s in [1, -1] {
            let mut k = 1;
            loop {
                let (px, py) = (x + s * nx * k, y + s * ny * k);
                if px < 0 || py < 0 || px >= w || py >= h {
                    return false;
                }
                if is_free(px, py) {
                    break;
                }
                run += 1;
                if run > most {
                    return false;
                }
                k += 1;
            }
        }
        true
    };
    let cells = free.as_slice();
    // Row by row in parallel, the rows' cuts in row order.
    let rows: Vec<(Vec<Cut>, Vec<End>)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let (mut out, mut ends) = (Vec::new(), Vec::new());
            for x in 0..w {
                let i = y as usize * free.width() + x as usize;
                if cells[i] {
                    continue;
                }
                for (dx, dy) in [(1, 0), (0, 1), (-1, 0), (0, -1)] {
                    if !is_free(x + dx, y + dy) {
                        continue;
                    }
                    let n = (-dy, dx);
                    let wall = (0..=behind).all(|k| {
                        let (bx, by) = (x - dx * k, y - dy * k);
                        !is_free(bx, by) && thin(bx, by, n)
                    });
                    if !wall {
                        continue;
                    }
                    ends.push(End { x, y, dx, dy });
                    let Some(k) = (1..=longest + 1).find(|&k| !is_free(x + dx * k, y + dy * k))
                    else {
                        continue;
                    };
                    if k - 1 <= shortest || k > longest {
                        continue;
                    }
                    // The wall met runs on beside the meeting point.
                    let (hx, hy) = (x + dx * k, y + dy * k);
                    let face = |s: isize| {
                        (0..=behind).all(|j| !is_free(hx + s * n.0 * j, hy + s * n.1 * j))
                    };
                    // Or it is a thin wall in line (a gap in a wall).
                    let in_line = (0..=behind).all(|j| {
                        let (ax, ay) = (hx + dx * j, hy + dy * j);
                        !is_free(ax, ay) && thin(ax, ay, n)
                    });
                    // Beside a gap, the space on one side at least is
                    // wider than the gap (a room, not a corridor crossing).
                    let wide = |side: isize| {
                        (2..=5).all(|step| {
                            let off = side * step * behind / 2;
                            let (mx, my) = (x + dx * k / 2 + n.0 * off, y + dy * k / 2 + n.1 * off);
                            let run = |t: isize| {
                                (1..)
                                    .take_while(|&i| {
                                        is_free(mx + t * dx * i, my + t * dy * i) && i <= k + behind
                                    })
                                    .count() as isize
                            };
                            is_free(mx, my) && run(1) + run(-1) + 1 > k - 1 + behind / 2
                        })
                    };
                    let faced = face(1) || face(-1);
                    if !((faced || in_line) && (wide(1) || wide(-1))) {
                        continue;
                    }
                    out.push(Cut {
                        a: (x as f64 + 0.5, y as f64 + 0.5),
                        b: (hx as f64 + 0.5, hy as f64 + 0.5),
                        half: (k - 1) as f64 / 2.0,
                        // A wide gap in a wall is judged as a doorway.
                        extension: faced,
                    });
                }
            }
            (out, ends)
        })
        .collect();
    let mut cuts = Vec::new();
    let mut ends = Vec::new();
    for (c, e) in rows {
        cuts.extend(c);
        ends.extend(e);
    }
    cuts.extend(end_to_end_cuts(
        &is_free,
        &tips(ends),
        (shortest, longest),
        behind,
    ));
    cuts
}

/// The tip of a thin wall: an obstacle cell that ends it, and the way out
/// of it along the wall (a grid axis).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct End {
    dx: isize,
    dy: isize,
    x: isize,
    y: isize,
}

/// The tips of the walls whose end cells are `ends`: each run of end
/// cells side by side across one wall's end, as the point in the middle
/// of its face.
fn tips(mut ends: Vec<End>) -> Vec<Pt> {
    let key = |e: &End| (e.dx, e.dy, e.x * e.dx + e.y * e.dy, e.y * e.dx - e.x * e.dy);
    ends.sort_by_key(key);
    let mut out = Vec::new();
    let mut i = 0;
    while i < ends.len() {
        let mut j = i + 1;
        while j < ends.len() && {
            let (a, b) = (key(&ends[j - 1]), key(&ends[j]));
            (a.0, a.1, a.2) == (b.0, b.1, b.2) && b.3 == a.3 + 1
        } {
            j += 1;
        }
        let e = ends[(i + j - 1) / 2];
        out.push((
            e.x as f64 + 0.5 + e.dx as f64 * 0.5,
            e.y as f64 + 0.5 + e.dy as f64 * 0.5,
        ));
        i = j;
    }
    out
}

/// Cuts from each wall's tip to the nearest other tip, where that lies
/// between a door's width and [`EXTENSION_M`] away over free cells, and
/// the space on one side at least of the cut is wider than the cut (the
/// open side of a room, not a corridor's cross-section).
fn end_to_end_cuts(
    is_free: &(impl Fn(isize, isize) -> bool + Sync),
    tips: &[Pt],
    (shortest, longest): (isize, isize),
    behind: isize,
) -> Vec<Cut> {
    let free_at = |p: Pt| p.0 >= 0.0 && p.1 >= 0.0 && is_free(p.0 as isize, p.1 as isize);
    let mut pairs = std::collections::BTreeSet::new();
    for (i, &a) in tips.iter().enumerate() {
        let nearest = tips
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, &b)| ((b.0 - a.0).hypot(b.1 - a.1), j))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        if let Some((d, j)) = nearest {
            if d > shortest as f64 && d <= longest as f64 {
                pairs.insert((i.min(j), i.max(j)));
            }
        }
    }
    let mut out = Vec::new();
    for (i, j) in pairs {
        let (a, b) = (tips[i], tips[j]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let u = ((b.0 - a.0) / len, (b.1 - a.1) / len);
        let open = (2..(2.0 * len) as usize - 1).all(|k| {
            let t = k as f64 / 2.0;
            free_at((a.0 + u.0 * t, a.1 + u.1 * t))
        });
        if !open {
            continue;
        }
        let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let wide = |side: f64| {
            (2..=5).all(|step| {
                let off = side * (step * behind) as f64 / 2.0;
                let p = (mid.0 - u.1 * off, mid.1 + u.0 * off);
                let run = |t: f64| {
                    (1..)
                        .take_while(|&k| {
                            let k = f64::from(k);
                            k <= len + behind as f64
                                && free_at((p.0 + t * u.0 * k, p.1 + t * u.1 * k))
                        })
                        .count() as f64
                };
                free_at(p) && run(1.0) + run(-1.0) + 1.0 > len + behind as f64 / 2.0
            })
        };
        if wide(1.0) || wide(-1.0) {
            out.push(Cut {
                a,
                b,
                half: len / 2.0,
                extension: false,
            });
        }
    }
    out
}

/// The free cells a cut crosses, its ends pushed a cell into the walls so
/// that no diagonal leak is left beside them.
fn cut_cells_of(free: &Grid<bool>, cut: &Cut) -> Vec<Cell> {
    let (dx, dy) = (cut.b.0 - cut.a.0, cut.b.1 - cut.a.1);
    let len = dx.hypot(dy).max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let a = oxcover_grid::Point::new(cut.a.0 - ux, cut.a.1 - uy);
    let b = oxcover_grid::Point::new(cut.b.0 + ux, cut.b.1 + uy);
    let mut cells = Vec::new();
    traverse(free.width(), free.height(), a, b, |c, _, _| {
        if let Some(c) = c.filter(|&c| free[c]) {
            cells.push(c);
        }
        true
    });
    cells
}

/// Gives each region smaller than `min_cells` that no free cell joins to
/// another (a pocket of floor inside a ring of chairs, behind a table)
/// the label of the nearest larger region, across whatever lies between.
fn join_pockets(labels: &mut Grid<u32>, min_cells: f64) {
    let top = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let mut cells: Vec<Vec<Cell>> = vec![Vec::new(); top + 1];
    let mut size = vec![0usize; top + 1];
    for &l in labels.as_slice() {
        size[l as usize] += 1;
    }
    let small = |l: u32| l != 0 && (size[l as usize] as f64) < min_cells;
    if !(1..=top as u32).any(small) {
        return;
    }
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

/// `labels` renumbered top-left first: rooms of at least `min_cells` in
/// row-major order of their first cell, then the smaller free regions;
/// with their areas and doors.
fn relabel(mut labels: Grid<u32>, min_cells: f64) -> Rooms {
    let top = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let mut size = vec![0usize; top + 1];
    let mut first: Vec<u32> = Vec::new();
    for &l in labels.as_slice() {
        if l != 0 {
            if size[l as usize] == 0 {
                first.push(l);
            }
            size[l as usize] += 1;
        }
    }
    let big = |l: &u32| size[*l as usize] as f64 >= min_cells;
    let order: Vec<u32> = first
        .iter()
        .filter(|l| big(l))
        .chain(first.iter().filter(|l| !big(l)))
        .copied()
        .collect();
    let seeded = first.iter().filter(|l| big(l)).count();
    let mut fresh = vec![0u32; top + 1];
    for (i, &l) in order.iter().enumerate() {
        fresh[l as usize] = i as u32 + 1;
    }
    let mut areas = vec![0usize; order.len()];
    for l in labels.as_mut_slice() {
        if *l != 0 {
            let id = fresh[*l as usize];
            areas[id as usize - 1] += 1;
            *l = id;
        }
    }
    let doors = doors(&labels);
    Rooms {
        seeded,
        labels,
        areas,
        doors,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two rooms 60 × 40 cells, one above the other, a wall 4 cells thick
    /// between them with an 18-cell gap.
    fn two_rooms() -> Grid<bool> {
        Grid::from_fn(64, 90, |c: Cell| {
            let inside = (2..62).contains(&c.col) && (2..88).contains(&c.row);
            let wall = (43..47).contains(&c.row) && !(23..41).contains(&c.col);
            inside && !wall
        })
    }

    #[test]
    fn a_gap_in_a_thin_wall_is_a_door() {
        let free = two_rooms();
        let r = doorways(&free, &RoomParams::indoor(0.05));
        assert_eq!(r.count(), 2, "{:?}", r.areas);
    }
}
