//! `lanes`: the pattern cleaning robots drive, planned for estimated time:
//! a loop along every wall and piece of furniture, then straight lanes
//! between them, ordered so that the robot turns and transits least.
//!
//! On its region (the whole map, or one room unit when the pipeline plans
//! room by room) `plan_lanes` runs these stages, one file each, in this
//! order:
//!
//! 1. `loops`: every contour of the C-space traced and driven once, its
//!    waypoints pushed towards the wall and straightened within a fraction
//!    of a cell. A room cut (no wall) opens the contour into runs.
//! 2. `layout`: the lane mask (the C-space a tool radius in from the
//!    walls: the loops cover the rest) and, at one angle, its lines one tool
//!    width apart, their clear runs as lanes and neighbouring lanes joined
//!    into chains driven back and forth.
//! 3. `angles`: the angles tried (every 15°, the walls' directions), each
//!    modelled by its chains' time; the best few go on.
//! 4. `rehatch`: each chain's part that the angle does not suit (a
//!    corridor's arm hatched across) hatched again along its walls or its
//!    own long axis, where the model finds that faster.
//! 5. `islands`: lanes run past small islands (specks, table legs), and an
//!    island's loop is driven from the lane passing nearest.
//! 6. `nodes`, `transits`, `order`: loops and chains ordered by a small
//!    generalised TSP (nearest neighbour, 2-opt, then an exact choice of
//!    every node's entry), its costs estimated seconds with the detour
//!    walls force on each transit.
//! 7. `build`: the best few angles driven to the end in parallel: transits
//!    by the shortest clear route, then the shared detours and tightening
//!    (`detours`); the path with the least estimated time is kept.
//!
//! Every segment is checked by exact traversal, so the path never leaves the
//! plannable cells, and a last pass visits any coverage cell still
//! uncovered: the plan is complete on the coverage grid. What each stage
//! buys on the shared maps, and what the path costs where: `docs/efficiency.md`.

mod angles;
mod build;
mod islands;
mod layout;
mod loops;
mod nodes;
mod order;
mod rehatch;
#[cfg(test)]
mod tests;
mod transits;

use rayon::prelude::*;

use oxcover_grid::traverse::cell_center;
use oxcover_grid::{Cell, Point};

use self::angles::Angles;
use self::build::Builder;
use self::islands::{island_masks, splices_for};
use self::layout::{LaneMask, Layout};
use self::loops::edge_loops;
use self::nodes::nodes_of;
use self::order::{Ordered, order_nodes};
use self::rehatch::Hatch;
use self::transits::Region;
use crate::error::{Error, Result};
use crate::planner::{Planner, PlannerOptions};
use crate::problem::{PlanOutput, PlannerInput};
use crate::time::TimeModel;

/// The `lanes` planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes {
    /// Fixed lane angle in degrees (map frame); `None` = fastest per region.
    angle_deg: Option<f64>,
    stages: LaneStages,
}

/// The stages of `lanes` that can be turned off, to measure what each
/// buys (`cargo xtask efficiency`, `docs/efficiency.md`). All on by
/// default, as the registry's `lanes` plans; with any off the path is still
/// complete and never leaves the plannable cells (what a stage would have
/// covered is left to the last pass and the boundary pass).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(clippy::struct_excessive_bools)]
pub struct LaneStages {
    /// Edge loops straightened within a fraction of a cell (off: every
    /// boundary cell's point is a waypoint).
    pub straighten_loops: bool,
    /// The outermost lines moved in to where their reach meets the loops'
    /// (off: lines spread over the whole lane mask).
    pub inset_lines: bool,
    /// Every 15° tried besides the wall directions (off: the two wall
    /// directions only).
    pub every_angle: bool,
    /// The best few angles built to the end and compared on the finished
    /// path (off: the model's best alone).
    pub build_several: bool,
    /// Chains whose area one angle does not suit hatched again.
    pub rehatch: bool,
    /// Lanes run past small islands and drive their loops (off: every
    /// island cuts the lanes and its loop is a node of the order).
    pub islands: bool,
    /// The order improved by 2-opt and the exact choice of entries (off:
    /// the nearest-neighbour order alone).
    pub improve_order: bool,
    /// Cells passed just out of reach covered by the cheapest detours.
    pub detours: bool,
    /// The path tightened for time.
    pub tighten: bool,
}

impl LaneStages {
    /// Every stage on (the planner as the registry gives it).
    pub const ALL: Self = Self {
        straighten_loops: true,
        inset_lines: true,
        every_angle: true,
        build_several: true,
        rehatch: true,
        islands: true,
        improve_order: true,
        detours: true,
        tighten: true,
    };
}

impl Default for LaneStages {
    fn default() -> Self {
        Self::ALL
    }
}

impl Default for Lanes {
    fn default() -> Self {
        Self::new()
    }
}

