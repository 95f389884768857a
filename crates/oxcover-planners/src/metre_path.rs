//! Building collision-free polylines for the planners that leave the cell
//! lattice (sweep lanes at any angle, border-expansion roads).
//!
//! Points are in grid coordinates ([`oxcover_grid::traverse`]). A straight
//! piece is added only when exact traversal finds every cell it crosses
//! plannable; otherwise the builder routes over the fine grid (a shortest
//! 4-connected path by A*) and straightens that route by string pulling,
//! each shortcut again checked by traversal. So no segment ever crosses a wall,
//! which is the usual failure of sweep planners that join cells by straight lines.
//!
//! `PathBuilder::cover_leftovers` makes the result complete on the coverage
//! grid: it visits, nearest first, every coverage cell whose representative
//! lies farther than half a coverage cell from the path (lane ends near
//! walls, inner strips where offsets vanish).

use oxcover_distance::{AStar, Wavefront, cidt};
use oxcover_grid::footprint::sample_parts;
use oxcover_grid::math::fast_floor;
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_clear, segment_distance};
use oxcover_grid::{Cell, CoarseGrid, Grid, MapFrame, Point};

use crate::error::{Error, Result};

/// A polyline under construction over a plannable mask.
#[derive(Debug)]
pub(crate) struct PathBuilder<'a> {
    plannable: &'a Grid<bool>,
    /// Made when first needed (a builder that only follows walks needs
    /// neither: allocating them per transit was most of a room tour's cost).
    wave: Option<Wavefront>,
    astar: Option<AStar>,
    points: Vec<GridPoint>,
    /// The least distance (cells) a new straight piece keeps from
    /// non-plannable cells; `None` = only exact traversal.
    clearance: Option<Clearance<'a>>,
}

impl<'a> PathBuilder<'a> {
    /// A path starting at the centre of `start` (a plannable cell).
    pub(crate) fn new(plannable: &'a Grid<bool>, start: Cell) -> Self {
        Self {
            plannable,
            wave: None,
            astar: None,
            points: vec![cell_center(start)],
            clearance: None,
        }
    }

    /// The same builder keeping every new straight piece at least
    /// `clearance` cells (at most 0.5, what a path through cell centres
    /// keeps) from non-plannable cells.
    pub(crate) fn with_clearance(mut self, clearance: f64) -> Self {
        let c = clearance.clamp(0.0, 0.5);
        self.clearance = (c > 0.0).then(|| Clearance::new(self.plannable, c));
        self
    }

    /// Whether the straight piece `a → b` may be added.
    pub(crate) fn clear(&self, a: GridPoint, b: GridPoint) -> bool {
        segment_clear(self.plannable, a, b)
            && self.clearance.as_ref().is_none_or(|c| c.segment(a, b))
    }

