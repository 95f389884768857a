//! Tightening: a path's vertices removed, moved towards the line of their
//! neighbours or slid along a piece, where that saves estimated time, stays
//! clear and leaves no coverable cell the path reached out of reach.
//!
//! Of the changes at a vertex the one saving the most is made (not the
//! first: 0.406 → 0.415 mean time efficiency on the ipa plans, rooms off).
//! Over a densely traced edge loop this, not the loop's first
//! straightening, is what takes out the turns of a ragged wall. A vertex's
//! moves are tested for clearance at once where the whole triangle of the
//! vertex and its neighbours is plannable (every move's point lies in it).
//! A long pass is split into a fixed number of bands of rows tightened in
//! parallel, each changing only the vertices whose change stays within its
//! rows, the rest afterwards one by one: the same path on any thread count.

use oxcover_grid::Grid;
use oxcover_grid::math::fast_floor;
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear, triangle_clear};
use rayon::prelude::*;

use super::Detours;
use super::geometry::{
    END, Linked, box_cells, cell_box, foot_on, off_edges, pieces, polyline_time,
};
use super::reach::{
    Counts, SAMPLE_GAP, near_pieces, pieces_reaching, sample_reaches, stroke_reaches, stroke_until,
};

/// How far along either piece a vertex is tried slid.
const SLIDES: [f64; 6] = [0.9, 0.75, 0.5, 0.25, 0.1, 0.03];

/// Passes over the path.
pub(super) const ROUNDS: usize = 8;

/// How far towards the line of its neighbours a vertex is tried moved.
const RELOCATIONS: [f64; 5] = [0.9, 0.75, 0.5, 0.25, 0.1];

/// Ways a vertex is tried replaced: removed, moved by each of
/// [`RELOCATIONS`], slid by each of [`SLIDES`] along either piece.
const MOVES: usize = 1 + RELOCATIONS.len() + 2 * SLIDES.len();

/// Largest box (cells) a vertex change looks at; larger triangles (the
/// corners of long lanes) are kept without a look.
const REMOVAL_BOX: usize = 4_000;

/// Where the vertices of a path may be moved: vertex `i` with a label
/// `of_vertex[i]` other than 0 only to a point of a cell with that label
/// in `labels` (the room it works in); removing it is always allowed.
pub(crate) struct Zone<'a> {
    pub labels: &'a Grid<u32>,
    pub of_vertex: &'a [u32],
}

impl Zone<'_> {
    fn allows(&self, v: usize, q: GridPoint) -> bool {
        match self.of_vertex.get(v) {
            None | Some(0) => true,
            Some(&z) => cell_of(self.labels, q).is_some_and(|c| self.labels[c] == z),
        }
    }
}

/// `points` tightened: each vertex from index `first` on is removed,
/// moved towards the line of its neighbours ([`RELOCATIONS`]) or slid
/// along one of its pieces ([`SLIDES`]), whichever saves the most
/// estimated time while clear, within its `zone` if one is given, and
/// leaving no coverable cell the path reached out of reach (the same
/// sample-exact counts as [`super::insert_detours`]); [`ROUNDS`] passes. The
/// vertices before `first` stay where they are, and still count for
/// coverage. After detours, some straightened corners and staircase
/// vertices are no longer needed and many are sharper than coverage
/// requires. `count` is how many segments of `points` reach each cell, as
/// [`super::insert_detours`] or [`super::reach_counts`] returns it. Returns the new
/// path, the index in `points` of each vertex kept (in order) and the
/// number of vertices removed or moved; and the result of `beside`, run
/// in parallel with the passes after the first (the first looks at every
/// vertex, in parallel where there are many; the later ones at the few
/// next to a change).
pub(crate) fn tighten_from<R: Send>(
    points: &[GridPoint],
    d: &Detours<'_>,
    count: Grid<u16>,
    first: usize,
    zone: Option<&Zone<'_>>,
    beside: impl FnOnce() -> R + Send,
) -> ((Vec<GridPoint>, Vec<usize>, usize), R) {
    let mut t = Tightening::new(points, count, first);
    t.pass(d, zone);
    let ((), beside) = rayon::join(|| while t.pass(d, zone) {}, beside);
    (t.finish(), beside)
}

