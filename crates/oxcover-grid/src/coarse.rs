//! Coarse coverage grids: a fine map grouped into `k × k` blocks (e.g. one tool
//! diameter), each block standing for one coverage cell of the grid planners.
//!
//! **Rule for partially blocked blocks**: a block is a coarse cell when at least
//! one of its fine cells is *plannable* (admissible and reachable); its
//! *representative* is the plannable cell nearest the block's nominal centre
//! (ties: row-major first), and a robot "visits" the coarse cell by standing
//! there. Blocks at the right and bottom map edges may be clipped; their nominal
//! centre is still that of a full block so lanes stay evenly spaced.
//!
//! Two 4-adjacent coarse cells are *connected* when a 4-connected path of
//! plannable fine cells joins their representatives inside the two blocks;
//! [`CoarseGrid::connect`] returns that path (shortest, by BFS in the window),
//! so every coarse move maps to a collision-free fine path. What a coarse grid
//! misses (the parts of a block not reachable from its representative inside the
//! window, strips along walls) is left to a boundary pass.

use std::collections::VecDeque;
use std::ops::Range;

use rayon::prelude::*;

use crate::frame::MapFrame;
use crate::grid::{Cell, Dir4, Grid};
use crate::math::Point;

/// A coarse grid of representative cells over a fine plannable mask.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoarseGrid {
    block: usize,
    fine_width: usize,
    fine_height: usize,
    reps: Grid<Option<Cell>>,
    moves: Grid<u8>,
}

impl CoarseGrid {
    /// Groups `plannable` into `block × block` cells (`block >= 1`; 0 is taken as 1).
    #[must_use]
    pub fn new(plannable: &Grid<bool>, block: usize) -> Self {
        let k = block.max(1);
        let (fw, fh) = (plannable.width(), plannable.height());
        let (cw, ch) = (fw.div_ceil(k), fh.div_ceil(k));
        // Each block's representative, and whether all its cells are
        // plannable (two such blocks side by side are linked: no search).
        // The cells of a block nearest its nominal centre first (doubled
        // coordinates keep the centre integral; ties in row-major order):
        // the first plannable one met is the representative.
        let mut order: Vec<(usize, usize)> =
            (0..k).flat_map(|r| (0..k).map(move |c| (r, c))).collect();
        order.sort_by_key(|&(r, c)| {
            let (dr, dc) = ((2 * r).abs_diff(k - 1), (2 * c).abs_diff(k - 1));
            (dr * dr + dc * dc, r, c)
        });
        let blocks = Grid::par_from_fn(cw, ch, |b| {
            let (r0, c0) = (b.row * k, b.col * k);
            let (rows, cols) = (r0..(r0 + k).min(fh), c0..(c0 + k).min(fw));
            let row = |r: usize| &plannable.row(r)[cols.clone()];
            let full = rows.clone().all(|r| row(r).iter().all(|&p| p));
            if !full && !rows.clone().any(|r| row(r).contains(&true)) {
                return (None, false);
            }
            let rep = order
                .iter()
                .map(|&(r, c)| Cell::new(r0 + r, c0 + c))
                .find(|c| c.row < fh && c.col < fw && plannable[*c]);
            (rep, full)
        });
        let reps = blocks.map(|b| b.0);
        let mut grid = Self {
            block: k,
            fine_width: fw,
            fine_height: fh,
            moves: Grid::new(cw, ch, 0),
            reps,
        };
        // Each block's links east and south, found in parallel (each task
        // with its own scratch window; the same whatever the thread count).
        const DIRS: [Dir4; 2] = [Dir4::East, Dir4::South];
        let links: Vec<[bool; 2]> = (0..cw * ch)
            .into_par_iter()
            .map_init(Window::default, |scratch, i| {
                let b = Cell::new(i / cw, i % cw);
                DIRS.map(|dir| {
                    let Some(n) = grid.reps.step(b, dir) else {
                        return false;
                    };
                    match (grid.reps[b], grid.reps[n]) {
                        (Some(a), Some(z)) if k == 1 => plannable[a] && plannable[z],
                        (Some(_), Some(_)) if blocks[b].1 && blocks[n].1 => true,
                        (Some(_), Some(_)) => grid.window_linked(plannable, b, n, scratch),
                        _ => false,
                    }
                })
            })
            .collect();
        for (i, pair) in links.into_iter().enumerate() {
            let b = Cell::new(i / cw, i % cw);
            for (dir, linked) in DIRS.into_iter().zip(pair) {
                if let (true, Some(n)) = (linked, grid.reps.step(b, dir)) {
                    grid.moves[b] |= dir.bit();
                    grid.moves[n] |= dir.opposite().bit();
                }
            }
        }
        grid
    }

