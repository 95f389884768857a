//! The plan pipeline: map + robot + start → metre path, for any registered planner.
//!
//! Pipeline: build the contract's coverage problem ([`Coverability`]); group the
//! plannable cells into coverage cells one tool diameter wide ([`CoarseGrid`],
//! block = `max(1, floor(2T / resolution))` cells, so lanes one block apart
//! leave no gap); run the planner ([`oxcover_planners::registry`]); make its
//! plan a fine, collision-free cell path ([`expand`]) preceded by the way from
//! the start to its coverage cell's representative; append the boundary pass
//! unless turned off; convert to metre waypoints.

use std::time::Instant;

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{
    Cell, CoarseGrid, Coverability, DiscRobot, OccupancyGrid, Point, TOLERANCE_CELLS,
};
use oxcover_planners::sweep::{Decomposition, Sweep};
use oxcover_planners::{
    BoundaryRoute, PlanOutput, Planner, PlannerInput, boundary_pass, expand, registry,
};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::metrics::{Evaluation, MetricParams, evaluate_problem};
use crate::path::cells_to_points;

/// A registered planner, as `oxcover planners` lists it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PlannerInfo {
    /// Name used on the command line.
    pub name: &'static str,
    /// Whether it promises to cover every coverage cell.
    pub complete: bool,
    /// One-line description with its source.
    pub summary: &'static str,
}

/// Every planner `plan --planner` accepts.
#[must_use]
pub fn planners() -> Vec<PlannerInfo> {
    registry()
        .iter()
        .map(|p| PlannerInfo {
            name: p.name(),
            complete: p.complete(),
            summary: p.summary(),
        })
        .collect()
}

/// Looks a planner up by name.
///
/// # Errors
/// [`Error::Argument`] listing the known names.
pub fn find_planner(name: &str) -> Result<&'static dyn Planner> {
    oxcover_planners::find(name).map_err(|_| Error::Argument {
        name: "--planner",
        value: name.to_string(),
        expected: format!(
            "one of: {}",
            registry()
                .iter()
                .map(|p| p.name())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    })
}

/// What to plan.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanRequest {
    /// Planner name (see [`planners`]).
    pub planner: String,
    /// Robot and tool.
    pub robot: DiscRobot,
    /// Start in metres; `None` = first admissible cell (contract).
    pub start: Option<Point>,
    /// Seed for randomised planners (recorded for all).
    pub seed: u64,
    /// Append the boundary pass. Default on.
    pub boundary_pass: bool,
    /// Fixed sweep angle in degrees for `boustrophedon` and `trapezoidal`
    /// (lanes along it, map frame); `None` = the best of their 12 angles.
    pub sweep_angle_deg: Option<f64>,
}

impl PlanRequest {
    /// A request with the contract's defaults for a map of `resolution`.
    #[must_use]
    pub fn new(planner: &str, resolution: f64) -> Self {
        Self {
            planner: planner.to_string(),
            robot: DiscRobot::cell_sized(resolution),
            start: None,
            seed: 0,
            boundary_pass: true,
            sweep_angle_deg: None,
        }
    }
}

/// The result of [`plan`].
#[derive(Clone, Debug)]
pub struct PlanOutcome {
    /// Metre waypoints (the path file).
    pub points: Vec<Point>,
    /// The fine cell path behind them (for a metre plan: its lead-in and the
    /// boundary pass only).
    pub cells: Vec<Cell>,
    /// Scores of the final path.
    pub evaluation: Evaluation,
    /// Coverage of the planner's own path, before the boundary pass.
    pub coverage_without_boundary_pass: f64,
    /// What the boundary pass did, if it ran.
    pub boundary: Option<BoundaryRoute>,
    /// Fine cells per coverage-cell side.
    pub coarse_block: usize,
    /// Planning time in milliseconds (problem, planner, boundary pass).
    pub plan_ms: f64,
}

/// Coverage-cell side in fine cells for a tool radius: one tool diameter.
#[must_use]
pub fn coarse_block(robot: &DiscRobot, resolution: f64) -> usize {
    let k = (2.0 * robot.tool_radius / resolution + TOLERANCE_CELLS).floor();
    if k.is_finite() && k >= 1.0 {
        k as usize
    } else {
        1
    }
}

