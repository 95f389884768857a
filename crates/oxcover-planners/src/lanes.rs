//! `lanes`: the pattern real cleaning robots drive, planned for time.
//!
//! On its region (the whole map, or one room when the pipeline plans room by
//! room) the planner lays out two kinds of work and then orders them:
//!
//! 1. **Edge loops.** Every contour of the plannable cells (the robot's
//!    C-space: walls and every piece of furniture) is traced (Moore
//!    neighbour tracing) and driven once. Its waypoints sit in the boundary
//!    cells, pushed 0.45 of a cell towards the wall (still inside the cell,
//!    so the tool reaches as far into the strip along the wall as the robot
//!    may go), and the staircase is straightened within half a tool radius
//!    (¼ to 0.8 of a cell). Where the region borders another room's plannable
//!    cells (a room cut, not a wall) the contour opens into runs along the
//!    walls only.
//! 2. **Lanes.** Straight metre segments, one tool width apart (less the
//!    sampling margin of the contract's coverage test), clipped to the part
//!    of the C-space at least a tool radius from any wall (the loops cover
//!    the rest): a lane ends where the wall is. The outermost lines lie
//!    further in, where their reach just meets the loops' (half a cell less
//!    than a tool radius), so that no line is spent on the strip a loop
//!    already covers. Lanes on
//!    neighbouring lines whose extents overlap, one to one, form a **chain**
//!    (a boustrophedon cell) driven back and forth with one turn at each end.
//!    The lane direction is the region's own: every 15° and the dominant
//!    wall direction are tried, and the one with the least estimated time
//!    ([`crate::TimeModel`]: lane and link length over v, π per link over w,
//!    a turn and a lane spacing per chain, three times the time of lanes for
//!    the lane-mask area the lanes leave) is preferred; another angle must
//!    beat the wall directions by 5 %. That model cannot see what detours
//!    and tightening will make of an angle, so the two best (by the model
//!    plus their ordered transits) are both built to the end, in parallel,
//!    and the path with the least estimated time is kept. A plan of fewer
//!    than 100,000 plannable cells builds more: 200,000 cells' worth of
//!    angles, every angle below about 14,000 cells (room by room, the whole
//!    map's count decides, so more rooms cost no more builds). An angle
//!    whose path after its detours and first tightening pass is more than
//!    5 % slower than the fastest's stops there (the later passes never
//!    made up that much on the shared maps).
//!
//!    One angle rarely suits every part of a region: a corridor's arm, or
//!    a strip beside a room, hatched across turns every few lanes. So each
//!    chain is cut where its lanes' extent jumps (a band and the arm that
//!    leaves it share a chain when each line's run overlaps the next one
//!    to one), and each piece whose links and U-turns are a tenth of its
//!    time or more has its area (the lane-mask cells within half a line
//!    step of its lanes) hatched again at the two wall directions, at the
//!    walls' own strongest directions where they differ from that mean
//!    (a building with two wall systems, a hexagonal arena) and at the
//!    area's own long axis (its cells' principal axis: an arm that
//!    leaves the building's grid at a slant runs along it); where
//!    the model finds the pieces, so treated, at least 20 % faster than
//!    the chain, or at least 10 % faster where they lay at most four
//!    fifths of its lanes and two fewer at least (a warehouse aisle
//!    hatched across), they replace it (the order below then places them
//!    like any other chain). Measured on the ipa plans and the ROS maps,
//!    rooms on: 5906 → 5834 s and 4937 → 4898 s mean estimated time,
//!    then 5802 → 5804 s and 4840 → 4808 s with the looser margin
//!    (`docs/efficiency.md`).
//!
//! **Small islands.** A speck, a table leg or a thin pillar in the open
//! (a blocked component of the C-space of at most (2 tool radii + 4
//! cells)² cells, off the walls) would cut every lane through the hole it
//! leaves in the lane mask, and each cut room would fall into chains of
//! its own, with a transit to the island's loop besides. Instead two runs
//! of a line whose gap holds only plannable cells and such an island are
//! one lane, driven round the island where it blocks the line, and the
//! island's loop is driven from the lane passing nearest (left at its
//! nearest point, round the loop the way the lane runs, back to that
//! point), not ordered as a node. An island up to twice as wide (a
//! pillar, a small table) still cuts the lanes, but its loop, too, is
//! driven from the lane passing nearest. Measured on rooms with 1, 4 and
//! 16 specks and on the shared maps (`docs/efficiency.md`).
//!
//! **Order.** Loops (entered and left at one of eight points) and chains
//! (entered at one of four corners, left at the opposite end) are ordered
//! by a small generalised TSP: nearest neighbour over every entry, 2-opt on
//! the order (a reversed stretch drives its chains backwards), then an
//! exact dynamic programme choosing every node's entry for that order, its
//! costs counting the turns at each junction too (off a node onto the
//! straight line to the next entry, and off that line into the node). All
//! costs are estimated seconds; a transit's is its straight line's, scaled
//! by how far the walls make the way round (a breadth-first search from
//! every end, over blocks of cells on a large region).
//!
//! Links that are not straight and clear take the shortest route,
//! straightened (string pulling over an A* route); every segment is checked by exact
//! traversal, so the path never leaves the plannable cells.
//!
//! **Detours.** The straightened loops pass some cells of the wall strip
//! just out of reach (with the contract's cell model the free cells next
//! to a ragged wall are within reach of only a few boundary cells each),
//! and lanes on lines fixed for the region leave strips where a room's
//! width is not a multiple of the spacing. Each such cell is then covered
//! by the cheapest detour in estimated time (`detours.rs`): one new
//! vertex on a nearby segment, or a shallow V that leaves and rejoins it,
//! never uncovering what the segment covered. A loop that followed the
//! staircase instead turns at almost every cell, and leaving the cells to
//! the pipeline's boundary pass costs a visit (there and back) each: both
//! were measured slower on the ipa floor plans (`docs/efficiency.md`).
//! A last pass visits any coverage cell still uncovered, nearest first,
//! so the plan is complete on the coverage grid like every complete
//! planner; the boundary pass takes what no clear detour reached.

use std::f64::consts::PI;
use std::sync::OnceLock;

use rayon::prelude::*;

use oxcover_distance::Wavefront;
use oxcover_grid::edt::{boundary_distance_sq4, center_within_sq};
use oxcover_grid::math::{fast_ceil, fast_floor};
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear, segment_distance};
use oxcover_grid::{Cell, Dir4, Grid, Vector};

use crate::buckets::Buckets;
use crate::detours::{
    Detours, Tightening, cell_box, heading_change, insert_detours, metric_reach, polyline_time,
};
use crate::error::{Error, Result};
use crate::metre_path::PathBuilder;
use crate::planner::{Planner, PlannerOptions};
use crate::problem::{PlanOutput, PlannerInput};
use crate::time::TimeModel;

/// The `lanes` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lanes {
    /// Fixed lane angle in degrees (map frame); `None` = fastest per region.
    angle_deg: Option<f64>,
}

impl Lanes {
    /// Lanes at each region's fastest angle.
    #[must_use]
    pub const fn new() -> Self {
        Self { angle_deg: None }
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
        let plan = plan_lanes(input, self.angle_deg)?;
        Ok(PlanOutput::Metres(plan))
    }
}

/// Factor by which an angle must beat the wall directions to be chosen
/// (measured on the 31 shared maps, `lanes` rooms on, mean estimated time
/// ipa plans / ROS maps: 1.10 5824 / 4868 s, 1.07 5824 / 4858, 1.05 5822 /
/// 4858, 1.03 5822 / 4850, 1.0 5830 / 4869; 1.05 is the middle of the
/// margins that gain, slower on one plan, lab_c rooms off +0.6 %).
const WALL_PREFERENCE: f64 = 1.05;
/// Shift of every lane line off the cell edges it would otherwise run
/// along (cells).
const EDGE_NUDGE: f64 = 1e-4;
/// Most nodes the order's 2-opt runs on.
const TWO_OPT_LIMIT: usize = 600;
/// The cheapest lane angles (by their chains) whose order is planned to
/// compare transits too, if within [`NEAR_TIE`] of the cheapest.
const ANGLES_ORDERED: usize = 3;
/// How much dearer than the cheapest (by its chains) an angle may be and
/// still have its transits compared.
const NEAR_TIE: f64 = 1.15;
/// Of the angles ordered, how many (the cheapest with their transits) are
/// built to the end (detours, tightening) and compared by the final
/// path's estimated time.
const ANGLES_BUILT: usize = 2;
/// Angle builds (each a whole plan: detours, tightening) a plan may spend,
/// in plannable cells: a plan of `n` cells builds `BUILD_BUDGET / n` of its
/// angles, at least [`ANGLES_BUILT`]; small maps try every angle to the end.
const BUILD_BUDGET: usize = 200_000;
/// Entry points tried per loop.
const LOOP_ENTRIES: usize = 8;
/// Largest island that lanes pass: at most (`ISLAND_SPAN` tool radii + 4
/// cells)² blocked cells of the C-space (with robot = tool radius, an
/// obstacle of about 0.2 m: a table leg, a thin pillar, a scanner's
/// speck). Larger islands, the pillar arenas' among them, were slower
/// passed this way (measured: `docs/efficiency.md`).
const ISLAND_SPAN: f64 = 2.0;
/// Largest island whose loop a lane drives as an excursion, as
/// [`ISLAND_SPAN`]: islands up to twice as wide across (a pillar, a
/// small table) cut the lanes beside them, yet their loops are still
/// driven from the lane passing nearest rather than reached as nodes of
/// the order of their own (measured: `docs/efficiency.md`).
const SPLICE_SPAN: f64 = 4.0;
/// How much slower than the fastest an angle's path may be after its
/// first tightening pass and still be built to the end: the passes after
/// the first never made up more on the 31 shared maps (measured, rooms on
/// and off: 136 of 410 builds stop early, none that would have won).
const LAST_PASSES_GAIN: f64 = 0.05;

/// An angle built: its path's estimated time after its detours and first
/// tightening pass, and the finished path with its estimated time (none
/// where it stopped then, too slow to be kept).
type Built<'a> = (f64, Option<(f64, PathBuilder<'a>)>);
/// An angle ordered: its modelled time, chains, order and splices.
type Ordered = (f64, Vec<Chain>, Tour, Vec<Splice>);

