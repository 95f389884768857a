//! # oxcover-robot
//!
//! The robot side of coverage (issue 5, first part): how a differential-drive
//! robot moves and how it tracks a planned path.
//!
//! - [`kinematics`]: the unicycle / differential-drive model ([`DiffDrive`]),
//!   exact integration of constant `(v, ω)` steps along arcs, wheel speeds,
//!   and saturation of commands by wheel speed and acceleration limits that
//!   keeps the commanded curvature.
//! - [`control`]: the [`Controller`] trait, the tracking error in the robot
//!   frame, and two controllers behind it: [`Kanayama`] (Kanayama et al. 1990)
//!   and [`Klancar`], the nonlinear controller of Klancar et al. 2005 (seed
//!   000's Fig. 3c) in its `sinc` form.
//! - [`timing`]: time parametrisation of a metre polyline under speed,
//!   acceleration and turn-rate limits (stops and turns in place at corners,
//!   curvature-limited speed on smooth curves): the reference to track.
//! - [`simulate`](mod@simulate): closed-loop tracking of a timed path at a fixed step
//!   (reference, controller, wheel limits, exact motion), recording the
//!   executed samples.
//! - [`energy`]: a DC-motor wheel power model (torque constant, armature
//!   resistance, rolling resistance, constant electronics load) giving the
//!   joules of a run, and the RON robot description ([`RobotSpec`]).
//! - [`geometry`]: a map's obstacles as boxes for ray casting (parry2d,
//!   kept behind this module).
//! - [`sensors`]: a ring of range rays with seeded Gaussian noise, cast
//!   against anything that is a [`RayCaster`].
//! - [`world`]: polygonal worlds (outer boundary, polygons convex or not,
//!   discs, rectangles) read from RON, rasterised to occupancy grids,
//!   ray-cast with parry2d, with exact clearances and exact critical points.
//! - [`random_world`](mod@random_world): seeded random worlds of convex and concave polygons
//!   with guaranteed passages, for property tests.
//! - [`critical_point`]: Demir 2018's three-ray critical-point detector (the
//!   dot-product test of its eqs. 1–3, with tolerances), classifying IN/OUT
//!   and convex/concave.
//! - [`wall_follow`]: PID wall following on the lateral range.
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
pub mod critical_point;
pub mod energy;
pub mod error;
pub mod geometry;
pub mod kinematics;
pub mod random_world;
pub mod sensors;
pub mod simulate;
pub mod spiral;
pub mod timing;
pub mod wall_follow;
pub mod world;

pub use bezier::{QuinticBezier, spline_derivatives, spline_through};
pub use control::{Controller, Kanayama, Klancar, Reference, TrackingError};
pub use critical_point::{Detection, Returns, ThreeRayDetector};
pub use energy::{EnergyModel, RobotSpec};
pub use error::{Error, Result};
pub use geometry::{Obstacles, RayCaster};
pub use kinematics::{DiffDrive, Pose, wrap_angle};
pub use random_world::{RandomWorldSpec, random_world};
pub use sensors::{RangeSensor, Reading};
pub use simulate::{Sample, simulate};
pub use spiral::ArchimedeanSpiral;
pub use timing::{Limits, Timing};
pub use wall_follow::{Side, WallFollower};
pub use world::{
    Convexity, CriticalKind, Event, Outline, Shape, TrueCriticalPoint, World, WorldGeometry,
};
