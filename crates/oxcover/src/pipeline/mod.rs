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
mod remainder;
mod request;
mod rooms;
#[cfg(test)]
mod tests;

use std::borrow::Cow;
use std::time::Instant;

use oxcover_decomp::Rooms;
use oxcover_grid::{Grid, OccupancyGrid, coverable_cells};
use oxcover_planners::{CoverageProblem, RoomUnits, Start};

use self::region::plan_whole;
use self::rooms::{
    PlanRooms, TransitWaves, in_several_rooms, min_unit_cells, plan_rooms, units_of,
};
use crate::error::Result;
use crate::targets::{RoomOrder, TargetCells, TargetSummary};

pub use self::load::{MapReading, load_map, load_map_with};
pub use self::outputs::{
    Outputs, coverage_notes, metres, plan_pictures, plan_scene, short_name, write_outputs,
};
pub use self::request::{PlanOutcome, PlanRequest, PlannerInfo, RoomStretch, planner, planners};
pub use self::rooms::{LOCAL_ROOMS_MARGIN_M, MIN_UNIT_M2, room_units};

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
    // Zones or a spot hold the required cells to a window: coverable
    // cells are looked for there only (unless the clearance's report asks
    // for the map's).
    let within = targets
        .extent(&work_map)
        .filter(|_| request.clearance <= 0.0);
    // The segmentation needs only the map: found while the problem, the
    // target's cells and its region are (same result whatever the thread
    // count).
    let (prepared, rooms) = rayon::join(
        || -> Result<_> {
            let problem = request.problem_within(&work_map, within)?;
            // (Here, while the rooms are segmented beside.)
            let target = targets
                .required(map, problem.cells())?
                .map(|t| prepared_target(&problem, t));
            Ok((problem, target))
        },
        || request.rooms.then(|| PlanRooms::new(&work_map, request)),
    );
    let (problem, target) = prepared?;
    let lost = clearance_lost(&work_map, &problem, request)?;
    let maps = (map, &*work_map, within.is_some());
    let mut outcome = plan_problem(maps, (problem, target), rooms, blocked_cells, request, t0)?;
    outcome.clearance_lost_cells = lost;
    Ok(outcome)
}

/// The coverable cells the clearance puts out of the tool's reach: those
/// of the robot without it (from the same start cell) less the problem's.
fn clearance_lost(
    map: &OccupancyGrid,
    problem: &CoverageProblem,
    request: &PlanRequest,
) -> Result<Option<usize>> {
    if request.clearance <= 0.0 {
        return Ok(None);
    }
    let plain = CoverageProblem::new(map, request.robot, Start::Cell(problem.start_cell()))?;
    let (with, without) = (&problem.cells().coverable, &plain.cells().coverable);
    let lost = without
        .as_slice()
        .iter()
        .zip(with.as_slice())
        .filter(|&(&a, &b)| a && !b)
        .count();
    Ok(Some(lost))
}