    /// Fine cells per block side.
    #[must_use]
    pub fn block_size(&self) -> usize {
        self.block
    }

    /// Coarse columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.reps.width()
    }

    /// Coarse rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.reps.height()
    }

    /// The representative fine cell of a coarse cell, if it has one.
    #[must_use]
    pub fn representative(&self, coarse: Cell) -> Option<Cell> {
        self.reps.get(coarse).copied().flatten()
    }

    /// Representatives of all coarse cells.
    #[must_use]
    pub fn representatives(&self) -> &Grid<Option<Cell>> {
        &self.reps
    }

    /// `true` where the coarse cell has a representative.
    #[must_use]
    pub fn passable(&self) -> Grid<bool> {
        self.reps.map(Option::is_some)
    }

    /// Open directions per coarse cell, one [`Dir4::bit`] each.
    #[must_use]
    pub fn moves(&self) -> &Grid<u8> {
        &self.moves
    }

    /// Whether the coarse move from `coarse` in `dir` is connected.
    #[must_use]
    pub fn can_move(&self, coarse: Cell, dir: Dir4) -> bool {
        self.moves.get(coarse).is_some_and(|m| m & dir.bit() != 0)
    }

    /// The coarse cell containing a fine cell.
    #[must_use]
    pub fn coarse_of(&self, fine: Cell) -> Cell {
        Cell::new(fine.row / self.block, fine.col / self.block)
    }

    /// Fine rows and columns of a coarse cell (clipped at the map edge).
    #[must_use]
    pub fn block_cells(&self, coarse: Cell) -> (Range<usize>, Range<usize>) {
        let k = self.block;
        (
            coarse.row * k..((coarse.row + 1) * k).min(self.fine_height),
            coarse.col * k..((coarse.col + 1) * k).min(self.fine_width),
        )
    }

    /// Nominal centre of a coarse cell in metres.
    #[must_use]
    pub fn center(&self, coarse: Cell, frame: &MapFrame) -> Point {
        let k = self.block as f64;
        frame.position(
            coarse.row as f64 * k + (k - 1.0) / 2.0,
            coarse.col as f64 * k + (k - 1.0) / 2.0,
        )
    }

    /// The fine path from the representative of `a` to that of `b`, a 4- or
    /// diagonal neighbour, inside the bounding rectangle of their blocks (both
    /// ends included; shortest by BFS), if there is one.
    #[must_use]
    pub fn connect(&self, plannable: &Grid<bool>, a: Cell, b: Cell) -> Option<Vec<Cell>> {
        if a == b || a.row.abs_diff(b.row) > 1 || a.col.abs_diff(b.col) > 1 {
            return None;
        }
        let mut scratch = Window::default();
        self.window_path(plannable, a, b, &mut scratch)
    }

    fn window_path(
        &self,
        plannable: &Grid<bool>,
        a: Cell,
        b: Cell,
        w: &mut Window,
    ) -> Option<Vec<Cell>> {
        let (from, to) = (self.representative(a)?, self.representative(b)?);
        let (rows, cols) = self.pair_window(a, b);
        w.shortest(plannable, rows, cols, from, to)
    }

    /// The fine rows and columns of the rectangle round blocks `a` and `b`.
    fn pair_window(&self, a: Cell, b: Cell) -> (Range<usize>, Range<usize>) {
        let (ra, ca) = self.block_cells(a);
        let (rb, cb) = self.block_cells(b);
        (
            ra.start.min(rb.start)..ra.end.max(rb.end),
            ca.start.min(cb.start)..ca.end.max(cb.end),
        )
    }

    /// Whether [`Self::window_path`] finds a path (the same answer, found
    /// by row masks where the window is at most 64 columns wide).
    fn window_linked(&self, plannable: &Grid<bool>, a: Cell, b: Cell, w: &mut Window) -> bool {
        let (Some(from), Some(to)) = (self.representative(a), self.representative(b)) else {
            return false;
        };
        let (rows, cols) = self.pair_window(a, b);
        if cols.len() > 64 {
            return w.shortest(plannable, rows, cols, from, to).is_some();
        }
        w.linked(plannable, rows, cols, from, to)
    }
}

/// The cells of the runs of `open` that hold a cell of `seed` (a subset of
/// `open`), a row of a window as bits: adding a seed's bit to its run
/// carries through the run's bits above it (the bits that flip), and the
/// same with the bits reversed fills the run below it.
fn fill_runs(seed: u64, open: u64) -> u64 {
    let up = |s: u64, o: u64| ((o.wrapping_add(s) ^ o) | s) & o;
    up(seed, open) | up(seed.reverse_bits(), open.reverse_bits()).reverse_bits()
}

