//! The nonlinear tracking controller of Klancar, Matko & Blazic (2005),
//! "Mobile robot control on a reference path" (Siamantas 2010's Fig. 3c; after de
//! Luca, Oriolo & Vendittelli): with `k = 2ζ√(ω_r² + g v_r²)`,
//! `v = v_r cos e_θ + k e_x`, `ω = ω_r + k e_θ + g v_r sinc(e_θ) e_y`.
//! The `sinc` form keeps the command bounded and exact as `e_θ → 0`.

use super::{Controller, Reference, TrackingError};
use crate::error::{Error, Result, positive};
use crate::kinematics::{Pose, sinc};

/// The nonlinear (`sinc`) tracking controller.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Klancar {
    /// Damping ratio, in `(0, 1)`.
    pub zeta: f64,
    /// Gain `g` (1/m²).
    pub g: f64,
}

impl Default for Klancar {
    /// `ζ = 0.7`, `g = 40 /m²`: at `v_r = 0.3 m/s` on a straight line the
    /// gain `k` is about 2.7 /s.
    fn default() -> Self {
        Self { zeta: 0.7, g: 40.0 }
    }
}

impl Klancar {
    /// A controller with damping `zeta` in `(0, 1)` and gain `g > 0`.
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming the bad parameter.
    pub fn new(zeta: f64, g: f64) -> Result<Self> {
        if !(zeta > 0.0 && zeta < 1.0) {
            return Err(Error::BadParameter {
                name: "Klancar zeta",
                value: zeta,
                expected: "a damping ratio strictly between 0 and 1",
            });
        }
        Ok(Self {
            zeta,
            g: positive("Klancar g", g)?,
        })
    }
}

impl Controller for Klancar {
    fn name(&self) -> &'static str {
        "klancar"
    }

    fn command(&self, pose: &Pose, r: &Reference) -> (f64, f64) {
        let e = TrackingError::of(pose, &r.pose);
        let k = 2.0 * self.zeta * (r.omega * r.omega + self.g * r.v * r.v).sqrt();
        (
            r.v * e.etheta.cos() + k * e.ex,
            r.omega + k * e.etheta + self.g * r.v * sinc(e.etheta) * e.ey,
        )
    }
}
