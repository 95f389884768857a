//! Tests of detours and tightening: hand-drawn cases, and properties against
//! the contract's own sampler.

use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear, segment_distance};
use oxcover_grid::{Cell, Grid, Vector};

use super::geometry::Linked;
use super::reach::{
    Capsule, SAMPLE_GAP, for_stroke_cells, near_pieces, pieces_reaching, sample_reaches,
};
use super::tighten::{PARALLEL_PASS, ROUNDS, lost_cell};
use super::*;
use oxcover_grid::footprint::for_each_sample;
use proptest::prelude::*;

fn mask(rows: &[&str]) -> Grid<bool> {
    oxcover_grid::io::ascii_mask(rows).expect("valid map")
}

/// [`tighten_from`] moving every vertex: the path and the number of
/// vertices removed or moved.
fn tighten(points: &[GridPoint], d: &Detours<'_>, count: Grid<u16>) -> (Vec<GridPoint>, usize) {
    let (points, _, changes) = tighten_from(points, d, count, 0, None, || ()).0;
    (points, changes)
}

fn time() -> TimeModel {
    TimeModel {
        linear_speed: 6.0,
        angular_speed: 0.52,
    }
}

/// Detours reaching 1 cell (no fragile margin) within `search` cells,
/// at [`time`]'s speeds.
fn reach_one<'a>(plannable: &'a Grid<bool>, coverable: &'a Grid<bool>, search: f64) -> Detours<'a> {
    Detours {
        plannable,
        coverable,
        reach: 1.0,
        fragile: 0.0,
        search,
        time: time(),
    }
}

/// Cells within `r` of one of the contract's samples of `pts`.
fn sampled(w: usize, h: usize, pts: &[GridPoint], r: f64) -> Grid<bool> {
    let mut g = Grid::new(w, h, false);
    for_each_sample(pts, 0.25, |p| {
        for c in Grid::<bool>::new(w, h, false).cells() {
            if (cell_center(c) - p).norm() <= r {
                g[c] = true;
            }
        }
    });
    g
}

#[test]
fn linked_insertions_keep_order() {
    let pts: Vec<GridPoint> = (0..4).map(|i| GridPoint::new(f64::from(i), 0.0)).collect();
    let mut l = Linked::new(&pts);
    let id = l.insert_after(1, GridPoint::new(1.5, 1.0));
    l.insert_after(id, GridPoint::new(1.7, 1.0));
    l.insert_after(0, GridPoint::new(0.5, 1.0));
    let xs: Vec<f64> = l.points().iter().map(|p| p.x).collect();
    assert_eq!(xs, vec![0.0, 0.5, 1.0, 1.5, 1.7, 2.0, 3.0]);
}

/// A lane along the middle of a room three rows wide, reach one cell:
/// the row below is covered, the nook above the lane's middle is not;
/// one V detour reaches it, the lane's ends stay where they were.
#[test]
fn a_nook_gets_one_v_detour() {
    let plannable = mask(&[
        "##########.##########",
        ".....................",
        ".....................",
    ]);
    let coverable = plannable.clone();
    let path = vec![GridPoint::new(0.5, 2.0), GridPoint::new(20.5, 2.0)];
    let d = reach_one(&plannable, &coverable, 2.0);
    let (out, _) = insert_detours(&path, &d);
    assert_eq!(out.len(), path.len() + 3, "one V: {out:?}");
    assert_eq!(out.first(), path.first());
    assert_eq!(out.last(), path.last());
    // The nook (row 0, column 10) is within reach of a sample now.
    let covered = sampled(21, 3, &out, 1.0);
    assert!(covered[Cell::new(0, 10)], "{out:?}");
    // Nothing the lane covered is lost.
    let before = sampled(21, 3, &path, 1.0);
    for c in before.true_cells() {
        assert!(covered[c], "{c:?} lost: {out:?}");
    }
    // Short and gentle: less than half a turn added in all.
    let turned: f64 = out
        .windows(3)
        .map(|w| heading_change(w[1] - w[0], w[2] - w[1]))
        .sum();
    assert!(turned < std::f64::consts::FRAC_PI_2, "{turned}: {out:?}");
}

