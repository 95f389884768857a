//! Slivers: what the rings leave, driven where worth its time.
//!
//! Rings of different walls meet at the medial axis; the strip between the
//! last rings can be up to `4R − 2T` cells wide, and the corners of inner
//! rings leave small pockets. These pieces are predicted from the rings
//! (cells the tool does not reach) and each is given a spine: the straight
//! segment along its principal axis, split in two at the median until each
//! segment passes within the reach of every cell of its piece and keeps
//! clearance. A spine is driven only when its time per newly covered area
//! (the way to it and along it at speed, plus two right-angle turns) is at
//! most [`super::Smooth::sliver_worth`] times the plan's so far: small
//! pockets far from the robot cost minutes per square metre and are left,
//! which is the seed's own measure (normalized time per covered area).

use std::f64::consts::FRAC_PI_2;

use oxcover_grid::Cell;
use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_distance};

use super::Run;
use super::run::path_length;

impl<'a> Run<'a> {
    /// A polyline through `cells` passing within the reach of each: the
    /// segment along their principal axis when it keeps clearance and
    /// reaches them all, otherwise the spines of the halves split at the
    /// median along that axis, in axis order.
    pub(super) fn spine(&self, cells: &[Cell]) -> Vec<GridPoint> {
        let centres: Vec<GridPoint> = cells.iter().map(|&c| cell_center(c)).collect();
        if cells.len() == 1 {
            return centres;
        }
        let n = cells.len() as f64;
        let (mx, my) = (
            centres.iter().map(|p| p.x).sum::<f64>() / n,
            centres.iter().map(|p| p.y).sum::<f64>() / n,
        );
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for p in &centres {
            let (dx, dy) = (p.x - mx, p.y - my);
            sxx += dx * dx;
            sxy += dx * dy;
            syy += dy * dy;
        }
        let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
        let (ux, uy) = (angle.cos(), angle.sin());
        let t: Vec<f64> = centres
            .iter()
            .map(|p| (p.x - mx) * ux + (p.y - my) * uy)
            .collect();
        let (lo, hi) = t
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let (a, b) = (
            GridPoint::new(mx + lo * ux, my + lo * uy),
            GridPoint::new(mx + hi * ux, my + hi * uy),
        );
        let inside = |p: GridPoint| cell_of(self.plannable, p).is_some_and(|c| self.plannable[c]);
        let reaches = centres
            .iter()
            .all(|&m| segment_distance(a, b, m) <= self.reach - 1e-6);
        if reaches && inside(a) && inside(b) && self.builder.clear(a, b) {
            return if norm(b.x - a.x, b.y - a.y) < 1e-9 {
                vec![a]
            } else {
                vec![a, b]
            };
        }
        let mut order: Vec<usize> = (0..cells.len()).collect();
        order.sort_by(|&i, &j| t[i].total_cmp(&t[j]));
        let half = cells.len() / 2;
        let first: Vec<Cell> = order[..half].iter().map(|&i| cells[i]).collect();
        let second: Vec<Cell> = order[half..].iter().map(|&i| cells[i]).collect();
        let mut out = self.spine(&first);
        out.extend(self.spine(&second));
        out
    }

    /// Whether a spine covering `gain` new cells is worth its time.
    pub(super) fn worth(&self, spine: &[GridPoint], gain: usize) -> bool {
        let (res, v) = (self.resolution, self.limits.v_max);
        let here = self.builder.last();
        let way = norm(spine[0].x - here.x, spine[0].y - here.y) + path_length(spine);
        let extra = way * res / v + 2.0 * FRAC_PI_2 / self.limits.omega_max;
        let area = |cells: usize| cells as f64 * res * res;
        let so_far = path_length(self.builder.points()) * res / v;
        let covered = area(self.touched.count_true()).max(area(1));
        extra / area(gain) <= self.smooth.sliver_worth * so_far / covered
    }
}
