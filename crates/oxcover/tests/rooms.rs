//! Room-by-room planning on seeded random room-like maps: rectangular rooms
//! in a grid, joined by doors along a random spanning tree (and a few extra
//! doors), with furniture inside. For each map and planner: complete
//! coverage, no collision, and every room finished before the next (each
//! room unit's work is one stretch of the path, every waypoint of it inside
//! that unit; transits between units aside).

use oxcover::grid::{Cell, DiscRobot, Grid, OccupancyGrid, Point};
use oxcover::pipeline::{PlanRequest, plan, room_units};
use oxcover::planners::Start;
use proptest::prelude::*;

/// Cells per metre is 20 (0.05 m cells).
const RES: f64 = 0.05;
const WALL: usize = 4;
const DOOR: usize = 18;

/// A small deterministic generator (the test must not depend on `rand`'s
/// stream, which may change between versions).
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 33) as usize) % n.max(1)
    }
}

/// `nx × ny` rooms of 2.5–4 m a side, doors 0.9 m wide, furniture.
fn room_map(nx: usize, ny: usize, seed: u64) -> OccupancyGrid {
    let mut rng = Lcg(seed);
    let widths: Vec<usize> = (0..nx).map(|_| 50 + rng.below(31)).collect();
    let heights: Vec<usize> = (0..ny).map(|_| 50 + rng.below(31)).collect();
    let w = widths.iter().sum::<usize>() + (nx + 1) * WALL;
    let h = heights.iter().sum::<usize>() + (ny + 1) * WALL;
    let x0: Vec<usize> = (0..nx)
        .map(|i| WALL + widths[..i].iter().sum::<usize>() + i * WALL)
        .collect();
    let y0: Vec<usize> = (0..ny)
        .map(|j| WALL + heights[..j].iter().sum::<usize>() + j * WALL)
        .collect();
    let mut free = Grid::new(w, h, false);
    for i in 0..nx {
        for j in 0..ny {
            for r in y0[j]..y0[j] + heights[j] {
                for c in x0[i]..x0[i] + widths[i] {
                    free[Cell::new(r, c)] = true;
                }
            }
            // Furniture: up to two blocks well inside the room.
            for _ in 0..rng.below(3) {
                let (fw, fh) = (6 + rng.below(9), 6 + rng.below(9));
                let c = x0[i] + 14 + rng.below(widths[i].saturating_sub(28 + fw).max(1));
                let r = y0[j] + 14 + rng.below(heights[j].saturating_sub(28 + fh).max(1));
                for rr in r..(r + fh).min(y0[j] + heights[j] - 14) {
                    for cc in c..(c + fw).min(x0[i] + widths[i] - 14) {
                        free[Cell::new(rr, cc)] = false;
                    }
                }
            }
        }
    }
    // Doors: a random spanning tree over the rooms, then a few more.
    let id = |i: usize, j: usize| j * nx + i;
    let mut joined = vec![false; nx * ny];
    joined[0] = true;
    let mut edges: Vec<((usize, usize), (usize, usize))> = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            if i + 1 < nx {
                edges.push(((i, j), (i + 1, j)));
            }
            if j + 1 < ny {
                edges.push(((i, j), (i, j + 1)));
            }
        }
    }
    let mut open = Vec::new();
    while joined.iter().any(|&j| !j) {
        let k = rng.below(edges.len());
        let (a, b) = edges[k];
        if joined[id(a.0, a.1)] != joined[id(b.0, b.1)] {
            joined[id(a.0, a.1)] = true;
            joined[id(b.0, b.1)] = true;
            open.push(edges.swap_remove(k));
        }
    }
    for _ in 0..rng.below(2) {
        if !edges.is_empty() {
            let k = rng.below(edges.len());
            open.push(edges.swap_remove(k));
        }
    }
    for ((i, j), (ii, jj)) in open {
        if ii > i {
            // A door in the wall between (i, j) and (i + 1, j).
            let r = y0[j] + 4 + rng.below(heights[j] - DOOR - 8);
            for rr in r..r + DOOR {
                for c in x0[i] + widths[i]..x0[ii] {
                    free[Cell::new(rr, c)] = true;
                }
            }
        } else {
            let c = x0[i] + 4 + rng.below(widths[i] - DOOR - 8);
            for cc in c..c + DOOR {
                for r in y0[j] + heights[j]..y0[jj] {
                    free[Cell::new(r, cc)] = true;
                }
            }
        }
    }
    metric(&free, Point::new(-1.0, 2.0))
}

/// A map at `RES` from a free mask.
fn metric(free: &Grid<bool>, origin: Point) -> OccupancyGrid {
    let unit = OccupancyGrid::from_free_mask(free);
    OccupancyGrid::new(unit.cells().clone(), RES, origin)
}

