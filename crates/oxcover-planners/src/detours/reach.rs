//! What a path reaches: a cell is reached by a segment when one of the
//! contract's samples of it (a quarter cell apart at most) lies within the
//! reach of the cell's centre.
//!
//! A segment's cells are found row by row over its capsule: the cells it
//! surely reaches (well within reach of the segment itself) as one interval
//! per row, only the rest tested against its samples. A reach count grid
//! says how many segments of a path reach each cell; a band of its rows can
//! be handed to one task of a parallel tightening pass.

use oxcover_grid::math::{fast_ceil, fast_floor};
use oxcover_grid::traverse::{GridPoint, cell_center, segment_distance, segment_distance_sq};
use oxcover_grid::{Cell, Grid, Vector};
use rayon::prelude::*;

use super::Detours;

/// Half the largest gap between the contract's samples (cells).
pub(super) const SAMPLE_GAP: f64 = 0.125 + 1e-9;

/// Whether one of the contract's samples of `a → b` (the segment split
/// into `ceil(len / ¼)` equal parts, ends included) lies within `r` of
/// `q`: the samples either side of `q`'s foot are the nearest.
pub(super) fn sample_reaches(a: GridPoint, b: GridPoint, q: GridPoint, r: f64) -> bool {
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
pub(super) fn for_stroke_cells(
    a: GridPoint,
    b: GridPoint,
    r: f64,
    w: usize,
    h: usize,
    f: impl FnMut(usize, Cell),
) {
    for_stroke_cells_in(a, b, r, (w, h), 0..h, f);
}

/// [`for_stroke_cells`] in the rows `rows` only.
pub(super) fn for_stroke_cells_in(
    a: GridPoint,
    b: GridPoint,
    r: f64,
    (w, h): (usize, usize),
    rows: std::ops::Range<usize>,
    mut f: impl FnMut(usize, Cell),
) {
    for span in stroke_spans(a, b, (r, r), (w, h), rows) {
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
pub(super) fn stroke_until(
    a: GridPoint,
    b: GridPoint,
    (r, inner): (f64, f64),
    (w, h): (usize, usize),
    want: impl Fn(usize) -> bool,
    mut stop: impl FnMut(usize, Cell, bool) -> bool,
) -> bool {
    for span in stroke_spans(a, b, (r, inner), (w, h), 0..h) {
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
/// the interval's own rounding on the safe side); only the rows in
/// `within`.
fn stroke_spans(
    a: GridPoint,
    b: GridPoint,
    (r, inner): (f64, f64),
    (w, h): (usize, usize),
    within: std::ops::Range<usize>,
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
        row0.max(within.start)..((row1 as usize).min(h.saturating_sub(1)) + 1).min(within.end)
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
pub(super) fn stroke_reaches(a: GridPoint, b: GridPoint, r: f64, c: Cell) -> bool {
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
pub(super) struct Capsule {
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
    pub(super) fn new(a: GridPoint, b: GridPoint) -> Self {
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
    pub(super) fn spans(&self, y: f64, r: f64, sure: Option<f64>) -> [Option<(f64, f64)>; 2] {
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

/// How many segments of `points` reach each cell (a contract sample
/// within `d.reach` of its centre).
///
/// Long paths are counted in bands of [`COUNT_ROWS`] rows in parallel,
/// each band adding the strokes of the segments near its rows to its own
/// cells (every cell gets the same additions, whatever the thread count).
pub(crate) fn reach_counts(points: &[GridPoint], d: &Detours<'_>) -> Grid<u16> {
    let (w, h) = (d.plannable.width(), d.plannable.height());
    let mut count = Grid::new(w, h, 0);
    if points.len() < PARALLEL_COUNT || w == 0 {
        let mut counts = Counts::whole(&mut count);
        for s in points.windows(2) {
            counts.add_stroke(s[0], s[1], d.reach);
        }
        return count;
    }
    // Each segment's rows (a cell more than its capsule's either way).
    let spans: Vec<(f64, f64)> = points
        .windows(2)
        .map(|s| {
            let (lo, hi) = (s[0].y.min(s[1].y), s[0].y.max(s[1].y));
            (lo - d.reach - 1.0, hi + d.reach + 1.0)
        })
        .collect();
    count
        .as_mut_slice()
        .par_chunks_mut(w * COUNT_ROWS)
        .enumerate()
        .for_each(|(k, band)| {
            let rows = k * COUNT_ROWS..k * COUNT_ROWS + band.len() / w;
            let (top, bottom) = (rows.start as f64, rows.end as f64);
            for (s, &(lo, hi)) in points.windows(2).zip(&spans) {
                if hi < top || lo > bottom {
                    continue;
                }
                let offset = rows.start * w;
                for_stroke_cells_in(s[0], s[1], d.reach, (w, h), rows.clone(), |i, _| {
                    band[i - offset] = band[i - offset].saturating_add(1);
                });
            }
        });
    count
}

/// Waypoints from which [`reach_counts`] counts in bands in parallel.
const PARALLEL_COUNT: usize = 256;

/// Rows per band of [`reach_counts`].
const COUNT_ROWS: usize = 64;

/// A band of whole rows of a reach count grid: all of it, or the rows one
/// strip of a parallel [`super::tighten_from`] round may change. Indexed by the
/// whole grid's row-major index; a cell outside the band is a bug (the
/// index panics).
pub(super) struct Counts<'a> {
    /// The band's counts, row-major.
    pub(super) data: &'a mut [u16],
    /// The whole grid's row-major index of the band's first cell.
    pub(super) offset: usize,
    /// The whole grid's width and height.
    pub(super) size: (usize, usize),
}

impl<'a> Counts<'a> {
    pub(super) fn whole(grid: &'a mut Grid<u16>) -> Self {
        let size = (grid.width(), grid.height());
        Self {
            data: grid.as_mut_slice(),
            offset: 0,
            size,
        }
    }

    /// The count of the cell at the whole grid's row-major index `i`.
    pub(super) fn get(&self, i: usize) -> u16 {
        self.data[i - self.offset]
    }

    /// Adds one to the count of every cell a sample of `a → b` reaches.
    pub(super) fn add_stroke(&mut self, a: GridPoint, b: GridPoint, r: f64) {
        let (w, h) = self.size;
        let (data, offset) = (&mut *self.data, self.offset);
        for_stroke_cells(a, b, r, w, h, |i, _| {
            data[i - offset] = data[i - offset].saturating_add(1);
        });
    }

    /// Takes one from the count of every cell a sample of `a → b` reaches
    /// (what [`Counts::add_stroke`] added).
    pub(super) fn sub_stroke(&mut self, a: GridPoint, b: GridPoint, r: f64) {
        let (w, h) = self.size;
        let (data, offset) = (&mut *self.data, self.offset);
        for_stroke_cells(a, b, r, w, h, |i, _| {
            data[i - offset] = data[i - offset].saturating_sub(1);
        });
    }
}

/// Whether a piece of `u → mid… → x` surely passes within `r` of `q`: its
/// squared distance is at most `r²` less a relative hair ([`NEAR_HAIR`]),
/// so that no rounding claims a point beyond `r` (no square root: this
/// runs for every cell a tightening move might lose). A point within `r`
/// by less than the hair may be answered `false`: callers test those
/// exactly.
pub(super) fn near_pieces(
    u: GridPoint,
    mid: &[GridPoint],
    x: GridPoint,
    q: GridPoint,
    r: f64,
) -> bool {
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
pub(super) fn pieces_reaching(
    u: GridPoint,
    mid: &[GridPoint],
    x: GridPoint,
    q: GridPoint,
    r: f64,
) -> u16 {
    let mut n = 0;
    let mut prev = u;
    for &p in mid.iter().chain(std::iter::once(&x)) {
        n += u16::from(sample_reaches(prev, p, q, r));
        prev = p;
    }
    n
}
