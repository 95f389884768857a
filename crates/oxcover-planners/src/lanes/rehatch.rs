//! Chains re-hatched: the parts of a region that one angle does not suit.
//!
//! A region's lanes lie at one angle, so a corridor's arm or a strip beside
//! a room hatched across turns every few lanes. Each chain is cut where its
//! lanes' extent jumps (a band and the arm that leaves it share a chain
//! when each line's run overlaps the next one to one), and each piece whose
//! links and U-turns are a tenth of its time or more has its area (the
//! lane-mask cells within half a line step of its lanes) hatched again at
//! the wall directions and at the area's own long axis. Where the model
//! finds the pieces so treated enough faster than the chain
//! ([`rehatch_taken`]) they replace it, and the order places them like any
//! other chain.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): without it
//! 0.9 % (ipa) / 2.2 % (ROS) slower.

use std::f64::consts::PI;

use rayon::prelude::*;

use oxcover_grid::traverse::{GridPoint, cell_center, segment_distance};
use oxcover_grid::{Cell, Grid, Vector};

use super::layout::{Chain, Lane, Layout, chains_at, modelled_time};
use crate::detours::cell_box;
use crate::time::TimeModel;

/// What re-hatching a chain's area at another angle needs.
pub(super) struct Hatch<'a> {
    plannable: &'a Grid<bool>,
    lane_mask: &'a Grid<bool>,
    spacing: f64,
    inset: f64,
    time: &'a TimeModel,
}

/// Fewest lanes a chain must have to be re-hatched.
const REHATCH_MIN_LANES: usize = 3;

/// How much faster (modelled) a re-hatched area must be than its chain
/// (0.8: of 0.8, 0.9 and 0.95, all alike in mean, the one slowing the
/// fewest maps and by the least).
const REHATCH_GAIN: f64 = 0.8;

/// The margin for a re-hatch that lays the area's lanes anew, at most
/// [`REHATCH_LANES`] of the chain's and two fewer at least: fewer lanes
/// are fewer U-turns whatever the model leaves out (a chain merely cut
/// into pieces loses transits the model does not count).
const LOOSE_REHATCH_GAIN: f64 = 0.9;

/// The largest share of a chain's lanes a re-hatch may lay to be taken
/// at [`LOOSE_REHATCH_GAIN`].
const REHATCH_LANES: f64 = 0.8;

/// Whether pieces modelled at `total` seconds replace a chain modelled at
/// `here`: by [`REHATCH_GAIN`], or by [`LOOSE_REHATCH_GAIN`] where they
/// lay `lanes_out` lanes for the chain's `lanes_in`, at most
/// [`REHATCH_LANES`] of them and two fewer at least.
fn rehatch_taken(total: f64, here: f64, lanes_in: usize, lanes_out: usize) -> bool {
    let relaid = lanes_out as f64 <= REHATCH_LANES * lanes_in as f64 && lanes_out + 2 <= lanes_in;
    total < REHATCH_GAIN * here || (relaid && total < LOOSE_REHATCH_GAIN * here)
}

impl<'a> Hatch<'a> {
    /// Re-hatching over `layout`'s region, mask and lines.
    pub(super) fn new(layout: &Layout<'a>) -> Self {
        Self {
            plannable: layout.plannable,
            lane_mask: &layout.mask.cells,
            spacing: layout.spacing,
            inset: layout.inset,
            time: layout.time,
        }
    }

    /// Each chain's area (the lane-mask cells within half a line step of
    /// one of its lanes) re-hatched at the angle of `angles` whose chains
    /// the model finds fastest there, where that beats the chain by
    /// [`REHATCH_GAIN`]; and the modelled seconds saved.
    /// `step` is the distance between the chains' lines ([`chains_at`]).
    pub(super) fn rehatch(
        &self,
        chains: Vec<Chain>,
        step: f64,
        angles: &[f64],
    ) -> (Vec<Chain>, f64) {
        let replaced: Vec<Option<(Vec<Chain>, f64)>> = chains
            .par_iter()
            .map(|chain| self.improve(chain, step, angles))
            .collect();
        let mut out = Vec::with_capacity(chains.len());
        let mut saving = 0.0;
        for (chain, new) in chains.into_iter().zip(replaced) {
            match new {
                Some((v, s)) => {
                    out.extend(v);
                    saving += s;
                }
                None => out.push(chain),
            }
        }
        (out, saving)
    }

