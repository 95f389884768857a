//! Slices of a grid along parallel lines, and the cellular decompositions
//! built from them (the common ground of [`crate::boustrophedon`](mod@crate::boustrophedon) and
//! [`crate::trapezoidal`](mod@crate::trapezoidal)).
//!
//! A sweep at angle `θ` (map frame, counter-clockwise from +x) lays parallel
//! lines `spacing` apart across the passable cells; each line is cut into its
//! free **intervals**: maximal runs of passable cells it crosses, found by
//! exact traversal ([`oxcover_grid::traverse`]), so an interval never touches a
//! blocked cell, not even at a corner. The lines are the lanes a robot drives
//! (spacing = one tool diameter), and the slices of the decomposition are
//! taken at those lanes: a decomposition cell is a run of intervals on
//! consecutive lines, and its lanes are exactly its intervals.
//!
//! Intervals on neighbouring lines are *adjacent* when their ranges along the
//! line overlap. A decomposition rule decides which adjacent pairs stay in one
//! cell; pairs where it cuts become edges of the adjacency graph (cells that
//! share a boundary).
//!
//! Geometry is in grid coordinates (`x` along columns, `y` along rows,
//! downwards); the line direction is `u = (cos θ, −sin θ)` and lines are
//! ordered along the normal `n = (sin θ, cos θ)`.

use oxcover_grid::Vector;
use oxcover_grid::traverse::{GridPoint, traverse};
use oxcover_grid::{Cell, Grid};

/// One free run on a line: parameter range along the line (grid cells).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Start parameter along the line.
    pub lo: f64,
    /// End parameter along the line.
    pub hi: f64,
}

impl Interval {
    /// Length along the line.
    #[must_use]
    pub fn len(&self) -> f64 {
        self.hi - self.lo
    }

    /// Whether the two ranges overlap (touching counts).
    #[must_use]
    pub fn overlaps(&self, other: &Interval) -> bool {
        self.lo <= other.hi && other.lo <= self.hi
    }
}

/// Distance kept between an interval's ends and the blocked cell beyond, so
/// an end point lies strictly inside a passable cell (also after conversion
/// to metres and back).
const END_MARGIN: f64 = 1e-4;

/// Snaps tiny direction components (from `cos 90°` and the like) to zero, so
/// axis-aligned lines stay exactly on their row or column.
fn snap(v: f64) -> f64 {
    if v.abs() < 1e-12 { 0.0 } else { v }
}

/// Parallel lines over a passable mask and their free intervals.
#[derive(Clone, Debug, PartialEq)]
pub struct Slices {
    angle: f64,
    spacing: f64,
    u: Vector,
    n: Vector,
    offsets: Vec<f64>,
    intervals: Vec<Vec<Interval>>,
}