/// A lane along a corridor's middle row, reach one cell, beside a bay
/// two rows deep: the bay's far row is bent into first, and the bend
/// reaches the near row on its way, so each stretch of the bay costs
/// one detour, not one per row; nothing is left and nothing lost.
#[test]
fn a_bay_is_bent_into_from_its_far_side() {
    let plannable = mask(&[
        "....................",
        "....................",
        "....................",
        "#######....#########",
        "#######....#########",
    ]);
    // The row beyond the lane needs no cover: the lane may bend away.
    let coverable = Grid::from_fn(20, 5, |c| c.row > 0 && plannable[c]);
    let path = vec![GridPoint::new(0.5, 1.5), GridPoint::new(19.5, 1.5)];
    let d = reach_one(&plannable, &coverable, 4.0);
    let (out, _) = insert_detours(&path, &d);
    let covered = sampled(20, 5, &out, 1.0);
    for c in coverable.true_cells() {
        assert!(covered[c], "{c:?} missed: {out:?}");
    }
    // The first bend goes a reach short of the far row (4): its vertex
    // lies in row 3, not in row 2 (a reach short of the near row).
    assert!(out[2].y > 3.0, "{out:?}");
    // Fewer new vertices than the bay has cells (row-major order, the
    // near row first, took 10 here).
    assert!(out.len() - path.len() < 8, "{out:?}");
}

/// A free 10 × 4 field where only the cell in row 2, column 5 (centre
/// (5.5, 2.5)) is to be covered.
fn one_cell_to_cover() -> (Grid<bool>, Grid<bool>) {
    let plannable = mask(&["..........", "..........", "..........", ".........."]);
    let mut coverable = Grid::new(10, 4, false);
    coverable[Cell::new(2, 5)] = true;
    (plannable, coverable)
}

/// A path along row 0 bent down to `y` in column 5.
fn bent_at(y: f64) -> Vec<GridPoint> {
    vec![
        GridPoint::new(0.5, 0.5),
        GridPoint::new(5.5, y),
        GridPoint::new(9.5, 0.5),
    ]
}

/// A cell the path reaches only a little beyond `reach` (as the
/// metrics may count it, by rounding) is kept within reach of
/// `reach + fragile` by tightening; with no such margin the vertex that
/// reaches it goes.
#[test]
fn a_cell_just_beyond_reach_is_kept_when_fragile() {
    let (plannable, coverable) = one_cell_to_cover();
    // The middle vertex is 1.05 from the cell's centre (5.5, 2.5).
    let path = bent_at(1.45);
    let tightened = |fragile: f64| {
        let d = Detours {
            fragile,
            ..reach_one(&plannable, &coverable, 2.0)
        };
        tighten(&path, &d, reach_counts(&path, &d)).0
    };
    let near = |pts: &[GridPoint]| {
        pts.windows(2)
            .map(|w| segment_distance(w[0], w[1], GridPoint::new(5.5, 2.5)))
            .fold(f64::INFINITY, f64::min)
    };
    assert!(near(&tightened(0.0)) > 1.1);
    let kept = tightened(0.1);
    assert!(near(&kept) <= 1.1, "{kept:?}");
}

/// A zone keeps a vertex in its label's cells: a vertex that tightening
/// moves towards its neighbours' line, across a label border, when
/// free, stays on its own side when zoned.
#[test]
fn a_zone_keeps_a_vertex_in_its_room() {
    let (plannable, coverable) = one_cell_to_cover();
    // Rows 0 and 1 are room 1, rows 2 and 3 room 2.
    let labels = Grid::from_fn(10, 4, |c| if c.row < 2 { 1u32 } else { 2 });
    let path = bent_at(3.5);
    let d = reach_one(&plannable, &coverable, 2.0);
    let room_of = |p: GridPoint| labels[cell_of(&labels, p).unwrap()];
    let (moved, kept, _) = tighten_from(&path, &d, reach_counts(&path, &d), 0, None, || ()).0;
    assert_eq!(kept, vec![0, 1, 2]);
    assert_eq!(room_of(moved[1]), 1, "{moved:?}");
    let of_vertex = [0, 2, 0];
    let zone = Zone {
        labels: &labels,
        of_vertex: &of_vertex,
    };
    let (zoned, kept, _) =
        tighten_from(&path, &d, reach_counts(&path, &d), 0, Some(&zone), || ()).0;
    assert_eq!(kept, vec![0, 1, 2]);
    assert_eq!(room_of(zoned[1]), 2, "{zoned:?}");
    // Still moved up as far as its room allows, and faster than before.
    assert!(zoned[1].y < 2.5, "{zoned:?}");
    assert!(polyline_time(&zoned, &d.time) < polyline_time(&path, &d.time));
}

