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
//! Both are separable: a column pass (distance to the nearest source in the
//! column), then a row pass computing `D(x) = min_q G(q) + h(x − q)` by the
//! lower envelope of parabolas (Felzenszwalb & Huttenlocher), with the
//! crossing of two parabolas in closed form: O(n) per line. A line's own
//! sources split it (our addition, not in the paper): no candidate beyond
//! the nearest source on either side can win, so each run between two
//! sources takes the envelope of its own cells and those two, and runs of
//! sources are skipped (most of a map's obstacle area).
//!
//! The boundary kernel is not a parabola, but for `x ≠ q` it is one in the
//! doubled coordinate: `h(x − q) = (2x − e)²` with `e = 2q ± 1` the edge of
//! cell `q` facing `x` (the far edge only ever gives a larger value). So the
//! row pass runs a parabola envelope over the cell edges `e = 2i − 1`, each
//! with the smaller `G` of the two cells it separates, evaluated at `2x`, and
//! takes `G(x)` itself where smaller (`h(0) = 0`).
//!
//! Where only "is a source within `limit`?" is asked (admissibility, the
//! coverable cells, the lane mask), [`boundary_within_sq4`] and
//! [`center_within_sq`] answer it exactly without the distances beyond:
//! the column pass counts rows only up to the limit, and the row pass
//! compares those counts, column offset by column offset, with the most
//! each offset allows, over the few columns within reach instead of an
//! envelope (our addition, not in the paper; beyond 32 cells along an
//! axis the full transform is thresholded).
//!
//! Each pass runs in parallel (rayon): the column pass by stripes of
//! columns, the row pass by blocks of rows. Every value is computed as a
//! single-threaded pass would compute it, so the result does not depend on
//! the thread count.

use rayon::prelude::*;

use crate::grid::Grid;

/// Marker for "no source on this line / in the grid".
pub const INFINITE: u64 = u64::MAX;

/// `4·d²` from each cell centre to the nearest source cell's boundary (0 on sources).
///
/// When `outside_is_source` is set, the area outside the grid counts as sources
/// (the map edge is a wall). Cells with no source at all get [`INFINITE`].
#[must_use]
pub fn boundary_distance_sq4(sources: &Grid<bool>, outside_is_source: bool) -> Grid<u64> {
    transform(sources, outside_is_source, Kernel::Boundary)
}

/// `d²` (cells²) from each cell centre to the nearest source cell centre.
///
/// Cells with no source at all get [`INFINITE`].
#[must_use]
pub fn center_distance_sq(sources: &Grid<bool>) -> Grid<u64> {
    transform(sources, false, Kernel::Center)
}

/// `true` where [`boundary_distance_sq4`] is at most `limit`, found
/// without working out the distances beyond it: where the nearest source
/// lies within the limit it lies within a few columns, so each cell looks
/// at those only (beyond 32 cells along an axis, the full transform is
/// thresholded).
#[must_use]
pub fn boundary_within_sq4(
    sources: &Grid<bool>,
    outside_is_source: bool,
    limit: u64,
) -> Grid<bool> {
    within(sources, outside_is_source, Kernel::Boundary, limit)
}

/// `true` where [`center_distance_sq`] is at most `limit`, found without
/// working out the distances beyond it (as [`boundary_within_sq4`]).
#[must_use]
pub fn center_within_sq(sources: &Grid<bool>, limit: u64) -> Grid<bool> {
    within(sources, false, Kernel::Center, limit)
}

/// Widest reach (cells along an axis) [`within`] looks at cell by cell;
/// beyond, the full transform is thresholded.
const WINDOW_MAX: i64 = 32;