/// Reusable BFS scratch over a small rectangular window.
#[derive(Default)]
struct Window {
    parent: Vec<u32>,
    queue: VecDeque<u32>,
    /// Per row of a window of at most 64 columns: its plannable cells and
    /// those reached, as bits.
    open: Vec<u64>,
    reached: Vec<u64>,
}

impl Window {
    const NONE: u32 = u32::MAX;

    /// Whether a 4-connected path of `plannable` cells inside the window
    /// joins `from` to `to` (both plannable, in the window of at most 64
    /// columns): the cells reached, row by row as bits, grown over whole
    /// runs of a row and into the rows above and below, sweeping down and
    /// up until nothing grows.
    fn linked(
        &mut self,
        plannable: &Grid<bool>,
        rows: Range<usize>,
        cols: Range<usize>,
        from: Cell,
        to: Cell,
    ) -> bool {
        debug_assert!(cols.len() <= 64);
        self.open.clear();
        self.open.extend(rows.clone().map(|r| {
            plannable.row(r)[cols.clone()]
                .iter()
                .enumerate()
                .fold(0u64, |m, (i, &p)| m | (u64::from(p) << i))
        }));
        let h = rows.len();
        self.reached.clear();
        self.reached.resize(h, 0);
        let bit = |c: Cell| 1u64 << (c.col - cols.start);
        let (r0, r1) = (from.row - rows.start, to.row - rows.start);
        self.reached[r0] = fill_runs(bit(from) & self.open[r0], self.open[r0]);
        let (open, reached) = (&self.open, &mut self.reached);
        // Grows row `r` from its neighbours; whether it grew.
        let grow = |reached: &mut [u64], r: usize| {
            let mut seed = reached[r];
            if r > 0 {
                seed |= reached[r - 1];
            }
            if r + 1 < h {
                seed |= reached[r + 1];
            }
            let new = fill_runs(seed & open[r], open[r]);
            let grew = new != reached[r];
            reached[r] = new;
            grew
        };
        loop {
            let mut grew = false;
            for r in (0..h).chain((0..h).rev()) {
                grew |= grow(reached, r);
            }
            if reached[r1] & bit(to) != 0 {
                return true;
            }
            if !grew {
                return false;
            }
        }
    }

