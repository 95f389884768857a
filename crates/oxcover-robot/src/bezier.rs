//! Quintic Bézier segments and splines (Lee 2011, eq. 13).
//!
//! A segment `Q(u) = Σ_{k=0}^{5} C(5,k) (1−u)^{5−k} u^k P_k`, `u ∈ [0, 1]`,
//! is built from its end points, end tangents `T` and end second
//! derivatives `A` by the seed's rules: `P₁ = P₀ + T₀/5`,
//! `P₄ = P₅ − T₁/5`, `P₂ = A₀/20 + 2P₁ − P₀`, `P₃ = A₁/20 + 2P₄ − P₅`, which
//! make `Q'(0) = T₀`, `Q'(1) = T₁`, `Q''(0) = A₀`, `Q''(1) = A₁`. A spline of
//! such segments that share `T` and `A` at its joins is C² continuous.
//!
//! Two splines through points: [`spline_through`], the paper's uniform
//! derivatives (C², but it loops where points are unevenly spaced), and
//! [`G2Spline`], chord-length tangents and circle curvatures (G², no loops),
//! which the smooth planner drives and tunes.

use oxcover_grid::math::norm;
use oxcover_grid::{Point, Vector};

/// Coordinates as a vector: control points and derivatives are combined
/// alike (de Casteljau), component by component.
type Vec2 = Vector;

fn add(a: Vec2, b: Vec2) -> Vec2 {
    Vector::new(a.x + b.x, a.y + b.y)
}

fn sub(a: Vec2, b: Vec2) -> Vec2 {
    Vector::new(a.x - b.x, a.y - b.y)
}

fn scale(a: Vec2, k: f64) -> Vec2 {
    Vector::new(a.x * k, a.y * k)
}

/// A quintic Bézier segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuinticBezier {
    /// Control points `P₀ … P₅`.
    pub control: [Point; 6],
}

impl QuinticBezier {
    /// The segment from `p0` to `p1` with end tangents `t0`, `t1` and end
    /// second derivatives `a0`, `a1` (Lee 2011's control-point rules).
    #[must_use]
    pub fn from_ends(p0: Point, p1: Point, t0: Vector, t1: Vector, a0: Vector, a1: Vector) -> Self {
        let (q0, q1) = (p0.coords, p1.coords);
        let c1 = add(q0, scale(t0, 0.2));
        let c4 = sub(q1, scale(t1, 0.2));
        let c2 = add(scale(a0, 1.0 / 20.0), sub(scale(c1, 2.0), q0));
        let c3 = add(scale(a1, 1.0 / 20.0), sub(scale(c4, 2.0), q1));
        Self {
            control: [p0, c1.into(), c2.into(), c3.into(), c4.into(), p1],
        }
    }

    /// The control points as vectors.
    #[inline]
    fn coords(&self) -> [Vec2; 6] {
        let c = &self.control;
        [
            c[0].coords,
            c[1].coords,
            c[2].coords,
            c[3].coords,
            c[4].coords,
            c[5].coords,
        ]
    }

    /// de Casteljau evaluation of the control polygon `c` at `u`.
    fn casteljau<const N: usize>(mut c: [Vec2; N], u: f64) -> Vec2 {
        for level in (1..N).rev() {
            for k in 0..level {
                c[k] = add(scale(c[k], 1.0 - u), scale(c[k + 1], u));
            }
        }
        c[0]
    }

    /// The point at `u ∈ [0, 1]`.
    #[must_use]
    pub fn point(&self, u: f64) -> Point {
        Self::casteljau(self.coords(), u).into()
    }

    /// `Q'(u)`.
    #[must_use]
    pub fn derivative(&self, u: f64) -> Vector {
        let c = &self.coords();
        let d: [Vec2; 5] = std::array::from_fn(|k| scale(sub(c[k + 1], c[k]), 5.0));
        Self::casteljau(d, u)
    }

    /// `Q''(u)`.
    #[must_use]
    pub fn second_derivative(&self, u: f64) -> Vector {
        let c = &self.coords();
        let d: [Vec2; 4] =
            std::array::from_fn(|k| scale(add(sub(c[k + 2], scale(c[k + 1], 2.0)), c[k]), 20.0));
        Self::casteljau(d, u)
    }