    /// The mask the path keeps to.
    pub(crate) fn mask(&self) -> &'a Grid<bool> {
        self.plannable
    }

    /// The current end point.
    pub(crate) fn last(&self) -> GridPoint {
        self.points[self.points.len() - 1]
    }

    /// The points so far.
    pub(crate) fn points(&self) -> &[GridPoint] {
        &self.points
    }

    /// Drops the points after the first `len` (at least the start stays).
    pub(crate) fn truncate(&mut self, len: usize) {
        self.points.truncate(len.max(1));
    }

    /// Replaces the points by `points` (the caller has checked every
    /// piece); the start stays when `points` is empty.
    pub(crate) fn replace(&mut self, points: Vec<GridPoint>) {
        if !points.is_empty() {
            self.points = points;
        }
    }

    /// Appends `p` as it is (the caller has checked the piece).
    pub(crate) fn push(&mut self, p: GridPoint) {
        if self.last() != p {
            self.points.push(p);
        }
    }

    /// Goes to `q` (inside a plannable cell): straight when clear, otherwise
    /// along a straightened shortest route.
    pub(crate) fn go_to(&mut self, q: GridPoint) -> Result<()> {
        let p = self.last();
        if self.clear(p, q) {
            self.push(q);
            return Ok(());
        }
        let (Some(a), Some(b)) = (cell_of(self.plannable, p), cell_of(self.plannable, q)) else {
            return Err(Error::Internal(format!(
                "route end outside the grid: {p:?} -> {q:?}"
            )));
        };
        let route = self.route(a, b)?;
        self.straighten(&route, Some(q), |_, _, _| true);
        Ok(())
    }

    /// Goes to `q` along the straight line, round what blocks it (each
    /// blocked stretch by the shortest route to the line's next clear
    /// point).
    pub(crate) fn go_along(&mut self, q: GridPoint) -> Result<()> {
        let p = self.last();
        if self.clear(p, q) {
            self.push(q);
            return Ok(());
        }
        let n = ((q - p).norm() / 0.25).ceil().max(1.0) as usize;
        let pt = |k: usize| p + (q - p) * (k as f64 / n as f64);
        let plannable = self.plannable;
        let inside = |k: usize| cell_of(plannable, pt(k)).is_some_and(|c| plannable[c]);
        let mut k = 0;
        while k < n {
            let mut j = k;
            while j < n && inside(j + 1) && self.clear(pt(j), pt(j + 1)) {
                j += 1;
            }
            if j > k {
                self.push(pt(j));
            }
            if j == n {
                break;
            }
            // The first sample after the blocked stretch from which the
            // line goes on clear (not one on a blocked cell's edge).
            let mut m = j + 1;
            while m < n && !(inside(m) && self.clear(pt(m), pt(m + 1))) {
                m += 1;
            }
            self.go_to(pt(m))?;
            k = m;
        }
        self.go_to(q)
    }

    /// A shortest 4-connected route `a ..= b` of plannable cells (A*).
    fn route(&mut self, a: Cell, b: Cell) -> Result<Vec<Cell>> {
        let plannable = self.plannable;
        self.astar
            .get_or_insert_with(|| AStar::new(plannable))
            .route(a, b)
            .ok_or_else(|| Error::Internal(format!("no route {a:?} -> {b:?}")))
    }

    /// Follows the 4-connected cell walk `cells` (its first cell is where the
    /// path is, or next to it), with shortcuts that
    /// stay within `tolerance` cells of the skipped cell centres.
    pub(crate) fn follow(&mut self, cells: &[Cell], tolerance: f64) {
        self.straighten(cells, None, |a, b, skipped| {
            tolerance.is_infinite()
                || skipped
                    .iter()
                    .all(|&m| segment_distance(a, b, m) <= tolerance)
        });
    }

    /// Follows the points `targets` (each piece from the path's end to the
    /// next target, and between consecutive targets, must be clear: the
    /// caller checks), with the clear shortcuts `keep(from, to, skipped
    /// targets)` accepts.
    pub(crate) fn follow_points(
        &mut self,
        targets: Vec<GridPoint>,
        keep: impl Fn(GridPoint, GridPoint, &[GridPoint]) -> bool,
    ) {
        self.straighten_points(targets, keep);
    }

    /// Appends the route's cell centres (then `end`), skipping those a clear
    /// straight shortcut makes unnecessary and that `keep` accepts skipping.
    ///
    /// From each anchor the shortcut's far end is found by galloping (1, 2, 4,
    /// … targets ahead) and then bisecting between the last good and the first
    /// bad end. Every accepted shortcut is checked (clear, and accepted by
    /// `keep`), so the result is always valid;
    /// the search costs O(log n) checks per shortcut instead of O(n).
    fn straighten(
        &mut self,
        cells: &[Cell],
        end: Option<GridPoint>,
        keep: impl Fn(GridPoint, GridPoint, &[GridPoint]) -> bool,
    ) {
        let mut targets: Vec<GridPoint> = cells.iter().map(|&c| cell_center(c)).collect();
        if let Some(e) = end {
            targets.push(e);
        }
        self.straighten_points(targets, keep);
    }

    /// [`Self::straighten`] over explicit points.
    fn straighten_points(
        &mut self,
        targets: Vec<GridPoint>,
        keep: impl Fn(GridPoint, GridPoint, &[GridPoint]) -> bool,
    ) {
        let mut anchor = self.last();
        let mut i = 0;
        while i < targets.len() {
            // Can the path go straight from `anchor` to `targets[j]`, skipping
            // `targets[i..j]`?
            let ok = |j: usize| {
                self.clear(anchor, targets[j]) && keep(anchor, targets[j], &targets[i..j])
            };
            // `good` passes (or is `i`, always taken); `bad` fails or is past the end.
            let (mut good, mut bad) = (i, targets.len());
            let mut step = 1;
            while good + step < targets.len() {
                if ok(good + step) {
                    good += step;
                    step *= 2;
                } else {
                    bad = good + step;
                    break;
                }
            }
            while bad - good > 1 {
                let mid = good + (bad - good) / 2;
                if ok(mid) {
                    good = mid;
                } else {
                    bad = mid;
                }
            }
            self.push(targets[good]);
            anchor = targets[good];
            i = good + 1;
        }
    }

    /// Visits every coverage cell whose representative is not within `reach`
    /// cells of the path, nearest first ([`crate::PlannerInput::visit_radius`]:
    /// half a coverage cell, or the tool radius when that is smaller).
    pub(crate) fn cover_leftovers(&mut self, coarse: &CoarseGrid, reach: f64) -> Result<()> {
        let radius = reach + 1e-9;
        let mut wanted = Grid::new(self.plannable.width(), self.plannable.height(), false);
        for rep in coarse.representatives().as_slice().iter().flatten() {
            wanted[*rep] = true;
        }
        let mut marked = 0;
        loop {
            mark_near(coarse, &self.points[marked..], radius, &mut wanted);
            marked = self.points.len().saturating_sub(1);
            let Some(here) = cell_of(self.plannable, self.last()) else {
                return Err(Error::Internal("path left the grid".into()));
            };
            // Nothing wanted is left: the search below would visit every
            // reachable cell to find none.
            if !wanted.as_slice().contains(&true) {
                return Ok(());
            }
            let plannable = self.plannable;
            let wave = self.wave.get_or_insert_with(|| Wavefront::new(plannable));
            let Some(near) = cidt(wave, &[here], |c| wanted[c]) else {
                return Ok(());
            };
            let route = wave
                .retrace(near.first())
                .ok_or_else(|| Error::Internal("leftover retrace failed".into()))?;
            if route.len() == 1 {
                // The path ends in a wanted cell but off its centre, out of
                // reach of it (a loop point pushed towards a wall, with a
                // reach under half a cell): go to the centre, or this loop
                // would find the same cell for ever.
                self.push(cell_center(here));
            } else {
                self.straighten(&route[1..], None, |_, _, _| true);
            }
        }
    }

    /// The path in metres.
    pub(crate) fn into_metres(self, frame: &MapFrame) -> Vec<Point> {
        grid_to_metres(frame, &self.points)
    }
}

