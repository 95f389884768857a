//! Admissible cells for a disc robot (contract: an exact Euclidean distance
//! transform, not a box dilation).
//!
//! A cell is admissible when it is free and the distance from its centre to the
//! boundary of every non-free cell is at least the robot radius. Cells outside
//! the map count as non-free: nothing is known beyond the edge. Distances are
//! compared with a tolerance of [`TOLERANCE_CELLS`], so a radius that is an exact
//! multiple of the resolution in decimal (0.15 m on 0.05 m cells) behaves as the
//! user means despite binary rounding.

use crate::edt::{boundary_distance_sq4, boundary_within_sq4};
use crate::grid::Grid;
use crate::occupancy::OccupancyGrid;

/// Tolerance, in cells, of every radius comparison in the workspace.
pub const TOLERANCE_CELLS: f64 = 1e-9;

/// `true` where a disc of `robot_radius` metres centred on the cell centre
/// touches no non-free cell (and does not cross the map edge).
#[must_use]
pub fn admissible(map: &OccupancyGrid, robot_radius: f64) -> Grid<bool> {
    let free = map.free_mask();
    let r = robot_radius / map.resolution();
    if r <= TOLERANCE_CELLS {
        return free;
    }
    let blocked = free.map(|f| !f);
    // sqrt(d4)/2 >= r - tol  <=>  d4 >= (2(r - tol))^2, for an integer d4
    // at least its ceiling: not within one less.
    let t = 2.0 * (r - TOLERANCE_CELLS);
    let least = (t * t).ceil();
    if !least.is_finite() {
        // No clearance is that large (or the radius is not a number).
        return Grid::new(free.width(), free.height(), false);
    }
    let near = boundary_within_sq4(&blocked, true, (least as u64).saturating_sub(1));
    free.zip_map(&near, |&f, &n| f && !n)
}

/// Clearance of every cell in metres: distance from its centre to the nearest
/// non-free cell boundary or the map edge (0 on non-free cells).
#[must_use]
pub fn clearance(map: &OccupancyGrid) -> Grid<f64> {
    let blocked = map.free_mask().map(|f| !f);
    let res = map.resolution();
    boundary_distance_sq4(&blocked, true).map(|&d4| (d4 as f64).sqrt() / 2.0 * res)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::parse_ascii;
    use crate::{Cell, OccupancyGrid};

    #[test]
    fn radius_exactly_at_a_wall_is_admissible() {
        let (m, _) = parse_ascii(
            "
            #######
            #.....#
            #.....#
            #.....#
            #######",
        )
        .unwrap();
        let m = OccupancyGrid::new(m.cells().clone(), 0.05, m.frame().origin());
        // 0.05 m cells: the cell next to the wall has clearance 0.025 m, the
        // middle row (cols 2..=4) 0.075 m.
        let a = admissible(&m, 0.025);
        assert!(a[Cell::new(1, 1)]);
        let a = admissible(&m, 0.075);
        assert_eq!(
            a.true_cells().collect::<Vec<_>>(),
            vec![Cell::new(2, 2), Cell::new(2, 3), Cell::new(2, 4)]
        );
        assert_eq!(admissible(&m, 0.0751).count_true(), 0);
        // A radius no clearance reaches, or none at all: nothing, no panic.
        for r in [1e300, f64::INFINITY, f64::NAN] {
            assert_eq!(admissible(&m, r).count_true(), 0, "{r}");
        }
        let c = clearance(&m);
        assert!((c[Cell::new(2, 3)] - 0.075).abs() < 1e-12);
    }

    #[test]
    fn decimal_radii_are_not_rounded_away() {
        // 0.15 / 0.05 = 2.9999999999999996 in binary floating point.
        let m = OccupancyGrid::new(
            crate::Grid::new(9, 9, crate::Occupancy::Free),
            0.05,
            crate::math::Point::origin(),
        );
        // Edge counts as a wall: the centre cell has clearance 4.5 cells; a cell
        // 3 cells from the edge has clearance 3 cells = 0.15 m exactly.
        let a = admissible(&m, 0.15);
        assert!(a[Cell::new(3, 3)]);
        assert!(!a[Cell::new(2, 3)]);
    }
}
