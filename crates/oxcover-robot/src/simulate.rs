//! Closed-loop tracking at a fixed step: the reference of a [`Timing`], a
//! [`Controller`], the wheel limits and the exact motion of a [`DiffDrive`].
//!
//! Each step reads the reference at the step's start, asks the controller
//! for `(v, ω)`, limits it by the wheels ([`DiffDrive::saturate`]) and moves
//! the robot exactly along the resulting arc. The run lasts the reference's
//! duration plus a settling time in which the final pose is held. The
//! executed samples are what the integration crate scores (the contract's
//! metrics apply to the EXECUTED trajectory, not the plan).

use crate::control::{Controller, TrackingError};
use crate::error::{Result, positive};
use crate::kinematics::{DiffDrive, Pose};
use crate::timing::Timing;

/// Most control steps one run may take (a sample each, about 50 bytes): a
/// smaller step or a longer run is refused rather than exhausting memory.
pub const MAX_STEPS: usize = 10_000_000;

/// Number of steps of `dt` in `seconds`, if at most [`MAX_STEPS`].
pub(crate) fn step_count(seconds: f64, dt: f64) -> Option<usize> {
    let n = (seconds / dt).ceil();
    (n.is_finite() && n <= MAX_STEPS as f64).then_some(n as usize)
}

/// One executed sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Pose at `t`.
    pub pose: Pose,
    /// Command applied from `t` to the next sample (after the wheel limits).
    pub v: f64,
    /// Turn rate applied from `t` (rad/s).
    pub omega: f64,
    /// Distance from the reference position at `t` (m).
    pub error: f64,
}

/// Tracks `timing` from `start` with `controller` on `robot`, steps of `dt`,
/// then `settle` seconds holding the final reference.
///
/// # Errors
/// A non-positive or non-finite `dt`, a negative or non-finite `settle`, or
/// more than [`MAX_STEPS`] steps ([`crate::Error::BadParameter`]).
pub fn simulate(
    timing: &Timing,
    controller: &dyn Controller,
    robot: &DiffDrive,
    start: Pose,
    dt: f64,
    settle: f64,
) -> Result<Vec<Sample>> {
    let dt = positive("time step", dt)?;
    if !(settle.is_finite() && settle >= 0.0) {
        return Err(crate::Error::BadParameter {
            name: "settling time",
            value: settle,
            expected: "a finite number of seconds, 0 or more",
        });
    }
    let Some(steps) = step_count(timing.duration() + settle, dt) else {
        return Err(crate::Error::BadParameter {
            name: "time step",
            value: dt,
            expected: "a step giving at most 10 million steps over the run",
        });
    };
    let mut out = Vec::with_capacity(steps + 1);
    let (mut pose, mut last) = (start, (0.0, 0.0));
    for k in 0..=steps {
        let t = k as f64 * dt;
        let r = timing.at(t);
        let e = TrackingError::of(&pose, &r.pose);
        let cmd = if k == steps {
            (0.0, 0.0)
        } else {
            robot.saturate(controller.command(&pose, &r), last, dt)
        };
        out.push(Sample {
            t,
            pose,
            v: cmd.0,
            omega: cmd.1,
            error: e.ex.hypot(e.ey),
        });
        pose = robot.integrate(pose, cmd.0, cmd.1, dt);
        last = cmd;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::{Kanayama, Klancar};
    use crate::timing::Limits;
    use oxcover_grid::Point;

    #[test]
    fn a_timed_square_is_tracked_closely() {
        let square = [
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(2.0, 2.0),
            Point::new(0.0, 2.0),
            Point::new(0.0, 0.0),
        ];
        let timing = Timing::new(&square, Limits::default()).unwrap();
        let robot = DiffDrive::default();
        for c in [
            &Kanayama::default() as &dyn Controller,
            &Klancar::default() as &dyn Controller,
        ] {
            // Starting 5 cm off to the side.
            let run = simulate(&timing, c, &robot, Pose::new(0.0, -0.05, 0.0), 0.01, 5.0).unwrap();
            let rms =
                (run.iter().map(|s| s.error * s.error).sum::<f64>() / run.len() as f64).sqrt();
            let worst = run.iter().map(|s| s.error).fold(0.0, f64::max);
            let end = run.last().unwrap();
            assert!(
                rms < 0.02 && worst < 0.06,
                "{}: rms {rms}, max {worst}",
                c.name()
            );
            assert!(
                end.pose.distance(&Pose::default()) < 0.005,
                "{}: {:?}",
                c.name(),
                end.pose
            );
            // The wheels never exceed their limits.
            for s in &run {
                let (l, r) = robot.wheel_speeds(s.v, s.omega);
                assert!(
                    l.abs() <= robot.max_wheel_speed + 1e-9
                        && r.abs() <= robot.max_wheel_speed + 1e-9
                );
            }
        }
    }

    #[test]
    fn bad_steps_are_refused() {
        let timing = Timing::new(
            &[Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
            Limits::default(),
        )
        .unwrap();
        let robot = DiffDrive::default();
        let c = Klancar::default();
        assert!(simulate(&timing, &c, &robot, Pose::default(), 0.0, 1.0).is_err());
        assert!(simulate(&timing, &c, &robot, Pose::default(), 0.01, f64::NAN).is_err());
        // Too many steps is refused, not allocated.
        assert!(simulate(&timing, &c, &robot, Pose::default(), 1e-9, 1.0).is_err());
        assert!(simulate(&timing, &c, &robot, Pose::default(), 0.01, 1e300).is_err());
    }
}
