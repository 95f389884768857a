//! Back-and-forth coverage of a cellular decomposition: the `boustrophedon`
//! and `trapezoidal` planners (Pavlíček 2002, §4; Choset & Pignon 1997).
//!
//! 1. **Decompose** the plannable cells with lanes one coverage cell apart
//!    (the tool diameter rounded down to whole cells, so lanes leave no gap)
//!    at a sweep angle: [`oxcover_decomp::boustrophedon()`] or
//!    [`oxcover_decomp::trapezoidal()`]. Each decomposition cell is covered by
//!    its own lanes, driven back and forth.
//! 2. **Order** the cells: distances between cells are shortest paths over the
//!    adjacency graph (edge weight = distance between the cells' centroids);
//!    a greedy nearest-neighbour order from the start's cell is improved by
//!    2-opt (open tour, first cell fixed). Each cell is then entered at the
//!    lane end (first or last lane, either end) nearest to where the robot is.
//! 3. **Connect**: lane to lane and cell to cell by `PathBuilder::go_to`:
//!    straight only where exact traversal finds every crossed cell plannable,
//!    else a shortest fine-grid route, straightened. Never through a wall.
//! 4. **Complete**: coverage cells the lanes missed (ends next to walls) are
//!    visited nearest first (`PathBuilder::cover_leftovers`).
//!
//! **Sweep angle**: fixed, or (default) the best of [`ANGLES_DEG`] by an
//! estimate of the path length (lanes + lane changes + greedy Euclidean
//! distances between cells); only the chosen angle is built in full. The
//! result is a metre path.

use oxcover_decomp::{SliceDecomposition, boustrophedon, trapezoidal};
use oxcover_grid::traverse::GridPoint;

use crate::error::{Error, Result};
use crate::metre_path::PathBuilder;
use crate::planner::{Planner, PlannerOptions};
use crate::problem::{PlanOutput, PlannerInput};

/// Candidate sweep angles (degrees, map frame) when none is fixed.
pub const ANGLES_DEG: [f64; 12] = [
    0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0, 165.0,
];

/// Largest cell count for which the order comes from all-pairs graph
/// distances improved by 2-opt; above it, a local greedy over the graph
/// (cluttered maps reach tens of thousands of cells).
const TWO_OPT_MAX_CELLS: usize = 1500;

/// Which decomposition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decomposition {
    /// Cut at critical events only.
    Boustrophedon,
    /// Also cut where a cell's side bends.
    Trapezoidal,
}

/// The `boustrophedon` / `trapezoidal` planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    /// The decomposition.
    pub decomposition: Decomposition,
    /// Sweep angle in degrees (map frame, lanes along it); `None` = best of [`ANGLES_DEG`].
    pub angle_deg: Option<f64>,
}

impl Sweep {
    /// A sweep planner choosing its angle.
    #[must_use]
    pub const fn new(decomposition: Decomposition) -> Self {
        Self {
            decomposition,
            angle_deg: None,
        }
    }

    /// The same planner at a fixed angle (degrees).
    #[must_use]
    pub const fn at_angle(mut self, angle_deg: f64) -> Self {
        self.angle_deg = Some(angle_deg);
        self
    }

    /// The decomposition at `angle_deg` with lanes `spacing` cells apart.
    #[must_use]
    pub fn decompose(
        &self,
        plannable: &oxcover_grid::Grid<bool>,
        angle_deg: f64,
        spacing: f64,
    ) -> SliceDecomposition {
        let a = angle_deg.to_radians();
        match self.decomposition {
            Decomposition::Boustrophedon => boustrophedon(plannable, a, spacing),
            Decomposition::Trapezoidal => trapezoidal(plannable, a, spacing),
        }
    }

    /// The plan with its decomposition and chosen angle.
    ///
    /// # Errors
    /// A non-finite fixed angle ([`Error::BadParameter`]); internal faults.
    pub fn plan_detailed(&self, input: &PlannerInput<'_>) -> Result<SweepPlan> {
        let spacing = input.coarse.block_size() as f64;
        let start = input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))?;
        let start_pt = oxcover_grid::traverse::cell_center(start);
        let (angle, decomposition, order) = match self.angle_deg {
            Some(a) if !a.is_finite() => {
                return Err(Error::BadParameter {
                    name: "sweep angle",
                    value: a.to_string(),
                    expected: "a finite angle in degrees",
                });
            }
            Some(a) => {
                let d = self.decompose(input.plannable, a, spacing);
                let order = order_cells(&d, start_pt, true);
                (a, d, order.0)
            }
            None => {
                let mut best: Option<(f64, f64, SliceDecomposition, Vec<usize>)> = None;
                for a in ANGLES_DEG {
                    let d = self.decompose(input.plannable, a, spacing);
                    let (order, cost) = order_cells(&d, start_pt, false);
                    if best.as_ref().is_none_or(|b| cost < b.0 - 1e-9) {
                        best = Some((cost, a, d, order));
                    }
                }
                let (_, a, d, _) = best.ok_or_else(|| Error::Internal("no sweep angle".into()))?;
                let order = order_cells(&d, start_pt, true).0;
                (a, d, order)
            }
        };
        let mut path = PathBuilder::new(input.plannable, start);
        for &cell in &order {
            sweep_cell(&mut path, &decomposition, cell)?;
        }
        path.cover_leftovers(input.coarse, input.visit_radius())?;
        let points = path.into_metres(&input.frame);
        Ok(SweepPlan {
            angle_deg: angle,
            decomposition,
            order,
            points,
        })
    }
}

