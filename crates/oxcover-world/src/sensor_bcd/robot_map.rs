//! The robot's own map: what its rays have seen (free, occupied, unknown),
//! where it has been, and routes through that knowledge.
//!
//! The map grows as the robot sees more (it is not told the world's size).
//! Routes run over cells the robot may cross: cells it has been in (their
//! first recorded position is known to be clear), and cells seen free whose
//! centre lies at least the keep-out distance from every cell not seen free
//! (unknown counts as blocked). Moves are 8-connected; the route is then
//! shortened by straight segments that stay in the seen-free cells.

use oxcover_grid::Point;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

const UNKNOWN: u8 = 0;
const FREE: u8 = 1;
const OCCUPIED: u8 = 2;

/// The robot's knowledge of the world, on a square grid.
#[derive(Clone, Debug)]
pub(crate) struct RobotMap {
    res: f64,
    /// Lower-left corner of cell (0, 0).
    origin: Point,
    w: usize,
    h: usize,
    cells: Vec<u8>,
    /// 1 + index into `visits` of the first position recorded in the cell, or 0.
    visited: Vec<u32>,
    visits: Vec<Point>,
}

/// Cells a route may use, from [`RobotMap::passable`].
pub(crate) struct Passable {
    /// Seen free and far enough from anything not seen free.
    open: Vec<bool>,
    /// `open` or visited.
    any: Vec<bool>,
}

impl RobotMap {
    /// An empty map of `res` cells around `centre`.
    pub(crate) fn new(res: f64, centre: Point) -> Self {
        let n = (4.0 / res).ceil() as usize;
        Self {
            res,
            origin: Point::new(
                centre.x - n as f64 * res / 2.0,
                centre.y - n as f64 * res / 2.0,
            ),
            w: n,
            h: n,
            cells: vec![UNKNOWN; n * n],
            visited: vec![0; n * n],
            visits: Vec::new(),
        }
    }

    /// Cell size (m).
    pub(crate) fn resolution(&self) -> f64 {
        self.res
    }

    fn coords(&self, p: Point) -> (i64, i64) {
        (
            ((p.x - self.origin.x) / self.res).floor() as i64,
            ((p.y - self.origin.y) / self.res).floor() as i64,
        )
    }

    fn index_of(&self, p: Point) -> Option<usize> {
        let (i, j) = self.coords(p);
        (i >= 0 && j >= 0 && (i as usize) < self.w && (j as usize) < self.h)
            .then(|| j as usize * self.w + i as usize)
    }

    /// Grows the map so `p` lies inside, with room to spare.
    fn ensure(&mut self, p: Point) -> usize {
        if let Some(k) = self.index_of(p) {
            return k;
        }
        let (i, j) = self.coords(p);
        let grow = |lo: i64, n: usize| -> (usize, usize) {
            // Cells to add below and above.
            let below = if lo < 0 { (-lo) as usize + n } else { 0 };
            let above = if lo >= n as i64 {
                lo as usize - n + 1 + n
            } else {
                0
            };
            (below, above)
        };
        let (left, right) = grow(i, self.w);
        let (down, up) = grow(j, self.h);
        let (w, h) = (self.w + left + right, self.h + down + up);
        let mut cells = vec![UNKNOWN; w * h];
        let mut visited = vec![0; w * h];
        for y in 0..self.h {
            let from = y * self.w;
            let to = (y + down) * w + left;
            cells[to..to + self.w].copy_from_slice(&self.cells[from..from + self.w]);
            visited[to..to + self.w].copy_from_slice(&self.visited[from..from + self.w]);
        }
        self.origin = Point::new(
            self.origin.x - left as f64 * self.res,
            self.origin.y - down as f64 * self.res,
        );
        (self.w, self.h, self.cells, self.visited) = (w, h, cells, visited);
        self.index_of(p).expect("the grown map contains the point")
    }

    /// Marks the ray from `from` to `to` seen free, and `to` occupied when
    /// the ray hit something there.
    pub(crate) fn ray(&mut self, from: Point, to: Point, hit: bool) {
        let len = (to.x - from.x).hypot(to.y - from.y);
        // Stop a cell short of the hit: the hit cell may be partly free.
        let free_len = if hit { len - self.res } else { len };
        let n = (free_len / (self.res / 2.0)).ceil().max(0.0) as usize;
        for k in 0..n {
            let t = k as f64 * self.res / 2.0 / len.max(1e-12);
            let q = Point::new(from.x + t * (to.x - from.x), from.y + t * (to.y - from.y));
            let c = self.ensure(q);
            if self.cells[c] == UNKNOWN {
                self.cells[c] = FREE;
            }
        }
        if hit {
            let c = self.ensure(to);
            self.cells[c] = OCCUPIED;
        }
    }