/// A [`tighten_from`] in progress, pass by pass (so that a caller can
/// look at the path between passes and stop early).
pub(crate) struct Tightening {
    path: Linked,
    count: Grid<u16>,
    /// Which vertices the next pass looks at: those next to a change of
    /// the pass before (the first pass at all); the fixed ones never.
    dirty: Vec<bool>,
    first: usize,
    passes: usize,
    changes: usize,
    /// Whether the last pass changed nothing (or the path is too short).
    settled: bool,
}

impl Tightening {
    /// `points` before any pass, with `count` as [`super::reach_counts`] finds it;
    /// the vertices before `first` stay.
    pub(crate) fn new(points: &[GridPoint], count: Grid<u16>, first: usize) -> Self {
        Self {
            path: Linked::new(points),
            count,
            dirty: (0..points.len()).map(|i| i >= first).collect(),
            first,
            passes: 0,
            changes: 0,
            settled: points.len() < 3,
        }
    }

    /// Runs the next pass, if any is left ([`ROUNDS`] in all, fewer when
    /// one changes nothing); returns whether it ran and changed anything.
    pub(crate) fn pass(&mut self, d: &Detours<'_>, zone: Option<&Zone<'_>>) -> bool {
        if self.settled || self.passes >= ROUNDS {
            return false;
        }
        self.passes += 1;
        let path = &mut self.path;
        // The pass's vertices in path order (the first and last stay; a
        // change at a vertex leaves the ones after it in place).
        let mut todo = Vec::new();
        let mut v = path.next[0];
        while v != END && path.next[v] != END {
            if self.dirty[v] {
                todo.push(v);
            }
            v = path.next[v];
        }
        let changed = tighten_round(path, &mut self.count, d, &todo, zone);
        self.settled = changed.is_empty();
        self.changes += changed.len();
        self.dirty.fill(false);
        for c in changed {
            for k in [c.before, c.vertex, c.after] {
                self.dirty[k] = k >= self.first;
            }
        }
        !self.settled
    }

    /// The path as it stands.
    pub(crate) fn points(&self) -> Vec<GridPoint> {
        self.path.points()
    }

    /// The path, the index in the original points of each vertex kept (in
    /// order), and the number of vertices removed or moved.
    pub(crate) fn finish(self) -> (Vec<GridPoint>, Vec<usize>, usize) {
        (self.path.points(), self.path.ids(), self.changes)
    }
}

/// Vertices a pass must look at before it is split into [`STRIPS`].
pub(super) const PARALLEL_PASS: usize = 512;

/// Bands of rows a large pass is split into, one task each: a fixed
/// number, so that the path does not depend on the thread count.
const STRIPS: usize = 4;

