//! The grid container, cell addresses and neighbourhoods.
//!
//! A [`Grid<T>`] stores one value per cell in row-major order. Cells are
//! addressed by `(row, col)` with row 0 at the TOP, as in the image a map was
//! read from; [`crate::MapFrame`] converts to metres. Moves are 4-connected
//! ([`Dir4`]) unless a caller asks for the 8-neighbourhood ([`Dir8`]).

use std::ops::{Index, IndexMut};

/// Rows per task of [`Grid::par_from_fn`] at least.
const PAR_ROWS: usize = 16;

/// A cell address: `row` counts down from the top row, `col` to the right.
///
/// The derived ordering is row-major, the order every tie-break in the
/// workspace falls back to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cell {
    /// Row, 0 = top.
    pub row: usize,
    /// Column, 0 = left.
    pub col: usize,
}

impl Cell {
    /// Builds a cell from `(row, col)`.
    #[must_use]
    pub const fn new(row: usize, col: usize) -> Self {
        Self { row, col }
    }

    /// Manhattan (l1) distance between two cells.
    #[must_use]
    pub fn manhattan(self, other: Cell) -> usize {
        self.row.abs_diff(other.row) + self.col.abs_diff(other.col)
    }

    /// The direction of a unit 4-connected move from `self` to `other`, if it is one.
    #[must_use]
    pub fn dir_to(self, other: Cell) -> Option<Dir4> {
        Dir4::ALL.into_iter().find(|d| {
            let (dr, dc) = d.offset();
            self.row.checked_add_signed(dr) == Some(other.row)
                && self.col.checked_add_signed(dc) == Some(other.col)
        })
    }
}

impl From<(usize, usize)> for Cell {
    fn from((row, col): (usize, usize)) -> Self {
        Self { row, col }
    }
}

/// The four axis directions. Order (N, E, S, W) is the fixed tie-break order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Dir4 {
    /// Up: row - 1 (towards +y in the map frame).
    North = 0,
    /// Right: col + 1 (towards +x).
    East = 1,
    /// Down: row + 1 (towards -y).
    South = 2,
    /// Left: col - 1 (towards -x).
    West = 3,
}

impl Dir4 {
    /// All four directions in tie-break order.
    pub const ALL: [Dir4; 4] = [Dir4::North, Dir4::East, Dir4::South, Dir4::West];

    /// `(drow, dcol)` of a unit move.
    #[must_use]
    pub const fn offset(self) -> (isize, isize) {
        match self {
            Dir4::North => (-1, 0),
            Dir4::East => (0, 1),
            Dir4::South => (1, 0),
            Dir4::West => (0, -1),
        }
    }

    /// The opposite direction.
    #[must_use]
    pub const fn opposite(self) -> Dir4 {
        match self {
            Dir4::North => Dir4::South,
            Dir4::East => Dir4::West,
            Dir4::South => Dir4::North,
            Dir4::West => Dir4::East,
        }
    }

    /// Index 0..4 in [`Dir4::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Bit `1 << index`, for move masks.
    #[must_use]
    pub const fn bit(self) -> u8 {
        1 << (self as u8)
    }

    /// The direction with the given index (taken modulo 4).
    #[must_use]
    pub const fn from_index(i: usize) -> Dir4 {
        Dir4::ALL[i % 4]
    }
}

/// The eight king-move directions, clockwise from north.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dir8 {
    /// row - 1
    North,
    /// row - 1, col + 1
    NorthEast,
    /// col + 1
    East,
    /// row + 1, col + 1
    SouthEast,
    /// row + 1
    South,
    /// row + 1, col - 1
    SouthWest,
    /// col - 1
    West,
    /// row - 1, col - 1
    NorthWest,
}

impl Dir8 {
    /// All eight directions, clockwise from north.
    pub const ALL: [Dir8; 8] = [
        Dir8::North,
        Dir8::NorthEast,
        Dir8::East,
        Dir8::SouthEast,
        Dir8::South,
        Dir8::SouthWest,
        Dir8::West,
        Dir8::NorthWest,
    ];