/// Plans `problem` (built on the map with keep-out applied, `work_map`;
/// coverable cells only in the target's window where `windowed`) for
/// `request`: its coverage target and the target's region
/// ([`target_region`]), if the request narrows what to cover.
fn plan_problem(
    (map, work_map, windowed): (&OccupancyGrid, &OccupancyGrid, bool),
    (problem, target): (
        CoverageProblem,
        Option<(TargetCells, Grid<bool>, TransitWaves)>,
    ),
    rooms: Option<PlanRooms<'_>>,
    blocked_cells: usize,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let targets = &request.targets;
    if let Some((target, region, waves)) = target {
        // The whole map's problem, should the target's plan be compared
        // with the map's (built again where its coverable cells were found
        // in the target's window only).
        let kept = (!windowed).then(|| problem.clone());
        let whole = || kept.map_or_else(|| request.problem(work_map), Ok);
        let problem = problem.with_required(&target.required)?;
        let mut outcome = plan_target(
            &problem,
            whole,
            (&target, region, waves),
            rooms.as_ref(),
            request,
            t0,
        )?;
        // Resuming: the interrupted plan's remainder, where it is faster.
        if let Some(rest) = remainder::continued(map, &problem, request, t0)?
            && rest.evaluation.metrics.est_time_s < outcome.evaluation.metrics.est_time_s
        {
            outcome = PlanOutcome {
                plan_ms: t0.elapsed().as_secs_f64() * 1e3,
                ..rest
            };
        }
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
    let whole_rooms = rooms.as_ref().map(PlanRooms::whole);
    let mut outcome = plan_map(&problem, whole_rooms.as_deref(), request, t0)?;
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

/// Plans every plannable cell of `problem`: room by room over the plan's
/// room units where there are several, else the whole at once.
fn plan_map(
    problem: &CoverageProblem,
    rooms: Option<&Rooms>,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    // The plannable cells are one 4-connected region: all in one room,
    // they are one unit, planned whole (no units to find).
    let units = rooms
        .filter(|rooms| in_several_rooms(problem.plannable(), &rooms.labels))
        .map(|rooms| units_of(problem, rooms));
    match units.filter(|u| u.count() > 1) {
        Some(units) => plan_rooms(problem, &units, None, request, t0, None),
        None => plan_whole(problem, request, t0),
    }
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
/// the required cells ([`target_region`]), cut into units by the plan's
/// rooms when rooms are on (a small target's own neighbourhood's, see
/// [`LOCAL_ROOMS_MARGIN_M`]; else by the chosen rooms, else one unit per
/// connected part) and planned unit by unit, the robot free to drive
/// anywhere between them; a target of more than half the plannable cells
/// is also planned as the whole map is (its required cells covered on the
/// way), and the whole map's own plan is stopped at the first waypoint by
/// which it has covered them ([`remainder::covering_part`]): the fastest
/// of the three is kept.
fn plan_target(
    problem: &CoverageProblem,
    whole: impl FnOnce() -> Result<CoverageProblem>,
    (target, region, waves): (&TargetCells, Grid<bool>, TransitWaves),
    rooms: Option<&PlanRooms<'_>>,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let (w, h) = (region.width(), region.height());
    let labels = match (rooms, &target.room_labels) {
        (Some(rooms), _) => Cow::Borrowed(&rooms.rooms.labels),
        (None, Some(chosen)) => Cow::Borrowed(chosen),
        (None, None) => Cow::Owned(Grid::new(w, h, 1)),
    };
    let units = RoomUnits::new(&region, &labels, min_unit_cells(problem));
    let given = match (&request.targets.rooms_only, &target.room_labels) {
        (Some(chosen), Some(room_labels)) if request.targets.room_order == RoomOrder::Given => {
            Some(given_order(&units, room_labels, chosen))
        }
        _ => None,
    };
    let keep_order = given.is_some();
    let by_units = plan_rooms(problem, &units, given, request, t0, Some(waves))?;
    // A target of most of the map: its units cost about the map's, and the
    // map's own plan (covering the required cells on the way) may be the
    // faster; the faster is kept (not when the room order is given).
    if keep_order || 2 * region.count_true() <= problem.plannable().count_true() {
        return Ok(by_units);
    }
    let rooms = rooms.map(PlanRooms::whole);
    let by_map = plan_map(problem, rooms.as_deref(), request, t0)?;
    let map_plan = plan_map(&whole()?, rooms.as_deref(), request, t0)?;
    let part = remainder::covering_part(problem, request, &map_plan, false, t0)?;
    let time = |o: &PlanOutcome| o.evaluation.metrics.est_time_s;
    let mut kept = [Some(by_map), part]
        .into_iter()
        .flatten()
        .fold(
            by_units,
            |best, o| if time(&o) < time(&best) { o } else { best },
        );
    kept.plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok(kept)
}

/// A target's cells `t` with where it is planned ([`target_region`]) and
/// the wavefronts its plan's searches reuse ([`TransitWaves`]; built on
/// `problem` before `with_required`, which narrows its coverable cells
/// only: the same plannable cells, the same wavefronts).
fn prepared_target(
    problem: &CoverageProblem,
    t: TargetCells,
) -> (TargetCells, Grid<bool>, TransitWaves) {
    let region = target_region(problem, &t.required);
    let waves = TransitWaves::for_target(problem, &region);
    (t, region, waves)
}

/// Where a target is planned: the plannable cells within the tool's reach
/// of its required cells.
fn target_region(problem: &CoverageProblem, required: &Grid<bool>) -> Grid<bool> {
    coverable_cells(problem.plannable(), required, problem.tool_cells())
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
