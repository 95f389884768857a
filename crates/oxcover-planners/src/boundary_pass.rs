//! The boundary pass: cover what a plan left uncovered, typically the strips
//! along walls and obstacles that a coarse coverage grid cannot reach.
//!
//! Pavlíček et al. 2002 propose "an additional run of the system along
//! obstacle boundaries". This module does it for any planner's output:
//!
//! 1. Score the plan's polyline exactly as the metrics do (samples every
//!    resolution/4): the coverable cells it leaves uncovered are *pending*.
//! 2. Choose *anchors*: greedily, for each pending cell in row-major order not
//!    yet planned, the plannable cell within the tool radius whose tool disc
//!    covers the most still-pending cells (ties row-major). Such a cell exists
//!    for every pending cell by the definition of coverable. Next to walls the
//!    best anchors are the admissible cells nearest the wall, so the route runs
//!    along the admissible boundary.
//! 3. Route: from the plan's last cell, repeatedly go by a shortest path (CIDT
//!    on the plannable cells) to the nearest anchor whose cells are still
//!    uncovered, marking what the route covers on the way.
//!
//! Every coverable cell ends covered, and every step is a 4-connected move
//! between plannable cells, so the pass keeps the plan collision-free. It is a
//! nearest-neighbour tour, not an optimal one: good enough for strips, which is
//! what it is for.
//!
//! Room by room the pipeline runs [`boundary_tour_to`] instead: the anchors
//! in a straightened open tour, ending towards the room's cell nearest the
//! next room (rooms on, measured over the shared maps when introduced: every
//! grid planner's mean estimated time fell on the ipa floor plans, by
//! 3–42 s, and on the ROS maps moved by −18 to +3 s; `smooth` went from 3
//! ROS maps slower with rooms on than off to 1). It tightens that tour and
//! the nearest-first pass for time
//! ([`crate::CoverageProblem::tighten_from`]: a route of cell centres turns
//! at almost every anchor) and keeps the faster.

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::footprint::{covered_cells_of, mark_covered, mark_disc};
use oxcover_grid::{Cell, Coverability, Grid, MapFrame, Point, TOLERANCE_CELLS};

use crate::error::{Error, Result};
use crate::metre_path::{PathBuilder, grid_to_metres};

/// What the pass did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BoundaryRoute {
    /// Fine cells to append after the plan's last cell (not repeated here).
    pub cells: Vec<Cell>,
    /// The route's waypoints (metres, map frame, after the last cell's
    /// centre): the cells' centres for [`boundary_pass`]; for
    /// [`boundary_tour`] each leg string-pulled over its cells, every
    /// shortcut checked by exact traversal, coverage marked along it.
    pub points: Vec<Point>,
    /// Coverable cells the plan left uncovered.
    pub pending: usize,
    /// Anchors chosen to cover them.
    pub anchors: usize,
}

/// Computes the route that covers the cells `points` leaves uncovered, starting
/// from the plannable cell `end` (where the plan stops).
///
/// # Errors
/// [`Error::Internal`] if `end` is not plannable or an anchor is unreachable
/// (neither can happen for a problem built by [`Coverability`]).
pub fn boundary_pass(
    frame: &MapFrame,
    problem: &Coverability,
    points: &[Point],
    end: Cell,
) -> Result<BoundaryRoute> {
    boundary_pass_covered(frame, problem, covered_by(frame, problem, points), end)
}

/// [`boundary_pass`] given the cells the plan covers: `covered`, a grid of
/// `frame`'s size as [`oxcover_grid::footprint::covered_cells`] finds it for the plan's polyline
/// and the problem's tool radius (for a caller that has it already).
///
/// # Errors
/// As [`boundary_pass`]; [`Error::Internal`] if `covered` is not of
/// `frame`'s size.
pub fn boundary_pass_covered(
    frame: &MapFrame,
    problem: &Coverability,
    covered: Grid<bool>,
    end: Cell,
) -> Result<BoundaryRoute> {
    let Some(plan) = choose_anchors(frame, problem, covered, end)? else {
        return Ok(BoundaryRoute::default());
    };
    nearest_first(frame, problem, plan, end)
}