impl Slices {
    /// Lines at `angle` (radians, map frame) `spacing` cells apart over the
    /// set cells of `passable`; the first line lies half a spacing inside the
    /// passable cells' extent along the normal.
    #[must_use]
    pub fn new(passable: &Grid<bool>, angle: f64, spacing: f64) -> Self {
        let spacing = if spacing.is_finite() && spacing > 0.0 {
            spacing
        } else {
            1.0
        };
        let u = Vector::new(snap(angle.cos()), snap(-angle.sin()));
        let n = Vector::new(snap(angle.sin()), snap(angle.cos()));
        let axis_aligned = u.x == 0.0 || u.y == 0.0;
        let proj = |p: GridPoint, d: Vector| p.x * d.x + p.y * d.y;
        let (mut nmin, mut nmax) = (f64::INFINITY, f64::NEG_INFINITY);
        // Extremes along any direction are reached at a row's first or last
        // set cell: two cells per row instead of all of them.
        for r in 0..passable.height() {
            let row = passable.row(r);
            let (Some(first), Some(last)) =
                (row.iter().position(|&b| b), row.iter().rposition(|&b| b))
            else {
                continue;
            };
            for col in [first, last] {
                for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                    let v = proj(GridPoint::new(col as f64 + dx, r as f64 + dy), n);
                    nmin = nmin.min(v);
                    nmax = nmax.max(v);
                }
            }
        }
        let mut offsets = Vec::new();
        if nmin.is_finite() {
            let mut o = nmin + spacing / 2.0;
            // Axis-aligned lines through cell centres, never along cell borders.
            if axis_aligned {
                o = o.floor() + 0.5;
            }
            // At least one line through any non-empty mask.
            loop {
                offsets.push(o.min(nmax - END_MARGIN));
                o += spacing;
                if o >= nmax {
                    break;
                }
            }
        }
        // Parameter range along a line covering the whole grid.
        let (w, h) = (passable.width() as f64, passable.height() as f64);
        let corners = [
            GridPoint::new(0.0, 0.0),
            GridPoint::new(w, 0.0),
            GridPoint::new(0.0, h),
            GridPoint::new(w, h),
        ];
        let tmin = corners
            .iter()
            .map(|&p| proj(p, u))
            .fold(f64::INFINITY, f64::min)
            - 1.0;
        let tmax = corners
            .iter()
            .map(|&p| proj(p, u))
            .fold(f64::NEG_INFINITY, f64::max)
            + 1.0;
        let mut slices = Self {
            angle,
            spacing,
            u,
            n,
            intervals: Vec::with_capacity(offsets.len()),
            offsets,
        };
        for i in 0..slices.offsets.len() {
            let a = slices.point(i, tmin);
            let b = slices.point(i, tmax);
            let len = tmax - tmin;
            let mut runs = Vec::new();
            let mut open: Option<f64> = None;
            let mut last_exit = tmin;
            traverse(passable.width(), passable.height(), a, b, |c, t0, t1| {
                let free = c.is_some_and(|c: Cell| passable[c]);
                match (free, open) {
                    (true, None) => open = Some(tmin + t0 * len),
                    (false, Some(lo)) => {
                        runs.push((lo, tmin + t0 * len));
                        open = None;
                    }
                    _ => {}
                }
                last_exit = tmin + t1 * len;
                true
            });
            if let Some(lo) = open {
                runs.push((lo, last_exit));
            }
            let inside = |t: f64| {
                oxcover_grid::traverse::cell_of(passable, slices.point(i, t))
                    .is_some_and(|c| passable[c])
            };
            let ivs = runs
                .into_iter()
                .filter(|&(lo, hi)| hi - lo > 2.0 * END_MARGIN)
                .map(|(lo, hi)| Interval {
                    lo: lo + END_MARGIN,
                    hi: hi - END_MARGIN,
                })
                // Rounding at a nearly parallel border could put an end in the
                // cell beyond: such intervals are dropped (the leftover pass of
                // the planners covers them).
                .filter(|iv| inside(iv.lo) && inside(iv.hi))
                .collect();
            slices.intervals.push(ivs);
        }
        slices
    }

    /// Sweep angle (radians).
    #[must_use]
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// Distance between lines (cells).
    #[must_use]
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Number of lines.
    #[must_use]
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there is no line (empty mask).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// The free intervals of line `i`, in order along the line.
    #[must_use]
    pub fn intervals(&self, i: usize) -> &[Interval] {
        &self.intervals[i]
    }

    /// The point at parameter `t` on line `i` (grid coordinates).
    #[must_use]
    pub fn point(&self, i: usize, t: f64) -> GridPoint {
        let o = self.offsets[i];
        GridPoint::new(o * self.n.x + t * self.u.x, o * self.n.y + t * self.u.y)
    }
}

/// One interval of a decomposition cell: line index and interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lane {
    /// Line index in the [`Slices`].
    pub line: usize,
    /// The free interval on that line.
    pub interval: Interval,
}

/// A cellular decomposition of the slices: cells of lanes on consecutive
/// lines, and the adjacency graph.
#[derive(Clone, Debug, PartialEq)]
pub struct SliceDecomposition {
    /// The lines it was built from.
    pub slices: Slices,
    /// Each cell's lanes, on consecutive lines in increasing order.
    pub cells: Vec<Vec<Lane>>,
    /// Adjacency graph: pairs `(a, b)`, `a < b`, of cells sharing a boundary.
    pub edges: Vec<(usize, usize)>,
}