    /// Signed curvature at `u` (1/m; positive turning left), 0 where the
    /// curve is stationary.
    #[must_use]
    pub fn curvature(&self, u: f64) -> f64 {
        let (d, dd) = (self.derivative(u), self.second_derivative(u));
        let speed = norm(d.x, d.y);
        if speed < 1e-12 {
            0.0
        } else {
            (d.x * dd.y - d.y * dd.x) / speed.powi(3)
        }
    }

    /// `n + 1` points at equal steps of `u`.
    #[must_use]
    pub fn sample(&self, n: usize) -> Vec<Point> {
        let n = n.max(1);
        (0..=n).map(|k| self.point(k as f64 / n as f64)).collect()
    }

    /// Arc length, by Gauss–Legendre quadrature (5 points) on 16 pieces.
    #[must_use]
    pub fn length(&self) -> f64 {
        const X: [f64; 5] = [
            0.0,
            -0.538_469_310_105_683,
            0.538_469_310_105_683,
            -0.906_179_845_938_664,
            0.906_179_845_938_664,
        ];
        const W: [f64; 5] = [
            0.568_888_888_888_889,
            0.478_628_670_499_366,
            0.478_628_670_499_366,
            0.236_926_885_056_189,
            0.236_926_885_056_189,
        ];
        let pieces = 16;
        let h = 1.0 / f64::from(pieces);
        (0..pieces)
            .map(|i| {
                let mid = (f64::from(i) + 0.5) * h;
                X.iter()
                    .zip(W)
                    .map(|(&x, w)| {
                        let d = self.derivative(mid + x * h / 2.0);
                        w * norm(d.x, d.y)
                    })
                    .sum::<f64>()
                    * h
                    / 2.0
            })
            .sum()
    }
}

/// The end derivatives [`spline_through`] uses at each of `points`:
/// tangents by centred differences (one-sided at the ends) and second
/// derivatives by the second difference (zero at the ends).
#[must_use]
pub fn spline_derivatives(points: &[Point]) -> (Vec<Vector>, Vec<Vector>) {
    let n = points.len();
    if n < 2 {
        return (vec![Vector::zeros(); n], vec![Vector::zeros(); n]);
    }
    let points: Vec<Vec2> = points.iter().map(|p| p.coords).collect();
    let tangents = (0..n)
        .map(|i| {
            if i == 0 {
                sub(points[1], points[0])
            } else if i == n - 1 {
                sub(points[n - 1], points[n - 2])
            } else {
                scale(sub(points[i + 1], points[i - 1]), 0.5)
            }
        })
        .collect();
    let accels = (0..n)
        .map(|i| {
            if i == 0 || i == n - 1 {
                Vector::zeros()
            } else {
                add(sub(points[i + 1], scale(points[i], 2.0)), points[i - 1])
            }
        })
        .collect();
    (tangents, accels)
}

/// A C² spline through `points` (at least two), one segment per pair of
/// points, with the derivatives of [`spline_derivatives`].
#[must_use]
pub fn spline_through(points: &[Point]) -> Vec<QuinticBezier> {
    let (t, a) = spline_derivatives(points);
    points
        .windows(2)
        .enumerate()
        .map(|(i, w)| QuinticBezier::from_ends(w[0], w[1], t[i], t[i + 1], a[i], a[i + 1]))
        .collect()
}

/// A G²-continuous spline of quintic Bézier segments through points: at each
/// point a unit tangent (the direction from the previous to the next point)
/// and a curvature (of the circle through the point and its neighbours; 0 at
/// the ends); a segment's end tangents have its chord's length, and its end
/// second derivatives give the points' curvatures. Unlike uniform
/// (Catmull–Rom) tangents, chord-length tangents do not loop where points are
/// unevenly spaced.
#[derive(Clone, Debug)]
pub struct G2Spline {
    points: Vec<Point>,
    /// Tangent angle at each point.
    angle: Vec<f64>,
    /// Tangent length factor at each point.
    scale: Vec<f64>,
    /// Signed curvature at each point.
    kappa: Vec<f64>,
}

