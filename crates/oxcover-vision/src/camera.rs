//! The camera model of Pavlíček 2002 (§2): radial distortion about `(u_c, v_c)`,
//! the projection of image points onto the floor, and the rotation into the
//! world frame.
//!
//! **Distortion.** The paper corrects a raw pixel `(u, v)` by
//!
//! ```text
//! dist = (u − u_c)² + (v − v_c)²
//! u'   = (u − u_c)(1 + p₁ dist + p₂ dist² + p₃ dist³)
//! v'   = (v − v_c)(1 + p₁ dist + p₂ dist² + p₃ dist³)
//! ```
//!
//! so `(u', v')` are corrected coordinates about the distortion centre.
//! [`Distortion::undistort`] is this formula; [`Distortion::distort`] its
//! inverse, found by Newton's method on the radius (the factor is radial).
//!
//! **Floor projection.** In the robot frame, with `x₀` to the camera's right
//! and `y₀` ahead (the paper's Fig. 2),
//!
//! ```text
//! x₀ = −(u' − Δu) X / (v' − Δv) + x_cam
//! y₀ = −Y / (v' − Δv) + y_cam
//! ```
//!
//! For a pinhole camera of focal length `f` (pixels) at height `H` with a
//! level optical axis, `Δv` is the horizon row, `X = −H` and `Y = −f H`
//! (image rows grow downwards): [`Projection::pinhole`] builds that case.
//!
//! **World frame.** `x = x_rob + x₀ cos(α + ω) − y₀ sin(α + ω)`,
//! `y = y_rob + x₀ sin(α + ω) + y₀ cos(α + ω)`; with the robot's heading
//! `ω` measured from the map's x axis and a camera looking along it,
//! `α = −π/2`.

use oxcover_grid::{Point, Pose};
use serde::{Deserialize, Serialize};

/// Radial distortion about `(u_c, v_c)` (pixels), coefficients `p₁..p₃`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Distortion {
    /// Distortion centre, column (px).
    pub uc: f64,
    /// Distortion centre, row (px).
    pub vc: f64,
    /// `p₁, p₂, p₃` (px⁻², px⁻⁴, px⁻⁶).
    pub p: [f64; 3],
}

impl Distortion {
    /// The radial factor `1 + p₁ d + p₂ d² + p₃ d³` at `d = r²`.
    pub(crate) fn factor(&self, d: f64) -> f64 {
        1.0 + d * (self.p[0] + d * (self.p[1] + d * self.p[2]))
    }

    /// Corrected coordinates `(u', v')` (about the centre) of a raw pixel.
    #[must_use]
    pub fn undistort(&self, u: f64, v: f64) -> Point {
        let (du, dv) = (u - self.uc, v - self.vc);
        let k = self.factor(du * du + dv * dv);
        Point::new(du * k, dv * k)
    }

    /// The raw pixel whose corrected coordinates are `(u', v')`: the
    /// inverse of [`Distortion::undistort`], by Newton's method on the
    /// radius; `None` where the correction is not invertible (its radial
    /// map stops growing before reaching the radius asked for).
    #[must_use]
    pub fn distort(&self, up: f64, vp: f64) -> Option<Point> {
        let target = up.hypot(vp);
        if target == 0.0 {
            return Some(Point::new(self.uc, self.vc));
        }
        // g(r) = r·factor(r²) − target, increasing where the map is invertible.
        let g = |r: f64| r * self.factor(r * r) - target;
        let dg = |r: f64| {
            let d = r * r;
            1.0 + d * (3.0 * self.p[0] + d * (5.0 * self.p[1] + d * 7.0 * self.p[2]))
        };
        let mut r = target;
        for _ in 0..100 {
            let slope = dg(r);
            if slope.is_nan() || slope <= 0.0 {
                return None;
            }
            let step = g(r) / slope;
            r -= step;
            if !(r.is_finite() && r >= 0.0) {
                return None;
            }
            if step.abs() < 1e-13 * target.max(1.0) {
                break;
            }
        }
        (g(r).abs() < 1e-9 * target.max(1.0)).then(|| {
            let s = r / target;
            Point::new(self.uc + up * s, self.vc + vp * s)
        })
    }
}

