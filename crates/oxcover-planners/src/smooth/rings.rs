//! Rings: the virtual walls, as level sets of the distance to the C-space
//! boundary.
//!
//! Ring `k` is the iso-contour of that distance at `½ + k·2R` cells
//! ([`oxcover_grid::contour`], marching squares): ring 0 runs through the
//! centres of the cells along the walls (wall following), each next ring one
//! lane `2R` further in. Where the boundary is a staircase of cells (a wall
//! off the grid axes, a round obstacle), ring 0 is lifted
//! [`super::STAIR_LIFT`] cells off the steps: hugging them is a zigzag the
//! robot drives at walking pace; a little further out the contour is a
//! smooth curve. The price is the outermost row of cells beside such walls,
//! which only the tool's rim reached. Rings from 1 on are resampled every
//! cell, smoothed by a Gaussian of ±3 cells (sharp corners kept) and thinned
//! by Douglas–Peucker within 0.05 cells; ring 0 is only thinned (0.15).

use oxcover_grid::components::components4;
use oxcover_grid::contour::{Contour, iso_contours};
use oxcover_grid::edt::{INFINITE, boundary_distance_sq4};
use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, segment_distance};
use oxcover_grid::{Cell, Grid};

use super::STAIR_LIFT;
use super::run::{SAMPLE_SLACK, mark_stroke, turn};
use super::{Item, Run};

/// How far (cells) under `½ + k·2R` the rings' levels lie.
const LEVEL_EPSILON: f64 = 1e-3;

impl<'a> Run<'a> {
    /// The distance field whose level sets are the rings: the distance (cells)
    /// from each cell centre to the nearest non-plannable cell, negative
    /// inside them, lowered by up to [`STAIR_LIFT`] where the boundary is a
    /// staircase (the field's gradient more than 5° off the grid axes, fully
    /// from 15°) and a neighbour lies a cell deeper, fading out over the
    /// first lane.
    pub(super) fn field(&self, spacing: f64) -> Grid<f64> {
        let (w, h) = (self.plannable.width(), self.plannable.height());
        let blocked = Grid::from_fn(w, h, |c| !self.plannable[c]);
        let inside = boundary_distance_sq4(&blocked, true);
        let outside = boundary_distance_sq4(self.plannable, false);
        let field = Grid::from_fn(w, h, |c| {
            if self.plannable[c] {
                (inside[c] as f64).sqrt() / 2.0
            } else if outside[c] == INFINITE {
                -(w.max(h) as f64)
            } else {
                -((outside[c] as f64).sqrt() / 2.0)
            }
        });
        let lift = STAIR_LIFT.min(self.tool);
        let at = |r: isize, c: isize| {
            let (r, c) = (r.clamp(0, h as isize - 1), c.clamp(0, w as isize - 1));
            field.as_slice()[r as usize * w + c as usize]
        };
        let stair = Grid::from_fn(w, h, |c| {
            let (r, k) = (c.row as isize, c.col as isize);
            let gx = at(r, k + 1) - at(r, k - 1);
            let gy = at(r + 1, k) - at(r - 1, k);
            if gx.abs() + gy.abs() < 1e-9 {
                return 0.0;
            }
            let a = gy.atan2(gx).to_degrees().rem_euclid(90.0);
            ((a.min(90.0 - a) - 5.0) / 10.0).clamp(0.0, 1.0)
        });
        let stair = blur(&stair, 1.0);
        Grid::from_fn(w, h, |c| {
            let fade = (1.0 - (field[c] - 0.5) / spacing).clamp(0.0, 1.0);
            // Only where there is room inwards (a neighbour a cell deeper):
            // in a corridor two cells wide the lift would drop the ring.
            let (r, k) = (c.row as isize, c.col as isize);
            let deepest = (-1..=1)
                .flat_map(|dr| (-1..=1).map(move |dc| (dr, dc)))
                .map(|(dr, dc)| at(r + dr, k + dc))
                .fold(f64::NEG_INFINITY, f64::max);
            let room = (2.0 * (deepest - field[c]) - 1.0).clamp(0.0, 1.0);
            field[c] - lift * stair[c] * fade * room
        })
    }