/// The cells a plan's polyline `points` covers for `problem`'s tool, as the
/// metrics find them ([`oxcover_grid::footprint::covered_cells`]; a long path in two halves side
/// by side, [`covered_cells_of`]).
#[must_use]
pub fn covered_by(frame: &MapFrame, problem: &Coverability, points: &[Point]) -> Grid<bool> {
    covered_cells_of(frame, &[points], problem.robot.tool_radius)
}

/// The same cells covered by a better tour: the anchors are ordered by an
/// open tour over their straight-line distances (nearest neighbour, then
/// 2-opt; [`crate::tour::open_tour`]) instead of nearest first, and each leg
/// is a shortest route straightened. Used when planning room by room, where
/// the pass runs per room; the map-wide pass keeps the order above.
///
/// # Errors
/// As [`boundary_pass`].
pub fn boundary_tour(
    frame: &MapFrame,
    problem: &Coverability,
    points: &[Point],
    end: Cell,
) -> Result<BoundaryRoute> {
    boundary_tour_to(frame, problem, points, end, None)
}

/// [`boundary_tour`] for a robot that goes on to the cell `exit` (room by
/// room: the room's cell nearest the next room): of the open tour from
/// `end` and the open tour from `exit` driven backwards (so that it ends
/// there), the one shorter with the straight way on to `exit` is driven.
///
/// # Errors
/// As [`boundary_pass`].
pub fn boundary_tour_to(
    frame: &MapFrame,
    problem: &Coverability,
    points: &[Point],
    end: Cell,
    exit: Option<Cell>,
) -> Result<BoundaryRoute> {
    let covered = covered_by(frame, problem, points);
    boundary_tour_to_covered(frame, problem, covered, end, exit)
}

/// [`boundary_tour_to`] given the cells the plan covers (`covered`, as for
/// [`boundary_pass_covered`]).
///
/// # Errors
/// As [`boundary_pass_covered`].
pub fn boundary_tour_to_covered(
    frame: &MapFrame,
    problem: &Coverability,
    covered: Grid<bool>,
    end: Cell,
    exit: Option<Cell>,
) -> Result<BoundaryRoute> {
    let Some(plan) = choose_anchors(frame, problem, covered, end)? else {
        return Ok(BoundaryRoute::default());
    };
    toured(frame, problem, plan, end, exit)
}

/// Anchors chosen for the pending cells.
struct AnchorPlan {
    covered: Grid<bool>,
    pending: usize,
    anchor_of: Grid<u32>,
    /// Pending cells each anchor covers, by anchor id - 1.
    targets: Vec<Vec<Cell>>,
}

