//! Critical lines and the walls at their ends: where a narrow passage
//! crosses the axis of the free space, and whether a wall ends there in line.

use oxcover_grid::math::fast_floor;
use oxcover_grid::traverse::traverse;
use oxcover_grid::{Cell, Grid};

use super::{Cut, Pt};

/// How far (m) the wall must run on in line beyond a doorway's end.
pub(super) const JAMB_RUN_M: f64 = 0.8;

/// Cells of thin wall a jamb needs before it may meet another wall (a door
/// beside a corner).
pub(super) const JUNCTION_CELLS: usize = 3;

/// Half the thickness (m) of the thickest wall taken for a jamb.
pub(super) const WALL_HALF_M: f64 = 0.5;

/// How much thicker (m) than twice its thinnest part a wall across a
/// line's end must be where the line meets it to count as a wall that
/// thins into one in line ([`thins_out`]).
pub(super) const THINS_OUT_M: f64 = 0.15;

/// Narrowest doorway (m): narrower gaps (between chairs, behind a table)
/// are no doors.
pub(super) const MIN_DOOR_M: f64 = 0.1;

/// Angle between a critical line's two ends seen from its axis cell within
/// which they count as straight across (about 11°): of such pairs the
/// shortest is the line, not a slant across a corridor.
const STRAIGHT_COS: f64 = -0.98;

/// Least angle between a critical line's two ends seen from its axis
/// cell: the two nearest obstacle points lie on opposite sides.
const OPPOSITE_COS: f64 = -0.8;

/// A cell of a ring round a cell: its offset (rows, columns), and the
/// point of its square nearest the centre cell's centre relative to that
/// centre, with its distance (exact in floating point, the same for every
/// centre: the offsets are whole or half cells).
#[derive(Clone, Copy, Debug)]
pub(super) struct RingCell {
    dr: isize,
    dc: isize,
    near: Pt,
    dist: f64,
}

/// For each whole clearance `R` up to `most`, the cells whose square may
/// hold a point at a distance between `R` and `R + 2.5` from a cell's
/// centre: where [`critical_line`] looks for the nearest obstacle points
/// of a cell of clearance in `R..R + 1` (nothing is nearer than the
/// clearance).
pub(super) fn rings(most: f64) -> Vec<Vec<RingCell>> {
    let top = most.max(0.0).ceil() as usize + 1;
    (0..=top)
        .map(|big_r| {
            let (lo, hi) = (big_r as f64 - 0.75, big_r as f64 + 2.5 + 0.75);
            let k = hi.ceil() as isize;
            (-k..=k)
                .flat_map(|dr| (-k..=k).map(move |dc| (dr, dc)))
                .filter(|&(dr, dc)| {
                    let d = (dr as f64).hypot(dc as f64);
                    d >= lo && d <= hi
                })
                .map(|(dr, dc)| {
                    // The square's point nearest the centre (0.5, 0.5)
                    // of cell (0, 0), less that centre.
                    let near = (
                        0.5f64.clamp(dc as f64, dc as f64 + 1.0) - 0.5,
                        0.5f64.clamp(dr as f64, dr as f64 + 1.0) - 0.5,
                    );
                    RingCell {
                        dr,
                        dc,
                        near,
                        dist: near.0.hypot(near.1),
                    }
                })
                .collect()
        })
        .collect()
}

/// The critical line through axis cell `c` of clearance `r`: the segment
/// between its two nearest obstacle points on opposite sides, if it has
/// two such.
pub(super) fn critical_line(
    free: &Grid<bool>,
    rings: &[Vec<RingCell>],
    c: Cell,
    r: f64,
) -> Option<Cut> {
    let centre = (c.col as f64 + 0.5, c.row as f64 + 0.5);
    let ring = rings.get(r.floor() as usize)?;
    let (w, h, cells) = (free.width(), free.height(), free.as_slice());
    // Each obstacle point and its offset from the centre and distance.
    let mut near: Vec<(Pt, Pt, f64)> = Vec::new();
    for cell in ring.iter().filter(|cell| cell.dist <= r + 1.5) {
        let (row, col) = (c.row as isize + cell.dr, c.col as isize + cell.dc);
        let inside = row >= 0 && col >= 0 && (row as usize) < h && (col as usize) < w;
        if !(inside && cells[row as usize * w + col as usize]) {
            let q = (centre.0 + cell.near.0, centre.1 + cell.near.1);
            near.push((q, cell.near, cell.dist));
        }
    }
    // The shortest pair straight across (a corridor's cross-section, not
    // a slant through it), else the pair farthest apart in angle.
    let mut straight: Option<(f64, Pt, Pt)> = None;
    let mut best: Option<(f64, Pt, Pt)> = None;
    for (i, &(p, (ux, uy), dp)) in near.iter().enumerate() {
        for &(q, (vx, vy), dq) in &near[i + 1..] {
            let (dot, den) = (ux * vx + uy * vy, (dp * dq).max(1e-9));
            // (Plainly not opposite, without the division.)
            if dot > OPPOSITE_COS * den * (1.0 - 1e-9) {
                continue;
            }
            let cos = dot / den;
            if cos > OPPOSITE_COS {
                continue;
            }
            if cos <= STRAIGHT_COS && straight.is_none_or(|b| dp + dq < b.0 - 1e-9) {
                straight = Some((dp + dq, p, q));
            }
            if best.is_none_or(|b| cos < b.0 - 1e-9) {
                best = Some((cos, p, q));
            }
        }
    }
    let best = straight.or(best);
    let (_, a, b) = best?;
    Some(Cut {
        a,
        b,
        half: r,
        extension: false,
    })
}

