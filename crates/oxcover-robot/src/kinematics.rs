//! The differential-drive (unicycle) model: `ẋ = v cos θ`, `ẏ = v sin θ`,
//! `θ̇ = ω`, with wheel rim speeds `v_L = v − ω·b/2`, `v_R = v + ω·b/2`
//! (`b` the wheel base).
//!
//! [`DiffDrive::integrate`] is exact for a constant `(v, ω)`: the robot runs
//! along a circular arc (a straight line when `ω = 0`), written with
//! `sinc(Δθ/2)` so that it stays accurate as `ω → 0`. Commands are limited by
//! [`DiffDrive::saturate`]: wheel speeds are scaled down together (which keeps
//! the curvature `ω/v`), then each wheel moves toward its commanded speed by
//! at most `max_wheel_accel · dt`, both by the same fraction.

use crate::error::{Result, positive};

pub use oxcover_grid::Pose;
use oxcover_grid::math::wrap_angle;

/// `sin x / x`, 1 at 0.
#[must_use]
pub(crate) fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-6 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// A differential-drive robot.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiffDrive {
    /// Distance between the wheels' contact points (m).
    pub wheel_base: f64,
    /// Wheel radius (m).
    pub wheel_radius: f64,
    /// Largest rim speed of a wheel (m/s).
    pub max_wheel_speed: f64,
    /// Largest rim acceleration of a wheel (m/s²).
    pub max_wheel_accel: f64,
}

impl Default for DiffDrive {
    /// A home floor-cleaning robot: the published iRobot Create 2 figures
    /// (wheel base 0.235 m, wheels 72 mm in diameter, 0.5 m/s top speed), with
    /// an assumed 1 m/s² wheel acceleration.
    fn default() -> Self {
        Self {
            wheel_base: 0.235,
            wheel_radius: 0.036,
            max_wheel_speed: 0.5,
            max_wheel_accel: 1.0,
        }
    }
}

impl DiffDrive {
    /// A robot; every parameter must be finite and positive.
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming the first bad parameter.
    pub fn new(
        wheel_base: f64,
        wheel_radius: f64,
        max_wheel_speed: f64,
        max_wheel_accel: f64,
    ) -> Result<Self> {
        Ok(Self {
            wheel_base: positive("wheel base", wheel_base)?,
            wheel_radius: positive("wheel radius", wheel_radius)?,
            max_wheel_speed: positive("max wheel speed", max_wheel_speed)?,
            max_wheel_accel: positive("max wheel acceleration", max_wheel_accel)?,
        })
    }

    /// The pose after driving `(v, ω)` for `dt` from `pose` (exact).
    #[must_use]
    pub fn integrate(&self, pose: Pose, v: f64, omega: f64, dt: f64) -> Pose {
        let dtheta = omega * dt;
        let s = v * dt * sinc(dtheta / 2.0);
        let mid = pose.theta + dtheta / 2.0;
        Pose {
            x: pose.x + s * mid.cos(),
            y: pose.y + s * mid.sin(),
            theta: wrap_angle(pose.theta + dtheta),
        }
    }

    /// Wheel rim speeds `(left, right)` for `(v, ω)`.
    #[must_use]
    pub fn wheel_speeds(&self, v: f64, omega: f64) -> (f64, f64) {
        let half = omega * self.wheel_base / 2.0;
        (v - half, v + half)
    }

    /// `(v, ω)` for wheel rim speeds `(left, right)`.
    #[must_use]
    pub fn from_wheels(&self, left: f64, right: f64) -> (f64, f64) {
        ((left + right) / 2.0, (right - left) / self.wheel_base)
    }

    /// Wheel angular speeds (rad/s) for `(v, ω)`.
    #[must_use]
    pub fn wheel_rates(&self, v: f64, omega: f64) -> (f64, f64) {
        let (l, r) = self.wheel_speeds(v, omega);
        (l / self.wheel_radius, r / self.wheel_radius)
    }

