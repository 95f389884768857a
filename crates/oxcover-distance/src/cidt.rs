//! Constrained inverse distance transform, CIDT (Lee et al. 2011).
//!
//! A wavefront from the robot that stops as soon as no cell of the current front
//! can beat the best target found so far, instead of labelling the whole map.
//! With unit moves the first layer holding a target is the last one needed: the
//! wave finishes that layer (so all equally near targets are seen, for a
//! deterministic tie-break) and stops. The labels stay in the [`Wavefront`], so
//! [`Wavefront::retrace`] gives the path to the chosen target. Cost O(cells
//! within the target distance), against O(all cells) for a full transform.

use oxcover_grid::Cell;

use crate::lee::Wavefront;

/// The result of a nearest-target search.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Nearest {
    /// Distance (moves) to the nearest targets.
    pub distance: u32,
    /// Every target at that distance, in row-major order.
    pub targets: Vec<Cell>,
    /// Cells the wave labelled.
    pub touched: usize,
}

impl Nearest {
    /// The first target in row-major order.
    #[must_use]
    pub fn first(&self) -> Cell {
        self.targets[0]
    }
}

/// Nearest cells (from any of `sources`) for which `is_target` holds, or `None`
/// when no reachable cell is a target.
pub fn cidt(
    wavefront: &mut Wavefront,
    sources: &[Cell],
    mut is_target: impl FnMut(Cell) -> bool,
) -> Option<Nearest> {
    let mut found: Option<(u32, Vec<Cell>)> = None;
    wavefront.run(sources, u32::MAX, |layer, d| {
        let mut hits: Vec<Cell> = layer.cells().filter(|&c| is_target(c)).collect();
        if hits.is_empty() {
            return false;
        }
        hits.sort_unstable();
        found = Some((d, hits));
        true
    });
    let touched = wavefront.touched();
    found.map(|(distance, targets)| Nearest {
        distance,
        targets,
        touched,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bfs_distances;
    use oxcover_grid::Grid;
    use oxcover_grid::random::random_density;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn same_distance_as_full_bfs(w in 2usize..48, h in 2usize..48, density in 0.0f64..0.45, seed in any::<u64>(), target_density in 0.0f64..0.1) {
            let free = random_density(w, h, density, seed).free_mask();
            let targets = random_density(w, h, 1.0 - target_density, seed ^ 0x5eed).free_mask().map(|f| !f);
            let Some(src) = free.true_cells().next() else { return Ok(()); };
            let full = bfs_distances(&free, src);
            let want = free.cells().filter(|&c| targets[c]).filter_map(|c| full[c]).min();
            let mut wf = Wavefront::new(&free);
            let got = cidt(&mut wf, &[src], |c| targets[c]);
            prop_assert_eq!(got.as_ref().map(|n| n.distance), want);
            if let Some(n) = got {
                prop_assert!(n.targets.iter().all(|&t| targets[t] && full[t] == Some(n.distance)));
                prop_assert!(n.touched <= free.count_true());
                let p = wf.retrace(n.first()).unwrap();
                prop_assert_eq!(p.len() as u32, n.distance + 1);
            }
        }
    }

    #[test]
    fn source_on_a_target_is_distance_zero() {
        let free = Grid::new(4, 4, true);
        let mut wf = Wavefront::new(&free);
        let n = cidt(&mut wf, &[Cell::new(1, 1)], |_| true).unwrap();
        assert_eq!(
            (n.distance, n.targets.clone(), n.touched),
            (0, vec![Cell::new(1, 1)], 1)
        );
        assert!(cidt(&mut wf, &[Cell::new(1, 1)], |_| false).is_none());
    }
}
