//! # oxcover-world
//!
//! Polygonal worlds and what senses them, apart from how a robot moves
//! (`oxcover-robot`) and from the grid planners (`oxcover-planners`):
//!
//! - [`world`](mod@world): polygonal worlds (outer boundary, polygons convex
//!   or not, discs, rectangles) read from RON, checked, rasterised to the
//!   contract's occupancy grids, with exact critical points.
//! - [`geometry`]: ray casting and exact clearances with parry2d, kept behind
//!   this one module: a world's boundary curves ([`WorldGeometry`]) and a
//!   grid map's obstacles as boxes ([`Obstacles`]), both [`RayCaster`]s.
//! - [`sensors`]: a ring of range rays with seeded Gaussian noise, cast
//!   against any [`RayCaster`].
//! - [`critical_point`]: Demir 2018's three-ray critical-point detector (the
//!   dot-product test of its eqs. 1–3, with tolerances), classifying IN/OUT
//!   and convex/concave.
//! - [`wall_follow`]: PID wall following on the lateral range.
//! - [`random_world`](mod@random_world): seeded random worlds of convex and
//!   concave polygons with guaranteed passages, for property tests.
//! - [`sensor_bcd`]: the online sensor-based planner of Demir 2018 (Acar &
//!   Choset 2002): it covers an unknown polygonal world with range rays,
//!   growing a boustrophedon decomposition and its Reeb graph as it goes
//!   (`oxcover explore`); beside it, the seed's own algorithm as published
//!   ([`sensor_bcd::Algorithm::Paper`]). It needs a world to sense, not a
//!   grid, so it is not a grid planner of `oxcover-planners`.
//!
//! ```
//! use oxcover_world::sensor_bcd::{Config, explore};
//! use oxcover_world::{World, WorldGeometry};
//!
//! // An empty 2 × 1.5 m room, covered from near its lower-left corner.
//! let world = World::parse(
//!     "(name: \"room\", width: 2.0, height: 1.5, resolution: 0.025, obstacles: [])",
//!     "room",
//! )
//! .unwrap();
//! let start = oxcover_grid::Point::new(0.3, 0.3);
//! let run = explore(&WorldGeometry::new(&world), start, &Config::default()).unwrap();
//! assert!(run.complete);
//! assert_eq!(run.collisions, 0);
//! ```

pub mod critical_point;
pub mod error;
pub mod geometry;
pub mod random_world;
pub mod sensor_bcd;
pub mod sensors;
pub mod wall_follow;
pub mod world;

pub use critical_point::{Detection, Returns, ThreeRayDetector};
pub use error::{Error, Result};
pub use geometry::{Obstacles, RayCaster, WorldGeometry};
pub use random_world::{RandomWorldSpec, random_world};
pub use sensors::{RangeSensor, Reading};
pub use wall_follow::{Side, WallFollower};
pub use world::{Convexity, CriticalKind, Event, Outline, Shape, TrueCriticalPoint, World};
