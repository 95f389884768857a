//! 4-connected components and the reachable set from a start.
//!
//! Components by row runs: each row's runs found in parallel, runs that
//! overlap the row above joined in a union-find over runs, labels numbered
//! in row-major order of each component's first cell, rows filled in
//! parallel. The reachable set by a flood fill with an explicit stack of
//! row runs (each run filled at once, one seed per run beside it). Both
//! O(cells), no recursion.

use crate::grid::{Cell, Grid};

/// Component labelling of a mask.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Components {
    /// 0 outside the mask, else the 1-based component number.
    pub labels: Grid<u32>,
    /// `sizes[i]` = cells in component `i + 1`.
    pub sizes: Vec<usize>,
}

impl Components {
    /// Number of components.
    #[must_use]
    pub fn count(&self) -> usize {
        self.sizes.len()
    }

    /// The first cell (row-major) of component `label`, if it has one.
    #[must_use]
    pub fn first_cell(&self, label: u32) -> Option<Cell> {
        let i = self.labels.as_slice().iter().position(|&l| l == label)?;
        Some(self.labels.cell_of(i))
    }

    /// The 1-based label of the largest component (first on ties), if any.
    #[must_use]
    pub fn largest(&self) -> Option<u32> {
        let mut best: Option<(usize, u32)> = None;
        for (i, &s) in self.sizes.iter().enumerate() {
            if best.is_none_or(|(b, _)| s > b) {
                best = Some((s, i as u32 + 1));
            }
        }
        best.map(|(_, l)| l)
    }
}

/// Labels the 4-connected components of the `true` cells, numbered from 1
/// in row-major order of their first cells (by row runs joined in a
/// union-find, as the module's page says).
#[must_use]
pub fn components4(mask: &Grid<bool>) -> Components {
    label_runs(mask, None)
}

/// Labels the 4-connected components of the `true` cells of `mask` whose
/// cells all share one `class` (two neighbours of different classes are
/// not connected), numbered from 1 in row-major order of their first
/// cells, as [`components4`].
///
/// # Panics
/// If `class` is not the size of `mask` (read by index).
#[must_use]
pub fn components4_by_class(mask: &Grid<bool>, class: &Grid<u32>) -> Components {
    assert_eq!(
        (mask.width(), mask.height()),
        (class.width(), class.height()),
        "classes must cover the mask cell for cell"
    );
    label_runs(mask, Some(class.as_slice()))
}