/// Plans a coverage path on `map`.
///
/// # Errors
/// Unknown planner, bad radii or start ([`oxcover_grid::Error`]), a planner's
/// refusal ([`oxcover_planners::Error::TooLarge`]) or an internal fault.
pub fn plan(map: &OccupancyGrid, request: &PlanRequest) -> Result<PlanOutcome> {
    let planner = find_planner(&request.planner)?;
    let Some(angle) = request.sweep_angle_deg else {
        return plan_with(map, planner, request);
    };
    let decomposition = match planner.name() {
        "boustrophedon" => Decomposition::Boustrophedon,
        "trapezoidal" => Decomposition::Trapezoidal,
        other => {
            return Err(Error::Argument {
                name: "--sweep-angle",
                value: format!("{angle} (with --planner {other})"),
                expected: "a sweep angle only with --planner boustrophedon or trapezoidal".into(),
            });
        }
    };
    plan_with(map, &Sweep::new(decomposition).at_angle(angle), request)
}

/// Plans with a given planner (registered or not); `request.planner` is ignored.
///
/// Coverage and fine cell paths are expanded to collision-free fine paths;
/// a metre path is used as given after the lead-in from the start, so its
/// collisions are whatever the planner made (the metrics count them).
///
/// # Errors
/// As [`plan`].
pub fn plan_with(
    map: &OccupancyGrid,
    planner: &dyn Planner,
    request: &PlanRequest,
) -> Result<PlanOutcome> {
    let t0 = Instant::now();
    let problem = Coverability::new(map, request.robot, request.start)?;
    let frame = map.frame();
    let k = coarse_block(&request.robot, frame.resolution());
    let coarse = CoarseGrid::new(&problem.reachable, k);
    let input = PlannerInput {
        plannable: &problem.reachable,
        coarse: &coarse,
        start: coarse.coarse_of(problem.start),
        seed: request.seed,
        frame: *frame,
        tool_cells: request.robot.tool_radius / frame.resolution(),
    };
    let output = planner.plan(&input)?;
    let (planned, tail) = match &output {
        PlanOutput::Metres(points) => {
            let first = points.first().and_then(|p| frame.cell_at(p));
            (
                first.into_iter().collect::<Vec<_>>(),
                points.get(1..).unwrap_or_default().to_vec(),
            )
        }
        _ => (expand(&input, &output)?, Vec::new()),
    };
    let mut cells = lead_in(&problem, planned.first().copied())?;
    cells.extend(planned.into_iter().skip(1));
    let mut prefix = Vec::new();
    if let Some(s) = request.start {
        if frame.cell_center(problem.start) != s {
            prefix.push(s);
        }
    }
    // A metre plan continues after the lead-in's cells; the boundary pass
    // then starts from the cell of its last point.
    let to_points = |cells: &[Cell], extra: &[Cell]| {
        let mut pts = prefix.clone();
        pts.extend(cells_to_points(frame, cells));
        pts.extend(tail.iter().copied());
        pts.extend(cells_to_points(frame, extra));
        pts
    };
    let raw_points = to_points(&cells, &[]);
    let mut plan_time = t0.elapsed();
    let raw = evaluate_problem(
        frame,
        problem.clone(),
        &raw_points,
        &MetricParams::default(),
    );
    let t1 = Instant::now();
    let mut extra = Vec::new();
    let boundary = if request.boundary_pass {
        let last_cell = raw_points
            .last()
            .and_then(|p| frame.cell_at(p))
            .filter(|&c| problem.reachable[c]);
        let end = last_cell
            .or_else(|| cells.last().copied())
            .unwrap_or(problem.start);
        let route = boundary_pass(frame, &problem, &raw_points, end)?;
        // The pass starts from `end`'s centre; a metre plan may stop elsewhere
        // in that cell, so go to the centre first (a move inside one cell).
        let off_centre = raw_points.last() != Some(&frame.cell_center(end));
        if off_centre && route.pending > 0 {
            extra.push(end);
        }
        extra.extend_from_slice(&route.cells);
        Some(route)
    } else {
        None
    };
    let points = to_points(&cells, &extra);
    cells.extend(extra);
    plan_time += t1.elapsed();
    let evaluation = evaluate_problem(frame, problem, &points, &MetricParams::default());
    Ok(PlanOutcome {
        points,
        cells,
        evaluation,
        coverage_without_boundary_pass: raw.metrics.coverage,
        boundary,
        coarse_block: k,
        plan_ms: plan_time.as_secs_f64() * 1e3,
    })
}