impl G2Spline {
    /// The spline through `points` (at least two).
    #[must_use]
    pub fn through(points: &[Point]) -> Self {
        let n = points.len();
        let dir = |a: Point, b: Point| (b.y - a.y).atan2(b.x - a.x);
        let angle = (0..n)
            .map(|i| {
                if i == 0 {
                    dir(points[0], points[1])
                } else if i == n - 1 {
                    dir(points[n - 2], points[n - 1])
                } else {
                    // Unit directions of both chords, summed (bisector).
                    let (a, b) = (dir(points[i - 1], points[i]), dir(points[i], points[i + 1]));
                    (a.sin() + b.sin()).atan2(a.cos() + b.cos())
                }
            })
            .collect();
        let kappa = (0..n)
            .map(|i| {
                if i == 0 || i == n - 1 {
                    return 0.0;
                }
                let (a, b, c) = (points[i - 1], points[i], points[i + 1]);
                let cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                let (ab, bc) = (norm(b.x - a.x, b.y - a.y), norm(c.x - b.x, c.y - b.y));
                let d = ab * bc * norm(c.x - a.x, c.y - a.y);
                // |κ|·chord ≤ 2 on both sides, so a sharp point cannot make a
                // segment loop (the same value on both sides keeps G²).
                let limit = 2.0 / ab.min(bc).max(1e-9);
                if d > 1e-12 {
                    (2.0 * cross / d).clamp(-limit, limit)
                } else {
                    0.0
                }
            })
            .collect();
        Self {
            points: points.to_vec(),
            angle,
            scale: vec![1.0; n],
            kappa,
        }
    }

    /// Point `i`.
    #[must_use]
    pub fn point(&self, i: usize) -> Point {
        self.points[i]
    }

    /// Segment `i` (from point `i` to `i + 1`) with its tangents scaled by
    /// `k` (1 = the spline's).
    #[must_use]
    pub fn segment(&self, i: usize, k: f64) -> QuinticBezier {
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        let chord = norm(p1.x - p0.x, p1.y - p0.y);
        let end = |j: usize| {
            let len = chord * self.scale[j] * k;
            let (sin, cos) = self.angle[j].sin_cos();
            // Curvature κ needs a normal second derivative κ·|T|².
            let a = self.kappa[j] * len * len;
            (
                Vector::new(len * cos, len * sin),
                Vector::new(-a * sin, a * cos),
            )
        };
        let ((t0, a0), (t1, a1)) = (end(i), end(i + 1));
        QuinticBezier::from_ends(p0, p1, t0, t1, a0, a1)
    }

