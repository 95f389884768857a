//! Exact grid traversal of straight segments (Amanatides & Woo 1987).
//!
//! Coordinates are continuous **grid coordinates** `(x, y)`: `x` along
//! columns, `y` along rows (downwards), cell `(r, c)` covering
//! `[c, c+1) × [r, r+1)`, so its centre is `(c + 0.5, r + 0.5)`. A segment
//! visits every cell its interior passes through, including cells it only
//! touches at a corner (the traversal steps one axis, then the other), so a
//! segment reported clear stays inside the mask whatever sampling a checker
//! uses. Used to lay sweep lanes and to straighten routes without cutting
//! through walls.

use crate::grid::{Cell, Grid};
use crate::math::{Point, Vector, fast_floor};

/// A point in grid coordinates (see the module docs): the workspace's
/// [`Point`], read as `x` along columns and `y` along rows (downwards).
pub type GridPoint = Point;

/// The grid coordinates of `cell`'s centre.
#[must_use]
#[inline]
pub fn cell_center(cell: Cell) -> GridPoint {
    Point::new(cell.col as f64 + 0.5, cell.row as f64 + 0.5)
}

/// The cell containing `p`, if inside the grid.
#[must_use]
#[inline]
pub fn cell_of<T>(grid: &Grid<T>, p: GridPoint) -> Option<Cell> {
    let (x, y) = (p.x, p.y);
    if !(x.is_finite() && y.is_finite()) || x < 0.0 || y < 0.0 {
        return None;
    }
    let (c, r) = (fast_floor(x) as usize, fast_floor(y) as usize);
    (c < grid.width() && r < grid.height()).then(|| Cell::new(r, c))
}

/// Distance from `m` to the segment `a b` (to `a` when the segment is a point).
#[must_use]
#[inline]
pub fn segment_distance(a: GridPoint, b: GridPoint, m: GridPoint) -> f64 {
    // Not `hypot`: this is a hot path of the metre planners and grid
    // coordinates are far from overflow.
    segment_distance_sq(a, b, m).sqrt()
}

/// The square of [`segment_distance`] (its square root is exactly
/// [`segment_distance`]).
#[must_use]
#[inline]
pub fn segment_distance_sq(a: GridPoint, b: GridPoint, m: GridPoint) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((m.x - a.x) * dx + (m.y - a.y) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (a.x + t * dx - m.x, a.y + t * dy - m.y);
    ex * ex + ey * ey
}

/// Calls `f(cell, t_enter, t_exit)` for every cell the segment `a → b`
/// crosses, in order, with the segment parameter `t ∈ [0, 1]` where it enters
/// and leaves the cell; stops early when `f` returns `false`. Parts outside the
/// grid are reported as `None` cells. Returns whether it ran to the end.
pub fn traverse(
    width: usize,
    height: usize,
    a: GridPoint,
    b: GridPoint,
    mut f: impl FnMut(Option<Cell>, f64, f64) -> bool,
) -> bool {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    if !(a.x.is_finite() && a.y.is_finite() && dx.is_finite() && dy.is_finite()) {
        return f(None, 0.0, 1.0);
    }
    let mut cx = fast_floor(a.x) as i64;
    let mut cy = fast_floor(a.y) as i64;
    let step_x: i64 = if dx > 0.0 { 1 } else { -1 };
    let step_y: i64 = if dy > 0.0 { 1 } else { -1 };
    // The parameter where the segment meets the next border of each axis,
    // computed afresh from the border's coordinate at every step (not
    // accumulated), so that two borders met at one corner give equal values
    // whenever the coordinates are exact (cell centres, half cells).
    let border_t = |border: i64, p: f64, d: f64| {
        if d == 0.0 {
            f64::INFINITY
        } else {
            (border as f64 - p) / d
        }
    };
    let mut bx = if dx > 0.0 { cx + 1 } else { cx };
    let mut by = if dy > 0.0 { cy + 1 } else { cy };
    let mut tx = border_t(bx, a.x, dx);
    let mut ty = border_t(by, a.y, dy);
    let mut t = 0.0;
    let cell = |cx: i64, cy: i64| {
        (cx >= 0 && cy >= 0 && (cx as usize) < width && (cy as usize) < height)
            .then(|| Cell::new(cy as usize, cx as usize))
    };
    // Bounded: a segment crosses at most |dx| + |dy| + 2 cell borders.
    let limit = (dx.abs() + dy.abs()) as usize + 4;
    for _ in 0..limit {
        let t_out = tx.min(ty).min(1.0);
        if !f(cell(cx, cy), t, t_out) {
            return false;
        }
        if t_out >= 1.0 {
            return true;
        }
        t = t_out;
        if (tx - ty).abs() <= CORNER_EPS {
            // Through a corner (or within rounding of one): both cells beside
            // it are touched at one point (either may own that point), then
            // the diagonal cell.
            if !f(cell(cx + step_x, cy), t, t) || !f(cell(cx, cy + step_y), t, t) {
                return false;
            }
            cx += step_x;
            cy += step_y;
            bx += step_x;
            by += step_y;
            tx = border_t(bx, a.x, dx);
            ty = border_t(by, a.y, dy);
        } else if tx < ty {
            cx += step_x;
            bx += step_x;
            tx = border_t(bx, a.x, dx);
        } else {
            cy += step_y;
            by += step_y;
            ty = border_t(by, a.y, dy);
        }
    }
    true
}

