//! Transit times between the ends of the order's nodes.
//!
//! A transit's estimated seconds are its straight line's, scaled by how far
//! the walls make the way round: the ratio of the 4-connected shortest
//! route to the Manhattan distance, one breadth-first search per distinct
//! end point (over blocks of cells on a large region, where the ratios
//! hardly change and the search visits a ninth of the cells), and the turns
//! onto and off the straight line at each junction.

use rayon::prelude::*;

use oxcover_distance::Wavefront;
use oxcover_grid::traverse::{GridPoint, cell_of};
use oxcover_grid::{Cell, Dir4, Grid, Vector};

use super::nodes::Node;
use crate::detours::heading_change;
use crate::time::TimeModel;

/// Transit seconds between the ends of the nodes, with the detour walls
/// force: the straight-line time times the ratio of the 4-connected
/// shortest route to the Manhattan distance (1 where a monotone staircase
/// is clear, more where walls are in the way). One breadth-first search per
/// distinct end point, over cells or, on a large region, over blocks of
/// cells ([`Region`]); above [`TRANSIT_BUDGET`] cell visits (large regions
/// with many nodes) straight lines only.
pub(super) struct Transits {
    /// Point ids of each node's option: (entry, exit).
    pub(super) ids: Vec<Vec<(usize, usize)>>,
    /// Point id of where the path should end, if given.
    end: Option<usize>,
    points: Vec<GridPoint>,
    /// Detour ratio from every point to every point (row-major), if
    /// measured.
    ratio: Option<Vec<f32>>,
    speed: f64,
    /// Directions each node's option is entered and left along.
    headings: Vec<Vec<(Vector, Vector)>>,
    /// Turning rate (rad/s).
    turn_rate: f64,
}

impl Transits {
    /// The table for `nodes` from `start` to `end` (if given) over `region`,
    /// at the speeds of `t` (cells per second).
    pub(super) fn new(
        nodes: &[Node<'_>],
        (start, end): (GridPoint, Option<GridPoint>),
        region: &mut Region<'_>,
        t: &TimeModel,
    ) -> Self {
        let mut points: Vec<GridPoint> = Vec::new();
        let mut index: std::collections::HashMap<(u64, u64), usize> =
            std::collections::HashMap::new();
        let mut id = |p: GridPoint, points: &mut Vec<GridPoint>| {
            *index
                .entry((p.x.to_bits(), p.y.to_bits()))
                .or_insert_with(|| {
                    points.push(p);
                    points.len() - 1
                })
        };
        id(start, &mut points);
        let end = end.map(|e| id(e, &mut points));
        let ids: Vec<Vec<(usize, usize)>> = nodes
            .iter()
            .map(|n| {
                (0..n.options())
                    .map(|k| {
                        let (a, b) = n.ends(k);
                        (id(a, &mut points), id(b, &mut points))
                    })
                    .collect()
            })
            .collect();
        let n = points.len();
        let cells = region.cells as f64;
        let ratio = (n as f64 * cells <= TRANSIT_BUDGET && n * n <= 16_000_000)
            .then(|| {
                let at: Vec<Option<Cell>> = points.iter().map(|&p| region.block_of(p)).collect();
                if region.wave.is_none() {
                    region.wave = Some(region.wavefront());
                }
                let wave = region.wave.as_ref()?;
                Some(ratio_table(&at, wave))
            })
            .flatten();
        let headings = nodes
            .iter()
            .map(|n| (0..n.options()).map(|k| n.headings(k)).collect())
            .collect();
        Self {
            ids,
            end,
            points,
            ratio,
            speed: t.linear_speed,
            headings,
            turn_rate: t.angular_speed,
        }
    }

    /// Seconds of turning from leaving `prev` by option `q` to entering
    /// `node` by option `k`: onto the straight line between the two ends
    /// and off it again (or straight from one heading to the other where
    /// the ends meet).
    pub(super) fn junction(&self, prev: usize, q: usize, node: usize, k: usize) -> f64 {
        let out = self.headings[prev][q].1;
        let into = self.headings[node][k].0;
        let d = self.points[self.ids[node][k].0] - self.points[self.ids[prev][q].1];
        let turn = if d.norm() < 1.0 {
            heading_change(out, into)
        } else {
            heading_change(out, d) + heading_change(d, into)
        };
        turn / self.turn_rate
    }

    /// Seconds from point `from` to point `to`.
    pub(super) fn between(&self, from: usize, to: usize) -> f64 {
        let d = (self.points[to] - self.points[from]).norm() / self.speed;
        match &self.ratio {
            Some(r) => d * f64::from(r[from * self.points.len() + to]),
            None => d,
        }
    }

    /// Seconds from point `from` into `node` by option `k`.
    pub(super) fn entering(&self, from: usize, node: usize, k: usize) -> f64 {
        self.between(from, self.ids[node][k].0)
    }

    /// The exit point of `node` by option `k`.
    pub(super) fn exit(&self, node: usize, k: usize) -> usize {
        self.ids[node][k].1
    }

    /// Seconds from point `from` to where the path should end (0 when
    /// that is not given).
    pub(super) fn finishing(&self, from: usize) -> f64 {
        self.end.map_or(0.0, |e| self.between(from, e))
    }
}

/// Detour ratios between the blocks `at` (row-major, `n × n`): the
/// search's distance over the Manhattan distance, `1e6` where no way
/// exists, 1 where a point has no block or two share one. Points in one
/// block share its searches: one search per distinct block. The distances
/// are symmetric (every move of the wavefront goes both ways), so the
/// search from the `k`-th distinct block fills its row and column and
/// stops once it has reached the blocks after it; the searches run side by
/// side, each task with its own copy of `wave`.
fn ratio_table(at: &[Option<Cell>], wave: &Wavefront) -> Vec<f32> {
    let n = at.len();
    // The distinct blocks in order of first appearance, and each point's.
    let mut blocks: Vec<Cell> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let of: Vec<Option<usize>> = at
        .iter()
        .map(|b| {
            b.map(|b| {
                *index.entry(b).or_insert_with(|| {
                    blocks.push(b);
                    blocks.len() - 1
                })
            })
        })
        .collect();
    let m = blocks.len();
    let rows: Vec<Vec<f32>> = (0..m)
        .into_par_iter()
        .map_init(
            || wave.clone(),
            |wave, k| {
                let a = blocks[k];
                wave.propagate_until_reached(&[a], &blocks[k + 1..]);
                blocks[k + 1..]
                    .iter()
                    .map(|&b| {
                        let manhattan = a.row.abs_diff(b.row) + a.col.abs_diff(b.col);
                        match wave.distance(b) {
                            Some(d) => (f64::from(d) / manhattan as f64) as f32,
                            None => 1e6,
                        }
                    })
                    .collect()
            },
        )
        .collect();
    // Ratio between distinct blocks `k < l`.
    let between = |k: usize, l: usize| rows[k][l - k - 1];
    let mut r = vec![1.0f32; n * n];
    for i in 0..n {
        for j in i + 1..n {
            if let (Some(k), Some(l)) = (of[i], of[j])
                && k != l
            {
                let v = between(k.min(l), k.max(l));
                r[i * n + j] = v;
                r[j * n + i] = v;
            }
        }
    }
    r
}

/// The region the transit table searches, in square blocks of cells, with
/// a wavefront over the blocks to reuse (made when first needed).
pub(super) struct Region<'a> {
    plannable: &'a Grid<bool>,
    /// Side of a block (cells).
    block: usize,
    /// Plannable cells.
    cells: usize,
    wave: Option<Wavefront>,
}