/// Pending cells (coverable, not `covered`) and their anchors; `None` when
/// nothing is pending.
fn choose_anchors(
    frame: &MapFrame,
    problem: &Coverability,
    covered: Grid<bool>,
    end: Cell,
) -> Result<Option<AnchorPlan>> {
    let plannable = &problem.reachable;
    if !plannable.is_set(end) {
        return Err(Error::Internal(format!(
            "boundary pass starts at {end:?}, which is not plannable"
        )));
    }
    if (covered.width(), covered.height()) != (frame.width(), frame.height()) {
        return Err(Error::Internal(format!(
            "boundary pass given covered cells of {}x{}, not the map's {}x{}",
            covered.width(),
            covered.height(),
            frame.width(),
            frame.height()
        )));
    }
    let pending: Vec<Cell> = problem
        .coverable
        .true_cells()
        .filter(|&c| !covered[c])
        .collect();
    if pending.is_empty() {
        return Ok(None);
    }

    let reach = problem.robot.tool_cells(frame.resolution()) + TOLERANCE_CELLS;
    // No cell lies farther than the map's width + height: clip absurd tool radii.
    let disc = disc_offsets(reach.min((frame.width() + frame.height()) as f64));
    let mut planned = covered.clone();
    let mut anchor_of = Grid::new(frame.width(), frame.height(), 0u32);
    let mut targets: Vec<Vec<Cell>> = Vec::new();
    let is_pending = |c: Cell, planned: &Grid<bool>| problem.coverable[c] && !planned[c];
    for &u in &pending {
        if planned[u] {
            continue;
        }
        let mut best: Option<(usize, Cell)> = None;
        for &o in &disc {
            let Some(a) = plannable.offset(u, o) else {
                continue;
            };
            if !plannable[a] {
                continue;
            }
            let gain = disc
                .iter()
                .filter_map(|&q| plannable.offset(a, q))
                .filter(|&v| is_pending(v, &planned))
                .count();
            if best.is_none_or(|(g, b)| gain > g || (gain == g && a < b)) {
                best = Some((gain, a));
            }
        }
        let Some((_, a)) = best else {
            return Err(Error::Internal(format!(
                "coverable cell {u:?} has no plannable cell within the tool radius"
            )));
        };
        let cells: Vec<Cell> = disc
            .iter()
            .filter_map(|&q| plannable.offset(a, q))
            .filter(|&v| is_pending(v, &planned))
            .collect();
        for &v in &cells {
            planned[v] = true;
        }
        if anchor_of[a] == 0 {
            targets.push(cells);
            anchor_of[a] = targets.len() as u32;
        } else {
            targets[anchor_of[a] as usize - 1].extend(cells);
        }
    }
    Ok(Some(AnchorPlan {
        covered,
        pending: pending.len(),
        anchor_of,
        targets,
    }))
}

/// Visits the anchors nearest first (by shortest route) from `end`.
fn nearest_first(
    frame: &MapFrame,
    problem: &Coverability,
    plan: AnchorPlan,
    end: Cell,
) -> Result<BoundaryRoute> {
    let AnchorPlan {
        mut covered,
        pending,
        anchor_of,
        targets,
    } = plan;
    let plannable = &problem.reachable;
    let tool = problem.robot.tool_radius;
    let anchors = targets.len();

    let mut wave = Wavefront::new(plannable);
    let mut done = vec![false; targets.len()];
    let mut here = end;
    let mut route = Vec::new();
    loop {
        let near = cidt(&mut wave, &[here], |c| {
            let id = anchor_of[c] as usize;
            id != 0 && !done[id - 1] && targets[id - 1].iter().any(|&v| !covered[v])
        });
        let Some(near) = near else {
            break;
        };
        let a = near.first();
        let seg = wave
            .retrace(a)
            .ok_or_else(|| Error::Internal("boundary pass retrace failed".into()))?;
        for &c in &seg[1..] {
            mark_disc(frame, &frame.cell_center(c), tool, &mut covered);
        }
        if seg.len() == 1 {
            mark_disc(frame, &frame.cell_center(a), tool, &mut covered);
        }
        route.extend_from_slice(&seg[1..]);
        done[anchor_of[a] as usize - 1] = true;
        here = a;
    }
    Ok(BoundaryRoute {
        points: route.iter().map(|&c| frame.cell_center(c)).collect(),
        cells: route,
        pending,
        anchors,
    })
}