/// Grid points (x = column, y = row, cell centres at `.5`) as metre
/// positions in `frame`.
pub(crate) fn grid_to_metres(frame: &MapFrame, points: &[GridPoint]) -> Vec<Point> {
    points
        .iter()
        .map(|p| frame.position(p.y - 0.5, p.x - 0.5))
        .collect()
}

/// Metre positions in `frame` as grid points ([`grid_to_metres`] undone).
pub(crate) fn metres_to_grid(frame: &MapFrame, points: &[Point]) -> Vec<GridPoint> {
    points
        .iter()
        .map(|p| {
            let (row, col) = frame.fractional_cell(p);
            GridPoint::new(col + 0.5, row + 0.5)
        })
        .collect()
}

/// Clearance checks against a plannable mask, with the cells whose 3 × 3
/// neighbourhood is plannable precomputed: every point of such a cell is at
/// least one cell from any non-plannable cell, so checks for a clearance
/// under one cell pass there at once (most of an open floor).
#[derive(Debug)]
pub(crate) struct Clearance<'a> {
    mask: &'a Grid<bool>,
    open: Grid<bool>,
    distance: f64,
}

impl<'a> Clearance<'a> {
    /// Checks keeping `distance` (< 1) cells from non-plannable cells.
    pub(crate) fn new(mask: &'a Grid<bool>, distance: f64) -> Self {
        let (w, h) = (mask.width(), mask.height());
        // Rows then columns: a cell is open when its ±1 window is all
        // plannable. `point_clearance` looks no farther than the 3 × 3
        // window (the distance is below one cell), so it holds for every
        // point of an open cell.
        let rows = Grid::from_fn(w, h, |c| {
            (c.col >= 1 && c.col + 1 < w)
                && (c.col - 1..=c.col + 1).all(|x| mask[Cell::new(c.row, x)])
        });
        let open = Grid::from_fn(w, h, |c| {
            (c.row >= 1 && c.row + 1 < h)
                && (c.row - 1..=c.row + 1).all(|y| rows[Cell::new(y, c.col)])
        });
        Self {
            mask,
            open,
            distance,
        }
    }