fn plan_lanes<'a>(
    input: &PlannerInput<'a>,
    angle_deg: Option<f64>,
) -> Result<Vec<oxcover_grid::Point>> {
    let plannable = input.plannable;
    // Where the robot stands: a path from its coverage cell's representative
    // would begin with a detour to it and back.
    let start = if plannable[input.start_cell] {
        input.start_cell
    } else {
        input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))?
    };
    let time = input.time;
    let tool = input.tool_cells.max(0.5);
    // A tool narrower than a cell: lanes through the cell centres, one row
    // or column apart, along the grid's axes only.
    let narrow = tool < 1.0;
    // The loops, the lane mask and the small islands, side by side
    // (independent). The lane mask's clearance (4·d², cells, to its
    // nearest outside cell's boundary) lets each line skip the samples
    // surely inside it. Lanes run past a small island, and a lane passing
    // by drives its loop.
    let (loops, ((lane_mask, mask_clearance), island_sizes)) = rayon::join(
        || edge_loops(plannable, input.admissible),
        || {
            rayon::join(
                || {
                    let mask = lane_mask(plannable, input.admissible, tool);
                    let clearance = boundary_distance_sq4(&mask.map(|&m| !m), true).into_vec();
                    (mask, clearance)
                },
                || (!narrow).then(|| island_masks(plannable, tool)),
            )
        },
    );
    // Islands that lanes pass, and islands whose loops lanes drive.
    let (islands, spliced) = island_sizes.unzip();
    // Lines one tool width apart, less the margin of the contract's samples
    // (a quarter of a cell apart along the path).
    let spacing = if narrow {
        1.0
    } else {
        2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999
    };
    // The outermost lines sit further in than the lane mask's edge, where
    // their reach meets the loops' (a loop runs `OUTSET` off the boundary
    // cells' centres, towards the wall, and reaches a tool radius from
    // there; the mask's edge is a cell and a tool radius from the wall):
    // a line less along every wall. A room cut, where no loop runs, is a
    // cell from the claimed cells' edge: the line still reaches past it.
    let line_inset = if narrow {
        0.0
    } else {
        (tool - OUTSET - LINE_MARGIN).max(0.0)
    };
    let res_m = input.frame.resolution();
    let cell_time = TimeModel {
        linear_speed: time.linear_speed / res_m,
        angular_speed: time.angular_speed,
    };
    let wall = wall_angle(&loops);
    let candidates: Vec<f64> = match angle_deg {
        // Grid rows grow downwards: a map-frame angle a is -a here.
        Some(a) => vec![-a.to_radians()],
        None if narrow => vec![0.0, PI / 2.0],
        None => {
            let mut v = vec![wall, wall + PI / 2.0];
            v.extend((0..12).map(|k| f64::from(k) * PI / 12.0));
            v
        }
    };
    let mask_area = lane_mask.count_true() as f64;
    // Each angle's chains and modelled time, in parallel (in the order of
    // `candidates` whatever the thread count).
    let score = |(i, &theta): (usize, &f64)| {
        let clearance = Some(mask_clearance.as_slice());
        let (chains, step) = chains_bridged(
            plannable,
            &lane_mask,
            clearance,
            islands.as_ref(),
            theta,
            spacing,
            line_inset,
        );
        let mut cost = chains
            .iter()
            .map(|c| c.time(&cell_time, spacing))
            .sum::<f64>();
        // What the lanes leave of the lane mask (corners cut by slanted
        // lane ends) is covered by detours, about three times slower.
        let lanes: f64 = chains.iter().flat_map(|c| &c.lanes).map(Lane::length).sum();
        let uncovered = (mask_area - lanes * step.max(1.0)).max(0.0);
        cost += 3.0 * cell_time.time(uncovered / spacing, 0.0);
        // Near-ties go to the wall directions, tried first.
        if i >= 2 {
            cost *= WALL_PREFERENCE;
        }
        (cost, chains, step)
    };
    let mut scored: Vec<(f64, Vec<Chain>, f64)> =
        candidates.par_iter().enumerate().map(score).collect();
    // The cheapest few angles, where near ties, are compared with their
    // transits too: the order of loops and chains from the start to the
    // exit (a direction that leaves a door's stub as chains of its own, or
    // ends its lanes far from the exit, costs there).
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let exit = input.exit.filter(|&c| plannable.is_set(c)).map(cell_center);
    let cheapest = scored.first().map_or(0.0, |b| b.0);
    // A small plan can afford to build more angles than the model's best
    // few: then every one of them is ordered and built, whatever the model
    // thinks of it.
    let affordable = (BUILD_BUDGET / input.plan_cells.max(1)).min(scored.len());
    let (ordered_count, built_count, tie) = if affordable > ANGLES_BUILT {
        (affordable, affordable, f64::INFINITY)
    } else {
        (ANGLES_ORDERED, ANGLES_BUILT, NEAR_TIE)
    };
    let near_ties: Vec<(f64, Vec<Chain>, f64)> = scored
        .into_iter()
        .take(ordered_count)
        .enumerate()
        .filter(|(i, (cost, _, _))| *i == 0 || *cost <= tie * cheapest)
        .map(|(_, c)| c)
        .collect();
    // Where one angle does not suit every part of the region (an arm of a
    // corridor hatched across), a chain's area is re-hatched at a wall
    // direction where the model finds that faster ([`Hatch`]). A fixed
    // angle is kept everywhere.
    let hatch = Hatch {
        plannable,
        lane_mask: &lane_mask,
        spacing,
        inset: line_inset,
        time: &cell_time,
    };
    // The first two candidates: the wall directions (the grid's axes for
    // a tool narrower than a cell).
    let mut wall_angles: Vec<f64> = candidates.iter().take(2).copied().collect();
    if angle_deg.is_none() && !narrow {
        for other in other_wall_angles(&loops, wall) {
            wall_angles.extend([other, other + PI / 2.0]);
        }
    }
    // Each near tie ordered on its own (in parallel, each with its own
    // transit search; in the order of `near_ties` whatever the thread
    // count).
    let order_angle = |region: &mut Region<'_>, (cost, chains, step): (f64, Vec<Chain>, f64)| {
        let (chains, saving) = if angle_deg.is_none() {
            hatch.rehatch(chains, step, &wall_angles)
        } else {
            (chains, 0.0)
        };
        let splices = spliced.as_ref().map_or_else(Vec::new, |isl| {
            splices_for(&loops, &chains, isl, plannable, spacing)
        });
        let nodes = nodes_of(&loops, &chains, &splices);
        let ends = (cell_center(start), exit);
        let (order, transit) = order_nodes(&nodes, ends, region, &cell_time);
        (cost - saving + transit, chains, order, splices)
    };
    let mut ordered: Vec<Ordered> = near_ties
        .into_par_iter()
        .map_init(|| Region::new(plannable, tool), order_angle)
        .collect();
    ordered.sort_by(|a, b| a.0.total_cmp(&b.0));
    let loop_tolerance = (tool / 2.0).clamp(LOOP_TOLERANCE.0, LOOP_TOLERANCE.1);
    // What the straightened loops and the lanes' ends pass just out of
    // reach: covered by bending the path where that costs least (within
    // five tool radii of a segment).
    // The metrics' own radius (either side of their tolerance).
    let (reach, fragile) = metric_reach(input.tool_cells);
    let detours = Detours {
        plannable,
        coverable: input.coverable,
        reach,
        fragile,
        search: 5.0 * tool,
        time: cell_time,
    };
    // The model above misjudges what detours and tightening will make of
    // an angle, so the best few are built to the end (in parallel, the
    // first of equal times winning) and the fastest path is kept. Only
    // those whose path, after its detours and first tightening pass, is
    // within `LAST_PASSES_GAIN` of the fastest's then are kept: each
    // angle stops as soon as every angle's time after that pass is known
    // and it is not among them (which ones stop does not depend on which
    // angle got there first, only how much work the others did before).
    let building = built_count.min(ordered.len());
    let first_pass: Vec<OnceLock<f64>> = (0..building).map(|_| OnceLock::new()).collect();
    let behind = |time: f64| {
        let known: Option<Vec<f64>> = first_pass.iter().map(|t| t.get().copied()).collect();
        known.is_some_and(|t| {
            time > (1.0 + LAST_PASSES_GAIN) * t.into_iter().fold(f64::INFINITY, f64::min)
        })
    };
    let build = |(i, (_, chains, order, splices)): (usize, &Ordered)| -> Result<Built<'a>> {
        let nodes = nodes_of(&loops, chains, splices);
        let first_chain = nodes.len() - chains.len();
        let mut path = PathBuilder::new(plannable, start);
        for &(node, option) in order {
            match nodes[node] {
                Node::Loop(l) => drive_loop(&mut path, l, option, loop_tolerance)?,
                Node::Chain(c) => {
                    let here: Vec<&Splice> = splices
                        .iter()
                        .filter(|s| s.chain == node - first_chain)
                        .collect();
                    drive_chain(&mut path, c, option, &here, &loops, loop_tolerance)?;
                }
            }
        }
        let (points, count) = insert_detours(path.points(), &detours);
        // Then the vertices detours made unneeded go, and the rest move
        // towards the line of their neighbours, where coverage allows.
        let mut tightening = Tightening::new(&points, count, 0);
        tightening.pass(&detours, None);
        let first = polyline_time(&tightening.points(), &cell_time);
        // Set once, here only.
        let _ = first_pass[i].set(first);
        loop {
            if behind(first) {
                return Ok((first, None));
            }
            if !tightening.pass(&detours, None) {
                break;
            }
        }
        path.replace(tightening.finish().0);
        path.cover_leftovers(input.coarse, input.visit_radius())?;
        let to_exit = exit.map_or(0.0, |e| cell_time.time((e - path.last()).norm(), 0.0));
        Ok((
            first,
            Some((polyline_time(path.points(), &cell_time) + to_exit, path)),
        ))
    };
    let built: Vec<Result<Built<'_>>> = ordered
        .par_iter()
        .take(building)
        .enumerate()
        .map(build)
        .collect();
    let built = built.into_iter().collect::<Result<Vec<_>>>()?;
    let lead = built.iter().map(|b| b.0).fold(f64::INFINITY, f64::min);
    let mut best: Option<(f64, PathBuilder<'_>)> = None;
    for (first, b) in built {
        let Some(b) = b.filter(|_| first <= (1.0 + LAST_PASSES_GAIN) * lead) else {
            continue;
        };
        if best.as_ref().is_none_or(|x| b.0 < x.0) {
            best = Some(b);
        }
    }
    let (_, path) = best.ok_or_else(|| Error::Internal("no lane angle was built".into()))?;
    Ok(path.into_metres(&input.frame))
}

/// Where lanes may run: the plannable cells at least a cell and a tool
/// radius (`tool` cells) from every non-admissible cell and from the
/// grid's edge. Walls only: a room cut is no wall, lanes run up to it.
fn lane_mask(plannable: &Grid<bool>, admissible: &Grid<bool>, tool: f64) -> Grid<bool> {
    let blocked = admissible.map(|&a| !a);
    let inset = 1.0 + tool;
    // An integer d² is at least inset² when at least its ceiling: not
    // within one less.
    let near = center_within_sq(&blocked, (inset * inset).ceil() as u64 - 1);
    let (w, h) = (plannable.width(), plannable.height());
    Grid::from_fn(w, h, |c| {
        // Beyond the grid counts as blocked too.
        let edge = (c.row + 1).min(c.col + 1).min(h - c.row).min(w - c.col) as f64;
        plannable[c] && !near[c] && edge >= inset
    })
}

// ---------------------------------------------------------------- loops

/// A traced contour, or the part of one that runs along walls: 4-connected
/// pieces of boundary cells (a diagonal step squeezing between two blocked
/// cells starts a new piece). A closed loop is driven round from any of its
/// entries back to it; an open run (a contour cut where the region borders
/// another room's plannable cells) from one end to the other.
#[derive(Clone, Debug, PartialEq)]
struct EdgeLoop {
    pieces: Vec<Vec<Cell>>,
    closed: bool,
}

impl EdgeLoop {
    #[cfg(test)]
    fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        self.pieces.iter().flatten().copied()
    }

    fn len(&self) -> usize {
        self.pieces.iter().map(Vec::len).sum()
    }

    /// The `k`-th of `LOOP_ENTRIES` evenly spaced entry cells.
    fn entry(&self, k: usize) -> (usize, usize) {
        let n = self.len();
        let mut i = (k * n) / LOOP_ENTRIES;
        for (p, piece) in self.pieces.iter().enumerate() {
            if i < piece.len() {
                return (p, i);
            }
            i -= piece.len();
        }
        (0, 0)
    }
}

/// Clockwise neighbours in grid coordinates (row down): W, NW, N, NE, E, SE, S, SW.
const RING: [(isize, isize); 8] = [
    (0, -1),
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
    (1, 0),
    (1, -1),
];

fn set_at(mask: &Grid<bool>, c: Cell, d: (isize, isize)) -> Option<Cell> {
    mask.offset(c, d).filter(|&n| mask[n])
}