    /// `(drow, dcol)` of the move.
    #[must_use]
    pub const fn offset(self) -> (isize, isize) {
        match self {
            Dir8::North => (-1, 0),
            Dir8::NorthEast => (-1, 1),
            Dir8::East => (0, 1),
            Dir8::SouthEast => (1, 1),
            Dir8::South => (1, 0),
            Dir8::SouthWest => (1, -1),
            Dir8::West => (0, -1),
            Dir8::NorthWest => (-1, -1),
        }
    }

    /// Whether the move is diagonal.
    #[must_use]
    pub const fn is_diagonal(self) -> bool {
        let (dr, dc) = self.offset();
        dr != 0 && dc != 0
    }
}

/// Rows `r0..r1` and columns `c0..c1` of a grid, as `(r0, r1, c0, c1)`.
pub type Window = (usize, usize, usize, usize);

/// A dense `width × height` grid of `T`, row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Grid<T> {
    width: usize,
    height: usize,
    data: Vec<T>,
}

impl<T: Clone> Grid<T> {
    /// A grid with every cell set to `fill`.
    #[must_use]
    pub fn new(width: usize, height: usize, fill: T) -> Self {
        Self {
            width,
            height,
            data: vec![fill; width * height],
        }
    }

    /// Sets every cell to `value`.
    pub fn fill(&mut self, value: T) {
        self.data.fill(value);
    }
}

impl<T> Grid<T> {
    /// Wraps row-major data; `None` when `data.len() != width * height`.
    #[must_use]
    pub fn from_vec(width: usize, height: usize, data: Vec<T>) -> Option<Self> {
        (width.checked_mul(height) == Some(data.len())).then_some(Self {
            width,
            height,
            data,
        })
    }

    /// [`Grid::from_fn`] with the rows in parallel (rayon), for grids
    /// large enough that a pass over them counts: the same grid whatever
    /// the thread count.
    #[must_use]
    pub fn par_from_fn(width: usize, height: usize, f: impl Fn(Cell) -> T + Sync) -> Self
    where
        T: Send + Clone + Default,
    {
        use rayon::prelude::*;
        let mut data = vec![T::default(); width * height];
        if width > 0 {
            data.par_chunks_mut(width * PAR_ROWS)
                .enumerate()
                .for_each(|(block, rows)| {
                    for (i, row) in rows.chunks_mut(width).enumerate() {
                        let r = block * PAR_ROWS + i;
                        for (col, v) in row.iter_mut().enumerate() {
                            *v = f(Cell::new(r, col));
                        }
                    }
                });
        }
        Self {
            width,
            height,
            data,
        }
    }

