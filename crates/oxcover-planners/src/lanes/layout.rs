//! Lane layout: where lanes may run, and the lanes and chains of one angle.
//!
//! The lane mask is the C-space at least a cell and a tool radius from the
//! walls (the loops cover the strip along them; a room cut is no wall).
//! At an angle its lines lie at most a tool width apart (less the margin of
//! the contract's samples), spread evenly over the mask's extent less an
//! inset at either side: the outermost lines lie where their reach just
//! meets the loops', so that no line is spent on the strip a loop covers.
//! Each line's runs inside the mask, sampled every quarter cell and cut
//! where a run grazes a blocked corner, are its lanes; two runs either side
//! of a small island are one lane, driven round it. Lanes on neighbouring
//! lines that overlap one to one form a chain (a boustrophedon cell),
//! driven back and forth with a half turn at each end.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): with the lines
//! spread over the whole mask instead of inset, 2.7 % (ipa) / 2.5 % (ROS)
//! slower.

use std::f64::consts::PI;

use oxcover_grid::edt::{boundary_distance_sq4, center_within_sq};
use oxcover_grid::math::{fast_ceil, fast_floor};
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear};
use oxcover_grid::{Cell, Grid};

use super::loops::OUTSET;
use crate::time::TimeModel;

/// Shift of every lane line off the cell edges it would otherwise run
/// along (cells).
const EDGE_NUDGE: f64 = 1e-4;

/// By how much (cells) the outermost lanes' reach still overlaps the
/// loops' (0.05: the margin of those measured that made the plans fastest).
pub(super) const LINE_MARGIN: f64 = 0.05;

/// The lane mask and each of its cells' clearance.
pub(super) struct LaneMask {
    /// Where lanes may run ([`lane_mask`]).
    pub(super) cells: Grid<bool>,
    /// Four times the squared distance (cells) from each cell's centre to
    /// the boundary of its nearest cell outside the mask: a line skips the
    /// samples surely inside.
    clearance: Vec<u64>,
}

impl LaneMask {
    /// The lane mask of `plannable` with walls where `admissible` is not
    /// set, for a tool of `tool` cells.
    pub(super) fn new(plannable: &Grid<bool>, admissible: &Grid<bool>, tool: f64) -> Self {
        let cells = lane_mask(plannable, admissible, tool);
        let clearance = boundary_distance_sq4(&cells.map(|&m| !m), true).into_vec();
        Self { cells, clearance }
    }
}

/// What laying lanes at an angle over a region needs.
pub(super) struct Layout<'a> {
    pub(super) plannable: &'a Grid<bool>,
    pub(super) mask: &'a LaneMask,
    /// The small islands lanes pass (none for a tool under a cell).
    islands: Option<&'a Grid<bool>>,
    /// Most distance between lines (cells).
    pub(super) spacing: f64,
    /// How far in from the mask's edges the outermost lines lie (cells).
    pub(super) inset: f64,
    /// Speeds in cells per second.
    pub(super) time: &'a TimeModel,
}

impl<'a> Layout<'a> {
    /// The layout for a tool of `tool` cells: lines one tool width apart,
    /// less the margin of the contract's samples (a quarter of a cell
    /// apart along the path); through the cell centres, a row or column
    /// apart, for a tool under a cell. The outermost lines are inset to
    /// meet the loops' reach if `inset_lines`.
    pub(super) fn new(
        plannable: &'a Grid<bool>,
        mask: &'a LaneMask,
        islands: Option<&'a Grid<bool>>,
        tool: f64,
        time: &'a TimeModel,
        inset_lines: bool,
    ) -> Self {
        let narrow = tool < 1.0;
        let spacing = if narrow {
            1.0
        } else {
            2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999
        };
        // The outermost lines sit further in than the lane mask's edge,
        // where their reach meets the loops' (a loop runs `OUTSET` off the
        // boundary cells' centres, towards the wall, and reaches a tool
        // radius from there; the mask's edge is a cell and a tool radius
        // from the wall): a line less along every wall. A room cut, where
        // no loop runs, is a cell from the claimed cells' edge: the line
        // still reaches past it.
        let inset = if narrow || !inset_lines {
            0.0
        } else {
            (tool - OUTSET - LINE_MARGIN).max(0.0)
        };
        Self {
            plannable,
            mask,
            islands,
            spacing,
            inset,
            time,
        }
    }