impl<'a> Region<'a> {
    /// `plannable` searched cell by cell up to [`TRANSIT_EXACT_CELLS`]
    /// plannable cells, beyond in blocks of about half a tool radius
    /// ([`transit_block`]; `tool` in cells).
    pub(super) fn new(plannable: &'a Grid<bool>, tool: f64) -> Self {
        let mut region = Self::with_block(plannable, 1);
        if region.cells > TRANSIT_EXACT_CELLS {
            region.block = transit_block(tool);
        }
        region
    }

    /// `plannable` searched in blocks of `block × block` cells.
    fn with_block(plannable: &'a Grid<bool>, block: usize) -> Self {
        Self {
            plannable,
            block: block.max(1),
            cells: plannable.count_true(),
            wave: None,
        }
    }

    /// The block holding point `p`, if `p` is in a plannable cell.
    fn block_of(&self, p: GridPoint) -> Option<Cell> {
        cell_of(self.plannable, p)
            .filter(|&c| self.plannable[c])
            .map(|c| Cell::new(c.row / self.block, c.col / self.block))
    }

    /// A wavefront over the blocks: a block is open where it holds a
    /// plannable cell, and a move between two blocks is allowed where a
    /// plannable cell of one borders a plannable cell of the other across
    /// their common side. The cells within a block are taken as connected,
    /// so a wall thinner than a block less a cell may be passed through
    /// inside one; a wall at least that thick never is. (With a robot
    /// radius of a tool radius the C-space's walls are over twice as
    /// thick as a block.)
    fn wavefront(&self) -> Wavefront {
        let k = self.block;
        let p = self.plannable;
        if k == 1 {
            return Wavefront::new(p);
        }
        let (w, h) = (p.width(), p.height());
        let (bw, bh) = (w.div_ceil(k), h.div_ceil(k));
        let mut open = Grid::new(bw, bh, false);
        // Whether block (r, c) joins its east / south neighbour.
        let mut east = Grid::new(bw, bh, false);
        let mut south = Grid::new(bw, bh, false);
        for c in p.true_cells() {
            let b = Cell::new(c.row / k, c.col / k);
            open[b] = true;
            if c.col % k == k - 1 && c.col + 1 < w && p[Cell::new(c.row, c.col + 1)] {
                east[b] = true;
            }
            if c.row % k == k - 1 && c.row + 1 < h && p[Cell::new(c.row + 1, c.col)] {
                south[b] = true;
            }
        }
        let moves = Grid::from_fn(bw, bh, |b: Cell| {
            let mut m = 0;
            if b.row > 0 && south[Cell::new(b.row - 1, b.col)] {
                m |= Dir4::North.bit();
            }
            if east[b] {
                m |= Dir4::East.bit();
            }
            if south[b] {
                m |= Dir4::South.bit();
            }
            if b.col > 0 && east[Cell::new(b.row, b.col - 1)] {
                m |= Dir4::West.bit();
            }
            m
        });
        Wavefront::with_moves(&open, &moves)
    }
}