    /// A grid whose cell values are `f(cell)`.
    #[must_use]
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(Cell) -> T) -> Self {
        let mut data = Vec::with_capacity(width * height);
        for row in 0..height {
            for col in 0..width {
                data.push(f(Cell::new(row, col)));
            }
        }
        Self {
            width,
            height,
            data,
        }
    }

    /// Number of columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Number of cells.
    #[must_use]
    pub fn len(&self) -> usize {
        self.data.len()
    }

    /// Whether the grid has no cell.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Whether `cell` lies inside the grid.
    #[must_use]
    pub fn contains(&self, cell: Cell) -> bool {
        cell.row < self.height && cell.col < self.width
    }

    /// Row-major index of `cell` (which must be inside).
    #[must_use]
    pub fn index_of(&self, cell: Cell) -> usize {
        debug_assert!(self.contains(cell));
        cell.row * self.width + cell.col
    }

    /// The cell at row-major index `index`.
    #[must_use]
    pub fn cell_of(&self, index: usize) -> Cell {
        Cell::new(index / self.width, index % self.width)
    }

    /// The value at `cell`, or `None` outside the grid.
    #[must_use]
    pub fn get(&self, cell: Cell) -> Option<&T> {
        self.contains(cell)
            .then(|| &self.data[cell.row * self.width + cell.col])
    }

    /// Mutable access to the value at `cell`, or `None` outside the grid.
    pub fn get_mut(&mut self, cell: Cell) -> Option<&mut T> {
        if self.contains(cell) {
            Some(&mut self.data[cell.row * self.width + cell.col])
        } else {
            None
        }
    }

    /// The cell one step from `cell` in direction `dir`, if inside the grid.
    #[must_use]
    pub fn step(&self, cell: Cell, dir: Dir4) -> Option<Cell> {
        self.offset(cell, dir.offset())
    }

    /// The cell at `cell + (drow, dcol)`, if inside the grid.
    #[must_use]
    pub fn offset(&self, cell: Cell, (dr, dc): (isize, isize)) -> Option<Cell> {
        let row = cell.row.checked_add_signed(dr)?;
        let col = cell.col.checked_add_signed(dc)?;
        (row < self.height && col < self.width).then_some(Cell::new(row, col))
    }

    /// The in-grid 4-neighbours of `cell`, in [`Dir4::ALL`] order.
    pub fn neighbours4(&self, cell: Cell) -> impl Iterator<Item = (Dir4, Cell)> + '_ {
        Dir4::ALL
            .into_iter()
            .filter_map(move |d| self.step(cell, d).map(|c| (d, c)))
    }

    /// The in-grid 8-neighbours of `cell`, clockwise from north.
    pub fn neighbours8(&self, cell: Cell) -> impl Iterator<Item = (Dir8, Cell)> + '_ {
        Dir8::ALL
            .into_iter()
            .filter_map(move |d| self.offset(cell, d.offset()).map(|c| (d, c)))
    }

    /// All cells in row-major order.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + use<T> {
        let (w, h) = (self.width, self.height);
        (0..h).flat_map(move |r| (0..w).map(move |c| Cell::new(r, c)))
    }

    /// `(cell, value)` pairs in row-major order.
    pub fn iter(&self) -> impl Iterator<Item = (Cell, &T)> + '_ {
        let w = self.width;
        self.data
            .iter()
            .enumerate()
            .map(move |(i, v)| (Cell::new(i / w, i % w), v))
    }

    /// The values in row-major order.
    #[must_use]
    pub fn as_slice(&self) -> &[T] {
        &self.data
    }

    /// Mutable values in row-major order.
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.data
    }

    /// The values of one row.
    #[must_use]
    pub fn row(&self, row: usize) -> &[T] {
        &self.data[row * self.width..(row + 1) * self.width]
    }

    /// Unwraps the row-major data.
    #[must_use]
    pub fn into_vec(self) -> Vec<T> {
        self.data
    }

    /// A grid of the same shape with `f` applied to every value.
    #[must_use]
    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> Grid<U> {
        Grid {
            width: self.width,
            height: self.height,
            data: self.data.iter().map(f).collect(),
        }
    }

    /// The smallest window holding every cell `inside` accepts: rows
    /// `r0..r1` and columns `c0..c1` as `(r0, r1, c0, c1)`, `None` where it
    /// accepts none. (Rows in parallel, each read 64 cells at a time to
    /// its first and last accepted cell.)
    #[must_use]
    pub fn bounding_box(&self, inside: impl Fn(&T) -> bool + Sync) -> Option<Window>
    where
        T: Sync,
    {
        use rayon::prelude::*;
        let (w, h) = (self.width, self.height);
        if w == 0 || h == 0 {
            return None;
        }
        let any = |run: &[T]| run.iter().fold(false, |x, v| x | inside(v));
        let (r0, r1, c0, c1) = self
            .data
            .par_chunks(w)
            .enumerate()
            .filter_map(|(r, row)| {
                let lo = row.chunks(64).position(any)? * 64;
                let hi = (0..=(w - 1) / 64 * 64)
                    .rev()
                    .step_by(64)
                    .find(|&i| any(&row[i..(i + 64).min(w)]))?;
                let a = lo + row[lo..].iter().position(&inside)?;
                let b = hi + row[hi..(hi + 64).min(w)].iter().rposition(&inside)?;
                Some((r, r + 1, a, b + 1))
            })
            .reduce(
                || (h, 0, w, 0),
                |x, y| (x.0.min(y.0), x.1.max(y.1), x.2.min(y.2), x.3.max(y.3)),
            );
        (r0 < r1).then_some((r0, r1, c0, c1))
    }

    /// The window `(r0, r1, c0, c1)` widened by `k` cells on every side,
    /// cut to this grid (saturating: a huge `k` takes the whole grid).
    #[must_use]
    pub fn widen(&self, (r0, r1, c0, c1): Window, k: usize) -> Window {
        (
            r0.saturating_sub(k),
            r1.saturating_add(k).min(self.height),
            c0.saturating_sub(k),
            c1.saturating_add(k).min(self.width),
        )
    }

    /// The window `(r0, r1, c0, c1)` (rows `r0..r1`, columns `c0..c1`, as
    /// [`Grid::bounding_box`] gives it) as a grid of its own.
    ///
    /// # Panics
    /// If the window reaches past the grid.
    #[must_use]
    pub fn crop(&self, (r0, r1, c0, c1): Window) -> Self
    where
        T: Clone,
    {
        assert!(
            r0 <= r1 && r1 <= self.height && c0 <= c1 && c1 <= self.width,
            "crop window outside the grid"
        );
        let data = (r0..r1)
            .flat_map(|r| self.row(r)[c0..c1].iter().cloned())
            .collect();
        Self {
            width: c1 - c0,
            height: r1 - r0,
            data,
        }
    }

    /// Writes `part` into this grid with its first cell at `at` (the
    /// inverse of [`Grid::crop`]).
    ///
    /// # Panics
    /// If `part` placed at `at` reaches past the grid.
    pub fn paste(&mut self, at: Cell, part: &Self)
    where
        T: Clone,
    {
        assert!(
            at.row + part.height <= self.height && at.col + part.width <= self.width,
            "pasted part outside the grid"
        );
        if part.width == 0 {
            return;
        }
        for (r, row) in part.data.chunks(part.width).enumerate() {
            let i = (at.row + r) * self.width + at.col;
            self.data[i..i + part.width].clone_from_slice(row);
        }
    }

    /// A grid of the same shape with `f` applied to every value and the
    /// value of the same cell in `other`.
    ///
    /// # Panics
    /// If `other` is not the same size.
    #[must_use]
    pub fn zip_map<U, V>(&self, other: &Grid<U>, mut f: impl FnMut(&T, &U) -> V) -> Grid<V> {
        assert_eq!(
            (self.width, self.height),
            (other.width, other.height),
            "zip_map needs grids of one size"
        );
        Grid {
            width: self.width,
            height: self.height,
            data: self
                .data
                .iter()
                .zip(&other.data)
                .map(|(a, b)| f(a, b))
                .collect(),
        }
    }

    /// Number of cells whose value satisfies `pred`.
    #[must_use]
    pub fn count(&self, mut pred: impl FnMut(&T) -> bool) -> usize {
        self.data.iter().filter(|v| pred(v)).count()
    }
}