/// Whether the distance (`kernel`'s) to the nearest source is at most
/// `limit`, cell by cell. A source within the limit is at most `K` cells
/// away along either axis, `K` the largest `k` with `h(k) ≤ limit`, so the
/// column pass need only count rows up to `K` (small integers, capped),
/// and each cell of the row pass look at the `2K + 1` columns round it
/// instead of a line's whole envelope: within the limit where, for some
/// column `q`, `h(rows) + h(x − q) ≤ limit`, that is where `rows` is at
/// most the largest count `q`'s offset allows (the same sum of a column
/// and a row term as [`transform`]'s, over fewer columns: where the
/// nearest source lies within the limit, it lies among them).
fn within(sources: &Grid<bool>, outside: bool, kernel: Kernel, limit: u64) -> Grid<bool> {
    let (w, hgt) = (sources.width(), sources.height());
    let mut reach = 0i64;
    while reach <= WINDOW_MAX && kernel.h(reach + 1) <= limit {
        reach += 1;
    }
    if reach > WINDOW_MAX {
        return transform(sources, outside, kernel).map(|&d| d <= limit);
    }
    if w == 0 || hgt == 0 {
        return Grid::new(w, hgt, false);
    }
    let src = sources.as_slice();
    // Rows to the nearest source in the column, `K + 1` where none lies
    // within `K` rows (or none at all).
    let cap = reach as u16 + 1;
    let stripes = capped_stripes(src, (w, hgt), outside, cap);
    // For each offset `j` in `0..=2K` of the window (column `x + j − K`),
    // the most rows `d` away a source there may lie: the largest `d` with
    // `h(d) + h(j − K) ≤ limit` (offsets whose `h` alone is beyond the
    // limit are left out).
    let most: Vec<(usize, u16)> = (-reach..=reach)
        .enumerate()
        .filter_map(|(j, k)| {
            let t = kernel.h(k);
            (t <= limit).then(|| {
                let mut d = 0;
                while d < reach && kernel.h(d + 1) + t <= limit {
                    d += 1;
                }
                (j, d as u16)
            })
        })
        .collect();
    let pad = reach as usize + 1;
    let mut out = vec![false; w * hgt];
    out.par_chunks_mut(w * ROWS).enumerate().for_each_init(
        || {
            // Beyond the grid: the frame of outside sources, then nothing.
            let mut line = vec![cap; w + 2 * pad];
            if outside {
                line[pad - 1] = 0;
                line[pad + w] = 0;
            }
            line
        },
        |line, (block, out)| {
            for (i, out) in out.chunks_mut(w).enumerate() {
                let r = block * ROWS + i;
                row_of(&stripes, w, r, &mut line[pad..pad + w]);
                // (A row with no source within reach at all: none.)
                if line.iter().all(|&d| d == cap) {
                    continue;
                }
                // Offset by offset over the whole row: compares of small
                // integers that vectorise.
                for &(j, most) in &most {
                    for (o, &d) in out.iter_mut().zip(&line[j + 1..j + 1 + w]) {
                        *o |= d <= most;
                    }
                }
            }
        },
    );
    Grid::from_vec(w, hgt, out).unwrap_or_else(|| Grid::new(w, hgt, false))
}

/// The per-axis kernel `h`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kernel {
    /// `h(k) = max(0, 2|k| − 1)²`: centre to the boundary of a cell.
    Boundary,
    /// `h(k) = k²`: centre to centre.
    Center,
}

impl Kernel {
    fn h(self, k: i64) -> u64 {
        let k = k.unsigned_abs();
        match self {
            Self::Boundary => (2 * k).saturating_sub(1).pow(2),
            Self::Center => k * k,
        }
    }
}

/// Columns per task of the column pass.
const STRIPE: usize = 256;
/// Rows per task of the row pass.
const ROWS: usize = 32;

fn transform(sources: &Grid<bool>, outside: bool, kernel: Kernel) -> Grid<u64> {
    let (w, hgt) = (sources.width(), sources.height());
    if w == 0 || hgt == 0 {
        return Grid::new(w, hgt, INFINITE);
    }
    let src = sources.as_slice();
    // Column pass, in stripes of columns side by side: each stripe's
    // values row-major within the stripe.
    // (One closure per kernel, so that each pass is compiled for its own.)
    let stripes = match kernel {
        Kernel::Boundary => {
            column_stripes(src, (w, hgt), outside, INFINITE, |k| Kernel::Boundary.h(k))
        }
        Kernel::Center => column_stripes(src, (w, hgt), outside, INFINITE, |k| Kernel::Center.h(k)),
    };
    // Row pass, blocks of rows side by side, on lines padded with a wall
    // column each side when the outside is a source.
    let pad = usize::from(outside);
    let m = w + 2 * pad;
    // (Every value is written by the row pass: zeroed memory, which the
    // allocator need not fill.)
    let mut g = vec![0; w * hgt];
    g.par_chunks_mut(w * ROWS).enumerate().for_each_init(
        || (Envelope::default(), vec![0u64; m]),
        |(env, line), (block, out)| {
            for (i, out) in out.chunks_mut(w).enumerate() {
                let r = block * ROWS + i;
                row_of(&stripes, w, r, &mut line[pad..pad + w]);
                row_pass(env, line, pad, kernel, out);
            }
        },
    );
    Grid::from_vec(w, hgt, g).unwrap_or_else(|| Grid::new(w, hgt, INFINITE))
}

