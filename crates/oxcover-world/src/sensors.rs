//! Range sensors: a ring of rays cast against anything that is a [`RayCaster`]
//! (map obstacles, polygonal worlds), with optional Gaussian noise from a
//! seeded generator (same seed, same readings).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::{Error, Result, positive};
use crate::geometry::RayCaster;
use oxcover_grid::{Point, Pose};

/// One range reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reading {
    /// Measured range (m), noise included; `max_range` when nothing was hit.
    pub range: f64,
    /// The surface hit (see [`RayCaster::cast_surface`]), if any.
    pub surface: Option<usize>,
}

/// A set of range rays fixed to the robot.
#[derive(Clone, Debug)]
pub struct RangeSensor {
    /// Ray directions relative to the heading (rad, counter-clockwise).
    pub angles: Vec<f64>,
    /// Longest reading (m); rays that hit nothing read this.
    pub max_range: f64,
    /// Standard deviation of the additive noise (m).
    pub noise_sd: f64,
    rng: ChaCha8Rng,
}

impl RangeSensor {
    /// `n` rays evenly around the robot, the first straight ahead.
    ///
    /// # Errors
    /// [`Error::BadParameter`] for `n = 0`, a bad range or a negative noise.
    pub fn ring(n: usize, max_range: f64, noise_sd: f64, seed: u64) -> Result<Self> {
        if n == 0 {
            return Err(Error::BadParameter {
                name: "number of rays",
                value: "0".into(),
                expected: "at least 1",
            });
        }
        let angles = (0..n)
            .map(|k| k as f64 * std::f64::consts::TAU / n as f64)
            .collect();
        Self::with_angles(angles, max_range, noise_sd, seed)
    }

    /// Rays at the given angles.
    ///
    /// # Errors
    /// [`Error::BadParameter`] for a bad range or noise.
    pub fn with_angles(angles: Vec<f64>, max_range: f64, noise_sd: f64, seed: u64) -> Result<Self> {
        if !(noise_sd.is_finite() && noise_sd >= 0.0) {
            return Err(Error::BadParameter {
                name: "range noise",
                value: noise_sd.to_string(),
                expected: "a standard deviation in metres, 0 or more",
            });
        }
        Ok(Self {
            angles,
            max_range: positive("max range", max_range)?,
            noise_sd,
            rng: ChaCha8Rng::seed_from_u64(seed),
        })
    }

    /// One reading per ray from `pose`, clamped to `[0, max_range]`.
    pub fn scan(&mut self, obstacles: &impl RayCaster, pose: &Pose) -> Vec<f64> {
        let angles = self.angles.clone();
        angles
            .iter()
            .map(|&a| {
                self.read(obstacles, Point::new(pose.x, pose.y), pose.theta + a)
                    .range
            })
            .collect()
    }

    /// One ray from `origin` along the absolute heading `angle`: its noisy
    /// range, clamped to `[0, max_range]`, and the surface it hit (`None`
    /// when nothing lies within `max_range`).
    pub fn read(&mut self, caster: &impl RayCaster, origin: Point, angle: f64) -> Reading {
        let hit = caster.cast_surface(origin, angle, self.max_range);
        let range = hit.map_or(self.max_range, |h| h.0);
        Reading {
            range: (range + self.noise()).clamp(0.0, self.max_range),
            surface: hit.map(|h| h.1),
        }
    }

    /// A normal sample of the noise (Box–Muller).
    fn noise(&mut self) -> f64 {
        if self.noise_sd == 0.0 {
            return 0.0;
        }
        let u1: f64 = self.rng.random::<f64>().max(f64::MIN_POSITIVE);
        let u2: f64 = self.rng.random::<f64>();
        self.noise_sd * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Obstacles;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn a_ring_reads_the_room_and_noise_is_seeded() {
        let (map, _) = parse_ascii(&vec![".".repeat(8); 6].join("\n")).unwrap();
        let obs = Obstacles::from_map(&map);
        let pose = Pose::new(2.0, 3.0, 0.0);
        let mut s = RangeSensor::ring(4, 10.0, 0.0, 0).unwrap();
        let r = s.scan(&obs, &pose);
        // Ahead 6 m to x = 8, left 3 m, behind 2 m, right 3 m.
        for (got, want) in r.iter().zip([6.0, 3.0, 2.0, 3.0]) {
            assert!((got - want).abs() < 1e-4, "{r:?}");
        }
        let mut a = RangeSensor::ring(4, 10.0, 0.05, 7).unwrap();
        let mut b = RangeSensor::ring(4, 10.0, 0.05, 7).unwrap();
        let (ra, rb) = (a.scan(&obs, &pose), b.scan(&obs, &pose));
        assert_eq!(ra, rb);
        assert!(ra.iter().zip(&r).any(|(x, y)| (x - y).abs() > 1e-6));
        assert!(RangeSensor::ring(0, 1.0, 0.0, 0).is_err());
        assert!(RangeSensor::ring(4, 1.0, -1.0, 0).is_err());
    }
}
