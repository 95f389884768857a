//! Exact Euclidean distance transforms on grids (Felzenszwalb & Huttenlocher 2012,
//! generalised to any convex separable kernel).
//!
//! Two transforms, both exact and in integer arithmetic:
//! - [`boundary_distance_sq4`]: for every cell, `4·d²` where `d` is the distance
//!   (in cells) from the cell's centre to the nearest *boundary* of a source cell
//!   (a closed unit square). This is the contract's admissibility distance. Per
//!   axis the gap is `max(0, |k| − ½)`, so `4·d² = h(Δr) + h(Δc)` with
//!   `h(k) = max(0, 2|k| − 1)²`.
//! - [`center_distance_sq`]: `d²` between cell centres, `h(k) = k²`.
//!
//! Both are separable: a column pass, then a row pass computing
//! `D(c) = min_q G(q) + h(c − q)` by the lower envelope of the functions
//! `G(q) + h(· − q)`. Because `h` is convex, two such functions cross once, so
//! the envelope is built in one sweep; the crossing is found by binary search
//! (the kernel need not be a parabola). O(n log n) per line, O(cells·log)
//! in total.

use crate::grid::Grid;

/// Marker for "no source on this line / in the grid".
pub const INFINITE: u64 = u64::MAX;

/// `4·d²` from each cell centre to the nearest source cell's boundary (0 on sources).
///
/// When `outside_is_source` is set, the area outside the grid counts as sources
/// (the map edge is a wall). Cells with no source at all get [`INFINITE`].
#[must_use]
pub fn boundary_distance_sq4(sources: &Grid<bool>, outside_is_source: bool) -> Grid<u64> {
    fn h(k: i64) -> u64 {
        let g = (2 * k.unsigned_abs()).saturating_sub(1);
        g * g
    }
    transform(sources, outside_is_source, h)
}

/// `d²` (cells²) from each cell centre to the nearest source cell centre.
///
/// Cells with no source at all get [`INFINITE`].
#[must_use]
pub fn center_distance_sq(sources: &Grid<bool>) -> Grid<u64> {
    fn h(k: i64) -> u64 {
        k.unsigned_abs() * k.unsigned_abs()
    }
    transform(sources, false, h)
}

fn transform(sources: &Grid<bool>, outside: bool, h: fn(i64) -> u64) -> Grid<u64> {
    let (w, hgt) = (sources.width(), sources.height());
    // Column pass: h of the distance to the nearest source in the column. `h` is
    // monotone in |k|, so the nearest source row gives the minimum.
    let mut g = vec![INFINITE; w * hgt];
    let src = sources.as_slice();
    for c in 0..w {
        // Distance (in rows) to the nearest source above, then below.
        let mut last: Option<i64> = if outside { Some(-1) } else { None };
        for r in 0..hgt {
            if src[r * w + c] {
                last = Some(r as i64);
            }
            if let Some(l) = last {
                g[r * w + c] = h(r as i64 - l);
            }
        }
        let mut next: Option<i64> = if outside { Some(hgt as i64) } else { None };
        for r in (0..hgt).rev() {
            if src[r * w + c] {
                next = Some(r as i64);
            }
            if let Some(n) = next {
                let v = h(n - r as i64);
                if v < g[r * w + c] {
                    g[r * w + c] = v;
                }
            }
        }
    }
    // Row pass.
    let mut out = vec![INFINITE; w * hgt];
    let mut env = Envelope::with_capacity(w + 2);
    let mut line = vec![INFINITE; w + 2];
    let mut res = vec![INFINITE; w + 2];
    for r in 0..hgt {
        if outside {
            // Columns -1 and w are walls: G = 0 there. Shift by one.
            line[0] = 0;
            line[1..=w].copy_from_slice(&g[r * w..(r + 1) * w]);
            line[w + 1] = 0;
            env.run(&line, h, &mut res);
            out[r * w..(r + 1) * w].copy_from_slice(&res[1..=w]);
        } else {
            env.run(&g[r * w..(r + 1) * w], h, &mut res[..w]);
            out[r * w..(r + 1) * w].copy_from_slice(&res[..w]);
        }
    }
    Grid::from_vec(w, hgt, out).unwrap_or_else(|| Grid::new(w, hgt, INFINITE))
}

