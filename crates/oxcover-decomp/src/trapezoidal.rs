//! Trapezoidal (slab) decomposition (Latombe 1991; Preparata & Shamos 1985)
//! on grid slices.
//!
//! Every boustrophedon event cuts (see [`crate::boustrophedon`](mod@crate::boustrophedon)), and so does
//! every vertex of a cell's side: a new cell starts wherever an interval's
//! start or end stops changing linearly along the sweep, i.e. where the
//! boundary bends. On a grid a straight wall at an angle moves in steps of
//! whole cells, so "bends" are second differences of an end above
//! [`BEND_CELLS`]; below that the side counts as straight. Hence many more,
//! smaller cells than boustrophedon, which is the point of Pavlíček 2002's Fig. 8.

use oxcover_grid::Grid;

use crate::slices::{Interval, Lane, SliceDecomposition, Slices};

/// Largest change of an end's step between lines still taken as a straight side (cells).
pub const BEND_CELLS: f64 = 2.0;

/// The trapezoidal decomposition of `passable` swept at `angle` (radians,
/// map frame) with lines `spacing` cells apart.
#[must_use]
pub fn trapezoidal(passable: &Grid<bool>, angle: f64, spacing: f64) -> SliceDecomposition {
    SliceDecomposition::build(Slices::new(passable, angle, spacing), straight_sides)
}

fn straight_sides(lanes: &[Lane], next: &Interval) -> bool {
    match lanes {
        [] => true,
        [.., a, b] => {
            let (a, b) = (a.interval, b.interval);
            let bend_lo = ((next.lo - b.lo) - (b.lo - a.lo)).abs();
            let bend_hi = ((next.hi - b.hi) - (b.hi - a.hi)).abs();
            bend_lo <= BEND_CELLS && bend_hi <= BEND_CELLS
        }
        // With one lane the slope is not known yet: any step starts it, but a
        // jump larger than a bend still cuts.
        [a] => {
            (next.lo - a.interval.lo).abs() <= BEND_CELLS
                && (next.hi - a.interval.hi).abs() <= BEND_CELLS
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::boustrophedon::boustrophedon;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    #[test]
    fn steps_in_a_wall_cut_cells_that_boustrophedon_keeps() {
        // The bottom wall steps up by three cells halfway: one boustrophedon
        // cell, two trapezoids.
        let m = mask(&[
            "..........",
            "..........",
            "..........",
            "..........",
            ".....#####",
            ".....#####",
            ".....#####",
        ]);
        let v = std::f64::consts::FRAC_PI_2;
        assert_eq!(boustrophedon(&m, v, 1.0).cells.len(), 1);
        let t = trapezoidal(&m, v, 1.0);
        assert_eq!(t.cells.len(), 2);
        assert_eq!(t.edges, vec![(0, 1)]);
    }

    #[test]
    fn a_slanted_wall_is_one_side() {
        // A 45° wall: every line's end moves by one cell, a straight side.
        let m = mask(&["........", ".......#", "......##", ".....###", "....####"]);
        assert_eq!(
            trapezoidal(&m, std::f64::consts::FRAC_PI_2, 1.0)
                .cells
                .len(),
            1
        );
    }
}