    /// Whether `p` lies in a plannable cell at least `distance` from the rest.
    pub(crate) fn point(&self, p: GridPoint) -> bool {
        match cell_of(self.mask, p) {
            Some(c) if self.open[c] => true,
            _ => point_clearance(self.mask, p, self.distance),
        }
    }

    /// Whether every point of `a → b` does (the tests' `segment_clearance`,
    /// sampled the same way, must agree).
    pub(crate) fn segment(&self, a: GridPoint, b: GridPoint) -> bool {
        self.box_open(a, b) || segment_points(a, b, self.distance).all(|q| self.point(q))
    }

    /// Whether every cell of the segment's bounding box (grown by a hair,
    /// for rounding; at most 16 cells) is open: then every sample of
    /// [`Self::segment`] lies in an open cell, and the answer is known
    /// without sampling. The same answer, faster: short segments between
    /// curve samples are most of what `smooth` checks.
    fn box_open(&self, a: GridPoint, b: GridPoint) -> bool {
        const HAIR: f64 = 1e-9;
        let (x0, x1) = (a.x.min(b.x) - HAIR, a.x.max(b.x) + HAIR);
        let (y0, y1) = (a.y.min(b.y) - HAIR, a.y.max(b.y) + HAIR);
        if !(x0 >= 0.0
            && y0 >= 0.0
            && x1 < self.open.width() as f64
            && y1 < self.open.height() as f64)
        {
            return false;
        }
        let (c0, c1) = (x0.floor() as usize, x1.floor() as usize);
        let (r0, r1) = (y0.floor() as usize, y1.floor() as usize);
        (c1 - c0 + 1) * (r1 - r0 + 1) <= 16
            && (r0..=r1).all(|r| (c0..=c1).all(|c| self.open[Cell::new(r, c)]))
    }
}

/// Points of `a → b` at most a quarter of `clearance` (and 0.1 cells) apart.
fn segment_points(a: GridPoint, b: GridPoint, clearance: f64) -> impl Iterator<Item = GridPoint> {
    let len = (b.x - a.x).hypot(b.y - a.y);
    let step = (clearance / 4.0).clamp(0.01, 0.1);
    let n = (len / step).ceil().max(1.0) as usize;
    (0..=n).map(move |i| {
        let t = i as f64 / n as f64;
        Point::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))
    })
}

/// Whether every point of the segment `a → b` keeps at least `clearance`
/// (the plain check [`Clearance`] must agree with)
/// cells from every non-plannable (or outside) cell square, checked at
/// points ¼ of the clearance apart (and never more than 0.1 cells apart).
#[cfg(test)]
pub(crate) fn segment_clearance(
    mask: &Grid<bool>,
    a: GridPoint,
    b: GridPoint,
    clearance: f64,
) -> bool {
    segment_points(a, b, clearance).all(|q| point_clearance(mask, q, clearance))
}

/// Whether `p` lies in a plannable cell and no non-plannable (or outside)
/// cell square comes within `clearance` (< 1) cells of it.
pub(crate) fn point_clearance(mask: &Grid<bool>, p: GridPoint, clearance: f64) -> bool {
    let Some(cell) = cell_of(mask, p) else {
        return false;
    };
    if !mask[cell] {
        return false;
    }
    let (r, c) = (cell.row as i64, cell.col as i64);
    for dr in -1..=1_i64 {
        for dc in -1..=1_i64 {
            let (rr, cc) = (r + dr, c + dc);
            let inside =
                rr >= 0 && cc >= 0 && (rr as usize) < mask.height() && (cc as usize) < mask.width();
            if inside && mask[Cell::new(rr as usize, cc as usize)] {
                continue;
            }
            // Distance from p to the square [cc, cc+1] × [rr, rr+1].
            let dx = (cc as f64 - p.x).max(p.x - (cc as f64 + 1.0)).max(0.0);
            let dy = (rr as f64 - p.y).max(p.y - (rr as f64 + 1.0)).max(0.0);
            if dx * dx + dy * dy < clearance * clearance {
                return false;
            }
        }
    }
    true
}

