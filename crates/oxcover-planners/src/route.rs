//! Shortest routes over the coverage grid, shared by the planners that jump
//! (Spiral-STC detours, BSA backtracking): a Lee wavefront over the coverage
//! grid's connected moves, stopped early by CIDT.

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{Cell, CoarseGrid, Grid};

/// Routes between coverage cells along connected coverage-grid moves.
#[derive(Clone, Debug)]
pub(crate) struct CoarseRouter {
    wave: Wavefront,
}

impl CoarseRouter {
    /// A router over `coarse`.
    pub(crate) fn new(coarse: &CoarseGrid) -> Self {
        Self {
            wave: Wavefront::with_moves(&coarse.passable(), coarse.moves()),
        }
    }

    /// The coverage cells linked to `start` (including it).
    pub(crate) fn reachable(&mut self, start: Cell) -> Grid<bool> {
        let mut seen = Grid::new(self.wave.width(), self.wave.height(), false);
        if self.wave.is_passable(start) {
            self.wave.propagate(&[start]);
            for c in self.wave.touched_cells() {
                seen[c] = true;
            }
        }
        seen
    }

    /// A shortest route `from ..= to`, or `None` if `to` is not reachable.
    pub(crate) fn route(&mut self, from: Cell, to: Cell) -> Option<Vec<Cell>> {
        if from == to {
            return Some(vec![from]);
        }
        let near = cidt(&mut self.wave, &[from], |c| c == to)?;
        self.wave.retrace(near.first())
    }

    /// A shortest route to the nearest cell where `is_target` holds (ties:
    /// row-major first), or `None` when there is none.
    pub(crate) fn nearest(
        &mut self,
        from: Cell,
        is_target: impl FnMut(Cell) -> bool,
    ) -> Option<Vec<Cell>> {
        let near = cidt(&mut self.wave, &[from], is_target)?;
        self.wave.retrace(near.first())
    }
}
