//! Small islands and splices: specks and table legs in the open cost no
//! more than their own loop.
//!
//! A small island (a blocked component of the C-space off the walls, of at
//! most ([`ISLAND_SPAN`] tool radii + 4 cells)² cells) would cut every lane
//! through the hole it leaves in the lane mask, and each cut room would fall
//! into chains of its own with a transit to the island's loop besides.
//! Instead two runs of a line whose gap holds only plannable cells and such
//! an island are one lane, driven round the island ([`super::layout`]), and
//! the island's loop is spliced into the lane passing nearest: left at its
//! nearest point, round the loop the way the lane runs, back to that point.
//! An island up to twice as wide ([`SPLICE_SPAN`]: a pillar, a small table)
//! still cuts the lanes, but its loop too is driven from the lane passing
//! nearest rather than reached as a node of the order.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): without it
//! 0.2 % (ipa) / 0.9 % (ROS) slower; in a room with 16 specks far more
//! (the synthetic rooms of the same page).

use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear};
use oxcover_grid::{Cell, Grid, Vector};

use super::layout::Chain;
use super::loops::{EdgeLoop, RING, drive_loop_from};
use crate::error::Result;
use crate::metre_path::PathBuilder;

/// Largest island that lanes pass, in tool radii across (with robot = tool
/// radius an obstacle of about 0.2 m; larger ones, the pillar arenas'
/// pillars, were slower passed).
const ISLAND_SPAN: f64 = 2.0;

/// Largest island whose loop a lane drives, in tool radii across (of 3 to
/// 6, the fastest on both map sets).
const SPLICE_SPAN: f64 = 4.0;

/// The small islands of blocked cells: 4-connected components of the
/// cells that are not plannable, of at most `max_cells` cells, off the
/// grid's edge and touching no other blocked component even diagonally.
/// Each island cell holds its island's size in cells, every other cell 0.
fn small_islands(plannable: &Grid<bool>, max_cells: usize) -> Grid<usize> {
    let blocked = plannable.map(|&p| !p);
    let comps = oxcover_grid::components::components4(&blocked);
    let mut ok = vec![false; comps.count() + 1];
    for (i, &n) in comps.sizes.iter().enumerate() {
        ok[i + 1] = n <= max_cells;
    }
    let (w, h) = (plannable.width(), plannable.height());
    for c in blocked.true_cells() {
        let l = comps.labels[c] as usize;
        if !ok[l] {
            continue;
        }
        if c.row == 0 || c.col == 0 || c.row + 1 == h || c.col + 1 == w {
            ok[l] = false;
            continue;
        }
        for d in RING {
            if let Some(n) = blocked.offset(c, d) {
                let m = comps.labels[n] as usize;
                if m != 0 && m != l {
                    ok[l] = false;
                }
            }
        }
    }
    comps.labels.map(|&l| {
        let l = l as usize;
        if ok[l] { comps.sizes[l - 1] } else { 0 }
    })
}

/// The islands that lanes pass ([`ISLAND_SPAN`]) and the islands whose
/// loops a lane drives ([`SPLICE_SPAN`]; the first are among them), for
/// a tool of `tool` cells.
pub(super) fn island_masks(plannable: &Grid<bool>, tool: f64) -> (Grid<bool>, Grid<bool>) {
    let most = |span: f64| ((span * tool).ceil() as usize + 4).pow(2);
    let sizes = small_islands(plannable, most(SPLICE_SPAN));
    let up_to = |n: usize| sizes.map(|&s| s > 0 && s <= n);
    (up_to(most(ISLAND_SPAN)), up_to(most(SPLICE_SPAN)))
}

/// A small island's loop driven as an excursion from the lane passing
/// nearest: the lane is left at the point nearest the loop, the loop is
/// driven round from there (the way the lane runs), and the lane goes on
/// from the same point.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Splice {
    /// The chain and its lane.
    pub(super) chain: usize,
    lane: usize,
    /// Where along the lane: 0 at its `a` end, 1 at `b`.
    u: f64,
    /// The loop, and the cell it is entered at (piece, index).
    pub(super) loop_index: usize,
    entry: (usize, usize),
}