/// The fine path from the start cell to where the planner's path begins.
fn lead_in(problem: &Coverability, to: Option<Cell>) -> Result<Vec<Cell>> {
    let start = problem.start;
    let Some(to) = to.filter(|&t| t != start) else {
        return Ok(vec![start]);
    };
    let mut wave = Wavefront::new(&problem.reachable);
    let near = cidt(&mut wave, &[start], |c| c == to).ok_or_else(|| {
        Error::Internal(format!("plan starts at {to:?}, unreachable from the start"))
    })?;
    wave.retrace(near.first())
        .ok_or_else(|| Error::Internal("lead-in retrace failed".into()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::random::rectangles;

    #[test]
    fn unknown_planner_lists_the_known_ones() {
        let e = find_planner("nope")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.contains("--planner is `nope`") && e.contains("grid-cover"),
            "{e}"
        );
    }

    #[test]
    fn block_is_one_tool_diameter() {
        assert_eq!(coarse_block(&DiscRobot::cell_sized(0.05), 0.05), 1);
        assert_eq!(coarse_block(&DiscRobot::new(0.15, 0.15).unwrap(), 0.05), 6);
        assert_eq!(coarse_block(&DiscRobot::new(0.0, 0.01).unwrap(), 0.05), 1);
    }

    /// A planner that returns a metre path: the start's centre, then a point
    /// half a cell to its east.
    struct Metric;

    impl Planner for Metric {
        fn name(&self) -> &'static str {
            "metric"
        }
        fn complete(&self) -> bool {
            false
        }
        fn summary(&self) -> &'static str {
            "test"
        }
        fn plan(&self, input: &PlannerInput<'_>) -> oxcover_planners::Result<PlanOutput> {
            let frame =
                oxcover_grid::MapFrame::unit(input.plannable.width(), input.plannable.height());
            let rep = input.coarse.representative(input.start).unwrap_or_default();
            let p = frame.cell_center(rep);
            Ok(PlanOutput::Metres(vec![p, Point::new(p.x + 0.5, p.y)]))
        }
    }

    #[test]
    fn metre_plans_pass_through_and_get_the_boundary_pass() {
        let (map, _) = oxcover_grid::io::parse_ascii("....\n....").unwrap();
        let out = plan_with(&map, &Metric, &PlanRequest::new("metric", 1.0)).unwrap();
        assert_eq!(out.points[0], Point::new(0.5, 1.5));
        assert_eq!(out.points[1], Point::new(1.0, 1.5));
        let m = &out.evaluation.metrics;
        assert_eq!((m.coverage, m.collisions), (1.0, 0));
        assert!(out.coverage_without_boundary_pass < 1.0);
    }

    #[test]
    fn wide_tool_plan_is_complete_and_collision_free() {
        let base = rectangles(80, 60, 6, 12, 11);
        let map = OccupancyGrid::new(base.cells().clone(), 0.05, Point::new(-1.0, 2.0));
        let mut req = PlanRequest::new("dtc", 0.05);
        req.robot = DiscRobot::new(0.15, 0.15).unwrap();
        let out = plan(&map, &req).unwrap();
        let m = &out.evaluation.metrics;
        assert_eq!(m.collisions, 0);
        assert_eq!(m.coverage, 1.0);
        assert!(out.coverage_without_boundary_pass < 1.0);
        assert_eq!(out.coarse_block, 6);
        req.boundary_pass = false;
        let raw = plan(&map, &req).unwrap();
        assert_eq!(
            raw.evaluation.metrics.coverage,
            out.coverage_without_boundary_pass
        );
    }
}
