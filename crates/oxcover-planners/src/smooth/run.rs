//! The state of one `smooth` plan: the path under construction, what it
//! covers (the contract's samples, marked stroke by stroke), its stretches
//! by behaviour, and the steps every stage shares.

use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, cell_center, segment_distance};
use oxcover_grid::{Cell, Grid, Point};
use oxcover_robot::{Limits, Timing};

use super::{Behaviour, CLEARANCE, Piece, Run, Smooth, Stats};
use crate::metre_path::{Clearance, PathBuilder};
use crate::problem::PlannerInput;

impl<'a> Run<'a> {
    pub(super) fn new(input: &PlannerInput<'a>, start: Cell, smooth: Smooth) -> Self {
        let plannable = input.plannable;
        let t = input.tool_cells;
        let margin = (0.12 * t).max(0.35);
        let reach = (t - margin).max(t.min(0.5));
        let mut run = Self {
            plannable,
            clear: Clearance::new(plannable, CLEARANCE),
            builder: PathBuilder::new(plannable, start).with_clearance(CLEARANCE),
            touched: Grid::new(plannable.width(), plannable.height(), false),
            rep: {
                let mut rep = Grid::new(plannable.width(), plannable.height(), false);
                for c in input.coarse.representatives().as_slice().iter().flatten() {
                    rep[*c] = true;
                }
                rep
            },
            visited: Grid::new(plannable.width(), plannable.height(), false),
            visit: input.visit_radius() + 1e-9,
            marked: 0,
            tool: t,
            reach,
            margin: t - reach,
            limits: Limits {
                v_max: input.time.linear_speed,
                omega_max: input.time.angular_speed,
                ..Limits::default()
            },
            resolution: input.frame.resolution(),
            bucket: input.coarse.block_size().max(4),
            smooth,
            seed: input.seed,
            corners: 0,
            pieces: Vec::new(),
            stats: Stats::default(),
        };
        run.mark();
        run
    }

    pub(super) fn len(&self) -> usize {
        self.builder.points().len()
    }

    /// Records a piece from `from` to the current end, rounds its sharp
    /// corners where that is faster, and marks what it covered.
    pub(super) fn close(&mut self, behaviour: Behaviour, from: usize) {
        if self.len() > from + 2 {
            let pts = self.builder.points()[from..].to_vec();
            let rounded = self.fillet_corners(&pts);
            self.builder.truncate(from + 1);
            for &q in &rounded[1..] {
                self.builder.push(q);
            }
        }
        let end = self.len() - 1;
        if end > from {
            match self.pieces.last_mut() {
                Some(last) if last.behaviour == behaviour && last.end == from => last.end = end,
                _ => self.pieces.push(Piece {
                    behaviour,
                    start: from,
                    end,
                }),
            }
        }
        self.mark();
    }

    /// Marks the cells the path's new samples cover (the contract's samples:
    /// segments split into pieces of at most ¼ cell).
    pub(super) fn mark(&mut self) {
        let pts = self.builder.points()[self.marked..].to_vec();
        self.marked = self.len().saturating_sub(1);
        mark_stroke(&mut self.touched, &pts, self.tool - SAMPLE_SLACK);
        mark_stroke(&mut self.visited, &pts, self.visit - SAMPLE_SLACK);
    }

    /// Seconds the time law needs for `pts` (grid coordinates).
    pub(super) fn secs(&self, pts: &[GridPoint]) -> f64 {
        let res = self.resolution;
        let m: Vec<Point> = pts
            .iter()
            .map(|p| Point::new(p.x * res, p.y * res))
            .collect();
        Timing::new(&m, self.limits).map_or(f64::INFINITY, |t| t.duration())
    }

    /// Plannable cells within `r` of `points` not covered yet.
    pub(super) fn gain(&self, points: &[GridPoint], r: f64) -> usize {
        points
            .iter()
            .flat_map(|&p| cells_within(self.plannable, p, r))
            .filter(|&c| self.plannable[c] && !self.touched[c])
            .count()
    }
}

/// How much closer than the tool radius a cell must be to a polyline to
/// count as covered by its contract samples (at most ¼ cell apart, so every
/// point of the line is within ⅛ cell of one).
pub(super) const SAMPLE_SLACK: f64 = 0.125 + 1e-6;

/// Marks every cell whose centre lies within `r` of the polyline `pts`
/// (each segment in pieces of at most `2r`, each piece scanning its
/// bounding box grown by `r`: `O(length · r)` cells).
pub(super) fn mark_stroke(grid: &mut Grid<bool>, pts: &[GridPoint], r: f64) {
    let (w, h) = (grid.width() as f64, grid.height() as f64);
    let mut piece = |a: GridPoint, b: GridPoint| {
        let (c0, c1) = (
            (a.x.min(b.x) - r).floor().max(0.0),
            (a.x.max(b.x) + r).ceil().min(w),
        );
        let (r0, r1) = (
            (a.y.min(b.y) - r).floor().max(0.0),
            (a.y.max(b.y) + r).ceil().min(h),
        );
        for row in r0 as usize..r1 as usize {
            for col in c0 as usize..c1 as usize {
                let c = Cell::new(row, col);
                if !grid[c] && segment_distance(a, b, cell_center(c)) <= r {
                    grid[c] = true;
                }
            }
        }
    };
    if pts.len() == 1 {
        piece(pts[0], pts[0]);
    }
    let step = (2.0 * r).max(1.0);
    for s in pts.windows(2) {
        let (a, b) = (s[0], s[1]);
        let n = (norm(b.x - a.x, b.y - a.y) / step).ceil().max(1.0) as usize;
        for k in 0..n {
            let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
            piece(
                GridPoint::new(a.x + t0 * (b.x - a.x), a.y + t0 * (b.y - a.y)),
                GridPoint::new(a.x + t1 * (b.x - a.x), a.y + t1 * (b.y - a.y)),
            );
        }
    }
}

/// Heading change (rad, signed) at `p` on `a → p → b`.
pub(super) fn turn(a: GridPoint, p: GridPoint, b: GridPoint) -> f64 {
    let (u, v) = ((p.x - a.x, p.y - a.y), (b.x - p.x, b.y - p.y));
    (u.0 * v.1 - u.1 * v.0).atan2(u.0 * v.0 + u.1 * v.1)
}

pub(super) fn path_length(p: &[GridPoint]) -> f64 {
    p.windows(2)
        .map(|w| norm(w[1].x - w[0].x, w[1].y - w[0].y))
        .sum()
}

/// The cells whose centre lies within `r` of `p`.
fn cells_within(grid: &Grid<bool>, p: GridPoint, r: f64) -> impl Iterator<Item = Cell> + use<> {
    let (w, h) = (grid.width() as f64, grid.height() as f64);
    let (c0, c1) = ((p.x - r).floor().max(0.0), (p.x + r).ceil().min(w));
    let (r0, r1) = ((p.y - r).floor().max(0.0), (p.y + r).ceil().min(h));
    (r0 as usize..r1 as usize).flat_map(move |row| {
        (c0 as usize..c1 as usize).filter_map(move |col| {
            let c = Cell::new(row, col);
            let m = cell_center(c);
            (norm(m.x - p.x, m.y - p.y) <= r + 1e-9).then_some(c)
        })
    })
}
