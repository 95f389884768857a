//! Room segmentation by the distance transform's medial axis: rooms are
//! split at the narrow points of the axis, the doors.
//!
//! 1. The clearance of every free cell (exact distance from its centre to
//!    the nearest non-free cell's boundary or the map edge) is computed once
//!    ([`oxcover_grid::edt::boundary_distance_sq4`]).
//! 2. **Medial axis** (a grid stand-in for the generalised Voronoi diagram):
//!    the free cells whose clearance is a crest along at least one of the
//!    four line directions through them (not lower than either neighbour on
//!    the line, higher than one): the ridge of the distance transform.
//! 3. **Door candidates**: axis cells at most half a door width
//!    ([`RoomParams::door_width_m`]) and at least a cell from the walls
//!    that no neighbouring axis cell undercuts: local minima of the
//!    clearance along the axis (Bormann et al. 2016's critical points).
//! 4. **Doors**: a candidate (narrowest first, skipped when its cut would
//!    overlap a door's already cut) is a door when the axis narrows there between two wider
//!    spaces: walking from it along the axis (across its critical line, the
//!    line to its nearest wall) on both sides, over free cells and within a
//!    wall's thickness, reaches a cell of clearance at least two cells more
//!    than the candidate's. A corridor (as wide on both sides) or the mouth
//!    of a corridor (wide on one side only) is no door. Of equally narrow
//!    candidates (a doorway of even width has one per cell along it) the
//!    one nearest where the doorway opens into the narrower of its two
//!    spaces comes first (the space's width: where a climb to ever wider
//!    cells from the opening stops), so a doorway belongs to the room it
//!    leads into, not to the corridor it leaves. The door is cut with
//!    a disc of the candidate's clearance plus 1.5 cells, which spans the
//!    gap between the two walls like the survey's critical line between the
//!    critical point's two nearest obstacle points.
//! 5. The free space minus the door discs falls into regions; regions below
//!    [`RoomParams::min_area_m2`] join the neighbour they share the longest
//!    border with; the regions grow back over the door discs (breadth
//!    first), and doors are where two rooms meet, as in [`crate::rooms`].
//!
//! Written for this workspace after the Voronoi segmentation of Bormann et
//! al. 2016 ("Room segmentation: survey, implementation, and analysis"), with
//! these departures: the medial axis is the distance transform's ridge, not
//! a polygonal Voronoi graph; a candidate must separate two wider spaces to
//! be a door (the survey cuts at every critical point and merges afterwards
//! by heuristics on room shape); of equally narrow candidates along a
//! doorway, the one where it opens into the narrower space is cut (the
//! survey leaves the choice open); [`RoomParams::max_area_m2`] plays no part.

use std::collections::VecDeque;

use oxcover_grid::edt::boundary_distance_sq4;
use oxcover_grid::grid::nearest_first;
use oxcover_grid::{Cell, Grid, components4};
use rayon::prelude::*;

use crate::rooms::{RoomParams, Rooms, doors, grow, label_the_rest, merge_small_regions};

/// How much wider (cells of clearance) than a door the spaces it joins are.
const WIDER: f64 = 2.0;

/// The eight neighbours of a cell.
const RING8: [(isize, isize); 8] = [
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, -1),
    (0, 1),
    (1, -1),
    (1, 0),
    (1, 1),
];

/// The four line directions through a cell.
const LINES: [(isize, isize); 4] = [(0, 1), (1, 0), (1, 1), (1, -1)];

