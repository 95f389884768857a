//! Rectangular decomposition (Zhang & Yan 2008).
//!
//! The environment is divided into square cells of the robot's size; each is a
//! *node* at its centre, *real* when it holds free space and *virtual* when it
//! is covered by obstacles. Two neighbouring nodes (8 directions) are
//! *connectible* when the robot can drive from one centre to the other without
//! meeting an obstacle; nodes and connectible links form the *interleaving
//! network*. Next to a neighbour it cannot connect to, a real node's square
//! grows into a rectangle: its border moves to 1.5 sides from the centre when
//! the sensors see free space there, i.e. it takes over the free part of that
//! neighbouring square. A rectangle grown on two adjacent sides also takes the
//! corner square between them, so rectangles span up to 3 × 3 squares (the
//! paper's "9 region coverage").
//!
//! On a grid (our reading of the paper, whose robot senses a continuous world):
//! - squares are the blocks of a [`CoarseGrid`] (one tool diameter, the robot
//!   size of the grid papers); a node is real when its block has a
//!   representative, which stands for the node centre;
//! - connectible = a fine, collision-free path joins the two representatives
//!   inside the two blocks (four neighbours) or the 2 × 2 blocks (diagonals);
//! - "the sensors see free space" = plannable fine cells of the neighbouring
//!   square connected to the node inside the rectangle; each such cell is
//!   given to one rectangle (the first node in row-major order), so rectangles
//!   never cover the same cell twice.
//!
//! Cells in no rectangle (e.g. cut off from every representative inside its
//! window) are left to a boundary pass. O(cells) to build.

use std::ops::Range;

use oxcover_grid::{Cell, CoarseGrid, Dir4, Dir8, Grid};

/// Bit of a [`Dir8`] in the link masks (clockwise from north).
#[must_use]
pub fn dir8_bit(d: Dir8) -> u8 {
    1 << (Dir8::ALL.iter().position(|&x| x == d).unwrap_or(0) as u8)
}

/// One node's rectangle: the squares it spans and the fine cells it covers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rectangle {
    /// Node rows spanned (the node's own row ± the grown sides).
    pub node_rows: Range<usize>,
    /// Node columns spanned.
    pub node_cols: Range<usize>,
    /// Fine rows spanned.
    pub rows: Range<usize>,
    /// Fine columns spanned.
    pub cols: Range<usize>,
    /// Sides the square grew on (one [`Dir4::bit`] each).
    pub grown: u8,
}

impl Rectangle {
    /// Squares across (1..=3).
    #[must_use]
    pub fn width_nodes(&self) -> usize {
        self.node_cols.len()
    }

    /// Squares down (1..=3).
    #[must_use]
    pub fn height_nodes(&self) -> usize {
        self.node_rows.len()
    }
}

/// The decomposition: nodes, the interleaving network, and the rectangles.
#[derive(Clone, Debug)]
pub struct RectangularDecomposition {
    coarse: CoarseGrid,
    links: Grid<u8>,
    rects: Grid<Option<Rectangle>>,
    owner: Grid<u32>,
}

impl RectangularDecomposition {
    /// Builds the decomposition of the `plannable` fine cells over the squares of `coarse`.
    #[must_use]
    pub fn new(plannable: &Grid<bool>, coarse: &CoarseGrid) -> Self {
        let (w, h) = (coarse.width(), coarse.height());
        let mut links = Grid::new(w, h, 0u8);
        for n in links.cells() {
            if coarse.representative(n).is_none() {
                continue;
            }
            for d in Dir8::ALL {
                let Some(m) = links.offset(n, d.offset()) else {
                    continue;
                };
                if coarse.representative(m).is_none() {
                    continue;
                }
                let ok = if d.is_diagonal() {
                    coarse.connect(plannable, n, m).is_some()
                } else {
                    let d4 = n.dir_to(m).unwrap_or(Dir4::North);
                    coarse.can_move(n, d4)
                };
                if ok {
                    links[n] |= dir8_bit(d);
                }
            }
        }
        // Each real node owns the cells of its block reachable from its
        // representative inside the block; then rectangles grow.
        let mut owner = Grid::new(plannable.width(), plannable.height(), 0u32);
        let id = |n: Cell| (n.row * w + n.col) as u32 + 1;
        for n in links.cells() {
            let Some(rep) = coarse.representative(n) else {
                continue;
            };
            let (rows, cols) = coarse.block_cells(n);
            claim(plannable, &mut owner, rep, &rows, &cols, id(n));
        }
        let mut rects = Grid::new(w, h, None);
        for n in links.cells() {
            let Some(rep) = coarse.representative(n) else {
                continue;
            };
            let mut grown = 0u8;
            for d in Dir4::ALL {
                let Some(m) = links.step(n, d) else {
                    continue;
                };
                let linked = coarse.can_move(n, d);
                let (rows, cols) = coarse.block_cells(m);
                let free_there = rows.clone().any(|r| {
                    cols.clone()
                        .any(|c| plannable[Cell::new(r, c)] && owner[Cell::new(r, c)] == 0)
                });
                if !linked && free_there {
                    grown |= d.bit();
                }
            }
            let up = grown & Dir4::North.bit() != 0;
            let down = grown & Dir4::South.bit() != 0;
            let left = grown & Dir4::West.bit() != 0;
            let right = grown & Dir4::East.bit() != 0;
            let node_rows = n.row - usize::from(up)..n.row + 1 + usize::from(down);
            let node_cols = n.col - usize::from(left)..n.col + 1 + usize::from(right);
            let first = coarse.block_cells(Cell::new(node_rows.start, node_cols.start));
            let last = coarse.block_cells(Cell::new(node_rows.end - 1, node_cols.end - 1));
            let rows = first.0.start..last.0.end;
            let cols = first.1.start..last.1.end;
            if grown != 0 {
                claim(plannable, &mut owner, rep, &rows, &cols, id(n));
            }
            rects[n] = Some(Rectangle {
                node_rows,
                node_cols,
                rows,
                cols,
                grown,
            });
        }
        Self {
            coarse: coarse.clone(),
            links,
            rects,
            owner,
        }
    }