/// The splices of the loops round `islands`: each closed loop all of whose
/// cells border an island cell goes to the lane whose nearest point to one of its cells is
/// nearest, plannable and in clear sight of that cell, among the lanes
/// within two lane spacings of the loop's box; a loop with no such lane
/// stays a node of the order.
pub(super) fn splices_for(
    loops: &[EdgeLoop],
    chains: &[Chain],
    islands: &Grid<bool>,
    plannable: &Grid<bool>,
    spacing: f64,
) -> Vec<Splice> {
    let margin = 2.0 * spacing.max(1.0);
    let mut out = Vec::new();
    for (li, l) in loops.iter().enumerate() {
        let round_island = l.closed
            && l.pieces.iter().flatten().all(|&c| {
                RING.iter()
                    .any(|&d| islands.offset(c, d).is_some_and(|n| islands[n]))
            });
        if !round_island {
            continue;
        }
        let cells: Vec<(GridPoint, (usize, usize))> = l
            .pieces
            .iter()
            .enumerate()
            .flat_map(|(p, piece)| {
                piece
                    .iter()
                    .enumerate()
                    .map(move |(i, &c)| (cell_center(c), (p, i)))
            })
            .collect();
        let (lo, hi) = cells.iter().fold(
            (
                GridPoint::new(f64::INFINITY, f64::INFINITY),
                GridPoint::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            ),
            |(lo, hi), (q, _)| (lo.inf(q), hi.sup(q)),
        );
        let mut best: Option<(f64, Splice)> = None;
        for (ci, c) in chains.iter().enumerate() {
            for (ki, lane) in c.lanes.iter().enumerate() {
                let (a, b) = (lane.a, lane.b);
                if a.x.max(b.x) < lo.x - margin
                    || a.x.min(b.x) > hi.x + margin
                    || a.y.max(b.y) < lo.y - margin
                    || a.y.min(b.y) > hi.y + margin
                {
                    continue;
                }
                let d = b - a;
                let len2 = d.norm_squared();
                for &(q, entry) in &cells {
                    let u = if len2 > 0.0 {
                        ((q - a).dot(&d) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let at = a + d * u;
                    let dist = (at - q).norm();
                    if best.as_ref().is_some_and(|b| dist >= b.0) {
                        continue;
                    }
                    if cell_of(plannable, at).is_some_and(|x| plannable[x])
                        && segment_clear(plannable, at, q)
                    {
                        let splice = Splice {
                            chain: ci,
                            lane: ki,
                            u,
                            loop_index: li,
                            entry,
                        };
                        best = Some((dist, splice));
                    }
                }
            }
        }
        out.extend(best.map(|(_, s)| s));
    }
    out
}

/// Drives chain `c` under `option`: each lane along its line (round any
/// island it passes), with the loops of `splices` (this chain's) driven
/// from their lanes.
pub(super) fn drive_chain(
    path: &mut PathBuilder<'_>,
    c: &Chain,
    option: usize,
    splices: &[&Splice],
    loops: &[EdgeLoop],
    tolerance: f64,
) -> Result<()> {
    let backwards = option & 1 == 1;
    let mut flip = option & 2 == 2;
    let idx: Vec<usize> = if backwards {
        (0..c.lanes.len()).rev().collect()
    } else {
        (0..c.lanes.len()).collect()
    };
    for k in idx {
        let l = c.lanes[k];
        let (from, to) = if flip { (l.b, l.a) } else { (l.a, l.b) };
        path.go_to(from)?;
        let mut here: Vec<(f64, &Splice)> = splices
            .iter()
            .filter(|s| s.lane == k)
            .map(|s| (if flip { 1.0 - s.u } else { s.u }, *s))
            .collect();
        here.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (v, s) in here {
            let at = from + (to - from) * v;
            path.go_along(at)?;
            drive_splice(path, &loops[s.loop_index], s.entry, to - from, tolerance)?;
            path.go_to(at)?;
        }
        path.go_along(to)?;
        flip = !flip;
    }
    Ok(())
}

/// Drives closed loop `l` from its cell `entry` back to it, round the way
/// that leaves the entry along `heading` rather than against it.
fn drive_splice(
    path: &mut PathBuilder<'_>,
    l: &EdgeLoop,
    entry: (usize, usize),
    heading: Vector,
    tolerance: f64,
) -> Result<()> {
    let (p, i) = entry;
    let flat: Vec<Cell> = l.pieces.iter().flatten().copied().collect();
    let e: usize = l.pieces[..p].iter().map(Vec::len).sum::<usize>() + i;
    let m = flat.len();
    let ahead = cell_center(flat[(e + 2) % m]) - cell_center(flat[(e + m - 2) % m]);
    path.go_to(cell_center(l.pieces[p][i]))?;
    if ahead.dot(&heading) < 0.0 {
        let reversed = EdgeLoop {
            pieces: l
                .pieces
                .iter()
                .rev()
                .map(|q| q.iter().rev().copied().collect())
                .collect(),
            closed: true,
        };
        let entry = (l.pieces.len() - 1 - p, l.pieces[p].len() - 1 - i);
        drive_loop_from(path, &reversed, 0, Some(entry), tolerance)
    } else {
        drive_loop_from(path, l, 0, Some(entry), tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    use crate::lanes::layout::{LINE_MARGIN, chains_at, chains_bridged, lane_mask};
    use crate::lanes::loops::{OUTSET, edge_loops};
    use crate::lanes::nodes::{Node, nodes_of};
    use oxcover_grid::traverse::segment_distance;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    /// A blocked cell of `rows` (a string of `.`) at each of `cells`.
    fn with_blocked(w: usize, h: usize, cells: &[(usize, usize)]) -> Vec<String> {
        let mut rows: Vec<String> = (0..h).map(|_| ".".repeat(w)).collect();
        for &(r, c) in cells {
            rows[r].replace_range(c..=c, "#");
        }
        rows
    }

    fn block(rows: std::ops::Range<usize>, cols: std::ops::Range<usize>) -> Vec<(usize, usize)> {
        rows.flat_map(|r| cols.clone().map(move |c| (r, c)))
            .collect()
    }

    /// A speck in the open is an island; a wall, a speck touching a wall
    /// diagonally and a block over the size limit are not.
    #[test]
    fn small_islands_are_specks_off_the_walls() {
        let mut cells = block(0..1, 0..30);
        cells.extend(block(8..10, 8..10));
        cells.extend([(1, 21), (2, 20)]);
        cells.extend(block(12..17, 18..23));
        let rows = with_blocked(30, 20, &cells);
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let islands = small_islands(&mask(&refs), 16).map(|&n| n > 0);
        let found: Vec<Cell> = islands.true_cells().collect();
        assert_eq!(
            found,
            vec![
                Cell::new(8, 8),
                Cell::new(8, 9),
                Cell::new(9, 8),
                Cell::new(9, 9)
            ]
        );
    }

    /// A room with a speck (its C-space blot 6 × 6 cells), tool 3 cells:
    /// without islands the lines through the speck's hole in the lane mask
    /// stop at it and the room falls into several chains; with them each
    /// line keeps one lane across the room, as in the bare room, and the
    /// speck's loop goes to the lane passing nearest.
    #[test]
    fn lanes_run_past_a_speck_and_drive_its_loop() {
        let (w, h, tool) = (60, 40, 3.0);
        let rows = with_blocked(w, h, &block(17..23, 27..33));
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let plannable = mask(&refs);
        let lanes = lane_mask(&plannable, &plannable, tool);
        let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
        let inset = tool - OUTSET - LINE_MARGIN;
        let islands = small_islands(&plannable, 100).map(|&n| n > 0);
        assert_eq!(islands.count_true(), 36);
        let (cut, _) = chains_at(&plannable, &lanes, None, PI / 2.0, spacing, inset);
        let (passed, _) = chains_bridged(
            &plannable,
            &lanes,
            None,
            Some(&islands),
            PI / 2.0,
            spacing,
            inset,
        );
        let bare = Grid::new(w, h, true);
        let bare_lanes = lane_mask(&bare, &bare, tool);
        let (open, _) = chains_at(&bare, &bare_lanes, None, PI / 2.0, spacing, inset);
        assert_eq!(open.len(), 1);
        assert!(cut.len() > 1, "{} chains", cut.len());
        assert_eq!(passed.len(), 1);
        assert_eq!(passed[0].lanes.len(), open[0].lanes.len());
        // The speck's loop is the second (traced after the room's border)
        // and goes to a lane; the order then has one loop node, the border.
        let loops = edge_loops(&plannable, &plannable);
        assert_eq!(loops.len(), 2);
        let splices = splices_for(&loops, &passed, &islands, &plannable, spacing);
        assert_eq!(splices.len(), 1);
        assert_eq!(splices[0].loop_index, 1);
        let nodes = nodes_of(&loops, &passed, &splices);
        assert_eq!(nodes.len(), 2);
        assert!(matches!(nodes[0], Node::Loop(l) if std::ptr::eq(l, &loops[0])));
        // Driven, every piece is clear and the loop is driven whole.
        assert_drives_clear_and_whole(&plannable, &passed[0], &splices, &loops[1], &loops);
    }

    /// Chain `c` driven with `splices`: every piece is clear, and each cell
    /// of `spliced` (a loop a lane drives) lies within the loop tolerance
    /// of the path.
    fn assert_drives_clear_and_whole(
        plannable: &Grid<bool>,
        c: &Chain,
        splices: &[Splice],
        spliced: &EdgeLoop,
        loops: &[EdgeLoop],
    ) {
        let here: Vec<&Splice> = splices.iter().collect();
        let mut path = PathBuilder::new(plannable, Cell::new(1, 1));
        drive_chain(&mut path, c, 0, &here, loops, 0.8).unwrap();
        let pts = path.points();
        for s in pts.windows(2) {
            assert!(segment_clear(plannable, s[0], s[1]), "{s:?}");
        }
        for cell in spliced.cells() {
            let near = pts
                .windows(2)
                .map(|s| segment_distance(s[0], s[1], cell_center(cell)))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= 1.0, "{cell:?} {near}");
        }
    }

    /// A room with a table (its C-space blot 12 × 12 cells), tool 3
    /// cells: too large for lanes to pass (the lines through it are cut),
    /// small enough that its loop is driven from the lane passing nearest
    /// rather than ordered as a node of its own.
    #[test]
    fn a_table_cuts_the_lanes_but_a_lane_drives_its_loop() {
        let (w, h, tool) = (60, 40, 3.0);
        let rows = with_blocked(w, h, &block(14..26, 24..36));
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let plannable = mask(&refs);
        let (passed, spliced) = island_masks(&plannable, tool);
        assert_eq!(passed.count_true(), 0);
        assert_eq!(spliced.count_true(), 144);
        let lanes = lane_mask(&plannable, &plannable, tool);
        let spacing = 2.0 * (tool * tool - 1.0 / 64.0).sqrt() * 0.999;
        let inset = tool - OUTSET - LINE_MARGIN;
        let (chains, _) = chains_bridged(
            &plannable,
            &lanes,
            None,
            Some(&passed),
            PI / 2.0,
            spacing,
            inset,
        );
        assert!(chains.len() > 1, "{} chains", chains.len());
        let loops = edge_loops(&plannable, &plannable);
        assert_eq!(loops.len(), 2);
        // Only the islands that lanes pass: the table's loop is a node.
        assert!(splices_for(&loops, &chains, &passed, &plannable, spacing).is_empty());
        let splices = splices_for(&loops, &chains, &spliced, &plannable, spacing);
        assert_eq!(splices.len(), 1);
        assert_eq!(splices[0].loop_index, 1);
        let nodes = nodes_of(&loops, &chains, &splices);
        assert_eq!(nodes.len(), chains.len() + 1);
        // The chain holding the splice, driven: every piece is clear and
        // the table's loop is driven whole.
        let c = &chains[splices[0].chain];
        assert_drives_clear_and_whole(&plannable, c, &splices, &loops[1], &loops);
    }
}