/// Segments the free cells of `free` into rooms at the narrow points of
/// the medial axis (see the module docs).
#[must_use]
pub fn voronoi(free: &Grid<bool>, params: &RoomParams) -> Rooms {
    let (w, h) = (free.width(), free.height());
    let blocked = free.map(|&f| !f);
    // 4·clearance² in cells (0 on non-free cells).
    let d4 = boundary_distance_sq4(&blocked, true);
    let clearance = |c: Cell| (d4[c] as f64).sqrt() / 2.0;
    let res = params.resolution;
    let door_half = if res.is_finite() && res > 0.0 {
        params.door_width_m / 2.0 / res
    } else {
        0.0
    };
    let min_cells = if res.is_finite() && res > 0.0 {
        (params.min_area_m2 / (res * res)).max(1.0)
    } else {
        1.0
    };
    let at = |c: Cell, d: (isize, isize)| free.offset(c, d).filter(|&n| free[n]);
    // The axis where it is narrow enough for a door: a candidate and every
    // axis neighbour narrower than it lie there.
    let narrow_axis = axis_cells_in(
        free,
        &d4,
        0..=((4.0 * door_half * door_half) as u64).saturating_add(1),
    );
    let mut axis = Grid::new(w, h, false);
    for &c in &narrow_axis {
        axis[c] = true;
    }
    // Candidates: narrowest axis cells within their neighbourhood.
    let mut candidates: Vec<(u64, Cell)> = Vec::new();
    for &c in &narrow_axis {
        let r = clearance(c);
        if r > door_half || r < 0.5 {
            continue;
        }
        // A local minimum along the axis: no axis neighbour is narrower.
        let narrowest = RING8
            .iter()
            .all(|&d| axis.offset(c, d).is_none_or(|n| !axis[n] || d4[n] >= d4[c]));
        if narrowest {
            candidates.push((d4[c], c));
        }
    }
    // Only candidates that narrow between two wider spaces can be doors;
    // of equally narrow ones (a passage of even width, a candidate per cell
    // along it), the one where the passage opens into the narrower of the
    // two spaces comes first, so that the passage belongs to the space it
    // leads into (an office's doorway to the office, not to the corridor).
    // Offsets as far as the widest candidate's search reaches.
    let widest = candidates.iter().map(|&(d, _)| d).max().unwrap_or(0);
    let nearest_first = nearest_first(((widest as f64).sqrt() / 2.0 + 2.0).ceil() as usize);
    let mut candidates: Vec<(u64, u32, Cell)> = candidates
        .into_par_iter()
        .filter_map(|(d, c)| {
            let [a, b] = openings(free, &d4, c, door_half, &nearest_first)?;
            let near = if a.space <= b.space { a.at } else { b.at };
            Some((d, (2.0 * near) as u32, c))
        })
        .collect();
    candidates.sort_unstable();
    let mut cut = Grid::new(w, h, false);
    // The doors chosen so far, in square buckets at least as wide as the
    // largest spacing tested below (both clearances at most `door_half`).
    // (At least one cell, whatever the parameters: NaN gives 1.)
    let bucket = (2.0 * door_half + 4.0).ceil().max(1.0) as usize;
    let (bw, bh) = (w.div_ceil(bucket), h.div_ceil(bucket));
    let mut chosen: Vec<Vec<(Cell, f64)>> = vec![Vec::new(); bw * bh];
    for &(_, _, c) in &candidates {
        let r = clearance(c);
        let (br, bc) = (c.row / bucket, c.col / bucket);
        let near = (br.saturating_sub(1)..(br + 2).min(bh))
            .flat_map(|i| (bc.saturating_sub(1)..(bc + 2).min(bw)).map(move |j| i * bw + j));
        if near.flat_map(|b| &chosen[b]).any(|&(o, ro)| {
            let d = (o.row as f64 - c.row as f64).hypot(o.col as f64 - c.col as f64);
            d < r + ro + 3.0
        }) {
            continue;
        }
        let disc = r + 1.5;
        chosen[br * bw + bc].push((c, r));
        let k = disc.ceil() as isize;
        for dr in -k..=k {
            for dc in -k..=k {
                if ((dr * dr + dc * dc) as f64) <= disc * disc {
                    if let Some(n) = at(c, (dr, dc)) {
                        cut[n] = true;
                    }
                }
            }
        }
    }
    // Regions of the free space minus the cuts (numbered by their first
    // cell in row-major order).
    let open = Grid::par_from_fn(w, h, |c| free[c] && !cut[c]);
    let regions = components4(&open);
    let count = regions.count() as u32;
    let mut labels = regions.labels;
    // Grow back over the cuts, then merge small regions.
    // Only labelled cells beside an unlabelled free one label anything (the
    // others, taken first in the same order, would find nothing to grow
    // into): the same rooms as from every labelled cell.
    let mut queue: VecDeque<Cell> = {
        let (ids, free) = (labels.as_slice(), free.as_slice());
        let unlabelled = |n: usize| free[n] && ids[n] == 0;
        let seeds: Vec<Cell> = (0..ids.len())
            .into_par_iter()
            .filter(|&i| {
                let col = i % w;
                ids[i] != 0
                    && (i.checked_sub(w).is_some_and(unlabelled)
                        || (col > 0 && unlabelled(i - 1))
                        || (col + 1 < w && unlabelled(i + 1))
                        || (i + w < ids.len() && unlabelled(i + w)))
            })
            .map(|i| Cell::new(i / w, i % w))
            .collect();
        seeds.into()
    };
    grow(free, &mut labels, &mut queue);
    // Regions made of cut cells only.
    label_the_rest(free, &mut labels, count + 1);
    merge_small_regions(&mut labels, min_cells);
    // Relabel: rooms of at least the smallest area first, then the smaller
    // free regions (isolated specks no door joins), each in row-major order
    // of first cells.
    // Labels are small integers: per-label tables are plain vectors.
    // By index: these passes read every cell.
    let top = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let mut size = vec![0usize; top + 1];
    let mut first: Vec<u32> = Vec::new();
    for &l in labels.as_slice() {
        if l != 0 {
            if size[l as usize] == 0 {
                first.push(l);
            }
            size[l as usize] += 1;
        }
    }
    let big = |l: &u32| size[*l as usize] as f64 >= min_cells;
    let order: Vec<u32> = first
        .iter()
        .filter(|l| big(l))
        .chain(first.iter().filter(|l| !big(l)))
        .copied()
        .collect();
    let seeded = first.iter().filter(|l| big(l)).count();
    let mut fresh = vec![0u32; top + 1];
    for (i, &l) in order.iter().enumerate() {
        fresh[l as usize] = i as u32 + 1;
    }
    let mut areas = vec![0usize; order.len()];
    for l in labels.as_mut_slice() {
        if *l != 0 {
            let id = fresh[*l as usize];
            areas[id as usize - 1] += 1;
            *l = id;
        }
    }
    let doors = doors(&labels);
    Rooms {
        seeded,
        labels,
        areas,
        doors,
    }
}

