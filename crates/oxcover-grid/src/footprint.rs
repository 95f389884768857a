//! The tool's footprint along a path: which cells a polyline covers.
//!
//! Contract: the path is the polyline through the waypoints; it is sampled every
//! `resolution / 4` (each segment split into `ceil(len / step)` equal parts, all
//! waypoints included), and a cell is covered when its centre lies within the
//! tool radius of a sample. The same sampler feeds the collision count, so
//! metrics, the boundary pass and the tests agree on what "covered" means.

use crate::admissible::TOLERANCE_CELLS;
use crate::frame::MapFrame;
use crate::grid::{Cell, Grid};
use crate::math::Point;

/// Calls `f` on samples of the polyline `points`, at most `step` apart.
///
/// A single waypoint yields one sample; an empty path none. Non-finite
/// waypoints are passed through as they are (callers validate paths first).
pub fn for_each_sample(points: &[Point], step: f64, mut f: impl FnMut(&Point)) {
    let Some(first) = points.first() else {
        return;
    };
    f(first);
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b - a).norm();
        // The tolerance keeps a segment of exactly m·step from getting an extra
        // sample through rounding, so samples of grid-aligned paths fall on the
        // cell centres they pass.
        let n = if step > 0.0 && len.is_finite() {
            (len / step - 1e-9).ceil().max(1.0) as usize
        } else {
            1
        };
        for i in 1..=n {
            let t = i as f64 / n as f64;
            f(&(a + (b - a) * t));
        }
    }
}

/// Sets `mask` on every cell whose centre lies within `radius` metres of `p`.
pub fn mark_disc(frame: &MapFrame, p: &Point, radius: f64, mask: &mut Grid<bool>) {
    let res = frame.resolution();
    let reach = radius / res + TOLERANCE_CELLS;
    let (row, col) = frame.fractional_cell(p);
    if !(row.is_finite() && col.is_finite()) {
        return;
    }
    let r0 = (row - reach).ceil().max(0.0);
    let r1 = (row + reach).floor().min(mask.height() as f64 - 1.0);
    let c0 = (col - reach).ceil().max(0.0);
    let c1 = (col + reach).floor().min(mask.width() as f64 - 1.0);
    if r0 > r1 || c0 > c1 {
        return;
    }
    let reach2 = reach * reach;
    for r in r0 as usize..=r1 as usize {
        let dr = r as f64 - row;
        for c in c0 as usize..=c1 as usize {
            let dc = c as f64 - col;
            if dr * dr + dc * dc <= reach2 {
                mask[Cell::new(r, c)] = true;
            }
        }
    }
}

/// Cells covered by a tool of `tool_radius` metres driven along `points`
/// (sampled every `resolution / 4`).
#[must_use]
pub fn covered_cells(frame: &MapFrame, points: &[Point], tool_radius: f64) -> Grid<bool> {
    let mut mask = Grid::new(frame.width(), frame.height(), false);
    mark_covered(frame, points, tool_radius, &mut mask);
    mask
}

/// Adds the cells covered along `points` to `mask`.
pub fn mark_covered(frame: &MapFrame, points: &[Point], tool_radius: f64, mask: &mut Grid<bool>) {
    let step = frame.resolution() / 4.0;
    for_each_sample(points, step, |p| mark_disc(frame, p, tool_radius, mask));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_include_vertices_and_respect_the_step() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 0.1),
        ];
        let mut s = Vec::new();
        for_each_sample(&pts, 0.25, |p| s.push(*p));
        assert_eq!(s.len(), 1 + 4 + 1);
        assert_eq!(s[4], Point::new(1.0, 0.0));
        assert!(s.windows(2).all(|w| (w[1] - w[0]).norm() <= 0.25 + 1e-12));
        let mut one = 0;
        for_each_sample(&pts[..1], 0.25, |_| one += 1);
        assert_eq!(one, 1);
    }

    #[test]
    fn half_cell_tool_covers_exactly_the_cells_visited() {
        let f = MapFrame::unit(5, 3);
        let path = [
            f.cell_center(Cell::new(1, 0)),
            f.cell_center(Cell::new(1, 4)),
        ];
        let m = covered_cells(&f, &path, 0.5);
        assert_eq!(
            m.true_cells().collect::<Vec<_>>(),
            (0..5).map(|c| Cell::new(1, c)).collect::<Vec<_>>()
        );
        let m = covered_cells(&f, &path, 1.0);
        assert_eq!(m.count_true(), 15);
    }
}
