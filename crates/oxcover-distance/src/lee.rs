//! Lee wavefront (Lee 1961): breadth-first distance labels over 4-connected
//! cells, and a retrace that prefers to keep its direction (fewest bends).
//!
//! [`Wavefront`] is a reusable workspace: the passability is baked once into a
//! label array padded with a blocked border (no bounds tests in the inner loop),
//! the queue doubles as the list of cells a query touched, and the next query
//! resets only those cells, so repeated queries neither allocate nor clear the
//! whole map. Cost per query O(cells touched). Optional per-cell move masks
//! ([`Wavefront::with_moves`]) restrict which of the four moves leave a cell,
//! for graphs like [`oxcover_grid::CoarseGrid`] whose neighbours are not all
//! connected.

use oxcover_grid::{Cell, Dir4, Grid};

const BLOCKED: u32 = u32::MAX;
const UNSEEN: u32 = u32::MAX - 1;

/// A reusable Lee wavefront over a fixed grid.
#[derive(Clone, Debug)]
pub struct Wavefront {
    width: usize,
    height: usize,
    stride: usize,
    labels: Vec<u32>,
    moves: Option<Vec<u8>>,
    queue: Vec<u32>,
    offsets: [isize; 4],
}

impl Wavefront {
    /// A workspace over the `true` cells of `passable`.
    #[must_use]
    pub fn new(passable: &Grid<bool>) -> Self {
        let (w, h) = (passable.width(), passable.height());
        let stride = w + 2;
        let mut labels = vec![BLOCKED; stride * (h + 2)];
        let mut open = 0;
        for r in 0..h {
            let row = passable.row(r);
            let base = (r + 1) * stride + 1;
            for (c, &p) in row.iter().enumerate() {
                if p {
                    labels[base + c] = UNSEEN;
                    open += 1;
                }
            }
        }
        let s = stride as isize;
        Self {
            width: w,
            height: h,
            stride,
            labels,
            moves: None,
            queue: Vec::with_capacity(open),
            offsets: [-s, 1, s, -1],
        }
    }

    /// A workspace where a move from a cell in direction `d` is allowed only when
    /// bit [`Dir4::bit`] of `moves[cell]` is set (and the target is passable).
    #[must_use]
    pub fn with_moves(passable: &Grid<bool>, moves: &Grid<u8>) -> Self {
        let mut wf = Self::new(passable);
        let mut padded = vec![0u8; wf.labels.len()];
        for r in 0..wf.height.min(moves.height()) {
            let base = (r + 1) * wf.stride + 1;
            let row = moves.row(r);
            let n = row.len().min(wf.width);
            padded[base..base + n].copy_from_slice(&row[..n]);
        }
        wf.moves = Some(padded);
        wf
    }

