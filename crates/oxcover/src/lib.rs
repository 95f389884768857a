//! # oxcover
//!
//! Complete coverage path planning, composed end to end: this crate joins the
//! grid model ([`oxcover_grid`]), the distance transforms
//! ([`oxcover_distance`]) and the planners ([`oxcover_planners`]) into one
//! pipeline, scores paths with the contract's metrics, draws them, and provides
//! the `oxcover` command line.
//!
//! - [`planner`]: the pipeline (coverage problem → coverage grid → planner →
//!   fine path → boundary pass → metre path) and the planner listing.
//! - [`closed_loop`]: a plan executed by a simulated differential-drive robot
//!   (time law, tracking controller, wheel limits, odometry noise, energy),
//!   scored on the executed trajectory.
//! - [`explore`]: the sensor-based planner `sensor-bcd` run on a polygonal
//!   world, scored on the world's raster, its Reeb graph matched against the
//!   world's exact critical points, and drawn (`oxcover explore`).
//! - [`metrics`]: coverage, collisions, length, turns, rotation, redundancy,
//!   steps, estimated time, exactly as the contract defines them.
//! - [`path`]: cell paths to metre waypoints; the CSV path file.
//! - [`render`]: SVG and PNG pictures with a metrics legend, and overlays
//!   (coloured strokes, lines, markers) for states and graphs.
//! - [`report`]: the JSON report of `plan --report`.
//! - [`cli`], [`demo`]: the command line (including `map-from-camera`, on
//!   `oxcover_vision`) and its no-argument demo.
//!
//! ```
//! use oxcover::planner::{plan, PlanRequest};
//! use oxcover_grid::io::parse_ascii;
//!
//! let (map, _) = parse_ascii("
//!     ......
//!     .##...
//!     ......
//! ").unwrap();
//! let outcome = plan(&map, &PlanRequest::new("dtc", map.resolution())).unwrap();
//! let m = &outcome.evaluation.metrics;
//! assert_eq!((m.coverage, m.collisions), (1.0, 0));
//! println!("{}", oxcover::path::to_csv(&outcome.points));
//! ```

pub mod cli;
pub mod closed_loop;
pub mod demo;
pub mod error;
pub mod explore;
pub mod metrics;
pub mod path;
pub mod planner;
pub mod render;
pub mod report;

pub use error::{Error, Result};
