//! # oxcover
//!
//! Complete coverage path planning, composed end to end: this crate joins the
//! grid model ([`oxcover_grid`]), the distance transforms
//! ([`oxcover_distance`]) and the planners ([`oxcover_planners`]) into one
//! pipeline, scores paths with the contract's metrics, draws them, and provides
//! the `oxcover` command line.
//!
//! - [`pipeline`]: the one plan pipeline (problem → plan → evaluate →
//!   outputs) behind the command line, the demo, every experiment and bench;
//!   the planner listing.
//! - [`bag`]: plans as ROS 2 bags (`--bag OUT.mcap`): the path stamped by
//!   the time model, rooms and targets as markers, odometry.
//! - [`closed_loop`]: a plan executed by a simulated differential-drive robot
//!   (time law, tracking controller, wheel limits, odometry noise, energy),
//!   scored on the executed trajectory.
//! - [`explore`]: the sensor-based planner `sensor-bcd` run on a polygonal
//!   world, scored on the world's raster, its Reeb graph matched against the
//!   world's exact critical points, and drawn (`oxcover explore`).
//! - [`memory`]: the memory a plan needs, estimated before it starts, and
//!   the machine's budget.
//! - [`output`]: outputs written whole or not at all.
//! - [`metrics`]: coverage, collisions, length, turns, rotation, redundancy,
//!   steps, estimated time, exactly as the contract defines them.
//! - [`path`]: cell paths to metre waypoints; the CSV path file.
//! - [`render`]: SVG and PNG pictures with a metrics legend, and overlays
//!   (coloured strokes, lines, markers) for states and graphs.
//! - [`report`]: the JSON report of `plan --report`.
//! - [`rooms`]: rooms of a map in metres, as JSON and as a picture
//!   (`oxcover segment`).
//! - [`targets`]: coverage targets (zones, spot, keep-out areas and virtual
//!   walls from GeoJSON, chosen rooms, resume) as cells.
//!
//! The command line (`oxcover`, including `map-from-camera` on
//! [`oxcover_vision`]) is the binary's own and uses only this API.
//!
//! Everything a user needs comes from this crate: the member crates are
//! re-exported ([`grid`], [`planners`], [`distance`], [`decomp`], [`robot`],
//! [`vision`], [`world`], [`rosbag`]) and the common names are at the root.
//!
//! ```
//! use oxcover::{parse_ascii, plan, PlanRequest};
//!
//! let (map, _) = parse_ascii("
//!     ......
//!     .##...
//!     ......
//! ").unwrap();
//! let request = PlanRequest::new("boustrophedon", map.resolution()).unwrap();
//! let outcome = plan(&map, &request).unwrap();
//! let m = &outcome.evaluation.metrics;
//! assert_eq!((m.coverage, m.collisions), (1.0, 0));
//! println!("{}", oxcover::path::to_csv(&outcome.points));
//! ```

pub mod bag;
pub mod closed_loop;
pub mod error;
pub mod explore;
pub mod memory;
pub mod metrics;
pub mod output;
pub mod path;
pub mod pipeline;
pub mod render;
pub mod report;
pub mod rooms;
pub mod targets;

pub use error::{Error, Result};
pub use metrics::{Evaluation, MetricParams, Metrics, evaluate};
pub use oxcover_grid::io::{ReadOptions, parse_ascii, read_map};
pub use oxcover_grid::{DiscRobot, OccupancyGrid, Point};
pub use oxcover_planners::{CoverageProblem, Planner, PlannerOptions, Start};
pub use path::{read_csv, write_csv};
pub use pipeline::{Outputs, PlanOutcome, PlanRequest, plan, planner, write_outputs};
pub use render::{Scene, render_to_file};

/// Decompositions ([`oxcover_decomp`]).
pub use oxcover_decomp as decomp;
/// Distance transforms ([`oxcover_distance`]).
pub use oxcover_distance as distance;
/// The grid and occupancy model ([`oxcover_grid`]).
pub use oxcover_grid as grid;
/// Planners, the registry and the coverage problem ([`oxcover_planners`]).
pub use oxcover_planners as planners;
/// Robot kinematics, control and polygonal worlds ([`oxcover_robot`]).
pub use oxcover_robot as robot;
/// ROS 2 bags: maps read from rosbag2, plans written as MCAP.
pub use oxcover_rosbag as rosbag;
/// Camera occupancy mapping ([`oxcover_vision`]).
pub use oxcover_vision as vision;
/// Polygonal worlds, range sensing and the sensor-based planner ([`oxcover_world`]).
pub use oxcover_world as world;
