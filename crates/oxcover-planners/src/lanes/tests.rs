//! Tests of the whole planner: determinism, the angle budget, an open room,
//! and exact paths on tiny hand-drawn maps.

use oxcover_grid::io::parse_ascii;
use oxcover_grid::traverse::segment_clear;
use oxcover_grid::{DiscRobot, Point};

use super::angles::BUILD_BUDGET;
use super::{LaneStages, plan_lanes};
use crate::problem::PlannerInput;
use crate::{CoverageProblem, Start};

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
            .install(|| plan_lanes(&problem.input(0), None, &LaneStages::ALL).expect("plan"))
    };
    let one = on(1);
    assert!(one.len() > 8, "{one:?}");
    assert_eq!(one, on(4));
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
            input
                .time
                .polyline(&plan_lanes(input, None, &LaneStages::ALL).expect("plan"))
        };
        let (all, two) = (time(&small), time(&large));
        assert!(all <= two + 1e-9, "{size}: {all} > {two}");
        faster += usize::from(all < two - 1e-6);
    }
    assert!(faster >= 1, "more angles never helped");
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
    let pts = plan_lanes(&input, None, &LaneStages::ALL).unwrap();
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

/// Exact paths on tiny hand-drawn maps (rounded to a hundredth of a cell).
mod exact {
    use super::*;

    fn plan(text: &str) -> Vec<Point> {
        let (map, _) = parse_ascii(text).expect("valid map");
        let problem =
            CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).expect("problem");
        let pts = plan_lanes(&problem.input(0), None, &LaneStages::ALL).expect("plan");
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
