//! Zelinsky's distance transform and path transform (Zelinsky et al. 1993).
//!
//! - [`distance_transform`]: a full Lee wavefront from the goal; every reachable
//!   free cell gets its move count to the goal. DTC coverage climbs it.
//! - [`path_transform`]: the same from the goal, but entering a cell costs
//!   `1 + alpha·proximity(cell)`, where proximity is
//!   `max(0, influence + 1 − brushfire distance)`: `influence` next to an
//!   obstacle, falling to 0 at `influence` cells away. Solved with Dijkstra.
//!   Paths that climb it keep off walls and turn less. The proximity shape is our
//!   choice (the paper only asks for a decreasing function of obstacle
//!   distance); the defaults below are documented where they come from.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use oxcover_grid::{Cell, Grid};

use crate::brushfire::{Connectivity, brushfire};
use crate::lee::Wavefront;

/// Move counts from every cell to `goal` (`None` where unreachable or blocked).
#[must_use]
pub fn distance_transform(passable: &Grid<bool>, goal: Cell) -> Grid<Option<u32>> {
    let mut wf = Wavefront::new(passable);
    wf.propagate(&[goal]);
    wf.distances()
}

/// Parameters of [`path_transform`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTransformParams {
    /// Weight of the obstacle term. Default 1.0: one cell of detour is worth one
    /// unit of proximity, the balance Zelinsky et al. illustrate.
    pub alpha: f64,
    /// Cells from an obstacle beyond which proximity is 0. Default 3.
    pub influence: u32,
}

impl Default for PathTransformParams {
    fn default() -> Self {
        Self {
            alpha: 1.0,
            influence: 3,
        }
    }
}

impl PathTransformParams {
    /// Default parameters.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the obstacle weight.
    #[must_use]
    pub fn alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }

    /// Sets the influence distance in cells.
    #[must_use]
    pub fn influence(mut self, influence: u32) -> Self {
        self.influence = influence;
        self
    }
}

/// Path-transform cost from every cell to `goal` (`None` where unreachable).
///
/// Non-finite or negative `alpha` is treated as 0 (plain distance transform).
#[must_use]
pub fn path_transform(
    passable: &Grid<bool>,
    goal: Cell,
    params: PathTransformParams,
) -> Grid<Option<f64>> {
    let alpha = if params.alpha.is_finite() && params.alpha > 0.0 {
        params.alpha
    } else {
        0.0
    };
    let near = brushfire(passable, Connectivity::Eight, true);
    let enter = |c: Cell| {
        let d = near[c];
        let prox = (params.influence + 1).saturating_sub(d);
        1.0 + alpha * f64::from(prox)
    };
    let mut cost: Grid<Option<f64>> = Grid::new(passable.width(), passable.height(), None);
    if !passable.is_set(goal) {
        return cost;
    }
    // Costs are non-negative, so their IEEE bit patterns order like the values.
    let mut heap = BinaryHeap::new();
    cost[goal] = Some(0.0);
    heap.push(Reverse((0f64.to_bits(), passable.index_of(goal))));
    while let Some(Reverse((bits, i))) = heap.pop() {
        let c = passable.cell_of(i);
        let d = f64::from_bits(bits);
        if cost[c].is_some_and(|best| d > best) {
            continue;
        }
        // Cost of moving c -> goal is paid on entering each cell after c; going
        // backwards from the goal we pay for entering c's successor, i.e. `c`'s
        // neighbours pay `enter(c)`.
        let step = enter(c);
        for (_, n) in passable.neighbours4(c) {
            if !passable[n] {
                continue;
            }
            let nd = d + step;
            if cost[n].is_none_or(|old| nd < old) {
                cost[n] = Some(nd);
                heap.push(Reverse((nd.to_bits(), passable.index_of(n))));
            }
        }
    }
    cost
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bfs_distances;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn path_transform_with_zero_weight_is_the_distance_transform() {
        let (m, _) = parse_ascii(
            "
            ....#...
            .##.#.#.
            ....#.#.
            .#....#.",
        )
        .unwrap();
        let f = m.free_mask();
        let goal = Cell::new(0, 7);
        let dt = distance_transform(&f, goal);
        assert_eq!(dt, bfs_distances(&f, goal));
        let pt = path_transform(&f, goal, PathTransformParams::new().alpha(0.0));
        for c in f.cells() {
            assert_eq!(pt[c], dt[c].map(f64::from));
        }
    }

    #[test]
    fn descending_the_path_transform_keeps_off_the_walls() {
        let mut rows = vec!["#".repeat(11)];
        for _ in 0..7 {
            rows.push(format!("#{}#", ".".repeat(9)));
        }
        rows.push("#".repeat(11));
        let (m, _) = parse_ascii(&rows.join("\n")).unwrap();
        let f = m.free_mask();
        let goal = Cell::new(1, 1);
        let pt = path_transform(&f, goal, PathTransformParams::new());
        let dt = distance_transform(&f, goal);
        for c in f.true_cells() {
            assert!(pt[c].unwrap() >= f64::from(dt[c].unwrap()));
        }
        let near = brushfire(&f, Connectivity::Eight, true);
        let mut c = Cell::new(7, 9);
        let mut path = vec![c];
        while c != goal {
            c = f
                .neighbours4(c)
                .map(|(_, n)| n)
                .filter(|&n| f[n])
                .min_by(|a, b| pt[*a].unwrap().total_cmp(&pt[*b].unwrap()))
                .unwrap();
            path.push(c);
            assert!(path.len() < 40);
        }
        let on_wall = path.iter().filter(|&&c| near[c] == 1).count();
        // A wall-hugging route has all 15 cells next to a wall; the descent leaves
        // the walls right after the start corner and rejoins them at the goal.
        assert!(on_wall <= 6, "{on_wall} wall cells on {path:?}");
        assert!(pt[Cell::new(0, 0)].is_none());
    }
}
