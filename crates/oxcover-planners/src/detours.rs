//! Cheapest-insertion detours: what a finished path leaves uncovered,
//! covered by bending the path where that costs least. Not from the seed
//! papers: cheapest insertion as in tour heuristics, scored by the
//! contract's estimated time, with coverage counted exactly as the
//! contract's samples count it.
//!
//! A cell the path misses is within the tool's reach of some plannable
//! point; the cheapest way to cover it is usually not a separate visit (a
//! boundary pass's anchor: there and back, a half turn) but a bend of a
//! nearby segment: one new vertex `a → p → b`, or a shallow V that leaves
//! the segment and rejoins it a few reaches either side of `p` (a long
//! lane keeps most of its line). Every segment near the cell is tried,
//! with `p` the point of the cell's reach disc nearest the segment, and
//! where no detour through it is accepted, points of the plannable cells
//! within reach (a cell's centre, or its point nearest the missed cell:
//! a slit in a wall is often within reach of boundary cells' edges only).
//! The cheapest in estimated time (length over speed, heading changes
//! over the turn rate) that is clear and leaves no cell the segment alone
//! reached uncovered is inserted; one detour serves a whole cluster of
//! missed cells, the farthest from the path first (one bend into a strip
//! beside a lane then reaches the nearer cells on its way). Cells no such
//! detour reaches are left (the caller's boundary pass visits them).
//!
//! [`tighten_from`] then removes the vertices detours made unneeded, moves the
//! others towards the line of their neighbours or slides them along a
//! piece: of the changes at a vertex that are clear, save time and
//! uncover nothing, the one saving the most. Over a densely traced edge
//! loop this, not the first straightening, is what takes out the turns of
//! a ragged wall. What a path reaches is counted with two radii either
//! side of the metrics' own ([`metric_reach`]): a change must reach a cell
//! within the inner one, and every cell the replaced pieces reach within
//! the outer one is kept, so that rounding never decides a cell's fate. A
//! [`Zone`] keeps each vertex in its room (the pipeline tightens a whole
//! room-by-room plan with one).
//!
//! Cost: the path's segments are kept in square buckets (each registered
//! along its length); a missed cell looks at the segments of the buckets
//! within its search radius. `O(missed · (segments near · candidates))`.
//! A segment's reach is found row by row over its capsule, the cells it
//! surely reaches as one interval per row and only the rest tested
//! against its samples. [`tighten_from`] tests a vertex's moves for clearance
//! at once where every cell of the triangle of the vertex and its
//! neighbours is plannable ([`triangle_clear`]: every move's point lies in
//! it), and traverses each move's pieces only elsewhere. A long pass is
//! split into bands of rows tightened in parallel, each changing only the
//! vertices whose change stays within its rows, the rest afterwards one
//! by one (a fixed number of bands: the same path on any thread count).

use oxcover_grid::math::{fast_ceil, fast_floor};
use oxcover_grid::traverse::{
    GridPoint, cell_center, cell_of, segment_clear, segment_distance, segment_distance_sq,
    triangle_clear,
};
use oxcover_grid::{Cell, Grid, Vector};
use rayon::prelude::*;

use crate::time::TimeModel;

/// Side of a segment bucket (cells).
const BUCKET: f64 = 8.0;
/// No successor.
const END: usize = usize::MAX;

/// The detour settings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Detours<'a> {
    /// Where the path may go.
    pub plannable: &'a Grid<bool>,
    /// What it must cover.
    pub coverable: &'a Grid<bool>,
    /// How near a cell centre one of the path's contract samples must be
    /// (cells; the tool radius).
    pub reach: f64,
    /// How much farther than `reach` a sample may still reach a cell as
    /// the metrics measure it (cells; 0 where the caller covers such cells
    /// itself). [`tighten_from`] never leaves out a cell the pieces it replaces
    /// reach within `reach + fragile`, unless another piece reaches it
    /// within `reach`: the two radii either side of the metrics' own keep
    /// rounding from deciding a cell's fate.
    pub fragile: f64,
    /// Farthest a detour's vertex may be from the segment it bends (cells).
    pub search: f64,
    /// Speeds in cells per second and radians per second.
    pub time: TimeModel,
}

/// `(reach, fragile)` of [`Detours`] for a tool of `tool_cells` scored as
/// the metrics score it: they count a cell within the tool radius and
/// their tolerance (`TOLERANCE_CELLS`) of a sample, so a change must reach
/// every cell a little inside that, and keeps every cell the old path
/// reached a little outside it (rounding of metres, and points moved off
/// cell edges, land on either side).
pub(crate) fn metric_reach(tool_cells: f64) -> (f64, f64) {
    let tolerance = oxcover_grid::TOLERANCE_CELLS;
    (tool_cells + 0.9 * tolerance, 0.2 * tolerance)
}

/// A polyline as a linked list, so vertices can be inserted in place.
#[derive(Clone)]
struct Linked {
    pts: Vec<GridPoint>,
    next: Vec<usize>,
    prev: Vec<usize>,
}

impl Linked {
    fn new(points: &[GridPoint]) -> Self {
        let n = points.len();
        Self {
            pts: points.to_vec(),
            next: (0..n)
                .map(|i| if i + 1 < n { i + 1 } else { END })
                .collect(),
            prev: (0..n).map(|i| if i > 0 { i - 1 } else { END }).collect(),
        }
    }

    fn insert_after(&mut self, a: usize, p: GridPoint) -> usize {
        let b = self.next[a];
        let id = self.pts.len();
        self.pts.push(p);
        self.next.push(b);
        self.prev.push(a);
        self.next[a] = id;
        if b != END {
            self.prev[b] = id;
        }
        id
    }

    fn points(&self) -> Vec<GridPoint> {
        self.ids().into_iter().map(|i| self.pts[i]).collect()
    }

    /// The vertices in path order, by their index (a vertex of the
    /// original path keeps its index there, moved or not).
    fn ids(&self) -> Vec<usize> {
        let mut out = Vec::with_capacity(self.pts.len());
        let mut i = if self.pts.is_empty() { END } else { 0 };
        while i != END {
            out.push(i);
            i = self.next[i];
        }
        out
    }
}

/// How far a new vertex keeps from the cell edges (cells): a point on an
/// edge lies in one cell here and may lie in its neighbour once written in
/// metres.
const EDGE_GAP: f64 = 1e-4;

/// `p` moved off the cell edges it lies on (within [`EDGE_GAP`]), into the
/// cell it is in.
fn off_edges(p: GridPoint) -> GridPoint {
    let pull = |v: f64| {
        let floor = fast_floor(v);
        let f = v - floor;
        if f < EDGE_GAP {
            floor + EDGE_GAP
        } else if f > 1.0 - EDGE_GAP {
            floor + 1.0 - EDGE_GAP
        } else {
            v
        }
    };
    GridPoint::new(pull(p.x), pull(p.y))
}