/// Visits the anchors in the order of an open tour from `end`.
fn toured(
    frame: &MapFrame,
    problem: &Coverability,
    plan: AnchorPlan,
    end: Cell,
    exit: Option<Cell>,
) -> Result<BoundaryRoute> {
    let AnchorPlan {
        mut covered,
        pending,
        anchor_of,
        targets,
    } = plan;
    let plannable = &problem.reachable;
    let tool = problem.robot.tool_radius;
    let mut cells_of: Vec<Cell> = vec![Cell::default(); targets.len()];
    for c in anchor_of.cells() {
        let id = anchor_of[c] as usize;
        if id > 0 {
            cells_of[id - 1] = c;
        }
    }
    // Place 0 is the start; places 1..=n the anchors.
    let mut places = vec![end];
    places.extend(cells_of.iter().copied());
    let xy: Vec<Point> = places
        .iter()
        .map(|p| Point::new(p.col as f64, p.row as f64))
        .collect();
    let order = ordered_towards(&xy, exit.map(|e| Point::new(e.col as f64, e.row as f64)));
    let mut wave = Wavefront::new(plannable);
    let mut route = Vec::new();
    let mut path = PathBuilder::new(plannable, end);
    let mut here = end;
    for &k in order.iter().skip(1) {
        let id = k - 1;
        if targets[id].iter().all(|&v| covered[v]) {
            continue;
        }
        let a = cells_of[id];
        let near = cidt(&mut wave, &[here], |c| c == a)
            .ok_or_else(|| Error::Internal(format!("boundary anchor {a:?} unreachable")))?;
        let seg = wave
            .retrace(near.first())
            .ok_or_else(|| Error::Internal("boundary pass retrace failed".into()))?;
        let from = path.points().len() - 1;
        path.follow(&seg[1..], f64::INFINITY);
        let leg = grid_to_metres(frame, &path.points()[from..]);
        mark_covered(frame, &leg, tool, &mut covered);
        route.extend_from_slice(&seg[1..]);
        here = a;
    }
    let mut points = path.into_metres(frame);
    points.remove(0);
    Ok(BoundaryRoute {
        cells: route,
        points,
        pending,
        anchors: targets.len(),
    })
}

/// An open tour over `xy` from place 0; with `exit`, the shorter (with
/// the straight way on to `exit`) of that tour and the open tour from
/// `exit` over places 1.. driven backwards, entered from place 0.
fn ordered_towards(xy: &[Point], exit: Option<Point>) -> Vec<usize> {
    let free = crate::tour::open_tour_euclidean(xy, 0);
    let Some(e) = exit else {
        return free;
    };
    let dist = |a: Point, b: Point| (a - b).norm();
    let length = |order: &[usize]| -> f64 {
        order
            .windows(2)
            .map(|w| dist(xy[w[0]], xy[w[1]]))
            .sum::<f64>()
            + order.last().map_or(0.0, |&k| dist(xy[k], e))
    };
    // Place 0 of the backward problem is the exit; places 1.. are the same.
    let mut back_xy = xy.to_vec();
    back_xy[0] = e;
    let back = crate::tour::open_tour_euclidean(&back_xy, 0);
    let mut towards = vec![0];
    towards.extend(back.iter().skip(1).rev());
    if length(&towards) < length(&free) {
        towards
    } else {
        free
    }
}

