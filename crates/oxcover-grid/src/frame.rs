//! The map frame: cells to metres and back, exactly as the contract says.
//!
//! ROS convention: `origin` is the lower-left corner of the bottom-left pixel,
//! x grows to the right, y grows up, and image row 0 is the TOP row. The cell at
//! row `r`, column `c` of an `H`-row map has its centre at
//! `x = ox + (c + 0.5)·res`, `y = oy + (H − 1 − r + 0.5)·res`.
//!
//! With a yaw θ (map_server's third `origin` value) the image is rotated by
//! θ about the origin: the centre is `(ox, oy) + R(θ)·((c + 0.5)·res,
//! (H − 1 − r + 0.5)·res)`. Yaw 0 takes the unrotated arithmetic, so maps
//! without a yaw give bit-identical coordinates.

use crate::grid::Cell;
use crate::math::{Point, Real, fast_floor};

/// Placement of a `width × height` grid in the map frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MapFrame {
    resolution: Real,
    origin: Point,
    width: usize,
    height: usize,
    /// Rotation of the image about the origin (radians, counter-clockwise).
    #[cfg_attr(feature = "serde", serde(default))]
    yaw: Real,
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
            yaw: 0.0,
        }
    }

    /// The same frame with the image rotated by `yaw` radians about the
    /// origin (the caller checks it is finite).
    #[must_use]
    pub fn with_yaw(mut self, yaw: Real) -> Self {
        self.yaw = yaw;
        self
    }

    /// The frame of the `height × width` block of cells whose top-left cell
    /// is `corner` (the same metres for the same cells).
    #[must_use]
    pub fn crop(&self, corner: Cell, width: usize, height: usize) -> Self {
        let res = self.resolution;
        // The block's lower-left corner, in this frame.
        let bottom = self.height - (corner.row + height);
        let origin = self.image_to_map(corner.col as Real * res, bottom as Real * res);
        Self {
            resolution: res,
            origin,
            width,
            height,
            yaw: self.yaw,
        }
    }

    /// The image's rotation about the origin (radians).
    #[must_use]
    pub fn yaw(&self) -> Real {
        self.yaw
    }

    /// A point `local` of the unrotated image frame (metres from the origin)
    /// in the map frame.
    #[inline]
    fn image_to_map(&self, lx: Real, ly: Real) -> Point {
        if self.yaw == 0.0 {
            return Point::new(self.origin.x + lx, self.origin.y + ly);
        }
        let (s, c) = self.yaw.sin_cos();
        Point::new(
            self.origin.x + c * lx - s * ly,
            self.origin.y + s * lx + c * ly,
        )
    }

    /// A map-frame point in the unrotated image frame (metres from the origin).
    #[inline]
    fn map_to_image(&self, p: &Point) -> (Real, Real) {
        let (dx, dy) = (p.x - self.origin.x, p.y - self.origin.y);
        if self.yaw == 0.0 {
            return (dx, dy);
        }
        let (s, c) = self.yaw.sin_cos();
        (c * dx + s * dy, -s * dx + c * dy)
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
        self.image_to_map(
            (cell.col as Real + 0.5) * res,
            ((self.height - 1 - cell.row) as Real + 0.5) * res,
        )
    }

    /// Centre of a fractional cell position `(row, col)` (cell centres at `.0`).
    #[must_use]
    pub fn position(&self, row: Real, col: Real) -> Point {
        let res = self.resolution;
        self.image_to_map(
            (col + 0.5) * res,
            ((self.height - 1) as Real - row + 0.5) * res,
        )
    }

    /// Fractional `(row, col)` of a point (cell centres at integer values).
    #[must_use]
    pub fn fractional_cell(&self, p: &Point) -> (Real, Real) {
        let res = self.resolution;
        let (lx, ly) = self.map_to_image(p);
        let col = lx / res - 0.5;
        let row = (self.height - 1) as Real - (ly / res - 0.5);
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
        let (lx, ly) = self.map_to_image(p);
        let fx = fast_floor(lx / self.resolution);
        let fy = fast_floor(ly / self.resolution);
        if fx < 0.0 || fy < 0.0 || fx >= self.width as Real || fy >= self.height as Real {
            return None;
        }
        let col = fx as usize;
        let k = fy as usize;
        Some(Cell::new(self.height - 1 - k, col))
    }

    /// `(min, max)` corners of the mapped area in metres (of its bounding
    /// box when the image is rotated).
    #[must_use]
    pub fn bounds(&self) -> (Point, Point) {
        let res = self.resolution;
        let (w, h) = (self.width as Real * res, self.height as Real * res);
        if self.yaw == 0.0 {
            return (
                self.origin,
                Point::new(self.origin.x + w, self.origin.y + h),
            );
        }
        let corners = [
            self.image_to_map(0.0, 0.0),
            self.image_to_map(w, 0.0),
            self.image_to_map(0.0, h),
            self.image_to_map(w, h),
        ];
        let lo = corners
            .iter()
            .fold(Point::new(Real::INFINITY, Real::INFINITY), |a, c| {
                Point::new(a.x.min(c.x), a.y.min(c.y))
            });
        let hi = corners.iter().fold(
            Point::new(Real::NEG_INFINITY, Real::NEG_INFINITY),
            |a, c| Point::new(a.x.max(c.x), a.y.max(c.y)),
        );
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_yaw_rotates_the_image_about_the_origin() {
        let f = MapFrame::new(4, 3, 0.5, Point::new(-1.0, 2.0));
        let r = f.with_yaw(std::f64::consts::FRAC_PI_2);
        // Bottom-left cell's centre (0.25, 0.25) from the origin, turned a
        // quarter: (-0.25, 0.25).
        let c = r.cell_center(Cell::new(2, 0));
        assert!(
            (c.x - -1.25).abs() < 1e-12 && (c.y - 2.25).abs() < 1e-12,
            "{c:?}"
        );
        for cell in [Cell::new(0, 0), Cell::new(1, 2), Cell::new(2, 3)] {
            let p = r.cell_center(cell);
            assert_eq!(r.cell_at(&p), Some(cell));
            let (row, col) = r.fractional_cell(&p);
            assert!((row - cell.row as f64).abs() < 1e-9 && (col - cell.col as f64).abs() < 1e-9);
        }
        let (lo, hi) = r.bounds();
        assert!(
            (lo.x - -2.5).abs() < 1e-12 && (hi.y - 4.0).abs() < 1e-12,
            "{lo:?} {hi:?}"
        );
        // A crop keeps the metres of its cells.
        let k = r.crop(Cell::new(1, 1), 2, 2);
        assert!((k.cell_center(Cell::new(0, 0)) - r.cell_center(Cell::new(1, 1))).norm() < 1e-12);
        // Yaw 0 is the plain frame, bit for bit.
        assert_eq!(
            f.with_yaw(0.0).cell_center(Cell::new(1, 1)),
            f.cell_center(Cell::new(1, 1))
        );
    }

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
