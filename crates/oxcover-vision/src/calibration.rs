//! Calibration by least squares (Pavlíček 2002, §2): the distortion parameters
//! from points on straight lines, the projection parameters from image
//! points paired with measured floor points. Both are solved by
//! Levenberg–Marquardt ([`levenberg_marquardt`]) on nalgebra, with
//! central-difference Jacobians, and report their residuals.
//!
//! - **Distortion** ([`calibrate_distortion`]): for each group of raw pixels
//!   known to lie on one straight line, the residuals are the distances of
//!   the corrected points to their best (total least squares) line, divided
//!   by the local radial scale (so in raw pixels: otherwise the fit could
//!   straighten every line by shrinking the image towards a far centre). The
//!   coefficients are solved scaled by the image radius (`p_k s^{2k}`) so
//!   all five unknowns are of order one.
//! - **Projection** ([`calibrate_projection`]): each pair is a raw pixel and
//!   the floor point a range finder measured, in the world frame, with the
//!   robot's pose; the residuals are the differences between the measured
//!   point and the one the camera model puts there (two per pair). The
//!   paper used 11 box measurements of four points each.

use nalgebra::{DMatrix, DVector, Matrix2, SymmetricEigen};
use oxcover_grid::{Point, Pose};
use serde::{Deserialize, Serialize};

use crate::camera::{Distortion, Projection};
use crate::error::{Error, Result};

/// What a least-squares fit ended with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Fit<T> {
    /// The parameters found.
    pub params: T,
    /// Root mean square of the residuals (px for distortion, m for projection).
    pub rms: f64,
    /// Largest absolute residual.
    pub max: f64,
    /// Iterations taken.
    pub iterations: usize,
}

/// Result of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub struct LmResult {
    /// Parameters at the end.
    pub x: DVector<f64>,
    /// Residuals there.
    pub residuals: DVector<f64>,
    /// Iterations taken.
    pub iterations: usize,
}

