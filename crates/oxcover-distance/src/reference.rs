//! Plain reference implementations, kept simple on purpose.
//!
//! [`bfs_distances`] is the textbook `VecDeque` breadth-first search with
//! bounds-checked neighbour lookups and a fresh distance array per call. Tests
//! check the fast transforms against it, and the benchmarks measure against it
//! in the same run (ratios are stable where absolute times are not).

use std::collections::VecDeque;

use oxcover_grid::{Cell, Grid};

/// 4-connected BFS distances from `source` over the `true` cells of `passable`.
#[must_use]
pub fn bfs_distances(passable: &Grid<bool>, source: Cell) -> Grid<Option<u32>> {
    let mut dist = Grid::new(passable.width(), passable.height(), None);
    if !passable.is_set(source) {
        return dist;
    }
    let mut queue = VecDeque::new();
    dist[source] = Some(0);
    queue.push_back(source);
    while let Some(c) = queue.pop_front() {
        let d = dist[c].unwrap_or(0);
        for (_, n) in passable.neighbours4(c) {
            if passable[n] && dist[n].is_none() {
                dist[n] = Some(d + 1);
                queue.push_back(n);
            }
        }
    }
    dist
}
