//! Test helpers: plan on ASCII maps (`S` marks the start).

use oxcover_grid::io::parse_ascii;
use oxcover_grid::{Cell, DiscRobot};

use crate::planner::Planner;
use crate::problem::{CoverageProblem, Start};

/// The problem of an ASCII map (1 m cells, start at its `S`) for a point
/// robot whose tool is `block` cells wide, so coverage cells are `block`
/// fine cells on a side.
pub(crate) fn problem(text: &str, block: usize) -> CoverageProblem {
    let (map, start) = parse_ascii(text).expect("valid ASCII map");
    let start = start.expect("an S in the map");
    let robot = DiscRobot::new(0.0, block as f64 / 2.0).expect("valid tool");
    let p = CoverageProblem::new(&map, robot, Start::Cell(start)).expect("S is admissible");
    assert_eq!(p.block(), block);
    p
}

/// The coverage path of `planner` on an ASCII map with unit coverage cells.
pub(crate) fn plan_ascii(planner: &dyn Planner, text: &str) -> Vec<Cell> {
    plan_cells(planner, text, 1).0
}

/// The coverage path and the fine path of `planner` with `block`-cell coverage cells.
pub(crate) fn plan_cells(
    planner: &dyn Planner,
    text: &str,
    block: usize,
) -> (Vec<Cell>, Vec<Cell>) {
    let p = problem(text, block);
    let out = planner.plan(&p.input(0)).expect("planner succeeds");
    let fine = p.expand(&out).expect("connected plan");
    (
        out.coverage().map(<[Cell]>::to_vec).unwrap_or_default(),
        fine,
    )
}

/// Cells from `(row, col)` pairs.
pub(crate) fn cells(list: &[(usize, usize)]) -> Vec<Cell> {
    list.iter().copied().map(Cell::from).collect()
}
