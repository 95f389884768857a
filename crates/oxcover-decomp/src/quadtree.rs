//! Quadtree decomposition, QTD (Samet 1980; used by Siamantas et al. 2010).
//!
//! A binary matrix is split into four equal quadrants, recursively, until every
//! block holds only one value. The matrix is padded to `2^k × 2^k` with `true`
//! cells (blocked), as Siamantas 2010 assumes `n = 2^k`. The decomposition is the set
//! of *maximal uniform nodes*: nodes whose cells all share a value and whose
//! parent does not.
//!
//! [`QuadTree`] stores the count of `true` cells of every node, level by level
//! (4/3 · side² counters), so a node is uniform when its count is 0 or its area.
//! Listing the blocks is a DFS that stops at uniform nodes, O(blocks · log).
//! [`QuadTree::set`] changes one cell in O(log side) and reports exactly which
//! blocks left and joined the decomposition: only nodes on the cell's root path
//! and their children can change, so comparing those before and after is enough.
//! That is what makes Grid_Cover's per-step decomposition incremental.

use oxcover_grid::{Cell, Grid};

/// One block of the decomposition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Block {
    /// Row of the upper-left cell.
    pub row: usize,
    /// Column of the upper-left cell.
    pub col: usize,
    /// Side in cells (a power of two).
    pub size: usize,
    /// The value every cell of the block holds.
    pub value: bool,
}

impl Block {
    /// Number of cells.
    #[must_use]
    pub fn area(&self) -> usize {
        self.size * self.size
    }

    /// The upper-left cell (the block's position in Siamantas 2010).
    #[must_use]
    pub fn position(&self) -> Cell {
        Cell::new(self.row, self.col)
    }
}

/// Blocks that left and joined the decomposition after a change.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BlockChanges {
    /// Blocks no longer in the decomposition.
    pub removed: Vec<Block>,
    /// Blocks new in the decomposition.
    pub added: Vec<Block>,
}

/// A quadtree over a binary matrix, padded to a power-of-two square.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QuadTree {
    side: usize,
    depth: usize,
    /// `counts[l][r * 2^l + c]`: `true` cells in node (r, c) of level l (level 0 = root).
    counts: Vec<Vec<u32>>,
}

impl QuadTree {
    /// Decomposes `values`, padding to `2^k × 2^k` with `true`.
    #[must_use]
    pub fn new(values: &Grid<bool>) -> Self {
        let side = values
            .width()
            .max(values.height())
            .max(1)
            .next_power_of_two();
        let depth = side.trailing_zeros() as usize;
        let mut leaf = vec![1u32; side * side];
        for r in 0..values.height() {
            for (c, &v) in values.row(r).iter().enumerate() {
                leaf[r * side + c] = u32::from(v);
            }
        }
        let mut counts = vec![Vec::new(); depth + 1];
        counts[depth] = leaf;
        for l in (0..depth).rev() {
            let n = 1usize << l;
            let below = &counts[l + 1];
            let mut here = vec![0u32; n * n];
            for r in 0..n {
                for c in 0..n {
                    let (r2, c2, w) = (2 * r, 2 * c, 2 * n);
                    here[r * n + c] = below[r2 * w + c2]
                        + below[r2 * w + c2 + 1]
                        + below[(r2 + 1) * w + c2]
                        + below[(r2 + 1) * w + c2 + 1];
                }
            }
            counts[l] = here;
        }
        Self {
            side,
            depth,
            counts,
        }
    }

    /// Side of the padded square.
    #[must_use]
    pub fn side(&self) -> usize {
        self.side
    }

    /// The value of a cell (`true` outside the original matrix).
    #[must_use]
    pub fn value(&self, cell: Cell) -> bool {
        cell.row >= self.side
            || cell.col >= self.side
            || self.counts[self.depth][cell.row * self.side + cell.col] != 0
    }

    fn node(&self, level: usize, r: usize, c: usize) -> Option<Block> {
        let size = self.side >> level;
        let count = self.counts[level][r * (1 << level) + c] as usize;
        let area = size * size;
        (count == 0 || count == area).then_some(Block {
            row: r * size,
            col: c * size,
            size,
            value: count == area,
        })
    }

    /// All blocks, in depth-first order (NW, NE, SW, SE).
    #[must_use]
    pub fn blocks(&self) -> Vec<Block> {
        let mut out = Vec::new();
        self.collect(0, 0, 0, &mut out);
        out
    }

    /// Blocks whose value is `false` (in Siamantas 2010: unvisited free space).
    #[must_use]
    pub fn free_blocks(&self) -> Vec<Block> {
        let mut v = self.blocks();
        v.retain(|b| !b.value);
        v
    }