    /// Point `i` of `base` adjusted by
    /// `x = (normal shift, tangent rotation, tangent scale − 1, curvature scale − 1)`
    /// (the smooth planner's PSO position).
    pub fn adjust(&mut self, base: &G2Spline, i: usize, x: &[f64; 4]) {
        let (sin, cos) = base.angle[i].sin_cos();
        let p = base.points[i];
        self.points[i] = Point::new(p.x - x[0] * sin, p.y + x[0] * cos);
        self.angle[i] = base.angle[i] + x[1];
        self.scale[i] = base.scale[i] * (1.0 + x[2]);
        self.kappa[i] = base.kappa[i] * (1.0 + x[3]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether two points (or two vectors, as points) are within `tol`.
    fn near(a: impl Into<Point>, b: impl Into<Point>, tol: f64) -> bool {
        let (a, b) = (a.into(), b.into());
        norm(a.x - b.x, a.y - b.y) < tol
    }

    #[test]
    fn ends_tangents_and_second_derivatives_are_the_given_ones() {
        let q = QuinticBezier::from_ends(
            Point::new(0.0, 0.0),
            Point::new(2.0, 1.0),
            Vector::new(1.0, 0.5),
            Vector::new(0.0, 3.0),
            Vector::new(0.3, -0.2),
            Vector::new(1.5, 0.7),
        );
        assert!(near(q.point(0.0), Point::new(0.0, 0.0), 1e-12));
        assert!(near(q.point(1.0), Point::new(2.0, 1.0), 1e-12));
        assert!(
            near(q.derivative(0.0), Vector::new(1.0, 0.5), 1e-12)
                && near(q.derivative(1.0), Vector::new(0.0, 3.0), 1e-12)
        );
        assert!(near(
            q.second_derivative(0.0),
            Vector::new(0.3, -0.2),
            1e-12
        ));
        assert!(near(q.second_derivative(1.0), Vector::new(1.5, 0.7), 1e-12));
        // Derivatives agree with finite differences inside.
        let (u, h) = (0.37, 1e-6);
        let fd = (q.point(u + h) - q.point(u - h)) * (0.5 / h);
        assert!(near(fd, q.derivative(u), 1e-6));
    }

    #[test]
    fn a_straight_segment_has_its_length_and_no_curvature() {
        let q = QuinticBezier::from_ends(
            Point::new(0.0, 0.0),
            Point::new(3.0, 4.0),
            Vector::new(3.0, 4.0),
            Vector::new(3.0, 4.0),
            Vector::new(0.0, 0.0),
            Vector::new(0.0, 0.0),
        );
        assert!((q.length() - 5.0).abs() < 1e-9);
        assert!(q.curvature(0.5).abs() < 1e-12);
        let pts = q.sample(10);
        assert_eq!(pts.len(), 11);
    }

    #[test]
    fn splines_are_c2_at_their_joins() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.2),
            Point::new(1.8, 1.0),
            Point::new(1.5, 2.0),
            Point::new(0.5, 2.4),
        ];
        let s = spline_through(&pts);
        assert_eq!(s.len(), 4);
        for w in s.windows(2) {
            assert!(near(w[0].point(1.0), w[1].point(0.0), 1e-12));
            assert!(near(w[0].derivative(1.0), w[1].derivative(0.0), 1e-12));
            assert!(near(
                w[0].second_derivative(1.0),
                w[1].second_derivative(0.0),
                1e-12
            ));
        }
        // The spline passes through every point.
        for (i, q) in s.iter().enumerate() {
            assert!(near(q.point(0.0), pts[i], 1e-12));
        }
        // A circle-like turn to the left has positive curvature.
        assert!(s[1].curvature(0.5) > 0.0);
        assert!(spline_through(&pts[..1]).is_empty());
    }

    #[test]
    fn spline_is_g2_at_joins_and_does_not_loop_on_uneven_points() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(0.3, 0.0),
            Point::new(5.0, 1.0),
            Point::new(5.4, 1.3),
            Point::new(6.0, 4.0),
            Point::new(2.0, 5.0),
        ];
        let sp = G2Spline::through(&pts);
        for (i, p) in pts.iter().enumerate().take(pts.len() - 1).skip(1) {
            let (a, b) = (sp.segment(i - 1, 1.0), sp.segment(i, 1.0));
            let (da, db) = (a.derivative(1.0), b.derivative(0.0));
            let cross = da.x * db.y - da.y * db.x;
            assert!(cross.abs() < 1e-9 * norm(da.x, da.y) * norm(db.x, db.y));
            assert!(da.x * db.x + da.y * db.y > 0.0, "same direction at {i}");
            assert!(
                (a.curvature(1.0) - b.curvature(0.0)).abs() < 1e-9,
                "curvature at {i}"
            );
            assert!((a.point(1.0).x - p.x).abs() < 1e-12);
        }
        let poly: f64 = pts
            .windows(2)
            .map(|w| norm(w[1].x - w[0].x, w[1].y - w[0].y))
            .sum();
        let curve: f64 = (0..pts.len() - 1)
            .map(|i| sp.segment(i, 1.0).length())
            .sum();
        assert!(curve < 1.3 * poly, "{curve} vs {poly}");
        // The seed's uniform derivatives loop on the same points.
        let uniform: f64 = spline_through(&pts).iter().map(QuinticBezier::length).sum();
        assert!(uniform > curve, "{uniform} vs {curve}");
    }
}