/// A cell no clear detour reaches is left as it is.
#[test]
fn an_unreachable_cell_is_left() {
    let plannable = mask(&[".....", "#####", "....."]);
    let mut coverable = plannable.clone();
    coverable[Cell::new(2, 2)] = true;
    let path = vec![GridPoint::new(0.5, 0.5), GridPoint::new(4.5, 0.5)];
    let d = reach_one(&plannable, &coverable, 3.0);
    let (out, _) = insert_detours(&path, &d);
    assert_eq!(out, path);
}

/// Pass by pass, a tightening ends where [`tighten_from`] does, in at
/// most [`ROUNDS`] passes, and then runs no more.
#[test]
fn a_tightening_pass_by_pass_is_tighten_from() {
    let plannable = mask(&["...................."; 6]);
    let coverable = plannable.clone();
    let path: Vec<GridPoint> = (0..40)
        .map(|i| {
            let (row, col) = (i / 20, i % 20);
            let col = if row == 0 { col } else { 19 - col };
            let y = 1.5 + 3.0 * row as f64 + if i % 2 == 0 { 0.3 } else { -0.3 };
            GridPoint::new(col as f64 + 0.5, y)
        })
        .collect();
    let d = reach_one(&plannable, &coverable, 2.0);
    let whole = tighten_from(&path, &d, reach_counts(&path, &d), 0, None, || ()).0;
    let mut t = Tightening::new(&path, reach_counts(&path, &d), 0);
    let mut passes = 0;
    while t.pass(&d, None) {
        passes += 1;
    }
    assert!(passes > 0 && passes <= ROUNDS, "{passes}");
    assert!(!t.pass(&d, None));
    assert_eq!(t.finish(), whole);
}

/// A zigzag through an open room where only the middle row must be
/// covered: tightened to (nearly) the straight line, still covering it.
#[test]
fn a_zigzag_is_tightened() {
    let plannable = mask(&[
        "....................",
        "....................",
        "....................",
    ]);
    let mut coverable = Grid::new(20, 3, false);
    for col in 0..20 {
        coverable[Cell::new(1, col)] = true;
    }
    let path: Vec<GridPoint> = (0..20)
        .map(|i| GridPoint::new(f64::from(i) + 0.5, if i % 2 == 0 { 1.1 } else { 1.9 }))
        .collect();
    let d = reach_one(&plannable, &coverable, 2.0);
    let (out, n) = tighten(&path, &d, reach_counts(&path, &d));
    assert!(n > 0);
    let covered = sampled(20, 3, &out, 1.0);
    for col in 0..20 {
        assert!(covered[Cell::new(1, col)], "{col}: {out:?}");
    }
    let before = polyline_time(&path, &d.time);
    let after = polyline_time(&out, &d.time);
    assert!(after < 0.5 * before, "{before} -> {after}: {out:?}");
}