/// A sweep plan and how it was made.
#[derive(Clone, Debug)]
pub struct SweepPlan {
    /// The sweep angle used (degrees).
    pub angle_deg: f64,
    /// The decomposition.
    pub decomposition: SliceDecomposition,
    /// The order in which cells were covered.
    pub order: Vec<usize>,
    /// The metre path.
    pub points: Vec<oxcover_grid::Point>,
}

impl Planner for Sweep {
    fn name(&self) -> &'static str {
        match self.decomposition {
            Decomposition::Boustrophedon => "boustrophedon",
            Decomposition::Trapezoidal => "trapezoidal",
        }
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        match self.decomposition {
            Decomposition::Boustrophedon => {
                "boustrophedon decomposition (Choset & Pignon 1997; Pavlíček 2002): lanes per cell, 2-opt cell order, best of 12 angles"
            }
            Decomposition::Trapezoidal => {
                "trapezoidal (slab) decomposition (Pavlíček 2002, Fig. 8): lanes per cell, 2-opt cell order, best of 12 angles"
            }
        }
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
    fn options(&self) -> PlannerOptions {
        PlannerOptions {
            sweep_angle_deg: self.angle_deg,
        }
    }
}

/// Drives the lanes of `cell` back and forth, entering at the lane end
/// nearest to the path's end.
fn sweep_cell(path: &mut PathBuilder<'_>, d: &SliceDecomposition, cell: usize) -> Result<()> {
    let lanes = &d.cells[cell];
    let (Some(first), Some(last)) = (lanes.first(), lanes.last()) else {
        return Ok(());
    };
    let here = path.last();
    let end = |lane: &oxcover_decomp::Lane, hi: bool| {
        d.slices.point(
            lane.line,
            if hi {
                lane.interval.hi
            } else {
                lane.interval.lo
            },
        )
    };
    let mut best = (f64::INFINITY, false, false);
    for reverse in [false, true] {
        for hi in [false, true] {
            let p = end(if reverse { last } else { first }, hi);
            let dist = dist(here, p);
            if dist < best.0 {
                best = (dist, reverse, hi);
            }
        }
    }
    let reverse = best.1;
    let order: Vec<_> = if reverse {
        lanes.iter().rev().collect()
    } else {
        lanes.iter().collect()
    };
    // Each lane from its end nearer to the robot: back and forth where
    // neighbouring lanes are alike, no doubling back where they are not.
    for lane in order {
        let here = path.last();
        let hi = dist(here, end(lane, true)) < dist(here, end(lane, false));
        path.go_to(end(lane, hi))?;
        path.go_to(end(lane, !hi))?;
    }
    Ok(())
}

fn dist(a: GridPoint, b: GridPoint) -> f64 {
    dist2(a, b).sqrt()
}

fn dist2(a: GridPoint, b: GridPoint) -> f64 {
    let (dx, dy) = (a.x - b.x, a.y - b.y);
    dx * dx + dy * dy
}