/// Segment parameters this close count as one corner: the segment is taken
/// to touch both cells beside it, so a checker sampling near the corner, with
/// its own rounding, cannot land in a cell the traversal did not report.
const CORNER_EPS: f64 = 1e-9;

/// Whether every cell the segment `a → b` crosses is set in `mask`.
///
/// An end on a cell border (within [`BORDER_EPS`]) touches the cells on
/// both sides of it, and so does the whole of a segment that runs along a
/// border: a point on a border belongs to either cell once a checker
/// converts it to metres and back with its own rounding. Such segments are
/// traversed again shifted a little across each border their ends lie on,
/// and are clear only if every copy is.
#[must_use]
pub fn segment_clear(mask: &Grid<bool>, a: GridPoint, b: GridPoint) -> bool {
    let clear = |a: GridPoint, b: GridPoint| {
        traverse(mask.width(), mask.height(), a, b, |c, _, _| {
            c.is_some_and(|c| mask[c])
        })
    };
    if !clear(a, b) {
        return false;
    }
    let on = |v: f64| (v - v.round()).abs() <= BORDER_EPS;
    let (sx, sy) = (on(a.x) || on(b.x), on(a.y) || on(b.y));
    if !(sx || sy) {
        return true;
    }
    let shift = 2.0 * BORDER_EPS;
    let xs: &[f64] = if sx { &[-shift, 0.0, shift] } else { &[0.0] };
    let ys: &[f64] = if sy { &[-shift, 0.0, shift] } else { &[0.0] };
    xs.iter().all(|&dx| {
        ys.iter().all(|&dy| {
            let d = Vector::new(dx, dy);
            (dx == 0.0 && dy == 0.0) || clear(a + d, b + d)
        })
    })
}

/// How near a cell border (cells) a segment's end counts as on it for
/// [`segment_clear`]: far beyond the rounding of a metre-to-grid round
/// trip, far within any step a planner takes.
pub const BORDER_EPS: f64 = 1e-6;

