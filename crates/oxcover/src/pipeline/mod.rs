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

use oxcover_grid::OccupancyGrid;

use self::region::plan_whole;
use self::rooms::{in_several_rooms, plan_rooms, room_labels, units_of};
use crate::error::Result;

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
    // The segmentation needs only the map: found while the problem is
    // built (same result whatever the thread count).
    let (problem, rooms) = rayon::join(
        || request.problem(map),
        || request.rooms.then(|| room_labels(map)),
    );
    let problem = problem?;
    // The plannable cells are one 4-connected region: all in one room,
    // they are one unit, planned whole (no units to find).
    let units = rooms
        .filter(|rooms| in_several_rooms(problem.plannable(), &rooms.labels))
        .map(|rooms| units_of(&problem, &rooms));
    match units.filter(|u| u.count() > 1) {
        Some(units) => plan_rooms(&problem, &units, request, t0),
        None => plan_whole(&problem, request, t0),
    }
}