impl Lanes {
    /// Lanes at each region's fastest angle, every stage on.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            angle_deg: None,
            stages: LaneStages::ALL,
        }
    }

    /// The same planner with only the stages `stages` on (for experiments:
    /// what each stage buys).
    #[must_use]
    pub const fn with_stages(mut self, stages: LaneStages) -> Self {
        self.stages = stages;
        self
    }

    /// Lanes at a fixed angle (degrees, counter-clockwise from the map's x axis).
    #[must_use]
    pub const fn at_angle(mut self, deg: f64) -> Self {
        self.angle_deg = Some(deg);
        self
    }
}

impl Planner for Lanes {
    fn name(&self) -> &'static str {
        "lanes"
    }

    fn complete(&self) -> bool {
        true
    }

    fn summary(&self) -> &'static str {
        "edge loops along walls and furniture, then straight lanes at the region's fastest angle (parts it does not suit hatched again along their walls), ordered by estimated time"
    }

    fn options(&self) -> PlannerOptions {
        let mut o = PlannerOptions::new();
        o.sweep_angle_deg = self.angle_deg;
        o
    }

    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        let plan = plan_lanes(input, self.angle_deg, &self.stages)?;
        Ok(PlanOutput::Metres(plan))
    }
}

/// The `lanes` path of `input`'s region (metres, map frame), its lanes at
/// `angle_deg` (degrees, map frame) if given, else at each part's fastest,
/// with the stages `stages` on.
fn plan_lanes(
    input: &PlannerInput<'_>,
    angle_deg: Option<f64>,
    stages: &LaneStages,
) -> Result<Vec<Point>> {
    let plannable = input.plannable;
    let start = start_cell(input)?;
    let tool = input.tool_cells.max(0.5);
    // A tool narrower than a cell: lanes through the cell centres, one row
    // or column apart, along the grid's axes only.
    let narrow = tool < 1.0;
    let time = cell_time(input);
    // Edge loops, the lane mask and the small islands (independent).
    let (loops, (lane_mask, islands)) = rayon::join(
        || edge_loops(plannable, input.admissible),
        || {
            rayon::join(
                || LaneMask::new(plannable, input.admissible, tool),
                || (!narrow && stages.islands).then(|| island_masks(plannable, tool)),
            )
        },
    );
    // Islands that lanes pass, and islands whose loops lanes drive.
    let (passed, spliced) = islands.unzip();
    let layout = Layout::new(
        plannable,
        &lane_mask,
        passed.as_ref(),
        tool,
        &time,
        stages.inset_lines,
    );
    // Every candidate angle's chains, modelled; the best few go on.
    let angles = Angles::new(&loops, angle_deg, narrow, stages);
    let (near_ties, built) = angles.near_ties(&layout, input.plan_cells, stages.build_several);
    // Each of them re-hatched where one angle does not suit a part (a fixed
    // angle is kept everywhere), its islands spliced into its lanes, and
    // its loops and chains ordered (in parallel, each with its own transit
    // search; in the order of `near_ties` whatever the thread count).
    let hatch = Hatch::new(&layout);
    let exit = input.exit.filter(|&c| plannable.is_set(c)).map(cell_center);
    let ends = (cell_center(start), exit);
    let order_angle = |region: &mut Region<'_>, tie: angles::Scored| {
        let (chains, saving) = if angle_deg.is_none() && stages.rehatch {
            hatch.rehatch(tie.chains, tie.step, &angles.walls)
        } else {
            (tie.chains, 0.0)
        };
        let splices = spliced.as_ref().map_or_else(Vec::new, |isl| {
            splices_for(&loops, &chains, isl, plannable, layout.spacing)
        });
        let nodes = nodes_of(&loops, &chains, &splices);
        let (tour, transit) = order_nodes(&nodes, ends, region, &time, stages.improve_order);
        Ordered {
            time: tie.cost - saving + transit,
            chains,
            tour,
            splices,
        }
    };
    let mut ordered: Vec<Ordered> = near_ties
        .into_par_iter()
        .map_init(|| Region::new(plannable, tool), order_angle)
        .collect();
    ordered.sort_by(|a, b| a.time.total_cmp(&b.time));
    // The best few driven to the end (detours, tightening); the fastest kept.
    let builder = Builder::new(input, &loops, start, exit, tool, time, *stages);
    builder.fastest(&ordered[..built.min(ordered.len())])
}

/// Where the robot stands: a path from its coverage cell's representative
/// would begin with a detour to it and back.
fn start_cell(input: &PlannerInput<'_>) -> Result<Cell> {
    if input.plannable[input.start_cell] {
        Ok(input.start_cell)
    } else {
        input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))
    }
}

/// The planner's time model in cells per second (the grid's unit).
fn cell_time(input: &PlannerInput<'_>) -> TimeModel {
    TimeModel {
        linear_speed: input.time.linear_speed / input.frame.resolution(),
        angular_speed: input.time.angular_speed,
    }
}
