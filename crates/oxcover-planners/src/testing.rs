//! Test helpers: plan on ASCII maps (`S` marks the start).

use oxcover_grid::io::parse_ascii;
use oxcover_grid::{Cell, CoarseGrid, Coverability, DiscRobot};

use crate::planner::{Planner, PlannerInput, expand};

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
    let (map, start) = parse_ascii(text).expect("valid ASCII map");
    let start = start.expect("an S in the map");
    let p = Coverability::with_start_cell(&map, DiscRobot::cell_sized(1.0), start)
        .expect("S is admissible");
    let coarse = CoarseGrid::new(&p.reachable, block);
    let input = PlannerInput::new(&p.reachable, &coarse, start);
    let out = planner.plan(&input).expect("planner succeeds");
    let fine = expand(&input, &out).expect("connected plan");
    (
        out.coverage().map(<[Cell]>::to_vec).unwrap_or_default(),
        fine,
    )
}

/// Cells from `(row, col)` pairs.
pub(crate) fn cells(list: &[(usize, usize)]) -> Vec<Cell> {
    list.iter().copied().map(Cell::from).collect()
}
