//! Energy of a run: a DC-motor model of each wheel plus a constant
//! electronics load, and the robot description file that holds it.
//!
//! Per wheel (rim speed `v_w`, rim acceleration `a_w`): the force at the rim
//! is `F = (m/2)·a_w + sign(v_w)·c_rr·(m/2)·g` (half the mass and half the
//! rolling resistance on each wheel; the robot's yaw inertia and the tyres'
//! scrub in turns are neglected). The wheel torque is `τ = F·r`, the motor
//! current `I = τ / (G·k_t)` (gear ratio `G`, torque constant `k_t`), and the
//! electrical power `P = max(F·v_w, 0) + I²R`: mechanical power plus copper
//! loss, with no energy recovered when braking. The electronics draw a
//! constant `P₀`. Parameters and their sources live in a RON file
//! (`fixtures/robots/floor_cleaner.ron`), read by [`RobotSpec::from_ron`].

use serde::Deserialize;

use crate::error::{Error, Result, non_negative, positive};
use crate::kinematics::DiffDrive;
use crate::simulate::Sample;

/// Standard gravity (m/s²).
const G: f64 = 9.81;

/// Parameters of the wheel-power model.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergyModel {
    /// Robot mass (kg).
    pub mass: f64,
    /// Rolling-resistance coefficient (dimensionless).
    pub rolling_resistance: f64,
    /// Motor torque constant (N·m/A, at the motor shaft).
    pub torque_constant: f64,
    /// Motor armature resistance (Ω).
    pub armature_resistance: f64,
    /// Motor turns per wheel turn.
    pub gear_ratio: f64,
    /// Constant electronics load (W).
    pub electronics_power: f64,
}

impl EnergyModel {
    /// Checks the parameters (positive; resistance to rolling and the
    /// electronics load may be 0).
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming the first bad parameter.
    pub fn validated(self) -> Result<Self> {
        Ok(Self {
            mass: positive("mass", self.mass)?,
            rolling_resistance: non_negative("rolling_resistance", self.rolling_resistance)?,
            torque_constant: positive("torque_constant", self.torque_constant)?,
            armature_resistance: non_negative("armature_resistance", self.armature_resistance)?,
            gear_ratio: positive("gear_ratio", self.gear_ratio)?,
            electronics_power: non_negative("electronics_power", self.electronics_power)?,
        })
    }

    /// Electrical power of one wheel (W) at rim speed `v` and acceleration `a`.
    fn wheel_power(&self, drive: &DiffDrive, v: f64, a: f64) -> f64 {
        let half = self.mass / 2.0;
        let roll = if v == 0.0 {
            0.0
        } else {
            v.signum() * self.rolling_resistance * half * G
        };
        let force = half * a + roll;
        let torque = force * drive.wheel_radius;
        let current = torque / (self.gear_ratio * self.torque_constant);
        (force * v).max(0.0) + current * current * self.armature_resistance
    }

    /// Electrical power (W) of both wheels and the electronics while driving
    /// `(v, ω)` with accelerations `(a, α)`.
    #[must_use]
    pub fn power(&self, drive: &DiffDrive, v: f64, omega: f64, a: f64, alpha: f64) -> f64 {
        let (vl, vr) = drive.wheel_speeds(v, omega);
        let (al, ar) = drive.wheel_speeds(a, alpha);
        self.wheel_power(drive, vl, al) + self.wheel_power(drive, vr, ar) + self.electronics_power
    }

    /// Cumulative energy (J) at each sample of a run: the power of each
    /// step's command (with the acceleration of the change into it) times
    /// the step.
    #[must_use]
    pub fn energy(&self, drive: &DiffDrive, samples: &[Sample]) -> Vec<f64> {
        let mut out = Vec::with_capacity(samples.len());
        let mut total = 0.0;
        for (k, s) in samples.iter().enumerate() {
            out.push(total);
            let Some(next) = samples.get(k + 1) else {
                break;
            };
            let dt = next.t - s.t;
            if dt <= 0.0 {
                continue;
            }
            let (a, alpha) = k.checked_sub(1).map_or((0.0, 0.0), |p| {
                ((s.v - samples[p].v) / dt, (s.omega - samples[p].omega) / dt)
            });
            total += self.power(drive, s.v, s.omega, a, alpha) * dt;
        }
        out
    }
}

/// A robot description: its drive, its energy model and how closely it
/// tracks a path.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// Kinematics and wheel limits.
    pub drive: DiffDrive,
    /// Wheel-power model.
    pub energy: EnergyModel,
    /// How far (m) the robot may stray from its path while tracking it:
    /// plans for it keep this much more clearance from walls (optional,
    /// default [`DEFAULT_TRACKING_MARGIN`]).
    #[serde(default = "default_tracking_margin")]
    pub tracking_margin: f64,
}

