//! Lane angle choice: which angles a region's lanes are laid at, and
//! which few of them go on to be ordered and built.
//!
//! Candidates are every 15° and the walls' mean direction with its normal
//! (the grid's axes only for a tool narrower than a cell). Each is scored
//! by its chains' modelled time ([`modelled_time`]); the wall directions
//! win near ties. The model cannot see what detours and tightening make of
//! an angle, so the best few, with their ordered transits, are built to the
//! end and compared on the finished path (a small region builds every
//! angle). The walls' own strongest directions, where they differ from the
//! mean (two wall systems, a hexagonal arena), are the re-hatching angles
//! besides the mean's ([`super::rehatch`]).
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): the wall
//! directions alone are 2.4 % (ipa) / 0.5 % (ROS) slower, the model's best
//! angle alone 2.4 % / 1.6 %.

use std::f64::consts::PI;

use rayon::prelude::*;

use super::LaneStages;
use super::layout::{Chain, Layout, modelled_time};
use super::loops::EdgeLoop;

/// Factor by which another angle must beat the wall directions in the
/// model (1.05: the middle of the margins that gained on the shared maps).
const WALL_PREFERENCE: f64 = 1.05;

/// The cheapest angles (by their chains) whose order is planned, to
/// compare transits too, if within [`NEAR_TIE`] of the cheapest.
const ANGLES_ORDERED: usize = 3;

/// How much dearer than the cheapest (by its chains) an angle may be and
/// still have its transits compared.
const NEAR_TIE: f64 = 1.15;

/// Of the angles ordered, how many (the cheapest with their transits) are
/// built to the end and compared by the finished path's estimated time.
const ANGLES_BUILT: usize = 2;

/// Angle builds a plan may spend, in plannable cells: a plan of `n` cells
/// builds `BUILD_BUDGET / n` of its angles, at least [`ANGLES_BUILT`]
/// (200,000: the most that kept the slowest shared map under 1 s).
pub(super) const BUILD_BUDGET: usize = 200_000;

/// The angles (radians, grid frame: rows grow downwards) a region is
/// hatched at, and those its chains may be re-hatched at.
pub(super) struct Angles {
    /// The candidates: the walls' mean direction and its normal first.
    pub(super) candidates: Vec<f64>,
    /// The re-hatching angles: the first two candidates, then each of the
    /// walls' own directions that differs from their mean, with its normal.
    pub(super) walls: Vec<f64>,
}

/// An angle's chains, the distance between their lines and their modelled
/// seconds.
pub(super) struct Scored {
    pub(super) cost: f64,
    pub(super) chains: Vec<Chain>,
    pub(super) step: f64,
}

impl Angles {
    /// The angles for a region with edge loops `loops`: `angle_deg` alone
    /// (degrees, map frame) where given; the grid's axes for a `narrow`
    /// tool (under a cell); else the wall directions and every 15°.
    pub(super) fn new(
        loops: &[EdgeLoop],
        angle_deg: Option<f64>,
        narrow: bool,
        stages: &LaneStages,
    ) -> Self {
        let wall = wall_angle(loops);
        let candidates: Vec<f64> = match angle_deg {
            // Grid rows grow downwards: a map-frame angle a is -a here.
            Some(a) => vec![-a.to_radians()],
            None if narrow => vec![0.0, PI / 2.0],
            None => {
                let mut v = vec![wall, wall + PI / 2.0];
                if stages.every_angle {
                    v.extend((0..12).map(|k| f64::from(k) * PI / 12.0));
                }
                v
            }
        };
        let mut walls: Vec<f64> = candidates.iter().take(2).copied().collect();
        if angle_deg.is_none() && !narrow {
            for other in other_wall_angles(loops, wall) {
                walls.extend([other, other + PI / 2.0]);
            }
        }
        Self { candidates, walls }
    }

