//! Boustrophedon decomposition (Choset & Pignon 1997) on grid slices.
//!
//! Cells are cut only at critical events: where the number of free intervals
//! changes along the sweep, i.e. where an interval splits (IN event) or two
//! merge (OUT), appears or ends. An interval continues its cell exactly when
//! it overlaps one interval on the previous line and that one overlaps only it
//! (a one-to-one link); any other overlap is a cell boundary and an edge of
//! the adjacency graph. Slices are taken at lane spacing ([`crate::slices`]),
//! so each cell is covered by its own lanes, back and forth.

use oxcover_grid::Grid;

use crate::slices::{SliceDecomposition, Slices};

/// The boustrophedon decomposition of `passable` swept at `angle` (radians,
/// map frame) with lines `spacing` cells apart.
#[must_use]
pub fn boustrophedon(passable: &Grid<bool>, angle: f64, spacing: f64) -> SliceDecomposition {
    SliceDecomposition::build(Slices::new(passable, angle, spacing), |_, _| true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::Grid;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    #[test]
    fn one_obstacle_gives_four_cells() {
        // Vertical lanes (90°): left of the obstacle, above, below, right.
        let m = mask(&["........", "........", "...##...", "...##...", "........"]);
        let d = boustrophedon(&m, std::f64::consts::FRAC_PI_2, 1.0);
        assert_eq!(d.cells.len(), 4);
        assert_eq!(d.edges, vec![(0, 1), (0, 2), (1, 3), (2, 3)]);
        let lanes: usize = d.cells.iter().map(Vec::len).sum();
        assert_eq!(lanes, 8 + 2);
    }

    #[test]
    fn open_room_is_one_cell() {
        let m = mask(&["......", "......", "......"]);
        for deg in [0.0f64, 30.0, 45.0, 90.0] {
            assert_eq!(
                boustrophedon(&m, deg.to_radians(), 1.0).cells.len(),
                1,
                "{deg}"
            );
        }
    }
}