impl SliceDecomposition {
    /// Builds cells with a rule: two overlapping intervals on lines `i` and
    /// `i + 1` that overlap nothing else on the other line are offered to
    /// `same_cell(lanes_so_far, next)`, which says whether `next` continues the
    /// cell; every other overlap starts new cells and becomes a graph edge.
    #[must_use]
    pub fn build(slices: Slices, mut same_cell: impl FnMut(&[Lane], &Interval) -> bool) -> Self {
        let mut cells: Vec<Vec<Lane>> = Vec::new();
        let mut edges = Vec::new();
        // Cell of each interval on the previous line.
        let mut prev_cells: Vec<usize> = Vec::new();
        for line in 0..slices.len() {
            let cur = slices.intervals(line);
            let prev = if line == 0 {
                &[][..]
            } else {
                slices.intervals(line - 1)
            };
            let mut cur_cells = Vec::with_capacity(cur.len());
            for iv in cur {
                let over: Vec<usize> = (0..prev.len()).filter(|&j| prev[j].overlaps(iv)).collect();
                let mut joined = None;
                if let [j] = over[..] {
                    let back = cur.iter().filter(|x| x.overlaps(&prev[j])).count();
                    let cell = prev_cells[j];
                    if back == 1 && same_cell(&cells[cell], iv) {
                        joined = Some(cell);
                    }
                }
                let id = joined.unwrap_or_else(|| {
                    cells.push(Vec::new());
                    cells.len() - 1
                });
                cells[id].push(Lane {
                    line,
                    interval: *iv,
                });
                for &j in &over {
                    let other = prev_cells[j];
                    if other != id {
                        edges.push((other.min(id), other.max(id)));
                    }
                }
                cur_cells.push(id);
            }
            prev_cells = cur_cells;
        }
        edges.sort_unstable();
        edges.dedup();
        Self {
            slices,
            cells,
            edges,
        }
    }

    /// Neighbours of each cell in the adjacency graph.
    #[must_use]
    pub fn neighbours(&self) -> Vec<Vec<usize>> {
        let mut adj = vec![Vec::new(); self.cells.len()];
        for &(a, b) in &self.edges {
            adj[a].push(b);
            adj[b].push(a);
        }
        adj
    }

    /// Total lane length (cells).
    #[must_use]
    pub fn lane_length(&self) -> f64 {
        self.cells.iter().flatten().map(|l| l.interval.len()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    #[test]
    fn horizontal_lines_through_cell_centres() {
        let m = mask(&["....", "..#.", "...."]);
        let s = Slices::new(&m, 0.0, 1.0);
        assert_eq!(s.len(), 3);
        // At angle 0 the lines run along rows through the cell centres, top first.
        let ys: Vec<f64> = (0..3).map(|i| s.point(i, 0.0).y).collect();
        assert_eq!(ys, [0.5, 1.5, 2.5]);
        let counts: Vec<usize> = (0..3).map(|i| s.intervals(i).len()).collect();
        assert_eq!(counts.iter().sum::<usize>(), 4);
        assert!(counts.contains(&2));
        for i in 0..3 {
            for iv in s.intervals(i) {
                let a = s.point(i, iv.lo);
                let b = s.point(i, iv.hi);
                assert!(oxcover_grid::traverse::segment_clear(&m, a, b));
            }
        }
    }

    #[test]
    fn rotated_lines_stay_clear_of_walls() {
        let m = mask(&["......", ".##...", ".##...", "......", "....#."]);
        for deg in [0.0f64, 15.0, 30.0, 45.0, 60.0, 90.0, 135.0] {
            let s = Slices::new(&m, deg.to_radians(), 1.3);
            assert!(!s.is_empty());
            for i in 0..s.len() {
                for iv in s.intervals(i) {
                    assert!(oxcover_grid::traverse::segment_clear(
                        &m,
                        s.point(i, iv.lo),
                        s.point(i, iv.hi)
                    ));
                }
            }
        }
    }
}