    /// The square nodes (with representatives as node centres).
    #[must_use]
    pub fn nodes(&self) -> &CoarseGrid {
        &self.coarse
    }

    /// Connectible directions of a node, one [`dir8_bit`] each.
    #[must_use]
    pub fn links(&self, node: Cell) -> u8 {
        self.links.get(node).copied().unwrap_or(0)
    }

    /// Whether `node` can connect to its neighbour in direction `d`.
    #[must_use]
    pub fn connectible(&self, node: Cell, d: Dir8) -> bool {
        self.links(node) & dir8_bit(d) != 0
    }

    /// A real node's rectangle (`None` for virtual nodes).
    #[must_use]
    pub fn rectangle(&self, node: Cell) -> Option<&Rectangle> {
        self.rects.get(node).and_then(Option::as_ref)
    }

    /// The node whose rectangle covers a fine cell, if any.
    #[must_use]
    pub fn owner(&self, fine: Cell) -> Option<Cell> {
        let id = *self.owner.get(fine)?;
        (id != 0).then(|| {
            let i = id as usize - 1;
            Cell::new(i / self.coarse.width(), i % self.coarse.width())
        })
    }

    /// Fine cells of a node's rectangle, row-major.
    #[must_use]
    pub fn cells_of(&self, node: Cell) -> Vec<Cell> {
        let Some(r) = self.rectangle(node) else {
            return Vec::new();
        };
        let mut v = Vec::new();
        for row in r.rows.clone() {
            for col in r.cols.clone() {
                let c = Cell::new(row, col);
                if self.owner(c) == Some(node) {
                    v.push(c);
                }
            }
        }
        v
    }
}

/// Gives `id` every unowned plannable cell in the window connected to `from`
/// through plannable cells of the window.
fn claim(
    plannable: &Grid<bool>,
    owner: &mut Grid<u32>,
    from: Cell,
    rows: &Range<usize>,
    cols: &Range<usize>,
    id: u32,
) {
    let inside = |c: Cell| rows.contains(&c.row) && cols.contains(&c.col);
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![from];
    seen.insert(from);
    while let Some(c) = stack.pop() {
        if owner[c] == 0 {
            owner[c] = id;
        }
        for (_, n) in plannable.neighbours4(c) {
            if inside(n) && plannable[n] && seen.insert(n) {
                stack.push(n);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn squares_grow_into_partly_free_neighbours() {
        // 2x2-cell squares. The middle-right square (node (1,2)) is blocked in
        // its left column, so node (1,1) cannot connect east; the free column
        // behind the wall is reachable from node (1,1) only around the wall,
        // outside the two-square window, so it is not taken either. The bottom
        // row of squares is half blocked: node (1,0) grows down into its free half.
        let (m, _) = parse_ascii(
            "
            ......
            ......
            ....#.
            ....#.
            ......
            ######",
        )
        .unwrap();
        let free = m.free_mask();
        let coarse = CoarseGrid::new(&free, 2);
        let d = RectangularDecomposition::new(&free, &coarse);
        assert!(d.connectible(Cell::new(1, 1), Dir8::North));
        assert!(d.connectible(Cell::new(0, 0), Dir8::SouthEast));
        // Row 2 of squares has a representative (free top row), so it is real
        // and linked: no growth there.
        assert!(coarse.representative(Cell::new(2, 0)).is_some());
        let r = d.rectangle(Cell::new(1, 1)).unwrap();
        assert_eq!(r.width_nodes(), 1);
        // Every plannable cell belongs to exactly one rectangle.
        for c in free.true_cells() {
            assert!(d.owner(c).is_some(), "{c:?}");
        }
        let total: usize = coarse
            .passable()
            .true_cells()
            .map(|n| d.cells_of(n).len())
            .sum();
        assert_eq!(total, free.count_true());
    }

    #[test]
    fn a_wall_between_real_squares_grows_the_far_side_up_to_the_wall() {
        // Three squares of 3x3 cells side by side; a wall cuts the middle square
        // after its first column. The middle representative (nearest free cell
        // to its centre, ties row-major) is left of the wall, so node 0 links
        // east to node 1, node 1 cannot link to node 2, and node 2's rectangle
        // grows west over the free column behind the wall.
        let (m, _) = parse_ascii(
            "
            ....#....
            ....#....
            ....#....",
        )
        .unwrap();
        let free = m.free_mask();
        let coarse = CoarseGrid::new(&free, 3);
        let d = RectangularDecomposition::new(&free, &coarse);
        assert_eq!(
            coarse.representative(Cell::new(0, 1)),
            Some(Cell::new(1, 3))
        );
        assert!(d.connectible(Cell::new(0, 0), Dir8::East));
        assert!(!d.connectible(Cell::new(0, 1), Dir8::East));
        let r2 = d.rectangle(Cell::new(0, 2)).unwrap();
        assert_eq!(r2.grown, Dir4::West.bit());
        assert_eq!(r2.width_nodes(), 2);
        assert_eq!(d.owner(Cell::new(1, 5)), Some(Cell::new(0, 2)));
        assert_eq!(d.owner(Cell::new(1, 3)), Some(Cell::new(0, 1)));
        assert_eq!(d.rectangle(Cell::new(0, 1)).unwrap().grown, 0);
    }
}