    /// The chains at direction `theta` (grid frame) and the distance
    /// between their lines ([`chains_bridged`]).
    pub(super) fn chains(&self, theta: f64) -> (Vec<Chain>, f64) {
        chains_bridged(
            self.plannable,
            &self.mask.cells,
            Some(&self.mask.clearance),
            self.islands,
            theta,
            self.spacing,
            self.inset,
        )
    }
}

/// The modelled seconds of `chains` (lines `step` apart, at most `spacing`)
/// over an area of `area` lane-mask cells: their own time, and what their
/// lanes leave of the area (corners cut by slanted lane ends) covered by
/// detours, about three times slower than lanes.
pub(super) fn modelled_time(
    chains: &[Chain],
    step: f64,
    area: f64,
    spacing: f64,
    time: &TimeModel,
) -> f64 {
    let t: f64 = chains.iter().map(|c| c.time(time, spacing)).sum();
    let lanes: f64 = chains.iter().flat_map(|c| &c.lanes).map(Lane::length).sum();
    let uncovered = (area - lanes * step.max(1.0)).max(0.0);
    t + 3.0 * time.time(uncovered / spacing, 0.0)
}

/// Where lanes may run: the plannable cells at least a cell and a tool
/// radius (`tool` cells) from every non-admissible cell and from the
/// grid's edge. Walls only: a room cut is no wall, lanes run up to it.
pub(super) fn lane_mask(plannable: &Grid<bool>, admissible: &Grid<bool>, tool: f64) -> Grid<bool> {
    let blocked = admissible.map(|&a| !a);
    let inset = 1.0 + tool;
    // An integer d² is at least inset² when at least its ceiling: not
    // within one less.
    let near = center_within_sq(&blocked, (inset * inset).ceil() as u64 - 1);
    let (w, h) = (plannable.width(), plannable.height());
    Grid::from_fn(w, h, |c| {
        // Beyond the grid counts as blocked too.
        let edge = (c.row + 1).min(c.col + 1).min(h - c.row).min(w - c.col) as f64;
        plannable[c] && !near[c] && edge >= inset
    })
}

/// A lane: a clear straight segment in grid coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Lane {
    pub(super) a: GridPoint,
    pub(super) b: GridPoint,
}

impl Lane {
    /// Its length (cells).
    pub(super) fn length(&self) -> f64 {
        (self.b - self.a).norm()
    }
}

/// Lanes on consecutive lines driven back and forth.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Chain {
    pub(super) lanes: Vec<Lane>,
}

impl Chain {
    /// Estimated seconds: lanes and links at speed, a half turn per link,
    /// and a turn plus a spacing of transit per chain.
    pub(super) fn time(&self, t: &TimeModel, spacing: f64) -> f64 {
        let lanes: f64 = self.lanes.iter().map(Lane::length).sum();
        let links = self.lanes.len().saturating_sub(1) as f64;
        t.time(lanes + links * spacing, links * PI) + t.time(spacing, PI / 2.0)
    }

    /// Entry and exit of option `k` (bit 0: from the last lane; bit 1:
    /// starting at each lane's `b` end).
    pub(super) fn ends(&self, k: usize) -> (GridPoint, GridPoint) {
        let seq = self.sequence(k);
        (seq[0], seq[seq.len() - 1])
    }

    /// The points driven under option `k`.
    pub(super) fn sequence(&self, k: usize) -> Vec<GridPoint> {
        let backwards = k & 1 == 1;
        let mut flip = k & 2 == 2;
        let idx: Vec<usize> = if backwards {
            (0..self.lanes.len()).rev().collect()
        } else {
            (0..self.lanes.len()).collect()
        };
        let mut pts = Vec::with_capacity(2 * idx.len());
        for i in idx {
            let l = self.lanes[i];
            if flip {
                pts.extend([l.b, l.a]);
            } else {
                pts.extend([l.a, l.b]);
            }
            flip = !flip;
        }
        pts
    }
}

/// The chains of lanes at direction `theta` (grid coordinates), lines at
/// most `spacing` apart spread evenly over the lane mask's extent less
/// `inset` at either side, and the distance between lines.
pub(super) fn chains_at(
    plannable: &Grid<bool>,
    lane_mask: &Grid<bool>,
    clearance: Option<&[u64]>,
    theta: f64,
    spacing: f64,
    inset: f64,
) -> (Vec<Chain>, f64) {
    chains_bridged(plannable, lane_mask, clearance, None, theta, spacing, inset)
}

