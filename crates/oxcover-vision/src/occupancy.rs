//! Occupancy grid updates (Pavlíček 2002, §2.1–2.2): the paper's Bayes formula,
//! kept internally as log-odds, and the accumulation of visibility along
//! rays from the robot.
//!
//! **Bayes.** With `P(R | Emp) = 1 − P(R | Occ)`,
//! `P(Occ | R) = P(R|Occ) P(Occ) / (P(R|Occ) P(Occ) + P(R|Emp) P(Emp))`.
//! In log-odds `l = ln(P / (1 − P))` this is `l ← l + ln(P(R|Occ) / P(R|Emp))`
//! ([`bayes`] is the formula itself; [`LogOddsGrid::observe`] the log-odds
//! form, clamped so that no cell becomes certain).
//!
//! **Visibility.** Floor-coloured pixels can appear on an obstacle above its
//! base; a cell seen past an obstacle must not be believed free. The paper
//! walks each ray from the robot outwards and combines a cell's probability
//! with the one accumulated before it, by a product or recursively by
//! Bayes. We read its probabilities in these two formulas as those of the
//! cell being *empty* (seen through), `E = 1 − P(Occ)`: only so does an
//! occupied cell darken what lies behind it. Along a ray,
//!
//! - product: `E_acc ← E_acc · E`, and a cell's final `E_new = E · E_acc`
//!   (accumulated before it). Cells that read free (`P(Occ) < 0.5`) count
//!   with `E = 1`: taken literally, the product of sixty floor cells each
//!   0.95 empty is 0.05, and everything beyond three metres of clear floor
//!   would read occupied;
//! - recursive Bayes: `E_acc ← E·E_acc / (E·E_acc + (1 − E)(1 − E_acc))`,
//!   `E_new` as above.
//!
//! The final occupancy is `1 − E_new`. The product starts from `E_acc = 1`
//! and makes anything past one dark cell dark. The Bayes form starts from
//! `E_acc = 0.5` (no evidence; 1 would be a certainty no reading moves) and
//! weighs evidence: a strongly occupied cell hides the cells right behind
//! it, a weakly occupied one after clear floor does not, and free-looking
//! cells further behind count again as evidence of a clear view (so a wall
//! face of floor colour two cells deep reads free again). The product is the
//! safer of the two for this purpose.

use oxcover_grid::{Cell, Grid, MapFrame, Point};
use serde::{Deserialize, Serialize};

/// The paper's Bayes update of `P(Occ)` by a reading with `P(R | Occ)`.
#[must_use]
pub fn bayes(prior: f64, p_r_occ: f64) -> f64 {
    let num = p_r_occ * prior;
    let den = num + (1.0 - p_r_occ) * (1.0 - prior);
    if den > 0.0 { num / den } else { prior }
}

/// Occupancy as log-odds per cell, prior 0.5 (log-odds 0).
#[derive(Clone, Debug, PartialEq)]
pub struct LogOddsGrid {
    frame: MapFrame,
    l: Grid<f64>,
    /// Log-odds are kept within `±clamp`.
    pub clamp: f64,
}

impl LogOddsGrid {
    /// An unknown grid (every cell 0.5) over `frame`.
    #[must_use]
    pub fn new(frame: MapFrame) -> Self {
        Self {
            l: Grid::new(frame.width(), frame.height(), 0.0),
            frame,
            clamp: 12.0,
        }
    }

    /// The frame.
    #[must_use]
    pub fn frame(&self) -> &MapFrame {
        &self.frame
    }

    /// Bayes update of `cell` by a reading with `P(R | Occ) = p`.
    pub fn observe(&mut self, cell: Cell, p: f64) {
        let p = p.clamp(1e-6, 1.0 - 1e-6);
        let l = &mut self.l[cell];
        *l = (*l + (p / (1.0 - p)).ln()).clamp(-self.clamp, self.clamp);
    }

    /// `P(Occ)` of a cell.
    #[must_use]
    pub fn probability(&self, cell: Cell) -> f64 {
        1.0 - 1.0 / (1.0 + self.l[cell].exp())
    }

    /// `P(Occ)` of every cell.
    #[must_use]
    pub fn probabilities(&self) -> Grid<f64> {
        Grid::from_fn(self.l.width(), self.l.height(), |c| self.probability(c))
    }
}

/// How visibility is accumulated along a ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Visibility {
    /// `E_acc ← E_acc · E`.
    Product,
    /// `E_acc ← E E_acc / (E E_acc + (1 − E)(1 − E_acc))`.
    Bayes,
}

/// The final grid from `p_occ` (per cell `P(Occ)`, NaN where this view saw
/// nothing) seen from `robot`: every seen cell's emptiness combined with
/// the emptiness accumulated before it along the ray from the robot,
/// `1 − E · E_acc` (the paper's formula; see [`accumulated`]).
#[must_use]
pub fn with_visibility(
    p_occ: &Grid<f64>,
    frame: &MapFrame,
    robot: Point,
    mode: Visibility,
) -> Grid<f64> {
    let acc = accumulated(p_occ, frame, robot, mode);
    Grid::from_fn(p_occ.width(), p_occ.height(), |c| {
        1.0 - (1.0 - p_occ[c]) * acc[c]
    })
}