/// One pass of [`tighten_from`] over the vertices `todo` (in path order):
/// each vertex replaced as [`try_replace`] finds best. Returns the
/// changes.
///
/// A pass of [`PARALLEL_PASS`] vertices or more is split into [`STRIPS`]
/// bands of rows, each holding about as many of the vertices: every band
/// tries, in parallel and in path order, its vertices whose change can
/// touch only its own rows (the box round the vertex and its neighbours,
/// widened by the reach they count with) and whose neighbours' neighbours
/// (which the time of a change counts) lie in its rows too; the rest are
/// then tried one by one, in path order. Two such changes in different
/// bands share no cell and no vertex, and a band reads only vertices no
/// other band moves, so each band's change is decided exactly as the one
/// by one pass would decide it from the same path; what differs is the
/// order (the rest come last).
fn tighten_round(
    path: &mut Linked,
    count: &mut Grid<u16>,
    d: &Detours<'_>,
    todo: &[usize],
    zone: Option<&Zone<'_>>,
) -> Vec<Change> {
    if todo.len() < PARALLEL_PASS {
        return one_by_one(
            path,
            &mut Counts::whole(count),
            d,
            todo.iter().copied(),
            zone,
        );
    }
    let (w, h) = (count.width(), count.height());
    let row = |p: GridPoint| (fast_floor(p.y).max(0.0) as usize).min(h - 1);
    // Band edges at the quantiles of the vertices' rows.
    let mut rows: Vec<usize> = todo.iter().map(|&v| row(path.pts[v])).collect();
    rows.sort_unstable();
    let mut edges = vec![0];
    edges.extend((1..STRIPS).map(|k| rows[k * rows.len() / STRIPS]));
    edges.push(h);
    // The band of a row: band `k` holds rows `edges[k]..edges[k + 1]`.
    let band_of = |r: usize| edges[1..].partition_point(|&e| e <= r);
    // The rows a change at a vertex may touch: the box round it and its
    // neighbours, widened by the reach a change is counted and judged
    // with, and a cell for the rounding of the rows' ends.
    let margin = d.reach + d.fragile + 1.0;
    let mut bands = Vec::with_capacity(STRIPS);
    let mut rest = count.as_mut_slice();
    for k in 0..STRIPS {
        let (band, tail) = rest.split_at_mut((edges[k + 1] - edges[k]) * w);
        rest = tail;
        bands.push(Counts {
            data: band,
            offset: edges[k] * w,
            size: (w, h),
        });
    }
    let start: &Linked = path;
    // Each band's changes and the positions in `todo` of the vertices it
    // leaves to the one-by-one pass.
    let done: Vec<(Vec<Change>, Vec<usize>)> = bands
        .into_par_iter()
        .enumerate()
        .map(|(k, mut counts)| {
            let mut own = start.clone();
            let mut log = Vec::new();
            let mut left = Vec::new();
            for (i, &v) in todo.iter().enumerate() {
                if band_of(row(start.pts[v])) != k {
                    continue;
                }
                let (u, x) = (own.prev[v], own.next[v]);
                let (rows, _) = cell_box(&[own.pts[u], own.pts[v], own.pts[x]], margin, (w, h));
                let row_in =
                    |n: usize| n == END || (edges[k]..edges[k + 1]).contains(&row(own.pts[n]));
                if rows.start < edges[k]
                    || rows.end > edges[k + 1]
                    || !row_in(own.prev[u])
                    || !row_in(own.next[x])
                {
                    left.push(i);
                } else if let Some(c) = try_replace(&mut own, &mut counts, d, v, zone) {
                    log.push(c);
                }
            }
            (log, left)
        })
        .collect();
    let mut changed = Vec::new();
    let mut left = Vec::new();
    for (log, band_left) in done {
        for c in log {
            match c.to {
                None => {
                    path.next[c.before] = c.after;
                    path.prev[c.after] = c.before;
                }
                Some(q) => path.pts[c.vertex] = q,
            }
            changed.push(c);
        }
        left.extend(band_left);
    }
    left.sort_unstable();
    let rest = left.into_iter().map(|i| todo[i]);
    changed.extend(one_by_one(path, &mut Counts::whole(count), d, rest, zone));
    changed
}

/// [`try_replace`] at each of `vertices` in turn; the changes.
fn one_by_one(
    path: &mut Linked,
    counts: &mut Counts<'_>,
    d: &Detours<'_>,
    vertices: impl Iterator<Item = usize>,
    zone: Option<&Zone<'_>>,
) -> Vec<Change> {
    // Each vertex removed, or moved towards the line of its neighbours
    // (replacing two at once was measured: no gain).
    vertices
        .filter_map(|v| try_replace(path, counts, d, v, zone))
        .collect()
}