/// Minimises `|r(x)|²` from `x0` by Levenberg–Marquardt with Marquardt's
/// diagonal scaling and central-difference Jacobians.
///
/// # Errors
/// [`Error::Calibration`] when the residuals are not finite at the start.
pub fn levenberg_marquardt(
    x0: DVector<f64>,
    r: impl Fn(&DVector<f64>) -> DVector<f64>,
    max_iterations: usize,
) -> Result<LmResult> {
    let mut x = x0;
    let mut res = r(&x);
    if res.iter().any(|v| !v.is_finite()) {
        return Err(Error::Calibration(
            "the residuals are not finite at the starting guess".into(),
        ));
    }
    let mut cost = res.norm_squared();
    let mut lambda = 1e-3;
    let n = x.len();
    let mut iterations = 0;
    while iterations < max_iterations && cost > 0.0 {
        iterations += 1;
        let mut jac = DMatrix::<f64>::zeros(res.len(), n);
        for j in 0..n {
            let h = 1e-6 * x[j].abs().max(1e-3);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += h;
            xm[j] -= h;
            let col = (r(&xp) - r(&xm)) / (2.0 * h);
            jac.set_column(j, &col);
        }
        let jtj = jac.transpose() * &jac;
        let g = jac.transpose() * &res;
        let mut improved = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for k in 0..n {
                a[(k, k)] += lambda * jtj[(k, k)].max(1e-12);
            }
            let Some(step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            let x_new = &x + &step;
            let res_new = r(&x_new);
            let cost_new = res_new.norm_squared();
            if cost_new.is_finite() && cost_new < cost {
                let small = step.norm() <= 1e-14 * (x.norm() + 1e-14);
                x = x_new;
                res = res_new;
                cost = cost_new;
                lambda = (lambda / 10.0).max(1e-12);
                improved = !small;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    Ok(LmResult {
        x,
        residuals: res,
        iterations,
    })
}

/// The image radius the distortion coefficients are scaled by (px).
fn radius(width: u32, height: u32) -> f64 {
    0.5 * f64::from(width).hypot(f64::from(height))
}

/// Distances of points to their total-least-squares line.
fn line_residuals(points: &[Point], out: &mut Vec<f64>) {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.x / n, a.1 + p.y / n));
    let mut cov = Matrix2::<f64>::zeros();
    for p in points {
        let (dx, dy) = (p.x - mx, p.y - my);
        cov[(0, 0)] += dx * dx;
        cov[(0, 1)] += dx * dy;
        cov[(1, 1)] += dy * dy;
    }
    cov[(1, 0)] = cov[(0, 1)];
    let eig = SymmetricEigen::new(cov);
    // The normal is the eigenvector of the smaller eigenvalue.
    let k = if eig.eigenvalues[0] <= eig.eigenvalues[1] {
        0
    } else {
        1
    };
    let mut nrm = (eig.eigenvectors[(0, k)], eig.eigenvectors[(1, k)]);
    // A fixed sign (left of the first-to-last direction), so the residuals
    // are smooth in the parameters.
    if let (Some(a), Some(b)) = (points.first(), points.last()) {
        if nrm.0 * -(b.y - a.y) + nrm.1 * (b.x - a.x) < 0.0 {
            nrm = (-nrm.0, -nrm.1);
        }
    }
    for p in points {
        out.push((p.x - mx) * nrm.0 + (p.y - my) * nrm.1);
    }
}

/// The distortion of a `width × height` camera from raw pixels grouped by
/// the straight lines they lie on, starting from `guess`.
///
/// # Errors
/// [`Error::Calibration`] for fewer than three lines or a line of fewer than
/// three points.
pub fn calibrate_distortion(
    lines: &[Vec<Point>],
    width: u32,
    height: u32,
    guess: Distortion,
) -> Result<Fit<Distortion>> {
    if lines.len() < 3 || lines.iter().any(|l| l.len() < 3) {
        return Err(Error::Calibration(
            "distortion needs at least three lines of three points or more".into(),
        ));
    }
    let s2 = radius(width, height).powi(2);
    let unpack = |x: &DVector<f64>| Distortion {
        uc: x[0],
        vc: x[1],
        p: [x[2] / s2, x[3] / s2.powi(2), x[4] / s2.powi(3)],
    };
    let residuals = |x: &DVector<f64>| {
        let d = unpack(x);
        let mut out = Vec::new();
        for line in lines {
            let pts: Vec<Point> = line.iter().map(|p| d.undistort(p.x, p.y)).collect();
            let from = out.len();
            line_residuals(&pts, &mut out);
            // Back to raw pixels: divide by the local radial scale, so the
            // fit cannot straighten lines by shrinking the image.
            for (r, p) in out[from..].iter_mut().zip(line) {
                let (du, dv) = (p.x - d.uc, p.y - d.vc);
                *r /= d.factor(du * du + dv * dv).abs().max(1e-9);
            }
        }
        DVector::from_vec(out)
    };
    // The centre trades off against the coefficients, and a far centre
    // with small coefficients bends lines little: fit the coefficients
    // about the guessed centre first, then everything.
    let (uc, vc) = (guess.uc, guess.vc);
    let coefficients = levenberg_marquardt(
        DVector::from_vec(vec![
            guess.p[0] * s2,
            guess.p[1] * s2.powi(2),
            guess.p[2] * s2.powi(3),
        ]),
        |q: &DVector<f64>| residuals(&DVector::from_vec(vec![uc, vc, q[0], q[1], q[2]])),
        200,
    )?;
    let q = &coefficients.x;
    let x0 = DVector::from_vec(vec![uc, vc, q[0], q[1], q[2]]);
    let fit = levenberg_marquardt(x0, residuals, 200)?;
    Ok(summary(unpack(&fit.x), &fit))
}

/// One calibration measurement: a raw pixel, the robot's pose `(x, y, ω)`
/// and the floor point measured in the world frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FloorPair {
    /// Raw pixel `(u, v)`.
    pub pixel: Point,
    /// Robot pose `(x, y, ω)`.
    pub robot: Pose,
    /// Measured floor point (m, world frame).
    pub floor: Point,
}

/// The projection parameters from pixel–floor pairs, with the distortion
/// already known, starting from `guess`.
///
/// # Errors
/// [`Error::Calibration`] for fewer than four pairs.
pub fn calibrate_projection(
    pairs: &[FloorPair],
    distortion: &Distortion,
    guess: Projection,
) -> Result<Fit<Projection>> {
    if pairs.len() < 4 {
        return Err(Error::Calibration(
            "the projection needs at least four pixel–floor pairs".into(),
        ));
    }
    let unpack = |x: &DVector<f64>| Projection {
        x_cam: x[0],
        y_cam: x[1],
        du: x[2],
        dv: x[3],
        big_x: x[4],
        big_y: x[5],
        alpha: x[6],
    };
    let corrected: Vec<Point> = pairs
        .iter()
        .map(|p| distortion.undistort(p.pixel.x, p.pixel.y))
        .collect();
    let residuals = |x: &DVector<f64>| {
        let proj = unpack(x);
        let mut out = Vec::with_capacity(2 * pairs.len());
        for (pair, q) in pairs.iter().zip(&corrected) {
            let (up, vp) = (q.x, q.y);
            // The projection's formula, also past the horizon, so the
            // residual stays smooth while the fit moves.
            let dv = vp - proj.dv;
            let p0 = Point::new(
                -(up - proj.du) * proj.big_x / dv + proj.x_cam,
                -proj.big_y / dv + proj.y_cam,
            );
            let w = proj.to_world(pair.robot, p0);
            out.push(w.x - pair.floor.x);
            out.push(w.y - pair.floor.y);
        }
        DVector::from_vec(out)
    };
    let x0 = DVector::from_vec(vec![
        guess.x_cam,
        guess.y_cam,
        guess.du,
        guess.dv,
        guess.big_x,
        guess.big_y,
        guess.alpha,
    ]);
    let fit = levenberg_marquardt(x0, residuals, 200)?;
    Ok(summary(unpack(&fit.x), &fit))
}