/// Every contour of `mask` (outer boundaries and holes), traced by Moore
/// neighbour tracing from each boundary cell whose west neighbour is not set
/// and that no earlier contour passed, keeping only the cells along walls:
/// a boundary cell all of whose outside neighbours are `admissible` borders
/// another region (a room cut), not a wall, and is left out, which opens
/// the contour into runs.
fn edge_loops(mask: &Grid<bool>, admissible: &Grid<bool>) -> Vec<EdgeLoop> {
    let mut on_contour = Grid::new(mask.width(), mask.height(), false);
    let mut loops = Vec::new();
    let by_wall = |c: Cell| {
        RING.iter().any(|&d| match mask.offset(c, d) {
            None => true,
            Some(n) => !mask[n] && !admissible[n],
        })
    };
    for s in mask.true_cells() {
        if on_contour[s] || set_at(mask, s, (0, -1)).is_some() {
            continue;
        }
        let trace = moore_trace(mask, s);
        for &c in &trace {
            on_contour[c] = true;
        }
        let walls: Vec<bool> = trace.iter().map(|&c| by_wall(c)).collect();
        if walls.iter().all(|&w| w) {
            loops.push(EdgeLoop {
                pieces: four_connected_pieces(mask, &trace, true),
                closed: true,
            });
            continue;
        }
        // Open runs: start after a cut cell so that no run wraps around.
        let n = trace.len();
        let first_cut = walls.iter().position(|&w| !w).unwrap_or(0);
        let mut run: Vec<Cell> = Vec::new();
        for k in 1..=n {
            let i = (first_cut + k) % n;
            if walls[i] {
                run.push(trace[i]);
            } else if !run.is_empty() {
                loops.push(EdgeLoop {
                    pieces: four_connected_pieces(mask, &run, false),
                    closed: false,
                });
                run.clear();
            }
        }
        if !run.is_empty() {
            loops.push(EdgeLoop {
                pieces: four_connected_pieces(mask, &run, false),
                closed: false,
            });
        }
    }
    loops
}

/// The closed Moore trace from `s` (its west neighbour unset), ending
/// before it returns to `s` the way it first left (Jacob's criterion).
fn moore_trace(mask: &Grid<bool>, s: Cell) -> Vec<Cell> {
    let Some((n1, b1)) = moore_step(mask, s, 0) else {
        return vec![s];
    };
    let mut trace = vec![s];
    let (mut here, mut back) = (n1, b1);
    let limit = 4 * mask.count_true() + 8;
    for _ in 0..limit {
        if here == s {
            let Some((n, b)) = moore_step(mask, s, back) else {
                break;
            };
            if n == n1 {
                break;
            }
            trace.push(s);
            (here, back) = (n, b);
            continue;
        }
        trace.push(here);
        match moore_step(mask, here, back) {
            Some((n, b)) => (here, back) = (n, b),
            None => break,
        }
    }
    trace
}

/// The next contour cell clockwise around `here` from the unset neighbour
/// at ring index `back`, and the new backtrack index seen from it.
fn moore_step(mask: &Grid<bool>, here: Cell, back: usize) -> Option<(Cell, usize)> {
    for k in 1..=8 {
        let idx = (back + k) % 8;
        if let Some(n) = set_at(mask, here, RING[idx]) {
            // The neighbour checked just before (unset), seen from `n`.
            let prev = RING[(idx + 7) % 8];
            let from_n = (
                here.row as isize + prev.0 - n.row as isize,
                here.col as isize + prev.1 - n.col as isize,
            );
            let b = RING.iter().position(|&d| d == from_n).unwrap_or(0);
            return Some((n, b));
        }
    }
    None
}

/// Splits an 8-connected trace (closed: back to its first cell) into
/// 4-connected pieces: a diagonal step gets the plannable cell beside it, or
/// starts a new piece when both are blocked; a larger jump starts a new piece.
fn four_connected_pieces(mask: &Grid<bool>, trace: &[Cell], close: bool) -> Vec<Vec<Cell>> {
    let mut pieces = vec![Vec::new()];
    let mut closed: Vec<Cell> = trace.to_vec();
    if let (true, Some(&f)) = (close, trace.first()) {
        closed.push(f);
    }
    for (i, &c) in closed.iter().enumerate() {
        if i == 0 {
            pieces[0].push(c);
            continue;
        }
        let a = closed[i - 1];
        let (dr, dc) = (
            c.row as isize - a.row as isize,
            c.col as isize - a.col as isize,
        );
        if dr != 0 && dc != 0 {
            let side = set_at(mask, a, (dr, 0)).or_else(|| set_at(mask, a, (0, dc)));
            match side {
                Some(m) => pieces.last_mut().map(|p| p.push(m)).unwrap_or_default(),
                None => pieces.push(Vec::new()),
            }
        }
        if let Some(p) = pieces.last_mut() {
            if p.last() != Some(&c) {
                p.push(c);
            }
        }
    }
    pieces.retain(|p| !p.is_empty());
    pieces
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
/// How much wall a second direction needs, as a share of the main one's.
/// Measured, `lanes` mean estimated time rooms on, ipa plans / ROS maps
/// (`docs/efficiency.md`): 0.5 5814 / 4842 s, 0.25 5811 / 4841 s, 0.1
/// 5802 / 4840 s (kept: no plan slower than without the peaks), 0.05
/// 5802 / 4839 s; without the peaks 5815 / 4844 s.
const SECOND_WALL_SHARE: f64 = 0.1;

/// Straightening tolerance of edge loops: half the tool radius, within
/// these bounds (cells). A loop through every boundary cell would cover the
/// whole strip along walls but turns at every pixel of a ragged wall. The
/// upper bound stays under one cell: a staircase's steps sit a whole cell
/// off the line that cuts them, and a loop allowed to skip them passes so
/// much of the strip out of reach that the detours cost more than the
/// straightening saved. `tighten` then removes, moves and slides the
/// loop's vertices wherever coverage allows (measured in
/// `docs/efficiency.md`: 1.0 → 0.8 cell raised the ipa plans' time
/// efficiency from 0.345 to 0.399, rooms off).
const LOOP_TOLERANCE: (f64, f64) = (0.25, 0.8);

/// The point of boundary cell `c` pushed towards its non-plannable
/// neighbours, at most `OUTSET` of a cell from its centre along each axis
/// (so still inside the cell).
fn outset_point(mask: &Grid<bool>, c: Cell) -> GridPoint {
    let (mut x, mut y) = (0.0, 0.0);
    for &(dr, dc) in &RING {
        if set_at(mask, c, (dr, dc)).is_none() {
            let n = ((dr * dr + dc * dc) as f64).sqrt();
            x += dc as f64 / n;
            y += dr as f64 / n;
        }
    }
    let centre = cell_center(c);
    let n = x.hypot(y);
    if n < 1e-9 {
        return centre;
    }
    let (ux, uy) = (x / n, y / n);
    let t = OUTSET / ux.abs().max(uy.abs());
    GridPoint::new(centre.x + t * ux, centre.y + t * uy)
}

/// How far a loop point sits from its cell's centre, towards the walls (cells).
const OUTSET: f64 = 0.45;
/// By how much (cells) the outermost lanes' reach still overlaps the
/// loops' (`docs/efficiency.md` gives the margins measured).
const LINE_MARGIN: f64 = 0.05;

fn drive_loop(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    option: usize,
    tolerance: f64,
) -> Result<()> {
    let entry = l.closed.then(|| l.entry(option));
    drive_loop_from(path, l, option, entry, tolerance)
}

fn drive_loop_from(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    option: usize,
    entry: Option<(usize, usize)>,
    tolerance: f64,
) -> Result<()> {
    let seq: Vec<Vec<Cell>> = if let Some((p, i)) = entry {
        // The loop from its entry: the rest of the entry piece, the other
        // pieces, the start of the entry piece, back to the entry.
        let mut seq = vec![l.pieces[p][i..].to_vec()];
        for k in 1..l.pieces.len() {
            seq.push(l.pieces[(p + k) % l.pieces.len()].clone());
        }
        // The last piece of a closed loop ends at the first cell: entered
        // there, the loop is done; entered later, finish the first piece.
        if (p, i) != (0, 0) {
            seq.push(l.pieces[p][..=i].to_vec());
        }
        seq
    } else if option == 0 {
        l.pieces.clone()
    } else {
        l.pieces
            .iter()
            .rev()
            .map(|p| p.iter().rev().copied().collect())
            .collect()
    };
    let mask = path.mask();
    for piece in &seq {
        let Some(&first) = piece.first() else {
            continue;
        };
        path.go_to(cell_center(first))?;
        // Outset points, with the cell centres between two of them whose
        // straight join is not clear.
        let mut targets: Vec<GridPoint> = Vec::with_capacity(piece.len());
        let mut prev = path.last();
        for (k, &c) in piece.iter().enumerate() {
            let q = outset_point(mask, c);
            if !segment_clear(mask, prev, q) {
                if k > 0 {
                    targets.push(cell_center(piece[k - 1]));
                }
                targets.push(cell_center(c));
            }
            targets.push(q);
            prev = q;
        }
        if let Some(&last) = piece.last() {
            targets.push(cell_center(last));
        }
        path.follow_points(targets, |a, b, skipped| {
            skipped
                .iter()
                .all(|&m| segment_distance(a, b, m) <= tolerance)
        });
    }
    Ok(())
}

// ---------------------------------------------------------------- lanes

/// A lane: a clear straight segment in grid coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lane {
    a: GridPoint,
    b: GridPoint,
}

impl Lane {
    fn length(&self) -> f64 {
        (self.b - self.a).norm()
    }
}

/// Lanes on consecutive lines driven back and forth.
#[derive(Clone, Debug, PartialEq)]
struct Chain {
    lanes: Vec<Lane>,
}

impl Chain {
    /// Estimated seconds: lanes and links at speed, a half turn per link,
    /// and a turn plus a spacing of transit per chain.
    fn time(&self, t: &TimeModel, spacing: f64) -> f64 {
        let lanes: f64 = self.lanes.iter().map(Lane::length).sum();
        let links = self.lanes.len().saturating_sub(1) as f64;
        t.time(lanes + links * spacing, links * PI) + t.time(spacing, PI / 2.0)
    }

    /// Entry and exit of option `k` (bit 0: from the last lane; bit 1:
    /// starting at each lane's `b` end).
    fn ends(&self, k: usize) -> (GridPoint, GridPoint) {
        let seq = self.sequence(k);
        (seq[0], seq[seq.len() - 1])
    }

    /// The points driven under option `k`.
    fn sequence(&self, k: usize) -> Vec<GridPoint> {
        let backwards = k & 1 == 1;
        let mut flip = k & 2 == 2;
        let idx: Vec<usize> = if backwards {
            (0..self.lanes.len()).rev().collect()
        } else {
            (0..self.lanes.len()).collect()
        };
        let mut pts = Vec::with_capacity(2 * idx.len());
        for i in idx {
            let l = self.lanes[i];
            if flip {
                pts.extend([l.b, l.a]);
            } else {
                pts.extend([l.a, l.b]);
            }
            flip = !flip;
        }
        pts
    }
}

/// A small island's loop driven as an excursion from the lane passing
/// nearest: the lane is left at the point nearest the loop, the loop is
/// driven round from there (the way the lane runs), and the lane goes on
/// from the same point.
#[derive(Clone, Debug, PartialEq)]
struct Splice {
    /// The chain and its lane.
    chain: usize,
    lane: usize,
    /// Where along the lane: 0 at its `a` end, 1 at `b`.
    u: f64,
    /// The loop, and the cell it is entered at (piece, index).
    loop_index: usize,
    entry: (usize, usize),
}