fn check(map: &OccupancyGrid, planner: &str) -> Result<(), TestCaseError> {
    let fail = |e: oxcover::Error| TestCaseError::fail(format!("{planner}: {e}"));
    let robot = DiscRobot::new(0.15, 0.15).map_err(|e| fail(e.into()))?;
    let req = PlanRequest::new(planner, RES)
        .map_err(fail)?
        .robot(robot)
        .start(Start::LargestRegion);
    let out = plan(map, &req).map_err(fail)?;
    let m = &out.evaluation.metrics;
    prop_assert_eq!(m.collisions, 0, "{}", planner);
    prop_assert_eq!(
        m.coverage,
        1.0,
        "{}: {}/{}",
        planner,
        m.covered_cells,
        m.coverable_cells
    );
    let units = room_units(map, &req.problem(map).map_err(fail)?);
    // One unit plans the map at once (nothing more to check).
    prop_assert_eq!(out.room_units, (units.count() > 1).then_some(units.count()));
    if units.count() < 2 {
        return Ok(());
    }
    // Every unit once, in disjoint stretches in path order, each inside its unit.
    let mut seen = vec![false; units.count()];
    let mut last_end = 0;
    for s in &out.room_stretches {
        prop_assert!(
            !seen[s.unit as usize - 1],
            "{}: unit {} twice",
            planner,
            s.unit
        );
        seen[s.unit as usize - 1] = true;
        prop_assert!(s.points.start >= last_end);
        last_end = s.points.end;
        for p in &out.points[s.points.clone()] {
            let c = map.frame().cell_at(p).unwrap_or_default();
            prop_assert_eq!(
                units.unit_of(c),
                s.unit,
                "{}: waypoint {:?} of unit {} lies in unit {}",
                planner,
                p,
                s.unit,
                units.unit_of(c)
            );
        }
    }
    prop_assert!(
        seen.iter().all(|&s| s),
        "{}: a unit was not planned",
        planner
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10))]

    #[test]
    fn rooms_are_finished_one_by_one(nx in 2usize..4, ny in 1usize..3, seed in any::<u64>()) {
        let map = room_map(nx, ny, seed);
        for planner in ["lanes", "boustrophedon", "dtc"] {
            check(&map, planner)?;
        }
    }
}

/// A room with a closet smaller than the robot, two rooms joined by a door
/// narrower than the robot, and a field with no wall at all plan without
/// error: the closet and the room behind the narrow door are not coverable
/// (a note says so), the rest plans. A map whose only room is smaller than
/// the robot is refused with the grid crate's clear message.
#[test]
fn odd_rooms_plan_without_error() {
    let robot = DiscRobot::new(0.15, 0.15).unwrap();
    // Two 2.5 m rooms joined by a 0.2 m slit: the robot cannot pass.
    let mut free = Grid::new(110, 54, false);
    for r in 2..52 {
        for c in (2..52).chain(56..108) {
            free[Cell::new(r, c)] = true;
        }
    }
    for r in 20..24 {
        for c in 52..56 {
            free[Cell::new(r, c)] = true;
        }
    }
    let slit = metric(&free, Point::origin());
    // A 2.5 m room with a closet 0.25 m square off it.
    let mut free = Grid::new(60, 54, false);
    for r in 2..52 {
        for c in 2..52 {
            free[Cell::new(r, c)] = true;
        }
    }
    for r in 20..25 {
        for c in 52..58 {
            free[Cell::new(r, c)] = true;
        }
    }
    let closet = metric(&free, Point::origin());
    // An open field: one room.
    let field = metric(&Grid::new(60, 40, true), Point::origin());
    for (name, map) in [("slit", &slit), ("closet", &closet), ("field", &field)] {
        for planner in ["lanes", "boustrophedon"] {
            let req = PlanRequest::new(planner, RES).unwrap().robot(robot);
            let out = plan(map, &req).unwrap_or_else(|e| panic!("{name} {planner}: {e}"));
            let m = &out.evaluation.metrics;
            assert_eq!((m.coverage, m.collisions), (1.0, 0), "{name} {planner}");
        }
    }
    let req = PlanRequest::new("lanes", RES).unwrap().robot(robot);
    let tiny = metric(&Grid::new(5, 5, true), Point::origin());
    let e = plan(&tiny, &req)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        e.contains("no admissible cell for robot radius 0.15 m"),
        "{e}"
    );
    let out = plan(&slit, &req).unwrap();
    let notes = oxcover::pipeline::coverage_notes(&slit, &out.evaluation.problem, true);
    assert!(
        notes.iter().any(|n| n.contains("not coverable")),
        "{notes:?}"
    );
}

/// Found by the property above: a lane line along a cell edge put waypoints
/// on the edge, in one cell of the room's crop and in the neighbouring
/// room's cell once in metres.
#[test]
fn lane_waypoints_keep_off_cell_edges() {
    let map = room_map(3, 2, 2_756_130_406_239_845_934);
    check(&map, "lanes").unwrap();
}

/// Four rooms round a cross of walls, each door found: every planner goes
/// room by room and finishes each room before the next.
#[test]
fn four_rooms_are_planned_one_by_one() {
    let map = room_map(2, 2, 8_822_461_184_539_923_430);
    let free = map.free_mask();
    let rooms = oxcover::decomp::voronoi(&free, &oxcover::decomp::RoomParams::indoor(RES));
    assert_eq!((rooms.seeded, rooms.doors.len()), (4, 4));
    for planner in ["lanes", "boustrophedon", "dtc", "bsa", "spiral-stc"] {
        check(&map, planner).unwrap();
    }
}

/// Room by room, the pipeline runs in parallel in several places (the
/// segmentation beside the problem's build, the room order's wavefronts,
/// each room's two tightened boundary routes, `lanes`' angles): the path is
/// the same on one thread as on four, for every planner kind.
#[test]
fn room_by_room_plans_do_not_depend_on_the_thread_count() {
    let map = room_map(3, 2, 7);
    let robot = DiscRobot::new(0.15, 0.15).unwrap();
    for planner in ["lanes", "boustrophedon", "dtc", "full-dtc", "smooth"] {
        let req = PlanRequest::new(planner, RES)
            .unwrap()
            .robot(robot)
            .start(Start::LargestRegion);
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| plan(&map, &req).expect("plan"))
        };
        let (one, four) = (on(1), on(4));
        assert!(one.room_units.is_some_and(|n| n > 1), "{planner}: one room");
        assert_eq!(one.points, four.points, "{planner}");
    }
}