/// Cell order from the cell nearest `start`; with `refine`, over graph
/// distances and improved by 2-opt. Returns the order and an estimate of the
/// whole path length (cells).
fn order_cells(d: &SliceDecomposition, start: GridPoint, refine: bool) -> (Vec<usize>, f64) {
    let n = d.cells.len();
    if n == 0 {
        return (Vec::new(), 0.0);
    }
    let centroids: Vec<GridPoint> = d
        .cells
        .iter()
        .map(|lanes| {
            let (mut x, mut y) = (0.0, 0.0);
            for l in lanes {
                let m = d
                    .slices
                    .point(l.line, 0.5 * (l.interval.lo + l.interval.hi));
                x += m.x;
                y += m.y;
            }
            let k = lanes.len().max(1) as f64;
            GridPoint::new(x / k, y / k)
        })
        .collect();
    let first = (0..n)
        .min_by(|&a, &b| dist(start, centroids[a]).total_cmp(&dist(start, centroids[b])))
        .unwrap_or(0);
    let lanes: usize = d.cells.iter().map(Vec::len).sum();
    let base = d.lane_length() + lanes as f64 * d.slices.spacing();
    if n > TWO_OPT_MAX_CELLS {
        // Many cells (cluttered maps): no all-pairs matrix (n² memory) and no
        // quadratic scans; greedy by graph distance, found locally.
        let (order, cost) = greedy_over_graph(d, &centroids, first);
        return (order, base + cost);
    }
    if !refine {
        // Greedy over Euclidean centroid distances: cheap, for angle choice.
        let mut left: Vec<bool> = vec![true; n];
        let (mut cur, mut cost) = (first, 0.0);
        left[cur] = false;
        let mut order = vec![cur];
        for _ in 1..n {
            let next = (0..n).filter(|&i| left[i]).min_by(|&a, &b| {
                dist2(centroids[cur], centroids[a]).total_cmp(&dist2(centroids[cur], centroids[b]))
            });
            let Some(next) = next else { break };
            cost += dist(centroids[cur], centroids[next]);
            left[next] = false;
            order.push(next);
            cur = next;
        }
        return (order, base + cost);
    }
    let dm = graph_distances(d, &centroids);
    let at = |a: usize, b: usize| dm[a * n + b];
    let mut left = vec![true; n];
    let mut order = vec![first];
    left[first] = false;
    let mut cur = first;
    for _ in 1..n {
        let Some(next) = (0..n)
            .filter(|&i| left[i])
            .min_by(|&a, &b| at(cur, a).total_cmp(&at(cur, b)))
        else {
            break;
        };
        left[next] = false;
        order.push(next);
        cur = next;
    }
    if n <= TWO_OPT_MAX_CELLS {
        two_opt(&mut order, &at);
    }
    let cost = order.windows(2).map(|w| at(w[0], w[1])).sum::<f64>();
    (order, base + cost)
}

/// Greedy nearest-unvisited order by adjacency-graph distance, each step a
/// Dijkstra search from the current cell that stops at the first unvisited
/// cell (so its cost is local); when none is linked, the Euclidean nearest
/// with the same penalty as [`graph_distances`]. Returns the order and its
/// travel estimate.
fn greedy_over_graph(
    d: &SliceDecomposition,
    centroids: &[GridPoint],
    first: usize,
) -> (Vec<usize>, f64) {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = centroids.len();
    let adj = d.neighbours();
    let key = |x: f64| (x * 1024.0) as u64;
    let mut left = vec![true; n];
    let mut best = vec![f64::INFINITY; n];
    let mut touched = Vec::new();
    let mut heap = BinaryHeap::new();
    let (mut cur, mut cost) = (first, 0.0);
    left[cur] = false;
    let mut order = vec![cur];
    for _ in 1..n {
        for &t in &touched {
            best[t] = f64::INFINITY;
        }
        touched.clear();
        heap.clear();
        best[cur] = 0.0;
        touched.push(cur);
        heap.push(Reverse((0u64, cur)));
        let mut found = None;
        while let Some(Reverse((k, u))) = heap.pop() {
            if k > key(best[u]) {
                continue;
            }
            if left[u] {
                found = Some((u, best[u]));
                break;
            }
            for &v in &adj[u] {
                let nd = best[u] + dist(centroids[u], centroids[v]);
                if nd < best[v] {
                    if best[v].is_infinite() {
                        touched.push(v);
                    }
                    best[v] = nd;
                    heap.push(Reverse((key(nd), v)));
                }
            }
        }
        let (next, step) = found.unwrap_or_else(|| {
            let far = (0..n)
                .filter(|&i| left[i])
                .min_by(|&a, &b| {
                    dist2(centroids[cur], centroids[a])
                        .total_cmp(&dist2(centroids[cur], centroids[b]))
                })
                .unwrap_or(cur);
            (far, 4.0 * dist(centroids[cur], centroids[far]))
        });
        if !left[next] {
            break;
        }
        cost += step;
        left[next] = false;
        order.push(next);
        cur = next;
    }
    (order, cost)
}

/// All-pairs shortest distances over the adjacency graph (row-major `n × n`);
/// cells in different graph components get the Euclidean distance times a
/// penalty (they are joined over the fine grid anyway).
fn graph_distances(d: &SliceDecomposition, centroids: &[GridPoint]) -> Vec<f64> {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = centroids.len();
    let adj = d.neighbours();
    let mut out = vec![f64::INFINITY; n * n];
    let key = |x: f64| (x * 1024.0) as u64;
    for s in 0..n {
        let row = &mut out[s * n..(s + 1) * n];
        row[s] = 0.0;
        let mut heap = BinaryHeap::new();
        heap.push(Reverse((0u64, s)));
        while let Some(Reverse((k, u))) = heap.pop() {
            if k > key(row[u]) {
                continue;
            }
            for &v in &adj[u] {
                let nd = row[u] + dist(centroids[u], centroids[v]);
                if nd < row[v] {
                    row[v] = nd;
                    heap.push(Reverse((key(nd), v)));
                }
            }
        }
        for v in 0..n {
            if row[v].is_infinite() {
                row[v] = 4.0 * dist(centroids[s], centroids[v]);
            }
        }
    }
    out
}