/// The column pass in stripes of [`STRIPE`] columns side by side, each
/// stripe's values row-major within the stripe ([`column_pass`]).
fn column_stripes<V: Copy + Ord + Send + Sync>(
    src: &[bool],
    (w, hgt): (usize, usize),
    outside: bool,
    none: V,
    h: impl Fn(i64) -> V + Sync,
) -> Vec<Vec<V>> {
    (0..w.div_ceil(STRIPE))
        .into_par_iter()
        .map(|k| {
            let cols = k * STRIPE..((k + 1) * STRIPE).min(w);
            column_pass(src, (w, hgt), cols, outside, (none, &h))
        })
        .collect()
}

/// The column pass of [`within`] in stripes of [`STRIPE`] columns side by
/// side (row-major within a stripe): the rows from each cell to the
/// nearest source in its column, `cap` where none lies within `cap − 1`
/// rows; with `outside`, the rows above and below the grid are sources.
/// Row by row down, then up, every column of the stripe at once.
fn capped_stripes(
    src: &[bool],
    (w, hgt): (usize, usize),
    outside: bool,
    cap: u16,
) -> Vec<Vec<u16>> {
    let edge = if outside { 0 } else { cap };
    (0..w.div_ceil(STRIPE))
        .into_par_iter()
        .map(|k| {
            let cols = k * STRIPE..((k + 1) * STRIPE).min(w);
            let sw = cols.len();
            let mut g = Vec::with_capacity(sw * hgt);
            let mut run = vec![edge; sw];
            for r in 0..hgt {
                let row = &src[r * w + cols.start..r * w + cols.end];
                for (d, &source) in run.iter_mut().zip(row) {
                    *d = if source { 0 } else { (*d + 1).min(cap) };
                }
                g.extend_from_slice(&run);
            }
            run.fill(edge);
            for r in (0..hgt).rev() {
                let row = &src[r * w + cols.start..r * w + cols.end];
                let out = &mut g[r * sw..(r + 1) * sw];
                for ((d, &source), o) in run.iter_mut().zip(row).zip(out) {
                    *d = if source { 0 } else { (*d + 1).min(cap) };
                    *o = (*o).min(*d);
                }
            }
            g
        })
        .collect()
}

/// Row `r` of the column pass, gathered from its `stripes` into `line`
/// (`w` values).
fn row_of<V: Copy>(stripes: &[Vec<V>], w: usize, r: usize, line: &mut [V]) {
    for (k, stripe) in stripes.iter().enumerate() {
        let c0 = k * STRIPE;
        let sw = (w - c0).min(STRIPE);
        line[c0..c0 + sw].copy_from_slice(&stripe[r * sw..(r + 1) * sw]);
    }
}

/// The column pass over `cols`: `h` of the distance to the nearest source
/// in the column (row-major within the stripe), `none` where there is
/// none. `h` is monotone in |k|, so the nearest source row gives the
/// minimum; rows are walked in memory order, every column of the stripe
/// at once.
fn column_pass<V: Copy + Ord>(
    src: &[bool],
    (w, hgt): (usize, usize),
    cols: std::ops::Range<usize>,
    outside: bool,
    (none_value, h): (V, impl Fn(i64) -> V),
) -> Vec<V> {
    let sw = cols.len();
    // (Row by row appended: the values are written once, not filled
    // first.)
    let mut g = Vec::with_capacity(sw * hgt);
    let none = if outside { -1 } else { i64::MIN };
    let mut last = vec![none; sw];
    for r in 0..hgt {
        let row = &src[r * w + cols.start..r * w + cols.end];
        g.extend(row.iter().zip(last.iter_mut()).map(|(&source, last)| {
            if source {
                *last = r as i64;
            }
            if *last == i64::MIN {
                none_value
            } else {
                h(r as i64 - *last)
            }
        }));
    }
    let none = if outside { hgt as i64 } else { i64::MIN };
    let next = &mut last;
    next.fill(none);
    for r in (0..hgt).rev() {
        let (row, out) = (
            &src[r * w + cols.start..r * w + cols.end],
            &mut g[r * sw..(r + 1) * sw],
        );
        for c in 0..sw {
            if row[c] {
                next[c] = r as i64;
            }
            if next[c] != i64::MIN {
                out[c] = out[c].min(h(next[c] - r as i64));
            }
        }
    }
    g
}

