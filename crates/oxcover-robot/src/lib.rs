//! # oxcover-robot
//!
//! The robot side of coverage: how a differential-drive robot moves, how it
//! tracks a planned path, what the run costs, and the curves smooth paths
//! are made of. Worlds and sensing live in `oxcover-world`.
//!
//! - [`kinematics`]: the unicycle / differential-drive model ([`DiffDrive`]),
//!   exact integration of constant `(v, ω)` steps along arcs, wheel speeds,
//!   and saturation of commands by wheel speed and acceleration limits that
//!   keeps the commanded curvature.
//! - [`control`]: the [`Controller`] trait, the tracking error in the robot
//!   frame, and two controllers behind it: [`Kanayama`] (Kanayama et al. 1990)
//!   and [`Klancar`], the nonlinear controller of Klancar et al. 2005
//!   (Siamantas 2010's Fig. 3c) in its `sinc` form.
//! - [`timing`]: time parametrisation of a metre polyline under speed,
//!   acceleration and turn-rate limits (stops and turns in place at corners,
//!   curvature-limited speed on smooth curves): the reference to track.
//! - [`simulate`](mod@simulate): closed-loop tracking of a timed path at a fixed step
//!   (reference, controller, wheel limits, exact motion), recording the
//!   executed samples.
//! - [`energy`]: a DC-motor wheel power model (torque constant, armature
//!   resistance, rolling resistance, constant electronics load) giving the
//!   joules of a run, and the RON robot description ([`RobotSpec`]).
//! - [`bezier`]: quintic Bézier segments from end points, tangents and second
//!   derivatives (Lee 2011, eq. 13) and C² splines through points.
//! - [`spiral`]: the Archimedean spiral `r = (R/π)|θ|` of Lee 2011's spiral
//!   path, turns one tool diameter apart.
//!
//! Angles are radians, counter-clockwise from the map's x axis; lengths are
//! metres; times seconds.
//!
//! ```
//! use oxcover_robot::{DiffDrive, Pose};
//!
//! // A quarter circle of radius 1 m at 0.5 m/s.
//! let robot = DiffDrive::default();
//! let p = robot.integrate(Pose::new(0.0, 0.0, 0.0), 0.5, 0.5, std::f64::consts::PI);
//! assert!((p.x - 1.0).abs() < 1e-12 && (p.y - 1.0).abs() < 1e-12);
//! ```

pub mod bezier;
pub mod control;
pub mod energy;
pub mod error;
pub mod kinematics;
pub mod simulate;
pub mod spiral;
pub mod timing;

pub use bezier::{G2Spline, QuinticBezier, spline_derivatives, spline_through};
pub use control::{Controller, Kanayama, Klancar, Reference, TrackingError};
pub use energy::{EnergyModel, RobotSpec};
pub use error::{Error, Result};
pub use kinematics::{DiffDrive, Pose};
pub use simulate::{Sample, simulate};
pub use spiral::ArchimedeanSpiral;
pub use timing::{Limits, Timing};