    /// Marks an obstacle point.
    pub(crate) fn occupied(&mut self, p: Point) {
        let c = self.ensure(p);
        self.cells[c] = OCCUPIED;
    }

    /// Records a position of the robot (known to be clear).
    pub(crate) fn visit(&mut self, p: Point) {
        let c = self.ensure(p);
        if self.visited[c] == 0 {
            self.visits.push(p);
            self.visited[c] = self.visits.len() as u32;
        }
        if self.cells[c] == UNKNOWN {
            self.cells[c] = FREE;
        }
    }

    /// Positions recorded so far (first visits of cells).
    pub(crate) fn visit_count(&self) -> usize {
        self.visits.len()
    }

    /// The order (0-based) in which the cell of `p` was first visited, if it was.
    pub(crate) fn first_visit(&self, p: Point) -> Option<usize> {
        let c = self.cell_index(p)?;
        (self.visited[c] > 0).then(|| self.visited[c] as usize - 1)
    }

    fn centre(&self, k: usize) -> Point {
        let (i, j) = (k % self.w, k / self.w);
        Point::new(
            self.origin.x + (i as f64 + 0.5) * self.res,
            self.origin.y + (j as f64 + 0.5) * self.res,
        )
    }

    /// Where a route through cell `k` passes: the first visit, or the centre.
    fn waypoint(&self, k: usize) -> Point {
        match self.visited[k] {
            0 => self.centre(k),
            v => self.visits[v as usize - 1],
        }
    }

    /// The cells a route may use for a robot keeping `keep_out` metres from
    /// anything not seen free.
    pub(crate) fn passable(&self, keep_out: f64) -> Passable {
        let mut near = vec![false; self.w * self.h];
        let rad = (keep_out / self.res).ceil() as i64;
        let r2 = (keep_out / self.res).powi(2);
        let (w, h) = (self.w as i64, self.h as i64);
        for j in 0..h {
            for i in 0..w {
                let k = (j * w + i) as usize;
                if self.cells[k] == FREE {
                    continue;
                }
                // Only blocked cells next to a free one matter.
                let edge = [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(di, dj)| {
                    let (a, b) = (i + di, j + dj);
                    a >= 0 && b >= 0 && a < w && b < h && self.cells[(b * w + a) as usize] == FREE
                });
                if !edge {
                    continue;
                }
                for dj in -rad..=rad {
                    for di in -rad..=rad {
                        let (a, b) = (i + di, j + dj);
                        if a >= 0 && b >= 0 && a < w && b < h && ((di * di + dj * dj) as f64) < r2 {
                            near[(b * w + a) as usize] = true;
                        }
                    }
                }
            }
        }
        let open: Vec<bool> = (0..self.w * self.h)
            .map(|k| self.cells[k] == FREE && !near[k])
            .collect();
        let any = (0..self.w * self.h)
            .map(|k| open[k] || self.visited[k] != 0)
            .collect();
        Passable { open, any }
    }