/// The emptiness accumulated along the ray from `robot` up to (not
/// including) each seen cell: rays to every cell of the border, sampled at
/// a quarter cell, a cell taking the value of the first ray reaching it.
/// Unseen cells (NaN in `p_occ`: the blind zone at the camera's feet,
/// outside its field) let the view through and stay NaN.
#[must_use]
pub fn accumulated(
    p_occ: &Grid<f64>,
    frame: &MapFrame,
    robot: Point,
    mode: Visibility,
) -> Grid<f64> {
    let (w, h) = (p_occ.width(), p_occ.height());
    let mut out = Grid::new(w, h, f64::NAN);
    let res = frame.resolution();
    let mut border: Vec<Cell> = Vec::new();
    for c in 0..w {
        border.push(Cell::new(0, c));
        border.push(Cell::new(h - 1, c));
    }
    for r in 0..h {
        border.push(Cell::new(r, 0));
        border.push(Cell::new(r, w - 1));
    }
    for target in border {
        let t = frame.cell_center(target);
        let len = (t - robot).norm();
        let n = (len / (res / 4.0)).ceil().max(1.0) as usize;
        // Nothing blocks the robot's own position (product); no evidence
        // either way yet (Bayes: 1 would be certainty no reading could move).
        let mut acc = match mode {
            Visibility::Product => 1.0,
            Visibility::Bayes => 0.5,
        };
        let mut last: Option<Cell> = None;
        for k in 0..=n {
            let q = robot + (t - robot) * (k as f64 / n as f64);
            let Some(cell) = frame.cell_at(&q) else {
                continue;
            };
            if last == Some(cell) {
                continue;
            }
            last = Some(cell);
            if p_occ[cell].is_nan() {
                continue;
            }
            let e = 1.0 - p_occ[cell];
            if out[cell].is_nan() {
                out[cell] = acc;
            }
            acc = match mode {
                // A cell that reads free does not hide what is behind it.
                Visibility::Product => acc * if p_occ[cell] < 0.5 { 1.0 } else { e },
                Visibility::Bayes => {
                    let num = e * acc;
                    let den = num + (1.0 - e) * (1.0 - acc);
                    if den > 0.0 { num / den } else { acc }
                }
            };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bayes_matches_a_hand_computed_sequence() {
        // Prior 0.5; readings with P(R|Occ) = 0.8, 0.8, 0.3:
        // 0.8·0.5 / (0.8·0.5 + 0.2·0.5) = 0.8;
        // 0.8·0.8 / (0.64 + 0.2·0.2) = 0.64 / 0.68 = 0.941176…;
        // 0.3·0.941176 / (0.3·0.941176 + 0.7·0.058824) = 0.872727…
        let mut p = 0.5;
        for (r, want) in [
            (0.8, 0.8),
            (0.8, 0.64 / 0.68),
            (0.3, 0.282_352_94 / 0.323_529_41),
        ] {
            p = bayes(p, r);
            assert!((p - want).abs() < 1e-6, "{p} vs {want}");
        }
        // The log-odds grid gives the same numbers.
        let frame = MapFrame::new(1, 1, 1.0, Point::new(0.0, 0.0));
        let mut g = LogOddsGrid::new(frame);
        let c = Cell::new(0, 0);
        for r in [0.8, 0.8, 0.3] {
            g.observe(c, r);
        }
        assert!((g.probability(c) - p).abs() < 1e-9);
    }

    #[test]
    fn visibility_stops_at_obstacles() {
        // One row: robot in cell 0, free, free, an obstacle, then cells that
        // look free (floor colour on the obstacle's face).
        let frame = MapFrame::new(8, 1, 1.0, Point::new(0.0, 0.0));
        let robot = Point::new(0.5, 0.5);
        let row = |wall: f64| Grid::from_fn(8, 1, |c| if c.col == 3 { wall } else { 0.1 });
        let behind_dark = |v: &Grid<f64>| (4..8).all(|c| v[Cell::new(0, c)] > 0.5);
        // The product: past one dark cell, nothing is believed free.
        let v = with_visibility(&row(0.95), &frame, robot, Visibility::Product);
        assert!(v[Cell::new(0, 1)] < 0.3 && v[Cell::new(0, 3)] > 0.9);
        assert!(behind_dark(&v), "{v:?}");
        // Recursive Bayes: a sure obstacle hides the cells right behind it,
        // but free-looking cells further on count again as evidence of a
        // clear line of sight, and two cells later the row reads free.
        let v = with_visibility(&row(0.9999), &frame, robot, Visibility::Bayes);
        assert!(v[Cell::new(0, 1)] < 0.3 && v[Cell::new(0, 3)] > 0.9);
        assert!(
            v[Cell::new(0, 4)] > 0.5 && v[Cell::new(0, 5)] > 0.5,
            "{v:?}"
        );
        assert!(v[Cell::new(0, 7)] < 0.5, "{v:?}");
        // ... a doubtful one after clear floor does not.
        let v = with_visibility(&row(0.6), &frame, robot, Visibility::Bayes);
        assert!(!behind_dark(&v));
    }
}
