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

/// A point in grid coordinates (see the module docs).
pub type GridPoint = (f64, f64);

/// The grid coordinates of `cell`'s centre.
#[must_use]
pub fn cell_center(cell: Cell) -> GridPoint {
    (cell.col as f64 + 0.5, cell.row as f64 + 0.5)
}

/// The cell containing `p`, if inside the grid.
#[must_use]
pub fn cell_of<T>(grid: &Grid<T>, p: GridPoint) -> Option<Cell> {
    let (x, y) = p;
    if !(x.is_finite() && y.is_finite()) || x < 0.0 || y < 0.0 {
        return None;
    }
    let (c, r) = (x.floor() as usize, y.floor() as usize);
    (c < grid.width() && r < grid.height()).then(|| Cell::new(r, c))
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
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    if !(a.0.is_finite() && a.1.is_finite() && dx.is_finite() && dy.is_finite()) {
        return f(None, 0.0, 1.0);
    }
    let mut cx = a.0.floor() as i64;
    let mut cy = a.1.floor() as i64;
    let step_x: i64 = if dx > 0.0 { 1 } else { -1 };
    let step_y: i64 = if dy > 0.0 { 1 } else { -1 };
    let inv = |d: f64| {
        if d == 0.0 {
            f64::INFINITY
        } else {
            1.0 / d.abs()
        }
    };
    let (dtx, dty) = (inv(dx), inv(dy));
    let next_boundary = |p: f64, c: i64, d: f64| {
        if d > 0.0 {
            (c as f64 + 1.0 - p) / d
        } else if d < 0.0 {
            (p - c as f64) / -d
        } else {
            f64::INFINITY
        }
    };
    let mut tx = next_boundary(a.0, cx, dx);
    let mut ty = next_boundary(a.1, cy, dy);
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
        if tx < ty {
            cx += step_x;
            tx += dtx;
        } else if ty < tx {
            cy += step_y;
            ty += dty;
        } else {
            // Through a corner: both cells beside it are touched at one
            // point (either may own that point), then the diagonal cell.
            if !f(cell(cx + step_x, cy), t, t) || !f(cell(cx, cy + step_y), t, t) {
                return false;
            }
            cx += step_x;
            cy += step_y;
            tx += dtx;
            ty += dty;
        }
    }
    true
}

/// Whether every cell the segment `a → b` crosses is set in `mask`.
#[must_use]
pub fn segment_clear(mask: &Grid<bool>, a: GridPoint, b: GridPoint) -> bool {
    traverse(mask.width(), mask.height(), a, b, |c, _, _| {
        c.is_some_and(|c| mask[c])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
            cells((0.5, 0.5), (3.5, 0.5)),
            [(0, 0), (0, 1), (0, 2), (0, 3)]
        );
        // Through corners: both side cells, then the diagonal one.
        assert_eq!(
            cells((0.5, 0.5), (2.5, 2.5)),
            [(0, 0), (0, 1), (1, 0), (1, 1), (1, 2), (2, 1), (2, 2)]
        );
        assert_eq!(
            cells((2.5, 0.2), (0.5, 1.8)),
            [(0, 2), (0, 1), (1, 1), (1, 0)]
        );
    }

    #[test]
    fn parameters_are_monotone_and_cover_the_segment() {
        let mut last = 0.0;
        let mut n = 0;
        traverse(10, 10, (0.3, 7.9), (9.2, 0.4), |_, t0, t1| {
            assert!(t0 >= last - 1e-12 && t1 >= t0);
            last = t1;
            n += 1;
            true
        });
        assert!((last - 1.0).abs() < 1e-12 && n >= 9 + 8);
    }

    #[test]
    fn clear_segments_respect_walls_and_the_grid_edge() {
        let mut mask = Grid::new(4, 4, true);
        mask[Cell::new(1, 2)] = false;
        assert!(segment_clear(&mask, (0.5, 0.5), (3.5, 0.5)));
        assert!(!segment_clear(&mask, (0.5, 1.5), (3.5, 1.5)));
        assert!(!segment_clear(&mask, (0.5, 0.5), (4.5, 0.5)));
        // A diagonal touching the blocked cell's corner is refused.
        assert!(!segment_clear(&mask, (1.5, 2.5), (2.5, 1.5)));
        assert!(!segment_clear(&mask, (3.5, 2.5), (2.5, 1.5)));
    }
}