    /// The rings, shaped, and the spines of what they would leave.
    pub(super) fn items(&mut self) -> Vec<Item> {
        let spacing = 2.0 * self.reach;
        let field = self.field(spacing);
        let top = field.as_slice().iter().copied().fold(0.0, f64::max);
        // Just under ½ + k·2R: a level equal to the samples' values would put
        // contour points on the samples themselves, where squares meet.
        let levels: Vec<f64> = (0..)
            .map(|k| 0.5 - LEVEL_EPSILON + k as f64 * spacing)
            .take_while(|&l| l <= top)
            .collect();
        let outside = field.as_slice().iter().copied().fold(0.0, f64::min) - 1.0;
        let mut items: Vec<Item> = iso_contours(&field, &levels, outside)
            .into_iter()
            .map(|Contour { level, points }| Item {
                points: self.shape_ring(snap_to_centres(points), level),
                closed: true,
                level,
                reps: Vec::new(),
            })
            .filter(|it| it.points.len() >= 2)
            .collect();
        // What the rings leave: cells their tool would not reach.
        let (w, h) = (self.plannable.width(), self.plannable.height());
        let mut reached = self.touched.clone();
        for it in &items {
            let mut pts = it.points.clone();
            pts.push(pts[0]);
            mark_stroke(&mut reached, &pts, self.tool - SAMPLE_SLACK);
        }
        let left = Grid::from_fn(w, h, |c| self.plannable[c] && !reached[c]);
        let comps = components4(&left);
        let mut groups: Vec<Vec<Cell>> = vec![Vec::new(); comps.sizes.len()];
        for c in left.true_cells() {
            groups[comps.labels[c] as usize - 1].push(c);
        }
        for g in &groups {
            let spine = self.spine(g);
            if !spine.is_empty() {
                items.push(Item {
                    points: spine,
                    closed: false,
                    level: usize::MAX,
                    reps: g.iter().copied().filter(|&c| self.rep[c]).collect(),
                });
            }
        }
        items
    }

    /// A ring's polyline: from level 1 on resampled, smoothed (each point
    /// pulled back towards the contour as far as clearance needs) and
    /// thinned; ring 0 thinned only.
    pub(super) fn shape_ring(&self, points: Vec<GridPoint>, level: usize) -> Vec<GridPoint> {
        if level == 0 {
            return simplify_loop(&points, 0.15);
        }
        let raw = resample_loop(&points, 1.0);
        let mut smooth = smooth_loop(&raw, 3);
        for (q, r) in smooth.iter_mut().zip(&raw) {
            if self.clear.point(*q) {
                continue;
            }
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..8 {
                let t = 0.5 * (lo + hi);
                let m = GridPoint::new(r.x + t * (q.x - r.x), r.y + t * (q.y - r.y));
                if self.clear.point(m) {
                    lo = t;
                } else {
                    hi = t;
                }
            }
            *q = GridPoint::new(r.x + lo * (q.x - r.x), r.y + lo * (q.y - r.y));
        }
        simplify_loop(&smooth, 0.05)
    }
}

