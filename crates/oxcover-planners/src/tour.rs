//! Open tours: the order in which to visit places (rooms, cells of a room)
//! so that the total transit cost is small, starting from a given place and
//! ending anywhere.
//!
//! - Up to [`EXACT_LIMIT`] places: exact, by Held–Karp dynamic programming
//!   over subsets (O(2ⁿ n²)).
//! - Beyond: nearest neighbour, then 2-opt (reverse a stretch) and, up to
//!   [`OR_OPT_LIMIT`] places, Or-opt (move a stretch of one to three places
//!   elsewhere), until no move improves the tour by more than a relative
//!   1e-12 or [`ROUNDS`] rounds have run.
//!
//! Costs may be asymmetric for Held–Karp; the local search assumes
//! symmetric costs (2-opt reverses stretches). Ties break towards lower
//! indices, so the result depends only on the costs.
//!
//! [`open_tour_euclidean`] orders points in the plane: as [`open_tour`] up to
//! [`NEIGHBOUR_LIMIT`] points; beyond (the boundary pass of a large map can
//! have ten thousand anchors, where the O(n²) rounds above take seconds),
//! nearest neighbour over a bucket grid, then 2-opt restricted to each
//! point's [`NEIGHBOURS`] nearest (Johnson & McGeoch's neighbour lists),
//! O(n · k) per round apart from the reversals.

use oxcover_grid::Point;
use oxcover_grid::math::norm;

use crate::buckets::Buckets;

/// Largest number of places ordered exactly.
pub const EXACT_LIMIT: usize = 13;
/// Largest number of places Or-opt runs on (its rounds cost O(n³)).
pub const OR_OPT_LIMIT: usize = 120;
/// Most improvement rounds.
pub const ROUNDS: usize = 30;

/// Largest number of points [`open_tour_euclidean`] orders with [`open_tour`].
pub const NEIGHBOUR_LIMIT: usize = 2000;
/// Candidate neighbours per point of the large-tour 2-opt.
pub const NEIGHBOURS: usize = 10;

/// An open tour over `points` (Euclidean distances) from `start` (see the
/// module docs).
#[must_use]
pub fn open_tour_euclidean(points: &[Point], start: usize) -> Vec<usize> {
    let n = points.len();
    let dist = |a: usize, b: usize| norm(points[a].x - points[b].x, points[a].y - points[b].y);
    if n <= NEIGHBOUR_LIMIT {
        return open_tour(n, start, &dist);
    }
    let mut grid = PointGrid::new(points);
    let mut tour = Vec::with_capacity(n);
    let mut here = start.min(n - 1);
    tour.push(here);
    let mut live = grid.clone();
    live.remove(here, points);
    for _ in 1..n {
        let Some(next) = live.nearest(points[here]) else {
            break;
        };
        live.remove(next, points);
        tour.push(next);
        here = next;
    }
    let neighbours: Vec<Vec<usize>> = (0..n)
        .map(|i| grid.k_nearest(i, points, NEIGHBOURS))
        .collect();
    two_opt_neighbours(&mut tour, &neighbours, &dist);
    tour
}

/// 2-opt on an open tour (first place fixed) trying, for each edge `(a, b)`,
/// only the edges that join `a` to one of its neighbours.
fn two_opt_neighbours(
    tour: &mut [usize],
    neighbours: &[Vec<usize>],
    dist: &dyn Fn(usize, usize) -> f64,
) {
    let n = tour.len();
    let mut pos = vec![0; n];
    for (i, &p) in tour.iter().enumerate() {
        pos[p] = i;
    }
    let edge = |t: &[usize], i: usize| if i + 1 < n { dist(t[i], t[i + 1]) } else { 0.0 };
    for _round in 0..ROUNDS {
        let mut better = false;
        for start in 0..n {
            let a = tour[start];
            for &c in &neighbours[a] {
                let (i, j) = (pos[a], pos[c]);
                // Reverse tour[lo..=hi] so that tour[i] and c become adjacent.
                let (lo, hi) = if j > i + 1 {
                    (i + 1, j)
                } else if j + 1 < i {
                    (j + 1, i)
                } else {
                    continue;
                };
                let before = edge(tour, lo - 1) + edge(tour, hi);
                let after = dist(tour[lo - 1], tour[hi])
                    + if hi + 1 < n {
                        dist(tour[lo], tour[hi + 1])
                    } else {
                        0.0
                    };
                if after < before - 1e-12 * before.max(1.0) {
                    tour[lo..=hi].reverse();
                    for (q, &p) in tour.iter().enumerate().take(hi + 1).skip(lo) {
                        pos[p] = q;
                    }
                    better = true;
                }
            }
        }
        if !better {
            break;
        }
    }
}

/// The points in buckets of about two points each, for nearest queries.
#[derive(Clone)]
struct PointGrid(Buckets<usize>);

