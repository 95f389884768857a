//! Time parametrisation of a metre polyline under speed, acceleration and
//! turn-rate limits: the reference a tracking controller follows.
//!
//! Each interior vertex turns the heading by `φ`. A sharp corner
//! (`φ > corner_angle`) is a stop: the robot brakes to rest, turns in place
//! (a trapezoidal turn-rate profile under `alpha_max` and `omega_max`), and
//! drives on. A gentle vertex belongs to a smooth
//! curve: its curvature is estimated as `κ = φ / ((l₀ + l₁)/2)` from the two
//! segment lengths, and the speed there is capped at `ω_max / κ`, so densely
//! sampled curves are driven at the speed their curvature allows and sharp
//! turns are slowed to a stop; a segment between two curve vertices keeps the
//! lower of their speeds along its whole length, and no more than
//! `sqrt(alpha_max · l / |Δκ|)` where the curvature changes by `Δκ` over it
//! (the turn rate must follow). Speeds at the vertices then obey the
//! acceleration limit by a forward and a backward pass (`v₁² ≤ v₀² + 2 a l`),
//! and every segment is driven with a trapezoidal (or triangular) speed
//! profile between its end speeds. Through a gentle vertex the reference
//! heading eases from one segment's heading to the next over 0.1 m (half a
//! segment when shorter) on either side, with the matching feed-forward turn
//! rate: a densely sampled curve is tracked as a curve, not as a chain of
//! heading jumps.

use crate::control::Reference;
use crate::error::{Result, positive};
use crate::kinematics::Pose;
use oxcover_grid::Point;
use oxcover_grid::math::wrap_angle;

/// Distance (m) over which the reference heading eases through a gentle
/// vertex on either side (half a segment when shorter).
const BEND_LENGTH: f64 = 0.1;

/// Limits for [`Timing::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Top linear speed (m/s).
    pub v_max: f64,
    /// Linear acceleration and deceleration (m/s²).
    pub a_max: f64,
    /// Top turn rate (rad/s), in place and along curves.
    pub omega_max: f64,
    /// Angular acceleration of turns in place (rad/s²).
    pub alpha_max: f64,
    /// Heading changes above this (rad) are corners: stop and turn in place.
    pub corner_angle: f64,
}

impl Default for Limits {
    /// The contract's estimate speeds (0.3 m/s, 0.52 rad/s), 0.5 m/s²,
    /// 3 rad/s², and corners above 20°.
    fn default() -> Self {
        Self {
            v_max: 0.3,
            a_max: 0.5,
            omega_max: 0.52,
            alpha_max: 3.0,
            corner_angle: 20f64.to_radians(),
        }
    }
}

impl Limits {
    /// Checks every limit is finite and positive.
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming the first bad limit.
    pub fn validated(self) -> Result<Self> {
        Ok(Self {
            v_max: positive("v_max", self.v_max)?,
            a_max: positive("a_max", self.a_max)?,
            omega_max: positive("omega_max", self.omega_max)?,
            alpha_max: positive("alpha_max", self.alpha_max)?,
            corner_angle: positive("corner_angle", self.corner_angle)?,
        })
    }
}

/// One piece of the timed path.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Piece {
    /// A straight segment from `from` (heading `from.theta`) of `length`,
    /// entered at `v0`, left at `v1`, cruising at most at `peak`; the
    /// reference heading goes from `from.theta + bend.0` to
    /// `from.theta + bend.1` along it (half of each gentle vertex's turn on
    /// either side, so a sampled curve has a continuous heading and a
    /// feed-forward turn rate).
    Drive {
        from: Pose,
        bend: (f64, f64),
        length: f64,
        v0: f64,
        v1: f64,
        peak: f64,
        duration: f64,
    },
    /// A turn in place at `at`, by `angle` (signed), trapezoidal in rate.
    Turn { at: Pose, angle: f64, duration: f64 },
}

