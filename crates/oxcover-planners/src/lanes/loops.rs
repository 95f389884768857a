//! Edge loops: a loop along every wall and piece of furniture.
//!
//! Every contour of the region's plannable cells (the robot's C-space) is
//! traced by Moore neighbour tracing and driven once. Its waypoints sit in
//! the boundary cells, pushed towards the wall ([`OUTSET`] of a cell, still
//! inside the cell, so the tool reaches as far into the strip along the
//! wall as the robot may go), and the staircase is straightened within
//! [`loop_tolerance`]. Where the region borders another room's plannable
//! cells (a room cut, not a wall) the contour opens into runs along the
//! walls only. A loop along a ragged wall turns at every pixel it follows;
//! the shared tightening ([`crate::detours`]) takes those turns out later,
//! wherever coverage allows.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): without the
//! straightening the mean estimated time is 7.1 % higher on the ipa plans,
//! 0.8 % on the ROS maps.

use oxcover_grid::traverse::{GridPoint, cell_center, segment_clear, segment_distance};
use oxcover_grid::{Cell, Grid};

use crate::error::Result;
use crate::metre_path::PathBuilder;

/// Entry points tried per loop.
pub(super) const LOOP_ENTRIES: usize = 8;

/// A traced contour, or the part of one that runs along walls: 4-connected
/// pieces of boundary cells (a diagonal step squeezing between two blocked
/// cells starts a new piece). A closed loop is driven round from any of its
/// entries back to it; an open run (a contour cut where the region borders
/// another room's plannable cells) from one end to the other.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct EdgeLoop {
    pub(super) pieces: Vec<Vec<Cell>>,
    pub(super) closed: bool,
}

impl EdgeLoop {
    /// Every cell of its pieces, in order.
    #[cfg(test)]
    pub(super) fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        self.pieces.iter().flatten().copied()
    }

    /// How many cells it holds.
    pub(super) fn len(&self) -> usize {
        self.pieces.iter().map(Vec::len).sum()
    }

    /// The `k`-th of `LOOP_ENTRIES` evenly spaced entry cells.
    pub(super) fn entry(&self, k: usize) -> (usize, usize) {
        let n = self.len();
        let mut i = (k * n) / LOOP_ENTRIES;
        for (p, piece) in self.pieces.iter().enumerate() {
            if i < piece.len() {
                return (p, i);
            }
            i -= piece.len();
        }
        (0, 0)
    }
}

/// Clockwise neighbours in grid coordinates (row down): W, NW, N, NE, E, SE, S, SW.
pub(super) const RING: [(isize, isize); 8] = [
    (0, -1),
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
    (1, 0),
    (1, -1),
];

fn set_at(mask: &Grid<bool>, c: Cell, d: (isize, isize)) -> Option<Cell> {
    mask.offset(c, d).filter(|&n| mask[n])
}

/// Every contour of `mask` (outer boundaries and holes), traced by Moore
/// neighbour tracing from each boundary cell whose west neighbour is not set
/// and that no earlier contour passed, keeping only the cells along walls:
/// a boundary cell all of whose outside neighbours are `admissible` borders
/// another region (a room cut), not a wall, and is left out, which opens
/// the contour into runs.
pub(super) fn edge_loops(mask: &Grid<bool>, admissible: &Grid<bool>) -> Vec<EdgeLoop> {
    let mut on_contour = Grid::new(mask.width(), mask.height(), false);
    let mut loops = Vec::new();
    let by_wall = |c: Cell| {
        RING.iter().any(|&d| match mask.offset(c, d) {
            None => true,
            Some(n) => !mask[n] && !admissible[n],
        })
    };
    for s in mask.true_cells() {
        if on_contour[s] || set_at(mask, s, (0, -1)).is_some() {
            continue;
        }
        let trace = moore_trace(mask, s);
        for &c in &trace {
            on_contour[c] = true;
        }
        let walls: Vec<bool> = trace.iter().map(|&c| by_wall(c)).collect();
        if walls.iter().all(|&w| w) {
            loops.push(EdgeLoop {
                pieces: four_connected_pieces(mask, &trace, true),
                closed: true,
            });
            continue;
        }
        // Open runs: start after a cut cell so that no run wraps around.
        let n = trace.len();
        let first_cut = walls.iter().position(|&w| !w).unwrap_or(0);
        let mut run: Vec<Cell> = Vec::new();
        for k in 1..=n {
            let i = (first_cut + k) % n;
            if walls[i] {
                run.push(trace[i]);
            } else if !run.is_empty() {
                loops.push(EdgeLoop {
                    pieces: four_connected_pieces(mask, &run, false),
                    closed: false,
                });
                run.clear();
            }
        }
        if !run.is_empty() {
            loops.push(EdgeLoop {
                pieces: four_connected_pieces(mask, &run, false),
                closed: false,
            });
        }
    }
    loops
}

