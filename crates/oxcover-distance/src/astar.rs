//! A* (Hart, Nilsson & Raphael 1968) between two cells on 4-connected unit
//! moves, with the Manhattan distance as heuristic.
//!
//! The heuristic is consistent, so the first time a cell leaves the queue its
//! distance is exact and the route is a shortest one (same length as the Lee
//! wavefront's). Every move changes `f = g + h` by 0 or 2, so the open set is
//! a bucket queue indexed by `(f − f₀)/2`; inside a bucket the newest cell is
//! taken first, which runs straight at the goal across open floor. Where a
//! Lee wavefront touches a disc of radius `d` around the start, A* touches
//! little more than the cells near the route on open floors.
//!
//! [`AStar`] is a reusable workspace like [`crate::Wavefront`]: the grid is
//! padded with a blocked border, and a query resets only the cells it touched.

use oxcover_grid::{Cell, Dir4, Grid};

const BLOCKED: u32 = u32::MAX;
const UNSEEN: u32 = u32::MAX - 1;

/// A reusable A* workspace over a fixed grid.
#[derive(Clone, Debug)]
pub struct AStar {
    width: usize,
    stride: usize,
    /// Best known `g` per padded cell (`UNSEEN`, or `BLOCKED` off the grid).
    g: Vec<u32>,
    /// Direction of the move that reached the cell.
    came: Vec<u8>,
    closed: Vec<bool>,
    touched: Vec<u32>,
    buckets: Vec<Vec<u32>>,
    offsets: [isize; 4],
}

impl AStar {
    /// A workspace over the `true` cells of `passable`.
    #[must_use]
    pub fn new(passable: &Grid<bool>) -> Self {
        let (w, h) = (passable.width(), passable.height());
        let stride = w + 2;
        let mut g = vec![BLOCKED; stride * (h + 2)];
        for c in passable.true_cells() {
            g[(c.row + 1) * stride + c.col + 1] = UNSEEN;
        }
        let s = stride as isize;
        Self {
            width: w,
            stride,
            came: vec![0; g.len()],
            closed: vec![false; g.len()],
            g,
            touched: Vec::new(),
            buckets: Vec::new(),
            // In `Dir4` order: north, east, south, west.
            offsets: [-s, 1, s, -1],
        }
    }

    /// Cells labelled by the last query.
    #[must_use]
    pub fn touched(&self) -> usize {
        self.touched.len()
    }

    fn pad(&self, c: Cell) -> usize {
        (c.row + 1) * self.stride + c.col + 1
    }

    fn unpad(&self, i: usize) -> Cell {
        Cell::new(i / self.stride - 1, i % self.stride - 1)
    }

    fn reset(&mut self) {
        for &i in &self.touched {
            self.g[i as usize] = UNSEEN;
            self.closed[i as usize] = false;
        }
        self.touched.clear();
        for b in &mut self.buckets {
            b.clear();
        }
    }

    /// A shortest 4-connected route `from ..= to` over passable cells, or
    /// `None` when either end is not passable or `to` cannot be reached.
    pub fn route(&mut self, from: Cell, to: Cell) -> Option<Vec<Cell>> {
        self.reset();
        if from.col >= self.width || to.col >= self.width {
            return None;
        }
        let (a, b) = (self.pad(from), self.pad(to));
        if self.g.get(a) != Some(&UNSEEN) || self.g.get(b) != Some(&UNSEEN) {
            return None;
        }
        let (bx, by) = ((b % self.stride) as i64, (b / self.stride) as i64);
        let stride = self.stride;
        let h = |i: usize| {
            ((i % stride) as i64 - bx).unsigned_abs() + ((i / stride) as i64 - by).unsigned_abs()
        };
        let f0 = h(a);
        self.g[a] = 0;
        self.touched.push(a as u32);
        self.push(0, a);
        let mut k = 0;
        while k < self.buckets.len() {
            let Some(i) = self.buckets[k].pop() else {
                k += 1;
                continue;
            };
            let i = i as usize;
            if self.closed[i] {
                continue;
            }
            self.closed[i] = true;
            if i == b {
                return Some(self.retrace(a, b));
            }
            let gi = self.g[i] + 1;
            for d in Dir4::ALL {
                let n = i.wrapping_add_signed(self.offsets[d.index()]);
                let gn = self.g[n];
                if gn == BLOCKED || (gn != UNSEEN && gn <= gi) {
                    continue;
                }
                if gn == UNSEEN {
                    self.touched.push(n as u32);
                }
                self.g[n] = gi;
                self.came[n] = d.index() as u8;
                let f = u64::from(gi) + h(n);
                self.push(((f - f0) / 2) as usize, n);
            }
        }
        None
    }

    fn push(&mut self, bucket: usize, i: usize) {
        if self.buckets.len() <= bucket {
            self.buckets.resize_with(bucket + 1, Vec::new);
        }
        self.buckets[bucket].push(i as u32);
    }

    fn retrace(&self, a: usize, b: usize) -> Vec<Cell> {
        let mut path = vec![self.unpad(b)];
        let mut i = b;
        while i != a {
            let back = Dir4::from_index(usize::from(self.came[i])).opposite();
            i = i.wrapping_add_signed(self.offsets[back.index()]);
            path.push(self.unpad(i));
        }
        path.reverse();
        path
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
    fn goes_around_a_wall() {
        let (m, _) = parse_ascii(
            "
            .....
            .###.
            .....
            ",
        )
        .unwrap();
        let mut a = AStar::new(&m.free_mask());
        let r = a.route(Cell::new(0, 2), Cell::new(2, 2)).unwrap();
        assert_eq!(r.len(), 7);
        assert_eq!((r[0], r[6]), (Cell::new(0, 2), Cell::new(2, 2)));
        assert_eq!(a.route(Cell::new(0, 0), Cell::new(1, 1)), None);
        assert_eq!(a.route(Cell::new(0, 0), Cell::new(0, 0)).unwrap().len(), 1);
        assert_eq!(a.route(Cell::new(0, 0), Cell::new(9, 9)), None);
    }

    proptest! {
        #[test]
        fn shortest_like_bfs(w in 1usize..40, h in 1usize..40, density in 0.0f64..0.45, seed in any::<u64>(), pick in any::<u64>()) {
            let free = random_density(w, h, density, seed).free_mask();
            let cells: Vec<Cell> = free.true_cells().collect();
            if cells.is_empty() { return Ok(()); }
            let mut astar = AStar::new(&free);
            // Several queries on one workspace: resets must be complete.
            for q in 0..4u64 {
                let (a, b) = (cells[((pick >> q) % cells.len() as u64) as usize],
                              cells[((pick >> (2 * q + 7)) % cells.len() as u64) as usize]);
                let want = bfs_distances(&free, a)[b];
                let got = astar.route(a, b);
                prop_assert_eq!(got.as_ref().map(|r| r.len() as u32 - 1), want);
                if let Some(r) = got {
                    prop_assert_eq!((r[0], r[r.len() - 1]), (a, b));
                    prop_assert!(r.iter().all(|&c| free[c]));
                    prop_assert!(r.windows(2).all(|s| s[0].manhattan(s[1]) == 1));
                }
            }
        }
    }
}