impl PointGrid {
    fn new(points: &[Point]) -> Self {
        let (mut lo, mut hi) = (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in points {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let area = ((hi.x - lo.x) * (hi.y - lo.y)).max(1.0);
        let size = (2.0 * area / points.len().max(1) as f64).sqrt();
        let mut b = Buckets::new(lo, hi, size);
        for (i, &p) in points.iter().enumerate() {
            b.insert(p, i);
        }
        Self(b)
    }

    fn remove(&mut self, i: usize, points: &[Point]) {
        self.0.bucket_mut(points[i]).retain(|e| e.1 != i);
    }

    /// The nearest point to `p` (ties: lower index).
    fn nearest(&mut self, p: Point) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        self.0.search(
            p,
            &mut best,
            |best, cell| {
                for &(q, j) in cell.iter() {
                    let d = norm(p.x - q.x, p.y - q.y);
                    if best.is_none_or(|b| (d, j) < b) {
                        *best = Some((d, j));
                    }
                }
            },
            |best, bound| best.is_some_and(|b| b.0 < bound),
        );
        best.map(|b| b.1)
    }

    /// The `k` points nearest point `i` (itself excluded; ties: lower index).
    fn k_nearest(&mut self, i: usize, points: &[Point], k: usize) -> Vec<usize> {
        let p = points[i];
        let mut found: Vec<(f64, usize)> = Vec::new();
        self.0.search(
            p,
            &mut found,
            |found, cell| {
                found.extend(
                    cell.iter()
                        .filter(|e| e.1 != i)
                        .map(|&(q, j)| (norm(p.x - q.x, p.y - q.y), j)),
                );
                found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                found.truncate(k);
            },
            |found, bound| found.len() >= k && found[k - 1].0 < bound,
        );
        found.into_iter().map(|f| f.1).collect()
    }
}

/// An open tour over places `0..n` starting at `start` (which must be
/// `< n`), every place exactly once, minimising the sum of `cost(a, b)` over
/// consecutive places (exactly up to [`EXACT_LIMIT`] places).
#[must_use]
pub fn open_tour(n: usize, start: usize, cost: &dyn Fn(usize, usize) -> f64) -> Vec<usize> {
    if n == 0 {
        return Vec::new();
    }
    let start = start.min(n - 1);
    if n <= 2 {
        let mut t = vec![start];
        t.extend((0..n).filter(|&i| i != start));
        return t;
    }
    if n <= EXACT_LIMIT {
        held_karp(n, start, cost)
    } else {
        let mut t = nearest_neighbour(n, start, cost);
        improve(&mut t, cost);
        t
    }
}

/// The cost of visiting `tour` in order.
#[must_use]
pub fn tour_cost(tour: &[usize], cost: &dyn Fn(usize, usize) -> f64) -> f64 {
    tour.windows(2).map(|w| cost(w[0], w[1])).sum()
}

fn held_karp(n: usize, start: usize, cost: &dyn Fn(usize, usize) -> f64) -> Vec<usize> {
    let full = 1usize << n;
    // best[set][last]: cheapest path from `start` over `set` ending at `last`.
    let mut best = vec![f64::INFINITY; full * n];
    let mut prev = vec![usize::MAX; full * n];
    best[(1 << start) * n + start] = 0.0;
    for set in 1..full {
        if set & (1 << start) == 0 {
            continue;
        }
        for last in 0..n {
            let here = best[set * n + last];
            if !here.is_finite() || set & (1 << last) == 0 {
                continue;
            }
            for next in 0..n {
                if set & (1 << next) != 0 {
                    continue;
                }
                let s2 = set | (1 << next);
                let c = here + cost(last, next);
                if c < best[s2 * n + next] {
                    best[s2 * n + next] = c;
                    prev[s2 * n + next] = last;
                }
            }
        }
    }
    let all = full - 1;
    let mut last = (0..n)
        .min_by(|&a, &b| best[all * n + a].total_cmp(&best[all * n + b]))
        .unwrap_or(start);
    let mut set = all;
    let mut tour = Vec::with_capacity(n);
    while last != usize::MAX {
        tour.push(last);
        let p = prev[set * n + last];
        set &= !(1 << last);
        last = p;
    }
    tour.reverse();
    tour
}

fn nearest_neighbour(n: usize, start: usize, cost: &dyn Fn(usize, usize) -> f64) -> Vec<usize> {
    let mut used = vec![false; n];
    let mut tour = vec![start];
    used[start] = true;
    let mut here = start;
    for _ in 1..n {
        let next = (0..n)
            .filter(|&i| !used[i])
            .min_by(|&a, &b| cost(here, a).total_cmp(&cost(here, b)))
            .unwrap_or(here);
        used[next] = true;
        tour.push(next);
        here = next;
    }
    tour
}

/// 2-opt and Or-opt on an open tour whose first place stays first.
fn improve(tour: &mut Vec<usize>, cost: &dyn Fn(usize, usize) -> f64) {
    let n = tour.len();
    let eps = |total: f64| 1e-12 * total.abs().max(1.0);
    for _round in 0..ROUNDS {
        let mut better = false;
        // 2-opt: reverse tour[i..=j] (i ≥ 1).
        for i in 1..n - 1 {
            for j in i + 1..n {
                let before = cost(tour[i - 1], tour[i])
                    + if j + 1 < n {
                        cost(tour[j], tour[j + 1])
                    } else {
                        0.0
                    };
                let after = cost(tour[i - 1], tour[j])
                    + if j + 1 < n {
                        cost(tour[i], tour[j + 1])
                    } else {
                        0.0
                    };
                if after < before - eps(before) {
                    tour[i..=j].reverse();
                    better = true;
                }
            }
        }
        // Or-opt: move a stretch of 1..=3 places to another gap.
        let longest = if n <= OR_OPT_LIMIT { 3 } else { 0 };
        for len in 1..=longest {
            let mut i = 1;
            while i + len <= n {
                let total = tour_cost(tour, cost);
                let mut moved = tour.clone();
                let seg: Vec<usize> = moved.drain(i..i + len).collect();
                let mut best: Option<(f64, Vec<usize>)> = None;
                for gap in 1..=moved.len() {
                    for rev in [false, true] {
                        let mut t = moved.clone();
                        let mut s = seg.clone();
                        if rev {
                            s.reverse();
                        }
                        t.splice(gap..gap, s);
                        let c = tour_cost(&t, cost);
                        if c < total - eps(total) && best.as_ref().is_none_or(|b| c < b.0) {
                            best = Some((c, t));
                        }
                    }
                }
                if let Some((_, t)) = best {
                    *tour = t;
                    better = true;
                }
                i += 1;
            }
        }
        if !better {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Places on a line: the best open tour from the left end walks right.
    #[test]
    fn a_line_is_walked_in_order() {
        let xs: [f64; 6] = [0.0, 5.0, 1.0, 4.0, 2.0, 3.0];
        let cost = |a: usize, b: usize| (xs[a] - xs[b]).abs();
        assert_eq!(open_tour(6, 0, &cost), vec![0, 2, 4, 5, 3, 1]);
    }

    /// Exact and heuristic agree in cost on seeded random points (the
    /// heuristic may tie with another order), and the heuristic is never far off.
    #[test]
    fn heuristic_is_close_to_exact() {
        let mut worst: f64 = 1.0;
        for seed in 0..20u64 {
            let mut s = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let mut rnd = || {
                s = s
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (s >> 11) as f64 / (1u64 << 53) as f64
            };
            let pts: Vec<(f64, f64)> = (0..10).map(|_| (rnd(), rnd())).collect();
            let cost = |a: usize, b: usize| (pts[a].0 - pts[b].0).hypot(pts[a].1 - pts[b].1);
            let exact = held_karp(10, 0, &cost);
            let mut heur = nearest_neighbour(10, 0, &cost);
            improve(&mut heur, &cost);
            let (e, h) = (tour_cost(&exact, &cost), tour_cost(&heur, &cost));
            assert!(e <= h + 1e-9, "exact {e} > heuristic {h}");
            assert_eq!(exact[0], 0);
            assert_eq!(heur[0], 0);
            let mut sorted = heur.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..10).collect::<Vec<_>>());
            worst = worst.max(h / e);
        }
        assert!(worst < 1.15, "heuristic up to {worst} times the optimum");
    }

    /// Past the limit: a permutation from the start, no longer than the
    /// nearest-neighbour tour, and within a few percent of the full 2-opt.
    #[test]
    fn large_euclidean_tours_are_close_to_the_full_search() {
        let mut s = 7u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let n = NEIGHBOUR_LIMIT + 500;
        let pts: Vec<Point> = (0..n)
            .map(|_| Point::new(100.0 * rnd(), 60.0 * rnd()))
            .collect();
        let cost = |a: usize, b: usize| (pts[a].x - pts[b].x).hypot(pts[a].y - pts[b].y);
        let fast = open_tour_euclidean(&pts, 3);
        assert_eq!(fast[0], 3);
        let mut sorted = fast.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n).collect::<Vec<_>>());
        let nn = nearest_neighbour(n, 3, &cost);
        let mut full = nn.clone();
        improve(&mut full, &cost);
        let (f, g, h) = (
            tour_cost(&fast, &cost),
            tour_cost(&nn, &cost),
            tour_cost(&full, &cost),
        );
        assert!(
            f <= g + 1e-9,
            "neighbour 2-opt {f} above nearest neighbour {g}"
        );
        assert!(f <= 1.05 * h, "neighbour 2-opt {f} against full 2-opt {h}");
        // Below the limit it is open_tour itself.
        let small = &pts[..50];
        let c2 = |a: usize, b: usize| (small[a].x - small[b].x).hypot(small[a].y - small[b].y);
        assert_eq!(open_tour_euclidean(small, 0), open_tour(50, 0, &c2));
    }
}