impl Piece {
    fn duration(&self) -> f64 {
        match *self {
            Self::Drive { duration, .. } | Self::Turn { duration, .. } => duration,
        }
    }
}

/// Top turn rate reached turning in place by `phi` (a triangle when short).
fn turn_peak(phi: f64, l: &Limits) -> f64 {
    (phi * l.alpha_max).sqrt().min(l.omega_max)
}

/// Duration of a turn in place by `phi ≥ 0`: a trapezoidal rate profile.
fn turn_duration(phi: f64, l: &Limits) -> f64 {
    let w = turn_peak(phi, l);
    if w <= 0.0 {
        return 0.0;
    }
    phi / w + w / l.alpha_max
}

/// Angle turned and turn rate at time `t` of a turn by `phi ≥ 0` lasting `duration`.
fn turn_profile(phi: f64, t: f64, duration: f64, l: &Limits) -> (f64, f64) {
    let w = turn_peak(phi, l);
    let ramp = w / l.alpha_max;
    let t = t.clamp(0.0, duration);
    if t < ramp {
        (l.alpha_max * t * t / 2.0, l.alpha_max * t)
    } else if t <= duration - ramp {
        (w * ramp / 2.0 + w * (t - ramp), w)
    } else {
        let r = duration - t;
        (phi - l.alpha_max * r * r / 2.0, l.alpha_max * r)
    }
}

/// A polyline with a time law: the reference at any time.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    pieces: Vec<Piece>,
    /// Start time of each piece.
    starts: Vec<f64>,
    limits: Limits,
}