/// 2-opt on an open tour with a fixed first element.
fn two_opt(order: &mut [usize], at: &impl Fn(usize, usize) -> f64) {
    let n = order.len();
    if n < 4 {
        return;
    }
    for _ in 0..50 {
        let mut improved = false;
        for i in 1..n - 1 {
            for j in i + 1..n {
                // Reverse order[i..=j]: edges (i-1,i) and (j,j+1) change.
                let (a, b) = (order[i - 1], order[i]);
                let (c, e) = (order[j], order.get(j + 1).copied());
                let before = at(a, b) + e.map_or(0.0, |e| at(c, e));
                let after = at(a, c) + e.map_or(0.0, |e| at(b, e));
                if after < before - 1e-9 {
                    order[i..=j].reverse();
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use oxcover_grid::Grid;
    use oxcover_grid::traverse::segment_clear;

    fn plan(text: &str, sweep: Sweep, block: usize) -> (SweepPlan, Grid<bool>) {
        let p = crate::testing::problem(text, block);
        (
            sweep.plan_detailed(&p.input(0)).unwrap(),
            p.plannable().clone(),
        )
    }

    fn grid_points(map: &Grid<bool>, points: &[oxcover_grid::Point]) -> Vec<GridPoint> {
        let h = map.height() as f64;
        points
            .iter()
            .map(|p| GridPoint::new(p.x, h - p.y))
            .collect()
    }

    const BOU: Sweep = Sweep::new(Decomposition::Boustrophedon);

    #[test]
    fn exact_path_in_a_u_shaped_room() {
        // Vertical lanes: every line has one interval, so one cell; the lanes
        // of the two arms are joined around the obstacle, never through it.
        let map = "S...\n.##.\n.##.";
        let (p, m) = plan(map, BOU.at_angle(90.0), 1);
        assert_eq!(p.decomposition.cells.len(), 1);
        let pts = grid_points(&m, &p.points);
        const M: f64 = 1e-4; // lane ends stay this far inside their cells
        let want = [
            GridPoint::new(0.5, 0.5),
            GridPoint::new(0.5, M),
            GridPoint::new(0.5, 3.0 - M),
            GridPoint::new(0.5, 0.5),
            GridPoint::new(1.5, 1.0 - M),
            GridPoint::new(1.5, M),
            GridPoint::new(2.5, M),
            GridPoint::new(2.5, 1.0 - M),
            GridPoint::new(3.5, M),
            GridPoint::new(3.5, 3.0 - M),
        ];
        assert_eq!(pts.len(), want.len(), "{pts:?}");
        for (a, b) in pts.iter().zip(want) {
            assert!(
                (a.x - b.x).abs() < 1e-6 && (a.y - b.y).abs() < 1e-6,
                "{pts:?}"
            );
        }
    }

    #[test]
    fn lanes_never_cross_walls_at_any_angle() {
        let map = "S.........\n..##......\n..##...#..\n.......#..\n...#......\n..........";
        for sweep in [BOU, Sweep::new(Decomposition::Trapezoidal)] {
            for a in [0.0, 30.0, 45.0, 90.0, 150.0] {
                let (p, m) = plan(map, sweep.at_angle(a), 1);
                let pts = grid_points(&m, &p.points);
                for w in pts.windows(2) {
                    assert!(segment_clear(&m, w[0], w[1]), "{a}: {w:?}");
                }
            }
        }
    }

    #[test]
    fn chooses_the_angle_with_fewer_lanes() {
        // A long thin room: lanes along it (0°) beat lanes across it.
        let map = "S...................\n....................\n....................";
        let (p, _) = plan(map, BOU, 1);
        assert!(
            p.angle_deg == 0.0 || p.angle_deg == 180.0,
            "{}",
            p.angle_deg
        );
    }

    #[test]
    fn corridor_one_tool_wide_is_one_lane() {
        let map = "#########\n#S......#\n#########";
        let (p, _) = plan(map, BOU, 1);
        assert_eq!(p.decomposition.cells.len(), 1);
        // From the start's centre to the lane's near end, then along it.
        assert_eq!(p.points.len(), 3);
        assert!(p.points.iter().all(|q| (q.y - 1.5).abs() < 1e-9));
    }
}