/// Most cell visits the transit table may cost (points × plannable cells;
/// its searches run over blocks, visiting fewer).
const TRANSIT_BUDGET: f64 = 6e7;

/// Side (cells) of the transit table's blocks for a tool of `tool` cells:
/// about half a tool radius, at most [`TRANSIT_BLOCK_MAX`]. The table
/// holds detour ratios (route length over Manhattan distance), which
/// blocks of that size hardly change; a search over them visits a ninth of
/// the cells at a 3-cell block.
fn transit_block(tool: f64) -> usize {
    // Truncation intended: a small whole number of cells.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    // (A tool radius computed as 0.15 / 0.05 is a hair under 3 cells.)
    let k = (tool / 2.0 + 1e-6).round().max(1.0) as usize;
    k.min(TRANSIT_BLOCK_MAX)
}

/// Most plannable cells a transit table searches cell by cell (small
/// regions, where the searches cost little, keep exact ratios).
const TRANSIT_EXACT_CELLS: usize = 20_000;

/// Largest side of a transit block (cells).
const TRANSIT_BLOCK_MAX: usize = 4;

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::traverse::cell_center;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    /// The transit table's blocks go round a wall as thick as a block less
    /// a cell, wherever it lies across the blocks, and measure an open
    /// floor as the cells do.
    #[test]
    fn transit_blocks_go_round_walls() {
        let floor = |wall: Option<usize>| {
            let rows: Vec<String> = (0..30)
                .map(|r| {
                    (0..60)
                        .map(|c| {
                            let in_wall = wall.is_some_and(|w| (w..w + 2).contains(&c));
                            if in_wall && r < 27 { '#' } else { '.' }
                        })
                        .collect()
                })
                .collect();
            let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
            mask(&refs)
        };
        let open = floor(None);
        let region = Region::with_block(&open, 3);
        let mut wave = region.wavefront();
        let (a, b) = (GridPoint::new(4.5, 2.5), GridPoint::new(52.5, 20.5));
        let (ba, bb) = (region.block_of(a).unwrap(), region.block_of(b).unwrap());
        wave.propagate(&[ba]);
        let manhattan = ba.row.abs_diff(bb.row) + ba.col.abs_diff(bb.col);
        assert_eq!(wave.distance(bb), Some(manhattan as u32));
        // A wall two cells thick, at each offset across the blocks, with a
        // gap at the bottom: the way from one side to the other goes round.
        for w in 29..32 {
            let walled = floor(Some(w));
            let region = Region::with_block(&walled, 3);
            let mut wave = region.wavefront();
            let (p, q) = (
                GridPoint::new(w as f64 - 1.5, 0.5),
                GridPoint::new(w as f64 + 3.5, 0.5),
            );
            let (bp, bq) = (region.block_of(p).unwrap(), region.block_of(q).unwrap());
            wave.propagate(&[bp]);
            // Down to the gap (rows 27-29, block row 9) and back up.
            assert!(
                wave.distance(bq).unwrap() >= 18,
                "wall at {w}: {:?}",
                wave.distance(bq)
            );
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(40))]
        /// The symmetric table (each search stopped at the points after its
        /// own) equals one full search from every point, on cells and on
        /// blocks.
        #[test]
        fn the_ratio_table_is_every_search_in_full(seed in 0u64..1000, blobs in 1usize..10, block in 1usize..4, picks in proptest::collection::vec((0usize..47, 0usize..61), 0..24)) {
            let plannable = oxcover_grid::random::blobs(61, 47, blobs, 6, seed).free_mask();
            let region = Region::with_block(&plannable, block);
            let wave = region.wavefront();
            let at: Vec<Option<Cell>> = picks
                .iter()
                .map(|&(r, c)| region.block_of(cell_center(Cell::new(r, c))))
                .collect();
            let n = at.len();
            let mut full = vec![1.0f32; n * n];
            let mut w = wave.clone();
            for i in 0..n {
                let Some(a) = at[i] else { continue };
                w.propagate(&[a]);
                for j in 0..n {
                    let Some(b) = at[j] else { continue };
                    let manhattan = a.row.abs_diff(b.row) + a.col.abs_diff(b.col);
                    if manhattan > 0 {
                        full[i * n + j] = w.distance(b).map_or(1e6, |d| (f64::from(d) / manhattan as f64) as f32);
                    }
                }
            }
            proptest::prop_assert_eq!(ratio_table(&at, &wave), full);
        }

    }
}