/// Contour points within a hundredth of a cell of a cell centre moved onto
/// it (the levels lie [`LEVEL_EPSILON`] under values the distance takes at
/// cell centres), and the repeats this makes dropped.
fn snap_to_centres(points: Vec<GridPoint>) -> Vec<GridPoint> {
    let mut out: Vec<GridPoint> = Vec::with_capacity(points.len());
    for p in points {
        let c = GridPoint::new(p.x.floor() + 0.5, p.y.floor() + 0.5);
        let q = if norm(p.x - c.x, p.y - c.y) < 0.01 {
            c
        } else {
            p
        };
        if out.last() != Some(&q) {
            out.push(q);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// A separable Gaussian blur (σ in cells, kernel to 3σ, edges clamped).
fn blur(field: &Grid<f64>, sigma: f64) -> Grid<f64> {
    let r = (3.0 * sigma).ceil() as isize;
    let k: Vec<f64> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let sum: f64 = k.iter().sum();
    let (w, h) = (field.width() as isize, field.height() as isize);
    let src = field.as_slice();
    let mut rows = vec![0.0; src.len()];
    for y in 0..h {
        for x in 0..w {
            let acc: f64 = k
                .iter()
                .enumerate()
                .map(|(i, kv)| kv * src[(y * w + (x + i as isize - r).clamp(0, w - 1)) as usize])
                .sum();
            rows[(y * w + x) as usize] = acc / sum;
        }
    }
    Grid::from_fn(w as usize, h as usize, |c| {
        let (x, y) = (c.col as isize, c.row as isize);
        let acc: f64 = k
            .iter()
            .enumerate()
            .map(|(i, kv)| kv * rows[((y + i as isize - r).clamp(0, h - 1) * w + x) as usize])
            .sum();
        acc / sum
    })
}

/// A closed polyline resampled every `step` cells along its length.
pub(super) fn resample_loop(points: &[GridPoint], step: f64) -> Vec<GridPoint> {
    let n = points.len();
    let mut out = vec![points[0]];
    let mut carry = 0.0;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let l = norm(b.x - a.x, b.y - a.y);
        let mut t = step - carry;
        while t < l {
            out.push(GridPoint::new(
                a.x + (b.x - a.x) * t / l,
                a.y + (b.y - a.y) * t / l,
            ));
            t += step;
        }
        carry = l - (t - step);
    }
    let (first, last) = (out[0], out[out.len() - 1]);
    if out.len() > 1 && norm(first.x - last.x, first.y - last.y) < 0.5 * step {
        out.pop();
    }
    out
}

/// A closed polyline of evenly spaced points smoothed by a Gaussian moving
/// average of `half` points either side (σ = half / 2). A corner (the loop
/// turning more than 50° between `half` points before and after) stays, and
/// no window reaches across one.
pub(super) fn smooth_loop(points: &[GridPoint], half: usize) -> Vec<GridPoint> {
    let n = points.len();
    if half == 0 || n < 2 * half + 3 {
        return points.to_vec();
    }
    let at = |i: isize| points[i.rem_euclid(n as isize) as usize];
    let h = half as isize;
    let corner: Vec<bool> = (0..n as isize)
        .map(|i| turn(at(i - h), at(i), at(i + h)).abs() > 50f64.to_radians())
        .collect();
    let is_corner = |i: isize| corner[i.rem_euclid(n as isize) as usize];
    let sigma = half as f64 / 2.0;
    (0..n as isize)
        .map(|i| {
            let p = at(i);
            if is_corner(i) {
                return p;
            }
            let (mut sx, mut sy, mut sw) = (p.x, p.y, 1.0);
            for dir in [-1isize, 1] {
                for k in 1..=h {
                    let j = i + dir * k;
                    if is_corner(j) {
                        break;
                    }
                    let w = (-(k * k) as f64 / (2.0 * sigma * sigma)).exp();
                    sx += w * at(j).x;
                    sy += w * at(j).y;
                    sw += w;
                }
            }
            GridPoint::new(sx / sw, sy / sw)
        })
        .collect()
}

/// A closed polyline simplified by Douglas–Peucker within `tol` (cells),
/// split first at the point farthest from the first.
pub(super) fn simplify_loop(points: &[GridPoint], tol: f64) -> Vec<GridPoint> {
    let n = points.len();
    if n < 4 {
        return points.to_vec();
    }
    let d0 = |i: usize| norm(points[i].x - points[0].x, points[i].y - points[0].y);
    let far = (1..n)
        .max_by(|&a, &b| d0(a).total_cmp(&d0(b)))
        .unwrap_or(n / 2);
    let at = |i: usize| points[i % n];
    let mut keep = vec![false; n + 1];
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        let (mut best, mut worst) = (0, tol);
        for i in a + 1..b {
            let d = segment_distance(at(a), at(b), at(i));
            if d > worst {
                best = i;
                worst = d;
            }
        }
        if best > 0 {
            keep[best] = true;
            stack.push((a, best));
            stack.push((best, b));
        }
    }
    (0..n).filter(|&i| keep[i]).map(|i| points[i]).collect()
}
