//! Full DTC (Siamantas 2010's comparison baseline): DTC run with every coverage cell
//! as the goal, keeping the shortest and the longest complete path.
//!
//! Siamantas et al. derived it "in order to compare it with the proposed
//! algorithm": DTC needs a goal, and its path length depends on that choice,
//! so full DTC brackets what DTC can do. O(n) DTC runs of O(n) each, hence
//! O(n²); refused above [`FullDtc::MAX_CELLS`] coverage cells. The planner
//! returns the shortest path; ties go to the goal first in row-major order.
//!
//! Room by room the pipeline passes the room's cell nearest the next room
//! ([`crate::PlannerInput::exit`]); the planner then keeps the path that,
//! with the moves on to it, takes the least estimated time
//! ([`full_dtc_towards`]). Rooms on, over the shared maps when introduced: mean estimated
//! time 16233 → 16125 s (ipa floor plans) and 9967 → 9841 s (ROS maps), and
//! rooms on is slower than off on 1 ROS map instead of 3 (scoring by moves
//! plus onward moves instead did worse on the ipa plans, 16318 s).

use oxcover_distance::Wavefront;
use oxcover_grid::{Cell, CoarseGrid, Point};

use crate::dtc::DtcWorkspace;
use crate::error::{Error, Result};
use crate::planner::{Planner, steps};
use crate::problem::{PlanOutput, PlannerInput};
use crate::time::TimeModel;

/// The `full-dtc` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FullDtc;

impl FullDtc {
    /// Largest problem accepted (coverage cells): full DTC is quadratic.
    pub const MAX_CELLS: usize = 20_000;

    /// The planner.
    #[must_use]
    pub const fn new() -> Self {
        Self
    }
}

/// Shortest and longest DTC paths over all goals.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FullDtcResult {
    /// The shortest path (first goal in row-major order on ties; from
    /// [`full_dtc_towards`] with an exit, the fastest with the way on).
    pub shortest: Vec<Cell>,
    /// Its goal.
    pub shortest_goal: Cell,
    /// The longest path (first goal in row-major order on ties; with an
    /// exit, the slowest with the way on).
    pub longest: Vec<Cell>,
    /// Its goal.
    pub longest_goal: Cell,
    /// DTC runs made (one per reachable coverage cell).
    pub runs: usize,
}

/// Runs DTC from the coverage cell `start` towards every reachable coverage cell.
///
/// # Errors
/// [`Error::TooLarge`] above [`FullDtc::MAX_CELLS`]; DTC's own errors.
pub fn full_dtc(coarse: &CoarseGrid, start: Cell) -> Result<FullDtcResult> {
    full_dtc_towards(coarse, start, None)
}

/// [`full_dtc`] for a robot that goes on to the coverage cell `exit`
/// afterwards (room by room: the cell nearest the next room): each path is
/// scored by its estimated time under `time` (cells `cell` long) plus the
/// time of the moves from its goal to `exit`, so the fastest kept is the one
/// that also leaves the robot nearest where it goes next. `None` (or an
/// `exit` off the coverage grid) is [`full_dtc`]: scored by moves.
///
/// # Errors
/// As [`full_dtc`].
pub fn full_dtc_towards(
    coarse: &CoarseGrid,
    start: Cell,
    exit: Option<(Cell, &TimeModel, f64)>,
) -> Result<FullDtcResult> {
    let cells = coarse.representatives().count(Option::is_some);
    if cells > FullDtc::MAX_CELLS {
        return Err(Error::TooLarge {
            planner: "full-dtc",
            cells,
            limit: FullDtc::MAX_CELLS,
            hint: " (it runs DTC once per goal; use dtc)",
        });
    }
    let passable = coarse.passable();
    // Moves from each goal on to the exit.
    let onwards = exit
        .filter(|&(e, _, _)| passable.is_set(e))
        .map(|(e, time, cell)| {
            let mut wave = Wavefront::with_moves(&passable, coarse.moves());
            wave.propagate(&[e]);
            (wave, time, cell)
        });
    let score = |path: &[Cell], goal: Cell| match &onwards {
        None => steps(path) as f64,
        Some((wave, time, cell)) => {
            let pts: Vec<Point> = path
                .iter()
                .map(|c| Point::new(c.col as f64 * cell, c.row as f64 * cell))
                .collect();
            let on = wave.distance(goal).map_or(f64::INFINITY, f64::from);
            time.polyline(&pts) + time.time(on * cell, 0.0)
        }
    };
    let mut ws = DtcWorkspace::new(coarse);
    let mut best: Option<(f64, Vec<Cell>, Cell)> = None;
    let mut worst: Option<(f64, Vec<Cell>, Cell)> = None;
    let mut runs = 0;
    let goals: Vec<Cell> = passable.true_cells().collect();
    for goal in goals {
        let Ok(path) = ws.run(coarse, start, Some(goal)) else {
            // Not reachable from the start in the coverage grid.
            continue;
        };
        runs += 1;
        let s = score(&path, goal);
        if best.as_ref().is_none_or(|b| s < b.0) {
            best = Some((s, path.clone(), goal));
        }
        if worst.as_ref().is_none_or(|w| s > w.0) {
            worst = Some((s, path, goal));
        }
    }
    let best = best.map(|(_, p, g)| (p, g));
    let worst = worst.map(|(_, p, g)| (p, g));
    match (best, worst) {
        (Some((shortest, shortest_goal)), Some((longest, longest_goal))) => Ok(FullDtcResult {
            shortest,
            shortest_goal,
            longest,
            longest_goal,
            runs,
        }),
        _ => Err(Error::Internal("full DTC found no goal".into())),
    }
}

