//! Fillets: sharp corners rounded where that is faster.
//!
//! Corners sharper than [`GENTLE`] are rounded by quintic Bézier fillets
//! tangent to both sides with zero end curvature (G²). A fillet is kept
//! only where the time law drives it faster than the stop-and-turn it
//! replaces, stays clear, and passes within the margin of the corner (so
//! what the corner covered with the reach, the fillet covers with the
//! tool). Its shape (how far it starts before and ends after the corner,
//! and its two end-tangent lengths) is tuned by the seed's PSO (Algorithm 1,
//! [`crate::pso`]) with the estimated closed-loop time of the corner as
//! cost, from the widest symmetric fillet that fits.

use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, segment_distance};
use oxcover_grid::{Point, Vector};
use oxcover_robot::QuinticBezier;

use super::Run;
use super::run::turn;

/// Largest turn (rad) the time law drives through without stopping; sharper
/// vertices are rounded when a fillet is faster.
const GENTLE: f64 = 0.33;

impl<'a> Run<'a> {
    /// Rounds the sharp vertices of a polyline where a fillet is faster (see
    /// the module docs).
    pub(super) fn fillet_corners(&mut self, pts: &[GridPoint]) -> Vec<GridPoint> {
        let mut out = vec![pts[0]];
        for i in 1..pts.len() - 1 {
            let (prev, p, next) = (*out.last().expect("a point"), pts[i], pts[i + 1]);
            let (lin, lout) = (
                norm(p.x - prev.x, p.y - prev.y),
                norm(next.x - p.x, next.y - p.y),
            );
            if lin < 1e-9 || lout < 1e-9 || turn(prev, p, next).abs() <= GENTLE {
                out.push(p);
                continue;
            }
            match self.fillet(prev, p, next) {
                Some(samples) => {
                    self.stats.fillets.0 += 1;
                    out.extend_from_slice(&samples);
                }
                None => {
                    self.stats.fillets.1 += 1;
                    out.push(p);
                }
            }
        }
        out.push(pts[pts.len() - 1]);
        out
    }

    /// The fastest fillet of the corner `prev → p → next`, if one is faster
    /// than stopping at `p`.
    pub(super) fn fillet(
        &mut self,
        prev: GridPoint,
        p: GridPoint,
        next: GridPoint,
    ) -> Option<Vec<GridPoint>> {
        if self.margin <= 0.0 {
            return None;
        }
        self.corners += 1;
        let seed = self.seed ^ self.corners.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let (lin, lout) = (
            norm(p.x - prev.x, p.y - prev.y),
            norm(next.x - p.x, next.y - p.y),
        );
        let cap = (0.5 * lin).min(0.5 * lout).min(3.0);
        // x = (start before p, end after p, start tangent, end tangent scale).
        let cost = |x: &[f64; 4]| -> Option<f64> {
            let samples = self.fillet_samples(prev, p, next, x)?;
            let mut window = vec![prev];
            window.extend_from_slice(&samples);
            window.push(next);
            Some(self.secs(&window))
        };
        // The widest symmetric fillet that fits is PSO's feasible start.
        let mut d = cap;
        let start = loop {
            if d < 0.05 {
                return None;
            }
            let x = [d, d, 1.0, 1.0];
            if let Some(c) = cost(&x) {
                break (x, c);
            }
            d /= 2.0;
        };
        let corner = self.secs(&[prev, p, next]);
        let best = self
            .smooth
            .pso
            .minimise(
                start.0,
                [0.05, 0.05, 0.3, 0.3],
                [cap, cap, 1.5, 1.5],
                seed,
                cost,
            )
            .map_or(start, |r| (r.x, r.cost));
        if best.1 >= corner {
            return None;
        }
        self.stats.fillet_time.0 += start.1;
        self.stats.fillet_time.1 += best.1;
        self.fillet_samples(prev, p, next, &best.0)
    }

    /// The fillet with shape `x` sampled, if it keeps clearance and passes
    /// within the margin of the corner it replaces.
    pub(super) fn fillet_samples(
        &self,
        prev: GridPoint,
        p: GridPoint,
        next: GridPoint,
        x: &[f64; 4],
    ) -> Option<Vec<GridPoint>> {
        let unit = |a: GridPoint, b: GridPoint| {
            let l = norm(b.x - a.x, b.y - a.y);
            ((b.x - a.x) / l, (b.y - a.y) / l)
        };
        let ((ux, uy), (vx, vy)) = (unit(prev, p), unit(p, next));
        let [din, dout, kin, kout] = *x;
        let a = GridPoint::new(p.x - din * ux, p.y - din * uy);
        let b = GridPoint::new(p.x + dout * vx, p.y + dout * vy);
        let l = norm(b.x - a.x, b.y - a.y);
        let seg = QuinticBezier::from_ends(
            a,
            b,
            Vector::new(kin * l * ux, kin * l * uy),
            Vector::new(kout * l * vx, kout * l * vy),
            Vector::new(0.0, 0.0),
            Vector::new(0.0, 0.0),
        );
        let angle = turn(prev, p, next).abs();
        let samples = seg.sample(((din + dout) / 0.25).max(angle / 0.08).ceil().max(4.0) as usize);
        let near = |q: GridPoint| {
            samples
                .windows(2)
                .any(|s| segment_distance(s[0], s[1], q) <= self.margin)
        };
        let covered = (0..=8).all(|k| {
            let t = k as f64 / 8.0;
            near(Point::new(a.x + t * (p.x - a.x), a.y + t * (p.y - a.y)))
                && near(Point::new(p.x + t * (b.x - p.x), p.y + t * (b.y - p.y)))
        });
        (covered && samples.windows(2).all(|s| self.clear.segment(s[0], s[1]))).then_some(samples)
    }
}
