//! Walls continued across openings wider than a door: a room's open side
//! closed from a wall's end to the wall ahead, or to the nearest other
//! wall end.

use rayon::prelude::*;

use oxcover_grid::{Cell, Grid};

use super::lines::{THINS_OUT_M, thins_out};
use super::{Cut, Pt};

/// Longest opening (m) closed by continuing a wall to the wall ahead.
const EXTENSION_M: f64 = 4.5;

/// How long (m) a wall must run behind its end to be continued, and how
/// far the wall it meets must run on beside the meeting point.
const EXT_WALL_M: f64 = 1.0;

/// Cuts that continue a wall across an opening wider than a door: from
/// each cell that ends a thin wall running along a grid axis for
/// [`EXT_WALL_M`] behind it, straight on over free cells to the first
/// obstacle, where that lies between a door's width and [`EXTENSION_M`]
/// ahead and is the face of a wall that runs on beside the meeting point
/// for [`EXT_WALL_M`] on one side at least. The ends are looked for among
/// `edges`, each row's obstacle cells beside a free one.
pub(super) fn extension_cuts(
    free: &Grid<bool>,
    edges: &[Vec<u32>],
    door_half: f64,
    per_metre: f64,
    wall_half: f64,
) -> Vec<Cut> {
    let (w, h) = (free.width() as isize, free.height() as isize);
    let is_free = |x: isize, y: isize| {
        x >= 0 && y >= 0 && x < w && y < h && free[Cell::new(y as usize, x as usize)]
    };
    let behind = (EXT_WALL_M * per_metre).ceil().max(1.0) as isize;
    let margin = THINS_OUT_M * per_metre;
    let most = (2.0 * wall_half).ceil().max(1.0) as isize;
    let (shortest, longest) = (
        (2.0 * door_half).floor() as isize,
        (EXTENSION_M * per_metre).floor() as isize,
    );
    // How thick a wall is across (nx, ny) at (x, y), if at most two half
    // thicknesses with free space on both sides: the obstacle cells
    // through (x, y) along (nx, ny), with a free cell at both ends (not
    // where they meet the grid's edge).
    let thickness = |x: isize, y: isize, (nx, ny): (isize, isize)| {
        let mut run = 1;
        for s in [1, -1] {
            let mut k = 1;
            loop {
                let (px, py) = (x + s * nx * k, y + s * ny * k);
                if px < 0 || py < 0 || px >= w || py >= h {
                    return None;
                }
                if is_free(px, py) {
                    break;
                }
                run += 1;
                if run > most {
                    return None;
                }
                k += 1;
            }
        }
        Some(run)
    };
    let thin = |x: isize, y: isize, n: (isize, isize)| thickness(x, y, n).is_some();
    let cells = free.as_slice();
    // Row by row in parallel, the rows' cuts in row order.
    let rows: Vec<(Vec<Cut>, Vec<End>)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let (mut out, mut ends) = (Vec::new(), Vec::new());
            let (wu, hu) = (free.width(), free.height());
            for &x in &edges[y as usize] {
                let (x, xu, yu) = (x as isize, x as usize, y as usize);
                let i = yu * wu + xu;
                // The free cells beside it.
                let near = [
                    xu + 1 < wu && cells[i + 1],
                    yu + 1 < hu && cells[i + wu],
                    xu > 0 && cells[i - 1],
                    yu > 0 && cells[i - wu],
                ];
                for (&(dx, dy), _) in [(1, 0), (0, 1), (-1, 0), (0, -1)]
                    .iter()
                    .zip(near)
                    .filter(|(_, f)| *f)
                {
                    let n = (-dy, dx);
                    // A thin wall behind the end (thin for `behind` cells
                    // on), not a wall across it that thins into one (a
                    // room's wall meeting a short piece of corridor wall
                    // between two doors).
                    let mut across = (0..=behind).map(|k| {
                        let (bx, by) = (x - dx * k, y - dy * k);
                        if is_free(bx, by) {
                            None
                        } else {
                            thickness(bx, by, n)
                        }
                    });
                    let Some(Some(first)) = across.next() else {
                        continue;
                    };
                    let least = across.try_fold(first, |m, t| t.map(|t| m.min(t)));
                    let wall =
                        least.is_some_and(|least| !thins_out(first as f64, least as f64, margin));
                    if !wall {
                        continue;
                    }
                    ends.push(End { x, y, dx, dy });
                    let Some(k) = (1..=longest + 1).find(|&k| !is_free(x + dx * k, y + dy * k))
                    else {
                        continue;
                    };
                    if k - 1 <= shortest || k > longest {
                        continue;
                    }
                    // The wall met runs on beside the meeting point.
                    let (hx, hy) = (x + dx * k, y + dy * k);
                    let face = |s: isize| {
                        (0..=behind).all(|j| !is_free(hx + s * n.0 * j, hy + s * n.1 * j))
                    };
                    // Or it is a thin wall in line (a gap in a wall).
                    let in_line = (0..=behind).all(|j| {
                        let (ax, ay) = (hx + dx * j, hy + dy * j);
                        !is_free(ax, ay) && thin(ax, ay, n)
                    });
                    // Beside a gap, the space on one side at least is
                    // wider than the gap (a room, not a corridor crossing).
                    let wide = |side: isize| {
                        (2..=5).all(|step| {
                            let off = side * step * behind / 2;
                            let (mx, my) = (x + dx * k / 2 + n.0 * off, y + dy * k / 2 + n.1 * off);
                            let run = |t: isize| {
                                (1..)
                                    .take_while(|&i| {
                                        is_free(mx + t * dx * i, my + t * dy * i) && i <= k + behind
                                    })
                                    .count() as isize
                            };
                            is_free(mx, my) && run(1) + run(-1) + 1 > k - 1 + behind / 2
                        })
                    };
                    let faced = face(1) || face(-1);
                    if !((faced || in_line) && (wide(1) || wide(-1))) {
                        continue;
                    }
                    out.push(Cut {
                        a: (x as f64 + 0.5, y as f64 + 0.5),
                        b: (hx as f64 + 0.5, hy as f64 + 0.5),
                        half: (k - 1) as f64 / 2.0,
                        // A wide gap in a wall is judged as a doorway.
                        extension: faced,
                    });
                }
            }
            (out, ends)
        })
        .collect();
    let mut cuts = Vec::new();
    let mut ends = Vec::new();
    for (c, e) in rows {
        cuts.extend(c);
        ends.extend(e);
    }
    cuts.extend(end_to_end_cuts(
        &is_free,
        &tips(ends),
        (shortest, longest),
        behind,
    ));
    cuts
}