/// The point of the segment `a → b` nearest `m`.
fn foot_on(a: GridPoint, b: GridPoint, m: GridPoint) -> GridPoint {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let t = if len2 > 0.0 {
        ((m - a).dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a + ab * t
}

/// Absolute heading change (rad) from `u` to `v`; 0 when either is null.
pub(crate) fn heading_change(u: Vector, v: Vector) -> f64 {
    // Squared: `norm() < 1e-12` without the square roots.
    if u.norm_squared() < 1e-24 || v.norm_squared() < 1e-24 {
        return 0.0;
    }
    (u.x * v.y - u.y * v.x).atan2(u.x * v.x + u.y * v.y).abs()
}

/// Segment ids in square buckets.
struct SegmentBuckets {
    cols: usize,
    rows: usize,
    cells: Vec<Vec<usize>>,
}

impl SegmentBuckets {
    fn new(w: usize, h: usize) -> Self {
        let cols = (w as f64 / BUCKET).ceil() as usize + 1;
        let rows = (h as f64 / BUCKET).ceil() as usize + 1;
        Self {
            cols,
            rows,
            cells: vec![Vec::new(); cols * rows],
        }
    }

    fn slot(&self, p: GridPoint) -> (usize, usize) {
        let c = ((p.x / BUCKET).max(0.0) as usize).min(self.cols - 1);
        let r = ((p.y / BUCKET).max(0.0) as usize).min(self.rows - 1);
        (r, c)
    }

    /// Registers segment `id` (`a → b`) in every bucket along it.
    fn add(&mut self, id: usize, a: GridPoint, b: GridPoint) {
        let n = ((b - a).norm() / (BUCKET / 2.0)).ceil().max(1.0) as usize;
        let mut last = usize::MAX;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let (r, c) = self.slot(a + (b - a) * t);
            let i = r * self.cols + c;
            if i != last && self.cells[i].last() != Some(&id) {
                self.cells[i].push(id);
            }
            last = i;
        }
    }

    /// Segment ids registered within `radius` of `p` (with repeats).
    fn near(&self, p: GridPoint, radius: f64, out: &mut Vec<usize>) {
        out.clear();
        let lo = self.slot(p - Vector::new(radius + BUCKET, radius + BUCKET));
        let hi = self.slot(p + Vector::new(radius + BUCKET, radius + BUCKET));
        for r in lo.0..=hi.0 {
            for c in lo.1..=hi.1 {
                out.extend_from_slice(&self.cells[r * self.cols + c]);
            }
        }
        out.sort_unstable();
        out.dedup();
    }
}

/// Whether one of the contract's samples of `a → b` (the segment split
/// into `ceil(len / ¼)` equal parts, ends included) lies within `r` of
/// `q`: the samples either side of `q`'s foot are the nearest.
fn sample_reaches(a: GridPoint, b: GridPoint, q: GridPoint, r: f64) -> bool {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 <= 0.0 {
        return (q - a).norm() <= r;
    }
    let t = ((q - a).dot(&ab) / len2).clamp(0.0, 1.0);
    // Decided without the samples where the answer is clear (a margin
    // either side leaves the boundary cases to the exact test): no sample
    // is nearer than the segment, and one lies within ⅛ cell of `q`'s foot.
    let d2 = (a + ab * t - q).norm_squared();
    if d2 > (r + 1e-9) * (r + 1e-9) {
        return false;
    }
    if d2 + 0.125 * 0.125 <= (r - 1e-9) * (r - 1e-9) {
        return true;
    }
    let len = len2.sqrt();
    let n = fast_ceil(len / 0.25 - 1e-9).max(1.0);
    let s = t * n;
    let at = |k: f64| a + ab * (k / n);
    (at(fast_floor(s)) - q).norm() <= r || (at(fast_ceil(s).min(n)) - q).norm() <= r
}

/// Calls `f` once for every cell of a `w × h` grid whose centre one of the
/// contract's samples of the segment `a → b` reaches within `r`
/// ([`sample_reaches`]), with the cell's row-major index (row by row; in
/// a row, the cells tested exactly first, then those surely reached).
fn for_stroke_cells(
    a: GridPoint,
    b: GridPoint,
    r: f64,
    w: usize,
    h: usize,
    mut f: impl FnMut(usize, Cell),
) {
    for span in stroke_spans(a, b, r, r, (w, h)) {
        let base = span.row * w;
        let cols = (span.first..span.sure.start).chain(span.sure.end..=span.last);
        for col in cols {
            let c = Cell::new(span.row, col);
            if stroke_reaches(a, b, r, c) {
                f(base + col, c);
            }
        }
        for col in span.sure {
            let c = Cell::new(span.row, col);
            debug_assert!(segment_distance(a, b, cell_center(c)) <= r - SAMPLE_GAP);
            f(base + col, c);
        }
    }
}

/// [`for_stroke_cells`] over the cells `want` accepts (given the cell's
/// row-major index in the `w × h` grid; asked before any geometry),
/// stopping at the first cell for which `stop` (given the index, the cell
/// and whether a sample surely reaches it within `inner`, at most `r`)
/// returns `true`; returns whether one did.
fn stroke_until(
    a: GridPoint,
    b: GridPoint,
    (r, inner): (f64, f64),
    (w, h): (usize, usize),
    want: impl Fn(usize) -> bool,
    mut stop: impl FnMut(usize, Cell, bool) -> bool,
) -> bool {
    for span in stroke_spans(a, b, r, inner, (w, h)) {
        let base = span.row * w;
        for col in span.first..=span.last {
            if !want(base + col) {
                continue;
            }
            let c = Cell::new(span.row, col);
            let sure = span.sure.contains(&col);
            debug_assert!(!sure || segment_distance(a, b, cell_center(c)) <= inner - SAMPLE_GAP);
            let reached = sure || stroke_reaches(a, b, r, c);
            if reached && stop(base + col, c, sure) {
                return true;
            }
        }
    }
    false
}

/// The cells of one row that a stroke may reach ([`stroke_spans`]).
struct StrokeSpan {
    row: usize,
    /// The first and last columns whose centres may be reached.
    first: usize,
    last: usize,
    /// The columns whose centres are surely reached (within the sure
    /// reach of the segment): a range inside `first..=last`, empty at its
    /// end when there are none.
    sure: std::ops::Range<usize>,
}

/// Row by row, the cells of a `w × h` grid within the capsule round the
/// segment `a → b` of radius `r` (its discs at the ends and the band
/// between, a hair wider), so that no cell outside it is looked at; each
/// with the columns a sample surely reaches within `inner` (at most `r`),
/// an interval per row rather than a test per cell ([`SURE_MARGIN`] keeps
/// the interval's own rounding on the safe side).
fn stroke_spans(
    a: GridPoint,
    b: GridPoint,
    r: f64,
    inner: f64,
    (w, h): (usize, usize),
) -> impl Iterator<Item = StrokeSpan> {
    debug_assert!(inner <= r);
    // A hair wider than `r`: the exact tests decide.
    let rr = r + 1e-7;
    // Centres within this of the segment are reached by a sample within
    // `inner` whatever the exact test says.
    let sure = inner - SAMPLE_GAP - SURE_MARGIN;
    let row0 = fast_ceil(a.y.min(b.y) - rr - 0.5).max(0.0) as usize;
    let row1 = fast_floor(a.y.max(b.y) + rr - 0.5);
    // No row when `row1` is negative.
    let rows = if row1 < 0.0 {
        1..1
    } else {
        row0..(row1 as usize).min(h.saturating_sub(1)) + 1
    };
    let capsule = Capsule::new(a, b);
    rows.filter_map(move |row| {
        let y = row as f64 + 0.5;
        let [span, sure_span] = capsule.spans(y, rr, (sure > 0.0).then_some(sure));
        let (x0, x1) = span?;
        let first = fast_ceil(x0 - 0.5).max(0.0) as usize;
        let last = fast_floor(x1 - 0.5);
        if last < 0.0 {
            return None;
        }
        let last = (last as usize).min(w.saturating_sub(1));
        // The columns whose centres lie within `sure`.
        let (s0, s1) = match sure_span {
            Some((s0, s1)) => (fast_ceil(s0 - 0.5), fast_floor(s1 - 0.5)),
            None => (1.0, 0.0),
        };
        let (lo, hi) = (s0.max(first as f64), s1.min(last as f64));
        let sure = if lo <= hi {
            lo as usize..hi as usize + 1
        } else {
            last + 1..last + 1
        };
        Some(StrokeSpan {
            row,
            first,
            last,
            sure,
        })
    })
}

/// Whether a sample of `a → b` reaches the centre of `c` within `r`, for a
/// cell outside the sure interval of [`stroke_spans`]: well within reach
/// of the segment, a sample reaches too; beyond it, none does; between,
/// the samples decide. (Inside the sure interval it holds too: checked in
/// debug builds.)
fn stroke_reaches(a: GridPoint, b: GridPoint, r: f64, c: Cell) -> bool {
    let q = cell_center(c);
    let gap = segment_distance(a, b, q);
    gap <= r - SAMPLE_GAP || (gap <= r && sample_reaches(a, b, q, r))
}

/// How far inside the sure reach of [`stroke_until`] its per-row interval
/// is drawn (cells): far beyond the rounding of the interval's square
/// roots, far within the margin of [`sample_reaches`]' own quick test.
const SURE_MARGIN: f64 = 1e-6;

/// The capsules round a segment `a → b` ([`Capsule::spans`]), with the
/// terms that do not depend on the row or the radius worked out once.
struct Capsule {
    a: GridPoint,
    b: GridPoint,
    ab: Vector,
    /// The unit normal (zero for a point).
    n: Vector,
    /// Whether the segment has a length.
    long: bool,
    /// Whether it is horizontal (then `m` is not used).
    flat: bool,
    /// `n.y / ab.y`: the band's parameter `t` falls by `m` per unit of `u`.
    m: f64,
}

impl Capsule {
    fn new(a: GridPoint, b: GridPoint) -> Self {
        let ab = b - a;
        let len = ab.norm();
        let long = len > 0.0;
        let n = if long {
            Vector::new(-ab.y, ab.x) / len
        } else {
            Vector::zeros()
        };
        let flat = ab.y.abs() < 1e-12;
        Self {
            a,
            b,
            ab,
            n,
            long,
            flat,
            m: n.y / ab.y,
        }
    }

    /// The x extents of the points of the line at height `y` within `r`
    /// and within `sure` (if given) of the segment (each capsule is
    /// convex: one interval, the hull of its end discs' and its band's).
    fn spans(&self, y: f64, r: f64, sure: Option<f64>) -> [Option<(f64, f64)>; 2] {
        let (a, b, ab, n, m) = (self.a, self.b, self.ab, self.n, self.m);
        let (da, db) = (y - a.y, y - b.y);
        // Band points a + t·ab + u·n, t in [0, 1], |u| <= r: on the line
        // where t(u) = (y - a.y - u·n.y) / ab.y = k - m·u, so 0 <= t <= 1
        // bounds u to `band` (whatever r; `None`: no u).
        let k = da / ab.y;
        let band = if !self.long || self.flat {
            None
        } else if m.abs() < 1e-12 {
            (0.0..=1.0)
                .contains(&k)
                .then_some((f64::NEG_INFINITY, f64::INFINITY))
        } else {
            let (ua, ub) = (k / m, (k - 1.0) / m);
            Some((ua.min(ub), ua.max(ub)))
        };
        let span = |r: f64| {
            let mut lo = f64::INFINITY;
            let mut hi = f64::NEG_INFINITY;
            for (p, dy) in [(a, da), (b, db)] {
                if dy.abs() <= r {
                    let s = (r * r - dy * dy).sqrt();
                    lo = lo.min(p.x - s);
                    hi = hi.max(p.x + s);
                }
            }
            if self.long && self.flat {
                // Horizontal: the line meets the band where |y - a.y| <= r.
                if da.abs() <= r {
                    lo = lo.min(a.x.min(b.x));
                    hi = hi.max(a.x.max(b.x));
                }
            } else if let Some((b0, b1)) = band {
                let (u0, u1) = ((-r).max(b0), r.min(b1));
                if u0 <= u1 {
                    for u in [u0, u1] {
                        let t = k - m * u;
                        let x = a.x + t * ab.x + u * n.x;
                        lo = lo.min(x);
                        hi = hi.max(x);
                    }
                }
            }
            (lo <= hi).then_some((lo, hi))
        };
        [span(r), sure.and_then(span)]
    }
}

/// The x extent of the points of the line at height `y` within `r` of the
/// segment `a → b` (the reference for [`Capsule::spans`], for tests).
#[cfg(test)]
fn capsule_span(a: GridPoint, b: GridPoint, r: f64, y: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for p in [a, b] {
        let dy = y - p.y;
        if dy.abs() <= r {
            let s = (r * r - dy * dy).sqrt();
            lo = lo.min(p.x - s);
            hi = hi.max(p.x + s);
        }
    }
    let ab = b - a;
    let len = ab.norm();
    if len > 0.0 {
        let n = Vector::new(-ab.y, ab.x) / len;
        let (mut u0, mut u1) = (-r, r);
        if ab.y.abs() < 1e-12 {
            if (y - a.y).abs() <= r {
                lo = lo.min(a.x.min(b.x));
                hi = hi.max(a.x.max(b.x));
            }
        } else {
            let (k, m) = ((y - a.y) / ab.y, n.y / ab.y);
            if m.abs() < 1e-12 {
                if !(0.0..=1.0).contains(&k) {
                    u1 = u0 - 1.0;
                }
            } else {
                let (ua, ub) = (k / m, (k - 1.0) / m);
                u0 = u0.max(ua.min(ub));
                u1 = u1.min(ua.max(ub));
            }
            if u0 <= u1 {
                for u in [u0, u1] {
                    let t = k - m * u;
                    let x = a.x + t * ab.x + u * n.x;
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// How many segments of `points` reach each cell (a contract sample
/// within `d.reach` of its centre).
pub(crate) fn reach_counts(points: &[GridPoint], d: &Detours<'_>) -> Grid<u16> {
    let mut count = Grid::new(d.plannable.width(), d.plannable.height(), 0);
    let mut counts = Counts::whole(&mut count);
    for s in points.windows(2) {
        counts.add_stroke(s[0], s[1], d.reach);
    }
    count
}

/// A band of whole rows of a reach count grid: all of it, or the rows one
/// strip of a parallel [`tighten_from`] round may change. Indexed by the
/// whole grid's row-major index; a cell outside the band is a bug (the
/// index panics).
struct Counts<'a> {
    /// The band's counts, row-major.
    data: &'a mut [u16],
    /// The whole grid's row-major index of the band's first cell.
    offset: usize,
    /// The whole grid's width and height.
    size: (usize, usize),
}

impl<'a> Counts<'a> {
    fn whole(grid: &'a mut Grid<u16>) -> Self {
        let size = (grid.width(), grid.height());
        Self {
            data: grid.as_mut_slice(),
            offset: 0,
            size,
        }
    }

    /// The count of the cell at the whole grid's row-major index `i`.
    fn get(&self, i: usize) -> u16 {
        self.data[i - self.offset]
    }

    /// Adds one to the count of every cell a sample of `a → b` reaches.
    fn add_stroke(&mut self, a: GridPoint, b: GridPoint, r: f64) {
        let (w, h) = self.size;
        let (data, offset) = (&mut *self.data, self.offset);
        for_stroke_cells(a, b, r, w, h, |i, _| {
            data[i - offset] = data[i - offset].saturating_add(1);
        });
    }

    /// Takes one from the count of every cell a sample of `a → b` reaches
    /// (what [`Counts::add_stroke`] added).
    fn sub_stroke(&mut self, a: GridPoint, b: GridPoint, r: f64) {
        let (w, h) = self.size;
        let (data, offset) = (&mut *self.data, self.offset);
        for_stroke_cells(a, b, r, w, h, |i, _| {
            data[i - offset] = data[i - offset].saturating_sub(1);
        });
    }
}

/// `points` with detours inserted until every coverable cell is within
/// `reach` of the path or no clear detour within `search` reaches it
/// without uncovering another. Returns the new path and, for each cell,
/// how many of its segments reach it (for [`tighten_from`]).
pub(crate) fn insert_detours(points: &[GridPoint], d: &Detours<'_>) -> (Vec<GridPoint>, Grid<u16>) {
    let (w, h) = (d.plannable.width(), d.plannable.height());
    let mut count = reach_counts(points, d);
    if points.len() < 2 {
        return (points.to_vec(), count);
    }
    let mut path = Linked::new(points);
    let mut buckets = SegmentBuckets::new(w, h);
    for i in 0..points.len() - 1 {
        buckets.add(i, points[i], points[i + 1]);
    }
    let mut near = Vec::new();
    let missed = deepest_first(d, points, &buckets, &count, &mut near);
    let mut options: Vec<(f64, usize, Via)> = Vec::new();
    for m in missed {
        if count[m] > 0 {
            continue;
        }
        let mc = cell_center(m);
        buckets.near(mc, d.search + d.reach, &mut near);
        // The nearest point of the reach disc first; the plannable cells
        // within reach only where no detour through it is accepted.
        let mut disc: Option<Vec<GridPoint>> = None;
        let mut accepted = None;
        for with_cells in [false, true] {
            if with_cells {
                disc = Some(reach_disc(d, mc));
            }
            options.clear();
            for &a in &near {
                let b = path.next[a];
                if b == END {
                    continue;
                }
                let (pa, pb) = (path.pts[a], path.pts[b]);
                if segment_distance(pa, pb, mc) > d.search + d.reach {
                    continue;
                }
                for p in candidates(d, pa, pb, mc, disc.as_deref_mut()) {
                    for k in 0..SHAPES.len() {
                        if let Some(via) = shape(pa, pb, p, d.reach, k) {
                            options.push((detour_cost(&path, a, via.points(), &d.time), a, via));
                        }
                    }
                }
            }
            let tried = options.len().min(TRIED);
            if options.len() > tried {
                options.select_nth_unstable_by(tried, |x, y| x.0.total_cmp(&y.0));
            }
            options[..tried].sort_by(|x, y| x.0.total_cmp(&y.0));
            accepted = options[..tried].iter().find(|(_, a, via)| {
                let (pa, pb) = (path.pts[*a], path.pts[path.next[*a]]);
                clear_through(d.plannable, pa, via.points(), pb)
                    && !uncovers(d, &count, pa, via.points(), pb)
            });
            if accepted.is_some() {
                break;
            }
        }
        let Some(&(_, a, via)) = accepted else {
            continue;
        };
        let via = via.points();
        let b = path.next[a];
        let (pa, pb) = (path.pts[a], path.pts[b]);
        changed_cells(
            (w, h),
            pa,
            via,
            pb,
            d.reach,
            |_| true,
            |c, old, new| {
                count[c] = (count[c] + new).saturating_sub(old);
                true
            },
        );
        let mut prev = (a, pa);
        for &p in via {
            let id = path.insert_after(prev.0, p);
            buckets.add(prev.0, prev.1, p);
            prev = (id, p);
        }
        buckets.add(prev.0, prev.1, pb);
    }
    (path.points(), count)
}

/// The coverable cells `count` says no segment of `points` reaches, the
/// farthest from the path first (a cell out of every segment's search
/// radius counts as farthest; ties in row-major order). A strip the path
/// runs beside is then bent into from its far side: the one bend reaches
/// the nearer cells on the way, where the nearest first would bend the
/// path again for each row of the strip.
fn deepest_first(
    d: &Detours<'_>,
    points: &[GridPoint],
    buckets: &SegmentBuckets,
    count: &Grid<u16>,
    near: &mut Vec<usize>,
) -> Vec<Cell> {
    let mut missed: Vec<(f64, Cell)> = d
        .coverable
        .true_cells()
        .filter(|&c| count[c] == 0)
        .map(|c| {
            let m = cell_center(c);
            buckets.near(m, d.search + d.reach, near);
            let depth = near
                .iter()
                .filter(|&&a| a + 1 < points.len())
                .map(|&a| segment_distance_sq(points[a], points[a + 1], m))
                .fold(f64::INFINITY, f64::min);
            (depth, c)
        })
        .collect();
    // Stable: equal depths keep the row-major order.
    missed.sort_by(|x, y| y.0.total_cmp(&x.0));
    missed.into_iter().map(|(_, c)| c).collect()
}

/// How far along either piece a vertex is tried slid.
const SLIDES: [f64; 6] = [0.9, 0.75, 0.5, 0.25, 0.1, 0.03];

/// Passes over the path.
const ROUNDS: usize = 8;

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
/// sample-exact counts as [`insert_detours`]); [`ROUNDS`] passes. The
/// vertices before `first` stay where they are, and still count for
/// coverage. After detours, some straightened corners and staircase
/// vertices are no longer needed and many are sharper than coverage
/// requires. `count` is how many segments of `points` reach each cell, as
/// [`insert_detours`] or [`reach_counts`] returns it. Returns the new
/// path, the index in `points` of each vertex kept (in order) and the
/// number of vertices removed or moved.
pub(crate) fn tighten_from(
    points: &[GridPoint],
    d: &Detours<'_>,
    count: Grid<u16>,
    first: usize,
    zone: Option<&Zone<'_>>,
) -> (Vec<GridPoint>, Vec<usize>, usize) {
    let mut t = Tightening::new(points, count, first);
    while t.pass(d, zone) {}
    t.finish()
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
    /// `points` before any pass, with `count` as [`reach_counts`] finds it;
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
const PARALLEL_PASS: usize = 512;

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
/// move's [`EDGE_GAP`] and the traversal's rounding.
const TRIANGLE_MARGIN: f64 = 1e-3;

/// Seconds to drive `pts`, turning on the spot at each vertex.
pub(crate) fn polyline_time(pts: &[GridPoint], t: &TimeModel) -> f64 {
    let length: f64 = pts.windows(2).map(|s| (s[1] - s[0]).norm()).sum();
    let rotation: f64 = pts
        .windows(3)
        .map(|s| heading_change(s[1] - s[0], s[2] - s[1]))
        .sum();
    t.time(length, rotation)
}

/// Cells in the box round `pts` widened by `r`.
fn box_cells(pts: &[GridPoint], r: f64) -> usize {
    let (lo, hi) = bounds(pts);
    ((hi.x - lo.x + 2.0 * r + 2.0) * (hi.y - lo.y + 2.0 * r + 2.0)).max(0.0) as usize
}

/// The rows and columns of a `w × h` grid whose centres may lie within
/// `r` of the box round `pts`.
pub(crate) fn cell_box(
    pts: &[GridPoint],
    r: f64,
    (w, h): (usize, usize),
) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
    let (lo, hi) = bounds(pts);
    let c0 = (lo.x - r).floor().max(0.0) as usize;
    let c1 = ((hi.x + r).ceil().max(0.0) as usize).min(w);
    let r0 = (lo.y - r).floor().max(0.0) as usize;
    let r1 = ((hi.y + r).ceil().max(0.0) as usize).min(h);
    (r0..r1, c0..c1)
}

fn bounds(pts: &[GridPoint]) -> (GridPoint, GridPoint) {
    let mut lo = pts[0];
    let mut hi = pts[0];
    for p in pts {
        lo = GridPoint::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = GridPoint::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    (lo, hi)
}

/// Half the largest gap between the contract's samples (cells).
const SAMPLE_GAP: f64 = 0.125 + 1e-9;

/// Whether a piece of `u → mid… → x` surely passes within `r` of `q`: its
/// squared distance is at most `r²` less a relative hair ([`NEAR_HAIR`]),
/// so that no rounding claims a point beyond `r` (no square root: this
/// runs for every cell a tightening move might lose). A point within `r`
/// by less than the hair may be answered `false`: callers test those
/// exactly.
fn near_pieces(u: GridPoint, mid: &[GridPoint], x: GridPoint, q: GridPoint, r: f64) -> bool {
    if r <= 0.0 {
        return false;
    }
    let r2 = r * r * (1.0 - NEAR_HAIR);
    let mut prev = u;
    for &p in mid.iter().chain(std::iter::once(&x)) {
        if segment_distance_sq(prev, p, q) <= r2 {
            return true;
        }
        prev = p;
    }
    false
}

/// Relative margin of [`near_pieces`]: far beyond the rounding of a
/// squared distance, far within the ⅛-cell margin its callers keep.
const NEAR_HAIR: f64 = 1e-12;

/// How many pieces of `u → mid… → x` have a sample within `r` of `q`.
fn pieces_reaching(u: GridPoint, mid: &[GridPoint], x: GridPoint, q: GridPoint, r: f64) -> u16 {
    let mut n = 0;
    let mut prev = u;
    for &p in mid.iter().chain(std::iter::once(&x)) {
        n += u16::from(sample_reaches(prev, p, q, r));
        prev = p;
    }
    n
}

/// The pieces of the polyline `u → mid… → x`.
fn pieces(u: GridPoint, mid: &[GridPoint], x: GridPoint) -> Vec<(GridPoint, GridPoint)> {
    let mut out = Vec::with_capacity(mid.len() + 1);
    let mut prev = u;
    for &p in mid.iter().chain(std::iter::once(&x)) {
        out.push((prev, p));
        prev = p;
    }
    out
}

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
fn lost_cell(
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

/// The new vertices of a detour (at most three).
#[derive(Clone, Copy, Debug)]
struct Via {
    pts: [GridPoint; 3],
    len: usize,
}

impl Via {
    fn points(&self) -> &[GridPoint] {
        &self.pts[..self.len]
    }
}

/// Shapes of a detour: `p` alone, or a V leaving and rejoining the
/// segment this many reaches either side of `p`'s foot.
const SHAPES: [f64; 4] = [0.0, 1.0, 2.0, 4.0];

/// The vertices of detour shape `SHAPES[k]` through `p` off `a → b`;
/// `None` where the shape does not apply: `p` alone bends a long segment
/// as a whole (it moves all of it), and a V wider than the segment is
/// `p` alone.
fn shape(a: GridPoint, b: GridPoint, p: GridPoint, reach: f64, k: usize) -> Option<Via> {
    let ab = b - a;
    let len = ab.norm();
    let p = off_edges(p);
    let mut via = Via {
        pts: [p; 3],
        len: 0,
    };
    if SHAPES[k] == 0.0 {
        via.len = 1;
        return (len <= 8.0 * reach).then_some(via);
    }
    if len < 1e-9 {
        return None;
    }
    let u = ab / len;
    let t = (p - a).dot(&u).clamp(0.0, len);
    let span = SHAPES[k] * reach;
    let (t1, t2) = (t - span, t + span);
    if t1 <= 0.0 && t2 >= len {
        return None;
    }
    let mut push = |q: GridPoint| {
        via.pts[via.len] = off_edges(q);
        via.len += 1;
    };
    if t1 > 0.0 {
        push(a + u * t1);
    }
    push(p);
    if t2 < len {
        push(a + u * t2);
    }
    Some(via)
}

/// Whether `a → via… → b` is clear.
fn clear_through(mask: &Grid<bool>, a: GridPoint, via: &[GridPoint], b: GridPoint) -> bool {
    let mut prev = a;
    for &p in via.iter().chain(std::iter::once(&b)) {
        if !segment_clear(mask, prev, p) {
            return false;
        }
        prev = p;
    }
    true
}

/// Calls `f(cell, old, new)` for every cell `want` accepts whose coverage
/// changes (until `f` returns `false`) when
/// `a → b` is replaced by `a → via… → b`: `old` is 1 when `a → b` reaches
/// it, `new` the number of new pieces that do. Where `via` starts or ends
/// on the segment, the pieces before and after coincide with it, so only
/// the box round the bent stretch (widened by `reach`) is looked at.
fn changed_cells(
    (grid_w, grid_h): (usize, usize),
    a: GridPoint,
    via: &[GridPoint],
    b: GridPoint,
    reach: f64,
    want: impl Fn(Cell) -> bool,
    mut f: impl FnMut(Cell, u16, u16) -> bool,
) {
    let ab = b - a;
    let len = ab.norm();
    let on_line = |p: GridPoint| len > 0.0 && segment_distance(a, b, p) < 1e-9;
    let param = |p: GridPoint| {
        if len > 0.0 {
            (p - a).dot(&ab) / len
        } else {
            0.0
        }
    };
    let (first, last) = (via[0], via[via.len() - 1]);
    let t_lo = if on_line(first) {
        (param(first) - reach).max(0.0)
    } else {
        0.0
    };
    let t_hi = if on_line(last) {
        (param(last) + reach).min(len)
    } else {
        len
    };
    let u = if len > 0.0 { ab / len } else { Vector::zeros() };
    let mut corners = vec![a + u * t_lo, a + u * t_hi];
    corners.extend_from_slice(via);
    let (rows, cols) = cell_box(&corners, reach, (grid_w, grid_h));
    for row in rows {
        for col in cols.clone() {
            let c = Cell::new(row, col);
            if !want(c) {
                continue;
            }
            let q = cell_center(c);
            let old = u16::from(sample_reaches(a, b, q, reach));
            let new = pieces_reaching(a, via, b, q, reach);
            if old != new && !f(c, old, new) {
                return;
            }
        }
    }
}

/// Whether replacing `a → b` by `a → via… → b` leaves a coverable cell
/// that only `a → b` reaches out of reach.
fn uncovers(
    d: &Detours<'_>,
    count: &Grid<u16>,
    a: GridPoint,
    via: &[GridPoint],
    b: GridPoint,
) -> bool {
    let mut lost = false;
    let (w, h) = (count.width(), count.height());
    let only_here = |c: Cell| count[c] == 1 && d.coverable[c];
    changed_cells((w, h), a, via, b, d.reach, only_here, |_, old, new| {
        lost = new == 0 && old == 1;
        !lost
    });
    lost
}

/// Points within reach of `m` in the plannable cells near it: each cell's
/// centre where that is within reach, else the cell's point nearest `m`
/// (a hair inside the cell) where that is: a cell in a slit of a wall is
/// often within reach of the edges of the boundary cells only.
fn reach_disc(d: &Detours<'_>, m: GridPoint) -> Vec<GridPoint> {
    let k = d.reach.ceil() as isize + 1;
    let (mr, mc) = ((m.y - 0.5).round() as isize, (m.x - 0.5).round() as isize);
    let mut out = Vec::new();
    for dr in -k..=k {
        for dc in -k..=k {
            let (rr, cc) = (mr + dr, mc + dc);
            if rr < 0 || cc < 0 {
                continue;
            }
            let c = Cell::new(rr as usize, cc as usize);
            if d.plannable.get(c).copied() != Some(true) {
                continue;
            }
            let q = cell_center(c);
            if (q - m).norm() <= d.reach {
                out.push(q);
                continue;
            }
            const IN: f64 = 0.49;
            let edge = GridPoint::new(m.x.clamp(q.x - IN, q.x + IN), m.y.clamp(q.y - IN, q.y + IN));
            if (edge - m).norm() <= d.reach {
                out.push(edge);
            }
        }
    }
    out
}

/// Plannable cell centres tried per segment, besides the nearest point.
const CELL_CANDIDATES: usize = 6;
/// Cheapest detours checked per missed cell.
const TRIED: usize = 12;

/// Where a detour from `a → b` to the cell centre `m` may put its vertex:
/// the point of `m`'s reach disc nearest the segment, or (given `disc`,
/// the plannable cell centres within reach of `m`, reordered here) those
/// nearest the segment.
fn candidates(
    d: &Detours<'_>,
    a: GridPoint,
    b: GridPoint,
    m: GridPoint,
    disc: Option<&mut [GridPoint]>,
) -> Vec<GridPoint> {
    let mut out = Vec::with_capacity(CELL_CANDIDATES + 1);
    let Some(disc) = disc else {
        let off = foot_on(a, b, m) - m;
        let r = d.reach - 2.0 * EDGE_GAP;
        if off.norm() > 1e-9 {
            let p = m + off * (r / off.norm());
            if cell_of(d.plannable, p).is_some_and(|c| d.plannable[c]) {
                out.push(p);
            }
        }
        return out;
    };
    let by_distance = |x: &GridPoint, y: &GridPoint| {
        segment_distance(a, b, *x).total_cmp(&segment_distance(a, b, *y))
    };
    let n = disc.len().min(CELL_CANDIDATES);
    if disc.len() > n {
        disc.select_nth_unstable_by(n, by_distance);
    }
    disc[..n].sort_by(by_distance);
    out.extend_from_slice(&disc[..n]);
    out
}

/// Estimated seconds added by making `via` vertices between `a` and its
/// successor.
fn detour_cost(path: &Linked, a: usize, via: &[GridPoint], t: &TimeModel) -> f64 {
    let b = path.next[a];
    let (pa, pb) = (path.pts[a], path.pts[b]);
    let mut length = -(pb - pa).norm();
    let mut rotation = 0.0;
    let mut prev = pa;
    let mut heading: Option<Vector> = (path.prev[a] != END).then(|| pa - path.pts[path.prev[a]]);
    if let Some(u) = heading {
        rotation -= heading_change(u, pb - pa);
    }
    for &p in via.iter().chain(std::iter::once(&pb)) {
        let v = p - prev;
        length += v.norm();
        if let Some(u) = heading {
            rotation += heading_change(u, v);
        }
        heading = Some(v);
        prev = p;
    }
    if path.next[b] != END {
        let v = path.pts[path.next[b]] - pb;
        if let Some(u) = heading {
            rotation += heading_change(u, v);
        }
        rotation -= heading_change(pb - pa, v);
    }
    t.time(length, rotation)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::footprint::for_each_sample;
    use proptest::prelude::*;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    /// [`tighten_from`] moving every vertex: the path and the number of
    /// vertices removed or moved.
    fn tighten(points: &[GridPoint], d: &Detours<'_>, count: Grid<u16>) -> (Vec<GridPoint>, usize) {
        let (points, _, changes) = tighten_from(points, d, count, 0, None);
        (points, changes)
    }

    fn time() -> TimeModel {
        TimeModel {
            linear_speed: 6.0,
            angular_speed: 0.52,
        }
    }

    /// Detours reaching 1 cell (no fragile margin) within `search` cells,
    /// at [`time`]'s speeds.
    fn reach_one<'a>(
        plannable: &'a Grid<bool>,
        coverable: &'a Grid<bool>,
        search: f64,
    ) -> Detours<'a> {
        Detours {
            plannable,
            coverable,
            reach: 1.0,
            fragile: 0.0,
            search,
            time: time(),
        }
    }

    /// Cells within `r` of one of the contract's samples of `pts`.
    fn sampled(w: usize, h: usize, pts: &[GridPoint], r: f64) -> Grid<bool> {
        let mut g = Grid::new(w, h, false);
        for_each_sample(pts, 0.25, |p| {
            for c in Grid::<bool>::new(w, h, false).cells() {
                if (cell_center(c) - p).norm() <= r {
                    g[c] = true;
                }
            }
        });
        g
    }

    #[test]
    fn linked_insertions_keep_order() {
        let pts: Vec<GridPoint> = (0..4).map(|i| GridPoint::new(f64::from(i), 0.0)).collect();
        let mut l = Linked::new(&pts);
        let id = l.insert_after(1, GridPoint::new(1.5, 1.0));
        l.insert_after(id, GridPoint::new(1.7, 1.0));
        l.insert_after(0, GridPoint::new(0.5, 1.0));
        let xs: Vec<f64> = l.points().iter().map(|p| p.x).collect();
        assert_eq!(xs, vec![0.0, 0.5, 1.0, 1.5, 1.7, 2.0, 3.0]);
    }

    /// A lane along the middle of a room three rows wide, reach one cell:
    /// the row below is covered, the nook above the lane's middle is not;
    /// one V detour reaches it, the lane's ends stay where they were.
    #[test]
    fn a_nook_gets_one_v_detour() {
        let plannable = mask(&[
            "##########.##########",
            ".....................",
            ".....................",
        ]);
        let coverable = plannable.clone();
        let path = vec![GridPoint::new(0.5, 2.0), GridPoint::new(20.5, 2.0)];
        let d = reach_one(&plannable, &coverable, 2.0);
        let (out, _) = insert_detours(&path, &d);
        assert_eq!(out.len(), path.len() + 3, "one V: {out:?}");
        assert_eq!(out.first(), path.first());
        assert_eq!(out.last(), path.last());
        // The nook (row 0, column 10) is within reach of a sample now.
        let covered = sampled(21, 3, &out, 1.0);
        assert!(covered[Cell::new(0, 10)], "{out:?}");
        // Nothing the lane covered is lost.
        let before = sampled(21, 3, &path, 1.0);
        for c in before.true_cells() {
            assert!(covered[c], "{c:?} lost: {out:?}");
        }
        // Short and gentle: less than half a turn added in all.
        let turned: f64 = out
            .windows(3)
            .map(|w| heading_change(w[1] - w[0], w[2] - w[1]))
            .sum();
        assert!(turned < std::f64::consts::FRAC_PI_2, "{turned}: {out:?}");
    }

    /// A lane along a corridor's middle row, reach one cell, beside a bay
    /// two rows deep: the bay's far row is bent into first, and the bend
    /// reaches the near row on its way, so each stretch of the bay costs
    /// one detour, not one per row; nothing is left and nothing lost.
    #[test]
    fn a_bay_is_bent_into_from_its_far_side() {
        let plannable = mask(&[
            "....................",
            "....................",
            "....................",
            "#######....#########",
            "#######....#########",
        ]);
        // The row beyond the lane needs no cover: the lane may bend away.
        let coverable = Grid::from_fn(20, 5, |c| c.row > 0 && plannable[c]);
        let path = vec![GridPoint::new(0.5, 1.5), GridPoint::new(19.5, 1.5)];
        let d = reach_one(&plannable, &coverable, 4.0);
        let (out, _) = insert_detours(&path, &d);
        let covered = sampled(20, 5, &out, 1.0);
        for c in coverable.true_cells() {
            assert!(covered[c], "{c:?} missed: {out:?}");
        }
        // The first bend goes a reach short of the far row (4): its vertex
        // lies in row 3, not in row 2 (a reach short of the near row).
        assert!(out[2].y > 3.0, "{out:?}");
        // Fewer new vertices than the bay has cells (row-major order, the
        // near row first, took 10 here).
        assert!(out.len() - path.len() < 8, "{out:?}");
    }

    /// A free 10 × 4 field where only the cell in row 2, column 5 (centre
    /// (5.5, 2.5)) is to be covered.
    fn one_cell_to_cover() -> (Grid<bool>, Grid<bool>) {
        let plannable = mask(&["..........", "..........", "..........", ".........."]);
        let mut coverable = Grid::new(10, 4, false);
        coverable[Cell::new(2, 5)] = true;
        (plannable, coverable)
    }

    /// A path along row 0 bent down to `y` in column 5.
    fn bent_at(y: f64) -> Vec<GridPoint> {
        vec![
            GridPoint::new(0.5, 0.5),
            GridPoint::new(5.5, y),
            GridPoint::new(9.5, 0.5),
        ]
    }

    /// A cell the path reaches only a little beyond `reach` (as the
    /// metrics may count it, by rounding) is kept within reach of
    /// `reach + fragile` by tightening; with no such margin the vertex that
    /// reaches it goes.
    #[test]
    fn a_cell_just_beyond_reach_is_kept_when_fragile() {
        let (plannable, coverable) = one_cell_to_cover();
        // The middle vertex is 1.05 from the cell's centre (5.5, 2.5).
        let path = bent_at(1.45);
        let tightened = |fragile: f64| {
            let d = Detours {
                fragile,
                ..reach_one(&plannable, &coverable, 2.0)
            };
            tighten(&path, &d, reach_counts(&path, &d)).0
        };
        let near = |pts: &[GridPoint]| {
            pts.windows(2)
                .map(|w| segment_distance(w[0], w[1], GridPoint::new(5.5, 2.5)))
                .fold(f64::INFINITY, f64::min)
        };
        assert!(near(&tightened(0.0)) > 1.1);
        let kept = tightened(0.1);
        assert!(near(&kept) <= 1.1, "{kept:?}");
    }

    /// A zone keeps a vertex in its label's cells: a vertex that tightening
    /// moves towards its neighbours' line, across a label border, when
    /// free, stays on its own side when zoned.
    #[test]
    fn a_zone_keeps_a_vertex_in_its_room() {
        let (plannable, coverable) = one_cell_to_cover();
        // Rows 0 and 1 are room 1, rows 2 and 3 room 2.
        let labels = Grid::from_fn(10, 4, |c| if c.row < 2 { 1u32 } else { 2 });
        let path = bent_at(3.5);
        let d = reach_one(&plannable, &coverable, 2.0);
        let room_of = |p: GridPoint| labels[cell_of(&labels, p).unwrap()];
        let (moved, kept, _) = tighten_from(&path, &d, reach_counts(&path, &d), 0, None);
        assert_eq!(kept, vec![0, 1, 2]);
        assert_eq!(room_of(moved[1]), 1, "{moved:?}");
        let of_vertex = [0, 2, 0];
        let zone = Zone {
            labels: &labels,
            of_vertex: &of_vertex,
        };
        let (zoned, kept, _) = tighten_from(&path, &d, reach_counts(&path, &d), 0, Some(&zone));
        assert_eq!(kept, vec![0, 1, 2]);
        assert_eq!(room_of(zoned[1]), 2, "{zoned:?}");
        // Still moved up as far as its room allows, and faster than before.
        assert!(zoned[1].y < 2.5, "{zoned:?}");
        assert!(polyline_time(&zoned, &d.time) < polyline_time(&path, &d.time));
    }

    /// A cell no clear detour reaches is left as it is.
    #[test]
    fn an_unreachable_cell_is_left() {
        let plannable = mask(&[".....", "#####", "....."]);
        let mut coverable = plannable.clone();
        coverable[Cell::new(2, 2)] = true;
        let path = vec![GridPoint::new(0.5, 0.5), GridPoint::new(4.5, 0.5)];
        let d = reach_one(&plannable, &coverable, 3.0);
        let (out, _) = insert_detours(&path, &d);
        assert_eq!(out, path);
    }

    /// A zigzag through an open room where only the middle row must be
    /// covered: tightened to (nearly) the straight line, still covering it.
    /// Pass by pass, a tightening ends where [`tighten_from`] does, in at
    /// most [`ROUNDS`] passes, and then runs no more.
    #[test]
    fn a_tightening_pass_by_pass_is_tighten_from() {
        let plannable = mask(&["...................."; 6]);
        let coverable = plannable.clone();
        let path: Vec<GridPoint> = (0..40)
            .map(|i| {
                let (row, col) = (i / 20, i % 20);
                let col = if row == 0 { col } else { 19 - col };
                let y = 1.5 + 3.0 * row as f64 + if i % 2 == 0 { 0.3 } else { -0.3 };
                GridPoint::new(col as f64 + 0.5, y)
            })
            .collect();
        let d = reach_one(&plannable, &coverable, 2.0);
        let whole = tighten_from(&path, &d, reach_counts(&path, &d), 0, None);
        let mut t = Tightening::new(&path, reach_counts(&path, &d), 0);
        let mut passes = 0;
        while t.pass(&d, None) {
            passes += 1;
        }
        assert!(passes > 0 && passes <= ROUNDS, "{passes}");
        assert!(!t.pass(&d, None));
        assert_eq!(t.finish(), whole);
    }

    #[test]
    fn a_zigzag_is_tightened() {
        let plannable = mask(&[
            "....................",
            "....................",
            "....................",
        ]);
        let mut coverable = Grid::new(20, 3, false);
        for col in 0..20 {
            coverable[Cell::new(1, col)] = true;
        }
        let path: Vec<GridPoint> = (0..20)
            .map(|i| GridPoint::new(f64::from(i) + 0.5, if i % 2 == 0 { 1.1 } else { 1.9 }))
            .collect();
        let d = reach_one(&plannable, &coverable, 2.0);
        let (out, n) = tighten(&path, &d, reach_counts(&path, &d));
        assert!(n > 0);
        let covered = sampled(20, 3, &out, 1.0);
        for col in 0..20 {
            assert!(covered[Cell::new(1, col)], "{col}: {out:?}");
        }
        let before = polyline_time(&path, &d.time);
        let after = polyline_time(&out, &d.time);
        assert!(after < 0.5 * before, "{before} -> {after}: {out:?}");
    }

    /// Cells of a `w × h` grid within `r` of one of the contract's samples
    /// of `pts` (as [`sampled`], looking only near each sample).
    fn sampled_near(w: usize, h: usize, pts: &[GridPoint], r: f64) -> Grid<bool> {
        let mut g = Grid::new(w, h, false);
        for_each_sample(pts, 0.25, |p| {
            let rows =
                ((p.y - r - 1.0).max(0.0) as usize)..((p.y + r + 1.0).max(0.0) as usize).min(h);
            for row in rows {
                let cols =
                    ((p.x - r - 1.0).max(0.0) as usize)..((p.x + r + 1.0).max(0.0) as usize).min(w);
                for col in cols {
                    let c = Cell::new(row, col);
                    if (cell_center(c) - p).norm() <= r {
                        g[c] = true;
                    }
                }
            }
        });
        g
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

        /// A pass long enough to be split into bands of rows: the path is
        /// the same whatever the thread count, every cell the path reached
        /// is still reached, and it is faster.
        #[test]
        fn a_banded_pass_keeps_coverage_and_ignores_the_thread_count(
            jitter in prop::collection::vec(-0.45..0.45f64, 64),
        ) {
            // An open room; a serpentine along every other row, a vertex
            // at every cell, each jittered across its row.
            let (w, h) = (40, 60);
            let plannable = Grid::new(w, h, true);
            let coverable = plannable.clone();
            let mut path = Vec::new();
            for (k, row) in (1..h - 1).step_by(2).enumerate() {
                let cols: Vec<usize> = if k % 2 == 0 {
                    (1..w - 1).collect()
                } else {
                    (1..w - 1).rev().collect()
                };
                for col in cols {
                    let j = jitter[(row * 7 + col) % jitter.len()];
                    path.push(GridPoint::new(col as f64 + 0.5, row as f64 + 0.5 + j));
                }
            }
            prop_assert!(path.len() > PARALLEL_PASS + 2);
            let d = reach_one(&plannable, &coverable, 2.0);
            let on = |threads: usize| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("pool")
                    .install(|| tighten(&path, &d, reach_counts(&path, &d)))
            };
            let (out, n) = on(1);
            prop_assert_eq!(&on(3).0, &out);
            prop_assert!(n > 0);
            let (before, after) = (sampled_near(w, h, &path, 1.0), sampled_near(w, h, &out, 1.0));
            for c in before.true_cells() {
                prop_assert!(after[c], "{:?} lost", c);
            }
            prop_assert!(polyline_time(&out, &d.time) < polyline_time(&path, &d.time));
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

        /// The row-by-row stroke visits exactly the cells a scan of the
        /// whole grid finds reached, each once.
        #[test]
        fn stroke_rows_match_a_whole_grid_scan(
            ax in -2.0..22.0f64, ay in -2.0..18.0f64, bx in -2.0..22.0f64, by in -2.0..18.0f64,
            r in 0.3..4.0f64, flat in 0usize..3,
        ) {
            // Some segments exactly horizontal or vertical.
            let b = match flat {
                0 => GridPoint::new(bx, ay),
                1 => GridPoint::new(ax, by),
                _ => GridPoint::new(bx, by),
            };
            let a = GridPoint::new(ax, ay);
            let (w, h) = (20usize, 16usize);
            let mut seen = Grid::new(w, h, 0u8);
            for_stroke_cells(a, b, r, w, h, |i, c| {
                assert_eq!(i, c.row * w + c.col);
                seen[c] += 1;
            });
            for c in seen.cells() {
                let q = cell_center(c);
                let gap = segment_distance(a, b, q);
                let reached = gap <= r - SAMPLE_GAP || (gap <= r && sample_reaches(a, b, q, r));
                prop_assert_eq!(seen[c], u8::from(reached), "{:?}", c);
            }
        }

        /// `near_pieces` never claims a point beyond `r` of every piece,
        /// and finds every point clearly within; a lost cell is found
        /// whichever cell is tried first.
        #[test]
        fn near_pieces_is_sound_and_lost_cells_do_not_depend_on_the_order(
            u in (0.0..20.0f64, 0.0..20.0f64), m in (0.0..20.0f64, 0.0..20.0f64),
            x in (0.0..20.0f64, 0.0..20.0f64), r in 0.5..6.0f64, first in 0usize..400,
        ) {
            let (u, m, x) = (
                GridPoint::new(u.0, u.1),
                GridPoint::new(m.0, m.1),
                GridPoint::new(x.0, x.1),
            );
            let cells: Vec<GridPoint> = (0..400)
                .map(|i| cell_center(Cell::new(i / 20, i % 20)))
                .collect();
            for &q in &cells {
                let d = segment_distance(u, m, q).min(segment_distance(m, x, q));
                let near = near_pieces(u, &[m], x, q, r);
                prop_assert!(!near || d <= r, "{:?} at {}", q, d);
                prop_assert!(near || d > r * (1.0 - 1e-9), "{:?} at {}", q, d);
            }
            let lost = lost_cell(&cells, first, u, &[m], x, r);
            prop_assert_eq!(lost.is_some(), lost_cell(&cells, 0, u, &[m], x, r).is_some());
            if let Some(k) = lost {
                prop_assert_eq!(pieces_reaching(u, &[m], x, cells[k], r), 0);
            }
        }

        /// The capsule's spans are, to the bit, those worked out one
        /// radius and row at a time.
        #[test]
        fn capsule_spans_match_the_one_at_a_time_span(
            ax in -2.0..22.0f64, ay in -2.0..18.0f64, bx in -2.0..22.0f64, by in -2.0..18.0f64,
            r in 0.3..6.0f64, gap in 0.0..0.5f64, kind in 0usize..4,
        ) {
            // Some segments horizontal, vertical, nearly so, or a point.
            let b = match kind {
                0 => GridPoint::new(bx, ay),
                1 => GridPoint::new(ax, by),
                2 => GridPoint::new(ax, ay),
                _ => GridPoint::new(bx, by),
            };
            let a = GridPoint::new(ax, ay);
            let capsule = Capsule::new(a, b);
            for row in -3..22 {
                let y = f64::from(row) + 0.5;
                let sure = r - gap;
                let [span, inner] = capsule.spans(y, r, Some(sure));
                prop_assert_eq!(span, capsule_span(a, b, r, y));
                prop_assert_eq!(inner, capsule_span(a, b, sure, y));
                prop_assert_eq!(capsule.spans(y, r, None)[1], None);
            }
        }

        /// The sample test agrees with the contract's sampler.
        #[test]
        fn sample_reaches_matches_the_sampler(
            ax in 0.0..20.0f64, ay in 0.0..20.0f64, bx in 0.0..20.0f64, by in 0.0..20.0f64,
            qx in 0.0..20.0f64, qy in 0.0..20.0f64, r in 0.3..4.0f64,
        ) {
            let (a, b, q) = (GridPoint::new(ax, ay), GridPoint::new(bx, by), GridPoint::new(qx, qy));
            let mut near = f64::INFINITY;
            for_each_sample(&[a, b], 0.25, |p| near = near.min((p - q).norm()));
            // Away from the boundary case, both agree.
            prop_assume!((near - r).abs() > 1e-9);
            prop_assert_eq!(sample_reaches(a, b, q, r), near <= r);
        }

        /// On random rooms with specks, detours keep the path clear, its
        /// ends, and everything it covered; they only add coverage.
        #[test]
        fn detours_only_add_coverage(seed in 0u64..1_000, reach in 1.0..3.0f64) {
            let (w, h) = (24usize, 16usize);
            let mut rng = seed;
            let mut next = || {
                rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                (rng >> 33) as usize
            };
            let mut plannable = Grid::new(w, h, true);
            for _ in 0..12 {
                let c = Cell::new(next() % h, next() % w);
                plannable[c] = false;
            }
            // Lanes along rows 2, 6, 10, 14 where clear, joined by straight links.
            let mut path: Vec<GridPoint> = Vec::new();
            for (k, row) in [2usize, 6, 10, 14].into_iter().enumerate() {
                let y = row as f64 + 0.5;
                let (x0, x1) = if k % 2 == 0 { (0.5, w as f64 - 0.5) } else { (w as f64 - 0.5, 0.5) };
                path.push(GridPoint::new(x0, y));
                path.push(GridPoint::new(x1, y));
            }
            // Keep the clear prefix.
            let mut clear = vec![path[0]];
            for p in path.iter().skip(1) {
                if cell_of(&plannable, *p).is_none_or(|c| !plannable[c])
                    || !segment_clear(&plannable, clear[clear.len() - 1], *p)
                {
                    break;
                }
                clear.push(*p);
            }
            prop_assume!(clear.len() >= 2 && cell_of(&plannable, clear[0]).is_some_and(|c| plannable[c]));
            let coverable = Grid::new(w, h, true);
            let d = Detours { plannable: &plannable, coverable: &coverable, reach, fragile: 0.0, search: 2.0 * reach, time: time() };
            let (detoured, count) = insert_detours(&clear, &d);
            let (out, _) = tighten(&detoured, &d, count);
            prop_assert_eq!(out.first(), clear.first());
            prop_assert_eq!(out.last(), clear.last());
            for s in out.windows(2) {
                prop_assert!(segment_clear(&plannable, s[0], s[1]), "{:?}", s);
            }
            let before = sampled(w, h, &clear, reach);
            let after = sampled(w, h, &out, reach);
            for c in before.true_cells() {
                prop_assert!(after[c], "{:?} lost", c);
            }
            prop_assert!(after.count_true() >= before.count_true());
        }
    }
}