impl Timing {
    /// Times the polyline `points` (`(x, y)` in metres; repeated points are
    /// dropped). The robot starts at rest facing the first segment and ends at
    /// rest.
    ///
    /// # Errors
    /// Bad limits ([`crate::Error::BadParameter`]).
    pub fn new(points: &[Point], limits: Limits) -> Result<Self> {
        let points: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.y)).collect();
        let limits = limits.validated()?;
        let mut pts: Vec<(f64, f64)> = Vec::with_capacity(points.len());
        for &p in &points {
            if p.0.is_finite()
                && p.1.is_finite()
                && pts
                    .last()
                    .is_none_or(|q: &(f64, f64)| (p.0 - q.0).hypot(p.1 - q.1) > 1e-9)
            {
                pts.push(p);
            }
        }
        let n = pts.len();
        let seg = |i: usize| {
            let (a, b) = (pts[i], pts[i + 1]);
            ((b.0 - a.0).hypot(b.1 - a.1), (b.1 - a.1).atan2(b.0 - a.0))
        };
        let segs: Vec<(f64, f64)> = (0..n.saturating_sub(1)).map(seg).collect();
        // Speed caps at the vertices (0 at both ends and at corners).
        let mut cap = vec![0.0; segs.len() + 1];
        let mut turn = vec![0.0; segs.len() + 1];
        for i in 1..segs.len() {
            let phi = wrap_angle(segs[i].1 - segs[i - 1].1);
            turn[i] = phi;
            cap[i] = if phi.abs() > limits.corner_angle {
                0.0
            } else if phi.abs() < 1e-12 {
                limits.v_max
            } else {
                let kappa = phi.abs() / ((segs[i - 1].0 + segs[i].0) / 2.0);
                (limits.omega_max / kappa).min(limits.v_max)
            };
        }
        // A segment between two curve vertices is a chord of the curve: its
        // whole length keeps the lower of their curvature speeds.
        let curve = |i: usize| {
            if i == 0 || i == segs.len() || cap[i] == 0.0 {
                limits.v_max
            } else {
                cap[i]
            }
        };
        // Signed curvature at gentle vertices (0 at corners and ends); along a
        // segment the turn rate changes by `v² Δκ / l`, so the speed there
        // is capped at `sqrt(alpha_max · l / |Δκ|)` (S-bends and curvature
        // jumps are driven slowly enough for the turn rate to follow).
        let kappa = |i: usize| {
            if i == 0 || i == segs.len() || turn[i].abs() > limits.corner_angle {
                0.0
            } else {
                turn[i] / ((segs[i - 1].0 + segs[i].0) / 2.0)
            }
        };
        let seg_cap: Vec<f64> = (0..segs.len())
            .map(|i| {
                let dk = (kappa(i + 1) - kappa(i)).abs();
                let jerk = if dk > 1e-12 {
                    (limits.alpha_max * segs[i].0 / dk).sqrt()
                } else {
                    f64::INFINITY
                };
                curve(i).min(curve(i + 1)).min(jerk)
            })
            .collect();
        for i in 0..segs.len() {
            cap[i] = cap[i].min(seg_cap[i]);
            cap[i + 1] = cap[i + 1].min(seg_cap[i]);
        }
        // Acceleration: forward, then backward.
        for i in 0..segs.len() {
            cap[i + 1] = cap[i + 1].min((cap[i] * cap[i] + 2.0 * limits.a_max * segs[i].0).sqrt());
        }
        for i in (0..segs.len()).rev() {
            cap[i] = cap[i].min((cap[i + 1] * cap[i + 1] + 2.0 * limits.a_max * segs[i].0).sqrt());
        }
        let mut pieces = Vec::new();
        for (i, &(length, heading)) in segs.iter().enumerate() {
            let from = Pose::new(pts[i].0, pts[i].1, heading);
            let gentle = |k: usize| {
                if k > 0 && k < segs.len() && turn[k].abs() <= limits.corner_angle {
                    turn[k] / 2.0
                } else {
                    0.0
                }
            };
            let bend = (-gentle(i), gentle(i + 1));
            if i > 0 && cap[i] == 0.0 && turn[i] != 0.0 {
                pieces.push(Piece::Turn {
                    at: Pose::new(pts[i].0, pts[i].1, segs[i - 1].1),
                    angle: turn[i],
                    duration: turn_duration(turn[i].abs(), &limits),
                });
            }
            let (v0, v1, a) = (cap[i], cap[i + 1], limits.a_max);
            // Highest speed reachable between the ends within the length.
            let peak = ((2.0 * a * length + v0 * v0 + v1 * v1) / 2.0)
                .sqrt()
                .min(seg_cap[i])
                .max(v0.max(v1));
            let accel = (peak - v0) / a;
            let decel = (peak - v1) / a;
            let cruise = (length
                - (peak * peak - v0 * v0) / (2.0 * a)
                - (peak * peak - v1 * v1) / (2.0 * a))
                .max(0.0)
                / peak;
            pieces.push(Piece::Drive {
                from,
                bend,
                length,
                v0,
                v1,
                peak,
                duration: accel + cruise + decel,
            });
        }
        let mut starts = Vec::with_capacity(pieces.len());
        let mut t = 0.0;
        for p in &pieces {
            starts.push(t);
            t += p.duration();
        }
        Ok(Self {
            pieces,
            starts,
            limits,
        })
    }

    /// Total duration (s).
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.pieces
            .last()
            .zip(self.starts.last())
            .map_or(0.0, |(p, s)| s + p.duration())
    }

    /// The limits used.
    #[must_use]
    pub fn limits(&self) -> Limits {
        self.limits
    }

    /// The reference at time `t` (clamped to `[0, duration]`).
    #[must_use]
    pub fn at(&self, t: f64) -> Reference {
        let Some(last) = self.pieces.last() else {
            return Reference::default();
        };
        let t = if t.is_finite() { t.max(0.0) } else { 0.0 };
        let k = self.starts.partition_point(|&s| s <= t).saturating_sub(1);
        let piece = self.pieces.get(k).unwrap_or(last);
        let local = (t - self.starts[k]).min(piece.duration());
        match *piece {
            Piece::Turn {
                at,
                angle,
                duration,
            } => {
                let (turned, rate) = turn_profile(angle.abs(), local, duration, &self.limits);
                Reference {
                    pose: Pose::new(at.x, at.y, wrap_angle(at.theta + angle.signum() * turned)),
                    v: 0.0,
                    omega: angle.signum() * rate,
                }
            }
            Piece::Drive {
                from,
                bend,
                length,
                v0,
                v1,
                peak,
                duration,
            } => {
                let a = self.limits.a_max;
                let ta = (peak - v0) / a;
                let td = (peak - v1) / a;
                let tc = (duration - ta - td).max(0.0);
                let (s, v) = if local <= ta {
                    (v0 * local + a * local * local / 2.0, v0 + a * local)
                } else if local <= ta + tc {
                    let sa = v0 * ta + a * ta * ta / 2.0;
                    (sa + peak * (local - ta), peak)
                } else {
                    let r = (duration - local).max(0.0);
                    (length - (v1 * r + a * r * r / 2.0), v1 + a * r)
                };
                let s = s.clamp(0.0, length);
                let (sin, cos) = from.theta.sin_cos();
                // Heading offset: `bend.0` at the start easing to 0 over
                // `d`, 0 easing to `bend.1` over the last `d`.
                let d = (length / 2.0).min(BEND_LENGTH);
                let (mut off, mut rate) = (0.0, 0.0);
                if d > 0.0 {
                    if s < d {
                        off += bend.0 * (1.0 - s / d);
                        rate -= bend.0 / d;
                    }
                    if length - s < d {
                        off += bend.1 * (1.0 - (length - s) / d);
                        rate += bend.1 / d;
                    }
                }
                Reference {
                    pose: Pose::new(
                        from.x + s * cos,
                        from.y + s * sin,
                        wrap_angle(from.theta + off),
                    ),
                    v,
                    omega: v * rate,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn a_straight_line_in_closed_form() {
        let l = Limits::default();
        // 3 m at 0.3 m/s with 0.5 m/s²: accelerate 0.6 s over 0.09 m, cruise,
        // brake 0.6 s: total 3/0.3 + 0.3/0.5 = 10.6 s.
        let t = Timing::new(&[Point::new(0.0, 0.0), Point::new(3.0, 0.0)], l).unwrap();
        assert!((t.duration() - 10.6).abs() < 1e-9, "{}", t.duration());
        let mid = t.at(5.3);
        assert!((mid.pose.x - 1.5).abs() < 1e-9 && (mid.v - 0.3).abs() < 1e-12);
        assert_eq!(t.at(0.0).v, 0.0);
        assert!((t.at(100.0).pose.x - 3.0).abs() < 1e-12 && t.at(100.0).v == 0.0);
        // Too short to reach top speed: a triangle, 2·sqrt(l/a).
        let t = Timing::new(&[Point::new(0.0, 0.0), Point::new(0.02, 0.0)], l).unwrap();
        assert!((t.duration() - 2.0 * (0.02f64 / 0.5).sqrt()).abs() < 1e-9);
    }

    #[test]
    fn corners_stop_and_turn_in_place() {
        let l = Limits::default();
        let square = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
            Point::new(0.0, 0.0),
        ];
        let t = Timing::new(&square, l).unwrap();
        let side = 1.0 / 0.3 + 0.3 / 0.5;
        // Each turn: π/2 at 0.52 rad/s plus one ramp of 0.52/3 s.
        let turn = FRAC_PI_2 / 0.52 + 0.52 / 3.0;
        let want = 4.0 * side + 3.0 * turn;
        assert!(
            (t.duration() - want).abs() < 1e-9,
            "{} vs {want}",
            t.duration()
        );
        // Halfway through the first turn: at the corner, at rest, turning.
        let r = t.at(side + turn / 2.0);
        assert!((r.pose.x - 1.0).abs() < 1e-12 && r.pose.y.abs() < 1e-12);
        assert!(r.v == 0.0 && (r.omega - 0.52).abs() < 1e-12);
        assert!((r.pose.theta - PI / 4.0).abs() < 1e-9);
    }

    #[test]
    fn turns_ramp_their_rate_within_alpha() {
        let l = Limits {
            omega_max: 1.5,
            ..Limits::default()
        };
        // A half turn: ramps of 0.5 s at 3 rad/s², then 1.5 rad/s.
        let t = Timing::new(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(0.0, 0.0),
            ],
            l,
        )
        .unwrap();
        let side = 1.0 / 0.3 + 0.3 / 0.5;
        let dur = PI / 1.5 + 0.5;
        assert!((t.duration() - (2.0 * side + dur)).abs() < 1e-9);
        let n = 1000;
        let mut prev = t.at(side);
        for k in 1..=n {
            let r = t.at(side + dur * k as f64 / n as f64);
            let dt = dur / n as f64;
            assert!((r.omega - prev.omega).abs() <= 3.0 * dt + 1e-9);
            assert!(r.omega <= 1.5 + 1e-12 && r.v == 0.0);
            prev = r;
        }
        assert!((t.at(side + dur).pose.theta.abs() - PI).abs() < 1e-9);
        // A small corner never reaches the top rate: a triangle of 2·sqrt(φ/α).
        assert!((turn_duration(0.3, &l) - 2.0 * (0.3f64 / 3.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn smooth_curves_are_driven_at_the_speed_their_curvature_allows() {
        // A circle of radius 0.25 m in 200 steps: ω_max·R = 0.13 m/s < v_max.
        let pts: Vec<Point> = (0..=200)
            .map(|k| {
                let a = k as f64 / 200.0 * 2.0 * PI;
                Point::new(0.25 * a.sin(), 0.25 - 0.25 * a.cos())
            })
            .collect();
        let t = Timing::new(&pts, Limits::default()).unwrap();
        let mut top: f64 = 0.0;
        let n = 2000;
        for k in 0..=n {
            let r = t.at(t.duration() * k as f64 / n as f64);
            assert!(r.v <= 0.52 * 0.25 * 1.001 && r.v >= 0.0, "{}", r.v);
            top = top.max(r.v);
        }
        // No stop inside: it reaches the curvature speed.
        assert!(top > 0.52 * 0.25 * 0.99, "{top}");
        // The heading turns continuously, with the curve's turn rate v/R as
        // feed-forward (away from the ends).
        let (mut prev, n) = (t.at(1.0), 4000);
        for k in 1..=n {
            let time = 1.0 + (t.duration() - 2.0) * k as f64 / n as f64;
            let r = t.at(time);
            assert!(wrap_angle(r.pose.theta - prev.pose.theta).abs() < 0.02);
            if r.v > 0.1 {
                assert!(
                    (r.omega - r.v / 0.25).abs() < 0.01 * r.v / 0.25 + 1e-3,
                    "{r:?}"
                );
            }
            prev = r;
        }
    }

    #[test]
    fn positions_are_continuous_and_limits_hold() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.1),
            Point::new(1.2, 0.9),
            Point::new(0.4, 1.3),
            Point::new(0.5, 1.31),
            Point::new(2.0, 2.0),
        ];
        let t = Timing::new(&pts, Limits::default()).unwrap();
        let n = 5000;
        let dt = t.duration() / n as f64;
        let mut prev = t.at(0.0);
        for k in 1..=n {
            let r = t.at(k as f64 * dt);
            let step = r.pose.distance(&prev.pose);
            assert!(step <= 0.3 * dt + 1e-9, "jump of {step} at {k}");
            assert!(r.v <= 0.3 + 1e-12 && (r.v - prev.v).abs() <= 0.5 * dt + 1e-9);
            prev = r;
        }
        assert!(prev.pose.distance(&Pose::new(2.0, 2.0, 0.0)) < 1e-9);
        assert!(
            Timing::new(
                &pts,
                Limits {
                    a_max: f64::NAN,
                    ..Limits::default()
                }
            )
            .is_err()
        );
        assert_eq!(Timing::new(&[], Limits::default()).unwrap().duration(), 0.0);
    }
}
