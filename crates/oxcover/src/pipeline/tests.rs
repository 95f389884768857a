//! Tests of the pipeline: room detection, unknown planners, metre plans
//! with their pass, the tightening's coverage check, wide tools.

use std::sync::Arc;

use oxcover_grid::footprint::covered_cells;
use oxcover_grid::{Cell, DiscRobot, Grid, Point};
use oxcover_planners::{PlanOutput, Planner, PlannerOptions};

use super::region::loses_coverage;
use super::rooms::in_several_rooms;
use super::*;
use oxcover_grid::random::rectangles;
use oxcover_planners::PlannerInput;

/// One label under every plannable cell (whatever the others carry) is
/// one room; a second label is several.
#[test]
fn several_rooms_need_two_labels_under_the_plannable_cells() {
    let plannable = Grid::from_fn(4, 2, |c| c.col < 3);
    let mut labels = Grid::from_fn(4, 2, |c| if c.col < 3 { 2 } else { 5 });
    assert!(!in_several_rooms(&plannable, &labels));
    labels[Cell::new(1, 2)] = 0;
    assert!(in_several_rooms(&plannable, &labels));
    assert!(!in_several_rooms(&Grid::new(4, 2, false), &labels));
}

#[test]
fn unknown_planner_lists_the_known_ones() {
    let e = planner("nope", &PlannerOptions::new())
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        e.contains("--planner is `nope`") && e.contains("grid-cover"),
        "{e}"
    );
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
        let rep = input.coarse.representative(input.start).unwrap_or_default();
        let p = input.frame.cell_center(rep);
        Ok(PlanOutput::Metres(vec![p, Point::new(p.x + 0.5, p.y)]))
    }
}

#[test]
fn metre_plans_pass_through_and_get_the_boundary_pass() {
    let (map, _) = oxcover_grid::io::parse_ascii("....\n....").unwrap();
    let req = PlanRequest::with_planner(Arc::new(Metric), 1.0);
    let out = plan(&map, &req.clone().rooms(false)).unwrap();
    assert_eq!(out.points[0], Point::new(0.5, 1.5));
    assert_eq!(out.points[1], Point::new(1.0, 1.5));
    let m = &out.evaluation.metrics;
    assert_eq!((m.coverage, m.collisions), (1.0, 0));
    assert!(out.coverage_without_boundary_pass < 1.0);
    // Rooms on, the whole path is tightened afterwards: from the same
    // start, as complete, never slower.
    let on = plan(&map, &req).unwrap();
    assert_eq!(on.points[0], out.points[0]);
    let n = &on.evaluation.metrics;
    assert_eq!((n.coverage, n.collisions), (1.0, 0));
    assert!(n.est_time_s <= m.est_time_s + 1e-9);
    // The pass's length: every segment but those ending at the
    // planner's own waypoint (the half cell east of the start). Rooms
    // on, that is measured on the tightened path, which here drops the
    // planner's waypoint: the pass is the whole of it.
    let own = |points: &[Point]| -> f64 {
        points
            .windows(2)
            .filter(|w| w[1] == Point::new(1.0, 1.5))
            .map(|w| (w[1] - w[0]).norm())
            .sum()
    };
    assert!((out.boundary_length_m - (m.length_m - own(&out.points))).abs() < 1e-9);
    assert!((own(&out.points) - 0.5).abs() < 1e-9);
    assert!((on.boundary_length_m - (n.length_m - own(&on.points))).abs() < 1e-9);
}

#[test]
fn a_tightening_that_uncovers_a_cell_is_caught() {
    // A 1 × 6 corridor, tool radius 0.5 (a cell's centre within half a
    // cell of the path, as sampled, is covered).
    let (map, _) = oxcover_grid::io::parse_ascii("......").unwrap();
    let frame = map.frame();
    let coverable = Grid::new(6, 1, true);
    let along = |x0: f64, x1: f64| vec![Point::new(x0, 0.5), Point::new(x1, 0.5)];
    let whole = along(0.5, 5.5);
    let loses_coverage = |frame, coverable, tool, before: &[Point], after: &[Point]| {
        loses_coverage(
            frame,
            coverable,
            tool,
            before,
            &covered_cells(frame, after, tool),
        )
    };
    // Nothing lost: the same cells, or a path that covers them all.
    assert!(!loses_coverage(frame, &coverable, 0.5, &whole, &whole));
    assert!(!loses_coverage(
        frame,
        &coverable,
        0.5,
        &along(1.5, 5.5),
        &whole
    ));
    // The last cell dropped, which `before` covered.
    assert!(loses_coverage(
        frame,
        &coverable,
        0.5,
        &whole,
        &along(0.5, 4.5)
    ));
    // A cell `before` missed too is not a loss.
    assert!(!loses_coverage(
        frame,
        &coverable,
        0.5,
        &along(0.5, 4.5),
        &along(0.5, 4.5)
    ));
    assert!(loses_coverage(
        frame,
        &coverable,
        0.5,
        &along(0.5, 4.5),
        &along(0.5, 3.5)
    ));
}