/// The tracking margin of a description that gives none (m): a centimetre
/// or two, as a real robot tracks its path (the bundled robot's runs on
/// the bundled maps stray 0.1-0.7 cm RMS).
pub const DEFAULT_TRACKING_MARGIN: f64 = 0.02;

fn default_tracking_margin() -> f64 {
    DEFAULT_TRACKING_MARGIN
}

impl RobotSpec {
    /// Parses and checks a RON description (see `fixtures/robots/`).
    ///
    /// # Errors
    /// [`Error::Spec`] for malformed RON or a missing field,
    /// [`Error::BadParameter`] for an out-of-range value.
    pub fn from_ron(text: &str) -> Result<Self> {
        let spec: Self = ron::from_str(text).map_err(|e| Error::Spec(e.to_string()))?;
        let d = spec.drive;
        Ok(Self {
            drive: DiffDrive::new(
                d.wheel_base,
                d.wheel_radius,
                d.max_wheel_speed,
                d.max_wheel_accel,
            )?,
            energy: spec.energy.validated()?,
            tracking_margin: if spec.tracking_margin.is_finite() && spec.tracking_margin >= 0.0 {
                spec.tracking_margin
            } else {
                return Err(Error::BadParameter {
                    name: "tracking_margin",
                    value: spec.tracking_margin,
                    expected: "a finite distance of at least 0 m",
                });
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> RobotSpec {
        let text = include_str!("../../../fixtures/robots/floor_cleaner.ron");
        RobotSpec::from_ron(text).expect("valid spec")
    }

    #[test]
    fn cruising_power_by_hand() {
        let s = spec();
        // 0.3 m/s straight: per wheel F = 0.02·1.8·9.81 = 0.35316 N,
        // F·v = 0.105948 W; τ = F·0.036 = 0.01271376 N·m,
        // I = τ/(30·0.01) = 0.0423792 A, I²R = 0.003591991 W.
        let want = 2.0 * (0.105_948 + 0.042_379_2f64.powi(2) * 2.0) + 5.0;
        let p = s.energy.power(&s.drive, 0.3, 0.0, 0.0, 0.0);
        assert!((p - want).abs() < 1e-9, "{p} vs {want}");
        // Standing still: the electronics only.
        assert!((s.energy.power(&s.drive, 0.0, 0.0, 0.0, 0.0) - 5.0).abs() < 1e-12);
        // Braking at 1 m/s² recovers nothing; the braking torque still costs
        // copper loss: F = 1.8·(−1) + 0.35316 = −1.44684 N per wheel,
        // I = F·0.036/0.3 = −0.1736208 A, I²R = 0.060288 W.
        let brake = s.energy.power(&s.drive, 0.3, 0.0, -1.0, 0.0);
        let want = 5.0 + 2.0 * 0.173_620_8f64.powi(2) * 2.0;
        assert!((brake - want).abs() < 1e-9, "{brake} vs {want}");
    }

    #[test]
    fn energy_accumulates_power_over_time() {
        let s = spec();
        let samples: Vec<Sample> = (0..=100)
            .map(|k| Sample {
                t: k as f64 * 0.1,
                pose: crate::Pose::default(),
                v: 0.3,
                omega: 0.0,
                error: 0.0,
            })
            .collect();
        let e = s.energy.energy(&s.drive, &samples);
        let p = s.energy.power(&s.drive, 0.3, 0.0, 0.0, 0.0);
        assert_eq!(e.len(), 101);
        assert!((e[100] - p * 10.0).abs() < 1e-9);
    }

    #[test]
    fn bad_descriptions_name_the_problem() {
        let text = include_str!("../../../fixtures/robots/floor_cleaner.ron");
        let e = RobotSpec::from_ron(&text.replace("mass: 3.6", "mass: -3.6")).unwrap_err();
        assert!(e.to_string().contains("mass"), "{e}");
        let e = RobotSpec::from_ron(&text.replace("gear_ratio: 30.0,", "")).unwrap_err();
        assert!(e.to_string().contains("gear_ratio"), "{e}");
        assert!(RobotSpec::from_ron("(drive: ").is_err());
    }

    #[test]
    fn the_tracking_margin_is_optional_and_checked() {
        let text = include_str!("../../../fixtures/robots/floor_cleaner.ron");
        assert_eq!(spec().tracking_margin, 0.02);
        let without = text.replace("tracking_margin: 0.02,", "");
        assert_ne!(without, text);
        let s = RobotSpec::from_ron(&without).unwrap();
        assert_eq!(s.tracking_margin, DEFAULT_TRACKING_MARGIN);
        let e =
            RobotSpec::from_ron(&text.replace("tracking_margin: 0.02", "tracking_margin: -1.0"))
                .unwrap_err();
        assert!(e.to_string().contains("tracking_margin"), "{e}");
    }
}