/// [`chains_at`], with two runs of a line joined into one lane where the
/// gap between them holds only plannable cells and cells of `islands`
/// (and some of the latter): the lane is driven round the island.
pub(super) fn chains_bridged(
    plannable: &Grid<bool>,
    lane_mask: &Grid<bool>,
    clearance: Option<&[u64]>,
    islands: Option<&Grid<bool>>,
    theta: f64,
    spacing: f64,
    inset: f64,
) -> (Vec<Chain>, f64) {
    let d = GridPoint::new(theta.cos(), theta.sin());
    let n = GridPoint::new(-d.y, d.x);
    let (mut nmin, mut nmax) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut dmin, mut dmax) = (f64::INFINITY, f64::NEG_INFINITY);
    // The mask's box (cells), for the samples below.
    let (mut rmin, mut rmax, mut cmin, mut cmax) = (usize::MAX, 0, usize::MAX, 0);
    for row in 0..lane_mask.height() {
        let cells = lane_mask.row(row);
        let (Some(first), Some(last)) = (
            cells.iter().position(|&x| x),
            cells.iter().rposition(|&x| x),
        ) else {
            continue;
        };
        (rmin, rmax) = (rmin.min(row), rmax.max(row));
        (cmin, cmax) = (cmin.min(first), cmax.max(last));
        // Along a row both projections are monotone in the column (so is
        // their rounding): a row's first and last cells hold its extremes.
        for col in [first, last] {
            let p = cell_center(Cell::new(row, col));
            let (u, v) = (p.x * d.x + p.y * d.y, p.x * n.x + p.y * n.y);
            nmin = nmin.min(v);
            nmax = nmax.max(v);
            dmin = dmin.min(u);
            dmax = dmax.max(u);
        }
    }
    if !nmin.is_finite() {
        return (Vec::new(), spacing);
    }
    let inset = inset.min((nmax - nmin) / 2.0);
    let (nmin, nmax) = (nmin + inset, nmax - inset);
    let extent = nmax - nmin;
    let lines = (extent / spacing).ceil().max(0.0) as usize + 1;
    let step = if lines > 1 {
        extent / (lines - 1) as f64
    } else {
        0.0
    };
    let at = |u: f64, v: f64| GridPoint::new(u * d.x + v * n.x, u * d.y + v * n.y);
    // Runs of the lane mask along each line, sampled every quarter cell.
    let mut rows: Vec<Vec<(f64, f64)>> = Vec::with_capacity(lines);
    // Samples and lines off the cell edges (a point exactly on an edge is
    // in one cell here and may be in its neighbour once in metres).
    let (u0, u1) = (dmin - 1.0 + 0.125, dmax + 1.0);
    let samples = ((u1 - u0) / 0.25).ceil() as usize;
    // The samples of a line that may fall in the mask's box widened by a
    // cell (the margin covers rounding): those before and after are
    // outside the mask, and a run neither starts nor goes on there.
    let in_box = |v: f64| -> std::ops::Range<usize> {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for (dk, nk, k0, k1) in [
            (d.x, n.x, cmin as f64 - 1.0, cmax as f64 + 2.0),
            (d.y, n.y, rmin as f64 - 1.0, rmax as f64 + 2.0),
        ] {
            // u·dk + v·nk within [k0, k1].
            if dk.abs() < 1e-12 {
                if !(k0..=k1).contains(&(v * nk)) {
                    return 0..0;
                }
            } else {
                let (a, b) = ((k0 - v * nk) / dk, (k1 - v * nk) / dk);
                lo = lo.max(a.min(b));
                hi = hi.min(a.max(b));
            }
        }
        if lo > hi {
            return 0..0;
        }
        let first = fast_floor((lo - u0) / 0.25 - 1.0).max(0.0);
        let last = fast_ceil((hi - u0) / 0.25 + 1.0).min(samples as f64);
        if first > last {
            return 0..0;
        }
        first as usize..last as usize + 1
    };
    let (w, h) = (lane_mask.width() as f64, lane_mask.height() as f64);
    let (mask, width) = (lane_mask.as_slice(), lane_mask.width());
    for j in 0..lines {
        let v = nmin + step * j as f64 + EDGE_NUDGE;
        let mut runs = Vec::new();
        let mut open: Option<f64> = None;
        let mut last_in = u0;
        // `at(u, v)` and `cell_of` on the lane mask, term for term, with
        // the line's own terms once per line.
        let (vx, vy) = (v * n.x, v * n.y);
        let range = in_box(v);
        let mut s = range.start;
        while s < range.end {
            let u = u0 + s as f64 * 0.25;
            let (x, y) = (u * d.x + vx, u * d.y + vy);
            let cell = (x >= 0.0 && y >= 0.0 && x < w && y < h)
                .then(|| (fast_floor(x), fast_floor(y)))
                .filter(|&(cx, cy)| mask[cy as usize * width + cx as usize]);
            let inside = cell.is_some();
            match (inside, open) {
                (true, None) => open = Some(u),
                (false, Some(o)) => {
                    runs.push((o, last_in));
                    open = None;
                }
                _ => {}
            }
            if let Some((cx, cy)) = cell {
                last_in = u;
                // The next samples within the cell's clearance less the
                // sample's offset from its centre are inside too.
                if let Some(clear4) = clearance {
                    let reach = (clear4[cy as usize * width + cx as usize] as f64).sqrt() / 2.0
                        - (x - cx - 0.5).hypot(y - cy - 0.5)
                        - JUMP_MARGIN;
                    let k = (reach / 0.25).max(0.0) as usize;
                    if k > 0 {
                        s = (s + k).min(range.end - 1);
                        last_in = u0 + s as f64 * 0.25;
                    }
                }
            }
            s += 1;
        }
        if let Some(o) = open {
            runs.push((o, last_in));
        }
        // Keep the clear part of each run (a run may graze a blocked
        // corner between samples): split at the first blocked stretch.
        let mut clear = Vec::new();
        for (a, b) in runs {
            split_clear(plannable, &at, v, a, b, &mut clear);
        }
        if let Some(isl) = islands {
            let mut merged: Vec<(f64, f64)> = Vec::with_capacity(clear.len());
            for r in clear {
                if let Some(last) = merged.last_mut() {
                    if bridgeable(plannable, isl, &at, v, last.1, r.0) {
                        last.1 = r.1;
                        continue;
                    }
                }
                merged.push(r);
            }
            clear = merged;
        }
        rows.push(clear);
    }
    // Chain runs of consecutive lines that overlap one to one.
    let overlaps = |x: (f64, f64), y: (f64, f64)| x.0.max(y.0) <= x.1.min(y.1);
    let mut chains: Vec<Chain> = Vec::new();
    let mut open_chain: Vec<Option<usize>> = Vec::new(); // per run of the previous line
    for j in 0..rows.len() {
        let mut now: Vec<Option<usize>> = vec![None; rows[j].len()];
        for (i, &r) in rows[j].iter().enumerate() {
            let v = nmin + step * j as f64 + EDGE_NUDGE;
            let lane = Lane {
                a: at(r.0, v),
                b: at(r.1, v),
            };
            let mut joined = None;
            if j > 0 {
                let prev: Vec<usize> = (0..rows[j - 1].len())
                    .filter(|&k| overlaps(rows[j - 1][k], r))
                    .collect();
                if let [k] = prev[..] {
                    let forward = rows[j]
                        .iter()
                        .filter(|&&q| overlaps(rows[j - 1][k], q))
                        .count();
                    if forward == 1 {
                        joined = open_chain.get(k).copied().flatten();
                    }
                }
            }
            let id = match joined {
                Some(id) => {
                    chains[id].lanes.push(lane);
                    id
                }
                None => {
                    chains.push(Chain { lanes: vec![lane] });
                    chains.len() - 1
                }
            };
            now[i] = Some(id);
        }
        open_chain = now;
    }
    (chains, if lines > 1 { step } else { spacing })
}