impl Planner for FullDtc {
    fn name(&self) -> &'static str {
        "full-dtc"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "DTC towards every possible goal, keeping the shortest path (Siamantas 2010's baseline; O(n^2))"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        let cell = input.coarse.block_size() as f64 * input.frame.resolution();
        let exit = input
            .exit
            .map(|c| (input.coarse.coarse_of(c), &input.time, cell));
        Ok(PlanOutput::Coverage(
            full_dtc_towards(input.coarse, input.start, exit)?.shortest,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dtc::Dtc;
    use crate::testing::plan_ascii;

    #[test]
    fn brackets_every_single_goal_run() {
        let text = "S..#\n.#..\n....";
        let p = crate::testing::problem(text, 1);
        let input = p.input(0);
        let coarse = input.coarse;
        let r = full_dtc(coarse, input.start).unwrap();
        assert_eq!(r.runs, 10);
        for goal in coarse.passable().true_cells() {
            let mut dtc = DtcWorkspace::new(coarse);
            let n = steps(&dtc.run(coarse, input.start, Some(goal)).unwrap());
            assert!(steps(&r.shortest) <= n && n <= steps(&r.longest));
        }
        // A Hamiltonian path exists (10 cells, 9 moves) and some goal finds it.
        assert_eq!(steps(&r.shortest), 9);
        assert_eq!(plan_ascii(&FullDtc::new(), text), r.shortest);
        assert!(steps(&plan_ascii(&Dtc::new(), text)) >= 9);
    }

    #[test]
    fn with_an_exit_the_fastest_path_there_is_kept() {
        let text = "S..#\n.#..\n....";
        let p = crate::testing::problem(text, 1);
        let mut input = p.input(0);
        let coarse = input.coarse;
        let time = input.time;
        let exit = Cell::new(1, 3);
        let r = full_dtc_towards(coarse, input.start, Some((exit, &time, 1.0))).unwrap();
        assert_eq!(r.runs, 10);
        // Every goal's path, timed with the moves on to the exit: the kept
        // one is the fastest, and the slowest is the other bracket.
        let mut wave = Wavefront::with_moves(&coarse.passable(), coarse.moves());
        wave.propagate(&[exit]);
        let timed = |path: &[Cell], goal: Cell| {
            let pts: Vec<Point> = path
                .iter()
                .map(|c| Point::new(c.col as f64, c.row as f64))
                .collect();
            time.polyline(&pts) + time.time(f64::from(wave.distance(goal).unwrap()), 0.0)
        };
        let best = timed(&r.shortest, r.shortest_goal);
        let worst = timed(&r.longest, r.longest_goal);
        for goal in coarse.passable().true_cells() {
            let mut dtc = DtcWorkspace::new(coarse);
            let t = timed(&dtc.run(coarse, input.start, Some(goal)).unwrap(), goal);
            assert!(best <= t + 1e-9 && t <= worst + 1e-9);
        }
        // The planner passes the pipeline's exit on.
        input.exit = Some(exit);
        let out = FullDtc::new().plan(&input).unwrap();
        assert_eq!(out.coverage().unwrap(), &r.shortest[..]);
    }

    #[test]
    fn in_a_corridor_the_exit_end_is_left_for_last() {
        // From the middle, both ends take six moves: without an exit the
        // first goal in row-major order wins; with the east end as exit the
        // path covers the west end first and ends at the exit.
        let p = crate::testing::problem("..S..", 1);
        let mut input = p.input(0);
        let plain = FullDtc::new().plan(&input).unwrap();
        assert_eq!(plain.coverage().unwrap().last(), Some(&Cell::new(0, 0)));
        input.exit = Some(Cell::new(0, 4));
        let out = FullDtc::new().plan(&input).unwrap();
        assert_eq!(
            out.coverage().unwrap(),
            crate::testing::cells(&[(0, 2), (0, 1), (0, 0), (0, 1), (0, 2), (0, 3), (0, 4)])
        );
    }
}
