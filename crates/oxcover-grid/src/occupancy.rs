//! Three-state occupancy maps placed in the map frame.
//!
//! **Unknown is never free**: an unknown cell is not entered and not counted as
//! area to cover, exactly like an occupied one; the two are kept apart only so
//! that renders and `oxcover info` can show them differently.

use crate::frame::MapFrame;
use crate::grid::{Cell, Grid};
use crate::math::{Point, Real};

/// The state of one map cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Occupancy {
    /// Known to be free.
    Free,
    /// Known to be occupied.
    #[default]
    Occupied,
    /// Not known (never treated as free).
    Unknown,
}

impl Occupancy {
    /// Whether the robot may use the cell.
    #[must_use]
    pub fn is_free(self) -> bool {
        self == Occupancy::Free
    }
}

/// An occupancy grid with its placement in the map frame.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OccupancyGrid {
    cells: Grid<Occupancy>,
    frame: MapFrame,
}

/// Cell counts by state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OccupancyCounts {
    /// Free cells.
    pub free: usize,
    /// Occupied cells.
    pub occupied: usize,
    /// Unknown cells.
    pub unknown: usize,
}

impl OccupancyGrid {
    /// Places `cells` at `resolution` metres per cell with lower-left corner `origin`.
    #[must_use]
    pub fn new(cells: Grid<Occupancy>, resolution: Real, origin: Point) -> Self {
        let frame = MapFrame::new(cells.width(), cells.height(), resolution, origin);
        Self { cells, frame }
    }

    /// A map on the unit frame (1 m cells, origin (0, 0)), as for MovingAI maps.
    #[must_use]
    pub fn unit(cells: Grid<Occupancy>) -> Self {
        Self::new(cells, 1.0, Point::origin())
    }

    /// The same map with its image rotated by `yaw` radians about the origin
    /// (map_server's third `origin` value, see [`MapFrame::with_yaw`]).
    #[must_use]
    pub fn with_yaw(mut self, yaw: Real) -> Self {
        self.frame = self.frame.with_yaw(yaw);
        self
    }

    /// A unit-frame map from a `free` mask (`false` = occupied).
    #[must_use]
    pub fn from_free_mask(free: &Grid<bool>) -> Self {
        Self::unit(free.map(|&f| {
            if f {
                Occupancy::Free
            } else {
                Occupancy::Occupied
            }
        }))
    }

    /// The cell states.
    #[must_use]
    pub fn cells(&self) -> &Grid<Occupancy> {
        &self.cells
    }

    /// Mutable cell states (the frame keeps its size).
    pub fn cells_mut(&mut self) -> &mut Grid<Occupancy> {
        &mut self.cells
    }

    /// Placement in the map frame.
    #[must_use]
    pub fn frame(&self) -> &MapFrame {
        &self.frame
    }

    /// Number of columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.cells.width()
    }

    /// Number of rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.cells.height()
    }

    /// Metres per cell.
    #[must_use]
    pub fn resolution(&self) -> Real {
        self.frame.resolution()
    }

    /// `true` where the cell is free.
    #[must_use]
    pub fn free_mask(&self) -> Grid<bool> {
        self.cells.map(|o| o.is_free())
    }

    /// Whether `cell` is inside and free.
    #[must_use]
    pub fn is_free(&self, cell: Cell) -> bool {
        self.cells.get(cell).is_some_and(|o| o.is_free())
    }

    /// Cell counts by state.
    #[must_use]
    pub fn counts(&self) -> OccupancyCounts {
        let mut c = OccupancyCounts::default();
        for o in self.cells.as_slice() {
            match o {
                Occupancy::Free => c.free += 1,
                Occupancy::Occupied => c.occupied += 1,
                Occupancy::Unknown => c.unknown += 1,
            }
        }
        c
    }
}