/// Slack (cells) kept when a line skips the samples within a mask cell's
/// clearance: rounding never decides that a sample is inside.
const JUMP_MARGIN: f64 = 1e-6;

/// Pushes the clear sub-runs of `[a, b]` on line `v` into `out`.
fn split_clear(
    plannable: &Grid<bool>,
    at: &impl Fn(f64, f64) -> GridPoint,
    v: f64,
    a: f64,
    b: f64,
    out: &mut Vec<(f64, f64)>,
) {
    if segment_clear(plannable, at(a, v), at(b, v)) {
        out.push((a, b));
        return;
    }
    // Walk in quarter cells, keeping maximal clear stretches.
    let mut s = a;
    let mut u = a;
    while u < b {
        let next = (u + 0.25).min(b);
        if !segment_clear(plannable, at(u, v), at(next, v)) {
            if u > s {
                out.push((s, u));
            }
            s = next;
        }
        u = next;
    }
    if b > s && segment_clear(plannable, at(s, v), at(b, v)) {
        out.push((s, b));
    }
}

/// Whether the gap `a..b` of line `v` holds only plannable and island
/// cells, and at least one island cell.
fn bridgeable(
    plannable: &Grid<bool>,
    islands: &Grid<bool>,
    at: &impl Fn(f64, f64) -> GridPoint,
    v: f64,
    a: f64,
    b: f64,
) -> bool {
    let mut island = false;
    let mut u = a;
    while u <= b {
        let Some(c) = cell_of(plannable, at(u, v)) else {
            return false;
        };
        if islands[c] {
            island = true;
        } else if !plannable[c] {
            return false;
        }
        u += 0.25;
    }
    island
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::loops::OUTSET;

    /// In a 40 × 24 room with a tool of 3 cells, the lane mask spans rows 4
    /// to 19 (centres 4.5 to 19.5): spread over all of it, four lines lie
    /// on its edges, in the loops' strip; moved in by the inset, three lines
    /// cover the same mask, the first and last an inset off its edges.
    #[test]
    fn the_outermost_lines_keep_off_the_loops_strip() {
        let plannable = Grid::new(40, 24, true);
        let lane_mask = Grid::from_fn(40, 24, |c: Cell| (4..20).contains(&c.row));
        let spacing = 2.0 * (9.0f64 - 1.0 / 64.0).sqrt() * 0.999;
        let rows = |inset: f64| -> Vec<f64> {
            let (chains, _) = chains_at(&plannable, &lane_mask, None, 0.0, spacing, inset);
            let mut v: Vec<f64> = chains
                .iter()
                .flat_map(|c| &c.lanes)
                .map(|l| ((l.a.y - EDGE_NUDGE) * 1e6).round() / 1e6)
                .collect();
            v.sort_by(f64::total_cmp);
            v
        };
        let inset = 3.0 - OUTSET - LINE_MARGIN;
        assert_eq!(rows(0.0), vec![4.5, 9.5, 14.5, 19.5]);
        assert_eq!(rows(inset), vec![7.0, 12.0, 17.0]);
        // Where the mask is narrower than two insets, one line down its middle.
        let thin = Grid::from_fn(40, 24, |c: Cell| (10..13).contains(&c.row));
        let (chains, _) = chains_at(&plannable, &thin, None, 0.0, spacing, inset);
        let ys: Vec<f64> = chains
            .iter()
            .flat_map(|c| &c.lanes)
            .map(|l| l.a.y)
            .collect();
        assert_eq!(ys.len(), 1);
        assert!((ys[0] - EDGE_NUDGE - 11.5).abs() < 1e-9, "{ys:?}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(40))]
        /// Lines that skip the samples within the lane mask's clearance
        /// find the same chains as lines sampled all along.
        #[test]
        fn skipping_the_clear_samples_finds_the_same_chains(
            seed in 0u64..1000,
            blobs in 1usize..8,
            theta in 0.0f64..std::f64::consts::PI,
            tool in 1.0f64..4.0,
        ) {
            let map = oxcover_grid::random::blobs(61, 47, blobs, 5, seed);
            let plannable = map.free_mask();
            let mask = lane_mask(&plannable, &plannable, tool);
            let clearance = boundary_distance_sq4(&mask.map(|&m| !m), true).into_vec();
            let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
            let inset = (tool - OUTSET - LINE_MARGIN).max(0.0);
            let all = chains_at(&plannable, &mask, None, theta, spacing, inset);
            let skipping = chains_at(&plannable, &mask, Some(&clearance), theta, spacing, inset);
            proptest::prop_assert_eq!(all, skipping);
        }
    }
}