/// Components by row runs: each row's runs of set cells (of one class)
/// found in parallel, runs that overlap a run of the row above (of the
/// same class) joined in a union-find whose root is always the set's first
/// run (so the first in row-major order, which holds the component's
/// first cell), labels given to the roots in run order, and the rows
/// filled in parallel. The same labels whatever the thread count.
fn label_runs(mask: &Grid<bool>, class: Option<&[u32]>) -> Components {
    use rayon::prelude::*;
    let (w, h) = (mask.width(), mask.height());
    let mut labels = Grid::new(w, h, 0u32);
    if w == 0 || h == 0 {
        return Components {
            labels,
            sizes: Vec::new(),
        };
    }
    let set = mask.as_slice();
    let class_at = |i: usize| class.map_or(0, |k| k[i]);
    // Each row's runs: (first column, end column, class).
    let rows: Vec<Vec<(usize, usize, u32)>> = (0..h)
        .into_par_iter()
        .map(|r| {
            let row = &set[r * w..(r + 1) * w];
            let mut runs = Vec::new();
            let mut c = 0;
            while c < w {
                if !row[c] {
                    c += 1;
                    continue;
                }
                let k = class_at(r * w + c);
                let start = c;
                while c < w && row[c] && class_at(r * w + c) == k {
                    c += 1;
                }
                runs.push((start, c, k));
            }
            runs
        })
        .collect();
    let mut first = Vec::with_capacity(h + 1);
    first.push(0);
    for runs in &rows {
        first.push(first[first.len() - 1] + runs.len());
    }
    let all: Vec<(usize, usize, u32)> = rows.iter().flatten().copied().collect();
    // Union-find over the runs, the smaller index the root.
    let mut parent: Vec<usize> = (0..all.len()).collect();
    let find = |parent: &mut Vec<usize>, mut x: usize| {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    };
    for r in 1..h {
        let (above, here) = (first[r - 1]..first[r], first[r]..first[r + 1]);
        let (mut i, mut j) = (above.start, here.start);
        while i < above.end && j < here.end {
            let (a, b) = (all[i], all[j]);
            if a.0 < b.1 && b.0 < a.1 && a.2 == b.2 {
                let (ra, rb) = (find(&mut parent, i), find(&mut parent, j));
                let (lo, hi) = (ra.min(rb), ra.max(rb));
                parent[hi] = lo;
            }
            // The run that ends first meets nothing further on.
            if a.1 <= b.1 {
                i += 1;
            } else {
                j += 1;
            }
        }
    }
    // Labels in run order (row-major order of first cells), sizes.
    let mut label_of = vec![0u32; all.len()];
    let mut sizes: Vec<usize> = Vec::new();
    for i in 0..all.len() {
        let root = find(&mut parent, i);
        if root == i {
            sizes.push(0);
            label_of[i] = sizes.len() as u32;
        } else {
            label_of[i] = label_of[root];
        }
        sizes[label_of[i] as usize - 1] += all[i].1 - all[i].0;
    }
    labels
        .as_mut_slice()
        .par_chunks_mut(w)
        .enumerate()
        .for_each(|(r, row)| {
            for i in first[r]..first[r + 1] {
                let (a, b, _) = all[i];
                row[a..b].fill(label_of[i]);
            }
        });
    Components { labels, sizes }
}

/// Cells of `mask` 4-connected to `start` (empty if `start` is not in the mask).
#[must_use]
pub fn reachable(mask: &Grid<bool>, start: Cell) -> Grid<bool> {
    let mut out = Grid::new(mask.width(), mask.height(), false);
    if mask.is_set(start) {
        let first = mask.index_of(start);
        fill_runs(
            (mask.width(), mask.height()),
            |i| mask.as_slice()[i],
            first,
            (out.as_mut_slice(), false, true),
            &mut Vec::new(),
        );
    }
    out
}