/// Lower envelope of `f(q) + h(x − q)` over the sources `q` of one line.
struct Envelope {
    v: Vec<usize>,
    z: Vec<i64>,
}

impl Envelope {
    fn with_capacity(n: usize) -> Self {
        Self {
            v: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
        }
    }

    fn run(&mut self, f: &[u64], h: fn(i64) -> u64, out: &mut [u64]) {
        let n = f.len();
        self.v.clear();
        self.z.clear();
        for q in 0..n {
            if f[q] == INFINITE {
                continue;
            }
            loop {
                let Some(&p) = self.v.last() else {
                    self.v.push(q);
                    self.z.push(i64::MIN);
                    break;
                };
                let s = first_dominated(f, h, p, q, n);
                if s <= *self.z.last().unwrap_or(&i64::MIN) {
                    self.v.pop();
                    self.z.pop();
                    continue;
                }
                if s < n as i64 {
                    self.v.push(q);
                    self.z.push(s);
                }
                break;
            }
        }
        if self.v.is_empty() {
            out.fill(INFINITE);
            return;
        }
        let mut j = 0;
        for (x, o) in out.iter_mut().enumerate() {
            while j + 1 < self.v.len() && self.z[j + 1] <= x as i64 {
                j += 1;
            }
            let q = self.v[j];
            *o = f[q] + h(x as i64 - q as i64);
        }
    }
}

/// First `x` in `0..n` where `f(q) + h(x−q) <= f(p) + h(x−p)` (`q > p`), or `n`.
///
/// The difference is non-increasing in `x` for convex `h`, so binary search works.
fn first_dominated(f: &[u64], h: fn(i64) -> u64, p: usize, q: usize, n: usize) -> i64 {
    let better = |x: i64| f[q] + h(x - q as i64) <= f[p] + h(x - p as i64);
    let (mut lo, mut hi) = (0i64, n as i64);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if better(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute(sources: &Grid<bool>, outside: bool, boundary: bool) -> Grid<u64> {
        let h = |k: i64| -> u64 {
            if boundary {
                let g = (2 * k.unsigned_abs()).saturating_sub(1);
                g * g
            } else {
                k.unsigned_abs() * k.unsigned_abs()
            }
        };
        let (w, hh) = (sources.width() as i64, sources.height() as i64);
        Grid::from_fn(sources.width(), sources.height(), |c| {
            let mut best = INFINITE;
            for r in -1..=hh {
                for col in -1..=w {
                    let inside = r >= 0 && col >= 0 && r < hh && col < w;
                    let is_src = if inside {
                        sources[crate::Cell::new(r as usize, col as usize)]
                    } else {
                        outside
                    };
                    if is_src {
                        best = best.min(h(c.row as i64 - r) + h(c.col as i64 - col));
                    }
                }
            }
            best
        })
    }

    proptest! {
        #[test]
        fn matches_brute_force(w in 1usize..14, h in 1usize..14, seed in any::<u64>(), density in 0.0f64..0.5, outside in any::<bool>()) {
            let mut s = seed;
            let sources = Grid::from_fn(w, h, |_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((s >> 33) as f64 / (1u64 << 31) as f64) < density
            });
            prop_assert_eq!(boundary_distance_sq4(&sources, outside), brute(&sources, outside, true));
            prop_assert_eq!(center_distance_sq(&sources), brute(&sources, false, false));
        }
    }

    #[test]
    fn boundary_distance_of_a_single_obstacle() {
        let mut s = Grid::new(5, 5, false);
        s[crate::Cell::new(2, 2)] = true;
        let d = boundary_distance_sq4(&s, false);
        assert_eq!(d[crate::Cell::new(2, 2)], 0);
        assert_eq!(d[crate::Cell::new(2, 3)], 1); // 0.5 cell
        assert_eq!(d[crate::Cell::new(3, 3)], 2); // (0.5, 0.5)
        assert_eq!(d[crate::Cell::new(2, 4)], 9); // 1.5 cells
        assert_eq!(center_distance_sq(&s)[crate::Cell::new(0, 0)], 8);
    }
}