    /// Whether `chain`'s links and turns take as much of its time as a
    /// re-hatch must save at the looser margin: only they can be saved
    /// (another angle's lanes cover the same area, so are about as long).
    fn may_gain(&self, chain: &Chain) -> bool {
        let links = chain.lanes.len().saturating_sub(1) as f64;
        let overhead = self.time.time(links * self.spacing, links * PI)
            + self.time.time(self.spacing, PI / 2.0);
        overhead >= (1.0 - LOOSE_REHATCH_GAIN) * chain.time(self.time, self.spacing)
    }

    /// `chain` cut into its pieces ([`pieces_at_jumps`]), each re-hatched
    /// where the model finds that faster (a piece with its links and turns
    /// as [`Self::may_gain`] asks), if the pieces together beat the chain
    /// as [`rehatch_taken`] asks; and the modelled seconds saved.
    fn improve(&self, chain: &Chain, step: f64, angles: &[f64]) -> Option<(Vec<Chain>, f64)> {
        if chain.lanes.len() < REHATCH_MIN_LANES {
            return None;
        }
        let pieces = pieces_at_jumps(chain);
        let whole = pieces.len() == 1;
        if whole && !self.may_gain(chain) {
            return None;
        }
        let mut here = if whole {
            None
        } else {
            Some(self.hatch_area(chain, step, &[])?.0)
        };
        let mut total = 0.0;
        let mut out = Vec::new();
        for piece in pieces {
            let eligible = piece.lanes.len() >= REHATCH_MIN_LANES && self.may_gain(&piece);
            let (own, alternative) =
                self.hatch_area(&piece, step, if eligible { angles } else { &[] })?;
            if whole {
                here = Some(own);
            }
            match alternative {
                Some((t, chains)) if t < own => {
                    total += t;
                    out.extend(chains);
                }
                _ => {
                    total += own;
                    out.push(piece);
                }
            }
        }
        let here = here?;
        let lanes_out = out.iter().map(|c| c.lanes.len()).sum();
        rehatch_taken(total, here, chain.lanes.len(), lanes_out).then_some((out, here - total))
    }

    /// The modelled seconds of `chain` over its area (the lane-mask cells
    /// within half a line step, `step`, of its lanes; detours for what its
    /// lanes leave of it), and the fastest hatching of that area at one of
    /// `angles` with its seconds. Worked out in the area's bounding box.
    #[allow(clippy::type_complexity)]
    fn hatch_area(
        &self,
        chain: &Chain,
        step: f64,
        angles: &[f64],
    ) -> Option<(f64, Option<(f64, Vec<Chain>)>)> {
        let (w, h) = (self.lane_mask.width(), self.lane_mask.height());
        let half = step / 2.0 + 1e-9;
        let ends: Vec<GridPoint> = chain.lanes.iter().flat_map(|l| [l.a, l.b]).collect();
        // A cell's margin round the area: a lane may graze a corner of the
        // cell beside the one it was sampled in.
        let (rows, cols) = cell_box(&ends, half + 1.0, (w, h));
        let (r0, c0) = (rows.start, cols.start);
        let (bw, bh) = (cols.len(), rows.len());
        if bw == 0 || bh == 0 {
            return None;
        }
        let mut mask = Grid::new(bw, bh, false);
        for l in &chain.lanes {
            let (lane_rows, lane_cols) = cell_box(&[l.a, l.b], half, (w, h));
            for row in lane_rows {
                for col in lane_cols.clone() {
                    let c = Cell::new(row, col);
                    if self.lane_mask[c] && segment_distance(l.a, l.b, cell_center(c)) <= half {
                        mask[Cell::new(row - r0, col - c0)] = true;
                    }
                }
            }
        }
        let area = mask.count_true() as f64;
        if area == 0.0 {
            return None;
        }
        let cost = |chains: &[Chain], step: f64| {
            modelled_time(chains, step, area, self.spacing, self.time)
        };
        let here = cost(std::slice::from_ref(chain), step);
        if angles.is_empty() {
            return Some((here, None));
        }
        let plannable = Grid::from_fn(bw, bh, |c: Cell| {
            self.plannable[Cell::new(c.row + r0, c.col + c0)]
        });
        let mut best: Option<(f64, Vec<Chain>)> = None;
        let mut angles = angles.to_vec();
        let axis = long_axis(&mask);
        if angles.iter().all(|&a| angle_gap(a, axis) > AXIS_MIN_GAP) {
            angles.push(axis);
        }
        for &theta in &angles {
            let (chains, step) =
                chains_at(&plannable, &mask, None, theta, self.spacing, self.inset);
            let t = cost(&chains, step);
            if best.as_ref().is_none_or(|b| t < b.0) {
                best = Some((t, chains));
            }
        }
        let shift = Vector::new(c0 as f64, r0 as f64);
        let best = best.map(|(t, chains)| {
            let chains = chains
                .into_iter()
                .map(|c| Chain {
                    lanes: c
                        .lanes
                        .into_iter()
                        .map(|l| Lane {
                            a: l.a + shift,
                            b: l.b + shift,
                        })
                        .collect(),
                })
                .collect();
            (t, chains)
        });
        Some((here, best))
    }
}