/// Clears `wanted` at every coverage-cell representative within `radius`
/// cells of a sample of the polyline `points`, looking at the blocks round
/// each sample's own ([`near_samples`] is the sample-by-sample
/// definition).
///
/// The samples are the contract's (`oxcover_grid::footprint`): each segment
/// split into `ceil(len / ¼)` equal parts, waypoints included, so a
/// representative marked here is one the metrics count as covered. (An exact
/// point-to-segment distance would also mark representatives that lie within
/// the radius of the segment but of no sample, which the metrics then miss.)
///
/// Segment by segment: a representative within `radius` of a sample lies
/// within `radius` of the segment, so each piece of a segment (about
/// `2·radius` of samples) looks at the blocks its box, grown by `radius`,
/// touches, and tests a wanted representative against the samples
/// nearest its foot on the segment only (the nearest is within one of the
/// foot's rounding; a farther sample is farther by at least a sample's
/// spacing). Where `radius` exceeds a block, the blocks round a sample
/// are not all those within reach, and every sample is visited as
/// defined.
fn mark_near(coarse: &CoarseGrid, points: &[GridPoint], radius: f64, wanted: &mut Grid<bool>) {
    let k = coarse.block_size() as f64;
    let Some(&first) = points.first() else {
        return;
    };
    if radius > k || !radius.is_finite() {
        near_samples(coarse, points, radius, |rep| wanted[rep] = false);
        return;
    }
    let reps = coarse.representatives();
    let reached = |p: GridPoint, r: i64, c: i64, q: GridPoint| {
        block_range(p.y, k, radius).contains(&r) && block_range(p.x, k, radius).contains(&c) && {
            let (dx, dy) = (q.x - p.x, q.y - p.y);
            dx * dx + dy * dy <= radius * radius
        }
    };
    visit_near(coarse, first, radius, |rep| wanted[rep] = false);
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = sample_parts(a, b, SAMPLE_STEP);
        let sample = |i: usize| a + (b - a) * (i as f64 / n as f64);
        let d = b - a;
        let len2 = d.norm_squared();
        if n <= 2 || !len2.is_finite() {
            for i in 1..=n {
                visit_near(coarse, sample(i), radius, |rep| wanted[rep] = false);
            }
            continue;
        }
        // The sample nearest the foot of `q`, either side of it.
        let nearest = |q: GridPoint| {
            let t = ((q - a).dot(&d) / len2).clamp(0.0, 1.0);
            let i = (t * n as f64).round() as usize;
            i.saturating_sub(1).max(1)..=(i + 1).min(n)
        };
        let per_piece = ((2.0 * radius) / (len2.sqrt() / n as f64)).floor().max(1.0) as usize;
        let mut k0 = 0;
        while k0 < n {
            let k1 = (k0 + per_piece).min(n);
            let (p, q) = (sample(k0), sample(k1));
            let rows = blocks_between(p.y.min(q.y) - radius, p.y.max(q.y) + radius, k);
            let cols = blocks_between(p.x.min(q.x) - radius, p.x.max(q.x) + radius, k);
            for r in rows {
                for c in cols.clone() {
                    let Some(Some(rep)) = reps.get(Cell::new(r as usize, c as usize)) else {
                        continue;
                    };
                    if !wanted[*rep] {
                        continue;
                    }
                    let at = cell_center(*rep);
                    if nearest(at).any(|i| reached(sample(i), r, c, at)) {
                        wanted[*rep] = false;
                    }
                }
            }
            k0 = k1;
        }
    }
}

/// The contract's sample spacing, in cells.
const SAMPLE_STEP: f64 = 0.25;

/// The blocks (of side `k`) from the one holding `lo` to the one holding
/// `hi`, none below 0.
fn blocks_between(lo: f64, hi: f64, k: f64) -> std::ops::RangeInclusive<i64> {
    (fast_floor(lo / k) as i64).max(0)..=fast_floor(hi / k) as i64
}