/// Sets to `value` every cell of `ids` (row-major, `w × h`) that is
/// 4-connected to the cell `start` through cells `set` takes in (by
/// index) whose `ids` are `blank`, a row's run at a time (one seed per
/// run beside a filled one, above and below; `stack` is scratch).
/// Returns how many cells it set.
fn fill_runs<T: Copy + PartialEq>(
    (w, h): (usize, usize),
    set: impl Fn(usize) -> bool,
    start: usize,
    (ids, blank, value): (&mut [T], T, T),
    stack: &mut Vec<(usize, usize)>,
) -> usize {
    let mut size = 0;
    stack.clear();
    stack.push((start / w, start % w));
    while let Some((r, c)) = stack.pop() {
        let row = r * w;
        if ids[row + c] != blank {
            continue;
        }
        // The seed's whole run of blank cells along its row.
        let open = |k: usize| set(row + k) && ids[row + k] == blank;
        let (mut a, mut b) = (c, c);
        while a > 0 && open(a - 1) {
            a -= 1;
        }
        while b + 1 < w && open(b + 1) {
            b += 1;
        }
        ids[row + a..=row + b].fill(value);
        size += b - a + 1;
        for next in [r.checked_sub(1), Some(r + 1).filter(|&n| n < h)]
            .into_iter()
            .flatten()
        {
            let nrow = next * w;
            let open = |k: usize| set(nrow + k) && ids[nrow + k] == blank;
            let mut k = a;
            while k <= b {
                if open(k) {
                    stack.push((next, k));
                    while k <= b && open(k) {
                        k += 1;
                    }
                } else {
                    k += 1;
                }
            }
        }
    }
    size
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::parse_ascii;

    #[test]
    fn labels_components_in_scan_order() {
        let (m, _) = parse_ascii(
            "
            ..#.
            ###.
            .#..",
        )
        .unwrap();
        let c = components4(&m.free_mask());
        assert_eq!(c.sizes, vec![2, 4, 1]);
        assert_eq!(c.largest(), Some(2));
        assert_eq!(c.first_cell(2), Some(Cell::new(0, 3)));
        assert_eq!(c.first_cell(3), Some(Cell::new(2, 0)));
        assert_eq!(c.first_cell(4), None);
        let r = reachable(&m.free_mask(), Cell::new(0, 3));
        assert_eq!(r.count_true(), 4);
        assert_eq!(reachable(&m.free_mask(), Cell::new(1, 0)).count_true(), 0);
    }

    /// Components by a plain flood from each unlabelled cell in turn.
    fn flooded(mask: &Grid<bool>) -> Components {
        flooded_by_class(mask, &Grid::new(mask.width(), mask.height(), 0))
    }

    /// The same, neighbours joined only within one class.
    fn flooded_by_class(mask: &Grid<bool>, class: &Grid<u32>) -> Components {
        let mut labels = Grid::new(mask.width(), mask.height(), 0u32);
        let mut sizes = Vec::new();
        for c in mask.true_cells() {
            if labels[c] != 0 {
                continue;
            }
            let label = sizes.len() as u32 + 1;
            let mut stack = vec![c];
            labels[c] = label;
            let mut size = 0;
            while let Some(x) = stack.pop() {
                size += 1;
                for (_, n) in mask.neighbours4(x) {
                    if mask[n] && labels[n] == 0 && class[n] == class[x] {
                        labels[n] = label;
                        stack.push(n);
                    }
                }
            }
            sizes.push(size);
        }
        Components { labels, sizes }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// Run by run, the same labels and sizes as a plain flood (mazes of
        /// runs: a seed pushed twice, runs that reach past the one above).
        #[test]
        fn runs_label_as_a_plain_flood_does(seed in 0u64..1000, density in 0.0f64..0.7, w in 1usize..40, h in 1usize..30) {
            let mask = crate::random::random_density(w, h, density, seed).free_mask();
            let runs = components4(&mask);
            let flood = flooded(&mask);
            proptest::prop_assert_eq!(&runs.labels, &flood.labels);
            proptest::prop_assert_eq!(runs.sizes, flood.sizes);
        }

        /// By class, the same as a plain flood that joins neighbours of one
        /// class only (classes in vertical bands and noise).
        #[test]
        fn classes_label_as_a_plain_flood_does(seed in 0u64..1000, density in 0.0f64..0.5, bands in 1usize..6, noise in 0.0f64..0.2) {
            let (w, h) = (31, 19);
            let mask = crate::random::random_density(w, h, density, seed).free_mask();
            let specks = crate::random::random_density(w, h, noise, seed ^ 1).free_mask();
            let class = Grid::from_fn(w, h, |c| {
                (c.col * bands / w) as u32 + u32::from(!specks[c]) * 7
            });
            let runs = components4_by_class(&mask, &class);
            let flood = flooded_by_class(&mask, &class);
            proptest::prop_assert_eq!(&runs.labels, &flood.labels);
            proptest::prop_assert_eq!(runs.sizes, flood.sizes);
        }

        /// The reachable set is the start's component.
        #[test]
        fn reachable_is_the_starts_component(seed in 0u64..1000, density in 0.0f64..0.6, at in 0usize..(23 * 17)) {
            let free = crate::random::random_density(23, 17, density, seed).free_mask();
            let start = Cell::new(at / 23, at % 23);
            let comps = components4(&free);
            let own = comps.labels[start];
            let expected = Grid::from_fn(23, 17, |c| own != 0 && comps.labels[c] == own);
            proptest::prop_assert_eq!(reachable(&free, start), expected);
        }
    }
}