/// How far (radians) an area's long axis must lie from every wall
/// direction to be tried as a re-hatching angle of its own (0.5°: of 0.5°,
/// 2° and 5° the fastest on the ROS maps).
const AXIS_MIN_GAP: f64 = 0.5 * PI / 180.0;

/// The angle between two lane directions (lines, so modulo π).
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(PI);
    d.min(PI - d)
}

/// The direction of `mask`'s long axis (its cells' principal axis; in the
/// grid's frame, as the lane angles): an arm's or a corridor's length.
fn long_axis(mask: &Grid<bool>) -> f64 {
    let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for c in mask.true_cells() {
        n += 1.0;
        sx += c.col as f64;
        sy += c.row as f64;
    }
    if n == 0.0 {
        return 0.0;
    }
    let (mx, my) = (sx / n, sy / n);
    let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
    for c in mask.true_cells() {
        let (dx, dy) = (c.col as f64 - mx, c.row as f64 - my);
        xx += dx * dx;
        yy += dy * dy;
        xy += dx * dy;
    }
    0.5 * (2.0 * xy).atan2(xx - yy)
}

/// Least overlap, as a share of the longer lane, of two neighbouring lanes
/// of one piece of a chain (below it, an arm leaves a band).
const JUMP_OVERLAP: f64 = 0.5;