/// The cells of the medial axis of the free cells of `free` (a grid
/// stand-in for the generalised Voronoi diagram: the free cells whose
/// clearance `d4`, 4·clearance² as [`boundary_distance_sq4`] gives it, is a
/// crest along at least one of the four line directions through them, not
/// lower than either neighbour on the line and higher than one) whose
/// `4·clearance²` lies in `range`, row-major: looks at the crest only where
/// the clearance is in range (the narrow parts of the axis, without the
/// whole grid's).
pub(crate) fn axis_cells_in(
    free: &Grid<bool>,
    d4: &Grid<u64>,
    range: std::ops::RangeInclusive<u64>,
) -> Vec<Cell> {
    let (w, h) = (free.width(), free.height());
    let (fs, ds) = (free.as_slice(), d4.as_slice());
    // (By index: the cell's value where free, 0 where not or off the grid.)
    let at = |r: isize, c: isize| {
        if r < 0 || c < 0 || r >= h as isize || c >= w as isize {
            0
        } else {
            let i = r as usize * w + c as usize;
            if fs[i] { ds[i] } else { 0 }
        }
    };
    let rows: Vec<Vec<Cell>> = (0..h)
        .into_par_iter()
        .map(|r| {
            let mut out = Vec::new();
            let (free_row, d_row) = (&fs[r * w..(r + 1) * w], &ds[r * w..(r + 1) * w]);
            for (col, (_, &v)) in free_row
                .iter()
                .zip(d_row)
                .enumerate()
                .filter(|&(_, (&f, v))| f && range.contains(v))
            {
                let (ri, ci) = (r as isize, col as isize);
                let crest = if r > 0 && col > 0 && r + 1 < h && col + 1 < w {
                    // (Inside the grid's frame: the neighbours by offset.)
                    let i = r * w + col;
                    let at = |j: usize| if fs[j] { ds[j] } else { 0 };
                    [1, w, w + 1, w - 1].iter().any(|&o| {
                        let (a, b) = (at(i + o), at(i - o));
                        v >= a && v >= b && (v > a || v > b)
                    })
                } else {
                    LINES.iter().any(|&(dr, dc)| {
                        let (a, b) = (at(ri + dr, ci + dc), at(ri - dr, ci - dc));
                        v >= a && v >= b && (v > a || v > b)
                    })
                };
                if crest {
                    out.push(Cell::new(r, col));
                }
            }
            out
        })
        .collect();
    rows.into_iter().flatten().collect()
}