#[test]
fn wide_tool_plan_is_complete_and_collision_free() {
    let base = rectangles(80, 60, 6, 12, 11);
    let map = OccupancyGrid::new(base.cells().clone(), 0.05, Point::new(-1.0, 2.0));
    let req = PlanRequest::new("dtc", 0.05)
        .unwrap()
        .robot(DiscRobot::new(0.15, 0.15).unwrap());
    let out = plan(&map, &req).unwrap();
    let m = &out.evaluation.metrics;
    assert_eq!(m.collisions, 0);
    assert_eq!(m.coverage, 1.0);
    assert!(out.coverage_without_boundary_pass < 1.0);
    assert_eq!(out.coarse_block, 6);
    // The planner's own coverage (rooms off: no tightening after it).
    let off = req.rooms(false);
    let out = plan(&map, &off).unwrap();
    let raw = plan(&map, &off.boundary_pass(false)).unwrap();
    assert_eq!(
        raw.evaluation.metrics.coverage,
        out.coverage_without_boundary_pass
    );
}

/// A small zone's rooms are segmented on its window only (no label beyond
/// it), a large zone's and a plain plan's on the whole map; the whole
/// map's rooms are at hand either way.
#[test]
fn a_small_zone_segments_its_neighbourhood() {
    use crate::targets::{Areas, Targets};
    let map = oxcover_grid::OccupancyGrid::new(
        rectangles(400, 300, 40, 30, 5).cells().clone(),
        0.05,
        Point::origin(),
    );
    let zone = |(x0, x1): (f64, f64), (y0, y1): (f64, f64)| {
        geo::Polygon::new(
            geo::LineString::from(vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]),
            Vec::new(),
        )
    };
    let request = |targets: Targets| {
        PlanRequest::new("lanes", 0.05)
            .unwrap()
            .robot(DiscRobot::new(0.1, 0.1).unwrap())
            .targets(targets)
    };
    let zoned = |x: (f64, f64), y: (f64, f64)| Targets {
        zones: Some(Areas {
            polygons: vec![zone(x, y)],
            lines: Vec::new(),
        }),
        ..Targets::default()
    };
    let whole = rooms::PlanRooms::new(&map, &request(Targets::default()));
    assert!(whole.local().is_none());
    let small = rooms::PlanRooms::new(&map, &request(zoned((8.0, 11.0), (5.0, 8.0))));
    let (r0, r1, c0, c1) = small.local().expect("a window");
    // The zone's box (columns 160 to 220, a cell more round) widened by
    // the margin and the tool (in cells, give or take rounding).
    let m = ((rooms::LOCAL_ROOMS_MARGIN_M + 0.1) / 0.05).round() as usize;
    assert!((159 - m - 1..=159 - m).contains(&c0), "{c0}");
    assert!((221 + m..=221 + m + 1).contains(&c1), "{c1}");
    assert!(r0 > 0 && r1 < 300);
    for c in small.rooms.labels.cells() {
        if !((r0..r1).contains(&c.row) && (c0..c1).contains(&c.col)) {
            assert_eq!(small.rooms.labels[c], 0, "{c:?}");
        }
    }
    assert!(small.rooms.labels.as_slice().iter().any(|&l| l > 0));
    assert_eq!(*small.whole(), *whole.whole());
    // A zone over most of the map: the whole map's rooms.
    assert!(
        rooms::PlanRooms::new(&map, &request(zoned((1.0, 19.0), (1.0, 14.0))))
            .local()
            .is_none()
    );
}

/// A zone's plan is the same whether the coverable cells were looked for
/// in the zone's window only or on the whole map: a small zone, and one
/// over the whole map (whose plan is compared with the map's, built again
/// for it).
#[test]
fn a_zone_plans_the_same_with_coverable_cells_in_its_window() {
    use crate::targets::{Areas, Targets};
    let map = oxcover_grid::OccupancyGrid::new(
        rectangles(120, 90, 12, 9, 3).cells().clone(),
        0.05,
        Point::origin(),
    );
    for (x0, x1, y0, y1) in [(1.5, 3.0, 1.5, 3.0), (-1.0, 7.0, -1.0, 5.0)] {
        let zone = geo::Polygon::new(
            geo::LineString::from(vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]),
            Vec::new(),
        );
        let request = PlanRequest::new("lanes", 0.05)
            .unwrap()
            .robot(DiscRobot::new(0.1, 0.1).unwrap())
            .targets(Targets {
                zones: Some(Areas {
                    polygons: vec![zone],
                    lines: Vec::new(),
                }),
                ..Targets::default()
            });
        let within = request.targets.extent(&map);
        assert!(within.is_some());
        let plan = |within| {
            let problem = request.problem_within(&map, within).unwrap();
            let target = request.targets.required(&map, problem.cells()).unwrap();
            let target = target.map(|t| prepared_target(&problem, t));
            let rooms = Some(rooms::PlanRooms::new(&map, &request));
            let maps = (&map, &map, within.is_some());
            plan_problem(maps, (problem, target), rooms, 0, &request, Instant::now()).unwrap()
        };
        let (windowed, everywhere) = (plan(within), plan(None));
        assert_eq!(windowed.points, everywhere.points);
        assert_eq!(
            windowed.evaluation.metrics.coverable_cells,
            everywhere.evaluation.metrics.coverable_cells
        );
    }
}