    /// The command `(v, ω)` limited by the wheels, given the previous
    /// (already feasible) command and the step `dt`. Non-finite commands
    /// become a stop.
    #[must_use]
    pub fn saturate(&self, command: (f64, f64), previous: (f64, f64), dt: f64) -> (f64, f64) {
        let (v, omega) = if command.0.is_finite() && command.1.is_finite() {
            command
        } else {
            (0.0, 0.0)
        };
        let (l, r) = self.wheel_speeds(v, omega);
        let top = l.abs().max(r.abs());
        let k = if top > self.max_wheel_speed {
            self.max_wheel_speed / top
        } else {
            1.0
        };
        let (l, r) = (l * k, r * k);
        let (pl, pr) = self.wheel_speeds(previous.0, previous.1);
        let (dl, dr) = (l - pl, r - pr);
        let step = self.max_wheel_accel * dt.max(0.0);
        let big = dl.abs().max(dr.abs());
        let f = if big > step { step / big } else { 1.0 };
        self.from_wheels(pl + f * dl, pr + f * dr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn close(a: Pose, b: Pose, tol: f64) -> bool {
        a.distance(&b) < tol && wrap_angle(a.theta - b.theta).abs() < tol
    }

    #[test]
    fn arcs_in_closed_form() {
        let r = DiffDrive::default();
        let o = Pose::new(1.0, 2.0, FRAC_PI_2);
        // A full circle of radius 0.5 m returns to the start.
        let p = r.integrate(o, 0.25, 0.5, 4.0 * PI);
        assert!(close(p, o, 1e-12), "{p:?}");
        // Half a circle of radius v/ω = 0.5 m, turning left from heading +y:
        // ends 1 m to the left (−x), heading −y.
        let p = r.integrate(o, 0.25, 0.5, 2.0 * PI);
        assert!(close(p, Pose::new(0.0, 2.0, -FRAC_PI_2), 1e-12), "{p:?}");
        // Straight ahead when ω = 0, and continuous as ω → 0.
        let s = r.integrate(o, 0.3, 0.0, 2.0);
        assert!(close(s, Pose::new(1.0, 2.6, FRAC_PI_2), 1e-12));
        assert!(close(r.integrate(o, 0.3, 1e-9, 2.0), s, 1e-8));
    }

    proptest! {
        #[test]
        fn steps_compose(v in -1.0f64..1.0, w in -3.0f64..3.0, a in 0.0f64..2.0, b in 0.0f64..2.0, th in -PI..PI) {
            let r = DiffDrive::default();
            let o = Pose::new(0.3, -0.2, th);
            let two = r.integrate(r.integrate(o, v, w, a), v, w, b);
            let one = r.integrate(o, v, w, a + b);
            prop_assert!(close(two, one, 1e-9), "{two:?} vs {one:?}");
        }

        #[test]
        fn saturation_keeps_curvature_and_limits(v in -3.0f64..3.0, w in -20.0f64..20.0) {
            let r = DiffDrive::default();
            // From a standstill with a long step: only the speed limit acts.
            let (sv, sw) = r.saturate((v, w), (0.0, 0.0), 100.0);
            let (l, rr) = r.wheel_speeds(sv, sw);
            prop_assert!(l.abs() <= r.max_wheel_speed + 1e-12 && rr.abs() <= r.max_wheel_speed + 1e-12);
            prop_assert!((sv * w - sw * v).abs() < 1e-9, "curvature changed");
            // A short step: each wheel changes by at most a·dt.
            let dt = 0.01;
            let (qv, qw) = r.saturate((v, w), (0.1, 0.0), dt);
            let (l0, r0) = r.wheel_speeds(0.1, 0.0);
            let (l1, r1) = r.wheel_speeds(qv, qw);
            prop_assert!((l1 - l0).abs() <= r.max_wheel_accel * dt + 1e-12);
            prop_assert!((r1 - r0).abs() <= r.max_wheel_accel * dt + 1e-12);
        }
    }

    #[test]
    fn wheels_round_trip_and_bad_parameters() {
        let r = DiffDrive::default();
        let (l, rr) = r.wheel_speeds(0.3, 1.0);
        assert!((l - (0.3 - 0.1175)).abs() < 1e-12 && (rr - 0.4175).abs() < 1e-12);
        let (v, w) = r.from_wheels(l, rr);
        assert!((v - 0.3).abs() < 1e-12 && (w - 1.0).abs() < 1e-12);
        assert_eq!(r.saturate((f64::NAN, 1.0), (0.0, 0.0), 1.0), (0.0, 0.0));
        let e = DiffDrive::new(0.2, f64::NAN, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("wheel radius"), "{e}");
        assert!(DiffDrive::new(0.2, 0.03, 0.0, 1.0).is_err());
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
    }
}