/// Where the axis at `c` opens into a wider space on either side, if it
/// narrows there between two: along the axis (across the critical line,
/// the line from `c` to its nearest wall cell) on both sides, within a
/// wall's thickness and the wider space's clearance, a straight walk over
/// free cells reaches a cell of clearance at least [`WIDER`] cells more
/// than `c`'s. Each side's opening: how far that cell is from `c`, and the
/// clearance of the space beyond ([`crest`]).
fn openings(
    free: &Grid<bool>,
    d4: &Grid<u64>,
    c: Cell,
    door_half: f64,
    nearest_first: &[(isize, isize)],
) -> Option<[Opening; 2]> {
    let r = (d4[c] as f64).sqrt() / 2.0;
    let wide = r + WIDER;
    let wide4 = (4.0 * wide * wide).ceil() as u64;
    // The nearest non-free cell (or the map edge) round `c`, within `k`
    // rows and columns: the first in `nearest_first` order. None lies
    // nearer than the clearance (a cell's boundary is no farther than its
    // centre), so the search starts there.
    let k = (r + 2.0).ceil() as isize;
    let from = nearest_first.partition_point(|&(dr, dc)| 4 * (dr * dr + dc * dc) < d4[c] as isize);
    let best = nearest_first[from..]
        .iter()
        .filter(|&&(dr, dc)| dr.abs() <= k && dc.abs() <= k)
        .find(|&&(dr, dc)| free.offset(c, (dr, dc)).is_none_or(|n| !free[n]))
        .map(|&(dr, dc)| {
            let d = ((dr * dr + dc * dc) as f64).sqrt();
            (d, (dr as f64 / d, dc as f64 / d))
        });
    let (_, (ur, uc)) = best?;
    // Along the axis: perpendicular to the critical line.
    let (pr, pc) = (-uc, ur);
    let reach = wide + door_half.min(2.0 * r) + 2.0;
    let cell_at = |sign: f64, t: f64| {
        let (rr, cc) = (
            c.row as f64 + 0.5 + sign * t * pr,
            c.col as f64 + 0.5 + sign * t * pc,
        );
        (rr >= 0.0 && cc >= 0.0)
            .then(|| Cell::new(rr as usize, cc as usize))
            .filter(|&q| free.get(q) == Some(&true))
    };
    let side = |sign: f64| {
        let mut t = 0.5;
        while t <= reach {
            let q = cell_at(sign, t)?;
            if d4[q] >= wide4 {
                return Some(Opening {
                    at: t,
                    space: crest(d4, q),
                });
            }
            t += 0.5;
        }
        None
    };
    Some([side(1.0)?, side(-1.0)?])
}

/// The clearance (4·d²) where a climb from `c` to ever wider neighbours
/// stops: the widest point of the space `c` opens into, as seen from it
/// (a climb never leads back through a narrower door).
fn crest(d4: &Grid<u64>, mut c: Cell) -> u64 {
    let (w, h) = (d4.width(), d4.height());
    let d = d4.as_slice();
    loop {
        // The widest neighbour, of equally wide ones the first in row-major
        // order: by index away from the grid's edge.
        let next = if c.row > 0 && c.col > 0 && c.row + 1 < h && c.col + 1 < w {
            let i = c.row * w + c.col;
            RING8
                .iter()
                .map(|&(dr, dc)| i.wrapping_add_signed(dr * w as isize + dc))
                .max_by_key(|&j| (d[j], std::cmp::Reverse(j)))
                .map(|j| Cell::new(j / w, j % w))
        } else {
            RING8
                .iter()
                .filter_map(|&o| d4.offset(c, o))
                .max_by_key(|&n| (d4[n], std::cmp::Reverse(n)))
        };
        match next {
            Some(n) if d4[n] > d4[c] => c = n,
            _ => return d4[c],
        }
    }
}

/// Where a narrowing opens into a wider space ([`openings`]).
#[derive(Clone, Copy, Debug)]
struct Opening {
    /// Distance from the candidate (cells).
    at: f64,
    /// The 4·clearance² of the space beyond: where a climb from the
    /// opening stops ([`crest`]).
    space: u64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::ascii_mask;

    fn params(res: f64) -> RoomParams {
        RoomParams {
            resolution: res,
            min_area_m2: 4.0,
            max_area_m2: 47.0,
            door_width_m: 1.2,
        }
    }