    /// Route lengths (m) from `from` over passable cells (8-connected moves
    /// between cells), infinite where unreachable; the search stops once the
    /// nearest of `targets` (metre points) is settled, so only distances up
    /// to that one are final (no target is nearer than it). The grid is
    /// indexed as [`RobotMap::cell_index`].
    pub(crate) fn distances(
        &self,
        pass: &Passable,
        from: Point,
        targets: &[Point],
    ) -> (Vec<f64>, Vec<u32>) {
        let n = self.w * self.h;
        let mut is_target = vec![false; n];
        for &t in targets {
            if let Some(k) = self.index_of(t) {
                is_target[k] = true;
            }
        }
        let mut dist = vec![f64::INFINITY; n];
        let mut parent = vec![u32::MAX; n];
        let Some(s) = self.index_of(from) else {
            return (dist, parent);
        };
        let mut heap = BinaryHeap::new();
        dist[s] = 0.0;
        heap.push(Reverse((0u64, s)));
        let (w, h) = (self.w as i64, self.h as i64);
        while let Some(Reverse((d, k))) = heap.pop() {
            let dk = d as f64 / 1e6;
            if dk > dist[k] {
                continue;
            }
            if is_target[k] {
                break;
            }
            let (i, j) = ((k % self.w) as i64, (k / self.w) as i64);
            for (di, dj) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                let (a, b) = (i + di, j + dj);
                if a < 0 || b < 0 || a >= w || b >= h {
                    continue;
                }
                let m = (b * w + a) as usize;
                if !pass.any[m] {
                    continue;
                }
                let step = if di != 0 && dj != 0 {
                    std::f64::consts::SQRT_2
                } else {
                    1.0
                } * self.res;
                let nd = dist[k] + step;
                if nd < dist[m] - 1e-12 {
                    dist[m] = nd;
                    parent[m] = k as u32;
                    heap.push(Reverse(((nd * 1e6) as u64, m)));
                }
            }
        }
        (dist, parent)
    }

    /// The cell index of `p`, if inside the map.
    pub(crate) fn cell_index(&self, p: Point) -> Option<usize> {
        self.index_of(p)
    }

    /// The route from the search's source to `to`, as metre waypoints
    /// (ending exactly at `to`), shortened by straight segments through
    /// open cells.
    pub(crate) fn route(&self, pass: &Passable, parent: &[u32], to: Point) -> Vec<Point> {
        let Some(mut k) = self.index_of(to) else {
            return vec![to];
        };
        let mut cells = vec![k];
        while parent[k] != u32::MAX {
            k = parent[k] as usize;
            cells.push(k);
        }
        cells.reverse();
        let mut pts: Vec<Point> = cells.iter().map(|&k| self.waypoint(k)).collect();
        pts.push(to);
        // String pulling: from each kept point, go as far as a straight
        // segment through open cells reaches.
        let mut out = vec![pts[0]];
        let mut i = 0;
        while i + 1 < pts.len() {
            let mut best = i + 1;
            for k in i + 2..pts.len() {
                if self.segment_open(pass, pts[i], pts[k]) {
                    best = k;
                } else if k > best + 8 {
                    break;
                }
            }
            out.push(pts[best]);
            i = best;
        }
        out
    }

    /// Whether the segment's samples lie in open cells (its end cells excepted).
    fn segment_open(&self, pass: &Passable, a: Point, b: Point) -> bool {
        let len = (b.x - a.x).hypot(b.y - a.y);
        let n = (len / (self.res / 2.0)).ceil() as usize;
        let (ka, kb) = (self.index_of(a), self.index_of(b));
        (1..n).all(|s| {
            let t = s as f64 / n as f64;
            let q = Point::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            match self.index_of(q) {
                Some(k) => pass.open[k] || Some(k) == ka || Some(k) == kb,
                None => false,
            }
        })
    }

    /// Cells seen occupied, as metre centres (for pictures).
    pub(crate) fn occupied_points(&self) -> Vec<Point> {
        (0..self.w * self.h)
            .filter(|&k| self.cells[k] == OCCUPIED)
            .map(|k| self.centre(k))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_marks_and_routes_around_what_it_saw() {
        let mut m = RobotMap::new(0.1, Point::new(0.0, 0.0));
        // See a 6 m x 4 m room from its middle row, with a wall at x = 3
        // from y = 2.6 up.
        for k in 0..60 {
            let x = k as f64 * 0.1 + 0.05;
            m.ray(Point::new(x, 2.0), Point::new(x, 0.0), true);
            m.ray(Point::new(x, 2.0), Point::new(x, 4.0), true);
            m.visit(Point::new(x, 2.0));
        }
        for k in 26..40 {
            m.occupied(Point::new(3.0, k as f64 * 0.1));
        }
        assert!(m.w * m.h > 40 * 40, "the map grew");
        let pass = m.passable(0.25);
        let (dist, parent) = m.distances(&pass, Point::new(0.55, 2.0), &[Point::new(5.55, 2.0)]);
        let k = m.cell_index(Point::new(5.55, 2.0)).unwrap();
        assert!((dist[k] - 5.0).abs() < 0.2, "{}", dist[k]);
        let r = m.route(&pass, &parent, Point::new(5.55, 2.0));
        assert_eq!(*r.last().unwrap(), Point::new(5.55, 2.0));
        // Unknown space is never entered.
        let k = m.cell_index(Point::new(1.0, 5.0));
        assert!(k.is_none_or(|k| !pass.any[k]));
    }
}
