//! How a segmentation is scored against ground-truth rooms, as the ipa
//! benchmark's survey scores it (Bormann et al. 2016;
//! `../shared/maps/ipa-rooms/SOURCE.md`).
//!
//! Over the pixels free in the plan that lie in a ground-truth room (the
//! domain): recall, for each ground-truth room, the largest share of it in
//! one segment (mean over rooms); precision, for each segment, the largest
//! share of it in one room (mean over the segments that meet the domain);
//! IoU, for each room, the best intersection over union with one segment
//! (mean over rooms).

use std::collections::BTreeMap;

use oxcover_grid::Grid;

/// A segmentation's scores on one plan.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Score {
    /// Mean over ground-truth rooms of the largest share in one segment.
    pub recall: f64,
    /// Mean over segments of the largest share in one room.
    pub precision: f64,
    /// Mean over ground-truth rooms of the best IoU with one segment.
    pub iou: f64,
    /// Ground-truth rooms.
    pub rooms: usize,
    /// Segments that meet the domain.
    pub segments: usize,
}

/// The scores of `segments` (0: no segment) against `truth` (0: no room),
/// over the cells where `free` is set and `truth` is not 0. The grids are
/// of one size.
///
/// # Panics
/// When the grids differ in size.
#[must_use]
pub fn score(truth: &Grid<u32>, segments: &Grid<u32>, free: &Grid<bool>) -> Score {
    assert_eq!(
        (truth.width(), truth.height()),
        (segments.width(), segments.height())
    );
    assert_eq!(
        (truth.width(), truth.height()),
        (free.width(), free.height())
    );
    let mut joint: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    let mut room_size: BTreeMap<u32, usize> = BTreeMap::new();
    let mut seg_size: BTreeMap<u32, usize> = BTreeMap::new();
    for ((&t, &s), &f) in truth
        .as_slice()
        .iter()
        .zip(segments.as_slice())
        .zip(free.as_slice())
    {
        if !f || t == 0 {
            continue;
        }
        *joint.entry((t, s)).or_default() += 1;
        *room_size.entry(t).or_default() += 1;
        *seg_size.entry(s).or_default() += 1;
    }
    let mut best_room: BTreeMap<u32, (usize, f64)> = BTreeMap::new();
    let mut best_seg: BTreeMap<u32, usize> = BTreeMap::new();
    for (&(t, s), &n) in &joint {
        let union = room_size[&t] + seg_size[&s] - n;
        let iou = n as f64 / union as f64;
        let e = best_room.entry(t).or_insert((0, 0.0));
        e.0 = e.0.max(n);
        e.1 = e.1.max(iou);
        let b = best_seg.entry(s).or_insert(0);
        *b = (*b).max(n);
    }
    let rooms = room_size.len();
    let segments = seg_size.len();
    if rooms == 0 {
        return Score::default();
    }
    let recall = best_room
        .iter()
        .map(|(t, (n, _))| *n as f64 / room_size[t] as f64)
        .sum::<f64>()
        / rooms as f64;
    let iou = best_room.values().map(|(_, i)| i).sum::<f64>() / rooms as f64;
    let precision = best_seg
        .iter()
        .map(|(s, n)| *n as f64 / seg_size[s] as f64)
        .sum::<f64>()
        / segments.max(1) as f64;
    Score {
        recall,
        precision,
        iou,
        rooms,
        segments,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::Cell;

    /// Two rooms side by side, 4 × 2 each.
    fn truth() -> Grid<u32> {
        Grid::from_fn(8, 2, |c: Cell| if c.col < 4 { 1 } else { 2 })
    }

    #[test]
    fn the_truth_scores_one() {
        let free = Grid::new(8, 2, true);
        let s = score(&truth(), &truth(), &free);
        assert_eq!((s.recall, s.precision, s.iou), (1.0, 1.0, 1.0));
        assert_eq!((s.rooms, s.segments), (2, 2));
    }

    /// One segment for the whole floor: recall 1, precision and IoU a half.
    #[test]
    fn one_segment_has_full_recall_and_half_the_rest() {
        let free = Grid::new(8, 2, true);
        let s = score(&truth(), &Grid::new(8, 2, 7), &free);
        assert_eq!((s.recall, s.precision, s.iou), (1.0, 0.5, 0.5));
    }

    /// Each room cut in two halves: recall and IoU a half, precision 1;
    /// cells outside the domain (not free, or no room) count for nothing.
    #[test]
    fn halves_have_full_precision() {
        let mut free = Grid::new(8, 2, true);
        let mut t = truth();
        let seg = Grid::from_fn(8, 2, |c: Cell| c.col as u32 / 2 + 1);
        free[Cell::new(0, 0)] = false;
        free[Cell::new(1, 0)] = false;
        t[Cell::new(0, 1)] = 0;
        t[Cell::new(1, 1)] = 0;
        let s = score(&t, &seg, &free);
        // Room 1 keeps only its cells of segment 2; room 2 is halved.
        assert_eq!(s.rooms, 2);
        assert!((s.recall - 0.75).abs() < 1e-12, "{s:?}");
        assert!((s.precision - 1.0).abs() < 1e-12, "{s:?}");
        assert!((s.iou - 0.75).abs() < 1e-12, "{s:?}");
    }
}