fn summary<T>(params: T, fit: &LmResult) -> Fit<T> {
    let r = &fit.residuals;
    Fit {
        params,
        rms: (r.norm_squared() / r.len().max(1) as f64).sqrt(),
        max: r.amax(),
        iterations: fit.iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;

    fn truth() -> Camera {
        crate::camera::test_camera()
    }

    /// Raw pixels of straight lines (straight after correction): a grid of
    /// lines across the image, as a chequerboard's edges would give.
    fn lines(cam: &Camera, jitter: impl Fn(usize) -> (f64, f64)) -> Vec<Vec<Point>> {
        let d = cam.distortion;
        let mut out = Vec::new();
        let mut k = 0;
        for &(a, b, c) in &[
            (0.0, 1.0, -80.0),
            (0.0, 1.0, -30.0),
            (0.0, 1.0, 40.0),
            (0.0, 1.0, 90.0),
            (1.0, 0.0, -120.0),
            (1.0, 0.0, -50.0),
            (1.0, 0.0, 60.0),
            (1.0, 0.0, 130.0),
            (0.6, 0.8, 20.0),
        ] {
            // Points (u', v') on a u' + b v' = c... parametrised along it.
            let (nx, ny): (f64, f64) = (a, b);
            let (tx, ty) = (-ny, nx);
            let line: Vec<Point> = (-8..=8)
                .filter_map(|t| {
                    let t = f64::from(t) * 14.0;
                    let (up, vp) = (c * nx + t * tx, c * ny + t * ty);
                    let (u, v) = {
                        let p = d.distort(up, vp)?;
                        (p.x, p.y)
                    };
                    let (ju, jv) = jitter(k);
                    k += 1;
                    (u >= 0.0 && v >= 0.0 && u < 320.0 && v < 240.0)
                        .then_some(Point::new(u + ju, v + jv))
                })
                .collect();
            out.push(line);
        }
        out
    }

    fn noise(seed: usize, sd: f64) -> (f64, f64) {
        // A small deterministic pseudo-random pair (no rand dependency).
        let h = |x: usize| {
            let mut z = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
            z = (z ^ (z >> 31)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            ((z >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        (sd * 3.46 * h(2 * seed), sd * 3.46 * h(2 * seed + 1))
    }

    #[test]
    fn distortion_is_recovered_from_clean_lines() {
        let cam = truth();
        // No distortion about the image centre: where a user would start.
        let guess = Distortion {
            uc: 160.0,
            vc: 120.0,
            p: [0.0; 3],
        };
        let fit = calibrate_distortion(&lines(&cam, |_| (0.0, 0.0)), 320, 240, guess).unwrap();
        let (t, f) = (cam.distortion, fit.params);
        assert!(
            (f.uc - t.uc).abs() < 1e-6 && (f.vc - t.vc).abs() < 1e-6,
            "{f:?}"
        );
        let s2 = 200.0f64.powi(2);
        for k in 0..3 {
            let scale = s2.powi(k as i32 + 1);
            assert!((f.p[k] - t.p[k]).abs() * scale < 1e-6, "p{} {f:?}", k + 1);
        }
        assert!(fit.rms < 1e-9, "{}", fit.rms);
    }

    #[test]
    fn distortion_degrades_gracefully_with_pixel_noise() {
        let cam = truth();
        // No distortion about the image centre: where a user would start.
        let guess = Distortion {
            uc: 160.0,
            vc: 120.0,
            p: [0.0; 3],
        };
        let fit = calibrate_distortion(&lines(&cam, |k| noise(k, 0.3)), 320, 240, guess).unwrap();
        // The residuals are of the noise's size. The centre is the weakly
        // determined part (moving it mostly translates the corrected image,
        // which keeps lines straight), so judge the fit by what it is for:
        // the noise-free lines, corrected by it, are straight to a fraction
        // of a pixel.
        assert!(fit.rms < 0.5, "{}", fit.rms);
        let mut bend = Vec::new();
        for line in lines(&cam, |_| (0.0, 0.0)) {
            let pts: Vec<Point> = line
                .iter()
                .map(|p| fit.params.undistort(p.x, p.y))
                .collect();
            line_residuals(&pts, &mut bend);
        }
        let worst = bend.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(worst < 0.5, "{worst}");
        let c = (fit.params.uc - cam.distortion.uc).hypot(fit.params.vc - cam.distortion.vc);
        assert!(c < 15.0, "centre off by {c} px");
    }

    fn pairs(cam: &Camera, jitter: impl Fn(usize) -> (f64, f64)) -> Vec<FloorPair> {
        // 11 box placements, four corners each, seen from three poses.
        let mut out = Vec::new();
        let poses = [
            Pose::new(0.0, 0.0, 0.0),
            Pose::new(1.0, 0.5, 0.4),
            Pose::new(-0.5, 2.0, -0.3),
        ];
        let mut k = 0;
        for (i, &robot) in poses.iter().cycle().take(11).enumerate() {
            let ahead = 0.6 + 0.15 * i as f64;
            let side = -0.3 + 0.06 * i as f64;
            for (dx, dy) in [(0.0, 0.0), (0.3, 0.0), (0.0, 0.2), (0.3, 0.2)] {
                let p = Point::new(side + dx, ahead + dy);
                let world = cam.projection.to_world(robot, p);
                let Some(px) = cam.world_to_pixel(robot, world) else {
                    continue;
                };
                let (ju, jv) = jitter(k);
                k += 1;
                out.push(FloorPair {
                    pixel: Point::new(px.x + ju, px.y + jv),
                    robot,
                    floor: world,
                });
            }
        }
        out
    }

    fn guess() -> Projection {
        Projection {
            x_cam: 0.0,
            y_cam: 0.0,
            du: 0.0,
            dv: 0.0,
            big_x: -0.25,
            big_y: -60.0,
            alpha: -1.4,
        }
    }

    #[test]
    fn projection_is_recovered_from_clean_pairs() {
        let cam = truth();
        let pairs = pairs(&cam, |_| (0.0, 0.0));
        assert_eq!(pairs.len(), 44);
        let fit = calibrate_projection(&pairs, &cam.distortion, guess()).unwrap();
        let (t, f) = (cam.projection, fit.params);
        for (a, b, name) in [
            (f.x_cam, t.x_cam, "x_cam"),
            (f.y_cam, t.y_cam, "y_cam"),
            (f.du, t.du, "du"),
            (f.dv, t.dv, "dv"),
            (f.big_x, t.big_x, "X"),
            (f.big_y, t.big_y, "Y"),
            (f.alpha, t.alpha, "alpha"),
        ] {
            assert!(
                (a - b).abs() <= 1e-6 * b.abs().max(1.0),
                "{name}: {a} vs {b}"
            );
        }
        assert!(fit.rms < 1e-9);
    }

    #[test]
    fn projection_degrades_gracefully_with_pixel_noise() {
        let cam = truth();
        let pairs = pairs(&cam, |k| noise(k, 0.5));
        let fit = calibrate_projection(&pairs, &cam.distortion, guess()).unwrap();
        // Half a pixel of noise: floor residuals of millimetres to a
        // centimetre or so. Single parameters trade off (a small turn α
        // looks much like a shift Δu), so check what matters: where the
        // fitted camera puts floor pixels, over the view below the horizon
        // up to 2 m (where one pixel row spans 6 cm of floor).
        assert!(fit.rms < 0.02, "{}", fit.rms);
        let fitted = Camera {
            projection: fit.params,
            ..cam
        };
        let robot = Pose::new(0.0, 0.0, 0.0);
        let mut worst: f64 = 0.0;
        for v in (130..240).step_by(10) {
            for u in (0..320).step_by(20) {
                let (u, v) = (f64::from(u), f64::from(v));
                if let (Some(a), Some(b)) = (
                    cam.pixel_to_world(robot, u, v),
                    fitted.pixel_to_world(robot, u, v),
                ) {
                    if a.x.hypot(a.y) < 2.0 {
                        worst = worst.max((a.x - b.x).hypot(a.y - b.y));
                    }
                }
            }
        }
        assert!(worst < 0.05, "{worst}");
        assert!((fit.params.alpha - cam.projection.alpha).abs() < 0.05);
    }

    #[test]
    fn too_little_data_is_an_error() {
        let cam = truth();
        assert!(calibrate_distortion(&[], 320, 240, cam.distortion).is_err());
        assert!(calibrate_projection(&[], &cam.distortion, guess()).is_err());
    }
}
