//! The polyline detours and tightening edit (a linked list, so vertices
//! can be inserted in place and removed), and the helpers they share: the
//! estimated time of a polyline, boxes of cells round points, and points
//! kept off cell edges.

use oxcover_grid::Vector;
use oxcover_grid::math::fast_floor;
use oxcover_grid::traverse::GridPoint;

use crate::time::TimeModel;

/// No successor.
pub(super) const END: usize = usize::MAX;

/// A polyline as a linked list, so vertices can be inserted in place.
#[derive(Clone)]
pub(super) struct Linked {
    pub(super) pts: Vec<GridPoint>,
    pub(super) next: Vec<usize>,
    pub(super) prev: Vec<usize>,
}

impl Linked {
    pub(super) fn new(points: &[GridPoint]) -> Self {
        let n = points.len();
        Self {
            pts: points.to_vec(),
            next: (0..n)
                .map(|i| if i + 1 < n { i + 1 } else { END })
                .collect(),
            prev: (0..n).map(|i| if i > 0 { i - 1 } else { END }).collect(),
        }
    }

    pub(super) fn insert_after(&mut self, a: usize, p: GridPoint) -> usize {
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

    pub(super) fn points(&self) -> Vec<GridPoint> {
        self.ids().into_iter().map(|i| self.pts[i]).collect()
    }

    /// The vertices in path order, by their index (a vertex of the
    /// original path keeps its index there, moved or not).
    pub(super) fn ids(&self) -> Vec<usize> {
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
pub(super) const EDGE_GAP: f64 = 1e-4;

/// `p` moved off the cell edges it lies on (within [`EDGE_GAP`]), into the
/// cell it is in.
pub(super) fn off_edges(p: GridPoint) -> GridPoint {
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
pub(super) fn foot_on(a: GridPoint, b: GridPoint, m: GridPoint) -> GridPoint {
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
    let (y, x) = (u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y);
    // Straight on, square and back: the values `atan2` gives exactly,
    // without its software routine (x86-64's baseline has no instruction).
    if y == 0.0 {
        if x > 0.0 {
            return 0.0;
        }
        if x < 0.0 {
            return std::f64::consts::PI;
        }
    } else if x == 0.0 {
        return std::f64::consts::FRAC_PI_2;
    }
    y.atan2(x).abs()
}

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
pub(super) fn box_cells(pts: &[GridPoint], r: f64) -> usize {
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

pub(super) fn bounds(pts: &[GridPoint]) -> (GridPoint, GridPoint) {
    let mut lo = pts[0];
    let mut hi = pts[0];
    for p in pts {
        lo = GridPoint::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = GridPoint::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    (lo, hi)
}

/// The pieces of the polyline `u → mid… → x`.
pub(super) fn pieces(u: GridPoint, mid: &[GridPoint], x: GridPoint) -> Vec<(GridPoint, GridPoint)> {
    let mut out = Vec::with_capacity(mid.len() + 1);
    let mut prev = u;
    for &p in mid.iter().chain(std::iter::once(&x)) {
        out.push((prev, p));
        prev = p;
    }
    out
}