impl Grid<bool> {
    /// Number of `true` cells.
    #[must_use]
    pub fn count_true(&self) -> usize {
        // Counted in bytes, 255 cells at a time: a sum that cannot wrap and
        // that the compiler vectorises (plans count map-sized grids often).
        let mut runs = self.data.chunks_exact(255);
        let whole: usize = (&mut runs)
            .map(|run| usize::from(run.iter().fold(0u8, |n, &b| n + u8::from(b))))
            .sum();
        whole + runs.remainder().iter().filter(|&&b| b).count()
    }

    /// Number of cells `true` in both grids (cell for cell, by index: grids
    /// of one size), counted as [`Self::count_true`] counts.
    #[must_use]
    pub fn count_both(&self, other: &Self) -> usize {
        let (a, b) = (self.data.as_slice(), other.data.as_slice());
        let n = a.len().min(b.len());
        let (a, b) = (&a[..n], &b[..n]);
        let both =
            |a: &[bool], b: &[bool]| a.iter().zip(b).fold(0u8, |n, (&x, &y)| n + u8::from(x & y));
        let runs = n / 255 * 255;
        let whole: usize = a[..runs]
            .chunks_exact(255)
            .zip(b[..runs].chunks_exact(255))
            .map(|(x, y)| usize::from(both(x, y)))
            .sum();
        whole + usize::from(both(&a[runs..], &b[runs..]))
    }

