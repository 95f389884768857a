//! Points in square buckets, for nearest-point searches that grow outwards
//! ring by ring of buckets (the `smooth` planner's order of rings and
//! spines, the large open tours of [`crate::tour`]).

use oxcover_grid::Point;

/// A point and its payload.
pub(crate) type Entry<T> = (Point, T);

/// Points with payloads `T` in square buckets of side `size`.
#[derive(Clone, Debug)]
pub(crate) struct Buckets<T> {
    origin: Point,
    size: f64,
    cols: usize,
    rows: usize,
    cells: Vec<Vec<Entry<T>>>,
    /// Buckets that have held an entry (some may be empty again): what a
    /// search far from every live entry scans instead of ring after ring.
    filled: Vec<usize>,
}

impl<T> Buckets<T> {
    /// Buckets of side `size` over the box `lo ..= hi`; points outside it
    /// fall into the border buckets.
    pub(crate) fn new(lo: Point, hi: Point, size: f64) -> Self {
        let size = size.max(1e-9);
        let cols = ((hi.x - lo.x).max(0.0) / size).floor() as usize + 1;
        let rows = ((hi.y - lo.y).max(0.0) / size).floor() as usize + 1;
        Self {
            origin: lo,
            size,
            cols,
            rows,
            cells: (0..cols * rows).map(|_| Vec::new()).collect(),
            filled: Vec::new(),
        }
    }

    fn slot(&self, p: Point) -> (usize, usize) {
        let c = (((p.x - self.origin.x) / self.size).max(0.0) as usize).min(self.cols - 1);
        let r = (((p.y - self.origin.y) / self.size).max(0.0) as usize).min(self.rows - 1);
        (r, c)
    }

    /// Adds `value` at `p`.
    pub(crate) fn insert(&mut self, p: Point, value: T) {
        let (r, c) = self.slot(p);
        let i = r * self.cols + c;
        if self.cells[i].is_empty() {
            self.filled.push(i);
        }
        self.cells[i].push((p, value));
    }

    /// The bucket of `p`, to edit in place.
    pub(crate) fn bucket_mut(&mut self, p: Point) -> &mut Vec<Entry<T>> {
        let (r, c) = self.slot(p);
        &mut self.cells[r * self.cols + c]
    }

    /// Hands `visit` the buckets around `p` ring by ring (the bucket of `p`
    /// first) with the search's `state`, stopping before a ring when
    /// `enough` accepts the state and the least distance any point of that
    /// ring can have, or when the grid is done. Once a ring would hold more
    /// buckets than there are non-empty ones, the non-empty buckets not yet
    /// seen are visited instead and the search ends (a query far from every
    /// entry costs the entries, not the grid).
    pub(crate) fn search<S>(
        &mut self,
        p: Point,
        state: &mut S,
        mut visit: impl FnMut(&mut S, &mut Vec<Entry<T>>),
        mut enough: impl FnMut(&S, f64) -> bool,
    ) {
        let (r0, c0) = self.slot(p);
        for ring in 0..=self.rows.max(self.cols) {
            if enough(state, ring.saturating_sub(1) as f64 * self.size) {
                return;
            }
            // Far out, the next ring has more buckets than hold entries at
            // all: visit those outside the rings seen, and stop.
            if (2 * ring + 1) * (2 * ring + 1) > 4 * self.filled.len() {
                self.filled.retain(|&i| !self.cells[i].is_empty());
                // A bucket emptied and filled again is listed twice.
                self.filled.sort_unstable();
                self.filled.dedup();
                let cols = self.cols;
                for &i in &self.filled {
                    let (r, c) = (i / cols, i % cols);
                    if r.abs_diff(r0).max(c.abs_diff(c0)) >= ring {
                        visit(state, &mut self.cells[i]);
                    }
                }
                return;
            }
            let (rlo, rhi) = (r0.saturating_sub(ring), (r0 + ring).min(self.rows - 1));
            let (clo, chi) = (c0.saturating_sub(ring), (c0 + ring).min(self.cols - 1));
            for r in rlo..=rhi {
                for c in clo..=chi {
                    if r.abs_diff(r0) == ring || c.abs_diff(c0) == ring {
                        visit(state, &mut self.cells[r * self.cols + c]);
                    }
                }
            }
            if rlo == 0 && clo == 0 && rhi == self.rows - 1 && chi == self.cols - 1 {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::math::norm;

    /// The search finds the nearest point whatever the bucket size, and
    /// stops early once nothing closer can remain.
    #[test]
    fn search_finds_the_nearest_point() {
        let pts = [(0.5, 0.5), (9.0, 9.0), (4.0, 5.0), (4.2, 4.9)].map(|(x, y)| Point::new(x, y));
        for size in [0.5, 1.0, 3.0, 20.0] {
            let mut b = Buckets::new(Point::new(0.0, 0.0), Point::new(10.0, 10.0), size);
            for (i, &p) in pts.iter().enumerate() {
                b.insert(p, i);
            }
            let q = Point::new(4.3, 4.8);
            let mut best: Option<(f64, usize)> = None;
            let mut rings = 0;
            b.search(
                q,
                &mut best,
                |best, cell| {
                    for &(p, i) in cell.iter() {
                        let d = norm(p.x - q.x, p.y - q.y);
                        if best.is_none_or(|b| (d, i) < b) {
                            *best = Some((d, i));
                        }
                    }
                },
                |best, bound| {
                    rings += 1;
                    best.is_some_and(|b| b.0 < bound)
                },
            );
            assert_eq!(best.map(|b| b.1), Some(3), "size {size}");
            // Far from the only live point: the scan of filled buckets finds it.
            for p in pts {
                b.bucket_mut(p).retain(|e| e.1 == 1);
            }
            let mut far: Option<(f64, usize)> = None;
            b.search(
                Point::new(0.0, 0.0),
                &mut far,
                |far, cell| {
                    for &(p, i) in cell.iter() {
                        let d = norm(p.x, p.y);
                        if far.is_none_or(|b| (d, i) < b) {
                            *far = Some((d, i));
                        }
                    }
                },
                |far, bound| far.is_some_and(|b| b.0 < bound),
            );
            assert_eq!(far.map(|b| b.1), Some(1), "size {size}");
            if size <= 1.0 {
                assert!(rings < 6, "size {size}: {rings} rings");
            }
        }
    }
}
