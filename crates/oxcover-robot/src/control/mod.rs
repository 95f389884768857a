//! Path-tracking controllers behind one trait.
//!
//! A [`Reference`] is where the robot should be now and how the reference
//! moves (`v_r`, `ω_r`). The [`TrackingError`] is the reference pose seen
//! from the robot: `e_x = cos θ·Δx + sin θ·Δy`, `e_y = −sin θ·Δx + cos θ·Δy`,
//! `e_θ = wrap(θ_r − θ)`. A [`Controller`] turns it into a command `(v, ω)`,
//! which the caller limits by the robot's wheels
//! ([`crate::DiffDrive::saturate`]).

mod kanayama;
mod klancar;

pub use kanayama::Kanayama;
pub use klancar::Klancar;

use crate::kinematics::Pose;
use oxcover_grid::math::wrap_angle;

/// A reference state to track.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reference {
    /// Where the robot should be.
    pub pose: Pose,
    /// Reference linear speed (m/s).
    pub v: f64,
    /// Reference angular speed (rad/s).
    pub omega: f64,
}

/// The reference pose in the robot's frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TrackingError {
    /// Ahead of the robot (m).
    pub ex: f64,
    /// To the robot's left (m).
    pub ey: f64,
    /// Heading error (rad, in `(−π, π]`).
    pub etheta: f64,
}

impl TrackingError {
    /// The error of `pose` with respect to `reference`.
    #[must_use]
    pub fn of(pose: &Pose, reference: &Pose) -> Self {
        let (dx, dy) = (reference.x - pose.x, reference.y - pose.y);
        let (s, c) = pose.theta.sin_cos();
        Self {
            ex: c * dx + s * dy,
            ey: -s * dx + c * dy,
            etheta: wrap_angle(reference.theta - pose.theta),
        }
    }
}

/// A tracking controller.
pub trait Controller {
    /// Short name (for reports).
    fn name(&self) -> &'static str;
    /// The command `(v, ω)` for the robot at `pose` tracking `reference`.
    fn command(&self, pose: &Pose, reference: &Reference) -> (f64, f64);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DiffDrive;

    /// Tracks `reference(t)` from `start` for `seconds` with steps of 10 ms
    /// under the default robot's limits; returns the final position error.
    fn track(
        controller: &dyn Controller,
        start: Pose,
        reference: impl Fn(f64) -> Reference,
        seconds: f64,
    ) -> f64 {
        let robot = DiffDrive::default();
        let dt = 0.01;
        let (mut pose, mut last) = (start, (0.0, 0.0));
        let steps = (seconds / dt) as usize;
        for k in 0..steps {
            let r = reference(k as f64 * dt);
            let cmd = robot.saturate(controller.command(&pose, &r), last, dt);
            pose = robot.integrate(pose, cmd.0, cmd.1, dt);
            last = cmd;
        }
        let r = reference(steps as f64 * dt);
        let e = TrackingError::of(&pose, &r.pose);
        e.ex.hypot(e.ey) + e.etheta.abs()
    }

    fn line(t: f64) -> Reference {
        Reference {
            pose: Pose::new(0.3 * t, 0.0, 0.0),
            v: 0.3,
            omega: 0.0,
        }
    }

    fn circle(t: f64) -> Reference {
        // Radius 1 m about (0, 1), counter-clockwise at 0.3 m/s.
        let robot = DiffDrive::default();
        Reference {
            pose: robot.integrate(Pose::default(), 0.3, 0.3, t),
            v: 0.3,
            omega: 0.3,
        }
    }

    fn controllers() -> [Box<dyn Controller>; 2] {
        [Box::new(Kanayama::default()), Box::new(Klancar::default())]
    }

    #[test]
    fn the_error_is_the_reference_seen_from_the_robot() {
        let e = TrackingError::of(
            &Pose::new(1.0, 1.0, std::f64::consts::FRAC_PI_2),
            &Pose::new(1.0, 2.0, 0.0),
        );
        assert!((e.ex - 1.0).abs() < 1e-12 && e.ey.abs() < 1e-12);
        assert!((e.etheta + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn on_the_reference_the_command_is_the_reference() {
        for c in controllers() {
            let r = circle(2.0);
            let (v, w) = c.command(&r.pose, &r);
            assert!(
                (v - 0.3).abs() < 1e-12 && (w - 0.3).abs() < 1e-12,
                "{}",
                c.name()
            );
        }
    }

    #[test]
    fn converge_on_a_line_from_an_offset_start() {
        for c in controllers() {
            let e0 = track(c.as_ref(), Pose::new(-0.2, 0.3, 0.4), line, 0.0);
            let e = track(c.as_ref(), Pose::new(-0.2, 0.3, 0.4), line, 30.0);
            assert!(e0 > 0.5 && e < 1e-3, "{}: {e0} -> {e}", c.name());
        }
    }

    #[test]
    fn converge_on_a_circle_from_an_offset_start() {
        for c in controllers() {
            let e = track(c.as_ref(), Pose::new(0.0, -0.3, -0.5), circle, 40.0);
            assert!(e < 1e-3, "{}: {e}", c.name());
        }
    }
}
