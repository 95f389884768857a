//! Wall following: a PID controller on the lateral distance to a wall, at
//! constant forward speed.
//!
//! A single sideways ray reads `d / cos α` when the robot is at angle `α` to
//! the wall, and turning changes that reading, which feeds back into the
//! turn. So two rays are used (the usual two-ray wall follower): one
//! sideways (`b`, at ∓90°) and one 45° further forward (`a`). They give the
//! angle to the wall `α = atan((a cos 45° − b) / (a sin 45°))` (positive when
//! heading away from it) and the true distance `D = b cos α`. The PID acts on
//! the distance a look-ahead `L` ahead, `e = D + L sin α − desired`; for small
//! angles `D̈ + K_p L Ḋ + K_p v D = …`, so `L` supplies the damping.

use crate::error::{Result, positive};

/// Which side the wall is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Wall on the left.
    Left,
    /// Wall on the right.
    Right,
}

impl Side {
    /// Directions of the sideways and the forward-diagonal ray relative to
    /// the heading (rad).
    #[must_use]
    pub fn ray_angles(self) -> [f64; 2] {
        use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
        match self {
            Self::Left => [FRAC_PI_2, FRAC_PI_4],
            Self::Right => [-FRAC_PI_2, -FRAC_PI_4],
        }
    }
}

/// A PID wall follower.
#[derive(Clone, Debug, PartialEq)]
pub struct WallFollower {
    /// Wall side.
    pub side: Side,
    /// Distance to keep (m).
    pub desired: f64,
    /// Forward speed (m/s).
    pub speed: f64,
    /// Gains `(K_p, K_i, K_d)` on the look-ahead distance error (rad/s per m,
    /// per m·s, per m/s).
    pub gains: (f64, f64, f64),
    /// Look-ahead `L` (m).
    pub look_ahead: f64,
    /// Largest commanded turn rate (rad/s).
    pub max_turn_rate: f64,
    integral: f64,
    last_error: Option<f64>,
}

impl WallFollower {
    /// A follower keeping `desired` metres at `speed`: `K_p = 1`,
    /// `K_i = 0.02`, `K_d = 0`, `L = 0.5 m`, turn rate at most 1 rad/s (at
    /// 0.2 m/s the small-angle damping ratio is about 0.56).
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] for a bad distance or speed.
    pub fn new(side: Side, desired: f64, speed: f64) -> Result<Self> {
        Ok(Self {
            side,
            desired: positive("wall distance", desired)?,
            speed: positive("wall-following speed", speed)?,
            gains: (1.0, 0.02, 0.0),
            look_ahead: 0.5,
            max_turn_rate: 1.0,
            integral: 0.0,
            last_error: None,
        })
    }

    /// The wall's angle (rad, positive heading away) and distance (m) from
    /// the sideways reading `b` and the diagonal reading `a`.
    #[must_use]
    pub fn wall(b: f64, a: f64) -> (f64, f64) {
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let alpha = ((a * c - b) / (a * c)).atan();
        (alpha, b * alpha.cos())
    }

    /// The command `(v, ω)` for readings `[sideways, diagonal]` (rays at
    /// [`Side::ray_angles`]) after `dt` seconds.
    pub fn command(&mut self, ranges: [f64; 2], dt: f64) -> (f64, f64) {
        let (alpha, d) = Self::wall(ranges[0], ranges[1]);
        let e = d + self.look_ahead * alpha.sin() - self.desired;
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        self.integral = (self.integral + e * dt).clamp(-1.0, 1.0);
        let de = match (self.last_error, dt > 0.0) {
            (Some(p), true) => (e - p) / dt,
            _ => 0.0,
        };
        self.last_error = Some(e);
        let (kp, ki, kd) = self.gains;
        let u =
            (kp * e + ki * self.integral + kd * de).clamp(-self.max_turn_rate, self.max_turn_rate);
        // Too far from a right-hand wall: turn right (negative ω).
        let omega = match self.side {
            Side::Right => -u,
            Side::Left => u,
        };
        (self.speed, omega)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Obstacles, RangeSensor};
    use oxcover_grid::Pose;
    use oxcover_grid::io::parse_ascii;
    use oxcover_robot::DiffDrive;

    #[test]
    fn two_rays_give_the_wall_angle_and_distance() {
        // 0.5 m from the wall, heading 10° away from it.
        let (y, t) = (0.5f64, 10f64.to_radians());
        let b = y / t.cos();
        let a = y / (std::f64::consts::FRAC_PI_4 - t).sin();
        let (alpha, d) = WallFollower::wall(b, a);
        assert!((alpha - t).abs() < 1e-12 && (d - y).abs() < 1e-12);
    }

    fn run(side: Side, start: Pose) -> Pose {
        // A 30 m × 4 m corridor (walls y = 0 and y = 4).
        let (map, _) = parse_ascii(&vec![".".repeat(30); 4].join("\n")).unwrap();
        let obs = Obstacles::from_map(&map);
        let robot = DiffDrive::default();
        let mut rays = RangeSensor::with_angles(side.ray_angles().to_vec(), 3.0, 0.0, 0).unwrap();
        let mut pid = WallFollower::new(side, 0.5, 0.2).unwrap();
        let (mut pose, mut last, dt) = (start, (0.0, 0.0), 0.05);
        for _ in 0..(60.0 / dt) as usize {
            let r = rays.scan(&obs, &pose);
            let cmd = robot.saturate(pid.command([r[0], r[1]], dt), last, dt);
            pose = robot.integrate(pose, cmd.0, cmd.1, dt);
            last = cmd;
        }
        pose
    }

    #[test]
    fn settles_at_the_desired_distance_from_a_wall() {
        let p = run(Side::Right, Pose::new(1.0, 0.9, 0.2));
        assert!(
            (p.y - 0.5).abs() < 0.02 && p.theta.abs() < 0.05 && p.x > 10.0,
            "{p:?}"
        );
        let p = run(Side::Left, Pose::new(1.0, 3.2, -0.2));
        assert!(
            (p.y - 3.5).abs() < 0.02 && p.theta.abs() < 0.05 && p.x > 10.0,
            "{p:?}"
        );
    }
}
