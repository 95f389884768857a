//! Full DTC (Siamantas 2010's comparison baseline): DTC run with every coverage cell
//! as the goal, keeping the shortest and the longest complete path.
//!
//! Siamantas et al. derived it "in order to compare it with the proposed
//! algorithm": DTC needs a goal, and its path length depends on that choice,
//! so full DTC brackets what DTC can do. O(n) DTC runs of O(n) each, hence
//! O(n²); refused above [`FullDtc::MAX_CELLS`] coverage cells. The planner
//! returns the shortest path; ties go to the goal first in row-major order.

use oxcover_grid::{Cell, CoarseGrid};

use crate::dtc::DtcWorkspace;
use crate::error::{Error, Result};
use crate::planner::{Planner, steps};
use crate::problem::{PlanOutput, PlannerInput};

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
    /// The shortest path (first goal in row-major order on ties).
    pub shortest: Vec<Cell>,
    /// Its goal.
    pub shortest_goal: Cell,
    /// The longest path (first goal in row-major order on ties).
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
    let cells = coarse.representatives().count(Option::is_some);
    if cells > FullDtc::MAX_CELLS {
        return Err(Error::TooLarge {
            planner: "full-dtc",
            cells,
            limit: FullDtc::MAX_CELLS,
            hint: " (it runs DTC once per goal; use dtc)",
        });
    }
    let mut ws = DtcWorkspace::new(coarse);
    let mut best: Option<(Vec<Cell>, Cell)> = None;
    let mut worst: Option<(Vec<Cell>, Cell)> = None;
    let mut runs = 0;
    let goals: Vec<Cell> = coarse.passable().true_cells().collect();
    for goal in goals {
        let Ok(path) = ws.run(coarse, start, Some(goal)) else {
            // Not reachable from the start in the coverage grid.
            continue;
        };
        runs += 1;
        if best.as_ref().is_none_or(|(b, _)| steps(&path) < steps(b)) {
            best = Some((path.clone(), goal));
        }
        if worst.as_ref().is_none_or(|(w, _)| steps(&path) > steps(w)) {
            worst = Some((path, goal));
        }
    }
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
        Ok(PlanOutput::Coverage(
            full_dtc(input.coarse, input.start)?.shortest,
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
}
