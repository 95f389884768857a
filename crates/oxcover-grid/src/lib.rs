//! # oxcover-grid
//!
//! The data layer of oxcover: occupancy grids for complete coverage path
//! planning, and the map semantics every planner relies on.
//!
//! - [`Grid`], [`Cell`], [`Dir4`]/[`Dir8`]: a dense row-major grid, row 0 at the top.
//! - [`MapFrame`]: cells to metres and back (ROS convention, see the contract).
//! - [`OccupancyGrid`]: free / occupied / unknown cells placed in the frame.
//!   Unknown is never free.
//! - [`io`]: ROS map_server yaml + PGM (P2/P5, 8/16 bit) / PNG / BMP, plain
//!   images, MovingAI `.map`, an ASCII test format; a PGM+yaml writer.
//! - [`admissible()`], [`edt`]: cells a disc robot may occupy, from an exact
//!   Euclidean distance transform (its passes run in parallel; the values
//!   do not depend on the thread count), thresholded without the distances
//!   beyond the threshold where only "within `r`?" is asked.
//! - [`contour`]: iso-contours of a field over the grid (marching squares).
//! - [`components`], [`Coverability`]: 4-connected components (also within
//!   classes, as room units are), reachable and coverable cells for a robot,
//!   a tool and a start.
//! - [`CoarseGrid`]: tool-sized coverage cells over a fine map.
//! - [`footprint`]: which cells a tool covers along a polyline.
//! - [`traverse`]: exact traversal of straight segments over a grid.
//! - [`rotate`](mod@rotate): maps rotated about their centre, for rotation studies.
//! - [`random`]: seeded random maps for experiments and property tests.
//! - [`math`]: the metre-space point and vector types of the workspace, and
//!   `floor`/`ceil` for hot paths without a library call.
//!
//! ```
//! use oxcover_grid::{io::parse_ascii, Coverability, DiscRobot};
//!
//! let (map, start) = parse_ascii("
//!     S..#
//!     .#..
//!     ....
//! ").unwrap();
//! let robot = DiscRobot::cell_sized(map.resolution());
//! let problem = Coverability::with_start_cell(&map, robot, start.unwrap()).unwrap();
//! assert_eq!(problem.coverable_count(), 10);
//! let centre = map.frame().cell_center(problem.start);
//! assert_eq!((centre.x, centre.y), (0.5, 2.5));
//! ```

pub mod admissible;
pub mod coarse;
pub mod components;
pub mod contour;
pub mod coverable;
pub mod edt;
pub mod error;
pub mod footprint;
pub mod frame;
pub mod grid;
pub mod io;
pub mod math;
pub mod occupancy;
pub mod random;
pub mod rotate;
pub mod traverse;

pub use admissible::{TOLERANCE_CELLS, admissible, clearance};
pub use coarse::CoarseGrid;
pub use components::{Components, components4, components4_by_class, reachable};
pub use coverable::{Coverability, DiscRobot, coverable_cells, coverable_cells_within};
pub use error::{Error, Result};
pub use frame::MapFrame;
pub use grid::{Cell, Dir4, Dir8, Grid, Window};
pub use math::{Point, Pose, Real, Vector};
pub use occupancy::{Occupancy, OccupancyCounts, OccupancyGrid};