/// Cells of a `w × h` grid within `r` of one of the contract's samples
/// of `pts` (as [`sampled`], looking only near each sample).
fn sampled_near(w: usize, h: usize, pts: &[GridPoint], r: f64) -> Grid<bool> {
    let mut g = Grid::new(w, h, false);
    for_each_sample(pts, 0.25, |p| {
        let rows = ((p.y - r - 1.0).max(0.0) as usize)..((p.y + r + 1.0).max(0.0) as usize).min(h);
        for row in rows {
            let cols =
                ((p.x - r - 1.0).max(0.0) as usize)..((p.x + r + 1.0).max(0.0) as usize).min(w);
            for col in cols {
                let c = Cell::new(row, col);
                if (cell_center(c) - p).norm() <= r {
                    g[c] = true;
                }
            }
        }
    });
    g
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    /// A pass long enough to be split into bands of rows: the path is
    /// the same whatever the thread count, every cell the path reached
    /// is still reached, and it is faster.
    #[test]
    fn a_banded_pass_keeps_coverage_and_ignores_the_thread_count(
        jitter in prop::collection::vec(-0.45..0.45f64, 64),
    ) {
        // An open room; a serpentine along every other row, a vertex
        // at every cell, each jittered across its row.
        let (w, h) = (40, 60);
        let plannable = Grid::new(w, h, true);
        let coverable = plannable.clone();
        let mut path = Vec::new();
        for (k, row) in (1..h - 1).step_by(2).enumerate() {
            let cols: Vec<usize> = if k % 2 == 0 {
                (1..w - 1).collect()
            } else {
                (1..w - 1).rev().collect()
            };
            for col in cols {
                let j = jitter[(row * 7 + col) % jitter.len()];
                path.push(GridPoint::new(col as f64 + 0.5, row as f64 + 0.5 + j));
            }
        }
        prop_assert!(path.len() > PARALLEL_PASS + 2);
        let d = reach_one(&plannable, &coverable, 2.0);
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| tighten(&path, &d, reach_counts(&path, &d)))
        };
        let (out, n) = on(1);
        prop_assert_eq!(&on(3).0, &out);
        prop_assert!(n > 0);
        let (before, after) = (sampled_near(w, h, &path, 1.0), sampled_near(w, h, &out, 1.0));
        for c in before.true_cells() {
            prop_assert!(after[c], "{:?} lost", c);
        }
        prop_assert!(polyline_time(&out, &d.time) < polyline_time(&path, &d.time));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The row-by-row stroke visits exactly the cells a scan of the
    /// whole grid finds reached, each once.
    #[test]
    fn stroke_rows_match_a_whole_grid_scan(
        ax in -2.0..22.0f64, ay in -2.0..18.0f64, bx in -2.0..22.0f64, by in -2.0..18.0f64,
        r in 0.3..4.0f64, flat in 0usize..3,
    ) {
        // Some segments exactly horizontal or vertical.
        let b = match flat {
            0 => GridPoint::new(bx, ay),
            1 => GridPoint::new(ax, by),
            _ => GridPoint::new(bx, by),
        };
        let a = GridPoint::new(ax, ay);
        let (w, h) = (20usize, 16usize);
        let mut seen = Grid::new(w, h, 0u8);
        for_stroke_cells(a, b, r, w, h, |i, c| {
            assert_eq!(i, c.row * w + c.col);
            seen[c] += 1;
        });
        for c in seen.cells() {
            let q = cell_center(c);
            let gap = segment_distance(a, b, q);
            let reached = gap <= r - SAMPLE_GAP || (gap <= r && sample_reaches(a, b, q, r));
            prop_assert_eq!(seen[c], u8::from(reached), "{:?}", c);
        }
    }

    /// `near_pieces` never claims a point beyond `r` of every piece,
    /// and finds every point clearly within; a lost cell is found
    /// whichever cell is tried first.
    #[test]
    fn near_pieces_is_sound_and_lost_cells_do_not_depend_on_the_order(
        u in (0.0..20.0f64, 0.0..20.0f64), m in (0.0..20.0f64, 0.0..20.0f64),
        x in (0.0..20.0f64, 0.0..20.0f64), r in 0.5..6.0f64, first in 0usize..400,
    ) {
        let (u, m, x) = (
            GridPoint::new(u.0, u.1),
            GridPoint::new(m.0, m.1),
            GridPoint::new(x.0, x.1),
        );
        let cells: Vec<GridPoint> = (0..400)
            .map(|i| cell_center(Cell::new(i / 20, i % 20)))
            .collect();
        for &q in &cells {
            let d = segment_distance(u, m, q).min(segment_distance(m, x, q));
            let near = near_pieces(u, &[m], x, q, r);
            prop_assert!(!near || d <= r, "{:?} at {}", q, d);
            prop_assert!(near || d > r * (1.0 - 1e-9), "{:?} at {}", q, d);
        }
        let lost = lost_cell(&cells, first, u, &[m], x, r);
        prop_assert_eq!(lost.is_some(), lost_cell(&cells, 0, u, &[m], x, r).is_some());
        if let Some(k) = lost {
            prop_assert_eq!(pieces_reaching(u, &[m], x, cells[k], r), 0);
        }
    }

    /// The capsule's spans are, to the bit, those worked out one
    /// radius and row at a time.
    #[test]
    fn capsule_spans_match_the_one_at_a_time_span(
        ax in -2.0..22.0f64, ay in -2.0..18.0f64, bx in -2.0..22.0f64, by in -2.0..18.0f64,
        r in 0.3..6.0f64, gap in 0.0..0.5f64, kind in 0usize..4,
    ) {
        // Some segments horizontal, vertical, nearly so, or a point.
        let b = match kind {
            0 => GridPoint::new(bx, ay),
            1 => GridPoint::new(ax, by),
            2 => GridPoint::new(ax, ay),
            _ => GridPoint::new(bx, by),
        };
        let a = GridPoint::new(ax, ay);
        let capsule = Capsule::new(a, b);
        for row in -3..22 {
            let y = f64::from(row) + 0.5;
            let sure = r - gap;
            let [span, inner] = capsule.spans(y, r, Some(sure));
            prop_assert_eq!(span, capsule_span(a, b, r, y));
            prop_assert_eq!(inner, capsule_span(a, b, sure, y));
            prop_assert_eq!(capsule.spans(y, r, None)[1], None);
        }
    }

    /// The sample test agrees with the contract's sampler.
    #[test]
    fn sample_reaches_matches_the_sampler(
        ax in 0.0..20.0f64, ay in 0.0..20.0f64, bx in 0.0..20.0f64, by in 0.0..20.0f64,
        qx in 0.0..20.0f64, qy in 0.0..20.0f64, r in 0.3..4.0f64,
    ) {
        let (a, b, q) = (GridPoint::new(ax, ay), GridPoint::new(bx, by), GridPoint::new(qx, qy));
        let mut near = f64::INFINITY;
        for_each_sample(&[a, b], 0.25, |p| near = near.min((p - q).norm()));
        // Away from the boundary case, both agree.
        prop_assume!((near - r).abs() > 1e-9);
        prop_assert_eq!(sample_reaches(a, b, q, r), near <= r);
    }

    /// On random rooms with specks, detours keep the path clear, its
    /// ends, and everything it covered; they only add coverage.
    #[test]
    fn detours_only_add_coverage(seed in 0u64..1_000, reach in 1.0..3.0f64) {
        let (w, h) = (24usize, 16usize);
        let mut rng = seed;
        let mut next = || {
            rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (rng >> 33) as usize
        };
        let mut plannable = Grid::new(w, h, true);
        for _ in 0..12 {
            let c = Cell::new(next() % h, next() % w);
            plannable[c] = false;
        }
        // Lanes along rows 2, 6, 10, 14 where clear, joined by straight links.
        let mut path: Vec<GridPoint> = Vec::new();
        for (k, row) in [2usize, 6, 10, 14].into_iter().enumerate() {
            let y = row as f64 + 0.5;
            let (x0, x1) = if k % 2 == 0 { (0.5, w as f64 - 0.5) } else { (w as f64 - 0.5, 0.5) };
            path.push(GridPoint::new(x0, y));
            path.push(GridPoint::new(x1, y));
        }
        // Keep the clear prefix.
        let mut clear = vec![path[0]];
        for p in path.iter().skip(1) {
            if cell_of(&plannable, *p).is_none_or(|c| !plannable[c])
                || !segment_clear(&plannable, clear[clear.len() - 1], *p)
            {
                break;
            }
            clear.push(*p);
        }
        prop_assume!(clear.len() >= 2 && cell_of(&plannable, clear[0]).is_some_and(|c| plannable[c]));
        let coverable = Grid::new(w, h, true);
        let d = Detours { plannable: &plannable, coverable: &coverable, reach, fragile: 0.0, search: 2.0 * reach, time: time() };
        let (detoured, count) = insert_detours(&clear, &d);
        let (out, _) = tighten(&detoured, &d, count);
        prop_assert_eq!(out.first(), clear.first());
        prop_assert_eq!(out.last(), clear.last());
        for s in out.windows(2) {
            prop_assert!(segment_clear(&plannable, s[0], s[1]), "{:?}", s);
        }
        let before = sampled(w, h, &clear, reach);
        let after = sampled(w, h, &out, reach);
        for c in before.true_cells() {
            prop_assert!(after[c], "{:?} lost", c);
        }
        prop_assert!(after.count_true() >= before.count_true());
    }
}
/// The x extent of the points of the line at height `y` within `r` of the
/// segment `a → b` (the reference for [`Capsule::spans`], for tests).
fn capsule_span(a: GridPoint, b: GridPoint, r: f64, y: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for p in [a, b] {
        let dy = y - p.y;
        if dy.abs() <= r {
            let s = (r * r - dy * dy).sqrt();
            lo = lo.min(p.x - s);
            hi = hi.max(p.x + s);
        }
    }
    let ab = b - a;
    let len = ab.norm();
    if len > 0.0 {
        let n = Vector::new(-ab.y, ab.x) / len;
        let (mut u0, mut u1) = (-r, r);
        if ab.y.abs() < 1e-12 {
            if (y - a.y).abs() <= r {
                lo = lo.min(a.x.min(b.x));
                hi = hi.max(a.x.max(b.x));
            }
        } else {
            let (k, m) = ((y - a.y) / ab.y, n.y / ab.y);
            if m.abs() < 1e-12 {
                if !(0.0..=1.0).contains(&k) {
                    u1 = u0 - 1.0;
                }
            } else {
                let (ua, ub) = (k / m, (k - 1.0) / m);
                u0 = u0.max(ua.min(ub));
                u1 = u1.min(ua.max(ub));
            }
            if u0 <= u1 {
                for u in [u0, u1] {
                    let t = k - m * u;
                    let x = a.x + t * ab.x + u * n.x;
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The heading change is `atan2`'s angle between the two directions, to
/// the bit, also where it answers straight on, square and back without it.
#[test]
fn heading_change_is_the_angle_between() {
    let dirs = [-3.0, -1.0, -0.5, 0.0, 0.25, 1.0, 2.0, 1e-13];
    for &ux in &dirs {
        for &uy in &dirs {
            for &vx in &dirs {
                for &vy in &dirs {
                    let (u, v) = (Vector::new(ux, uy), Vector::new(vx, vy));
                    let want = if u.norm() < 1e-12 || v.norm() < 1e-12 {
                        0.0
                    } else {
                        (u.x * v.y - u.y * v.x).atan2(u.x * v.x + u.y * v.y).abs()
                    };
                    assert_eq!(
                        heading_change(u, v).to_bits(),
                        want.to_bits(),
                        "{u:?} {v:?}"
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// A long path's reach counts, found in bands of rows in parallel, are
    /// those its segments' strokes add one by one, on any thread count.
    #[test]
    fn banded_reach_counts_are_the_strokes(seed in 0u64..1_000, reach in 0.5..9.0f64) {
        let (w, h) = (90usize, 300usize);
        let mut rng = seed;
        let mut next = |n: f64| {
            rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (rng >> 11) as f64 / (1u64 << 53) as f64 * n
        };
        // A random walk folded back into the grid and 10 cells round it.
        let fold = |v: f64, n: usize| (v + 10.0).rem_euclid(n as f64 + 20.0) - 10.0;
        let mut p = GridPoint::new(next(w as f64), next(h as f64));
        let mut path = vec![p];
        for _ in 0..400 {
            let step = Vector::new(next(40.0) - 20.0, next(40.0) - 20.0);
            p = GridPoint::new(fold(p.x + step.x, w), fold(p.y + step.y, h));
            path.push(p);
        }
        prop_assert!(path.iter().filter(|q| q.x > 0.0 && q.x < w as f64 && q.y > 0.0 && q.y < h as f64).count() > 200);
        let plannable = Grid::new(w, h, true);
        let mut d = reach_one(&plannable, &plannable, 2.0);
        d.reach = reach;
        let mut want = Grid::new(w, h, 0u16);
        for s in path.windows(2) {
            for_stroke_cells(s[0], s[1], reach, w, h, |i, _| want.as_mut_slice()[i] += 1);
        }
        for threads in [1, 3] {
            let got = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| reach_counts(&path, &d));
            prop_assert!(got == want, "{} threads", threads);
        }
    }
}