/// The blocks (of side `k`) along one axis that a sample at `x` looks at:
/// its own and its neighbours, as far as they come within `radius` of it
/// (a representative is a cell centre, half a cell inside its block).
fn block_range(x: f64, k: f64, radius: f64) -> std::ops::RangeInclusive<i64> {
    let b = fast_floor(x / k) as i64;
    let lo = fast_floor((x - radius) / k) as i64;
    let hi = fast_floor((x + radius) / k) as i64;
    lo.max(b - 1)..=hi.min(b + 1)
}

/// Calls `f` on every representative within `radius` of `p` among the
/// blocks round `p`'s ([`block_range`]).
fn visit_near(coarse: &CoarseGrid, p: GridPoint, radius: f64, mut f: impl FnMut(Cell)) {
    let reps = coarse.representatives();
    let k = coarse.block_size() as f64;
    for r in block_range(p.y, k, radius) {
        for c in block_range(p.x, k, radius) {
            if r < 0 || c < 0 {
                continue;
            }
            let Some(Some(rep)) = reps.get(Cell::new(r as usize, c as usize)) else {
                continue;
            };
            let q = cell_center(*rep);
            let (dx, dy) = (q.x - p.x, q.y - p.y);
            if dx * dx + dy * dy <= radius * radius {
                f(*rep);
            }
        }
    }
}

/// The definition [`mark_near`] follows: `f` on every representative
/// within `radius` of a contract sample of `points`, among the blocks
/// round the sample's own, sample by sample.
fn near_samples(coarse: &CoarseGrid, points: &[GridPoint], radius: f64, mut f: impl FnMut(Cell)) {
    for_each_contract_sample(points, |p| visit_near(coarse, p, radius, &mut f));
}

