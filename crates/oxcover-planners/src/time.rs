//! The time a robot needs to drive a path, the objective planners optimise
//! (the contract's `est_time_s`): `length / v + rotation / w`, with v the
//! linear speed and w the turning rate (defaults 0.3 m/s and 0.52 rad/s).
//!
//! Planners score their own choices (sweep angle, order of rooms and cells,
//! lane direction) with the same model, so a plan that is shorter but turns
//! more is not preferred when it takes longer.

use oxcover_grid::Point;
use oxcover_grid::math::wrap_angle;
use serde::Serialize;

use crate::error::Result;

/// Speeds for estimated time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TimeModel {
    /// Linear speed v in m/s. Default 0.3 (contract).
    pub linear_speed: f64,
    /// Turning rate w in rad/s. Default 0.52 (contract).
    pub angular_speed: f64,
}

impl Default for TimeModel {
    fn default() -> Self {
        Self {
            linear_speed: 0.3,
            angular_speed: 0.52,
        }
    }
}

impl TimeModel {
    /// A model with speed `v` (m/s) and turning rate `w` (rad/s).
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming `--speed` or `--turn-rate` when a value
    /// is not finite and positive.
    pub fn new(v: f64, w: f64) -> Result<Self> {
        Ok(Self {
            linear_speed: oxcover_grid::error::positive("--speed", v)?,
            angular_speed: oxcover_grid::error::positive("--turn-rate", w)?,
        })
    }

    /// Seconds for `length` metres and `rotation` radians of turning.
    #[must_use]
    pub fn time(&self, length: f64, rotation: f64) -> f64 {
        length / self.linear_speed + rotation / self.angular_speed
    }

    /// Seconds to turn by `angle` radians (its absolute value).
    #[must_use]
    pub fn turn(&self, angle: f64) -> f64 {
        angle.abs() / self.angular_speed
    }

    /// Seconds to drive the polyline `points` (any unit of length the speed
    /// uses), turning on the spot at each vertex. Unlike the contract's
    /// metric no short segment is merged: this is for planners' choices.
    #[must_use]
    pub fn polyline(&self, points: &[Point]) -> f64 {
        let mut length = 0.0;
        let mut rotation = 0.0;
        let mut heading: Option<f64> = None;
        for w in points.windows(2) {
            let d = w[1] - w[0];
            let n = d.norm();
            if n <= 0.0 {
                continue;
            }
            length += n;
            let h = d.y.atan2(d.x);
            if let Some(prev) = heading {
                rotation += wrap_angle(h - prev).abs();
            }
            heading = Some(h);
        }
        self.time(length, rotation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_l_costs_its_length_and_a_quarter_turn() {
        let t = TimeModel::default();
        let l = [
            Point::new(0.0, 0.0),
            Point::new(3.0, 0.0),
            Point::new(3.0, 3.0),
        ];
        let expect = 6.0 / 0.3 + std::f64::consts::FRAC_PI_2 / 0.52;
        assert!((t.polyline(&l) - expect).abs() < 1e-9);
        assert!(TimeModel::new(0.0, 1.0).is_err());
        assert!(TimeModel::new(1.0, f64::NAN).is_err());
    }
}
