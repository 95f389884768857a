//! One region planned: the planner's path on it, the lead-in from the
//! start, its boundary pass, and the finished path scored. The whole map
//! at once is one region.

use std::time::Instant;

use oxcover_grid::footprint::covered_cells;
use oxcover_grid::{Cell, Coverability, Grid, MapFrame, Point};
use oxcover_planners::{BoundaryRoute, CoverageProblem, PlanOutput, RoomUnits};

use super::request::{PlanOutcome, PlanRequest, RoomStretch};
use crate::error::Result;
use crate::metrics::{coverage_of, covered_fraction, evaluate_covered};
use crate::path::cells_to_points;

/// One region's plan: the planner's path from the region's start (after
/// `prefix`), then its boundary pass.
pub(super) struct RegionPlan {
    /// Fine cells (lead-in and plan; the pass's cells after them).
    pub(super) cells: Vec<Cell>,
    /// `prefix`, then the plan's waypoints, before the boundary pass.
    pub(super) raw: Vec<Point>,
    /// `raw`, then the boundary pass.
    pub(super) points: Vec<Point>,
    /// The cells `raw` covers, where the boundary pass worked them out.
    pub(super) raw_covered: Option<Grid<bool>>,
    pub(super) boundary: Option<BoundaryRoute>,
    /// The plannable cell the region's path ends in.
    pub(super) end: Cell,
}

pub(super) fn plan_region(
    problem: &CoverageProblem,
    request: &PlanRequest,
    prefix: Vec<Point>,
    exit: Option<Cell>,
    plan_cells: Option<usize>,
) -> Result<RegionPlan> {
    let frame = problem.frame();
    let mut input = problem.input(request.seed);
    input.exit = exit;
    if let Some(n) = plan_cells {
        input.plan_cells = n;
    }
    let output = request.planner.plan(&input)?;
    let (planned, tail) = match &output {
        PlanOutput::Metres(points) => {
            let first = points.first().and_then(|p| frame.cell_at(p));
            (
                first.into_iter().collect::<Vec<_>>(),
                points.get(1..).unwrap_or_default().to_vec(),
            )
        }
        _ => (problem.expand(&output)?, Vec::new()),
    };
    let mut cells = problem.lead_in(planned.first().copied())?;
    cells.extend(planned.into_iter().skip(1));
    // A metre plan continues after the lead-in's cells; the boundary pass
    // then starts from the cell of its last point.
    let mut raw = prefix;
    raw.extend(cells_to_points(frame, &cells));
    raw.extend(tail);
    let last_cell = raw
        .last()
        .and_then(|p| frame.cell_at(p))
        .filter(|&c| problem.plannable()[c]);
    let end = last_cell
        .or_else(|| cells.last().copied())
        .unwrap_or(problem.start_cell());
    let mut points = raw.clone();
    // What the plan covers: found once, for the boundary pass (both its
    // routes) and the report's coverage before it.
    let raw_covered = request.boundary_pass.then(|| problem.covered_by(&raw));
    let boundary = if let Some(covered) = &raw_covered {
        // The pass starts from `end`'s centre; a metre plan may stop elsewhere
        // in that cell, so go to the centre first (a move inside one cell).
        let off_centre = raw.last() != Some(&frame.cell_center(end));
        // The points a route appends, as a tour (straightened metres) or as
        // the nearest-first pass (collinear cells merged, as every cell path
        // is written); and its cells.
        let appended = |route: &BoundaryRoute, tour: bool| {
            let mut extra = Vec::new();
            if off_centre && route.pending > 0 {
                extra.push(end);
            }
            extra.extend_from_slice(&route.cells);
            let pts = if tour {
                let mut v = Vec::new();
                if off_centre && route.pending > 0 {
                    v.push(frame.cell_center(end));
                }
                v.extend(route.points.iter().copied());
                v
            } else {
                cells_to_points(frame, &extra)
            };
            (pts, extra)
        };
        // Rooms on, the pass is a straightened tour ending towards the next
        // room or the nearest-first pass, whichever is faster once both are
        // tightened; rooms off keeps the nearest-first pass as it is (the
        // papers' experiments).
        let (route, whole, extra) = if request.rooms {
            // Independent: found in parallel (each works out what `raw`
            // leaves uncovered).
            let (tour, pass) = rayon::join(
                || problem.boundary_tour_to_covered(covered.clone(), end, exit),
                || problem.boundary_pass_covered(covered.clone(), end),
            );
            let (tour, pass) = (tour?, pass?);
            let (a, b) = (appended(&tour, true), appended(&pass, false));
            // Each tightened for time (as `lanes` tightens its path; the
            // two in parallel), then the faster kept, with the way on to the
            // next room where there is one.
            let tightened = |tail: &[Point]| {
                problem.tighten_from(&[points.as_slice(), tail].concat(), points.len())
            };
            let (ta, tb) = rayon::join(|| tightened(&a.0), || tightened(&b.0));
            let onward: Vec<Point> = exit.map(|c| frame.cell_center(c)).into_iter().collect();
            let time = |whole: &[Point]| {
                let from = points.len().saturating_sub(1);
                request
                    .time
                    .polyline(&[&whole[from.min(whole.len())..], onward.as_slice()].concat())
            };
            if time(&tb) < time(&ta) {
                (pass, tb, b.1)
            } else {
                (tour, ta, a.1)
            }
        } else {
            let pass = problem.boundary_pass_covered(covered.clone(), end)?;
            let (pts, extra) = appended(&pass, false);
            let mut whole = points.clone();
            whole.extend(pts);
            (pass, whole, extra)
        };
        points = whole;
        cells.extend(extra);
        Some(route)
    } else {
        None
    };
    // Where the region's path stops (the next transit starts there).
    let end = points
        .last()
        .and_then(|p| frame.cell_at(p))
        .filter(|&c| problem.plannable()[c])
        .or_else(|| cells.last().copied())
        .unwrap_or(end);
    Ok(RegionPlan {
        cells,
        raw,
        points,
        raw_covered,
        boundary,
        end,
    })
}