/// The splices of the loops round `islands`: each closed loop all of whose
/// cells border an island cell goes to the lane whose nearest point to one of its cells is
/// nearest, plannable and in clear sight of that cell, among the lanes
/// within two lane spacings of the loop's box; a loop with no such lane
/// stays a node of the order.
fn splices_for(
    loops: &[EdgeLoop],
    chains: &[Chain],
    islands: &Grid<bool>,
    plannable: &Grid<bool>,
    spacing: f64,
) -> Vec<Splice> {
    let margin = 2.0 * spacing.max(1.0);
    let mut out = Vec::new();
    for (li, l) in loops.iter().enumerate() {
        let round_island = l.closed
            && l.pieces.iter().flatten().all(|&c| {
                RING.iter()
                    .any(|&d| islands.offset(c, d).is_some_and(|n| islands[n]))
            });
        if !round_island {
            continue;
        }
        let cells: Vec<(GridPoint, (usize, usize))> = l
            .pieces
            .iter()
            .enumerate()
            .flat_map(|(p, piece)| {
                piece
                    .iter()
                    .enumerate()
                    .map(move |(i, &c)| (cell_center(c), (p, i)))
            })
            .collect();
        let (lo, hi) = cells.iter().fold(
            (
                GridPoint::new(f64::INFINITY, f64::INFINITY),
                GridPoint::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            ),
            |(lo, hi), (q, _)| (lo.inf(q), hi.sup(q)),
        );
        let mut best: Option<(f64, Splice)> = None;
        for (ci, c) in chains.iter().enumerate() {
            for (ki, lane) in c.lanes.iter().enumerate() {
                let (a, b) = (lane.a, lane.b);
                if a.x.max(b.x) < lo.x - margin
                    || a.x.min(b.x) > hi.x + margin
                    || a.y.max(b.y) < lo.y - margin
                    || a.y.min(b.y) > hi.y + margin
                {
                    continue;
                }
                let d = b - a;
                let len2 = d.norm_squared();
                for &(q, entry) in &cells {
                    let u = if len2 > 0.0 {
                        ((q - a).dot(&d) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let at = a + d * u;
                    let dist = (at - q).norm();
                    if best.as_ref().is_some_and(|b| dist >= b.0) {
                        continue;
                    }
                    if cell_of(plannable, at).is_some_and(|x| plannable[x])
                        && segment_clear(plannable, at, q)
                    {
                        let splice = Splice {
                            chain: ci,
                            lane: ki,
                            u,
                            loop_index: li,
                            entry,
                        };
                        best = Some((dist, splice));
                    }
                }
            }
        }
        out.extend(best.map(|(_, s)| s));
    }
    out
}

/// The nodes of the order: the loops no lane drives, then the chains.
fn nodes_of<'n>(loops: &'n [EdgeLoop], chains: &'n [Chain], splices: &[Splice]) -> Vec<Node<'n>> {
    let mut driven = vec![false; loops.len()];
    for s in splices {
        driven[s.loop_index] = true;
    }
    let mut nodes: Vec<Node> = loops
        .iter()
        .zip(driven)
        .filter(|(_, d)| !d)
        .map(|(l, _)| Node::Loop(l))
        .collect();
    nodes.extend(chains.iter().map(Node::Chain));
    nodes
}

/// Drives chain `c` under `option`: each lane along its line (round any
/// island it passes), with the loops of `splices` (this chain's) driven
/// from their lanes.
fn drive_chain(
    path: &mut PathBuilder<'_>,
    c: &Chain,
    option: usize,
    splices: &[&Splice],
    loops: &[EdgeLoop],
    tolerance: f64,
) -> Result<()> {
    let backwards = option & 1 == 1;
    let mut flip = option & 2 == 2;
    let idx: Vec<usize> = if backwards {
        (0..c.lanes.len()).rev().collect()
    } else {
        (0..c.lanes.len()).collect()
    };
    for k in idx {
        let l = c.lanes[k];
        let (from, to) = if flip { (l.b, l.a) } else { (l.a, l.b) };
        path.go_to(from)?;
        let mut here: Vec<(f64, &Splice)> = splices
            .iter()
            .filter(|s| s.lane == k)
            .map(|s| (if flip { 1.0 - s.u } else { s.u }, *s))
            .collect();
        here.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (v, s) in here {
            let at = from + (to - from) * v;
            path.go_along(at)?;
            drive_splice(path, &loops[s.loop_index], s.entry, to - from, tolerance)?;
            path.go_to(at)?;
        }
        path.go_along(to)?;
        flip = !flip;
    }
    Ok(())
}

/// Drives closed loop `l` from its cell `entry` back to it, round the way
/// that leaves the entry along `heading` rather than against it.
fn drive_splice(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    entry: (usize, usize),
    heading: Vector,
    tolerance: f64,
) -> Result<()> {
    let (p, i) = entry;
    let flat: Vec<Cell> = l.pieces.iter().flatten().copied().collect();
    let e: usize = l.pieces[..p].iter().map(Vec::len).sum::<usize>() + i;
    let m = flat.len();
    let ahead = cell_center(flat[(e + 2) % m]) - cell_center(flat[(e + m - 2) % m]);
    path.go_to(cell_center(l.pieces[p][i]))?;
    if ahead.dot(&heading) < 0.0 {
        let reversed = EdgeLoop {
            pieces: l
                .pieces
                .iter()
                .rev()
                .map(|q| q.iter().rev().copied().collect())
                .collect(),
            closed: true,
        };
        let entry = (l.pieces.len() - 1 - p, l.pieces[p].len() - 1 - i);
        drive_loop_from(path, &reversed, 0, Some(entry), tolerance)
    } else {
        drive_loop_from(path, l, 0, Some(entry), tolerance)
    }
}

/// The chains of lanes at direction `theta` (grid coordinates), lines at
/// most `spacing` apart spread evenly over the lane mask's extent less
/// `inset` at either side, and the distance between lines.
fn chains_at(
    plannable: &Grid<bool>,
    lane_mask: &Grid<bool>,
    clearance: Option<&[u64]>,
    theta: f64,
    spacing: f64,
    inset: f64,
) -> (Vec<Chain>, f64) {
    chains_bridged(plannable, lane_mask, clearance, None, theta, spacing, inset)
}

/// [`chains_at`], with two runs of a line joined into one lane where the
/// gap between them holds only plannable cells and cells of `islands`
/// (and some of the latter): the lane is driven round the island.
fn chains_bridged(
    plannable: &Grid<bool>,
    lane_mask: &Grid<bool>,
    clearance: Option<&[u64]>,
    islands: Option<&Grid<bool>>,
    theta: f64,
    spacing: f64,
    inset: f64,
) -> (Vec<Chain>, f64) {
    let d = GridPoint::new(theta.cos(), theta.sin());
    let n = GridPoint::new(-d.y, d.x);
    let (mut nmin, mut nmax) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut dmin, mut dmax) = (f64::INFINITY, f64::NEG_INFINITY);
    // The mask's box (cells), for the samples below.
    let (mut rmin, mut rmax, mut cmin, mut cmax) = (usize::MAX, 0, usize::MAX, 0);
    for row in 0..lane_mask.height() {
        let cells = lane_mask.row(row);
        let (Some(first), Some(last)) = (
            cells.iter().position(|&x| x),
            cells.iter().rposition(|&x| x),
        ) else {
            continue;
        };
        (rmin, rmax) = (rmin.min(row), rmax.max(row));
        (cmin, cmax) = (cmin.min(first), cmax.max(last));
        // Along a row both projections are monotone in the column (so is
        // their rounding): a row's first and last cells hold its extremes.
        for col in [first, last] {
            let p = cell_center(Cell::new(row, col));
            let (u, v) = (p.x * d.x + p.y * d.y, p.x * n.x + p.y * n.y);
            nmin = nmin.min(v);
            nmax = nmax.max(v);
            dmin = dmin.min(u);
            dmax = dmax.max(u);
        }
    }
    if !nmin.is_finite() {
        return (Vec::new(), spacing);
    }
    let inset = inset.min((nmax - nmin) / 2.0);
    let (nmin, nmax) = (nmin + inset, nmax - inset);
    let extent = nmax - nmin;
    let lines = (extent / spacing).ceil().max(0.0) as usize + 1;
    let step = if lines > 1 {
        extent / (lines - 1) as f64
    } else {
        0.0
    };
    let at = |u: f64, v: f64| GridPoint::new(u * d.x + v * n.x, u * d.y + v * n.y);
    // Runs of the lane mask along each line, sampled every quarter cell.
    let mut rows: Vec<Vec<(f64, f64)>> = Vec::with_capacity(lines);
    // Samples and lines off the cell edges (a point exactly on an edge is
    // in one cell here and may be in its neighbour once in metres).
    let (u0, u1) = (dmin - 1.0 + 0.125, dmax + 1.0);
    let samples = ((u1 - u0) / 0.25).ceil() as usize;
    // The samples of a line that may fall in the mask's box widened by a
    // cell (the margin covers rounding): those before and after are
    // outside the mask, and a run neither starts nor goes on there.
    let in_box = |v: f64| -> std::ops::Range<usize> {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for (dk, nk, k0, k1) in [
            (d.x, n.x, cmin as f64 - 1.0, cmax as f64 + 2.0),
            (d.y, n.y, rmin as f64 - 1.0, rmax as f64 + 2.0),
        ] {
            // u·dk + v·nk within [k0, k1].
            if dk.abs() < 1e-12 {
                if !(k0..=k1).contains(&(v * nk)) {
                    return 0..0;
                }
            } else {
                let (a, b) = ((k0 - v * nk) / dk, (k1 - v * nk) / dk);
                lo = lo.max(a.min(b));
                hi = hi.min(a.max(b));
            }
        }
        if lo > hi {
            return 0..0;
        }
        let first = fast_floor((lo - u0) / 0.25 - 1.0).max(0.0);
        let last = fast_ceil((hi - u0) / 0.25 + 1.0).min(samples as f64);
        if first > last {
            return 0..0;
        }
        first as usize..last as usize + 1
    };
    let (w, h) = (lane_mask.width() as f64, lane_mask.height() as f64);
    let (mask, width) = (lane_mask.as_slice(), lane_mask.width());
    for j in 0..lines {
        let v = nmin + step * j as f64 + EDGE_NUDGE;
        let mut runs = Vec::new();
        let mut open: Option<f64> = None;
        let mut last_in = u0;
        // `at(u, v)` and `cell_of` on the lane mask, term for term, with
        // the line's own terms once per line.
        let (vx, vy) = (v * n.x, v * n.y);
        let range = in_box(v);
        let mut s = range.start;
        while s < range.end {
            let u = u0 + s as f64 * 0.25;
            let (x, y) = (u * d.x + vx, u * d.y + vy);
            let cell = (x >= 0.0 && y >= 0.0 && x < w && y < h)
                .then(|| (fast_floor(x), fast_floor(y)))
                .filter(|&(cx, cy)| mask[cy as usize * width + cx as usize]);
            let inside = cell.is_some();
            match (inside, open) {
                (true, None) => open = Some(u),
                (false, Some(o)) => {
                    runs.push((o, last_in));
                    open = None;
                }
                _ => {}
            }
            if let Some((cx, cy)) = cell {
                last_in = u;
                // The next samples within the cell's clearance less the
                // sample's offset from its centre are inside too.
                if let Some(clear4) = clearance {
                    let reach = (clear4[cy as usize * width + cx as usize] as f64).sqrt() / 2.0
                        - (x - cx - 0.5).hypot(y - cy - 0.5)
                        - JUMP_MARGIN;
                    let k = (reach / 0.25).max(0.0) as usize;
                    if k > 0 {
                        s = (s + k).min(range.end - 1);
                        last_in = u0 + s as f64 * 0.25;
                    }
                }
            }
            s += 1;
        }
        if let Some(o) = open {
            runs.push((o, last_in));
        }
        // Keep the clear part of each run (a run may graze a blocked
        // corner between samples): split at the first blocked stretch.
        let mut clear = Vec::new();
        for (a, b) in runs {
            split_clear(plannable, &at, v, a, b, &mut clear);
        }
        if let Some(isl) = islands {
            let mut merged: Vec<(f64, f64)> = Vec::with_capacity(clear.len());
            for r in clear {
                if let Some(last) = merged.last_mut() {
                    if bridgeable(plannable, isl, &at, v, last.1, r.0) {
                        last.1 = r.1;
                        continue;
                    }
                }
                merged.push(r);
            }
            clear = merged;
        }
        rows.push(clear);
    }
    // Chain runs of consecutive lines that overlap one to one.
    let overlaps = |x: (f64, f64), y: (f64, f64)| x.0.max(y.0) <= x.1.min(y.1);
    let mut chains: Vec<Chain> = Vec::new();
    let mut open_chain: Vec<Option<usize>> = Vec::new(); // per run of the previous line
    for j in 0..rows.len() {
        let mut now: Vec<Option<usize>> = vec![None; rows[j].len()];
        for (i, &r) in rows[j].iter().enumerate() {
            let v = nmin + step * j as f64 + EDGE_NUDGE;
            let lane = Lane {
                a: at(r.0, v),
                b: at(r.1, v),
            };
            let mut joined = None;
            if j > 0 {
                let prev: Vec<usize> = (0..rows[j - 1].len())
                    .filter(|&k| overlaps(rows[j - 1][k], r))
                    .collect();
                if let [k] = prev[..] {
                    let forward = rows[j]
                        .iter()
                        .filter(|&&q| overlaps(rows[j - 1][k], q))
                        .count();
                    if forward == 1 {
                        joined = open_chain.get(k).copied().flatten();
                    }
                }
            }
            let id = match joined {
                Some(id) => {
                    chains[id].lanes.push(lane);
                    id
                }
                None => {
                    chains.push(Chain { lanes: vec![lane] });
                    chains.len() - 1
                }
            };
            now[i] = Some(id);
        }
        open_chain = now;
    }
    (chains, if lines > 1 { step } else { spacing })
}

/// Slack (cells) kept when a line skips the samples within a mask cell's
/// clearance: rounding never decides that a sample is inside.
const JUMP_MARGIN: f64 = 1e-6;

/// What re-hatching a chain's area at another angle needs.
struct Hatch<'a> {
    plannable: &'a Grid<bool>,
    lane_mask: &'a Grid<bool>,
    spacing: f64,
    inset: f64,
    time: &'a TimeModel,
}