    /// Every candidate's chains on `layout`, modelled (in parallel, in the
    /// order of the candidates whatever the thread count), cheapest first;
    /// of them the few whose order is planned, and how many of those are
    /// built. A plan of `plan_cells` plannable cells small enough to build
    /// more than [`ANGLES_BUILT`] orders and builds that many, whatever
    /// the model thinks of them.
    /// With `several` off, the model's best alone is ordered and built.
    pub(super) fn near_ties(
        &self,
        layout: &Layout<'_>,
        plan_cells: usize,
        several: bool,
    ) -> (Vec<Scored>, usize) {
        let area = layout.mask.cells.count_true() as f64;
        let score = |(i, &theta): (usize, &f64)| {
            let (chains, step) = layout.chains(theta);
            let mut cost = modelled_time(&chains, step, area, layout.spacing, layout.time);
            // Near ties go to the wall directions, tried first.
            if i >= 2 {
                cost *= WALL_PREFERENCE;
            }
            Scored { cost, chains, step }
        };
        let mut scored: Vec<Scored> = self.candidates.par_iter().enumerate().map(score).collect();
        scored.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        let cheapest = scored.first().map_or(0.0, |b| b.cost);
        let affordable = (BUILD_BUDGET / plan_cells.max(1)).min(scored.len());
        let (ordered, built, tie) = if !several {
            (1, 1, NEAR_TIE)
        } else if affordable > ANGLES_BUILT {
            (affordable, affordable, f64::INFINITY)
        } else {
            (ANGLES_ORDERED, ANGLES_BUILT, NEAR_TIE)
        };
        let near: Vec<Scored> = scored
            .into_iter()
            .take(ordered)
            .enumerate()
            .filter(|(i, s)| *i == 0 || s.cost <= tie * cheapest)
            .map(|(_, s)| s)
            .collect();
        (near, built)
    }
}

/// The dominant wall direction (radians, modulo π/2) of the loops: the
/// length-weighted circular mean of 4θ over steps between cells a few
/// apart along each piece.
fn wall_angle(loops: &[EdgeLoop]) -> f64 {
    let (mut sx, mut sy) = (0.0, 0.0);
    for l in loops {
        for piece in &l.pieces {
            for w in piece.chunks(4).collect::<Vec<_>>().windows(2) {
                let (a, b) = (w[0][0], w[1][0]);
                let (dx, dy) = (b.col as f64 - a.col as f64, b.row as f64 - a.row as f64);
                let len = dx.hypot(dy);
                if len > 0.0 {
                    let t = 4.0 * dy.atan2(dx);
                    sx += len * t.cos();
                    sy += len * t.sin();
                }
            }
        }
    }
    if sx == 0.0 && sy == 0.0 {
        0.0
    } else {
        sy.atan2(sx) / 4.0
    }
}

