//! Grid_Cover (Siamantas, Gatsis & Tzes 2010).
//!
//! Visited cells become soft obstacles. At every step the unvisited space is
//! decomposed by a quadtree (QTD), and for each feasible move `X_ij` (an
//! unvisited 4-neighbour) the paper computes eq. (2)–(3):
//! `Δ_ij = Σ_B A_B · Σ_{X_kl ∈ C_feas \ X_ij} d(X_kl, B)`, the area-weighted
//! Lee distances from the *other* candidate moves to the upper-left cell of
//! every free block, and moves to the argmin (eq. 5). A single feasible move is
//! taken directly; with none, the robot backtracks along a shortest path over
//! visited cells to the nearest unvisited cell. Distances are measured through
//! unvisited cells only; an unreachable block gets a large finite value
//! ([`unreachable_distance`]: the padded grid's area, larger than any path).
//!
//! **Speed-up, same path.** With `W_i = Σ_B A_B · d(X_i, B)`, eq. (2)–(3) give
//! `Δ_i = Σ_k W_k − W_i`, so argmin Δ = argmax W exactly (integers, same ties):
//! one wavefront per candidate instead of a double sum. The quadtree is
//! updated incrementally ([`QuadTree::set`], O(log n) per visited cell) and
//! each block's area is kept at its upper-left cell, so `W_i` is a sum over the
//! current free blocks. Wavefronts reuse one workspace. The straightforward
//! formulation (fresh QTD and fresh BFS per candidate, literal eq. (2)–(5)) is
//! kept as [`grid_cover_reference`]; tests check both give the same path on
//! random maps. Cost stays O(n²) in the worst case, as the paper states, with a
//! much smaller constant (see `docs/benchmarks.md`).
//!
//! **Ties** (equal Δ), which the paper leaves open: keep the current heading,
//! then N, E, S, W. Backtracking goes to the nearest unvisited cell (ties
//! row-major) along a shortest path that keeps its direction where it can.

use oxcover_decomp::{Block, QuadTree};
use oxcover_distance::reference::bfs_distances;
use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{Cell, CoarseGrid, Dir4, Grid};

use crate::error::{Error, Result};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};

/// The `grid-cover` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GridCover;

impl GridCover {
    /// The planner.
    #[must_use]
    pub const fn new() -> Self {
        Self
    }
}

impl Planner for GridCover {
    fn name(&self) -> &'static str {
        "grid-cover"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "Grid_Cover (Siamantas et al. 2010): quadtree of unvisited space, minimise the summed distances of the other moves"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Coverage(grid_cover(input.coarse, input.start)?))
    }
}

/// The "very large value" of an unreachable distance: the area of the padded
/// `side × side` grid, which exceeds every path length in it.
#[must_use]
pub fn unreachable_distance(side: usize) -> u64 {
    (side * side) as u64
}

/// The free blocks of the current decomposition: each block's area kept at
/// its upper-left cell, and the list of those cells (swap-remove on change).
struct FreeBlocks {
    area: Grid<u64>,
    slot: Grid<usize>,
    cells: Vec<Cell>,
}

impl FreeBlocks {
    fn new(w: usize, h: usize) -> Self {
        Self {
            area: Grid::new(w, h, 0),
            slot: Grid::new(w, h, usize::MAX),
            cells: Vec::new(),
        }
    }

    fn apply(&mut self, removed: &[Block], added: &[Block]) {
        for b in removed.iter().filter(|b| !b.value) {
            let p = b.position();
            self.area[p] = 0;
            let i = self.slot[p];
            self.slot[p] = usize::MAX;
            self.cells.swap_remove(i);
            if i < self.cells.len() {
                self.slot[self.cells[i]] = i;
            }
        }
        for b in added.iter().filter(|b| !b.value) {
            let p = b.position();
            self.area[p] = b.area() as u64;
            self.slot[p] = self.cells.len();
            self.cells.push(p);
        }
    }
}

/// Chooses among candidates by score (larger wins), then same heading, then N, E, S, W.
fn choose(cands: &[(Dir4, Cell)], scores: &[u64], heading: Option<Dir4>) -> (Dir4, Cell) {
    let mut best = 0;
    for i in 1..cands.len() {
        let key = |j: usize| {
            (
                scores[j],
                heading == Some(cands[j].0),
                3 - cands[j].0.index(),
            )
        };
        if key(i) > key(best) {
            best = i;
        }
    }
    cands[best]
}