/// Calls `f` on the contract's samples of the polyline `points` (grid
/// coordinates, so a quarter of a cell apart: [`oxcover_grid::footprint`]).
pub(crate) fn for_each_contract_sample(points: &[GridPoint], mut f: impl FnMut(GridPoint)) {
    oxcover_grid::footprint::for_each_sample(points, 0.25, |p| f(*p));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Grid<bool> {
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
    }

    #[test]
    fn routes_around_walls_and_straightens() {
        let m = mask(&["......", ".####.", "......"]);
        let mut b = PathBuilder::new(&m, Cell::new(0, 0));
        b.go_to(Point::new(0.5, 2.5)).unwrap();
        // Straight down the left column: clear.
        assert_eq!(
            b.points(),
            [GridPoint::new(0.5, 0.5), GridPoint::new(0.5, 2.5)]
        );
        b.go_to(Point::new(5.5, 0.5)).unwrap();
        let pts = b.points().to_vec();
        assert_eq!(pts.last(), Some(&GridPoint::new(5.5, 0.5)));
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        // Straightened: along the bottom row and up the right column.
        assert_eq!(pts.len(), 4);
    }

    /// Along a line through a pillar: straight up to it, round it by the
    /// shortest way, and back on the line to its end (not a route that
    /// leaves the line for good, as `go_to` takes).
    #[test]
    fn goes_along_a_line_round_what_blocks_it() {
        let m = mask(&[
            "..........",
            "..........",
            "....##....",
            "....##....",
            "..........",
        ]);
        let mut b = PathBuilder::new(&m, Cell::new(2, 0));
        b.go_along(Point::new(9.5, 2.5)).unwrap();
        let pts = b.points().to_vec();
        assert_eq!(pts.last(), Some(&GridPoint::new(9.5, 2.5)));
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        // On the line up to the pillar and again after it.
        let on_line = |p: &GridPoint| (p.y - 2.5).abs() < 1e-9;
        assert!(
            pts.iter().any(|p| on_line(p) && p.x <= 4.0 && p.x > 0.5),
            "{pts:?}"
        );
        assert!(
            pts.iter().any(|p| on_line(p) && p.x >= 6.0 && p.x < 9.5),
            "{pts:?}"
        );
        // A clear line is one segment.
        let mut c = PathBuilder::new(&m, Cell::new(0, 0));
        c.go_along(Point::new(9.5, 0.5)).unwrap();
        assert_eq!(c.points().len(), 2);
    }

    proptest::proptest! {
        /// The open-cell shortcut never changes a clearance verdict.
        #[test]
        fn clearance_shortcut_agrees_with_the_plain_check(
            seed in proptest::prelude::any::<u64>(),
            a in (0.0..12.0f64, 0.0..12.0f64),
            b in (0.0..12.0f64, 0.0..12.0f64),
            c in 0.05..0.95f64,
        ) {
            let map = oxcover_grid::random::random_density(12, 12, 0.1, seed);
            let m = map.free_mask();
            let fast = Clearance::new(&m, c);
            let (a, b) = (GridPoint::new(a.0, a.1), GridPoint::new(b.0, b.1));
            proptest::prop_assert_eq!(fast.segment(a, b), segment_clearance(&m, a, b, c));
            proptest::prop_assert_eq!(fast.point(a), point_clearance(&m, a, c));
        }

        /// Short segments, where the bounding-box shortcut answers, agree
        /// too (also on cell edges and corners).
        #[test]
        fn short_segments_agree_with_the_plain_check(
            seed in proptest::prelude::any::<u64>(),
            a in (0.0..12.0f64, 0.0..12.0f64),
            d in (-1.5..1.5f64, -1.5..1.5f64),
            snap in proptest::prelude::any::<bool>(),
            c in 0.05..0.95f64,
        ) {
            let map = oxcover_grid::random::random_density(12, 12, 0.1, seed);
            let m = map.free_mask();
            let fast = Clearance::new(&m, c);
            let mut a = GridPoint::new(a.0, a.1);
            if snap {
                a = GridPoint::new(a.x.round(), a.y.round());
            }
            let b = GridPoint::new(a.x + d.0, a.y + d.1);
            proptest::prop_assert_eq!(fast.segment(a, b), segment_clearance(&m, a, b, c));
        }
    }

    proptest::proptest! {
        /// Segment by segment, the same representatives as sample by
        /// sample: long and short segments at any angle, on cell borders
        /// and of no length, with a radius within a block and beyond.
        #[test]
        fn marking_by_segment_is_marking_by_sample(
            seed in proptest::prelude::any::<u64>(),
            block in 1usize..7,
            radius in 0.1..8.0f64,
            pts in proptest::collection::vec((0usize..4, 0.0..40.0f64, 0.0..30.0f64), 1..12),
        ) {
            let map = oxcover_grid::random::random_density(40, 30, 0.2, seed);
            let coarse = CoarseGrid::new(&map.free_mask(), block);
            let mut points: Vec<GridPoint> = Vec::new();
            for (kind, x, y) in pts {
                let p = match (kind, points.last()) {
                    // Snapped to a cell border or centre.
                    (0, _) => GridPoint::new(x.round(), y.round()),
                    (1, _) => GridPoint::new(x.floor() + 0.5, y.floor() + 0.5),
                    // The same point again, or a hair away.
                    (2, Some(&q)) => GridPoint::new(q.x, q.y + (x - 20.0) * 1e-3),
                    _ => GridPoint::new(x, y),
                };
                points.push(p);
            }
            let (w, h) = (40, 30);
            let mut fast = Grid::new(w, h, true);
            mark_near(&coarse, &points, radius, &mut fast);
            let mut plain = Grid::new(w, h, true);
            near_samples(&coarse, &points, radius, |rep| plain[rep] = false);
            proptest::prop_assert_eq!(fast, plain);
        }
    }

    #[test]
    fn leftovers_are_visited() {
        let m = mask(&["....", "....", "...."]);
        let coarse = CoarseGrid::new(&m, 1);
        let mut b = PathBuilder::new(&m, Cell::new(0, 0));
        b.go_to(Point::new(3.5, 0.5)).unwrap();
        b.cover_leftovers(&coarse, 0.5).unwrap();
        let mut left = Grid::new(4, 3, true);
        mark_near(&coarse, b.points(), 0.5 + 1e-9, &mut left);
        assert_eq!(left.count_true(), 0);
        for w in b.points().windows(2) {
            assert!(segment_clear(&m, w[0], w[1]));
        }
    }
}