/// `chain`'s lanes cut into runs where a lane overlaps its neighbour by
/// less than [`JUMP_OVERLAP`] of the longer of the two (along the lanes):
/// a band and the arm that leaves it, which no single angle suits.
fn pieces_at_jumps(chain: &Chain) -> Vec<Chain> {
    let mut out = Vec::new();
    let mut run: Vec<Lane> = Vec::new();
    for &lane in &chain.lanes {
        if let Some(&last) = run.last() {
            let d = (last.b - last.a) / last.length().max(1e-12);
            let span = |l: Lane| {
                let (u, v) = (l.a.coords.dot(&d), l.b.coords.dot(&d));
                (u.min(v), u.max(v))
            };
            let ((a0, a1), (b0, b1)) = (span(last), span(lane));
            if a1.min(b1) - a0.max(b0) < JUMP_OVERLAP * (a1 - a0).max(b1 - b0) {
                out.push(Chain {
                    lanes: std::mem::take(&mut run),
                });
            }
        }
        run.push(lane);
    }
    if !run.is_empty() {
        out.push(Chain { lanes: run });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::layout::LINE_MARGIN;
    use crate::lanes::loops::OUTSET;
    use oxcover_grid::traverse::cell_of;

    /// The re-hatching of a lane mask `mask` hatched at `theta`, tool 3
    /// cells, contract speeds.
    fn rehatched(mask: &Grid<bool>, theta: f64) -> (Vec<Chain>, Vec<Chain>, f64) {
        let plannable = Grid::new(mask.width(), mask.height(), true);
        let spacing = 2.0 * (9.0f64 - 1.0 / 64.0).sqrt() * 0.999;
        let inset = 3.0 - OUTSET - LINE_MARGIN;
        let time = TimeModel {
            linear_speed: 6.0,
            angular_speed: 0.52,
        };
        let hatch = Hatch {
            plannable: &plannable,
            lane_mask: mask,
            spacing,
            inset,
            time: &time,
        };
        let (chains, step) = chains_at(&plannable, mask, None, theta, spacing, inset);
        let (new, saving) = hatch.rehatch(chains.clone(), step, &[0.0, PI / 2.0]);
        (chains, new, saving)
    }

    /// How many lanes of `chains` run along y and are longer than `min`.
    fn vertical_lanes(chains: &[Chain], min: f64) -> usize {
        chains
            .iter()
            .flat_map(|c| &c.lanes)
            .filter(|l| (l.b.x - l.a.x).abs() < 1e-9 && l.length() > min)
            .count()
    }

    /// An H of lanes: two 12-cell-wide arms down the sides of a 120 × 102
    /// box, joined by a 12-cell crossbar. Hatched along x, the arms above
    /// and below the bar are four chains of 12-cell lanes (a U-turn every
    /// 12 cells); re-hatched, each is a few lanes down the arm, and the
    /// bar's chain stays as it was.
    #[test]
    fn arms_hatched_across_are_rehatched_along() {
        let mask = Grid::from_fn(120, 102, |c: Cell| {
            c.col < 12 || c.col >= 108 || (45..57).contains(&c.row)
        });
        let short = |c: &Chain| c.lanes.len() >= 5 && c.lanes.iter().all(|l| l.length() < 13.0);
        let (before, after, saving) = rehatched(&mask, 0.0);
        assert_eq!(before.iter().filter(|c| short(c)).count(), 4, "{before:?}");
        assert!(saving > 0.0);
        assert_eq!(after.iter().filter(|c| short(c)).count(), 0, "{after:?}");
        let down = vertical_lanes(&after, 40.0);
        assert!(down >= 8, "{after:?}");
        // The bar's chain is kept, and every lane stays in the mask.
        let bar = |c: &&Chain| c.lanes.iter().all(|l| l.length() > 100.0);
        assert_eq!(before.iter().find(bar), after.iter().find(bar));
        for l in after.iter().flat_map(|c| &c.lanes) {
            for k in 0..=20 {
                let p = l.a + (l.b - l.a) * (f64::from(k) / 20.0);
                assert!(cell_of(&mask, p).is_some_and(|c| mask[c]), "{l:?}");
            }
        }
        // Far fewer lanes, so far fewer U-turns.
        let lanes = |v: &[Chain]| v.iter().map(|c| c.lanes.len()).sum::<usize>();
        assert!(
            2 * lanes(&after) < lanes(&before),
            "{} {}",
            lanes(&after),
            lanes(&before)
        );
    }

    /// A wide aisle, 90 × 150 cells, hatched across (along x): 26 lanes of
    /// about 85 cells. Along y it takes 16 lanes of about 145: the model
    /// finds that about a tenth faster (the drive is the same, only 10
    /// U-turns go), under the fifth asked, but so many lanes fewer that
    /// the looser margin takes it.
    #[test]
    fn a_wide_aisle_hatched_across_is_rehatched_along() {
        let mask = Grid::new(90, 150, true);
        let (before, after, saving) = rehatched(&mask, 0.0);
        assert_eq!(before.len(), 1, "{before:?}");
        let time = TimeModel {
            linear_speed: 6.0,
            angular_speed: 0.52,
        };
        let spacing = 2.0 * (9.0f64 - 1.0 / 64.0).sqrt() * 0.999;
        let here = before[0].time(&time, spacing);
        assert!(
            saving > 0.1 * here && saving < 0.2 * here,
            "{saving} of {here}"
        );
        let lanes = |v: &[Chain]| v.iter().map(|c| c.lanes.len()).sum::<usize>();
        assert!(
            5 * lanes(&after) <= 4 * lanes(&before),
            "{} {}",
            lanes(&after),
            lanes(&before)
        );
        assert_eq!(vertical_lanes(&after, 100.0), lanes(&after), "{after:?}");
    }

    /// The two margins: a fifth faster always; a tenth faster only with
    /// at most four fifths of the lanes and two fewer at least (a chain
    /// merely cut into its pieces keeps its lanes and is not taken).
    #[test]
    fn the_looser_margin_asks_for_fewer_lanes() {
        assert!(rehatch_taken(79.0, 100.0, 10, 10));
        assert!(!rehatch_taken(85.0, 100.0, 10, 10));
        assert!(rehatch_taken(85.0, 100.0, 10, 8));
        assert!(!rehatch_taken(85.0, 100.0, 10, 9));
        assert!(!rehatch_taken(85.0, 100.0, 3, 2));
        assert!(rehatch_taken(85.0, 100.0, 3, 1));
        assert!(!rehatch_taken(91.0, 100.0, 10, 2));
    }

    /// An L: a 120 × 12 band along x and a 12 × 90 arm down from its east
    /// end. Hatched along x, band and arm are one chain (each line's run
    /// overlaps the next one to one); cut where the lanes shrink from 120
    /// to 12 cells, the arm is re-hatched down its length and the band's
    /// two lanes stay.
    #[test]
    fn an_arm_that_shares_a_chain_with_its_band_is_cut_off_and_rehatched() {
        let mask = Grid::from_fn(120, 102, |c: Cell| c.row < 12 || c.col >= 108);
        let (before, after, saving) = rehatched(&mask, 0.0);
        assert_eq!(before.len(), 1, "{before:?}");
        let pieces = pieces_at_jumps(&before[0]);
        let lens: Vec<usize> = pieces.iter().map(|c| c.lanes.len()).collect();
        assert_eq!(lens[0], 2, "{lens:?}");
        assert_eq!(lens.iter().sum::<usize>(), before[0].lanes.len());
        assert!(saving > 0.0);
        assert_eq!(after.iter().find(|c| c.lanes.len() == 2), Some(&pieces[0]));
        let down = vertical_lanes(&after, 80.0);
        assert!(down >= 2, "{after:?}");
        assert!(
            after
                .iter()
                .flat_map(|c| &c.lanes)
                .all(|l| l.length() > 80.0),
            "{after:?}"
        );
    }

    /// A band 12 cells wide and 150 long running at 30° to the grid:
    /// neither wall direction of the test (0° and 90°) suits it, its long
    /// axis does. Hatched across (at 120°), its lanes are 12 cells long;
    /// re-hatched, they run along it.
    #[test]
    fn a_slanted_band_is_rehatched_along_its_own_axis() {
        let (dir, normal) = (
            Vector::new(30f64.to_radians().cos(), 30f64.to_radians().sin()),
            Vector::new(-30f64.to_radians().sin(), 30f64.to_radians().cos()),
        );
        let centre = GridPoint::new(80.0, 50.0);
        let mask = Grid::from_fn(160, 100, |c: Cell| {
            let d = cell_center(c) - centre;
            d.dot(&normal).abs() < 6.0 && d.dot(&dir).abs() < 75.0
        });
        assert!(angle_gap(long_axis(&mask), 30f64.to_radians()) < 0.5f64.to_radians());
        let (before, after, saving) = rehatched(&mask, 120f64.to_radians());
        let lanes = |v: &[Chain]| v.iter().map(|c| c.lanes.len()).sum::<usize>();
        assert!(lanes(&before) >= 20, "{before:?}");
        assert!(saving > 0.0);
        assert!(lanes(&after) <= 4, "{after:?}");
        for l in after.iter().flat_map(|c| &c.lanes) {
            let d = l.b - l.a;
            assert!(
                angle_gap(d.y.atan2(d.x), 30f64.to_radians()) < 1f64.to_radians(),
                "{l:?}"
            );
            assert!(l.length() > 100.0, "{l:?}");
        }
        // An axis within half a degree of a wall direction adds nothing.
        assert!(angle_gap(PI - 0.001, 0.0) < AXIS_MIN_GAP);
    }

    /// A plain band hatched along its length is left as it is.
    #[test]
    fn a_band_hatched_along_is_kept() {
        let mask = Grid::from_fn(120, 30, |c: Cell| (4..26).contains(&c.row));
        let (before, after, saving) = rehatched(&mask, 0.0);
        assert_eq!(before, after);
        assert_eq!(saving, 0.0);
        // Hatched across instead, it is re-hatched along.
        let (before, after, saving) = rehatched(&mask, PI / 2.0);
        assert!(
            saving > 0.0 && after.len() == 1 && after[0].lanes.len() < 6,
            "{before:?} {after:?}"
        );
    }
}
