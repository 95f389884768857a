//! The map frame: cells to metres and back, exactly as the contract says.
//!
//! ROS convention: `origin` is the lower-left corner of the bottom-left pixel,
//! x grows to the right, y grows up, and image row 0 is the TOP row. The cell at
//! row `r`, column `c` of an `H`-row map has its centre at
//! `x = ox + (c + 0.5)·res`, `y = oy + (H − 1 − r + 0.5)·res`.

use crate::grid::Cell;
use crate::math::{Point, Real};

/// Placement of a `width × height` grid in the map frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MapFrame {
    resolution: Real,
    origin: Point,
    width: usize,
    height: usize,
}

impl MapFrame {
    /// A frame with `resolution` metres per cell and the given lower-left `origin`.
    ///
    /// The caller guarantees `resolution` is finite and positive (the map readers
    /// check it and report a clear error otherwise).
    #[must_use]
    pub fn new(width: usize, height: usize, resolution: Real, origin: Point) -> Self {
        debug_assert!(resolution.is_finite() && resolution > 0.0);
        Self {
            resolution,
            origin,
            width,
            height,
        }
    }

    /// A unit frame: 1 m cells, origin (0, 0).
    #[must_use]
    pub fn unit(width: usize, height: usize) -> Self {
        Self::new(width, height, 1.0, Point::origin())
    }

    /// Metres per cell.
    #[must_use]
    pub fn resolution(&self) -> Real {
        self.resolution
    }

    /// Lower-left corner of the bottom-left cell.
    #[must_use]
    pub fn origin(&self) -> Point {
        self.origin
    }

    /// Number of columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Centre of `cell` in metres.
    #[must_use]
    pub fn cell_center(&self, cell: Cell) -> Point {
        let res = self.resolution;
        Point::new(
            self.origin.x + (cell.col as Real + 0.5) * res,
            self.origin.y + ((self.height - 1 - cell.row) as Real + 0.5) * res,
        )
    }

    /// Centre of a fractional cell position `(row, col)` (cell centres at `.0`).
    #[must_use]
    pub fn position(&self, row: Real, col: Real) -> Point {
        let res = self.resolution;
        Point::new(
            self.origin.x + (col + 0.5) * res,
            self.origin.y + ((self.height - 1) as Real - row + 0.5) * res,
        )
    }

    /// Fractional `(row, col)` of a point (cell centres at integer values).
    #[must_use]
    pub fn fractional_cell(&self, p: &Point) -> (Real, Real) {
        let res = self.resolution;
        let col = (p.x - self.origin.x) / res - 0.5;
        let row = (self.height - 1) as Real - ((p.y - self.origin.y) / res - 0.5);
        (row, col)
    }

    /// The cell containing `p`, or `None` outside the map (or for a non-finite point).
    ///
    /// A point on a cell border belongs to the cell on its upper-x / upper-y side
    /// (`floor` semantics), as in ROS.
    #[must_use]
    pub fn cell_at(&self, p: &Point) -> Option<Cell> {
        if !(p.x.is_finite() && p.y.is_finite()) {
            return None;
        }
        let fx = ((p.x - self.origin.x) / self.resolution).floor();
        let fy = ((p.y - self.origin.y) / self.resolution).floor();
        if fx < 0.0 || fy < 0.0 || fx >= self.width as Real || fy >= self.height as Real {
            return None;
        }
        let col = fx as usize;
        let k = fy as usize;
        Some(Cell::new(self.height - 1 - k, col))
    }

    /// `(min, max)` corners of the mapped area in metres.
    #[must_use]
    pub fn bounds(&self) -> (Point, Point) {
        let res = self.resolution;
        (
            self.origin,
            Point::new(
                self.origin.x + self.width as Real * res,
                self.origin.y + self.height as Real * res,
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_follow_the_contract() {
        let f = MapFrame::new(4, 3, 0.5, Point::new(-1.0, 2.0));
        // Top-left cell: x = -1 + 0.25, y = 2 + (3 - 1 - 0 + 0.5) * 0.5.
        let c = f.cell_center(Cell::new(0, 0));
        assert!((c.x - -0.75).abs() < 1e-12 && (c.y - 3.25).abs() < 1e-12);
        // Bottom-right cell.
        let c = f.cell_center(Cell::new(2, 3));
        assert!((c.x - 0.75).abs() < 1e-12 && (c.y - 2.25).abs() < 1e-12);
    }

    #[test]
    fn cell_at_inverts_cell_center() {
        let f = MapFrame::new(7, 5, 0.05, Point::new(-10.0, -3.3));
        for row in 0..5 {
            for col in 0..7 {
                let cell = Cell::new(row, col);
                assert_eq!(f.cell_at(&f.cell_center(cell)), Some(cell));
                let (r, c) = f.fractional_cell(&f.cell_center(cell));
                assert!((r - row as f64).abs() < 1e-9 && (c - col as f64).abs() < 1e-9);
            }
        }
        assert_eq!(f.cell_at(&Point::new(-10.01, -3.0)), None);
        assert_eq!(f.cell_at(&Point::new(f64::NAN, 0.0)), None);
        // Lower-left corner belongs to the bottom-left cell.
        assert_eq!(f.cell_at(&Point::new(-10.0, -3.3)), Some(Cell::new(4, 0)));
    }
}
