//! Cheapest-insertion detours: what a finished path leaves uncovered,
//! covered by bending the path where that costs least.
//!
//! A missed cell is usually cheapest covered not by a visit of its own
//! (there and back, a half turn) but by a bend of a nearby segment: one new
//! vertex `a → p → b`, or a shallow V leaving and rejoining the segment a
//! few reaches either side of `p` (a long lane keeps most of its line).
//! Every segment near the cell is tried with `p` the point of the cell's
//! reach disc nearest it, and where none is accepted, points of the
//! plannable cells within reach (a slit in a wall is often within reach of
//! boundary cells' edges only). The cheapest in estimated time that is
//! clear and leaves no cell the segment alone reached uncovered is
//! inserted; the farthest missed cells go first, so one bend into a strip
//! beside a lane reaches the nearer cells on its way. Cells no such detour
//! reaches are left to the caller.
//!
//! Cost: the segments sit in square buckets (each registered along its
//! length), so a missed cell looks only at those within its search radius:
//! `O(missed · segments near · candidates)`.

use oxcover_grid::traverse::{
    GridPoint, cell_center, cell_of, segment_clear, segment_distance, segment_distance_sq,
};
use oxcover_grid::{Cell, Grid, Vector};

use super::Detours;
use super::geometry::{EDGE_GAP, END, Linked, cell_box, foot_on, heading_change, off_edges};
use super::reach::{pieces_reaching, reach_counts, sample_reaches};
use crate::time::TimeModel;

/// Side of a segment bucket (cells).
const BUCKET: f64 = 8.0;

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

/// `points` with detours inserted until every coverable cell is within
/// `reach` of the path or no clear detour within `search` reaches it
/// without uncovering another. Returns the new path and, for each cell,
/// how many of its segments reach it (for [`super::tighten_from`]).
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
pub(super) fn uncovers(
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