/// The start position when it is not its cell's centre (the path's first
/// waypoint then).
pub(super) fn start_prefix(problem: &CoverageProblem) -> Vec<Point> {
    problem
        .start_point()
        .filter(|&s| problem.frame().cell_center(problem.start_cell()) != s)
        .into_iter()
        .collect()
}

/// Plans the whole problem at once.
pub(super) fn plan_whole(
    problem: &CoverageProblem,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let region = plan_region(problem, request, start_prefix(problem), None, None)?;
    let in_pass = pass_flags(&region);
    let (points, _, covered, in_pass) = if request.rooms {
        tighten_plan(problem, None, region.points, (Vec::new(), in_pass), || ()).0
    } else {
        (region.points, Vec::new(), None, in_pass)
    };
    let boundary_length_m = pass_length(&points, &in_pass);
    // The final path's cells, if known: from the tightening's check, or
    // the plan's own where the path is the plan (nothing appended, moved).
    let covered = covered.or_else(|| {
        (points == region.raw)
            .then(|| region.raw_covered.clone())
            .flatten()
    });
    let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    let known = KnownCoverage {
        raws: region.raw_covered,
        path: covered,
        cells: None,
    };
    finish(
        problem,
        request,
        points,
        region.cells,
        (&[region.raw], known),
        region.boundary,
        boundary_length_m,
        Vec::new(),
        plan_ms,
    )
}

/// Which of a region's waypoints its boundary pass added: those after its
/// planner's own path (`raw`, which `points` begins with).
pub(super) fn pass_flags(region: &RegionPlan) -> Vec<bool> {
    let own = region.raw.len().min(region.points.len());
    (0..region.points.len()).map(|i| i >= own).collect()
}

/// The length of the segments of `points` that end at a waypoint the
/// boundary pass added (`in_pass`, one flag per waypoint): the pass's
/// share of the path, the way to its first waypoint included.
pub(super) fn pass_length(points: &[Point], in_pass: &[bool]) -> f64 {
    points
        .windows(2)
        .zip(in_pass.iter().skip(1))
        .filter(|(_, pass)| **pass)
        // From +0.0: an empty `sum` of floats is -0.0.
        .fold(0.0, |total, (w, _)| total + (w[1] - w[0]).norm())
}

/// Whether a path that covers the cells `reached` leaves a coverable cell
/// uncovered that the path `before` covered (a tool of `tool` metres, the
/// metrics' own coverage, [`covered_cells`]). `before`'s cells are only
/// worked out where `reached` misses a coverable cell: a complete plan
/// costs one coverage test, not two.
pub(super) fn loses_coverage(
    frame: &MapFrame,
    coverable: &Grid<bool>,
    tool: f64,
    before: &[Point],
    reached: &Grid<bool>,
) -> bool {
    // (Most often none is missed: two counts tell, without a cell list.)
    if coverable.count_both(reached) == coverable.count_true() {
        return false;
    }
    let missed: Vec<Cell> = coverable.true_cells().filter(|&c| !reached[c]).collect();
    let was = covered_cells(frame, before, tool);
    missed.into_iter().any(|c| was[c])
}