/// Fewest lanes a chain must have to be re-hatched.
const REHATCH_MIN_LANES: usize = 3;
/// How much faster (modelled) a re-hatched area must be than its chain
/// (measured on both map sets: 0.8, 0.9 and 0.95 within 0.002 of each
/// other in mean time efficiency; 0.8 slows the fewest maps and by the
/// least, `docs/efficiency.md`).
const REHATCH_GAIN: f64 = 0.8;
/// The margin for a re-hatch that lays the area's lanes anew, at most
/// [`REHATCH_LANES`] of the chain's and two fewer at least: fewer lanes
/// are fewer U-turns whatever the model leaves out, where a chain only
/// cut into its pieces, or re-laid with about as many lanes, gains
/// what the model counts and loses the transits between the new chains
/// it does not (measured, `docs/efficiency.md`).
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

impl Hatch<'_> {
    /// Each chain's area (the lane-mask cells within half a line step of
    /// one of its lanes) re-hatched at the angle of `angles` whose chains
    /// the model finds fastest there, where that beats the chain by
    /// [`REHATCH_GAIN`]; and the modelled seconds saved.
    /// `step` is the distance between the chains' lines ([`chains_at`]).
    fn rehatch(&self, chains: Vec<Chain>, step: f64, angles: &[f64]) -> (Vec<Chain>, f64) {
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
            let t: f64 = chains.iter().map(|c| c.time(self.time, self.spacing)).sum();
            let lanes: f64 = chains.iter().flat_map(|c| &c.lanes).map(Lane::length).sum();
            let uncovered = (area - lanes * step.max(1.0)).max(0.0);
            t + 3.0 * self.time.time(uncovered / self.spacing, 0.0)
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
/// direction to be tried as a re-hatching angle of its own. Measured with
/// the axis added, `lanes` mean estimated time rooms on / off, ROS maps:
/// 0.5° 4844 / 4857 s (kept), 2° 4845 / 4858 s, 5° 4846 / 4884 s, without
/// the axis 4847 / 4886 s (`docs/efficiency.md`).
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

/// Pushes the clear sub-runs of `[a, b]` on line `v` into `out`.
/// Whether the gap `a..b` of line `v` holds only plannable and island
/// cells, and at least one island cell.
fn bridgeable(
    plannable: &Grid<bool>,
    islands: &Grid<bool>,
    at: &impl Fn(f64, f64) -> GridPoint,
    v: f64,
    a: f64,
    b: f64,
) -> bool {
    let mut island = false;
    let mut u = a;
    while u <= b {
        let Some(c) = cell_of(plannable, at(u, v)) else {
            return false;
        };
        if islands[c] {
            island = true;
        } else if !plannable[c] {
            return false;
        }
        u += 0.25;
    }
    island
}

/// The small islands of blocked cells: 4-connected components of the
/// cells that are not plannable, of at most `max_cells` cells, off the
/// grid's edge and touching no other blocked component even diagonally.
/// Each island cell holds its island's size in cells, every other cell 0.
fn small_islands(plannable: &Grid<bool>, max_cells: usize) -> Grid<usize> {
    let blocked = plannable.map(|&p| !p);
    let comps = oxcover_grid::components::components4(&blocked);
    let mut ok = vec![false; comps.count() + 1];
    for (i, &n) in comps.sizes.iter().enumerate() {
        ok[i + 1] = n <= max_cells;
    }
    let (w, h) = (plannable.width(), plannable.height());
    for c in blocked.true_cells() {
        let l = comps.labels[c] as usize;
        if !ok[l] {
            continue;
        }
        if c.row == 0 || c.col == 0 || c.row + 1 == h || c.col + 1 == w {
            ok[l] = false;
            continue;
        }
        for d in RING {
            if let Some(n) = blocked.offset(c, d) {
                let m = comps.labels[n] as usize;
                if m != 0 && m != l {
                    ok[l] = false;
                }
            }
        }
    }
    comps.labels.map(|&l| {
        let l = l as usize;
        if ok[l] { comps.sizes[l - 1] } else { 0 }
    })
}

/// The islands that lanes pass ([`ISLAND_SPAN`]) and the islands whose
/// loops a lane drives ([`SPLICE_SPAN`]; the first are among them), for
/// a tool of `tool` cells.
fn island_masks(plannable: &Grid<bool>, tool: f64) -> (Grid<bool>, Grid<bool>) {
    let most = |span: f64| ((span * tool).ceil() as usize + 4).pow(2);
    let sizes = small_islands(plannable, most(SPLICE_SPAN));
    let up_to = |n: usize| sizes.map(|&s| s > 0 && s <= n);
    (up_to(most(ISLAND_SPAN)), up_to(most(SPLICE_SPAN)))
}

fn split_clear(
    plannable: &Grid<bool>,
    at: &impl Fn(f64, f64) -> GridPoint,
    v: f64,
    a: f64,
    b: f64,
    out: &mut Vec<(f64, f64)>,
) {
    if segment_clear(plannable, at(a, v), at(b, v)) {
        out.push((a, b));
        return;
    }
    // Walk in quarter cells, keeping maximal clear stretches.
    let mut s = a;
    let mut u = a;
    while u < b {
        let next = (u + 0.25).min(b);
        if !segment_clear(plannable, at(u, v), at(next, v)) {
            if u > s {
                out.push((s, u));
            }
            s = next;
        }
        u = next;
    }
    if b > s && segment_clear(plannable, at(s, v), at(b, v)) {
        out.push((s, b));
    }
}

// ---------------------------------------------------------------- order

#[derive(Clone, Copy, Debug)]
enum Node<'a> {
    Loop(&'a EdgeLoop),
    Chain(&'a Chain),
}

impl Node<'_> {
    fn options(&self) -> usize {
        match self {
            Node::Loop(l) if !l.closed => 2,
            Node::Loop(_) => LOOP_ENTRIES,
            Node::Chain(_) => 4,
        }
    }

    fn ends(&self, k: usize) -> (GridPoint, GridPoint) {
        match self {
            Node::Loop(l) if !l.closed => {
                let first = l
                    .pieces
                    .first()
                    .and_then(|p| p.first())
                    .copied()
                    .unwrap_or_default();
                let last = l
                    .pieces
                    .last()
                    .and_then(|p| p.last())
                    .copied()
                    .unwrap_or_default();
                let (a, b) = (cell_center(first), cell_center(last));
                if k == 0 { (a, b) } else { (b, a) }
            }
            Node::Loop(l) => {
                let (p, i) = l.entry(k);
                let c = cell_center(l.pieces[p][i]);
                (c, c)
            }
            Node::Chain(c) => c.ends(k),
        }
    }

    /// The directions option `k` is entered and left along (zero where a
    /// node is a single point). A loop's are taken over a few cells, as
    /// its straightened segments run.
    fn headings(&self, k: usize) -> (Vector, Vector) {
        const SPAN: usize = 3;
        match self {
            Node::Loop(l) => {
                let flat: Vec<GridPoint> =
                    l.pieces.iter().flatten().map(|&c| cell_center(c)).collect();
                let n = flat.len();
                if n < 2 {
                    return (Vector::zeros(), Vector::zeros());
                }
                let span = SPAN.min(n - 1);
                if !l.closed {
                    let first = flat[span] - flat[0];
                    let last = flat[n - 1] - flat[n - 1 - span];
                    return if k == 0 {
                        (first, last)
                    } else {
                        (-last, -first)
                    };
                }
                let (p, i) = l.entry(k);
                let e: usize = l.pieces[..p].iter().map(Vec::len).sum::<usize>() + i;
                (
                    flat[(e + span) % n] - flat[e],
                    flat[e] - flat[(e + n - span) % n],
                )
            }
            Node::Chain(c) => {
                let seq = c.sequence(k);
                let n = seq.len();
                if n < 2 {
                    return (Vector::zeros(), Vector::zeros());
                }
                (seq[1] - seq[0], seq[n - 1] - seq[n - 2])
            }
        }
    }

    /// The option driving the same work backwards (exit and entry swapped).
    fn reversed(&self, k: usize) -> usize {
        match self {
            Node::Loop(l) if !l.closed => k ^ 1,
            Node::Loop(_) => k,
            Node::Chain(c) => {
                // Backwards flips bit 0; the start side of the new first
                // lane is the old exit's side.
                let odd = c.lanes.len() % 2 == 1;
                let flip = if odd { (k & 2) ^ 2 } else { k & 2 };
                (k & 1 ^ 1) | flip
            }
        }
    }
}

/// Transit seconds between the ends of the nodes, with the detour walls
/// force: the straight-line time times the ratio of the 4-connected
/// shortest route to the Manhattan distance (1 where a monotone staircase
/// is clear, more where walls are in the way). One breadth-first search per
/// distinct end point, over cells or, on a large region, over blocks of
/// cells ([`Region`]); above [`TRANSIT_BUDGET`] cell visits (large regions
/// with many nodes) straight lines only.
struct Transits {
    /// Point ids of each node's option: (entry, exit).
    ids: Vec<Vec<(usize, usize)>>,
    /// Point id of where the path should end, if given.
    end: Option<usize>,
    points: Vec<GridPoint>,
    /// Detour ratio from every point to every point (row-major), if
    /// measured.
    ratio: Option<Vec<f32>>,
    speed: f64,
    /// Directions each node's option is entered and left along.
    headings: Vec<Vec<(Vector, Vector)>>,
    /// Turning rate (rad/s).
    turn_rate: f64,
}

/// Detour ratios between the blocks `at` (row-major, `n × n`): the
/// search's distance over the Manhattan distance, `1e6` where no way
/// exists, 1 where a point has no block or two share one. The distances
/// are symmetric (every move of the wavefront goes both ways), so the
/// search from point `i` fills row and column `i` and stops once it has
/// reached the points after `i`; the searches run side by side, each task
/// with its own copy of `wave`.
fn ratio_table(at: &[Option<Cell>], wave: &Wavefront) -> Vec<f32> {
    let n = at.len();
    let rows: Vec<Vec<(usize, f32)>> = (0..n)
        .into_par_iter()
        .map_init(
            || wave.clone(),
            |wave, i| {
                let Some(a) = at[i] else {
                    return Vec::new();
                };
                let later: Vec<Cell> = at[i + 1..].iter().flatten().copied().collect();
                wave.propagate_until_reached(&[a], &later);
                let mut row = Vec::new();
                for (j, b) in at.iter().enumerate().skip(i + 1) {
                    let Some(b) = *b else { continue };
                    let manhattan = a.row.abs_diff(b.row) + a.col.abs_diff(b.col);
                    if manhattan == 0 {
                        continue;
                    }
                    let r = match wave.distance(b) {
                        Some(d) => (f64::from(d) / manhattan as f64) as f32,
                        None => 1e6,
                    };
                    row.push((j, r));
                }
                row
            },
        )
        .collect();
    let mut r = vec![1.0f32; n * n];
    for (i, row) in rows.into_iter().enumerate() {
        for (j, v) in row {
            r[i * n + j] = v;
            r[j * n + i] = v;
        }
    }
    r
}

/// The region the transit table searches, in square blocks of cells, with
/// a wavefront over the blocks to reuse (made when first needed).
struct Region<'a> {
    plannable: &'a Grid<bool>,
    /// Side of a block (cells).
    block: usize,
    /// Plannable cells.
    cells: usize,
    wave: Option<Wavefront>,
}