/// A change [`try_replace`] made at `vertex`, between `before` and
/// `after`: removed (`to` is `None`) or moved to `to`.
#[derive(Clone, Copy, Debug)]
struct Change {
    vertex: usize,
    before: usize,
    after: usize,
    to: Option<GridPoint>,
}

/// Replaces node `v` by the fastest of: nothing, a point on the way from
/// it to the line of its neighbours ([`RELOCATIONS`]), or a point along
/// one of its pieces ([`SLIDES`]), that is clear, saves time and uncovers
/// nothing (the fastest, not the first: measured on the ipa plans, 0.406
/// → 0.415 time efficiency, rooms off). Returns the change, if it made one.
fn try_replace(
    path: &mut Linked,
    count: &mut Counts<'_>,
    d: &Detours<'_>,
    v: usize,
    zone: Option<&Zone<'_>>,
) -> Option<Change> {
    let (u, x) = (path.prev[v], path.next[v]);
    if u == END || x == END {
        return None;
    }
    let (pu, pv, px) = (path.pts[u], path.pts[v], path.pts[x]);
    if box_cells(&[pu, pv, px], d.reach) > REMOVAL_BOX {
        return None;
    }
    let (before, after) = (path.prev[u], path.next[x]);
    // Seconds of the stretch from `v`'s neighbours' neighbours, with `mid`
    // (at most one point) between `u` and `x`.
    let local = |mid: &[GridPoint]| {
        let mut pts = [pu; 5];
        let mut n = 0;
        let mut push = |p: GridPoint| {
            pts[n] = p;
            n += 1;
        };
        if before != END {
            push(path.pts[before]);
        }
        push(pu);
        if let Some(&m) = mid.first() {
            push(m);
        }
        push(px);
        if after != END {
            push(path.pts[after]);
        }
        polyline_time(&pts[..n], &d.time)
    };
    let here = local(&[pv]);
    let foot = foot_on(pu, px, pv);
    // Removal first, then the relocations, then the slides (in arrays: this
    // runs for every vertex of every pass).
    let mut moves = [None; MOVES];
    let mut n = 1;
    for f in RELOCATIONS {
        moves[n] = Some(off_edges(pv + (foot - pv) * f));
        n += 1;
    }
    // Or slid along either piece (a V's shoulder slid outwards flattens it).
    for f in SLIDES {
        moves[n] = Some(off_edges(pv + (pu - pv) * f));
        moves[n + 1] = Some(off_edges(pv + (px - pv) * f));
        n += 2;
    }
    // The coverable cells only `v`'s two pieces reach: the same for every
    // move, found once (at the first move that saves time and is clear).
    let mut lone: Option<Vec<GridPoint>> = None;
    // The lone cell the last move left out of reach: tried first for the
    // next (the moves are alike; most that lose a cell lose that one).
    let mut culprit = 0;
    let mut timed = [(0.0, None); MOVES];
    let mut saving = 0;
    for m in moves {
        let t = local(m.as_slice());
        // A move must save time; a removal need only not cost any (a
        // vertex on the line of its neighbours goes).
        if t < here - 1e-9 || (m.is_none() && t <= here + 1e-9) {
            timed[saving] = (t, m);
            saving += 1;
        }
    }
    let timed = &mut timed[..saving];
    // The fastest first (stable: ties keep the order above).
    timed.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Every move's point lies in the triangle `u v x` (or off a cell edge
    // by `EDGE_GAP`), so every move is clear where the whole triangle is:
    // one test (asked at the first move tested) instead of two traversals
    // a move.
    let mut whole_clear = None;
    for &(_, m) in timed.iter() {
        let mid = m.as_slice();
        if m.is_some_and(|q| zone.is_some_and(|z| !z.allows(v, q))) {
            continue;
        }
        let triangle = *whole_clear
            .get_or_insert_with(|| triangle_clear(d.plannable, [pu, pv, px], TRIANGLE_MARGIN));
        let clear = triangle
            || match m {
                None => segment_clear(d.plannable, pu, px),
                Some(q) => {
                    cell_of(d.plannable, q).is_some_and(|c| d.plannable[c])
                        && segment_clear(d.plannable, pu, q)
                        && segment_clear(d.plannable, q, px)
                }
            };
        if !clear {
            continue;
        }
        let lone = lone.get_or_insert_with(|| reached_only_by(d, count, pu, &[pv], px));
        if let Some(k) = lost_cell(lone, culprit, pu, mid, px, d.reach) {
            culprit = k;
            continue;
        }
        for (a, b) in pieces(pu, &[pv], px) {
            count.sub_stroke(a, b, d.reach);
        }
        for (a, b) in pieces(pu, mid, px) {
            count.add_stroke(a, b, d.reach);
        }
        match m {
            None => {
                path.next[u] = x;
                path.prev[x] = u;
            }
            Some(q) => path.pts[v] = q,
        }
        return Some(Change {
            vertex: v,
            before: u,
            after: x,
            to: m,
        });
    }
    None
}

