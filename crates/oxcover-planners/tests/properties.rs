//! Every registered planner, checked the same way on seeded random maps: its
//! fine path stays on plannable cells and moves 4-connected; complete planners
//! visit every coverage cell; `optimal` is at most every other planner's moves
//! and at least its lower bound (parity, dead ends, count).

use oxcover_grid::Point;
use oxcover_grid::random::{random_density, uniform_connected};
use oxcover_grid::traverse::{cell_center, segment_clear, segment_distance};
use oxcover_grid::{CoarseGrid, DiscRobot, Grid, OccupancyGrid};
use oxcover_planners::optimal::{Optimal, lower_bound, optimal};
use oxcover_planners::{CoverageProblem, PlanOutput, PlannerInput, Start, registry};

/// A metre plan (unit frame): starts where the robot stands or at its
/// coverage cell's representative, every
/// segment crosses plannable cells only, and (if complete) passes within half
/// a coverage cell of every representative.
fn check_metres(input: &PlannerInput<'_>, points: &[Point], complete: bool) -> Result<(), String> {
    let h = input.plannable.height() as f64;
    let pts: Vec<Point> = points.iter().map(|p| Point::new(p.x, h - p.y)).collect();
    let rep = input
        .coarse
        .representative(input.start)
        .ok_or("no start representative")?;
    let first = pts.first();
    if first != Some(&cell_center(rep)) && first != Some(&cell_center(input.start_cell)) {
        return Err(format!(
            "starts at {:?}, not {:?}",
            pts.first(),
            cell_center(rep)
        ));
    }
    for w in pts.windows(2) {
        if !segment_clear(input.plannable, w[0], w[1]) {
            return Err(format!("segment {:?} crosses a wall", w));
        }
    }
    if complete {
        let r = input.coarse.block_size() as f64 / 2.0 + 1e-9;
        for rep in input.coarse.representatives().as_slice().iter().flatten() {
            let c = cell_center(*rep);
            let near = pts.windows(2).any(|w| segment_distance(w[0], w[1], c) <= r)
                || pts.iter().any(|&p| (p.x - c.x).hypot(p.y - c.y) <= r);
            if !near {
                return Err(format!("missed representative {rep:?}"));
            }
        }
    }
    Ok(())
}

use proptest::prelude::*;

/// The problem of `map` (1 m cells, the contract's default start) for a
/// point robot whose tool is `block` cells wide.
fn problem(map: &OccupancyGrid, block: usize, start: Start) -> Option<CoverageProblem> {
    let robot = DiscRobot::new(0.0, block as f64 / 2.0).ok()?;
    CoverageProblem::new(map, robot, start).ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn plans_are_admissible_and_complete(w in 3usize..14, h in 3usize..14, density in 0.0f64..0.35, seed in any::<u64>(), block in 1usize..4) {
        let map = random_density(w, h, density, seed);
        let Some(p) = problem(&map, block, Start::First) else { return Ok(()); };
        let input = p.input(0);
        let coarse = p.coarse();
        for planner in registry() {
            // The exact search is exponential in the grid's width; keep it to
            // widths where it is quick (the optimality checks are below).
            if planner.name() == "optimal" && coarse.width().min(coarse.height()) > 8 {
                continue;
            }
            let out = match planner.plan(&input) {
                Ok(o) => o,
                Err(oxcover_planners::Error::TooLarge { .. } | oxcover_planners::Error::TooWide { .. }) => continue,
                Err(e) => return Err(TestCaseError::fail(format!("{}: {e}", planner.name()))),
            };
            if let PlanOutput::Metres(points) = &out {
                check_metres(&input, points, planner.complete())
                    .map_err(|e| TestCaseError::fail(format!("{}: {e}", planner.name())))?;
                continue;
            }
            let fine = p.expand(&out).unwrap();
            prop_assert_eq!(fine.first().copied(), coarse.representative(input.start), "{}", planner.name());
            prop_assert!(fine.iter().all(|&c| p.plannable()[c]), "{} leaves the plannable cells", planner.name());
            prop_assert!(fine.windows(2).all(|s| s[0].manhattan(s[1]) == 1), "{} is not 4-connected", planner.name());
            if planner.complete() {
                let mut seen = Grid::new(coarse.width(), coarse.height(), false);
                match out.coverage() {
                    Some(path) => path.iter().for_each(|&c| seen[c] = true),
                    None => fine.iter().for_each(|&c| seen[coarse.coarse_of(c)] = true),
                }
                // Every coverage cell linked to the start in the coverage grid.
                let mut wave = oxcover_distance::Wavefront::with_moves(&coarse.passable(), coarse.moves());
                wave.propagate(&[input.start]);
                for c in wave.touched_cells() {
                    prop_assert!(seen[c], "{} missed coverage cell {:?}", planner.name(), c);
                }
            }
        }
    }

    #[test]
    fn optimal_is_a_lower_envelope(seed in 0u64..400, start_pick in any::<u32>()) {
        let map = uniform_connected(7, 7, 11, seed).unwrap();
        let free = map.free_mask();
        let cells: Vec<_> = free.true_cells().collect();
        let start = cells[start_pick as usize % cells.len()];
        let p = problem(&map, 1, Start::Cell(start)).unwrap();
        let input = p.input(0);
        let coarse = CoarseGrid::new(&free, 1);
        let best = optimal(&coarse, start, &Optimal::new()).unwrap();
        prop_assert!(best.proven);
        prop_assert!(best.steps >= lower_bound(&coarse, start));
        prop_assert!(best.steps >= cells.len() - 1);
        // Incomplete planners (plain STC) may stop short of the optimum.
        for planner in registry().filter(|p| p.complete()) {
            let out = planner.plan(&input).unwrap();
            if let PlanOutput::Metres(points) = &out {
                // A metre path has no move count to compare with the optimum.
                let _ = points;
                continue;
            }
            let fine = p.expand(&out).unwrap();
            prop_assert!(best.steps < fine.len(), "{} beat the optimum: {} < {}", planner.name(), fine.len() - 1, best.steps);
        }
    }
}