impl<'a> Region<'a> {
    /// `plannable` searched cell by cell up to [`TRANSIT_EXACT_CELLS`]
    /// plannable cells, beyond in blocks of about half a tool radius
    /// ([`transit_block`]; `tool` in cells).
    fn new(plannable: &'a Grid<bool>, tool: f64) -> Self {
        let mut region = Self::with_block(plannable, 1);
        if region.cells > TRANSIT_EXACT_CELLS {
            region.block = transit_block(tool);
        }
        region
    }

    /// `plannable` searched in blocks of `block × block` cells.
    fn with_block(plannable: &'a Grid<bool>, block: usize) -> Self {
        Self {
            plannable,
            block: block.max(1),
            cells: plannable.count_true(),
            wave: None,
        }
    }

    /// The block holding point `p`, if `p` is in a plannable cell.
    fn block_of(&self, p: GridPoint) -> Option<Cell> {
        cell_of(self.plannable, p)
            .filter(|&c| self.plannable[c])
            .map(|c| Cell::new(c.row / self.block, c.col / self.block))
    }

    /// A wavefront over the blocks: a block is open where it holds a
    /// plannable cell, and a move between two blocks is allowed where a
    /// plannable cell of one borders a plannable cell of the other across
    /// their common side. The cells within a block are taken as connected,
    /// so a wall thinner than a block less a cell may be passed through
    /// inside one; a wall at least that thick never is. (With a robot
    /// radius of a tool radius the C-space's walls are over twice as
    /// thick as a block.)
    fn wavefront(&self) -> Wavefront {
        let k = self.block;
        let p = self.plannable;
        if k == 1 {
            return Wavefront::new(p);
        }
        let (w, h) = (p.width(), p.height());
        let (bw, bh) = (w.div_ceil(k), h.div_ceil(k));
        let mut open = Grid::new(bw, bh, false);
        // Whether block (r, c) joins its east / south neighbour.
        let mut east = Grid::new(bw, bh, false);
        let mut south = Grid::new(bw, bh, false);
        for c in p.true_cells() {
            let b = Cell::new(c.row / k, c.col / k);
            open[b] = true;
            if c.col % k == k - 1 && c.col + 1 < w && p[Cell::new(c.row, c.col + 1)] {
                east[b] = true;
            }
            if c.row % k == k - 1 && c.row + 1 < h && p[Cell::new(c.row + 1, c.col)] {
                south[b] = true;
            }
        }
        let moves = Grid::from_fn(bw, bh, |b: Cell| {
            let mut m = 0;
            if b.row > 0 && south[Cell::new(b.row - 1, b.col)] {
                m |= Dir4::North.bit();
            }
            if east[b] {
                m |= Dir4::East.bit();
            }
            if south[b] {
                m |= Dir4::South.bit();
            }
            if b.col > 0 && east[Cell::new(b.row, b.col - 1)] {
                m |= Dir4::West.bit();
            }
            m
        });
        Wavefront::with_moves(&open, &moves)
    }
}

/// Most cell visits the transit table may cost (points × plannable cells;
/// its searches run over blocks, visiting fewer).
const TRANSIT_BUDGET: f64 = 6e7;

/// Side (cells) of the transit table's blocks for a tool of `tool` cells:
/// about half a tool radius, at most [`TRANSIT_BLOCK_MAX`]. The table
/// holds detour ratios (route length over Manhattan distance), which
/// blocks of that size hardly change; a search over them visits a ninth of
/// the cells at a 3-cell block.
fn transit_block(tool: f64) -> usize {
    // Truncation intended: a small whole number of cells.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    // (A tool radius computed as 0.15 / 0.05 is a hair under 3 cells.)
    let k = (tool / 2.0 + 1e-6).round().max(1.0) as usize;
    k.min(TRANSIT_BLOCK_MAX)
}

/// Most plannable cells a transit table searches cell by cell (small
/// regions, where the searches cost little, keep exact ratios).
const TRANSIT_EXACT_CELLS: usize = 40_000;

/// Largest side of a transit block (cells).
const TRANSIT_BLOCK_MAX: usize = 4;