/// The row pass over one padded `line` of column-pass values, into `out`
/// (zeroed: the sources' values).
///
/// A source in the line itself (value 0) splits it: between two sources
/// `s1 < x < s2`, every candidate left of `s1` (or right of `s2`) is
/// further than `s1` (`s2`) with no smaller value, so each run of
/// non-source cells takes the envelope of its own cells and the sources
/// that bound it, and the sources are 0. The same values as one envelope
/// over the line, in a fraction of the work where sources are many.
fn row_pass(env: &mut Envelope, line: &[u64], pad: usize, kernel: Kernel, out: &mut [u64]) {
    let m = line.len();
    let mut a = 0;
    while a < m {
        if line[a] == 0 {
            // (A run of sources: 0, as `out` holds already.)
            a = line[a..].iter().position(|&v| v != 0).map_or(m, |n| a + n);
            continue;
        }
        let b = line[a..].iter().position(|&v| v == 0).map_or(m, |n| a + n);
        // Candidates: the run `a..b` and the sources either side of it.
        let (lo, hi) = (a.saturating_sub(1), (b + 1).min(m));
        run_pass(env, line, (lo, hi), kernel);
        for (xp, &v) in line.iter().enumerate().take(b).skip(a) {
            let Some(o) = xp.checked_sub(pad).and_then(|x| out.get_mut(x)) else {
                continue;
            };
            *o = if kernel == Kernel::Boundary {
                v.min(env.eval(2 * xp as i64))
            } else {
                env.eval(xp as i64)
            };
        }
        a = b;
    }
}

/// Builds `env` over the candidates `lo..hi` of `line`: for the boundary
/// kernel the cell edges `lo..=hi` (edge `i`, doubled coordinate `2i − 1`,
/// between cells `i − 1` and `i`, with the smaller value of the two), for
/// the centre kernel the cells.
fn run_pass(env: &mut Envelope, line: &[u64], (lo, hi): (usize, usize), kernel: Kernel) {
    if kernel == Kernel::Boundary {
        env.build((lo..=hi).map(|i| {
            let left = if i > 0 { line[i - 1] } else { INFINITE };
            let right = line.get(i).copied().unwrap_or(INFINITE);
            (2 * i as i64 - 1, left.min(right))
        }));
    } else {
        env.build((lo..hi).map(|q| (q as i64, line[q])));
    }
}

/// Lower envelope of the parabolas `v + (x − c)²` of one line.
#[derive(Default)]
struct Envelope {
    /// Parabolas `(c, v)` of the envelope, left to right.
    v: Vec<(i64, u64)>,
    /// Where each starts to be the lowest.
    z: Vec<f64>,
    /// Evaluation cursor.
    k: usize,
}

impl Envelope {
    /// Builds the envelope of `(c, v)` with increasing `c` (infinite `v` skipped).
    fn build(&mut self, parabolas: impl Iterator<Item = (i64, u64)>) {
        self.v.clear();
        self.z.clear();
        self.k = 0;
        for (c, v) in parabolas {
            if v == INFINITE {
                continue;
            }
            let key = v as i64 + c * c;
            loop {
                let Some(&(pc, pv)) = self.v.last() else {
                    self.v.push((c, v));
                    self.z.push(f64::NEG_INFINITY);
                    break;
                };
                // Crossing of the two parabolas.
                let s = (key - (pv as i64 + pc * pc)) as f64 / (2 * (c - pc)) as f64;
                if s <= *self.z.last().unwrap_or(&f64::NEG_INFINITY) {
                    self.v.pop();
                    self.z.pop();
                    continue;
                }
                self.v.push((c, v));
                self.z.push(s);
                break;
            }
        }
    }