/// Whether every cell that meets the triangle `tri` widened by `margin`
/// cells (each of its points moved by up to `margin` along each axis) is
/// inside `mask` and set. Then [`segment_clear`] holds for every segment
/// between two points of the triangle, or of the triangle widened by a
/// little less than `margin` (the traversal's own rounding is far smaller
/// than any sensible `margin`): one test for many segments.
#[must_use]
pub fn triangle_clear(mask: &Grid<bool>, tri: [GridPoint; 3], margin: f64) -> bool {
    if !tri.iter().all(|p| p.x.is_finite() && p.y.is_finite()) || margin.is_nan() || margin < 0.0 {
        return false;
    }
    let (w, h) = (mask.width() as f64, mask.height() as f64);
    let y_lo = tri.iter().map(|p| p.y).fold(f64::INFINITY, f64::min) - margin;
    let y_hi = tri.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max) + margin;
    let (r0, r1) = (fast_floor(y_lo), fast_floor(y_hi));
    if r0 < 0.0 || r1 >= h {
        return false;
    }
    let edges = [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])];
    for row in r0 as usize..=r1 as usize {
        // The triangle's points whose height lies in the row's band
        // (widened): their x extent, from each edge clipped to the band.
        let (b0, b1) = (row as f64 - margin, row as f64 + 1.0 + margin);
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for (p, q) in edges {
            let (e0, e1) = (p.y.min(q.y), p.y.max(q.y));
            if e1 < b0 || e0 > b1 {
                continue;
            }
            if q.y == p.y {
                lo = lo.min(p.x.min(q.x));
                hi = hi.max(p.x.max(q.x));
                continue;
            }
            for y in [e0.max(b0), e1.min(b1)] {
                let x = p.x + (y - p.y) / (q.y - p.y) * (q.x - p.x);
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
        if lo > hi {
            continue;
        }
        let (c0, c1) = (fast_floor(lo - margin), fast_floor(hi + margin));
        if c0 < 0.0 || c1 >= w {
            return false;
        }
        if !mask.row(row)[c0 as usize..=c1 as usize]
            .iter()
            .all(|&set| set)
        {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A segment along a row border, or ending on a border, touches the
    /// cells on both sides: a blocked cell there makes it unclear (a
    /// checker rounding its samples may place them on that side); the same
    /// segments between free cells are clear.
    #[test]
    fn segments_on_borders_touch_both_sides() {
        let mut mask = Grid::new(8, 4, true);
        // Row 1 blocked at column 4.
        mask[Cell::new(1, 4)] = false;
        let p = |x: f64, y: f64| GridPoint::new(x, y);
        // Along the border between rows 1 and 2, past the blocked cell.
        assert!(!segment_clear(&mask, p(0.5, 2.0), p(7.5, 2.0)));
        // Within rounding of it, either side.
        assert!(!segment_clear(
            &mask,
            p(0.5, 2.0 + 1e-9),
            p(7.5, 2.0 + 1e-9)
        ));
        assert!(!segment_clear(
            &mask,
            p(0.5, 2.0 - 1e-9),
            p(7.5, 2.0 - 1e-9)
        ));
        // Along the next border down (rows 2 and 3, all free): clear.
        assert!(segment_clear(&mask, p(0.5, 3.0), p(7.5, 3.0)));
        // Ending on the blocked cell's left border, coming from below.
        assert!(!segment_clear(&mask, p(2.5, 3.5), p(4.0, 1.5)));
        assert!(segment_clear(&mask, p(2.5, 3.5), p(3.9, 1.5)));
        // Off every border: as the plain traversal says.
        assert!(segment_clear(&mask, p(0.5, 2.5), p(7.5, 2.5)));
    }

    fn cells(a: GridPoint, b: GridPoint) -> Vec<(usize, usize)> {
        let mut v = Vec::new();
        traverse(10, 10, a, b, |c, _, _| {
            if let Some(c) = c {
                v.push((c.row, c.col));
            }
            true
        });
        v
    }

    #[test]
    fn horizontal_and_diagonal_segments() {
        assert_eq!(
            cells(Point::new(0.5, 0.5), Point::new(3.5, 0.5)),
            [(0, 0), (0, 1), (0, 2), (0, 3)]
        );
        // Through corners: both side cells, then the diagonal one.
        assert_eq!(
            cells(Point::new(0.5, 0.5), Point::new(2.5, 2.5)),
            [(0, 0), (0, 1), (1, 0), (1, 1), (1, 2), (2, 1), (2, 2)]
        );
        assert_eq!(
            cells(Point::new(2.5, 0.2), Point::new(0.5, 1.8)),
            [(0, 2), (0, 1), (1, 1), (1, 0)]
        );
    }

    #[test]
    fn parameters_are_monotone_and_cover_the_segment() {
        let mut last = 0.0;
        let mut n = 0;
        traverse(
            10,
            10,
            Point::new(0.3, 7.9),
            Point::new(9.2, 0.4),
            |_, t0, t1| {
                assert!(t0 >= last - 1e-12 && t1 >= t0);
                last = t1;
                n += 1;
                true
            },
        );
        assert!((last - 1.0).abs() < 1e-12 && n >= 9 + 8);
    }

    #[test]
    fn clear_segments_respect_walls_and_the_grid_edge() {
        let mut mask = Grid::new(4, 4, true);
        mask[Cell::new(1, 2)] = false;
        assert!(segment_clear(
            &mask,
            Point::new(0.5, 0.5),
            Point::new(3.5, 0.5)
        ));
        assert!(!segment_clear(
            &mask,
            Point::new(0.5, 1.5),
            Point::new(3.5, 1.5)
        ));
        assert!(!segment_clear(
            &mask,
            Point::new(0.5, 0.5),
            Point::new(4.5, 0.5)
        ));
        // A diagonal touching the blocked cell's corner is refused.
        assert!(!segment_clear(
            &mask,
            Point::new(1.5, 2.5),
            Point::new(2.5, 1.5)
        ));
        assert!(!segment_clear(
            &mask,
            Point::new(3.5, 2.5),
            Point::new(2.5, 1.5)
        ));
    }

    /// Every cell a sample of the segment can be assigned to (either side of
    /// a border it lies on) is reported.
    fn assert_samples_reported(a: GridPoint, b: GridPoint, size: usize) {
        let mut seen = std::collections::HashSet::new();
        traverse(size, size, a, b, |c, _, _| {
            seen.insert(c);
            true
        });
        let len = (b.x - a.x).hypot(b.y - a.y);
        let n = (len * 4.0).ceil().max(1.0) as usize;
        let sides = |v: f64| {
            let f = v.floor() as i64;
            if v == v.floor() {
                vec![f - 1, f]
            } else {
                vec![f]
            }
        };
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            for cx in sides(x) {
                for cy in sides(y) {
                    // Only cells the sample is inside or on the border of.
                    let inside = (cx as f64) <= x
                        && x <= cx as f64 + 1.0
                        && (cy as f64) <= y
                        && y <= cy as f64 + 1.0;
                    let cell = (cx >= 0 && cy >= 0 && (cx as usize) < size && (cy as usize) < size)
                        .then(|| Cell::new(cy as usize, cx as usize));
                    assert!(
                        !inside || seen.contains(&cell),
                        "{a:?}->{b:?} at {t}: {cell:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn distance_to_a_segment() {
        assert!(
            (segment_distance(
                Point::new(0.0, 0.0),
                Point::new(4.0, 0.0),
                Point::new(2.0, 3.0)
            ) - 3.0)
                .abs()
                < 1e-12
        );
        // Beyond an end: to the end point.
        assert!(
            (segment_distance(
                Point::new(0.0, 0.0),
                Point::new(4.0, 0.0),
                Point::new(7.0, 4.0)
            ) - 5.0)
                .abs()
                < 1e-12
        );
        assert!(
            (segment_distance(
                Point::new(1.0, 1.0),
                Point::new(1.0, 1.0),
                Point::new(4.0, 5.0)
            ) - 5.0)
                .abs()
                < 1e-12
        );
    }

    #[test]
    fn corners_met_after_many_steps_are_corners() {
        // Found on a MovingAI map: the tie at t = 0.5 was lost to rounding
        // when the border parameters were accumulated.
        assert_samples_reported(Point::new(863.5, 492.5), Point::new(856.5, 465.5), 1500);
    }

    proptest::proptest! {
        #[test]
        fn every_sample_lies_in_a_reported_cell(
            ax in 0u32..60, ay in 0u32..60, bx in 0u32..60, by in 0u32..60,
        ) {
            let c = |v: u32| f64::from(v) + 0.5;
            assert_samples_reported(Point::new(c(ax), c(ay)), Point::new(c(bx), c(by)), 60);
        }

        /// A clear triangle makes every segment between its points (and
        /// points a hair outside) clear; a blocked cell inside it, or the
        /// triangle leaving the grid, makes it not clear.
        #[test]
        fn clear_triangles_hold_clear_segments(
            tri in proptest::array::uniform3((0.0..24.0f64, 0.0..24.0f64)),
            walls in proptest::collection::vec((0usize..24, 0usize..24), 0..12),
            weights in proptest::collection::vec((0.0..1.0f64, 0.0..1.0f64), 8),
            nudge in proptest::array::uniform2(-1e-4..1e-4f64),
        ) {
            let tri = tri.map(|(x, y)| Point::new(x, y));
            let mut mask = Grid::new(24, 24, true);
            for &(r, c) in &walls {
                mask[Cell::new(r, c)] = false;
            }
            // Points of the triangle (barycentric), nudged off it.
            let inside: Vec<Point> = weights
                .iter()
                .map(|&(u, v)| {
                    let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
                    let p = tri[0] + (tri[1] - tri[0]) * u + (tri[2] - tri[0]) * v;
                    Point::new(p.x + nudge[0], p.y + nudge[1])
                })
                .chain(tri)
                .collect();
            let clear = triangle_clear(&mask, tri, 1e-3);
            if clear {
                for &p in &inside {
                    for &q in &inside {
                        proptest::prop_assert!(segment_clear(&mask, p, q), "{:?} {:?}", p, q);
                    }
                }
            }
            // Not clear where a blocked cell holds a vertex.
            let blocked_vertex = tri.iter().any(|p| !mask[Cell::new(p.y as usize, p.x as usize)]);
            proptest::prop_assert!(!(clear && blocked_vertex));
            // Nor where it leaves the grid.
            let off = [tri[0], tri[1], Point::new(-0.5, tri[2].y)];
            proptest::prop_assert!(!triangle_clear(&Grid::new(24, 24, true), off, 1e-3));
            // With no wall, every triangle in the grid (and off its edge by
            // more than the margin) is clear.
            let open = Grid::new(24, 24, true);
            let inner = tri.map(|p| Point::new(p.x.clamp(0.01, 23.99), p.y.clamp(0.01, 23.99)));
            proptest::prop_assert!(triangle_clear(&open, inner, 1e-3));
        }
    }
}
