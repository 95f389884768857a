//! Tests of the Reeb graph: intervals on their slices, repeats merged,
//! splits and merges making cells.

use super::*;

const IN_CONVEX: CriticalKind = CriticalKind {
    event: Event::In,
    convexity: Convexity::Convex,
};
const OUT_CONVEX: CriticalKind = CriticalKind {
    event: Event::Out,
    convexity: Convexity::Convex,
};

#[test]
fn intervals_match_on_their_slice_only() {
    let mut r = Reeb::default();
    let a = r.interval(0, Point::new(0.0, 0.2), Point::new(0.0, 3.0));
    assert_eq!(
        r.interval(0, Point::new(0.0, 2.9), Point::new(0.0, 0.25)),
        a
    );
    assert_ne!(r.interval(1, Point::new(0.5, 0.2), Point::new(0.5, 3.0)), a);
    // Another interval of the same slice, past an obstacle.
    assert_ne!(r.interval(0, Point::new(0.0, 3.5), Point::new(0.0, 5.0)), a);
    assert_eq!(r.intervals.len(), 3);
}

#[test]
fn repeats_merge_and_walls_along_y_are_one_point() {
    let mut r = Reeb::default();
    let a = r.critical(
        Point::new(1.0, 1.0),
        Point::new(0.76, 1.0),
        (1.0, 1.0),
        IN_CONVEX,
        true,
        0.01,
    );
    assert_eq!(
        r.critical(
            Point::new(1.02, 1.01),
            Point::new(0.78, 1.01),
            (1.01, 1.01),
            IN_CONVEX,
            true,
            0.01
        ),
        a
    );
    // One wall along y found at two heights: the same critical stretch.
    let w = r.critical(
        Point::new(5.0, 1.0),
        Point::new(4.76, 1.0),
        (0.5, 2.0),
        OUT_CONVEX,
        true,
        0.01,
    );
    assert_eq!(
        r.critical(
            Point::new(5.0, 1.8),
            Point::new(4.765, 1.8),
            (1.5, 2.5),
            OUT_CONVEX,
            true,
            0.01
        ),
        w
    );
    // Facing walls of a narrow gap at nearly the same x stay apart.
    assert_ne!(
        r.critical(
            Point::new(5.5, 1.5),
            Point::new(4.77, 1.5),
            (1.0, 2.0),
            CriticalKind {
                convexity: Convexity::Concave,
                ..OUT_CONVEX
            },
            true,
            0.01
        ),
        w
    );
    assert_eq!(r.criticals.len(), 3);
}

#[test]
fn a_split_and_a_merge_make_four_cells() {
    // Slices 0 to 3 and an obstacle from x = 1.5 to 2.5, laid out by
    // hand: slab 0–1 plain, slab 1–2 holds the split (one interval on
    // slice 1, two on slice 2), slab 2–3 the merge.
    let mut r = Reeb::default();
    let i0 = r.interval(0, Point::new(0.0, 0.0), Point::new(0.0, 4.0));
    let i1 = r.interval(1, Point::new(1.0, 0.0), Point::new(1.0, 4.0));
    let lo2 = r.interval(2, Point::new(2.0, 0.0), Point::new(2.0, 1.5));
    let hi2 = r.interval(2, Point::new(2.0, 2.5), Point::new(2.0, 4.0));
    let i3 = r.interval(3, Point::new(3.0, 0.0), Point::new(3.0, 4.0));
    let split = r.critical(
        Point::new(1.5, 2.0),
        Point::new(1.26, 2.0),
        (2.0, 2.0),
        IN_CONVEX,
        true,
        0.01,
    );
    let merge = r.critical(
        Point::new(2.5, 2.0),
        Point::new(2.74, 2.0),
        (2.0, 2.0),
        OUT_CONVEX,
        true,
        0.01,
    );
    let slab = |left, intervals: Vec<usize>, criticals: Vec<usize>| SlabRecord {
        left,
        x: (f64::from(left as i32), f64::from(left as i32 + 1)),
        boundary: Vec::new(),
        intervals,
        criticals,
    };
    r.slabs = vec![
        slab(0, vec![i0, i1], vec![]),
        slab(1, vec![i1, lo2, hi2], vec![split]),
        slab(2, vec![lo2, hi2, i3], vec![merge]),
    ];
    for iv in &mut r.intervals {
        iv.done = [true; 2];
    }
    let g = r.graph();
    assert_eq!(g.edges.len(), 4);
    let ends: Vec<_> = g
        .edges
        .iter()
        .map(|e| (e.from, e.to, e.laps.len()))
        .collect();
    assert!(ends.contains(&(None, Some(split), 2)));
    assert_eq!(
        ends.iter()
            .filter(|e| **e == (Some(split), Some(merge), 1))
            .count(),
        2
    );
    assert!(ends.contains(&(Some(merge), None, 1)));
    assert!(g.edges.iter().all(|e| e.covered));
}

#[test]
fn two_merges_between_the_same_slices_are_joined_by_a_lapless_cell() {
    // A C opening to +x whose arms end at x = 7.1 (upper) and 7.2
    // (lower), both between slices 7.0 and 7.5: above the C, its pocket
    // and below it enter the slab; one cell leaves it.
    let mut r = Reeb::default();
    let above = r.interval(14, Point::new(7.0, 7.6), Point::new(7.0, 9.8));
    let pocket = r.interval(14, Point::new(7.0, 4.5), Point::new(7.0, 5.6));
    let below = r.interval(14, Point::new(7.0, 0.2), Point::new(7.0, 2.5));
    let after = r.interval(15, Point::new(7.5, 0.2), Point::new(7.5, 9.8));
    let upper = r.critical(
        Point::new(7.1, 6.0),
        Point::new(7.34, 6.0),
        (6.0, 6.0),
        OUT_CONVEX,
        true,
        0.01,
    );
    let lower = r.critical(
        Point::new(7.2, 4.0),
        Point::new(7.44, 4.0),
        (4.0, 4.0),
        OUT_CONVEX,
        true,
        0.01,
    );
    r.slabs.push(SlabRecord {
        left: 14,
        x: (7.0, 7.5),
        boundary: Vec::new(),
        intervals: vec![above, pocket, below, after],
        criticals: vec![upper, lower],
    });
    let g = r.graph();
    let ends = |iv: usize| {
        let lap = (r.intervals[iv].lo, r.intervals[iv].hi);
        let e = g
            .edges
            .iter()
            .find(|e| e.laps.contains(&lap))
            .expect("a cell");
        (e.from, e.to)
    };
    assert_eq!(ends(above).1, Some(upper));
    assert_eq!(ends(pocket).1, Some(upper));
    assert_eq!(ends(below).1, Some(lower));
    assert_eq!(ends(after).0, Some(lower));
    let short: Vec<_> = g.edges.iter().filter(|e| e.laps.is_empty()).collect();
    assert_eq!(short.len(), 1);
    assert_eq!((short[0].from, short[0].to), (Some(upper), Some(lower)));
    // Four cells with laps and the lap-less one.
    assert_eq!(g.edges.len(), 5);
}