/// How far beyond the triangle of a vertex and its neighbours the cells
/// [`try_replace`] tests at once must be clear (cells): far more than a
/// move's [`super::geometry::EDGE_GAP`] and the traversal's rounding.
const TRIANGLE_MARGIN: f64 = 1e-3;

/// The centres of the coverable cells that the pieces `u → old… → x` reach
/// and no other piece of the path does (the only cells a replacement of
/// those pieces can leave out of reach).
fn reached_only_by(
    d: &Detours<'_>,
    count: &Counts<'_>,
    u: GridPoint,
    old: &[GridPoint],
    x: GridPoint,
) -> Vec<GridPoint> {
    let size = count.size;
    assert_eq!(size, (d.coverable.width(), d.coverable.height()));
    // By row-major index (the grids are of one size).
    let coverable = d.coverable.as_slice();
    let most = old.len() as u16 + 1;
    let at_risk = |i: usize| coverable[i] && count.get(i) <= most;
    let outer = d.reach + d.fragile;
    let all = pieces(u, old, x);
    let reaches = |(a, b): (GridPoint, GridPoint), q| u16::from(sample_reaches(a, b, q, d.reach));
    let mut out = Vec::new();
    // Every cell the old pieces may reach (within `outer`) that no other
    // piece reaches (within `reach`: `count` counts those, the old pieces
    // among them): each cell once, with the first piece that reaches it
    // within `outer` (the earlier ones then reach it within neither).
    for (j, &(a, b)) in all.iter().enumerate() {
        stroke_until(a, b, (outer, d.reach), size, at_risk, |i, c, sure| {
            if all[..j]
                .iter()
                .any(|&(p, q)| stroke_reaches(p, q, outer, c))
            {
                return false;
            }
            let q = cell_center(c);
            let n = count.get(i);
            let mut reached = if sure { 1 } else { reaches((a, b), q) };
            for &later in &all[j + 1..] {
                if reached > n {
                    break;
                }
                reached += reaches(later, q);
            }
            if reached == n {
                out.push(q);
            }
            false
        });
    }
    out
}

/// The index of a cell of those centred at `lone` that the pieces
/// `u → new… → x` leave out of reach, if any; the cell at `first` is
/// tried first (whether one is lost does not depend on the order).
pub(super) fn lost_cell(
    lone: &[GridPoint],
    first: usize,
    u: GridPoint,
    new: &[GridPoint],
    x: GridPoint,
    r: f64,
) -> Option<usize> {
    let lost = |q: GridPoint| {
        // Well within reach of a new piece: one of its samples (at most ¼
        // cell apart) reaches it too.
        !near_pieces(u, new, x, q, r - SAMPLE_GAP) && pieces_reaching(u, new, x, q, r) == 0
    };
    if lone.get(first).is_some_and(|&q| lost(q)) {
        return Some(first);
    }
    lone.iter().position(|&q| lost(q))
}