/// Grid_Cover over the coverage grid from `start`; returns the coverage path.
///
/// # Errors
/// [`Error::Internal`] if `start` has no representative.
pub fn grid_cover(coarse: &CoarseGrid, start: Cell) -> Result<Vec<Cell>> {
    let passable = coarse.passable();
    if !passable.is_set(start) {
        return Err(Error::Internal(format!(
            "Grid_Cover start {start:?} is not a coverage cell"
        )));
    }
    let moves = coarse.moves();
    let mut all = Wavefront::with_moves(&passable, moves);
    let mut left = all.propagate(&[start]);
    let mut unvisited = Wavefront::with_moves(&passable, moves);
    let mut qt = QuadTree::new(&passable.map(|p| !p));
    let big = unreachable_distance(qt.side());
    let (w, h) = (passable.width(), passable.height());
    let mut blocks = FreeBlocks::new(w, h);
    blocks.apply(&[], &qt.free_blocks());
    let visit = |c: Cell, qt: &mut QuadTree, unvisited: &mut Wavefront, blocks: &mut FreeBlocks| {
        unvisited.set_passable(c, false);
        let ch = qt.set(c, true);
        blocks.apply(&ch.removed, &ch.added);
    };
    let mut visited = Grid::new(w, h, false);
    visited[start] = true;
    visit(start, &mut qt, &mut unvisited, &mut blocks);
    left -= 1;
    let mut path = vec![start];
    let mut cur = start;
    let mut heading: Option<Dir4> = None;
    let mut cands: Vec<(Dir4, Cell)> = Vec::with_capacity(4);
    let mut scores: Vec<u64> = Vec::with_capacity(4);
    while left > 0 {
        cands.clear();
        for d in Dir4::ALL {
            if let Some(n) = visited.step(cur, d) {
                if coarse.can_move(cur, d) && !visited[n] {
                    cands.push((d, n));
                }
            }
        }
        let next = match cands.len() {
            0 => {
                let near = cidt(&mut all, &[cur], |c| !visited[c])
                    .ok_or_else(|| Error::Internal("unvisited coverage cell unreachable".into()))?;
                let seg = all
                    .retrace(near.first())
                    .ok_or_else(|| Error::Internal("backtrack retrace failed".into()))?;
                path.extend_from_slice(&seg[1..seg.len() - 1]);
                heading = seg
                    .len()
                    .checked_sub(2)
                    .and_then(|i| seg[i].dir_to(seg[i + 1]));
                near.first()
            }
            1 => {
                heading = Some(cands[0].0);
                cands[0].1
            }
            _ => {
                scores.clear();
                for &(_, c) in &cands {
                    unvisited.propagate(&[c]);
                    let s: u64 = blocks
                        .cells
                        .iter()
                        .map(|&u| blocks.area[u] * unvisited.distance(u).map_or(big, u64::from))
                        .sum();
                    scores.push(s);
                }
                let (d, n) = choose(&cands, &scores, heading);
                heading = Some(d);
                n
            }
        };
        path.push(next);
        visited[next] = true;
        visit(next, &mut qt, &mut unvisited, &mut blocks);
        cur = next;
        left -= 1;
    }
    Ok(path)
}

/// Grid_Cover exactly as the paper states it, for unit grids (`free` cells,
/// 4-connected): a fresh QTD every step, a fresh BFS from every candidate, and
/// the literal sums of eq. (2)–(3). Quadratic and slow; the reference the fast
/// [`grid_cover`] is tested against.
#[must_use]
pub fn grid_cover_reference(free: &Grid<bool>, start: Cell) -> Vec<Cell> {
    let mut visited = Grid::new(free.width(), free.height(), false);
    if !free.is_set(start) {
        return Vec::new();
    }
    let reachable = bfs_distances(free, start);
    let mut left = reachable.count(Option::is_some) - 1;
    visited[start] = true;
    let mut path = vec![start];
    let mut cur = start;
    let mut heading: Option<Dir4> = None;
    while left > 0 {
        let g = Grid::from_fn(free.width(), free.height(), |c| !free[c] || visited[c]);
        let qt = QuadTree::new(&g);
        let big = unreachable_distance(qt.side());
        let blocks = qt.free_blocks();
        let cands: Vec<(Dir4, Cell)> = free
            .neighbours4(cur)
            .filter(|&(_, n)| free[n] && !visited[n])
            .collect();
        let next = match cands.len() {
            0 => {
                // Nearest unvisited over all free cells (ties row-major), then a
                // shortest path that keeps its direction: Lee's retrace.
                let d = bfs_distances(free, cur);
                let target = free
                    .cells()
                    .filter(|&c| !visited[c] && d[c].is_some())
                    .min_by_key(|&c| (d[c], c))
                    .unwrap_or(cur);
                let seg = retrace(&d, target);
                path.extend_from_slice(&seg[1..seg.len() - 1]);
                heading = seg
                    .len()
                    .checked_sub(2)
                    .and_then(|i| seg[i].dir_to(seg[i + 1]));
                target
            }
            1 => {
                heading = Some(cands[0].0);
                cands[0].1
            }
            _ => {
                let unvisited =
                    Grid::from_fn(free.width(), free.height(), |c| free[c] && !visited[c]);
                let dist: Vec<Grid<Option<u32>>> = cands
                    .iter()
                    .map(|&(_, c)| bfs_distances(&unvisited, c))
                    .collect();
                // Eq. (2)-(3): Δ_i = Σ_B A_B Σ_{k != i} d_k(B); eq. (5): argmin.
                let delta: Vec<u64> = (0..cands.len())
                    .map(|i| {
                        blocks
                            .iter()
                            .map(|b| {
                                let sum: u64 = (0..cands.len())
                                    .filter(|&k| k != i)
                                    .map(|k| dist[k][b.position()].map_or(big, u64::from))
                                    .sum();
                                b.area() as u64 * sum
                            })
                            .sum()
                    })
                    .collect();
                // Smaller Δ wins: score = max - Δ keeps the shared tie rule.
                let top = delta.iter().copied().max().unwrap_or(0);
                let scores: Vec<u64> = delta.iter().map(|d| top - d).collect();
                let (d, n) = choose(&cands, &scores, heading);
                heading = Some(d);
                n
            }
        };
        path.push(next);
        visited[next] = true;
        cur = next;
        left -= 1;
    }
    path
}

