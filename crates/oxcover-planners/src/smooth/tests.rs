//! Tests of `smooth`: an exact path on a tiny room, rings one lane apart,
//! the loop shaping, and the item index.

use oxcover_grid::Grid;
use oxcover_grid::traverse::GridPoint;

use super::Item;
use super::order::ItemIndex;
use super::rings::{resample_loop, simplify_loop, smooth_loop};
use super::*;
use oxcover_grid::traverse::segment_clear;

/// The plan on an ASCII map with `block`-cell coverage cells, its path in
/// grid coordinates, and the plannable mask.
fn plan(text: &str, block: usize) -> (SmoothPlan, Vec<GridPoint>, Grid<bool>) {
    let p = crate::testing::problem(text, block);
    let plan = Smooth::new().plan_detailed(&p.input(0)).unwrap();
    let h = p.plannable().height() as f64;
    let pts = plan
        .points
        .iter()
        .map(|q| GridPoint::new(q.x, h - q.y))
        .collect();
    (plan, pts, p.plannable().clone())
}

/// Exact path on a tiny map: unit cells, a reach of half a cell, so
/// lanes one cell apart. Ring 0 is the border through the cell centres
/// (entered at the start, driven once round in the contour's own
/// direction, the robot having no heading yet); ring 1 is the centre
/// cell alone, a degenerate contour the completion visits.
#[test]
fn three_by_three_room_exact() {
    let (p, pts, m) = plan("S..\n...\n...", 1);
    for w in pts.windows(2) {
        assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
    }
    let kinds: Vec<Behaviour> = p.pieces.iter().map(|q| q.behaviour).collect();
    assert_eq!(kinds, [Behaviour::WallFollowing, Behaviour::Transit]);
    assert_eq!(
        pts,
        [
            GridPoint::new(0.5, 0.5),
            GridPoint::new(0.5, 2.5),
            GridPoint::new(2.5, 2.5),
            GridPoint::new(2.5, 0.5),
            GridPoint::new(0.5, 0.5),
            GridPoint::new(1.5, 1.5),
        ]
    );
}

#[test]
fn rings_nest_one_lane_apart_in_an_open_room() {
    // 30 x 20 free cells, tool 3 cells: reach 2.64, lanes 5.28 apart.
    let rows = [".............................."; 20].join("\n");
    let text = format!("S{}", &rows[1..]);
    let (p, pts, m) = plan(&text, 6);
    assert!(p.rings.0 >= 2, "{:?}", p.rings);
    // The first ring runs along the walls through the border cells'
    // centres, its corners rounded within the margin (0.36 cells here).
    let first = p
        .pieces
        .iter()
        .find(|q| q.behaviour == Behaviour::WallFollowing)
        .copied()
        .unwrap();
    assert!(
        pts[first.start..=first.end]
            .iter()
            .all(|q| q.x.min(q.y).min(30.0 - q.x).min(20.0 - q.y)
                < 0.5 + 0.36 * std::f64::consts::SQRT_2 + 0.1),
        "{:?}",
        &pts[first.start..=first.end]
    );
    for w in pts.windows(2) {
        assert!(
            crate::metre_path::segment_clearance(&m, w[0], w[1], CLEARANCE - 1e-9),
            "{w:?}"
        );
    }
    // PSO never made a fillet slower than its start.
    assert!(
        p.fillet_time.1 <= p.fillet_time.0 + 1e-9,
        "{:?}",
        p.fillet_time
    );
}

#[test]
fn loops_resample_smooth_and_simplify() {
    let square: Vec<GridPoint> = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]
        .iter()
        .map(|&(x, y)| GridPoint::new(x, y))
        .collect();
    let dense = resample_loop(&square, 1.0);
    assert_eq!(dense.len(), 40);
    // Corners stay, sides stay straight, and thinning gives the square back.
    let smooth = smooth_loop(&dense, 3);
    assert!(smooth.contains(&GridPoint::new(10.0, 10.0)));
    let thin = simplify_loop(&smooth, 0.05);
    assert_eq!(thin.len(), 4, "{thin:?}");
}

#[test]
fn buckets_find_the_nearest_live_item() {
    let items = vec![
        Item {
            points: vec![GridPoint::new(1.0, 1.0)],
            closed: false,
            level: usize::MAX,
            reps: Vec::new(),
        },
        Item {
            points: vec![GridPoint::new(30.0, 30.0), GridPoint::new(31.0, 30.0)],
            closed: true,
            level: 0,
            reps: Vec::new(),
        },
    ];
    let mut b = ItemIndex::new(40, 40, 4);
    b.insert(items[0].points[0], 0, 0);
    b.insert(items[1].points[0], 1, 0);
    b.insert(items[1].points[1], 1, 1);
    assert_eq!(
        b.nearest(GridPoint::new(2.0, 2.0), &[false, false], &items),
        Some((0, 0))
    );
    assert_eq!(
        b.nearest(GridPoint::new(2.0, 2.0), &[true, false], &items),
        Some((1, 0))
    );
    assert_eq!(
        b.nearest(GridPoint::new(39.0, 30.0), &[false, false], &items),
        Some((1, 1))
    );
    assert_eq!(
        b.nearest(GridPoint::new(2.0, 2.0), &[true, true], &items),
        None
    );
}