/// The floor projection's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Projection {
    /// Camera offset from the robot centre, to the right (m).
    pub x_cam: f64,
    /// Camera offset from the robot centre, ahead (m).
    pub y_cam: f64,
    /// `Δu` (px, about the distortion centre).
    pub du: f64,
    /// `Δv`: the horizon row (px, about the distortion centre).
    pub dv: f64,
    /// `X` (m).
    pub big_x: f64,
    /// `Y` (m·px).
    pub big_y: f64,
    /// `α`: camera axis against the robot's (rad).
    pub alpha: f64,
}

impl Projection {
    /// A level pinhole camera of focal length `f` (px) at height `h` (m),
    /// optical axis at `(du, dv)` about the distortion centre, mounted at
    /// `(x_cam, y_cam)` and looking along the robot's heading.
    #[must_use]
    pub fn pinhole(f: f64, h: f64, du: f64, dv: f64, x_cam: f64, y_cam: f64) -> Self {
        Self {
            x_cam,
            y_cam,
            du,
            dv,
            big_x: -h,
            big_y: -f * h,
            alpha: -std::f64::consts::FRAC_PI_2,
        }
    }

    /// The floor point `(x₀, y₀)` (robot frame) seen at corrected `(u', v')`,
    /// or `None` on or above the horizon (`v' ≤ Δv` for a camera whose `Y`
    /// is negative, the usual case).
    #[must_use]
    pub fn floor(&self, up: f64, vp: f64) -> Option<Point> {
        let dv = vp - self.dv;
        let ahead = -self.big_y / dv;
        (dv.abs() > 1e-12 && ahead * self.big_y.signum() < 0.0).then(|| {
            Point::new(
                -(up - self.du) * self.big_x / dv + self.x_cam,
                ahead + self.y_cam,
            )
        })
    }

    /// The corrected coordinates `(u', v')` at which the floor point
    /// `(x₀, y₀)` (robot frame) is seen; `None` behind the camera.
    #[must_use]
    pub fn image(&self, x0: f64, y0: f64) -> Option<Point> {
        let ahead = y0 - self.y_cam;
        (ahead * self.big_y.signum() < 0.0).then(|| {
            let dv = -self.big_y / ahead;
            Point::new(self.du - (x0 - self.x_cam) * dv / self.big_x, self.dv + dv)
        })
    }

    /// The world point of the robot-frame point `(x₀, y₀)` for a robot at
    /// `(x, y)` heading `ω`.
    #[must_use]
    pub fn to_world(&self, robot: Pose, p: Point) -> Point {
        let (s, c) = (self.alpha + robot.theta).sin_cos();
        Point::new(robot.x + p.x * c - p.y * s, robot.y + p.x * s + p.y * c)
    }

    /// The robot-frame point of the world point `q`.
    #[must_use]
    pub fn to_robot(&self, robot: Pose, q: Point) -> Point {
        let (s, c) = (self.alpha + robot.theta).sin_cos();
        let (dx, dy) = (q.x - robot.x, q.y - robot.y);
        Point::new(dx * c + dy * s, -dx * s + dy * c)
    }
}

/// A calibrated camera: distortion and projection.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Camera {
    /// Image width (px).
    pub width: u32,
    /// Image height (px).
    pub height: u32,
    /// Lens distortion.
    pub distortion: Distortion,
    /// Floor projection.
    pub projection: Projection,
}

impl Camera {
    /// Checks a camera read from a file: at least one pixel wide and high.
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] naming `camera`.
    pub fn check(&self) -> crate::Result<()> {
        if self.width == 0 || self.height == 0 {
            return Err(crate::Error::BadParameter {
                name: "camera",
                value: format!("{}x{}", self.width, self.height),
                expected: "a camera at least one pixel wide and high",
            });
        }
        Ok(())
    }

    /// The world floor point seen at raw pixel `(u, v)` by a robot at
    /// `(x, y, ω)`; `None` on or above the horizon.
    #[must_use]
    pub fn pixel_to_world(&self, robot: Pose, u: f64, v: f64) -> Option<Point> {
        let q = self.distortion.undistort(u, v);
        let (up, vp) = (q.x, q.y);
        let p = self.projection.floor(up, vp)?;
        Some(self.projection.to_world(robot, p))
    }

    /// The raw pixel at which a robot at `(x, y, ω)` sees the world floor
    /// point `q`; `None` behind the camera or where the lens map does not
    /// invert.
    #[must_use]
    pub fn world_to_pixel(&self, robot: Pose, q: Point) -> Option<Point> {
        let p = self.projection.to_robot(robot, q);
        let q = self.projection.image(p.x, p.y)?;
        let (up, vp) = (q.x, q.y);
        self.distortion.distort(up, vp)
    }
}