/// Lee's retrace on a distance grid: from `target` down to the source, keeping
/// the current direction when a shortest path allows, else N, E, S, W (the rule
/// of [`Wavefront::retrace`], restated for the reference).
fn retrace(d: &Grid<Option<u32>>, target: Cell) -> Vec<Cell> {
    let mut path = vec![target];
    let mut c = target;
    let mut dir: Option<Dir4> = None;
    while let Some(l) = d[c].filter(|&l| l > 0) {
        let next = dir.into_iter().chain(Dir4::ALL).find_map(|fwd| {
            let p = d.step(c, fwd.opposite())?;
            (d[p] == Some(l - 1)).then_some((p, fwd))
        });
        let Some((p, fwd)) = next else {
            break;
        };
        path.push(p);
        c = p;
        dir = Some(fwd);
    }
    path.reverse();
    path
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::{CoverageProblem, Start};
    use crate::testing::{cells, plan_ascii};
    use oxcover_grid::random::{random_density, uniform_connected};
    use oxcover_grid::{DiscRobot, OccupancyGrid};
    use proptest::prelude::*;

    #[test]
    fn exact_path_with_a_tie() {
        // 2x3, S top-left, padded to 4x4. Step 1: E (0,1) and S (1,0) are
        // feasible; the free blocks are the five unvisited cells. Lee distances
        // from E: 0, 2, 1, 1, 2 -> W = 6; from S: 2, 0, 1, 3, 2 -> W = 8. The
        // larger W (smaller Δ) wins: S. Then (1,1) is the only move (heading E).
        // There N (0,1) and E (1,2) tie at W = 3; the heading picks E.
        let path = plan_ascii(&GridCover::new(), "S..\n...");
        assert_eq!(
            path,
            cells(&[(0, 0), (1, 0), (1, 1), (1, 2), (0, 2), (0, 1)])
        );
    }

    #[test]
    fn dead_ends_are_entered_first() {
        // A one-cell pocket north of the corridor: Grid_Cover takes it before
        // leaving it behind (the move cut off from the most area wins).
        let path = plan_ascii(&GridCover::new(), "#.##\nS...");
        assert_eq!(
            path,
            cells(&[(1, 0), (1, 1), (0, 1), (1, 1), (1, 2), (1, 3)])
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        #[test]
        fn same_path_as_the_reference(w in 2usize..11, h in 2usize..11, density in 0.0f64..0.4, seed in any::<u64>()) {
            let map = random_density(w, h, density, seed);
            let Ok(p) = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First) else { return Ok(()); };
            let fast = grid_cover(p.coarse(), p.start_cell()).unwrap();
            let slow = grid_cover_reference(&map.free_mask(), p.start_cell());
            prop_assert_eq!(fast, slow);
        }
    }

    #[test]
    fn same_path_as_the_reference_on_seed_000_maps() {
        for seed in 0..30 {
            let map: OccupancyGrid = uniform_connected(8, 8, 15, seed).unwrap();
            let free = map.free_mask();
            let start = free.true_cells().nth((seed as usize * 7) % 49).unwrap();
            let coarse = CoarseGrid::new(&free, 1);
            assert_eq!(
                grid_cover(&coarse, start).unwrap(),
                grid_cover_reference(&free, start),
                "seed {seed}"
            );
        }
    }
}
