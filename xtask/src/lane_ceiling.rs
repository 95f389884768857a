//! The efficiency page's per-map **lane-and-loop ceiling**: what the
//! contract's time model leaves of a map's time efficiency for a plan of
//! straight lanes and wall loops that wastes nothing else.
//!
//! The model, for the reachable admissible cells (the C-space region the
//! robot drives in) of the page's problem:
//!
//! - the drive is the bound itself (`bound_time_s`: every coverable cell
//!   swept once by the tool's width, no overlap, no link, no transit);
//! - one loop, a full turn (2π), round each boundary of the region: its
//!   outline and every hole in it (an obstacle the region surrounds). With
//!   robot radius = tool radius the cells along an obstacle are within
//!   reach only of the region's edge beside them, so a path must trace
//!   every edge, and a closed edge turns by a full turn at least;
//! - straight lanes at one angle, the tool's width apart, passing every
//!   hole for free (no turn, no way round): a line across the region with
//!   its holes filled in, cut into runs where it leaves the region, each
//!   run at least a tool width long is one lane, and each lane after the
//!   first costs a half turn (π) to enter;
//! - the angle (whole degrees) with the fewest lanes.
//!
//! Beside it, the **cut** ceiling: the same with every hole cutting the
//! lines that cross it (a lane is a run of a line across the region as it
//! is, holes left open), again at the angle with the fewest lanes. Real
//! lanes stop at a building or a rack; the planner's lanes pass only small
//! islands, bending round them, which costs turning too. Optimistic in the
//! same terms as the first, and no bound either: a plan whose parts lie at
//! different angles may need fewer lanes than any one angle's.
//!
//! That is a model of the pattern, optimistic in every term it leaves out
//! (overlap, links, transits, the corners of non-convex outlines, the
//! wiggles of raster walls, the way round an island), not a proof that no
//! path does better: a path may join two lanes with less than a half turn
//! where they do not face each other.

use std::f64::consts::PI;

use oxcover::planners::{CoverageProblem, Start, TimeModel};
use oxcover_grid::{Cell, DiscRobot, Grid, OccupancyGrid};

/// One map's ceiling.
#[derive(Clone, Debug)]
pub struct Ceiling {
    /// The contract's `bound_time_s` for the map's coverable cells.
    pub bound_s: f64,
    /// Holes in the region (obstacles it surrounds).
    pub holes: usize,
    /// Lanes at the best angle.
    pub lanes: usize,
    /// The best angle, degrees.
    pub angle_deg: u32,
    /// `bound / (bound + turning)`, turning = (2π · (holes + 1) + π · (lanes − 1)) / w.
    pub efficiency: f64,
    /// Lanes at the best angle when the holes cut them.
    pub cut_lanes: usize,
    /// The cut ceiling: as `efficiency`, with `cut_lanes` lanes.
    pub cut_efficiency: f64,
}

/// The ceiling of `map` for robot = tool radius `radius` (metres), starting
/// in the largest admissible region, as the efficiency page plans it.
///
/// # Errors
/// When the map has no admissible cell for this robot.
pub fn ceiling(map: &OccupancyGrid, radius: f64, time: &TimeModel) -> anyhow::Result<Ceiling> {
    let problem = CoverageProblem::new(map, DiscRobot::new(radius, radius)?, Start::LargestRegion)?;
    let res = map.resolution();
    let cells = problem.cells();
    let area = cells.coverable.count_true() as f64 * res * res;
    let swept = (area - std::f64::consts::PI * radius * radius).max(0.0);
    let bound_s = time.time(swept / (2.0 * radius), 0.0);
    let region = &cells.reachable;
    let (filled, holes) = fill_holes(region);
    let spacing = 2.0 * radius / res;
    let fewest = |mask: &Grid<bool>| {
        (0..180)
            .map(|deg| (lanes_at(mask, f64::from(deg).to_radians(), spacing), deg))
            .min()
            .unwrap_or((0, 0))
    };
    let (lanes, angle_deg) = fewest(&filled);
    let (cut_lanes, _) = fewest(region);
    let efficiency = |lanes: usize| {
        let turning = 2.0 * PI * (holes as f64 + 1.0) + PI * lanes.saturating_sub(1) as f64;
        bound_s / (bound_s + time.time(0.0, turning))
    };
    Ok(Ceiling {
        bound_s,
        holes,
        lanes,
        angle_deg,
        efficiency: efficiency(lanes),
        cut_lanes,
        cut_efficiency: efficiency(cut_lanes),
    })
}

/// `region` with its holes filled, and how many holes there were: the
/// 8-connected components of the cells outside it that do not reach the
/// grid's edge (the holes of a 4-connected region).
#[must_use]
pub fn fill_holes(region: &Grid<bool>) -> (Grid<bool>, usize) {
    let (w, h) = (region.width(), region.height());
    let mut seen = region.clone();
    let mut filled = region.clone();
    let mut holes = 0;
    let mut stack = Vec::new();
    for start in region.cells() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut members = Vec::new();
        let mut edge = false;
        while let Some(c) = stack.pop() {
            members.push(c);
            edge |= c.row == 0 || c.col == 0 || c.row + 1 == h || c.col + 1 == w;
            for (_, n) in region.neighbours8(c) {
                if !seen[n] {
                    seen[n] = true;
                    stack.push(n);
                }
            }
        }
        if !edge {
            holes += 1;
            for c in members {
                filled[c] = true;
            }
        }
    }
    (filled, holes)
}