    fn shortest(
        &mut self,
        plannable: &Grid<bool>,
        rows: Range<usize>,
        cols: Range<usize>,
        from: Cell,
        to: Cell,
    ) -> Option<Vec<Cell>> {
        let (h, w) = (rows.len(), cols.len());
        let local = |c: Cell| ((c.row - rows.start) * w + (c.col - cols.start)) as u32;
        let global = |i: u32| Cell::new(rows.start + i as usize / w, cols.start + i as usize % w);
        self.parent.clear();
        self.parent.resize(w * h, Self::NONE);
        self.queue.clear();
        let (s, t) = (local(from), local(to));
        self.parent[s as usize] = s;
        self.queue.push_back(s);
        while let Some(i) = self.queue.pop_front() {
            if i == t {
                break;
            }
            let c = global(i);
            for d in Dir4::ALL {
                let Some(n) = plannable.step(c, d) else {
                    continue;
                };
                if !rows.contains(&n.row) || !cols.contains(&n.col) || !plannable[n] {
                    continue;
                }
                let j = local(n);
                if self.parent[j as usize] == Self::NONE {
                    self.parent[j as usize] = i;
                    self.queue.push_back(j);
                }
            }
        }
        if self.parent[t as usize] == Self::NONE {
            return None;
        }
        let mut path = vec![to];
        let mut i = t;
        while i != s {
            i = self.parent[i as usize];
            path.push(global(i));
        }
        path.reverse();
        Some(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::parse_ascii;

    #[test]
    fn representatives_and_connections() {
        let (m, _) = parse_ascii(
            "
            ...#..
            ...#..
            ......
            ......",
        )
        .unwrap();
        let free = m.free_mask();
        let g = CoarseGrid::new(&free, 3);
        assert_eq!((g.width(), g.height()), (2, 2));
        // Block (0,0): centre (1,1).
        assert_eq!(g.representative(Cell::new(0, 0)), Some(Cell::new(1, 1)));
        // Block (0,1) spans cols 3..6 with col 3 blocked in rows 0..2: centre (1,4).
        assert_eq!(g.representative(Cell::new(0, 1)), Some(Cell::new(1, 4)));
        // Clipped bottom blocks: nominal centre row 4 is outside, nearest row 3.
        assert_eq!(g.representative(Cell::new(1, 0)), Some(Cell::new(3, 1)));
        // The wall in column 3 separates the top blocks inside their window only
        // down to row 1; row 2 is open, so they connect around it.
        assert!(g.can_move(Cell::new(0, 0), Dir4::East));
        let p = g.connect(&free, Cell::new(0, 0), Cell::new(0, 1)).unwrap();
        assert_eq!(p.first(), Some(&Cell::new(1, 1)));
        assert_eq!(p.last(), Some(&Cell::new(1, 4)));
        assert_eq!(p.len(), 6);
        assert!(
            p.windows(2)
                .all(|w| w[0].manhattan(w[1]) == 1 && free[w[1]])
        );
    }

    #[test]
    fn walls_inside_the_window_disconnect() {
        let (m, _) = parse_ascii(
            "
            ..#..
            ..#..",
        )
        .unwrap();
        let g = CoarseGrid::new(&m.free_mask(), 2);
        assert!(!g.can_move(Cell::new(0, 0), Dir4::East));
        assert!(g.representative(Cell::new(0, 1)).is_some());
        // Unit blocks are the fine grid itself.
        let g = CoarseGrid::new(&m.free_mask(), 1);
        assert_eq!(
            g.moves()[Cell::new(0, 0)],
            Dir4::East.bit() | Dir4::South.bit()
        );
    }

    #[test]
    fn runs_fill_from_their_seeds() {
        // Runs 0-2, 4-5, 7-9 and 63; seeds in the first, at the end of the
        // last two.
        let open = 0b11_1011_0111 | 1 << 63;
        assert_eq!(fill_runs(0b10, open), 0b111);
        assert_eq!(fill_runs(1 << 9 | 1 << 63, open), 0b11_1000_0000 | 1 << 63);
        assert_eq!(fill_runs(0, open), 0);
        assert_eq!(fill_runs(0b101, open), 0b111);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// Each block's representative is its plannable cell nearest the
        /// block's nominal centre (ties: row-major first), found by a scan
        /// of the block; clipped blocks at the edges included.
        #[test]
        fn representatives_are_the_nearest(seed in 0u64..1000, density in 0.0f64..0.9, block in 1usize..9) {
            let free = crate::random::random_density(37, 23, density, seed).free_mask();
            let g = CoarseGrid::new(&free, block);
            for b in g.representatives().cells() {
                let (rows, cols) = g.block_cells(b);
                let (cr, cc) = (2 * b.row * block + block - 1, 2 * b.col * block + block - 1);
                let mut best: Option<(usize, Cell)> = None;
                for r in rows {
                    for c in cols.clone() {
                        let d = (2 * r).abs_diff(cr).pow(2) + (2 * c).abs_diff(cc).pow(2);
                        if free[Cell::new(r, c)] && best.is_none_or(|(bd, _)| d < bd) {
                            best = Some((d, Cell::new(r, c)));
                        }
                    }
                }
                proptest::prop_assert_eq!(g.representative(b), best.map(|(_, c)| c), "{:?}", b);
            }
        }

        /// Row masks find a link exactly where the window search finds a
        /// path, windows of up to 64 columns and wider (the search itself).
        #[test]
        fn masks_link_as_the_search_does(seed in 0u64..1000, density in 0.0f64..0.6, block in 1usize..40) {
            let free = crate::random::random_density(90, 70, density, seed).free_mask();
            let g = CoarseGrid::new(&free, block);
            let mut w = Window::default();
            for b in g.representatives().cells() {
                for dir in [Dir4::East, Dir4::South] {
                    let Some(n) = g.representatives().step(b, dir) else {
                        continue;
                    };
                    let path = g.window_path(&free, b, n, &mut w).is_some();
                    proptest::prop_assert_eq!(g.window_linked(&free, b, n, &mut w), path);
                }
            }
        }

        /// Every move is the window search's answer (blocks whose cells are
        /// all plannable are linked without one).
        #[test]
        fn moves_are_the_window_paths(seed in 0u64..1000, density in 0.0f64..0.4, block in 1usize..5) {
            let free = crate::random::random_density(19, 14, density, seed).free_mask();
            let g = CoarseGrid::new(&free, block);
            for b in g.representatives().cells() {
                for dir in [Dir4::East, Dir4::South] {
                    let Some(n) = g.representatives().step(b, dir) else {
                        continue;
                    };
                    let linked = g.connect(&free, b, n).is_some();
                    proptest::prop_assert_eq!(g.can_move(b, dir), linked, "{:?} {:?}", b, dir);
                    proptest::prop_assert_eq!(g.can_move(n, dir.opposite()), linked);
                }
            }
        }
    }
}