impl Transits {
    fn new(
        nodes: &[Node<'_>],
        (start, end): (GridPoint, Option<GridPoint>),
        region: &mut Region<'_>,
        t: &TimeModel,
    ) -> Self {
        let mut points: Vec<GridPoint> = Vec::new();
        let mut index: std::collections::HashMap<(u64, u64), usize> =
            std::collections::HashMap::new();
        let mut id = |p: GridPoint, points: &mut Vec<GridPoint>| {
            *index
                .entry((p.x.to_bits(), p.y.to_bits()))
                .or_insert_with(|| {
                    points.push(p);
                    points.len() - 1
                })
        };
        id(start, &mut points);
        let end = end.map(|e| id(e, &mut points));
        let ids: Vec<Vec<(usize, usize)>> = nodes
            .iter()
            .map(|n| {
                (0..n.options())
                    .map(|k| {
                        let (a, b) = n.ends(k);
                        (id(a, &mut points), id(b, &mut points))
                    })
                    .collect()
            })
            .collect();
        let n = points.len();
        let cells = region.cells as f64;
        let ratio = (n as f64 * cells <= TRANSIT_BUDGET && n * n <= 16_000_000)
            .then(|| {
                let at: Vec<Option<Cell>> = points.iter().map(|&p| region.block_of(p)).collect();
                if region.wave.is_none() {
                    region.wave = Some(region.wavefront());
                }
                let wave = region.wave.as_ref()?;
                Some(ratio_table(&at, wave))
            })
            .flatten();
        let headings = nodes
            .iter()
            .map(|n| (0..n.options()).map(|k| n.headings(k)).collect())
            .collect();
        Self {
            ids,
            end,
            points,
            ratio,
            speed: t.linear_speed,
            headings,
            turn_rate: t.angular_speed,
        }
    }

    /// Seconds of turning from leaving `prev` by option `q` to entering
    /// `node` by option `k`: onto the straight line between the two ends
    /// and off it again (or straight from one heading to the other where
    /// the ends meet).
    fn junction(&self, prev: usize, q: usize, node: usize, k: usize) -> f64 {
        let out = self.headings[prev][q].1;
        let into = self.headings[node][k].0;
        let d = self.points[self.ids[node][k].0] - self.points[self.ids[prev][q].1];
        let turn = if d.norm() < 1.0 {
            heading_change(out, into)
        } else {
            heading_change(out, d) + heading_change(d, into)
        };
        turn / self.turn_rate
    }

    /// Seconds from point `from` to point `to`.
    fn between(&self, from: usize, to: usize) -> f64 {
        let d = (self.points[to] - self.points[from]).norm() / self.speed;
        match &self.ratio {
            Some(r) => d * f64::from(r[from * self.points.len() + to]),
            None => d,
        }
    }

    /// Seconds from point `from` into `node` by option `k`.
    fn entering(&self, from: usize, node: usize, k: usize) -> f64 {
        self.between(from, self.ids[node][k].0)
    }

    /// The exit point of `node` by option `k`.
    fn exit(&self, node: usize, k: usize) -> usize {
        self.ids[node][k].1
    }

    /// Seconds from point `from` to where the path should end (0 when
    /// that is not given).
    fn finishing(&self, from: usize) -> f64 {
        self.end.map_or(0.0, |e| self.between(from, e))
    }
}

/// Nodes in the order driven, each with its option.
type Tour = Vec<(usize, usize)>;

/// Order and entry options of `nodes` from `start`, minimising estimated
/// transit time ([`Transits`]; a generalised TSP).
fn order_nodes(
    nodes: &[Node<'_>],
    ends: (GridPoint, Option<GridPoint>),
    region: &mut Region<'_>,
    t: &TimeModel,
) -> (Tour, f64) {
    let n = nodes.len();
    if n == 0 {
        return (Vec::new(), 0.0);
    }
    let start = ends.0;
    let transits = Transits::new(nodes, ends, region, t);
    const START: usize = 0;
    // Nearest neighbour over every entry: the least cost, ties to the lower
    // node and option. Entries sit in buckets, searched ring by ring
    // outwards until no farther ring can hold a cheaper one (a full scan
    // was O(n²): 35 s on a 512² random grid of 20 % obstacles).
    let entries: Vec<(GridPoint, usize, usize)> = nodes
        .iter()
        .enumerate()
        .flat_map(|(i, node)| (0..node.options()).map(move |k| (node.ends(k).0, i, k)))
        .collect();
    let mut index = entry_buckets(&entries);
    let mut used = vec![false; n];
    let mut tour: Vec<(usize, usize)> = Vec::with_capacity(n);
    let mut here = start;
    let mut here_id = START;
    for _ in 0..n {
        let mut best: Option<(f64, usize, usize)> = None;
        index.search(
            here,
            &mut best,
            |best, cell| {
                cell.retain(|e| !used[e.1.0]);
                for &(_, (i, k)) in cell.iter() {
                    let c = transits.entering(here_id, i, k);
                    if best.is_none_or(|b| (c, i, k) < b) {
                        *best = Some((c, i, k));
                    }
                }
            },
            // Every entry of the next ring is at least `bound` away.
            |best, bound| best.is_some_and(|b| b.0 < bound * (1.0 - 1e-12) / t.linear_speed),
        );
        let Some((_, i, k)) = best else { break };
        used[i] = true;
        tour.push((i, k));
        here = nodes[i].ends(k).1;
        here_id = transits.exit(i, k);
    }
    // 2-opt: reversing a stretch drives its nodes backwards.
    let exit = |tour: &[(usize, usize)], i: usize| {
        if i == 0 {
            START
        } else {
            transits.exit(tour[i - 1].0, tour[i - 1].1)
        }
    };
    // 2-opt is O(n²) per round: on large regions (a whole map of tiny
    // cells) the nearest-neighbour order and the exact entry choice stand.
    let rounds = if n <= TWO_OPT_LIMIT { 50 } else { 0 };
    for _round in 0..rounds {
        let mut better = false;
        for i in 0..n {
            for j in i + 1..n {
                let before_in = exit(&tour, i);
                let a_in = transits.ids[tour[i].0][tour[i].1].0;
                let b_out = transits.exit(tour[j].0, tour[j].1);
                let after = tour.get(j + 1).map(|&(m, k)| transits.ids[m][k].0);
                let onwards = |from: usize| match after {
                    Some(q) => transits.between(from, q),
                    None => transits.finishing(from),
                };
                let old = transits.between(before_in, a_in) + onwards(b_out);
                // Reversed: enter at b's old exit, leave at a's old entry.
                let new = transits.between(before_in, b_out) + onwards(a_in);
                if new < old - 1e-9 {
                    tour[i..=j].reverse();
                    for e in &mut tour[i..=j] {
                        e.1 = nodes[e.0].reversed(e.1);
                    }
                    better = true;
                }
            }
        }
        if !better {
            break;
        }
    }
    let seconds = best_options(nodes, &mut tour, &transits);
    (tour, seconds)
}

/// The entries `(point, node, option)` in buckets of about two each.
fn entry_buckets(entries: &[(GridPoint, usize, usize)]) -> Buckets<(usize, usize)> {
    let (mut lo, mut hi) = (
        GridPoint::new(f64::INFINITY, f64::INFINITY),
        GridPoint::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for (p, _, _) in entries {
        lo = GridPoint::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = GridPoint::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let area = ((hi.x - lo.x) * (hi.y - lo.y)).max(1.0);
    let mut b = Buckets::new(lo, hi, (2.0 * area / entries.len().max(1) as f64).sqrt());
    for &(p, i, k) in entries {
        b.insert(p, (i, k));
    }
    b
}

/// Chooses every node's option for the fixed order (exact: a shortest path
/// through layers of options); returns the transit seconds of the result.
fn best_options(nodes: &[Node<'_>], tour: &mut [(usize, usize)], transits: &Transits) -> f64 {
    let mut layers: Vec<Vec<(f64, usize)>> = Vec::with_capacity(tour.len());
    for (i, &(node, _)) in tour.iter().enumerate() {
        let m = nodes[node].options();
        let mut layer = Vec::with_capacity(m);
        for k in 0..m {
            let (c, from) = if i == 0 {
                (transits.entering(0, node, k), 0)
            } else {
                let prev = tour[i - 1].0;
                (0..layers[i - 1].len())
                    .map(|q| {
                        let out = transits.exit(prev, q);
                        let turn = transits.junction(prev, q, node, k);
                        (
                            layers[i - 1][q].0 + transits.entering(out, node, k) + turn,
                            q,
                        )
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .unwrap_or((f64::INFINITY, 0))
            };
            layer.push((c, from));
        }
        layers.push(layer);
    }
    let Some(last) = layers.last() else {
        return 0.0;
    };
    let Some(&(last_node, _)) = tour.last() else {
        return 0.0;
    };
    let total = |k: usize| last[k].0 + transits.finishing(transits.exit(last_node, k));
    let mut k = (0..last.len())
        .min_by(|&a, &b| total(a).total_cmp(&total(b)))
        .unwrap_or(0);
    let seconds = total(k);
    for i in (0..tour.len()).rev() {
        tour[i].1 = k;
        k = layers[i][k].1;
    }
    seconds
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::{DiscRobot, Point};

    use crate::{CoverageProblem, Start};

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    /// The angles built in parallel give the same path on one thread as on
    /// four: a square room with a pillar, where both axes are near ties.
    #[test]
    fn the_path_does_not_depend_on_the_thread_count() {
        let mut rows = vec![".".repeat(24); 24];
        for r in rows.iter_mut().take(14).skip(10) {
            r.replace_range(9..13, "####");
        }
        let text = rows.join("\n");
        let (map, _) = parse_ascii(&text).expect("valid map");
        let problem =
            CoverageProblem::new(&map, DiscRobot::new(1.5, 1.5).expect("robot"), Start::First)
                .expect("problem");
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| plan_lanes(&problem.input(0), None).expect("plan"))
        };
        let one = on(1);
        assert!(one.len() > 8, "{one:?}");
        assert_eq!(one, on(4));
    }

    /// The transit table's blocks go round a wall as thick as a block less
    /// a cell, wherever it lies across the blocks, and measure an open
    /// floor as the cells do.
    #[test]
    fn transit_blocks_go_round_walls() {
        let floor = |wall: Option<usize>| {
            let rows: Vec<String> = (0..30)
                .map(|r| {
                    (0..60)
                        .map(|c| {
                            let in_wall = wall.is_some_and(|w| (w..w + 2).contains(&c));
                            if in_wall && r < 27 { '#' } else { '.' }
                        })
                        .collect()
                })
                .collect();
            let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
            mask(&refs)
        };
        let open = floor(None);
        let region = Region::with_block(&open, 3);
        let mut wave = region.wavefront();
        let (a, b) = (GridPoint::new(4.5, 2.5), GridPoint::new(52.5, 20.5));
        let (ba, bb) = (region.block_of(a).unwrap(), region.block_of(b).unwrap());
        wave.propagate(&[ba]);
        let manhattan = ba.row.abs_diff(bb.row) + ba.col.abs_diff(bb.col);
        assert_eq!(wave.distance(bb), Some(manhattan as u32));
        // A wall two cells thick, at each offset across the blocks, with a
        // gap at the bottom: the way from one side to the other goes round.
        for w in 29..32 {
            let walled = floor(Some(w));
            let region = Region::with_block(&walled, 3);
            let mut wave = region.wavefront();
            let (p, q) = (
                GridPoint::new(w as f64 - 1.5, 0.5),
                GridPoint::new(w as f64 + 3.5, 0.5),
            );
            let (bp, bq) = (region.block_of(p).unwrap(), region.block_of(q).unwrap());
            wave.propagate(&[bp]);
            // Down to the gap (rows 27-29, block row 9) and back up.
            assert!(
                wave.distance(bq).unwrap() >= 18,
                "wall at {w}: {:?}",
                wave.distance(bq)
            );
        }
    }

    /// A plan small enough to build every angle is never slower than the
    /// same region planned as part of a large map (the model's best two
    /// built): the angles built then include those two. On some of these
    /// rooms with a pillar it is faster.
    #[test]
    fn a_small_plan_builds_more_angles_and_is_never_slower() {
        let mut faster = 0;
        for (size, pillar) in [(24, 9..13), (30, 5..9), (20, 12..17)] {
            let mut rows = vec![".".repeat(size); size];
            for r in rows.iter_mut().take(pillar.end + 2).skip(pillar.start) {
                r.replace_range(pillar.clone(), &"#".repeat(pillar.len()));
            }
            let (map, _) = parse_ascii(&rows.join("\n")).expect("valid map");
            let problem =
                CoverageProblem::new(&map, DiscRobot::new(1.5, 1.5).expect("robot"), Start::First)
                    .expect("problem");
            let small = problem.input(0);
            assert!(
                BUILD_BUDGET / small.plan_cells >= 14,
                "{}",
                small.plan_cells
            );
            let mut large = problem.input(0);
            large.plan_cells = BUILD_BUDGET;
            let time = |input: &PlannerInput<'_>| {
                input.time.polyline(&plan_lanes(input, None).expect("plan"))
            };
            let (all, two) = (time(&small), time(&large));
            assert!(all <= two + 1e-9, "{size}: {all} > {two}");
            faster += usize::from(all < two - 1e-6);
        }
        assert!(faster >= 1, "more angles never helped");
    }

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

    #[test]
    fn a_rectangle_has_one_loop_of_its_border() {
        let m = mask(&["....", "....", "...."]);
        let loops = edge_loops(&m, &Grid::new(m.width(), m.height(), false));
        assert_eq!(loops.len(), 1);
        let cells: std::collections::BTreeSet<Cell> = loops[0].cells().collect();
        assert_eq!(cells.len(), 10);
        assert!(!cells.contains(&Cell::new(1, 1)) && !cells.contains(&Cell::new(1, 2)));
    }

    #[test]
    fn a_pillar_gets_its_own_loop() {
        let m = mask(&[".....", ".....", "..#..", ".....", "....."]);
        let loops = edge_loops(&m, &Grid::new(m.width(), m.height(), false));
        assert_eq!(loops.len(), 2);
        // The pillar's loop: the eight cells around it.
        let cells: std::collections::BTreeSet<Cell> = loops[1].cells().collect();
        assert_eq!(cells.len(), 8);
    }

    #[test]
    fn chains_reverse_consistently() {
        let lanes = |k: usize| Chain {
            lanes: (0..k)
                .map(|i| Lane {
                    a: Point::new(0.0, i as f64),
                    b: Point::new(5.0, i as f64),
                })
                .collect(),
        };
        for k in 1..5 {
            let c = lanes(k);
            let node = Node::Chain(&c);
            for opt in 0..4 {
                let (a, b) = c.ends(opt);
                let (ra, rb) = c.ends(node.reversed(opt));
                assert_eq!((ra, rb), (b, a), "{k} lanes, option {opt}");
            }
        }
    }

    /// In a 40 × 24 room with a tool of 3 cells, the lane mask spans rows 4
    /// to 19 (centres 4.5 to 19.5): spread over all of it, four lines lie
    /// on its edges, in the loops' strip; moved in by the inset, three lines
    /// cover the same mask, the first and last an inset off its edges.
    #[test]
    fn the_outermost_lines_keep_off_the_loops_strip() {
        let plannable = Grid::new(40, 24, true);
        let lane_mask = Grid::from_fn(40, 24, |c: Cell| (4..20).contains(&c.row));
        let spacing = 2.0 * (9.0f64 - 1.0 / 64.0).sqrt() * 0.999;
        let rows = |inset: f64| -> Vec<f64> {
            let (chains, _) = chains_at(&plannable, &lane_mask, None, 0.0, spacing, inset);
            let mut v: Vec<f64> = chains
                .iter()
                .flat_map(|c| &c.lanes)
                .map(|l| ((l.a.y - EDGE_NUDGE) * 1e6).round() / 1e6)
                .collect();
            v.sort_by(f64::total_cmp);
            v
        };
        let inset = 3.0 - OUTSET - LINE_MARGIN;
        assert_eq!(rows(0.0), vec![4.5, 9.5, 14.5, 19.5]);
        assert_eq!(rows(inset), vec![7.0, 12.0, 17.0]);
        // Where the mask is narrower than two insets, one line down its middle.
        let thin = Grid::from_fn(40, 24, |c: Cell| (10..13).contains(&c.row));
        let (chains, _) = chains_at(&plannable, &thin, None, 0.0, spacing, inset);
        let ys: Vec<f64> = chains
            .iter()
            .flat_map(|c| &c.lanes)
            .map(|l| l.a.y)
            .collect();
        assert_eq!(ys.len(), 1);
        assert!((ys[0] - EDGE_NUDGE - 11.5).abs() < 1e-9, "{ys:?}");
    }

    /// A blocked cell of `rows` (a string of `.`) at each of `cells`.
    fn with_blocked(w: usize, h: usize, cells: &[(usize, usize)]) -> Vec<String> {
        let mut rows: Vec<String> = (0..h).map(|_| ".".repeat(w)).collect();
        for &(r, c) in cells {
            rows[r].replace_range(c..=c, "#");
        }
        rows
    }

    fn block(rows: std::ops::Range<usize>, cols: std::ops::Range<usize>) -> Vec<(usize, usize)> {
        rows.flat_map(|r| cols.clone().map(move |c| (r, c)))
            .collect()
    }

    /// A speck in the open is an island; a wall, a speck touching a wall
    /// diagonally and a block over the size limit are not.
    #[test]
    fn small_islands_are_specks_off_the_walls() {
        let mut cells = block(0..1, 0..30);
        cells.extend(block(8..10, 8..10));
        cells.extend([(1, 21), (2, 20)]);
        cells.extend(block(12..17, 18..23));
        let rows = with_blocked(30, 20, &cells);
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let islands = small_islands(&mask(&refs), 16).map(|&n| n > 0);
        let found: Vec<Cell> = islands.true_cells().collect();
        assert_eq!(
            found,
            vec![
                Cell::new(8, 8),
                Cell::new(8, 9),
                Cell::new(9, 8),
                Cell::new(9, 9)
            ]
        );
    }

    /// A room with a speck (its C-space blot 6 × 6 cells), tool 3 cells:
    /// without islands the lines through the speck's hole in the lane mask
    /// stop at it and the room falls into several chains; with them each
    /// line keeps one lane across the room, as in the bare room, and the
    /// speck's loop goes to the lane passing nearest.
    #[test]
    fn lanes_run_past_a_speck_and_drive_its_loop() {
        let (w, h, tool) = (60, 40, 3.0);
        let rows = with_blocked(w, h, &block(17..23, 27..33));
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let plannable = mask(&refs);
        let lanes = lane_mask(&plannable, &plannable, tool);
        let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
        let inset = tool - OUTSET - LINE_MARGIN;
        let islands = small_islands(&plannable, 100).map(|&n| n > 0);
        assert_eq!(islands.count_true(), 36);
        let (cut, _) = chains_at(&plannable, &lanes, None, PI / 2.0, spacing, inset);
        let (passed, _) = chains_bridged(
            &plannable,
            &lanes,
            None,
            Some(&islands),
            PI / 2.0,
            spacing,
            inset,
        );
        let bare = Grid::new(w, h, true);
        let bare_lanes = lane_mask(&bare, &bare, tool);
        let (open, _) = chains_at(&bare, &bare_lanes, None, PI / 2.0, spacing, inset);
        assert_eq!(open.len(), 1);
        assert!(cut.len() > 1, "{} chains", cut.len());
        assert_eq!(passed.len(), 1);
        assert_eq!(passed[0].lanes.len(), open[0].lanes.len());
        // The speck's loop is the second (traced after the room's border)
        // and goes to a lane; the order then has one loop node, the border.
        let loops = edge_loops(&plannable, &plannable);
        assert_eq!(loops.len(), 2);
        let splices = splices_for(&loops, &passed, &islands, &plannable, spacing);
        assert_eq!(splices.len(), 1);
        assert_eq!(splices[0].loop_index, 1);
        let nodes = nodes_of(&loops, &passed, &splices);
        assert_eq!(nodes.len(), 2);
        assert!(matches!(nodes[0], Node::Loop(l) if std::ptr::eq(l, &loops[0])));
        // Driven, every piece is clear and the loop is driven whole.
        assert_drives_clear_and_whole(&plannable, &passed[0], &splices, &loops[1], &loops);
    }

    /// Chain `c` driven with `splices`: every piece is clear, and each cell
    /// of `spliced` (a loop a lane drives) lies within the loop tolerance
    /// of the path.
    fn assert_drives_clear_and_whole(
        plannable: &Grid<bool>,
        c: &Chain,
        splices: &[Splice],
        spliced: &EdgeLoop,
        loops: &[EdgeLoop],
    ) {
        let here: Vec<&Splice> = splices.iter().collect();
        let mut path = PathBuilder::new(plannable, Cell::new(1, 1));
        drive_chain(&mut path, c, 0, &here, loops, 0.8).unwrap();
        let pts = path.points();
        for s in pts.windows(2) {
            assert!(segment_clear(plannable, s[0], s[1]), "{s:?}");
        }
        for cell in spliced.cells() {
            let near = pts
                .windows(2)
                .map(|s| segment_distance(s[0], s[1], cell_center(cell)))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= 1.0, "{cell:?} {near}");
        }
    }

    /// A room with a table (its C-space blot 12 × 12 cells), tool 3
    /// cells: too large for lanes to pass (the lines through it are cut),
    /// small enough that its loop is driven from the lane passing nearest
    /// rather than ordered as a node of its own.
    #[test]
    fn a_table_cuts_the_lanes_but_a_lane_drives_its_loop() {
        let (w, h, tool) = (60, 40, 3.0);
        let rows = with_blocked(w, h, &block(14..26, 24..36));
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let plannable = mask(&refs);
        let (passed, spliced) = island_masks(&plannable, tool);
        assert_eq!(passed.count_true(), 0);
        assert_eq!(spliced.count_true(), 144);
        let lanes = lane_mask(&plannable, &plannable, tool);
        let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
        let inset = tool - OUTSET - LINE_MARGIN;
        let (chains, _) = chains_bridged(
            &plannable,
            &lanes,
            None,
            Some(&passed),
            PI / 2.0,
            spacing,
            inset,
        );
        assert!(chains.len() > 1, "{} chains", chains.len());
        let loops = edge_loops(&plannable, &plannable);
        assert_eq!(loops.len(), 2);
        // Only the islands that lanes pass: the table's loop is a node.
        assert!(splices_for(&loops, &chains, &passed, &plannable, spacing).is_empty());
        let splices = splices_for(&loops, &chains, &spliced, &plannable, spacing);
        assert_eq!(splices.len(), 1);
        assert_eq!(splices[0].loop_index, 1);
        let nodes = nodes_of(&loops, &chains, &splices);
        assert_eq!(nodes.len(), chains.len() + 1);
        // The chain holding the splice, driven: every piece is clear and
        // the table's loop is driven whole.
        let c = &chains[splices[0].chain];
        assert_drives_clear_and_whole(&plannable, c, &splices, &loops[1], &loops);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(40))]
        /// The symmetric table (each search stopped at the points after its
        /// own) equals one full search from every point, on cells and on
        /// blocks.
        #[test]
        fn the_ratio_table_is_every_search_in_full(seed in 0u64..1000, blobs in 1usize..10, block in 1usize..4, picks in proptest::collection::vec((0usize..47, 0usize..61), 0..24)) {
            let plannable = oxcover_grid::random::blobs(61, 47, blobs, 6, seed).free_mask();
            let region = Region::with_block(&plannable, block);
            let wave = region.wavefront();
            let at: Vec<Option<Cell>> = picks
                .iter()
                .map(|&(r, c)| region.block_of(cell_center(Cell::new(r, c))))
                .collect();
            let n = at.len();
            let mut full = vec![1.0f32; n * n];
            let mut w = wave.clone();
            for i in 0..n {
                let Some(a) = at[i] else { continue };
                w.propagate(&[a]);
                for j in 0..n {
                    let Some(b) = at[j] else { continue };
                    let manhattan = a.row.abs_diff(b.row) + a.col.abs_diff(b.col);
                    if manhattan > 0 {
                        full[i * n + j] = w.distance(b).map_or(1e6, |d| (f64::from(d) / manhattan as f64) as f32);
                    }
                }
            }
            proptest::prop_assert_eq!(ratio_table(&at, &wave), full);
        }

        /// Lines that skip the samples within the lane mask's clearance
        /// find the same chains as lines sampled all along.
        #[test]
        fn skipping_the_clear_samples_finds_the_same_chains(
            seed in 0u64..1000,
            blobs in 1usize..8,
            theta in 0.0f64..std::f64::consts::PI,
            tool in 1.0f64..4.0,
        ) {
            let map = oxcover_grid::random::blobs(61, 47, blobs, 5, seed);
            let plannable = map.free_mask();
            let mask = lane_mask(&plannable, &plannable, tool);
            let clearance = boundary_distance_sq4(&mask.map(|&m| !m), true).into_vec();
            let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
            let inset = (tool - OUTSET - LINE_MARGIN).max(0.0);
            let all = chains_at(&plannable, &mask, None, theta, spacing, inset);
            let skipping = chains_at(&plannable, &mask, Some(&clearance), theta, spacing, inset);
            proptest::prop_assert_eq!(all, skipping);
        }
    }

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

    /// An open 24 × 9 room, tool 1.5 cells: one edge loop and lanes cover
    /// all but the corners' last cells (the boundary pass's share), nothing
    /// is crossed.
    #[test]
    fn an_open_room_is_one_loop_and_long_lanes() {
        let (map, _) = parse_ascii(&["........................"; 9].join("\n")).unwrap();
        let problem =
            CoverageProblem::new(&map, DiscRobot::new(0.0, 1.5).unwrap(), Start::First).unwrap();
        let input = problem.input(0);
        let pts = plan_lanes(&input, None).unwrap();
        let f = problem.frame();
        let covered = oxcover_grid::footprint::covered_cells(f, &pts, 1.5);
        assert!(
            covered.count_true() >= 24 * 9 - 8,
            "{}",
            covered.count_true()
        );
        let end = f.cell_at(pts.last().unwrap()).unwrap();
        let rest = problem.boundary_tour(&pts, end).unwrap();
        assert!(rest.anchors <= 4, "{}", rest.anchors);
        let grid_pts = crate::metre_path::metres_to_grid(f, &pts);
        for w in grid_pts.windows(2) {
            assert!(segment_clear(input.plannable, w[0], w[1]), "{w:?}");
        }
        // One loop round the room (62 cells) and lanes one tool width
        // apart over the rest: far less than a cell-by-cell sweep (216).
        let total: f64 = pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        assert!(total < 62.0 + 1.3 * 216.0 / 3.0, "{total}: {pts:?}");
    }
}
#[cfg(test)]
mod exact {
    use super::*;
    use crate::{CoverageProblem, Start};
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::{DiscRobot, Point};

