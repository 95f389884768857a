//! Iso-contours of a scalar field sampled at cell centres (marching squares).
//!
//! The field is read at the centres of the grid's cells, `(col + ½, row + ½)`
//! in grid coordinates, and padded with `outside` beyond the grid, so every
//! contour is a closed loop. A sample is *inside* when its value is at least
//! the level. Each unit square between four neighbouring centres adds a
//! segment per inside/outside separation, its ends linearly interpolated on
//! the square's edges; a saddle square (inside on one diagonal only) is
//! resolved by the mean of its four corners. Segments are linked through the
//! edges they share into loops that keep the inside on their right in the
//! `(x, y)` plane of grid coordinates: a loop around an inside region has a
//! negative signed area (on a screen, rows downwards, it runs anticlockwise).
//!
//! [`iso_contours`] extracts several levels in one pass over the squares:
//! O(cells + contour points) whatever the number of levels.

use std::collections::HashMap;

use crate::grid::Grid;
use crate::traverse::GridPoint;

/// A closed iso-contour: its points in order, the first not repeated at the end.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// Index of its level in the levels asked for.
    pub level: usize,
    /// The loop's points (grid coordinates).
    pub points: Vec<GridPoint>,
}

/// The closed contours of `field` at each of `levels` (ascending), with
/// `outside` as the value beyond the grid. Contours come level by level, each
/// level's in the order of their first square (row-major), so the result is
/// deterministic.
///
/// # Panics
/// If `levels` is not strictly ascending or holds a NaN.
#[must_use]
pub fn iso_contours(field: &Grid<f64>, levels: &[f64], outside: f64) -> Vec<Contour> {
    assert!(
        levels.windows(2).all(|w| w[0] < w[1]),
        "contour levels must ascend"
    );
    let (w, h) = (field.width() as isize, field.height() as isize);
    let value = |r: isize, c: isize| -> f64 {
        if r < 0 || c < 0 || r >= h || c >= w {
            outside
        } else {
            field.as_slice()[(r * w + c) as usize]
        }
    };
    let pos = |r: isize, c: isize| GridPoint::new(c as f64 + 0.5, r as f64 + 0.5);
    // Edge keys over the padded lattice: horizontal edge (r, c)–(r, c+1) is
    // 2·id, vertical (r, c)–(r+1, c) is 2·id + 1, id = (r+1)(w+2) + (c+1).
    let id = |r: isize, c: isize| ((r + 1) * (w + 2) + (c + 1)) as u64;
    // Per level: segment start edge -> (end edge, start point), and the start
    // edges in order of discovery.
    let mut links: Vec<HashMap<u64, (u64, GridPoint)>> = vec![HashMap::new(); levels.len()];
    let mut order: Vec<Vec<u64>> = vec![Vec::new(); levels.len()];
    for r in -1..h {
        for c in -1..w {
            // Corners clockwise on screen (rows grow downwards): top-left,
            // top-right, bottom-right, bottom-left; edge k joins corner k to k+1.
            let corner = [(r, c), (r, c + 1), (r + 1, c + 1), (r + 1, c)];
            let v = corner.map(|(a, b)| value(a, b));
            let (lo, hi) = v
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            let first = levels.partition_point(|&l| l <= lo);
            let last = levels.partition_point(|&l| l <= hi);
            let edge_key = [
                id(r, c) * 2,
                id(r, c + 1) * 2 + 1,
                id(r + 1, c) * 2,
                id(r, c) * 2 + 1,
            ];
            for (li, &level) in levels.iter().enumerate().take(last).skip(first) {
                let inside = v.map(|x| x >= level);
                let point = |k: usize| {
                    let (a, b) = (k, (k + 1) % 4);
                    let t = ((level - v[a]) / (v[b] - v[a])).clamp(0.0, 1.0);
                    let (p, q) = (pos(corner[a].0, corner[a].1), pos(corner[b].0, corner[b].1));
                    GridPoint::new(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y))
                };
                // In-edges go outside -> inside along the corner order, out-edges inside -> outside.
                let ins: Vec<usize> = (0..4)
                    .filter(|&k| !inside[k] && inside[(k + 1) % 4])
                    .collect();
                let pair = |k_in: usize| -> usize {
                    if ins.len() == 1 {
                        (0..4)
                            .find(|&k| inside[k] && !inside[(k + 1) % 4])
                            .expect("one out-edge")
                    } else if (v.iter().sum::<f64>() / 4.0) >= level {
                        (k_in + 3) % 4 // centre inside: join the insides
                    } else {
                        (k_in + 1) % 4 // centre outside: cut the inside corners off
                    }
                };
                for &k_in in &ins {
                    let k_out = pair(k_in);
                    let start = edge_key[k_in];
                    links[li].insert(start, (edge_key[k_out], point(k_in)));
                    order[li].push(start);
                }
            }
        }
    }
    let mut out = Vec::new();
    for (li, (mut map, starts)) in links.into_iter().zip(order).enumerate() {
        for s in starts {
            let mut points = Vec::new();
            let mut e = s;
            while let Some((next, p)) = map.remove(&e) {
                points.push(p);
                e = next;
            }
            if !points.is_empty() {
                out.push(Contour { level: li, points });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cell;

    fn field(rows: &[&[f64]]) -> Grid<f64> {
        Grid::from_fn(rows[0].len(), rows.len(), |c: Cell| rows[c.row][c.col])
    }

    #[test]
    fn one_inside_sample_gives_a_diamond() {
        let f = field(&[&[0.0, 0.0, 0.0], &[0.0, 1.0, 0.0], &[0.0, 0.0, 0.0]]);
        let cs = iso_contours(&f, &[0.5], 0.0);
        assert_eq!(cs.len(), 1);
        let mut pts: Vec<(f64, f64)> = cs[0].points.iter().map(|p| (p.x, p.y)).collect();
        assert_eq!(pts.len(), 4);
        pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(pts, [(1.0, 1.5), (1.5, 1.0), (1.5, 2.0), (2.0, 1.5)]);
        // Inside on the right in the (x, y) plane: negative signed area.
        let p = &cs[0].points;
        let area: f64 = (0..p.len())
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        assert!(area < 0.0, "{area}");
    }

    #[test]
    fn a_ring_gives_two_loops_and_levels_nest() {
        // A 7 x 7 pyramid: value = distance (Chebyshev) from the border + 1.
        let f = Grid::from_fn(7, 7, |c: Cell| {
            let d = c.row.min(c.col).min(6 - c.row).min(6 - c.col);
            d as f64 + 1.0
        });
        let cs = iso_contours(&f, &[0.5, 1.5, 2.5, 3.5, 9.0], 0.0);
        let per: Vec<usize> = (0..5)
            .map(|l| cs.iter().filter(|c| c.level == l).count())
            .collect();
        assert_eq!(per, [1, 1, 1, 1, 0]);
        // Level 1.5 runs halfway between the border ring and the next:
        // a square of side 6 - 2 = 5 (x from 1 to 6).
        let l1 = cs.iter().find(|c| c.level == 1).unwrap();
        for p in &l1.points {
            let on_side = |v: f64| (v - 1.0).abs() < 1e-9 || (v - 6.0).abs() < 1e-9;
            assert!(on_side(p.x) || on_side(p.y), "{p:?}");
        }
        // A hole (value below the level) inside a plateau gives an inner loop too.
        let g = field(&[
            &[2.0, 2.0, 2.0, 2.0],
            &[2.0, 0.0, 0.0, 2.0],
            &[2.0, 2.0, 2.0, 2.0],
        ]);
        assert_eq!(iso_contours(&g, &[1.0], 0.0).len(), 2);
    }

    use proptest::prelude::*;

    proptest! {
        /// On seeded random fields: every contour point lies on a lattice
        /// edge between a sample at or above the level and one below, where
        /// the linear interpolation of the two equals the level; consecutive
        /// points share a unit square; every edge that changes side is
        /// crossed exactly once.
        #[test]
        fn contours_cross_each_changing_edge_once(
            w in 1usize..9, h in 1usize..9, seed in any::<u64>(), level in -0.5f64..1.5,
        ) {
            let mut s = seed | 1;
            let f = Grid::from_fn(w, h, |_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s % 1000) as f64 / 1000.0
            });
            let outside = -1.0;
            let value = |r: isize, c: isize| {
                if r < 0 || c < 0 || r >= h as isize || c >= w as isize {
                    outside
                } else {
                    f[Cell::new(r as usize, c as usize)]
                }
            };
            let cs = iso_contours(&f, &[level], outside);
            let mut crossings = 0;
            for c in &cs {
                for (i, p) in c.points.iter().enumerate() {
                    let (x, y) = (p.x - 0.5, p.y - 0.5); // sample coordinates
                    let on_col = (x - x.round()).abs() < 1e-9;
                    let on_row = (y - y.round()).abs() < 1e-9;
                    prop_assert!(on_col || on_row, "{p:?} not on a lattice edge");
                    let (a, b, t) = if on_row {
                        let r = y.round() as isize;
                        let c0 = x.floor() as isize;
                        (value(r, c0), value(r, c0 + 1), x - c0 as f64)
                    } else {
                        let k = x.round() as isize;
                        let r0 = y.floor() as isize;
                        (value(r0, k), value(r0 + 1, k), y - r0 as f64)
                    };
                    prop_assert!((a >= level) != (b >= level), "{p:?}: {a} {b} same side");
                    prop_assert!((a + t * (b - a) - level).abs() < 1e-9);
                    let q = c.points[(i + 1) % c.points.len()];
                    prop_assert!((q.x - p.x).abs() <= 1.0 + 1e-9 && (q.y - p.y).abs() <= 1.0 + 1e-9);
                    crossings += 1;
                }
            }
            let mut changing = 0;
            for r in -1..=h as isize {
                for c in -1..=w as isize {
                    let here = value(r, c) >= level;
                    if c < w as isize && here != (value(r, c + 1) >= level) {
                        changing += 1;
                    }
                    if r < h as isize && here != (value(r + 1, c) >= level) {
                        changing += 1;
                    }
                }
            }
            prop_assert_eq!(crossings, changing);
        }
    }

    #[test]
    fn saddles_follow_the_centre_value() {
        // Diagonal insides: joined when the centre mean is inside.
        let joined = field(&[&[3.0, 0.0], &[0.0, 3.0]]);
        assert_eq!(iso_contours(&joined, &[1.0], 0.0).len(), 1);
        let apart = field(&[&[1.0, 0.0], &[0.0, 1.0]]);
        assert_eq!(iso_contours(&apart, &[0.9], 0.0).len(), 2);
    }
}