/// Largest obstacle (m²) standing alone, not touching the map's edge,
/// taken for furniture: no jamb, no end of a doorway (a cabinet pointing
/// at a door is no wall).
pub(super) const ISLAND_M2: f64 = 2.0;

/// Thinnest furniture (m, both ways): thinner pieces standing alone are
/// walls broken up in a scan.
pub(super) const ISLAND_THICK_M: f64 = 0.3;

/// Whether beyond `end` (coming from `from`) the obstacle runs on in line
/// as a thin wall for `run` cells, or for [`JUNCTION_CELLS`] up to another
/// wall it meets: every point along the line past `end` is in a non-free
/// cell (or beside one, a cell's tolerance) of a wall at most
/// `2 · wall_half` cells thick, free space on both its sides, and not
/// `furniture`; and no wall across the end that thins into one in line
/// ([`thins_out`] with `margin`).
pub(super) fn jamb(
    free: &Grid<bool>,
    furniture: &Grid<bool>,
    from: Pt,
    end: Pt,
    run: f64,
    wall_half: f64,
    margin: f64,
) -> bool {
    let (dx, dy) = (end.0 - from.0, end.1 - from.1);
    let len = dx.hypot(dy);
    if len < 1e-9 {
        return false;
    }
    let (ux, uy) = (dx / len, dy / len);
    let (nx, ny) = (-uy, ux);
    let blocked_at = |x: f64, y: f64| {
        let (col, row) = (fast_floor(x), fast_floor(y));
        col < 0.0
            || row < 0.0
            || col as usize >= free.width()
            || row as usize >= free.height()
            || !free[Cell::new(row as usize, col as usize)]
    };
    let free_at = |x: f64, y: f64| !blocked_at(x, y);
    let furniture_at = |x: f64, y: f64| {
        x >= 0.0
            && y >= 0.0
            && furniture
                .get(Cell::new(fast_floor(y) as usize, fast_floor(x) as usize))
                .is_some_and(|&f| f)
    };
    let steps = run.ceil().max(1.0) as usize;
    // The wall's thickness across the line where it starts and its least
    // on the way ([`thins_out`]).
    let (mut first, mut least) = (None, usize::MAX);
    let crossing = |first: Option<usize>, least: usize| {
        first.is_some_and(|f: usize| {
            least != usize::MAX && thins_out(f as f64, least as f64, margin)
        })
    };
    for k in 0..steps {
        let t = k as f64 + 0.5;
        let (x, y) = (end.0 + ux * t, end.1 + uy * t);
        let on_wall = blocked_at(x, y)
            || blocked_at(x + nx * 0.7, y + ny * 0.7)
            || blocked_at(x - nx * 0.7, y - ny * 0.7);
        if !on_wall || furniture_at(x, y) {
            return false;
        }
        // A thin wall: free on both sides, at most two half thicknesses
        // apart.
        let most = (2.0 * wall_half).ceil().max(1.0) as usize;
        let reach = |sx: f64, sy: f64| {
            (0..=most).find(|&j| {
                let j = j as f64;
                free_at(x + sx * j, y + sy * j)
            })
        };
        match (reach(nx, ny), reach(-nx, -ny)) {
            (Some(p), Some(q)) if (p + q) as f64 <= 2.0 * wall_half + 1.0 => {
                // (Only where the point is in the wall, not beside it.)
                if p + q > 0 {
                    first.get_or_insert(p + q);
                    least = least.min(p + q);
                }
            }
            // The wall meets another (a corner, a junction): a jamb if it
            // ran thin for a few cells first.
            _ => return k >= JUNCTION_CELLS && !crossing(first, least),
        }
    }
    !crossing(first, least)
}

/// Whether a wall `first` cells thick where it ends and `least` at its
/// thinnest behind is a wall across the end that thins into one in line
/// (a room's wall meeting a short piece of corridor wall between two
/// doors): a junction, not a wall's end. `margin` ([`THINS_OUT_M`] in
/// cells) is how much thicker than twice the thinnest it must be.
pub(super) fn thins_out(first: f64, least: f64, margin: f64) -> bool {
    first > 2.0 * least + margin
}

/// Whether the obstacle at `end` (coming from `from`) is `furniture`: the
/// cell just beyond `end`, or beside it within a cell.
pub(super) fn on_furniture(furniture: &Grid<bool>, from: Pt, end: Pt) -> bool {
    let (dx, dy) = (end.0 - from.0, end.1 - from.1);
    let len = dx.hypot(dy).max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let (x, y) = (end.0 + ux * 0.5, end.1 + uy * 0.5);
    [(0.0, 0.0), (-uy * 0.7, ux * 0.7), (uy * 0.7, -ux * 0.7)]
        .iter()
        .any(|&(ox, oy)| {
            let (cx, cy) = (x + ox, y + oy);
            cx >= 0.0
                && cy >= 0.0
                && furniture
                    .get(Cell::new(fast_floor(cy) as usize, fast_floor(cx) as usize))
                    .is_some_and(|&f| f)
        })
}

/// The free cells a cut crosses, its ends pushed a cell into the walls so
/// that no diagonal leak is left beside them.
pub(super) fn cut_cells_of(free: &Grid<bool>, cut: &Cut) -> Vec<Cell> {
    let (dx, dy) = (cut.b.0 - cut.a.0, cut.b.1 - cut.a.1);
    let len = dx.hypot(dy).max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let a = oxcover_grid::Point::new(cut.a.0 - ux, cut.a.1 - uy);
    let b = oxcover_grid::Point::new(cut.b.0 + ux, cut.b.1 + uy);
    let mut cells = Vec::new();
    traverse(free.width(), free.height(), a, b, |c, _, _| {
        if let Some(c) = c.filter(|&c| free[c]) {
            cells.push(c);
        }
        true
    });
    cells
}
