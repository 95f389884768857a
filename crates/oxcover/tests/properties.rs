//! Planner properties on seeded random maps, the same checks for every planner:
//! the path never leaves the admissible cells and covers every coverable cell.
//! Heavier than unit tests: the README's test command runs them in release.

use oxcover::metrics::{MetricParams, evaluate};
use oxcover::planner::{PLANNERS, PlanRequest, plan};
use oxcover_grid::random::{blobs, random_density, rectangles};
use oxcover_grid::{DiscRobot, OccupancyGrid, Point};
use proptest::prelude::*;

fn random_map(kind: u8, w: usize, h: usize, seed: u64, res: f64) -> OccupancyGrid {
    let m = match kind {
        0 => rectangles(w, h, w * h / 300 + 1, 10, seed),
        1 => blobs(w, h, w * h / 400 + 1, 5, seed),
        _ => random_density(w, h, 0.25, seed),
    };
    OccupancyGrid::new(m.cells().clone(), res, Point::new(-3.0, 1.5))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn every_complete_planner_covers_everything_without_collisions(
        kind in 0u8..3, w in 12usize..90, h in 12usize..90, seed in any::<u64>(),
        res in prop::sample::select(vec![0.03, 0.05, 0.1, 1.0]),
        robot_cells in 0.0f64..3.5, tool_cells in 0.3f64..4.5,
    ) {
        let map = random_map(kind, w, h, seed, res);
        let robot = DiscRobot::new(robot_cells * res, tool_cells * res).unwrap();
        for info in PLANNERS.iter().filter(|p| p.complete) {
            let mut req = PlanRequest::new(info.name, res);
            req.robot = robot;
            let out = match plan(&map, &req) {
                Ok(o) => o,
                // Maps with no room for this robot are a clear error, not a plan.
                Err(oxcover::Error::Map(oxcover_grid::Error::NoAdmissibleCell { .. } | oxcover_grid::Error::NoFreeCell { .. })) => return Ok(()),
                Err(e) => return Err(TestCaseError::fail(e.to_string())),
            };
            let m = &out.evaluation.metrics;
            prop_assert_eq!(m.collisions, 0, "{}", info.name);
            prop_assert_eq!(m.coverage, 1.0, "{}: {}/{}", info.name, m.covered_cells, m.coverable_cells);
            let reach = &out.evaluation.problem.reachable;
            prop_assert!(out.cells.iter().all(|&c| reach[c]));
            prop_assert!(out.cells.windows(2).all(|s| s[0].manhattan(s[1]) <= 1));
            // Scoring the written path from scratch gives the same numbers.
            let again = evaluate(&map, robot, &out.points, &MetricParams::default()).unwrap();
            prop_assert_eq!(&again.metrics, m);
        }
    }
}