/// Lanes at angle `theta` (radians from the grid's x axis): lines
/// `spacing` cells apart across `mask` (the first half a spacing in from
/// the mask's extent), sampled every half cell, each run of at least
/// `spacing` cells inside the mask one lane.
#[must_use]
pub fn lanes_at(mask: &Grid<bool>, theta: f64, spacing: f64) -> usize {
    let (dir, normal) = ((theta.cos(), theta.sin()), (-theta.sin(), theta.cos()));
    let (mut lo, mut hi) = (
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for c in mask.true_cells() {
        let (x, y) = (c.col as f64 + 0.5, c.row as f64 + 0.5);
        let (u, v) = (x * dir.0 + y * dir.1, x * normal.0 + y * normal.1);
        lo = (lo.0.min(u), lo.1.min(v));
        hi = (hi.0.max(u), hi.1.max(v));
    }
    if lo.0 > hi.0 {
        return 0;
    }
    let step = 0.5;
    let min_samples = (spacing / step).ceil() as usize;
    let inside = |x: f64, y: f64| {
        x >= 0.0
            && y >= 0.0
            && mask
                .get(Cell::new(y as usize, x as usize))
                .copied()
                .unwrap_or(false)
    };
    let mut lanes = 0;
    let mut v = lo.1 + spacing / 2.0;
    loop {
        let mut run = 0usize;
        let mut u = lo.0 - step;
        while u <= hi.0 + step {
            let (x, y) = (u * dir.0 + v * normal.0, u * dir.1 + v * normal.1);
            if inside(x, y) {
                run += 1;
            } else {
                if run >= min_samples {
                    lanes += 1;
                }
                run = 0;
            }
            u += step;
        }
        if run >= min_samples {
            lanes += 1;
        }
        if v + spacing / 2.0 >= hi.1 {
            break;
        }
        v += spacing;
    }
    lanes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: &[&str]) -> Grid<bool> {
        Grid::from_fn(rows[0].len(), rows.len(), |c| {
            rows[c.row].as_bytes()[c.col] == b'.'
        })
    }

    #[test]
    fn a_ring_has_one_hole_and_a_bar_none() {
        let ring = grid(&["#####", "#...#", "#.#.#", "#...#", "#####"]);
        let (filled, holes) = fill_holes(&ring);
        assert_eq!(holes, 1);
        assert!(filled[Cell::new(2, 2)]);
        assert!(!filled[Cell::new(0, 0)]);
        let bar = grid(&["#####", "#...#", "#####"]);
        assert_eq!(fill_holes(&bar).1, 0);
        // Two obstacle cells touching at a corner are one hole.
        let corner = grid(&["......", ".#....", "..#...", "......"]);
        assert_eq!(fill_holes(&corner).1, 1);
    }

    #[test]
    fn a_rectangle_has_one_lane_per_tool_width_along_its_long_side() {
        // 40 × 12 cells, lanes 4 cells apart: 3 along, 10 across.
        let room = Grid::new(40, 12, true);
        assert_eq!(lanes_at(&room, 0.0, 4.0), 3);
        assert_eq!(lanes_at(&room, PI / 2.0, 4.0), 10);
    }

    #[test]
    fn a_wall_across_the_lines_cuts_each_into_two_lanes() {
        let mut room = Grid::new(40, 12, true);
        for row in 0..12 {
            room[Cell::new(row, 20)] = false;
        }
        assert_eq!(lanes_at(&room, 0.0, 4.0), 6);
        // Runs shorter than a tool width are not lanes.
        let mut stub = Grid::new(40, 12, true);
        for row in 0..12 {
            stub[Cell::new(row, 2)] = false;
        }
        assert_eq!(lanes_at(&stub, 0.0, 4.0), 3);
    }

    #[test]
    fn the_ceiling_of_a_bare_room_counts_its_loop_and_half_turns() {
        let time = TimeModel::default();
        let map = crate::bare_rooms::room(8.0, 6.0, 0);
        let c = ceiling(&map, 0.15, &time).unwrap();
        assert_eq!(c.holes, 0);
        assert!(c.angle_deg == 0 || c.angle_deg == 90, "{}", c.angle_deg);
        // 6 m less a robot radius either side, lanes 0.3 m apart.
        assert_eq!(c.lanes, 19);
        let turning = time.time(0.0, 2.0 * PI + 18.0 * PI);
        assert!((c.efficiency - c.bound_s / (c.bound_s + turning)).abs() < 1e-12);
        // One speck: a hole, a loop more, the lanes pass it.
        // Without a hole, cutting changes nothing.
        assert_eq!(c.cut_lanes, c.lanes);
        assert!((c.cut_efficiency - c.efficiency).abs() < 1e-12);
        // One speck: a hole, a loop more; the lanes pass it, or are cut by
        // it: the one or two lines across it become two lanes each.
        let speck = ceiling(&crate::bare_rooms::room(8.0, 6.0, 1), 0.15, &time).unwrap();
        assert_eq!((speck.holes, speck.lanes), (1, 19));
        assert!(speck.efficiency < c.efficiency);
        assert!(
            (20..=21).contains(&speck.cut_lanes),
            "{} lanes cut",
            speck.cut_lanes
        );
        assert!(speck.cut_efficiency < speck.efficiency);
    }
}
