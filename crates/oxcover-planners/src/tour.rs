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

/// Largest number of places ordered exactly.
pub const EXACT_LIMIT: usize = 13;
/// Largest number of places Or-opt runs on (its rounds cost O(n³)).
pub const OR_OPT_LIMIT: usize = 120;
/// Most improvement rounds.
pub const ROUNDS: usize = 30;

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
}