    /// Cells that are `true`, row-major.
    pub fn true_cells(&self) -> impl Iterator<Item = Cell> + '_ {
        let w = self.width;
        self.data
            .iter()
            .enumerate()
            .filter(|(_, b)| **b)
            .map(move |(i, _)| Cell::new(i / w, i % w))
    }

    /// Whether `cell` is inside and `true`.
    #[must_use]
    pub fn is_set(&self, cell: Cell) -> bool {
        self.get(cell).copied().unwrap_or(false)
    }
}

impl<T> Index<Cell> for Grid<T> {
    type Output = T;
    fn index(&self, cell: Cell) -> &T {
        assert!(self.contains(cell), "cell {cell:?} outside grid");
        &self.data[cell.row * self.width + cell.col]
    }
}

impl<T> IndexMut<Cell> for Grid<T> {
    fn index_mut(&mut self, cell: Cell) -> &mut T {
        assert!(self.contains(cell), "cell {cell:?} outside grid");
        &mut self.data[cell.row * self.width + cell.col]
    }
}

/// The offsets `(dr, dc)` of the square of `k` cells round a cell, nearest
/// first; of equally near ones, first the one a row-major scan of the
/// square meets first. A search that takes the first offset it accepts
/// then finds the nearest cell, ties broken as a scan would break them.
#[must_use]
pub fn nearest_first(k: usize) -> Vec<(isize, isize)> {
    let k = k as isize;
    let mut offsets: Vec<(isize, isize)> = (-k..=k)
        .flat_map(|dr| (-k..=k).map(move |dc| (dr, dc)))
        .collect();
    offsets.sort_by_key(|&(dr, dc)| (dr * dr + dc * dc, dr, dc));
    offsets
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_true_and_count_both_count_every_true_cell() {
        // Sizes round the 255-cell runs, all true (a run's byte sum at its
        // largest) and scattered.
        for n in [0usize, 1, 254, 255, 256, 510, 511, 1000] {
            let all = Grid::new(n, 1, true);
            assert_eq!(all.count_true(), n);
            let some = Grid::from_fn(n, 3, |c: Cell| (c.col * 7 + c.row) % 3 == 0);
            let plain = some.as_slice().iter().filter(|&&b| b).count();
            assert_eq!(some.count_true(), plain, "{n}");
            assert_eq!(all.count_both(&all), n);
            let other = Grid::from_fn(n, 3, |c: Cell| (c.col + 2 * c.row) % 5 < 2);
            let plain = some
                .as_slice()
                .iter()
                .zip(other.as_slice())
                .filter(|&(&a, &b)| a && b)
                .count();
            assert_eq!(some.count_both(&other), plain, "{n}");
        }
    }

    #[test]
    fn bounding_box_is_the_accepted_cells_extent() {
        assert_eq!(Grid::new(0, 0, true).bounding_box(|&v| v), None);
        assert_eq!(Grid::new(150, 3, false).bounding_box(|&v| v), None);
        // Rows wider than 64 cells, the accepted cells anywhere in them.
        for seed in 0..20u64 {
            let mut s = seed;
            let g = Grid::from_fn(70 + seed as usize * 13, 9, |_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 33) % 97 == 0
            });
            let cells: Vec<Cell> = g.true_cells().collect();
            let brute = (!cells.is_empty()).then(|| {
                (
                    cells.iter().map(|c| c.row).min().unwrap_or(0),
                    cells.iter().map(|c| c.row + 1).max().unwrap_or(0),
                    cells.iter().map(|c| c.col).min().unwrap_or(0),
                    cells.iter().map(|c| c.col + 1).max().unwrap_or(0),
                )
            });
            assert_eq!(g.bounding_box(|&v| v), brute, "seed {seed}");
        }
    }

    #[test]
    fn offsets_come_nearest_first_and_windows_widen_within_the_grid() {
        let o = nearest_first(2);
        assert_eq!(o.len(), 25);
        assert_eq!(&o[..5], &[(0, 0), (-1, 0), (0, -1), (0, 1), (1, 0)]);
        assert!(o.windows(2).all(|w| {
            let d = |(r, c): (isize, isize)| r * r + c * c;
            (d(w[0]), w[0]) < (d(w[1]), w[1])
        }));
        let g = Grid::new(10, 8, 0u8);
        assert_eq!(g.widen((2, 4, 3, 5), 2), (0, 6, 1, 7));
        assert_eq!(g.widen((2, 4, 3, 5), usize::MAX), (0, 8, 0, 10));
    }

    #[test]
    fn crop_reads_the_window_and_paste_puts_it_back() {
        let g = Grid::from_fn(7, 5, |c| c.row * 10 + c.col);
        let part = g.crop((1, 4, 2, 6));
        assert_eq!((part.width(), part.height()), (4, 3));
        assert_eq!(part.row(0), &[12, 13, 14, 15]);
        assert_eq!(part[Cell::new(2, 3)], 35);
        assert_eq!(g.crop((2, 2, 0, 7)).len(), 0);
        let mut blank = Grid::new(7, 5, 0);
        blank.paste(Cell::new(1, 2), &part);
        for c in g.cells() {
            let inside = (1..4).contains(&c.row) && (2..6).contains(&c.col);
            assert_eq!(blank[c], if inside { g[c] } else { 0 }, "{c:?}");
        }
        blank.paste(Cell::new(5, 7), &Grid::new(0, 0, 1));
    }

    #[test]
    fn par_from_fn_is_from_fn() {
        let f = |c: Cell| c.row * 1000 + c.col;
        for (w, h) in [
            (0, 5),
            (5, 0),
            (1, 1),
            (7, PAR_ROWS - 1),
            (13, 3 * PAR_ROWS + 5),
        ] {
            assert_eq!(
                Grid::par_from_fn(w, h, f),
                Grid::from_fn(w, h, f),
                "{w} × {h}"
            );
        }
    }

    #[test]
    fn neighbours_stay_inside_and_follow_order() {
        let g = Grid::new(3, 2, 0u8);
        let n: Vec<_> = g.neighbours4(Cell::new(0, 0)).collect();
        assert_eq!(
            n,
            vec![
                (Dir4::East, Cell::new(0, 1)),
                (Dir4::South, Cell::new(1, 0))
            ]
        );
        assert_eq!(g.neighbours8(Cell::new(1, 1)).count(), 5);
        assert_eq!(g.neighbours4(Cell::new(1, 1)).count(), 3);
    }

    #[test]
    fn index_round_trip_and_row_major_order() {
        let g = Grid::from_fn(4, 3, |c| c.row * 10 + c.col);
        for (i, c) in g.cells().enumerate() {
            assert_eq!(g.index_of(c), i);
            assert_eq!(g.cell_of(i), c);
            assert_eq!(g[c], c.row * 10 + c.col);
        }
        assert_eq!(g.row(2), &[20, 21, 22, 23]);
        assert!(Grid::from_vec(2, 2, vec![1, 2, 3]).is_none());
    }

    #[test]
    fn dir_helpers() {
        for d in Dir4::ALL {
            assert_eq!(d.opposite().opposite(), d);
            assert_eq!(Dir4::from_index(d.index()), d);
            let c = Cell::new(5, 5);
            let (dr, dc) = d.offset();
            let n = Cell::new((5 + dr) as usize, (5 + dc) as usize);
            assert_eq!(c.dir_to(n), Some(d));
        }
        assert_eq!(Cell::new(0, 0).dir_to(Cell::new(1, 1)), None);
        assert_eq!(Dir8::ALL.iter().filter(|d| d.is_diagonal()).count(), 4);
    }
}