/// A 320×240 camera with barrel distortion, 0.3 m up, focal 220 px (for tests).
#[cfg(test)]
/// A calibrated 320 × 240 camera for tests.
pub(crate) fn test_camera() -> Camera {
    Camera {
        width: 320,
        height: 240,
        distortion: Distortion {
            uc: 161.5,
            vc: 118.0,
            p: [2.0e-6, -1.5e-12, 4.0e-18],
        },
        projection: Projection::pinhole(220.0, 0.3, 0.5, -2.0, 0.02, 0.10),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        test_camera()
    }

    #[test]
    fn distort_inverts_undistort_within_a_micro_pixel() {
        let cam = camera();
        let d = cam.distortion;
        for v in (0..240).step_by(7) {
            for u in (0..320).step_by(9) {
                let (up, vp) = {
                    let p = d.undistort(f64::from(u), f64::from(v));
                    (p.x, p.y)
                };
                let (ub, vb) = {
                    let p = d.distort(up, vp).expect("invertible");
                    (p.x, p.y)
                };
                assert!((ub - f64::from(u)).abs() < 1e-6 && (vb - f64::from(v)).abs() < 1e-6);
            }
        }
        // Strong enough barrel distortion folds over: not invertible there.
        let folded = Distortion {
            uc: 0.0,
            vc: 0.0,
            p: [-1e-4, 0.0, 0.0],
        };
        assert!(folded.distort(1000.0, 0.0).is_none());
    }

    #[test]
    fn known_floor_points_project_and_return() {
        // Level pinhole without distortion: a point 1 m ahead and 0.2 m to
        // the right of the camera is seen f·H/d = 66 px below the horizon
        // and f·x/d = 44 px right of the axis.
        let p = Projection::pinhole(220.0, 0.3, 0.0, 0.0, 0.0, 0.0);
        let (up, vp) = {
            let p = p.image(0.2, 1.0).expect("ahead");
            (p.x, p.y)
        };
        assert!(
            (up - 44.0).abs() < 1e-12 && (vp - 66.0).abs() < 1e-12,
            "{up} {vp}"
        );
        let (x0, y0) = {
            let p = p.floor(up, vp).expect("below the horizon");
            (p.x, p.y)
        };
        assert!((x0 - 0.2).abs() < 1e-12 && (y0 - 1.0).abs() < 1e-12);
        assert!(p.floor(10.0, -5.0).is_none(), "above the horizon");
        assert!(p.image(0.0, -1.0).is_none(), "behind");
        // In the world: a robot at (2, 1) heading +y sees "ahead" along +y
        // and "right" along +x.
        let robot = Pose::new(2.0, 1.0, std::f64::consts::FRAC_PI_2);
        let (x, y) = {
            let p = p.to_world(robot, Point::new(0.2, 1.0));
            (p.x, p.y)
        };
        assert!(
            (x - 2.2).abs() < 1e-12 && (y - 2.0).abs() < 1e-12,
            "{x} {y}"
        );
        let back = p.to_robot(robot, Point::new(x, y));
        assert!((back.x - 0.2).abs() < 1e-12 && (back.y - 1.0).abs() < 1e-12);
        // Through the whole camera, with distortion and mounting offsets.
        let cam = camera();
        let robot = Pose::new(3.0, -1.0, 0.7);
        for q in [
            Point::new(3.5, -0.2),
            Point::new(4.2, -1.3),
            Point::new(3.9, 0.1),
        ] {
            let (u, v) = {
                let p = cam.world_to_pixel(robot, q).expect("in view");
                (p.x, p.y)
            };
            let w = cam.pixel_to_world(robot, u, v).expect("on the floor");
            assert!(
                (w.x - q.x).abs() < 1e-9 && (w.y - q.y).abs() < 1e-9,
                "{q:?} {w:?}"
            );
        }
    }
}