/// The closed Moore trace from `s` (its west neighbour unset), ending
/// before it returns to `s` the way it first left (Jacob's criterion).
fn moore_trace(mask: &Grid<bool>, s: Cell) -> Vec<Cell> {
    let Some((n1, b1)) = moore_step(mask, s, 0) else {
        return vec![s];
    };
    let mut trace = vec![s];
    let (mut here, mut back) = (n1, b1);
    let limit = 4 * mask.count_true() + 8;
    for _ in 0..limit {
        if here == s {
            let Some((n, b)) = moore_step(mask, s, back) else {
                break;
            };
            if n == n1 {
                break;
            }
            trace.push(s);
            (here, back) = (n, b);
            continue;
        }
        trace.push(here);
        match moore_step(mask, here, back) {
            Some((n, b)) => (here, back) = (n, b),
            None => break,
        }
    }
    trace
}

/// The next contour cell clockwise around `here` from the unset neighbour
/// at ring index `back`, and the new backtrack index seen from it.
fn moore_step(mask: &Grid<bool>, here: Cell, back: usize) -> Option<(Cell, usize)> {
    for k in 1..=8 {
        let idx = (back + k) % 8;
        if let Some(n) = set_at(mask, here, RING[idx]) {
            // The neighbour checked just before (unset), seen from `n`.
            let prev = RING[(idx + 7) % 8];
            let from_n = (
                here.row as isize + prev.0 - n.row as isize,
                here.col as isize + prev.1 - n.col as isize,
            );
            let b = RING.iter().position(|&d| d == from_n).unwrap_or(0);
            return Some((n, b));
        }
    }
    None
}

/// Splits an 8-connected trace (closed: back to its first cell) into
/// 4-connected pieces: a diagonal step gets the plannable cell beside it, or
/// starts a new piece when both are blocked; a larger jump starts a new piece.
fn four_connected_pieces(mask: &Grid<bool>, trace: &[Cell], close: bool) -> Vec<Vec<Cell>> {
    let mut pieces = vec![Vec::new()];
    let mut closed: Vec<Cell> = trace.to_vec();
    if let (true, Some(&f)) = (close, trace.first()) {
        closed.push(f);
    }
    for (i, &c) in closed.iter().enumerate() {
        if i == 0 {
            pieces[0].push(c);
            continue;
        }
        let a = closed[i - 1];
        let (dr, dc) = (
            c.row as isize - a.row as isize,
            c.col as isize - a.col as isize,
        );
        if dr != 0 && dc != 0 {
            let side = set_at(mask, a, (dr, 0)).or_else(|| set_at(mask, a, (0, dc)));
            match side {
                Some(m) => pieces.last_mut().map(|p| p.push(m)).unwrap_or_default(),
                None => pieces.push(Vec::new()),
            }
        }
        if let Some(p) = pieces.last_mut() {
            if p.last() != Some(&c) {
                p.push(c);
            }
        }
    }
    pieces.retain(|p| !p.is_empty());
    pieces
}

/// Straightening tolerance of edge loops: half the tool radius, within
/// these bounds (cells). Under a cell: a staircase's steps sit a whole cell
/// off the line that cuts them, and skipping them left so much of the strip
/// along walls out of reach that the detours cost more than the
/// straightening saved (1.0 → 0.8: ipa plans' time efficiency 0.345 → 0.399).
const LOOP_TOLERANCE: (f64, f64) = (0.25, 0.8);

/// The straightening tolerance (cells) of a loop for a tool of `tool` cells.
pub(super) fn loop_tolerance(tool: f64) -> f64 {
    (tool / 2.0).clamp(LOOP_TOLERANCE.0, LOOP_TOLERANCE.1)
}