/// Offsets `(dr, dc)` with `dr² + dc² <= reach²`, row-major.
fn disc_offsets(reach: f64) -> Vec<(isize, isize)> {
    let r = reach.floor() as isize;
    let mut v = Vec::new();
    for dr in -r..=r {
        for dc in -r..=r {
            if ((dr * dr + dc * dc) as f64) <= reach * reach {
                v.push((dr, dc));
            }
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::footprint::covered_cells;
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::{DiscRobot, OccupancyGrid};

    fn centres(frame: &MapFrame, cells: &[Cell]) -> Vec<Point> {
        cells.iter().map(|&c| frame.cell_center(c)).collect()
    }

    fn coverage(frame: &MapFrame, problem: &Coverability, pts: &[Point]) -> (usize, usize) {
        let cov = covered_cells(frame, pts, problem.robot.tool_radius);
        let n = problem.coverable.true_cells().filter(|&c| cov[c]).count();
        (n, problem.coverable_count())
    }

    #[test]
    fn covers_the_strip_a_coarse_lane_misses() {
        // 0.1 m cells, tool radius 0.1 m (one cell each side). A single lane
        // through row 2 of a 6-row room misses rows 0 and 4..5.
        let (m, _) = parse_ascii(
            "
            ..........
            ..........
            ..........
            ..........
            ..........
            ..........",
        )
        .unwrap();
        let map = OccupancyGrid::new(m.cells().clone(), 0.1, Point::origin());
        let robot = DiscRobot::new(0.0, 0.1).unwrap();
        let problem = Coverability::with_start_cell(&map, robot, Cell::new(2, 0)).unwrap();
        let lane: Vec<Cell> = (0..10).map(|c| Cell::new(2, c)).collect();
        let pts = centres(map.frame(), &lane);
        assert_eq!(coverage(map.frame(), &problem, &pts), (30, 60));
        let r = boundary_pass(map.frame(), &problem, &pts, Cell::new(2, 9)).unwrap();
        assert_eq!(r.pending, 30);
        let mut all = lane.clone();
        all.extend_from_slice(&r.cells);
        assert!(all.windows(2).all(|w| w[0].manhattan(w[1]) == 1));
        assert!(all.iter().all(|&c| problem.reachable[c]));
        let pts = centres(map.frame(), &all);
        assert_eq!(coverage(map.frame(), &problem, &pts), (60, 60));
        // Given the lane's covered cells, the same pass and tour.
        let lane_pts = centres(map.frame(), &lane);
        let covered = covered_by(map.frame(), &problem, &lane_pts);
        let end = Cell::new(2, 9);
        let given = boundary_pass_covered(map.frame(), &problem, covered.clone(), end);
        assert_eq!(given.unwrap(), r);
        let tour = boundary_tour_to(map.frame(), &problem, &lane_pts, end, None).unwrap();
        let given = boundary_tour_to_covered(map.frame(), &problem, covered, end, None);
        assert_eq!(given.unwrap(), tour);
        // Covered cells of another grid's size are refused.
        let wrong = Grid::new(9, 6, false);
        assert!(boundary_pass_covered(map.frame(), &problem, wrong.clone(), end).is_err());
        assert!(boundary_tour_to_covered(map.frame(), &problem, wrong, end, None).is_err());
    }

    #[test]
    fn a_tour_with_an_exit_ends_next_to_it() {
        // From the middle of a row of anchors, the free tour may end at
        // either end; with the exit beyond the west end, the west end is
        // left for last.
        let mut xy = vec![Point::new(5.0, 0.0)];
        xy.extend(
            (0..=10)
                .filter(|&x| x != 5)
                .map(|x| Point::new(f64::from(x), 0.0)),
        );
        let exit = Point::new(-1.0, 0.0);
        let total = |order: &[usize]| {
            order
                .windows(2)
                .map(|w| (xy[w[1]] - xy[w[0]]).norm())
                .sum::<f64>()
                + (xy[*order.last().unwrap()] - exit).norm()
        };
        let towards = ordered_towards(&xy, Some(exit));
        let free = ordered_towards(&xy, None);
        assert_eq!(free, crate::tour::open_tour_euclidean(&xy, 0));
        assert_eq!(towards[0], 0);
        let mut seen = towards.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..xy.len()).collect::<Vec<_>>());
        assert_eq!(xy[*towards.last().unwrap()], Point::new(0.0, 0.0));
        assert!(total(&towards) <= total(&free));
        assert!((total(&towards) - 16.0).abs() < 1e-9);
    }

    #[test]
    fn nothing_to_do_on_a_complete_plan() {
        let (m, s) = parse_ascii("S..").unwrap();
        let problem =
            Coverability::with_start_cell(&m, DiscRobot::cell_sized(1.0), s.unwrap()).unwrap();
        let pts = centres(m.frame(), &[Cell::new(0, 0), Cell::new(0, 2)]);
        let r = boundary_pass(m.frame(), &problem, &pts, Cell::new(0, 2)).unwrap();
        assert_eq!((r.cells.len(), r.pending, r.anchors), (0, 0, 0));
        assert!(boundary_pass(m.frame(), &problem, &pts, Cell::new(5, 5)).is_err());
    }
}