    fn plan(text: &str) -> Vec<Point> {
        let (map, _) = parse_ascii(text).expect("valid map");
        let problem =
            CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).expect("problem");
        let pts = plan_lanes(&problem.input(0), None).expect("plan");
        // Rounded to a hundredth of a cell.
        pts.iter()
            .map(|p| Point::new((p.x * 100.0).round() / 100.0, (p.y * 100.0).round() / 100.0))
            .collect()
    }

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    /// A corridor one cell wide: its contour, out towards the east wall
    /// and back (no lane fits: the tool is half a cell). Tightening drops
    /// the trip to the west wall (the start cell's centre covers it) and
    /// pulls the far end in as far as the last cell's centre stays within
    /// half a cell.
    #[test]
    fn a_corridor_is_driven_out_and_back() {
        assert_eq!(plan("......"), pts(&[(0.5, 0.5), (5.07, 0.5), (0.5, 0.5)]));
    }

    /// Two rows: one loop through the four corners, tightened: every
    /// corner moved in as far as the cells' centres stay within half a
    /// cell of the path (the tool), so the loop is a thin sliver through
    /// the middle of the room and back to the start cell.
    #[test]
    fn a_two_row_room_is_one_loop_through_its_corners() {
        assert_eq!(
            plan("...\n..."),
            pts(&[
                (0.5, 1.5),
                (2.42, 1.01),
                (2.47, 1.0),
                (0.77, 0.92),
                (0.5, 1.5)
            ])
        );
    }

    /// A ring round a two-cell block: every ring cell is on the outer
    /// contour, so the block's own contour is not traced again: one loop
    /// round the block, its corners tightened until the ring's cell
    /// centres are just within half a cell of it.
    #[test]
    // 3.14 is a coordinate, not π.
    #[allow(clippy::approx_constant)]
    fn a_ring_is_one_loop() {
        assert_eq!(
            plan("....\n.##.\n...."),
            pts(&[
                (0.5, 2.5),
                (3.14, 2.18),
                (3.26, 0.94),
                (0.85, 0.84),
                (0.5, 2.5)
            ])
        );
    }
}