    /// The envelope at `x`; calls must come with non-decreasing `x`.
    fn eval(&mut self, x: i64) -> u64 {
        if self.v.is_empty() {
            return INFINITE;
        }
        while self.k + 1 < self.v.len() && self.z[self.k + 1] <= x as f64 {
            self.k += 1;
        }
        let (c, v) = self.v[self.k];
        v + (x - c).unsigned_abs().pow(2)
    }
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

    proptest! {
        /// The thresholded transforms are the full ones compared with the
        /// limit, for limits within the window and beyond it.
        #[test]
        fn within_is_the_transform_thresholded(
            w in 1usize..40,
            h in 1usize..40,
            seed in any::<u64>(),
            density in 0.0f64..0.3,
            outside in any::<bool>(),
            limit in prop_oneof![0u64..200, 4000u64..5000],
        ) {
            let sources = crate::random::random_density(w, h, density, seed)
                .free_mask()
                .map(|f| !f);
            let b = boundary_distance_sq4(&sources, outside).map(|&d| d <= limit);
            prop_assert_eq!(boundary_within_sq4(&sources, outside, limit), b);
            let c = center_distance_sq(&sources).map(|&d| d <= limit);
            prop_assert_eq!(center_within_sq(&sources, limit), c);
        }
    }

    /// Thresholded across the passes' stripes and row blocks.
    #[test]
    fn within_across_stripes_and_row_blocks() {
        let (w, h) = (2 * STRIPE + 37, 2 * ROWS + 5);
        let sources = crate::random::random_density(w, h, 0.002, 5)
            .free_mask()
            .map(|f| !f);
        for limit in [0, 1, 9, 37, 144, 400] {
            for outside in [false, true] {
                let b = boundary_distance_sq4(&sources, outside).map(|&d| d <= limit);
                assert_eq!(boundary_within_sq4(&sources, outside, limit), b);
            }
            let c = center_distance_sq(&sources).map(|&d| d <= limit);
            assert_eq!(center_within_sq(&sources, limit), c);
        }
    }

    #[test]
    fn matches_brute_force_on_a_larger_grid() {
        // Long lines, where envelopes hold many parabolas.
        let sources = crate::random::random_density(61, 47, 0.02, 7)
            .free_mask()
            .map(|f| !f);
        for outside in [false, true] {
            assert_eq!(
                boundary_distance_sq4(&sources, outside),
                brute(&sources, outside, true)
            );
        }
        assert_eq!(center_distance_sq(&sources), brute(&sources, false, false));
    }

    /// Brute force over a list of sources (and the frame round the grid
    /// when the outside is a source).
    fn sparse_brute(sources: &Grid<bool>, outside: bool, boundary: bool) -> Grid<u64> {
        let h = |k: i64| -> u64 {
            let k = k.unsigned_abs();
            if boundary {
                (2 * k).saturating_sub(1).pow(2)
            } else {
                k * k
            }
        };
        let (w, hh) = (sources.width() as i64, sources.height() as i64);
        let mut list: Vec<(i64, i64)> = sources
            .true_cells()
            .map(|c| (c.row as i64, c.col as i64))
            .collect();
        if outside {
            list.extend((-1..=w).flat_map(|c| [(-1, c), (hh, c)]));
            list.extend((0..hh).flat_map(|r| [(r, -1), (r, w)]));
        }
        Grid::from_fn(sources.width(), sources.height(), |c| {
            list.iter()
                .map(|&(r, col)| h(c.row as i64 - r) + h(c.col as i64 - col))
                .min()
                .unwrap_or(INFINITE)
        })
    }

    /// A grid of several column stripes and row blocks (the passes' tasks).
    #[test]
    fn matches_brute_force_across_stripes_and_row_blocks() {
        let (w, h) = (2 * STRIPE + 37, 2 * ROWS + 5);
        let mut s = 11u64;
        let sources = Grid::from_fn(w, h, |_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) % 500 == 0
        });
        assert!(sources.count_true() > 10);
        for outside in [false, true] {
            assert_eq!(
                boundary_distance_sq4(&sources, outside),
                sparse_brute(&sources, outside, true)
            );
        }
        assert_eq!(
            center_distance_sq(&sources),
            sparse_brute(&sources, false, false)
        );
        let none = Grid::new(w, h, false);
        assert_eq!(center_distance_sq(&none), Grid::new(w, h, INFINITE));
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
