//! The plan pipeline, the one path from a map to written outputs that the
//! command line, the demo, every experiment and every bench share:
//!
//! 1. **problem**: the map (`load`: any format the command line reads), the
//!    robot and the start make a [`oxcover_planners::CoverageProblem`] (admissible, reachable
//!    and coverable cells; the coverage grid one tool diameter wide; the
//!    tool radius in cells); `request` holds what to plan;
//! 2. **plan**: the planner (a value from [`oxcover_planners::build`] or any
//!    [`oxcover_planners::Planner`]) plans on the problem's input, the whole
//!    map at once or room by room (`region`, `rooms`); its plan becomes a
//!    fine, collision-free cell path (coverage plans are expanded) preceded
//!    by the lead-in from the start, then the boundary pass unless turned
//!    off, then metre waypoints;
//! 3. **evaluate**: the contract's metrics of the final path, and the
//!    coverage of the planner's own path before the boundary pass;
//! 4. **outputs**: the path CSV, pictures and JSON report ([`write_outputs`]).

mod load;
mod outputs;
mod region;
mod request;
mod rooms;
#[cfg(test)]
mod tests;

use std::time::Instant;

use oxcover_decomp::Rooms;
use oxcover_grid::{Grid, OccupancyGrid, coverable_cells};
use oxcover_planners::{CoverageProblem, RoomUnits, Start};

use self::region::plan_whole;
use self::rooms::{in_several_rooms, min_unit_cells, plan_rooms, room_labels, units_of};
use crate::error::Result;
use crate::targets::{RoomOrder, TargetCells, TargetSummary};

pub use self::load::{MapReading, load_map, load_map_with};
pub use self::outputs::{Outputs, coverage_notes, metres, plan_scene, short_name, write_outputs};
pub use self::request::{PlanOutcome, PlanRequest, PlannerInfo, RoomStretch, planner, planners};
pub use self::rooms::{MIN_UNIT_M2, room_units};

/// Plans a coverage path on `map`.
///
/// Coverage and fine cell paths are expanded to collision-free fine paths;
/// a metre path is used as given after the lead-in from the start, so its
/// collisions are whatever the planner made (the metrics count them).
///
/// With [`PlanRequest::rooms`] on and more than one room unit on the map
/// ([`room_units`]), the planner plans each unit on its own
/// ([`oxcover_planners::CoverageProblem::restricted`]), the boundary pass runs per unit (the
/// straightened tour or the nearest-first pass, whichever has the lower
/// estimated time), and
/// the units are visited in the order of [`oxcover_planners::room_order`], joined by
/// straightened shortest transits ([`oxcover_planners::CoverageProblem::transit`]): every room
/// is finished before the robot leaves it. With rooms on (one unit or
/// more) the finished path is then tightened for time as a whole, each
/// unit's waypoints kept in their unit ([`oxcover_planners::CoverageProblem::tighten_within`]);
/// rooms off, the planner's path and the nearest-first pass stay as they are
/// (the papers' experiments).
///
/// # Errors
/// A map too large for [`PlanRequest::memory_limit`] ([`crate::Error::MemoryLimit`]),
/// bad radii or start ([`oxcover_grid::Error`]), a planner's refusal
/// ([`oxcover_planners::Error::TooLarge`]) or an internal fault.
pub fn plan(map: &OccupancyGrid, request: &PlanRequest) -> Result<PlanOutcome> {
    request.check_memory(map, "map")?;
    let t0 = Instant::now();
    let targets = &request.targets;
    let (work_map, blocked_cells) = targets.blocked_map(map)?;
    keep_out_spares_start(map, &work_map, request)?;
    // The segmentation needs only the map: found while the problem is
    // built (same result whatever the thread count).
    let (problem, rooms) = rayon::join(
        || request.problem(&work_map),
        || request.rooms.then(|| room_labels(&work_map)),
    );
    let problem = problem?;
    if let Some(target) = targets.required(map, problem.cells())? {
        let mut outcome = plan_target(problem, &target, rooms.as_ref(), request, t0)?;
        let res = map.resolution();
        let required_cells = target.required.count_true();
        outcome.targets = Some(TargetSummary {
            required_cells,
            required_area_m2: required_cells as f64 * res * res,
            done_cells: target.done_cells,
            blocked_cells,
        });
        outcome.notes = target.notes;
        return Ok(outcome);
    }
    // The plannable cells are one 4-connected region: all in one room,
    // they are one unit, planned whole (no units to find).
    let units = rooms
        .filter(|rooms| in_several_rooms(problem.plannable(), &rooms.labels))
        .map(|rooms| units_of(&problem, &rooms));
    let mut outcome = match units.filter(|u| u.count() > 1) {
        Some(units) => plan_rooms(&problem, &units, None, request, t0),
        None => plan_whole(&problem, request, t0),
    }?;
    if targets.keep_out.is_some() {
        outcome.targets = Some(TargetSummary {
            required_cells: outcome.evaluation.metrics.coverable_cells,
            required_area_m2: outcome.evaluation.metrics.coverable_cells as f64
                * map.resolution()
                * map.resolution(),
            done_cells: 0,
            blocked_cells,
        });
    }
    Ok(outcome)
}