/// The point of boundary cell `c` pushed towards its non-plannable
/// neighbours, at most `OUTSET` of a cell from its centre along each axis
/// (so still inside the cell).
fn outset_point(mask: &Grid<bool>, c: Cell) -> GridPoint {
    let (mut x, mut y) = (0.0, 0.0);
    for &(dr, dc) in &RING {
        if set_at(mask, c, (dr, dc)).is_none() {
            let n = ((dr * dr + dc * dc) as f64).sqrt();
            x += dc as f64 / n;
            y += dr as f64 / n;
        }
    }
    let centre = cell_center(c);
    let n = x.hypot(y);
    if n < 1e-9 {
        return centre;
    }
    let (ux, uy) = (x / n, y / n);
    let t = OUTSET / ux.abs().max(uy.abs());
    GridPoint::new(centre.x + t * ux, centre.y + t * uy)
}

/// How far a loop point sits from its cell's centre, towards the walls (cells).
pub(super) const OUTSET: f64 = 0.45;

/// Drives loop `l` under `option`: a closed loop round from its entry
/// `option` ([`EdgeLoop::entry`]) back to it, an open run from its first
/// cell (option 0) or its last; straightened within `tolerance` cells.
pub(super) fn drive_loop(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    option: usize,
    tolerance: f64,
) -> Result<()> {
    let entry = l.closed.then(|| l.entry(option));
    drive_loop_from(path, l, option, entry, tolerance)
}

/// [`drive_loop`] with a closed loop's entry (piece, index) given.
pub(super) fn drive_loop_from(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    option: usize,
    entry: Option<(usize, usize)>,
    tolerance: f64,
) -> Result<()> {
    let seq: Vec<Vec<Cell>> = if let Some((p, i)) = entry {
        // The loop from its entry: the rest of the entry piece, the other
        // pieces, the start of the entry piece, back to the entry.
        let mut seq = vec![l.pieces[p][i..].to_vec()];
        for k in 1..l.pieces.len() {
            seq.push(l.pieces[(p + k) % l.pieces.len()].clone());
        }
        // The last piece of a closed loop ends at the first cell: entered
        // there, the loop is done; entered later, finish the first piece.
        if (p, i) != (0, 0) {
            seq.push(l.pieces[p][..=i].to_vec());
        }
        seq
    } else if option == 0 {
        l.pieces.clone()
    } else {
        l.pieces
            .iter()
            .rev()
            .map(|p| p.iter().rev().copied().collect())
            .collect()
    };
    let mask = path.mask();
    for piece in &seq {
        let Some(&first) = piece.first() else {
            continue;
        };
        path.go_to(cell_center(first))?;
        // Outset points, with the cell centres between two of them whose
        // straight join is not clear.
        let mut targets: Vec<GridPoint> = Vec::with_capacity(piece.len());
        let mut prev = path.last();
        for (k, &c) in piece.iter().enumerate() {
            let q = outset_point(mask, c);
            if !segment_clear(mask, prev, q) {
                if k > 0 {
                    targets.push(cell_center(piece[k - 1]));
                }
                targets.push(cell_center(c));
            }
            targets.push(q);
            prev = q;
        }
        if let Some(&last) = piece.last() {
            targets.push(cell_center(last));
        }
        path.follow_points(targets, |a, b, skipped| {
            skipped
                .iter()
                .all(|&m| segment_distance(a, b, m) <= tolerance)
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    #[test]
    fn a_rectangle_has_one_loop_of_its_border() {
        let m = mask(&["....", "....", "...."]);
        let loops = edge_loops(&m, &Grid::new(m.width(), m.height(), false));
        assert_eq!(loops.len(), 1);
        let cells: std::collections::BTreeSet<Cell> = loops[0].cells().collect();
        assert_eq!(cells.len(), 10);
        assert!(!cells.contains(&Cell::new(1, 1)) && !cells.contains(&Cell::new(1, 2)));
    }

    #[test]
    fn a_pillar_gets_its_own_loop() {
        let m = mask(&[".....", ".....", "..#..", ".....", "....."]);
        let loops = edge_loops(&m, &Grid::new(m.width(), m.height(), false));
        assert_eq!(loops.len(), 2);
        // The pillar's loop: the eight cells around it.
        let cells: std::collections::BTreeSet<Cell> = loops[1].cells().collect();
        assert_eq!(cells.len(), 8);
    }
}
