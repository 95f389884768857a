//! Kanayama, Kimura, Miyazaki & Noguchi (1990), "A stable tracking control
//! method for an autonomous mobile robot":
//! `v = v_r cos e_θ + K_x e_x`, `ω = ω_r + v_r (K_y e_y + K_θ sin e_θ)`.

use super::{Controller, Reference, TrackingError};
use crate::error::{Result, positive};
use crate::kinematics::Pose;

/// Kanayama's tracking controller.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kanayama {
    /// Gain on the along-track error (1/s).
    pub kx: f64,
    /// Gain on the cross-track error (1/m²).
    pub ky: f64,
    /// Gain on the heading error (1/m).
    pub ktheta: f64,
}

impl Default for Kanayama {
    /// `K_x = 1`, `K_y = 4`, `K_θ = 4`: the linearised cross-track dynamics
    /// `ë + v_r K_θ ė + v_r² K_y e = 0` are critically damped (`K_y = K_θ²/4`)
    /// at any reference speed.
    fn default() -> Self {
        Self {
            kx: 1.0,
            ky: 4.0,
            ktheta: 4.0,
        }
    }
}

impl Kanayama {
    /// A controller with the given gains (finite, positive).
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming the first bad gain.
    pub fn new(kx: f64, ky: f64, ktheta: f64) -> Result<Self> {
        Ok(Self {
            kx: positive("Kanayama K_x", kx)?,
            ky: positive("Kanayama K_y", ky)?,
            ktheta: positive("Kanayama K_theta", ktheta)?,
        })
    }
}

impl Controller for Kanayama {
    fn name(&self) -> &'static str {
        "kanayama"
    }

    fn command(&self, pose: &Pose, r: &Reference) -> (f64, f64) {
        let e = TrackingError::of(pose, &r.pose);
        (
            r.v * e.etheta.cos() + self.kx * e.ex,
            r.omega + r.v * (self.ky * e.ey + self.ktheta * e.etheta.sin()),
        )
    }
}