/// A start given in metres that keep-out areas cover is refused by name
/// (not as a start that is not admissible).
fn keep_out_spares_start(
    map: &OccupancyGrid,
    work_map: &OccupancyGrid,
    request: &PlanRequest,
) -> Result<()> {
    if let Start::At(p) = request.start
        && let Some(c) = map.frame().cell_at(&p)
        && map.is_free(c)
        && !work_map.is_free(c)
    {
        return Err(crate::Error::Target {
            what: "--keep-out".into(),
            message: format!(
                "a keep-out area or virtual wall covers the start ({}, {})",
                p.x, p.y
            ),
        });
    }
    Ok(())
}

/// Plans a coverage target: the plannable cells within the tool's reach of
/// a required cell, cut into units (by the chosen rooms, else by the
/// plan's rooms when rooms are on) and planned unit by unit, the robot
/// free to drive anywhere between them.
fn plan_target(
    problem: CoverageProblem,
    target: &TargetCells,
    rooms: Option<&Rooms>,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let problem = problem.with_required(&target.required)?;
    let near = coverable_cells(problem.plannable(), &target.required, problem.tool_cells());
    let (w, h) = (near.width(), near.height());
    let labels = match (&target.room_labels, rooms) {
        (Some(chosen), _) => chosen.clone(),
        (None, Some(rooms)) => rooms.labels.clone(),
        (None, None) => Grid::new(w, h, 1),
    };
    let units = RoomUnits::new(&near, &labels, min_unit_cells(&problem));
    let order = match (&request.targets.rooms_only, request.targets.room_order) {
        (Some(chosen), RoomOrder::Given) => Some(given_order(&units, &labels, chosen)),
        _ => None,
    };
    plan_rooms(&problem, &units, order, request, t0)
}

/// The units in the order of the room labels `chosen`: each unit goes with
/// the chosen room most of its cells lie in (ties: the first unit first).
fn given_order(units: &RoomUnits, labels: &Grid<u32>, chosen: &[u32]) -> Vec<u32> {
    let n = units.count();
    let mut votes = vec![vec![0usize; chosen.len()]; n];
    for c in units.labels.cells() {
        let u = units.labels[c] as usize;
        if u > 0
            && let Some(k) = chosen.iter().position(|&l| l == labels[c])
        {
            votes[u - 1][k] += 1;
        }
    }
    let rank = |u: usize| {
        let v = &votes[u];
        // Most cells; a unit of no chosen room goes last.
        v.iter()
            .enumerate()
            .max_by_key(|&(k, &count)| (count, std::cmp::Reverse(k)))
            .filter(|&(_, &count)| count > 0)
            .map_or(chosen.len(), |(k, _)| k)
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&u| (rank(u), u));
    order.into_iter().map(|u| u as u32 + 1).collect()
}