/// The walls' own directions (radians, modulo a quarter turn) where they
/// differ from `first` (the loops' mean direction, [`wall_angle`], which
/// lands between two wall systems): the peak of a histogram of 1° bins of
/// the loops' 16-cell steps, weighted by length and smoothed over ±2°, and
/// a second peak at least `SECOND_WALL_MIN_GAP` from it with at least
/// `SECOND_WALL_SHARE` of its weight; either left out within 1° of
/// `first`.
fn other_wall_angles(loops: &[EdgeLoop], first: f64) -> Vec<f64> {
    const BINS: usize = 90;
    let mut hist = [0.0f64; BINS];
    for l in loops {
        for piece in &l.pieces {
            // Steps of 16 cells (taken every 4): a raster line's direction
            // to within about 4°, where a 4-cell step takes only a few
            // directions (0°, 14°, 27°, 37°, 45°, ...).
            for w in piece.iter().step_by(4).collect::<Vec<_>>().windows(5) {
                let (a, b) = (w[0], w[4]);
                let (dx, dy) = (b.col as f64 - a.col as f64, b.row as f64 - a.row as f64);
                let len = dx.hypot(dy) / 4.0;
                if len > 0.0 {
                    let deg = dy.atan2(dx).to_degrees().rem_euclid(90.0);
                    hist[(deg as usize).min(BINS - 1)] += len;
                }
            }
        }
    }
    let smooth: Vec<f64> = (0..BINS)
        .map(|i| (0..5).map(|k| hist[(i + BINS + k - 2) % BINS]).sum())
        .collect();
    let gap = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(90.0);
        d.min(90.0 - d)
    };
    let at = |i: usize| i as f64 + 0.5;
    let peak = |skip: Option<usize>| {
        (0..BINS)
            .filter(|&i| skip.is_none_or(|p| gap(at(i), at(p)) >= SECOND_WALL_MIN_GAP))
            .map(|i| (i, smooth[i]))
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
            .filter(|p| p.1 > 0.0)
    };
    let Some(top) = peak(None) else {
        return Vec::new();
    };
    let mut peaks = vec![top.0];
    if let Some(second) = peak(Some(top.0)).filter(|p| p.1 >= SECOND_WALL_SHARE * top.1) {
        peaks.push(second.0);
    }
    // Each peak at its window's mean direction (on the quarter-turn circle).
    let refine = |i: usize| {
        let (mut x, mut y) = (0.0, 0.0);
        for k in 0..5 {
            let j = (i + BINS + k - 2) % BINS;
            let t = (4.0 * at(j)).to_radians();
            x += hist[j] * t.cos();
            y += hist[j] * t.sin();
        }
        (y.atan2(x).to_degrees() / 4.0).rem_euclid(90.0)
    };
    peaks
        .into_iter()
        .map(refine)
        .filter(|&deg| gap(deg, first.to_degrees()) > 1.0)
        .map(f64::to_radians)
        .collect()
}

/// How far from the walls' main direction a second must lie (degrees).
const SECOND_WALL_MIN_GAP: f64 = 8.0;

/// How much wall a second direction needs, as a share of the main one's
/// (0.1: the least that made no plan slower than without the peaks).
const SECOND_WALL_SHARE: f64 = 0.1;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::loops::edge_loops;
    use oxcover_grid::traverse::{GridPoint, cell_center};
    use oxcover_grid::{Cell, Grid, Vector};

    #[test]
    fn a_second_wall_direction_is_found_where_the_walls_hold_one() {
        let none = |m: &Grid<bool>| Grid::new(m.width(), m.height(), false);
        // A bare rectangle: one wall system only.
        let rect = Grid::from_fn(200, 120, |c: Cell| {
            (10..110).contains(&c.row) && (10..190).contains(&c.col)
        });
        let loops = edge_loops(&rect, &none(&rect));
        let bare = other_wall_angles(&loops, wall_angle(&loops));
        assert!(bare.is_empty(), "{bare:?} {}", wall_angle(&loops));
        // The rectangle and a wing 40 cells wide and 150 long at 30° to it:
        // the loops' mean direction lies between the two systems, and both
        // are found.
        let (dir, normal) = (
            Vector::new(30f64.to_radians().cos(), 30f64.to_radians().sin()),
            Vector::new(-30f64.to_radians().sin(), 30f64.to_radians().cos()),
        );
        let wing = Grid::from_fn(400, 300, |c: Cell| {
            let d = cell_center(c) - GridPoint::new(200.0, 200.0);
            rect.get(c).copied().unwrap_or(false)
                || (d.dot(&normal).abs() < 20.0 && d.dot(&dir).abs() < 75.0)
        });
        let loops = edge_loops(&wing, &none(&wing));
        let mut found: Vec<f64> = other_wall_angles(&loops, wall_angle(&loops))
            .into_iter()
            .map(f64::to_degrees)
            .collect();
        found.sort_by(f64::total_cmp);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0] < 2.0 || found[0] > 88.0, "{found:?}");
        assert!((found[1] - 30.0).abs() < 3.0, "{found:?}");
    }
}