    /// Grid width.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    fn pad(&self, c: Cell) -> usize {
        (c.row + 1) * self.stride + c.col + 1
    }

    fn unpad(&self, i: usize) -> Cell {
        Cell::new(i / self.stride - 1, i % self.stride - 1)
    }

    fn inside(&self, c: Cell) -> bool {
        c.row < self.height && c.col < self.width
    }

    /// Whether `cell` is passable.
    #[must_use]
    pub fn is_passable(&self, cell: Cell) -> bool {
        self.inside(cell) && self.labels[self.pad(cell)] != BLOCKED
    }

    /// Changes the passability of a cell. Invalidates the labels of the last query.
    pub fn set_passable(&mut self, cell: Cell, passable: bool) {
        if !self.inside(cell) {
            return;
        }
        self.reset();
        let i = self.pad(cell);
        self.labels[i] = if passable { UNSEEN } else { BLOCKED };
    }

    /// Clears the labels of the last query (O(cells it touched)).
    pub fn reset(&mut self) {
        for &i in &self.queue {
            let l = &mut self.labels[i as usize];
            if *l != BLOCKED {
                *l = UNSEEN;
            }
        }
        self.queue.clear();
    }

    /// Labels every passable cell reachable from `sources` with its distance.
    /// Returns the number of cells labelled.
    pub fn propagate(&mut self, sources: &[Cell]) -> usize {
        self.run(sources, u32::MAX, |_, _| false);
        self.queue.len()
    }

    /// Like [`Wavefront::propagate`] but stops after distance `max_distance`.
    pub fn propagate_within(&mut self, sources: &[Cell], max_distance: u32) -> usize {
        self.run(sources, max_distance, |_, _| false);
        self.queue.len()
    }

    /// Core BFS. After each completed layer of distance `d`, `on_layer(cells, d)`
    /// sees the cells of that layer and may stop the wave by returning `true`.
    /// Distance-0 sources are reported as the first layer.
    pub(crate) fn run(
        &mut self,
        sources: &[Cell],
        max_distance: u32,
        mut on_layer: impl FnMut(&[Cell], u32) -> bool,
    ) {
        self.reset();
        for &s in sources {
            if !self.inside(s) {
                continue;
            }
            let i = self.pad(s);
            if self.labels[i] == UNSEEN {
                self.labels[i] = 0;
                self.queue.push(i as u32);
            }
        }
        let mut layer_cells: Vec<Cell> =
            self.queue.iter().map(|&i| self.unpad(i as usize)).collect();
        if on_layer(&layer_cells, 0) {
            return;
        }
        let mut head = 0;
        let mut d = 0u32;
        while head < self.queue.len() && d < max_distance {
            d += 1;
            let end = self.queue.len();
            if self.moves.is_some() {
                self.expand_masked(head, end, d);
            } else {
                self.expand(head, end, d);
            }
            head = end;
            if head == self.queue.len() {
                break;
            }
            layer_cells.clear();
            layer_cells.extend(self.queue[head..].iter().map(|&i| self.unpad(i as usize)));
            if on_layer(&layer_cells, d) {
                return;
            }
        }
    }

    #[inline]
    fn expand(&mut self, from: usize, to: usize, d: u32) {
        let offsets = self.offsets;
        for qi in from..to {
            let i = self.queue[qi] as usize;
            for off in offsets {
                let n = i.wrapping_add_signed(off);
                if self.labels[n] == UNSEEN {
                    self.labels[n] = d;
                    self.queue.push(n as u32);
                }
            }
        }
    }

    fn expand_masked(&mut self, from: usize, to: usize, d: u32) {
        let offsets = self.offsets;
        let Some(moves) = self.moves.as_ref() else {
            return;
        };
        for qi in from..to {
            let i = self.queue[qi] as usize;
            let m = moves[i];
            for (k, off) in offsets.into_iter().enumerate() {
                if m & (1 << k) == 0 {
                    continue;
                }
                let n = i.wrapping_add_signed(off);
                if self.labels[n] == UNSEEN {
                    self.labels[n] = d;
                    self.queue.push(n as u32);
                }
            }
        }
    }

    /// Number of cells the last query labelled.
    #[must_use]
    pub fn touched(&self) -> usize {
        self.queue.len()
    }

    /// Cells labelled by the last query, in BFS order.
    pub fn touched_cells(&self) -> impl Iterator<Item = Cell> + '_ {
        self.queue.iter().map(|&i| self.unpad(i as usize))
    }

    /// Distance of `cell` from the sources of the last query, if it was reached.
    #[must_use]
    pub fn distance(&self, cell: Cell) -> Option<u32> {
        if !self.inside(cell) {
            return None;
        }
        let l = self.labels[self.pad(cell)];
        (l < UNSEEN).then_some(l)
    }

    /// The labels of the last query as a grid (`None` = not reached or blocked).
    #[must_use]
    pub fn distances(&self) -> Grid<Option<u32>> {
        Grid::from_fn(self.width, self.height, |c| self.distance(c))
    }

    fn can_step(&self, from: usize, dir: Dir4) -> bool {
        self.moves.as_ref().is_none_or(|m| m[from] & dir.bit() != 0)
    }

    /// The shortest path from the nearest source to `target` (both included),
    /// following labels down and keeping the current direction whenever a
    /// shortest path allows it (then N, E, S, W). `None` if not reached.
    #[must_use]
    pub fn retrace(&self, target: Cell) -> Option<Vec<Cell>> {
        let mut l = self.distance(target)?;
        let mut i = self.pad(target);
        let mut path = vec![target];
        // Direction of travel of the forward path, seen from its end.
        let mut dir: Option<Dir4> = None;
        while l > 0 {
            let order = dir.into_iter().chain(Dir4::ALL);
            let mut next = None;
            for d in order {
                // Forward move was `d`, so the previous cell lies opposite.
                let back = d.opposite();
                let n = i.wrapping_add_signed(self.offsets[back.index()]);
                if self.labels[n] == l - 1 && self.can_step(n, d) {
                    next = Some((n, d));
                    break;
                }
            }
            let (n, d) = next?;
            i = n;
            dir = Some(d);
            l -= 1;
            path.push(self.unpad(i));
        }
        path.reverse();
        Some(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bfs_distances;
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::random::random_density;
    use proptest::prelude::*;

    #[test]
    fn retrace_keeps_direction() {
        let (m, _) = parse_ascii(
            "
            .....
            .....
            .....",
        )
        .unwrap();
        let mut wf = Wavefront::new(&m.free_mask());
        wf.propagate(&[Cell::new(0, 0)]);
        let p = wf.retrace(Cell::new(2, 4)).unwrap();
        // One bend: the last move is kept as long as possible going back.
        let bends = p
            .windows(3)
            .filter(|w| w[0].dir_to(w[1]) != w[1].dir_to(w[2]))
            .count();
        assert_eq!(bends, 1);
        assert_eq!(p.len(), 7);
        assert_eq!(p[0], Cell::new(0, 0));
    }

    #[test]
    fn masks_restrict_moves_and_queries_reuse_the_workspace() {
        let free = Grid::new(3, 1, true);
        let mut moves = Grid::new(3, 1, Dir4::East.bit() | Dir4::West.bit());
        moves[Cell::new(0, 1)] = Dir4::West.bit(); // one-way: 1 -> 2 closed
        let mut wf = Wavefront::with_moves(&free, &moves);
        wf.propagate(&[Cell::new(0, 0)]);
        assert_eq!(wf.distance(Cell::new(0, 1)), Some(1));
        assert_eq!(wf.distance(Cell::new(0, 2)), None);
        wf.propagate(&[Cell::new(0, 2)]);
        assert_eq!(wf.distance(Cell::new(0, 0)), Some(2));
        assert_eq!(wf.retrace(Cell::new(0, 0)).unwrap().len(), 3);
        wf.set_passable(Cell::new(0, 1), false);
        wf.propagate(&[Cell::new(0, 2)]);
        assert_eq!(wf.distance(Cell::new(0, 0)), None);
        assert_eq!(wf.touched(), 1);
    }

    proptest! {
        #[test]
        fn equals_reference_bfs(w in 1usize..40, h in 1usize..40, density in 0.0f64..0.5, seed in any::<u64>(), sr in 0usize..40, sc in 0usize..40) {
            let map = random_density(w, h, density, seed);
            let free = map.free_mask();
            let src = Cell::new(sr % h, sc % w);
            let mut wf = Wavefront::new(&free);
            // A previous query must not leak into the next.
            wf.propagate(&[Cell::new(0, 0)]);
            wf.propagate(&[src]);
            let want = bfs_distances(&free, src);
            for c in free.cells() {
                prop_assert_eq!(wf.distance(c), want[c]);
                if let Some(d) = want[c] {
                    let p = wf.retrace(c).unwrap();
                    prop_assert_eq!(p.len(), d as usize + 1);
                    prop_assert_eq!(p[0], src);
                    prop_assert!(p.windows(2).all(|s| s[0].manhattan(s[1]) == 1 && free[s[1]]));
                }
            }
        }
    }
}