/// The tip of a thin wall: an obstacle cell that ends it, and the way out
/// of it along the wall (a grid axis).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct End {
    dx: isize,
    dy: isize,
    x: isize,
    y: isize,
}

/// The tips of the walls whose end cells are `ends`: each run of end
/// cells side by side across one wall's end, as the point in the middle
/// of its face, with the way out of the wall there.
fn tips(mut ends: Vec<End>) -> Vec<(Pt, Pt)> {
    let key = |e: &End| (e.dx, e.dy, e.x * e.dx + e.y * e.dy, e.y * e.dx - e.x * e.dy);
    ends.sort_by_key(key);
    let mut out = Vec::new();
    let mut i = 0;
    while i < ends.len() {
        let mut j = i + 1;
        while j < ends.len() && {
            let (a, b) = (key(&ends[j - 1]), key(&ends[j]));
            (a.0, a.1, a.2) == (b.0, b.1, b.2) && b.3 == a.3 + 1
        } {
            j += 1;
        }
        let e = ends[(i + j - 1) / 2];
        out.push((
            (
                e.x as f64 + 0.5 + e.dx as f64 * 0.5,
                e.y as f64 + 0.5 + e.dy as f64 * 0.5,
            ),
            (e.dx as f64, e.dy as f64),
        ));
        i = j;
    }
    out
}

/// Cuts from each wall's tip to the nearest other tip, where that lies
/// between a door's width and [`EXTENSION_M`] away over free cells, not
/// behind either tip (a cut that turns back round a wall's end, from a
/// door's jamb across a room's corner, continues no wall), and the space
/// on one side at least of the cut is wider than the cut (the open side of
/// a room, not a corridor's cross-section).
fn end_to_end_cuts(
    is_free: &(impl Fn(isize, isize) -> bool + Sync),
    tips: &[(Pt, Pt)],
    (shortest, longest): (isize, isize),
    behind: isize,
) -> Vec<Cut> {
    let free_at = |p: Pt| p.0 >= 0.0 && p.1 >= 0.0 && is_free(p.0 as isize, p.1 as isize);
    let mut pairs = std::collections::BTreeSet::new();
    for (i, &(a, _)) in tips.iter().enumerate() {
        let nearest = tips
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, &(b, _))| ((b.0 - a.0).hypot(b.1 - a.1), j))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        if let Some((d, j)) = nearest {
            if d > shortest as f64 && d <= longest as f64 {
                pairs.insert((i.min(j), i.max(j)));
            }
        }
    }
    let mut out = Vec::new();
    for (i, j) in pairs {
        let ((a, out_a), (b, out_b)) = (tips[i], tips[j]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let u = ((b.0 - a.0) / len, (b.1 - a.1) / len);
        if u.0 * out_a.0 + u.1 * out_a.1 < 0.0 || -u.0 * out_b.0 - u.1 * out_b.1 < 0.0 {
            continue;
        }
        let open = (2..(2.0 * len) as usize - 1).all(|k| {
            let t = k as f64 / 2.0;
            free_at((a.0 + u.0 * t, a.1 + u.1 * t))
        });
        if !open {
            continue;
        }
        let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let wide = |side: f64| {
            (2..=5).all(|step| {
                let off = side * (step * behind) as f64 / 2.0;
                let p = (mid.0 - u.1 * off, mid.1 + u.0 * off);
                let run = |t: f64| {
                    (1..)
                        .take_while(|&k| {
                            let k = f64::from(k);
                            k <= len + behind as f64
                                && free_at((p.0 + t * u.0 * k, p.1 + t * u.1 * k))
                        })
                        .count() as f64
                };
                free_at(p) && run(1.0) + run(-1.0) + 1.0 > len + behind as f64 / 2.0
            })
        };
        if wide(1.0) || wide(-1.0) {
            out.push(Cut {
                a,
                b,
                half: len / 2.0,
                extension: false,
            });
        }
    }
    out
}