    fn collect(&self, level: usize, r: usize, c: usize, out: &mut Vec<Block>) {
        if let Some(b) = self.node(level, r, c) {
            out.push(b);
            return;
        }
        for (dr, dc) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            self.collect(level + 1, 2 * r + dr, 2 * c + dc, out);
        }
    }

    /// The maximal blocks meeting the root-to-`cell` path, plus the uniform
    /// children hanging off it (every block that a change of `cell` can affect).
    fn path_blocks(&self, cell: Cell) -> Vec<Block> {
        let mut out = Vec::new();
        let (mut r, mut c) = (0, 0);
        for level in 0..=self.depth {
            if let Some(b) = self.node(level, r, c) {
                out.push(b);
                break;
            }
            let shift = self.depth - level - 1;
            let (cr, cc) = (
                2 * r + ((cell.row >> shift) & 1),
                2 * c + ((cell.col >> shift) & 1),
            );
            for (dr, dc) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let (nr, nc) = (2 * r + dr, 2 * c + dc);
                if (nr, nc) != (cr, cc) {
                    if let Some(b) = self.node(level + 1, nr, nc) {
                        out.push(b);
                    }
                }
            }
            (r, c) = (cr, cc);
        }
        out
    }

    /// Sets one cell of the original matrix; returns the blocks that changed.
    /// Cells outside the padded square are ignored.
    pub fn set(&mut self, cell: Cell, value: bool) -> BlockChanges {
        if cell.row >= self.side || cell.col >= self.side || self.value(cell) == value {
            return BlockChanges::default();
        }
        let before = self.path_blocks(cell);
        for level in 0..=self.depth {
            let shift = self.depth - level;
            let n = 1usize << level;
            let i = (cell.row >> shift) * n + (cell.col >> shift);
            let cnt = &mut self.counts[level][i];
            if value {
                *cnt += 1;
            } else {
                *cnt -= 1;
            }
        }
        let after = self.path_blocks(cell);
        BlockChanges {
            removed: before
                .iter()
                .filter(|b| !after.contains(b))
                .copied()
                .collect(),
            added: after
                .iter()
                .filter(|b| !before.contains(b))
                .copied()
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::random::random_density;
    use proptest::prelude::*;

    fn cover(blocks: &[Block], side: usize) -> Grid<Option<bool>> {
        let mut g = Grid::new(side, side, None);
        for b in blocks {
            for r in b.row..b.row + b.size {
                for c in b.col..b.col + b.size {
                    assert!(g[Cell::new(r, c)].is_none(), "blocks overlap");
                    g[Cell::new(r, c)] = Some(b.value);
                }
            }
        }
        g
    }

    #[test]
    fn pads_and_decomposes_a_small_matrix() {
        // 3x3 all false -> padded to 4x4: the 2x2 NW quadrant is free, the rest
        // mixes free cells with padding.
        let q = QuadTree::new(&Grid::new(3, 3, false));
        assert_eq!(q.side(), 4);
        let b = q.blocks();
        assert_eq!(
            b[0],
            Block {
                row: 0,
                col: 0,
                size: 2,
                value: false
            }
        );
        assert_eq!(
            b.iter()
                .filter(|b| !b.value)
                .map(Block::area)
                .sum::<usize>(),
            9
        );
        // NE, SW and SE quadrants each mix free cells with padding: 4 cells each.
        assert_eq!(b.len(), 1 + 4 + 4 + 4);
        assert!(q.value(Cell::new(3, 0)));
    }

    proptest! {
        #[test]
        fn blocks_tile_the_matrix_and_are_maximal(w in 1usize..20, h in 1usize..20, seed in any::<u64>(), d in 0.0f64..1.0) {
            let m = random_density(w, h, d, seed).free_mask().map(|f| !f);
            let q = QuadTree::new(&m);
            let blocks = q.blocks();
            let g = cover(&blocks, q.side());
            for c in g.cells() {
                let want = if c.row < h && c.col < w { m[c] } else { true };
                prop_assert_eq!(g[c], Some(want));
            }
            // Maximal: no four sibling blocks of one size share a value.
            for b in &blocks {
                if b.size < q.side() && b.row % (2 * b.size) == 0 && b.col % (2 * b.size) == 0 {
                    let sibs = [(0, b.size), (b.size, 0), (b.size, b.size)];
                    let merged = sibs.iter().all(|&(dr, dc)| blocks.contains(&Block { row: b.row + dr, col: b.col + dc, ..*b }));
                    prop_assert!(!merged, "{b:?} and its siblings should be one block");
                }
            }
        }

        #[test]
        fn incremental_changes_match_a_fresh_decomposition(w in 1usize..17, h in 1usize..17, seed in any::<u64>(), flips in proptest::collection::vec((0usize..17, 0usize..17, any::<bool>()), 1..40)) {
            let mut m = random_density(w, h, 0.3, seed).free_mask().map(|f| !f);
            let mut q = QuadTree::new(&m);
            let mut set: std::collections::BTreeSet<Block> = q.blocks().into_iter().collect();
            for (r, c, v) in flips {
                let cell = Cell::new(r % h, c % w);
                let ch = q.set(cell, v);
                m[cell] = v;
                for b in &ch.removed { prop_assert!(set.remove(b)); }
                for b in &ch.added { prop_assert!(set.insert(*b)); }
                let fresh: std::collections::BTreeSet<Block> = QuadTree::new(&m).blocks().into_iter().collect();
                prop_assert_eq!(&set, &fresh);
            }
        }
    }
}