    /// Two 10 × 10 rooms joined by a door 2 cells wide (0.2 m cells: rooms
    /// of 4 m², a 0.4 m door): two rooms, one door between them.
    #[test]
    fn two_rooms_and_a_door() {
        let mut rows = Vec::new();
        for r in 0..10 {
            let door = if r == 4 || r == 5 { '.' } else { '#' };
            rows.push(format!("{}{door}{}", ".".repeat(10), ".".repeat(10)));
        }
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let free = ascii_mask(&refs).unwrap();
        let rooms = voronoi(&free, &params(0.2));
        assert_eq!(rooms.count(), 2, "{:?}", rooms.areas);
        assert_ne!(
            rooms.labels[Cell::new(0, 0)],
            rooms.labels[Cell::new(0, 20)]
        );
        assert_eq!(rooms.doors.len(), 1);
    }

    /// A plain corridor is one room: its constant width is no narrowing.
    #[test]
    fn a_corridor_is_one_room() {
        let rows = vec!["........................................"; 3];
        let free = ascii_mask(&rows).unwrap();
        assert_eq!(voronoi(&free, &params(0.2)).count(), 1);
    }

    /// Three rooms in a row, joined by two doors.
    #[test]
    fn a_chain_of_three() {
        let mut rows = Vec::new();
        for r in 0..12 {
            let door = if (5..=6).contains(&r) { '.' } else { '#' };
            rows.push(format!(
                "{}{door}{}{door}{}",
                ".".repeat(12),
                ".".repeat(12),
                ".".repeat(12)
            ));
        }
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let free = ascii_mask(&refs).unwrap();
        let rooms = voronoi(&free, &params(0.2));
        assert_eq!(rooms.count(), 3, "{:?}", rooms.areas);
        assert_eq!(rooms.doors.len(), 2);
    }

    /// An office (14 × 14 cells) opens onto a corridor 7 cells wide through
    /// a doorway 2 cells wide and 4 long: the doorway is the office's, cut
    /// where it meets the narrower corridor (its last row, which the cut's
    /// disc centres on, may go either way), whichever side the office is
    /// on (a row-major tie-break among the doorway's equally narrow cells
    /// gave it to whichever space lies below).
    #[test]
    fn a_doorway_belongs_to_the_room_it_leads_into() {
        for office_above in [true, false] {
            let office: Vec<String> = (0..14)
                .map(|_| format!("{}{}{}", "#".repeat(10), ".".repeat(14), "#".repeat(16)))
                .collect();
            let doorway: Vec<String> = (0..4)
                .map(|_| format!("{}..{}", "#".repeat(16), "#".repeat(22)))
                .collect();
            let corridor: Vec<String> = (0..7).map(|_| ".".repeat(40)).collect();
            let rows: Vec<String> = if office_above {
                [office, doorway, corridor].concat()
            } else {
                [corridor, doorway, office].concat()
            };
            let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
            let free = ascii_mask(&refs).unwrap();
            let rooms = voronoi(&free, &params(0.2));
            assert_eq!(rooms.count(), 2, "{:?}", rooms.areas);
            let (office_cell, doorway_rows) = if office_above {
                (Cell::new(5, 15), 14..17)
            } else {
                (Cell::new(15, 15), 8..11)
            };
            let office_label = rooms.labels[office_cell];
            for r in doorway_rows {
                for c in 16..18 {
                    assert_eq!(
                        rooms.labels[Cell::new(r, c)],
                        office_label,
                        "office above: {office_above}, doorway cell ({r}, {c})"
                    );
                }
            }
        }
    }

    /// Door widths the CLI refuses still segment (as one room) when the
    /// library is called with them, never panic.
    #[test]
    fn odd_door_widths_do_not_panic() {
        let rows = vec!["....#....", ".........", "....#...."];
        let free = ascii_mask(&rows).unwrap();
        for door in [f64::NAN, -3.0, 0.0, f64::INFINITY, 1e300] {
            let p = RoomParams {
                door_width_m: door,
                ..params(0.2)
            };
            let rooms = voronoi(&free, &p);
            assert!(
                rooms
                    .labels
                    .as_slice()
                    .iter()
                    .all(|&l| l <= rooms.areas.len() as u32)
            );
        }
    }
}