/// Coverage a plan has worked out on the way, each `None` where it has not
/// (then [`finish`] finds it).
pub(super) struct KnownCoverage {
    /// The cells all the planners' paths cover before the boundary pass,
    /// on the map's grid.
    pub(super) raws: Option<Grid<bool>>,
    /// The cells the final path covers.
    pub(super) path: Option<Grid<bool>>,
    /// A copy of the problem's cells for the evaluation to keep, made
    /// ahead where a core had time.
    pub(super) cells: Option<Coverability>,
}

/// Scores a finished plan.
#[allow(clippy::too_many_arguments)]
pub(super) fn finish(
    problem: &CoverageProblem,
    request: &PlanRequest,
    points: Vec<Point>,
    cells: Vec<Cell>,
    (raws, known): (&[Vec<Point>], KnownCoverage),
    boundary: Option<BoundaryRoute>,
    boundary_length_m: f64,
    room_stretches: Vec<RoomStretch>,
    plan_ms: f64,
) -> Result<PlanOutcome> {
    let frame = problem.frame();
    // The two coverages, where not known yet, side by side.
    let (coverage_without_boundary_pass, covered) = rayon::join(
        || match &known.raws {
            Some(g) => covered_fraction(problem.cells(), g),
            None => coverage_of(frame, problem.cells(), raws),
        },
        || known.path.unwrap_or_else(|| problem.covered_by(&points)),
    );
    let evaluation = evaluate_covered(
        frame,
        known.cells.unwrap_or_else(|| problem.cells().clone()),
        &points,
        covered,
        &request.time,
    );
    Ok(PlanOutcome {
        points,
        cells,
        evaluation,
        coverage_without_boundary_pass,
        boundary,
        boundary_length_m,
        room_units: (!room_stretches.is_empty()).then_some(room_stretches.len()),
        room_stretches,
        coarse_block: problem.block(),
        plan_ms,
        targets: None,
        notes: Vec::new(),
        clearance_lost_cells: None,
    })
}

/// A plan's waypoints, its room stretches, the cells it covers (where
/// known) and which waypoints belong to a boundary pass.
pub(super) type TightPlan = (Vec<Point>, Vec<RoomStretch>, Option<Grid<bool>>, Vec<bool>);

/// A finished plan (rooms on) tightened for time as a whole, as `lanes`
/// tightens its own path ([`oxcover_planners::CoverageProblem::tighten_within`]): the
/// planner's waypoints, the transits and the boundary passes together, so
/// that what a transit or the next room already covers is not driven
/// twice and every junction between them is straightened. Each room's
/// waypoints stay in their room (`units`); `stretches` are renumbered for
/// the waypoints kept. Should rounding leave a cell the plan covered
/// uncovered, the plan is returned as it was. `beside` runs while the
/// path is tightened (after its first pass,
/// [`oxcover_planners::CoverageProblem::tighten_within_beside`]); its
/// result is returned too.
pub(super) fn tighten_plan<R: Send>(
    problem: &CoverageProblem,
    units: Option<&RoomUnits>,
    points: Vec<Point>,
    (stretches, in_pass): (Vec<RoomStretch>, Vec<bool>),
    beside: impl FnOnce() -> R + Send,
) -> (TightPlan, R) {
    let mut of_vertex = vec![0u32; points.len()];
    for s in &stretches {
        for z in &mut of_vertex[s.points.clone()] {
            *z = s.unit;
        }
    }
    let zones = units.map(|u| (&u.labels, of_vertex.as_slice()));
    let ((tight, kept), beside) = problem.tighten_within_beside(&points, 0, zones, beside);
    if tight == points {
        return ((points, stretches, None, in_pass), beside);
    }
    let reached = problem.covered_by(&tight);
    let tool = problem.robot().tool_radius;
    let (frame, coverable) = (problem.frame(), &problem.cells().coverable);
    if loses_coverage(frame, coverable, tool, &points, &reached) {
        return ((points, stretches, None, in_pass), beside);
    }
    let in_pass = kept.iter().map(|&k| in_pass[k]).collect();
    let at = |i: usize| kept.partition_point(|&k| k < i);
    let stretches = stretches
        .into_iter()
        .map(|s| RoomStretch {
            unit: s.unit,
            points: at(s.points.start)..at(s.points.end),
        })
        .collect();
    ((tight, stretches, Some(reached), in_pass), beside)
}
