//! Smooth coverage (after Lee, Baek, Choi & Oh 2011), built for time.
//!
//! The seed covers a room with a spiral, wall following, and then
//! "virtual-wall" paths: each one runs round the boundary of the region not
//! yet covered, one lane width inside it, and is smoothed by quintic Bézier
//! curves that a PSO tunes. Its claim is that smooth paths clean faster than
//! grid planners. This planner keeps the seed's passes (wall following, then
//! virtual walls nested inwards, Bézier curves, PSO) and lays them out for
//! the time a robot needs, the time law of [`oxcover_robot::Timing`] (speed,
//! acceleration, turn rate, stops at sharp corners) with the input's speed
//! and turn rate:
//!
//! 1. **Rings.** The virtual walls of a room whose every pass is driven
//!    are the level sets of the distance to the C-space boundary. Ring `k`
//!    is the iso-contour of that distance at `½ + k·2R` cells
//!    ([`oxcover_grid::contour`], marching squares): ring 0 runs through the
//!    centres of the cells along the walls (wall following), each next ring
//!    one lane `2R` further in, where `R` is the covering reach (below).
//!    Where the boundary is a staircase of cells (a wall off the grid axes,
//!    a round obstacle), ring 0 is lifted [`STAIR_LIFT`] cells off the steps:
//!    hugging them is a zigzag the robot drives at walking pace (turns every
//!    cell); a little further out the contour is a smooth curve. The price is
//!    the outermost row of cells beside such walls, which only the tool's
//!    rim reached. Rings from 1 on are resampled every cell, smoothed by a
//!    Gaussian of ±3 cells (sharp corners kept) and thinned by
//!    Douglas–Peucker within 0.05 cells; ring 0 is only thinned (0.15).
//! 2. **Slivers.** Rings of different walls meet at the medial axis; the
//!    strip between the last rings can be up to `4R − 2T` cells wide, and
//!    the corners of inner rings leave small pockets. These pieces are
//!    predicted from the rings (cells the tool does not reach) and each is
//!    given a spine: the straight segment along its principal axis, split in
//!    two at the median until each segment passes within the reach of every
//!    cell of its piece and keeps clearance.
//! 3. **Order.** Rings and spines are driven nearest first (a ring entered at
//!    its nearest point and driven once round, in the direction closest to
//!    the current heading; a spine entered at its nearer end); a ring that
//!    would reach no cell not yet covered is dropped. A spine is driven only
//!    when its time per newly covered area (the way to it and along it at
//!    speed, plus two right-angle turns) is at most
//!    [`Smooth::sliver_worth`] times the plan's so far (its length at speed
//!    per covered area): small pockets far from the robot cost minutes per
//!    square metre and are left, which is the seed's own measure
//!    (normalized time per covered area). Transits are straight where clear,
//!    otherwise straightened shortest routes.
//! 4. **Complete.** Every coverage cell whose representative the path has
//!    not passed within the visit radius is then visited nearest first, so
//!    the plan is complete on the coverage grid like every complete planner.
//! 5. **Corners.** Sharp corners (over 0.33 rad) left on each stretch are
//!    rounded by quintic Bézier fillets tangent to both sides with zero end
//!    curvature (G²). A fillet is kept only where the time law drives it
//!    faster than the stop-and-turn it replaces, stays clear, and passes
//!    within the margin of the corner (so what the corner covered with the
//!    reach, the fillet covers with the tool). Its shape (how far it starts
//!    before and ends after the corner, and its two end-tangent lengths) is
//!    tuned by the seed's PSO (Algorithm 1, [`crate::pso`]) with the
//!    estimated closed-loop time of the corner (the time law over the
//!    fillet and the segments either side) as cost, from the widest
//!    symmetric fillet that fits.
//!
//! **Overlap.** Lanes are `2R` apart with `R = T − margin`, `T` the tool
//! radius in cells and the margin 12 % of it (at least 0.35 cells), but `R`
//! never below half a cell (or the tool radius when that is smaller). The
//! margin is what keeps a tracked robot's coverage when it deviates from the
//! plan (the lee2011 reproduction measures the tracking error it must
//! absorb); paths keep [`CLEARANCE`] cells from non-plannable cells for the
//! same reason.
//!
//! **Complexity** for `N` grid cells, `P` ring points and `C` sharp corners:
//! the distance transform and the contours are `O(N + P)`; the order is a
//! nearest search per item over square buckets of a coverage cell (points of
//! driven items dropped as the searches meet them; a search far from every
//! live point scans the filled buckets, not the grid); marking what the path
//! covers is `O(length · T)` (a stroke per segment); each fillet costs a fixed number of
//! PSO evaluations (particles × rounds), each a time law over a few dozen
//! points: `O(C)`. The completion step is one CIDT wave per leftover.

use std::f64::consts::FRAC_PI_2;

use oxcover_grid::components::components4;
use oxcover_grid::contour::{Contour, iso_contours};
use oxcover_grid::edt::{INFINITE, boundary_distance_sq4};
use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_distance};
use oxcover_grid::{Cell, Grid, Point, Vector};
use oxcover_robot::{Limits, QuinticBezier, Timing};

use crate::buckets::Buckets;
use crate::error::{Error, Result};
use crate::metre_path::{Clearance, PathBuilder};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};
use crate::pso::Pso;

/// Least distance (cells) the path keeps from non-plannable cells. A path
/// through cell centres keeps 0.5.
pub const CLEARANCE: f64 = 0.45;

/// How far (cells) ring 0 is lifted off a staircase boundary (at most the
/// tool radius).
pub const STAIR_LIFT: f64 = 0.35;

/// How far (cells) under `½ + k·2R` the rings' levels lie.
const LEVEL_EPSILON: f64 = 1e-3;

/// Largest turn (rad) the time law drives through without stopping; sharper
/// vertices are rounded when a fillet is faster.
const GENTLE: f64 = 0.33;

/// What the robot is doing on a stretch of the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Behaviour {
    /// Ring 0: along the walls and round the obstacles.
    WallFollowing,
    /// A ring further in: a virtual wall one lane inside the last.
    VirtualWall,
    /// Along the spine of a piece left between rings.
    Sliver,
    /// Between passes, and the completion visits.
    Transit,
}

/// A stretch of the path: points `start ..= end` (indices into the path).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Piece {
    /// Behaviour.
    pub behaviour: Behaviour,
    /// First point (the end of the previous piece).
    pub start: usize,
    /// Last point.
    pub end: usize,
}

/// A smooth plan with its behaviours and statistics.
#[derive(Clone, Debug)]
pub struct SmoothPlan {
    /// The metre path.
    pub points: Vec<Point>,
    /// Its stretches by behaviour.
    pub pieces: Vec<Piece>,
    /// Rings driven / dropped (nothing new to cover).
    pub rings: (usize, usize),
    /// Sliver spines driven / left (too slow per covered area).
    pub slivers: (usize, usize),
    /// Sharp corners rounded / left to stop and turn.
    pub fillets: (usize, usize),
    /// Summed estimated time (s) of the rounded corners: the widest
    /// symmetric fillet, then after PSO.
    pub fillet_time: (f64, f64),
}

/// The `smooth` planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    /// PSO parameters for the fillets.
    pub pso: Pso,
    /// A sliver spine is driven when its time per newly covered area is at
    /// most this many times the plan's so far.
    pub sliver_worth: f64,
}

impl Smooth {
    /// The planner with the seed's PSO weights (`w = 0.8, c₁ = 0.5,
    /// c₂ = 0.2`) on 8 particles for 6 rounds per corner, and slivers worth
    /// up to 16 times the plan's time per area.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            pso: Pso {
                particles: 8,
                w: 0.8,
                c1: 0.5,
                c2: 0.2,
                rounds: 6,
            },
            sliver_worth: 16.0,
        }
    }

    /// The plan with its behaviours.
    ///
    /// # Errors
    /// Internal faults only.
    pub fn plan_detailed(&self, input: &PlannerInput<'_>) -> Result<SmoothPlan> {
        let start = input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))?;
        let mut run = Run::new(input, start, *self);
        let items = run.items();
        run.drive_items(items)?;
        let from = run.len() - 1;
        run.builder
            .cover_leftovers(input.coarse, input.visit_radius())?;
        run.close(Behaviour::Transit, from);
        let Run {
            builder,
            pieces,
            stats,
            ..
        } = run;
        Ok(SmoothPlan {
            points: builder.into_metres(&input.frame),
            pieces,
            rings: stats.rings,
            slivers: stats.slivers,
            fillets: stats.fillets,
            fillet_time: stats.fillet_time,
        })
    }
}

impl Default for Smooth {
    fn default() -> Self {
        Self::new()
    }
}

impl Planner for Smooth {
    fn name(&self) -> &'static str {
        "smooth"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "Lee et al. 2011 for time: wall following and nested virtual-wall rings, slivers, PSO-tuned Bezier fillets"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
}

/// A ring (closed) or a sliver's spine (open) to drive.
#[derive(Clone, Debug)]
struct Item {
    points: Vec<GridPoint>,
    closed: bool,
    /// Ring level (0 = wall following); `usize::MAX` for spines.
    level: usize,
    /// Coverage cells' representatives in a sliver: it is driven, however
    /// slow, while one of them is still to visit (completeness).
    reps: Vec<Cell>,
}

#[derive(Clone, Copy, Debug, Default)]
struct Stats {
    rings: (usize, usize),
    slivers: (usize, usize),
    fillets: (usize, usize),
    fillet_time: (f64, f64),
}

/// The planner's state.
struct Run<'a> {
    plannable: &'a Grid<bool>,
    clear: Clearance<'a>,
    builder: PathBuilder<'a>,
    /// Cells whose centre a path sample passed within the tool radius (the
    /// contract's coverage).
    touched: Grid<bool>,
    /// Coverage cells' representatives, and the cells the path passed
    /// within the visit radius of.
    rep: Grid<bool>,
    visited: Grid<bool>,
    visit: f64,
    marked: usize,
    tool: f64,
    reach: f64,
    /// Tool radius less the reach.
    margin: f64,
    limits: Limits,
    resolution: f64,
    /// Bucket size (cells) of the nearest-item index.
    bucket: usize,
    smooth: Smooth,
    seed: u64,
    corners: u64,
    pieces: Vec<Piece>,
    stats: Stats,
}

impl<'a> Run<'a> {
    fn new(input: &PlannerInput<'a>, start: Cell, smooth: Smooth) -> Self {
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

    fn len(&self) -> usize {
        self.builder.points().len()
    }

    /// Records a piece from `from` to the current end, rounds its sharp
    /// corners where that is faster, and marks what it covered.
    fn close(&mut self, behaviour: Behaviour, from: usize) {
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
    fn mark(&mut self) {
        let pts = self.builder.points()[self.marked..].to_vec();
        self.marked = self.len().saturating_sub(1);
        mark_stroke(&mut self.touched, &pts, self.tool - SAMPLE_SLACK);
        mark_stroke(&mut self.visited, &pts, self.visit - SAMPLE_SLACK);
    }

    /// Seconds the time law needs for `pts` (grid coordinates).
    fn secs(&self, pts: &[GridPoint]) -> f64 {
        let res = self.resolution;
        let m: Vec<Point> = pts
            .iter()
            .map(|p| Point::new(p.x * res, p.y * res))
            .collect();
        Timing::new(&m, self.limits).map_or(f64::INFINITY, |t| t.duration())
    }

    /// The distance field whose level sets are the rings: the distance (cells)
    /// from each cell centre to the nearest non-plannable cell, negative
    /// inside them, lowered by up to [`STAIR_LIFT`] where the boundary is a
    /// staircase (the field's gradient more than 5° off the grid axes, fully
    /// from 15°) and a neighbour lies a cell deeper, fading out over the
    /// first lane.
    fn field(&self, spacing: f64) -> Grid<f64> {
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
    fn items(&mut self) -> Vec<Item> {
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
    fn shape_ring(&self, points: Vec<GridPoint>, level: usize) -> Vec<GridPoint> {
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

    /// A polyline through `cells` passing within the reach of each: the
    /// segment along their principal axis when it keeps clearance and
    /// reaches them all, otherwise the spines of the halves split at the
    /// median along that axis, in axis order.
    fn spine(&self, cells: &[Cell]) -> Vec<GridPoint> {
        let centres: Vec<GridPoint> = cells.iter().map(|&c| cell_center(c)).collect();
        if cells.len() == 1 {
            return centres;
        }
        let n = cells.len() as f64;
        let (mx, my) = (
            centres.iter().map(|p| p.x).sum::<f64>() / n,
            centres.iter().map(|p| p.y).sum::<f64>() / n,
        );
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for p in &centres {
            let (dx, dy) = (p.x - mx, p.y - my);
            sxx += dx * dx;
            sxy += dx * dy;
            syy += dy * dy;
        }
        let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
        let (ux, uy) = (angle.cos(), angle.sin());
        let t: Vec<f64> = centres
            .iter()
            .map(|p| (p.x - mx) * ux + (p.y - my) * uy)
            .collect();
        let (lo, hi) = t
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let (a, b) = (
            GridPoint::new(mx + lo * ux, my + lo * uy),
            GridPoint::new(mx + hi * ux, my + hi * uy),
        );
        let inside = |p: GridPoint| cell_of(self.plannable, p).is_some_and(|c| self.plannable[c]);
        let reaches = centres
            .iter()
            .all(|&m| segment_distance(a, b, m) <= self.reach - 1e-6);
        if reaches && inside(a) && inside(b) && self.builder.clear(a, b) {
            return if norm(b.x - a.x, b.y - a.y) < 1e-9 {
                vec![a]
            } else {
                vec![a, b]
            };
        }
        let mut order: Vec<usize> = (0..cells.len()).collect();
        order.sort_by(|&i, &j| t[i].total_cmp(&t[j]));
        let half = cells.len() / 2;
        let first: Vec<Cell> = order[..half].iter().map(|&i| cells[i]).collect();
        let second: Vec<Cell> = order[half..].iter().map(|&i| cells[i]).collect();
        let mut out = self.spine(&first);
        out.extend(self.spine(&second));
        out
    }

    /// Plannable cells within `r` of `points` not covered yet.
    fn gain(&self, points: &[GridPoint], r: f64) -> usize {
        points
            .iter()
            .flat_map(|&p| cells_within(self.plannable, p, r))
            .filter(|&c| self.plannable[c] && !self.touched[c])
            .count()
    }

    /// Drives the items nearest first (see the module docs).
    fn drive_items(&mut self, mut items: Vec<Item>) -> Result<()> {
        let mut index =
            ItemIndex::new(self.plannable.width(), self.plannable.height(), self.bucket);
        for (i, it) in items.iter().enumerate() {
            if it.closed {
                for (j, &p) in it.points.iter().enumerate() {
                    index.insert(p, i, j);
                }
            } else {
                index.insert(it.points[0], i, 0);
                index.insert(it.points[it.points.len() - 1], i, it.points.len() - 1);
            }
        }
        let mut done = vec![false; items.len()];
        while let Some((i, entry)) = index.nearest(self.builder.last(), &done, &items) {
            done[i] = true;
            let it = Item {
                points: std::mem::take(&mut items[i].points),
                reps: std::mem::take(&mut items[i].reps),
                ..items[i]
            };
            if it.closed {
                if self.gain(&it.points, self.reach) == 0 {
                    self.stats.rings.1 += 1;
                    continue;
                }
                self.stats.rings.0 += 1;
                let seq = self.ring_sequence(&it.points, entry);
                let behaviour = if it.level == 0 {
                    Behaviour::WallFollowing
                } else {
                    Behaviour::VirtualWall
                };
                self.drive(&seq, behaviour)?;
            } else {
                let mut spine = it.points;
                if entry > 0 {
                    spine.reverse();
                }
                let gain = self.gain(&spine, self.reach);
                if gain == 0 {
                    continue;
                }
                let needed = it.reps.iter().any(|&c| !self.visited[c]);
                if !needed && !self.worth(&spine, gain) {
                    self.stats.slivers.1 += 1;
                    continue;
                }
                self.stats.slivers.0 += 1;
                self.drive(&spine, Behaviour::Sliver)?;
            }
        }
        Ok(())
    }

    /// Whether a spine covering `gain` new cells is worth its time.
    fn worth(&self, spine: &[GridPoint], gain: usize) -> bool {
        let (res, v) = (self.resolution, self.limits.v_max);
        let here = self.builder.last();
        let way = norm(spine[0].x - here.x, spine[0].y - here.y) + path_length(spine);
        let extra = way * res / v + 2.0 * FRAC_PI_2 / self.limits.omega_max;
        let area = |cells: usize| cells as f64 * res * res;
        let so_far = path_length(self.builder.points()) * res / v;
        let covered = area(self.touched.count_true()).max(area(1));
        extra / area(gain) <= self.smooth.sliver_worth * so_far / covered
    }

    /// The order in which a ring is driven from `entry` back to it, in the
    /// direction closer to the current heading.
    fn ring_sequence(&self, ring: &[GridPoint], entry: usize) -> Vec<GridPoint> {
        let n = ring.len();
        let here = self.builder.last();
        let pts = self.builder.points();
        let forward = if pts.len() >= 2 {
            let (hx, hy) = (here.x - pts[pts.len() - 2].x, here.y - pts[pts.len() - 2].y);
            let (a, b, e) = (
                ring[(entry + 1) % n],
                ring[(entry + n - 1) % n],
                ring[entry],
            );
            (a.x - e.x) * hx + (a.y - e.y) * hy >= (b.x - e.x) * hx + (b.y - e.y) * hy
        } else {
            true
        };
        (0..=n)
            .map(|k| {
                if forward {
                    ring[(entry + k) % n]
                } else {
                    ring[(entry + n - k) % n]
                }
            })
            .collect()
    }

    /// A transit to `seq[0]`, then `seq` (straight where clear, routed where not).
    fn drive(&mut self, seq: &[GridPoint], behaviour: Behaviour) -> Result<()> {
        let from = self.len() - 1;
        self.builder.go_to(seq[0])?;
        self.close(Behaviour::Transit, from);
        let from = self.len() - 1;
        for &q in &seq[1..] {
            if self.builder.clear(self.builder.last(), q) {
                self.builder.push(q);
            } else {
                self.builder.go_to(q)?;
            }
        }
        self.close(behaviour, from);
        Ok(())
    }

    /// Rounds the sharp vertices of a polyline where a fillet is faster (see
    /// the module docs).
    fn fillet_corners(&mut self, pts: &[GridPoint]) -> Vec<GridPoint> {
        let mut out = vec![pts[0]];
        for i in 1..pts.len() - 1 {
            let (prev, p, next) = (*out.last().expect("a point"), pts[i], pts[i + 1]);
            let (lin, lout) = (
                norm(p.x - prev.x, p.y - prev.y),
                norm(next.x - p.x, next.y - p.y),
            );
            if lin < 1e-9 || lout < 1e-9 || turn(prev, p, next).abs() <= GENTLE {
                out.push(p);
                continue;
            }
            match self.fillet(prev, p, next) {
                Some(samples) => {
                    self.stats.fillets.0 += 1;
                    out.extend_from_slice(&samples);
                }
                None => {
                    self.stats.fillets.1 += 1;
                    out.push(p);
                }
            }
        }
        out.push(pts[pts.len() - 1]);
        out
    }

    /// The fastest fillet of the corner `prev → p → next`, if one is faster
    /// than stopping at `p`.
    fn fillet(&mut self, prev: GridPoint, p: GridPoint, next: GridPoint) -> Option<Vec<GridPoint>> {
        if self.margin <= 0.0 {
            return None;
        }
        self.corners += 1;
        let seed = self.seed ^ self.corners.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let (lin, lout) = (
            norm(p.x - prev.x, p.y - prev.y),
            norm(next.x - p.x, next.y - p.y),
        );
        let cap = (0.5 * lin).min(0.5 * lout).min(3.0);
        // x = (start before p, end after p, start tangent, end tangent scale).
        let cost = |x: &[f64; 4]| -> Option<f64> {
            let samples = self.fillet_samples(prev, p, next, x)?;
            let mut window = vec![prev];
            window.extend_from_slice(&samples);
            window.push(next);
            Some(self.secs(&window))
        };
        // The widest symmetric fillet that fits is PSO's feasible start.
        let mut d = cap;
        let start = loop {
            if d < 0.05 {
                return None;
            }
            let x = [d, d, 1.0, 1.0];
            if let Some(c) = cost(&x) {
                break (x, c);
            }
            d /= 2.0;
        };
        let corner = self.secs(&[prev, p, next]);
        let best = self
            .smooth
            .pso
            .minimise(
                start.0,
                [0.05, 0.05, 0.3, 0.3],
                [cap, cap, 1.5, 1.5],
                seed,
                cost,
            )
            .map_or(start, |r| (r.x, r.cost));
        if best.1 >= corner {
            return None;
        }
        self.stats.fillet_time.0 += start.1;
        self.stats.fillet_time.1 += best.1;
        self.fillet_samples(prev, p, next, &best.0)
    }

    /// The fillet with shape `x` sampled, if it keeps clearance and passes
    /// within the margin of the corner it replaces.
    fn fillet_samples(
        &self,
        prev: GridPoint,
        p: GridPoint,
        next: GridPoint,
        x: &[f64; 4],
    ) -> Option<Vec<GridPoint>> {
        let unit = |a: GridPoint, b: GridPoint| {
            let l = norm(b.x - a.x, b.y - a.y);
            ((b.x - a.x) / l, (b.y - a.y) / l)
        };
        let ((ux, uy), (vx, vy)) = (unit(prev, p), unit(p, next));
        let [din, dout, kin, kout] = *x;
        let a = GridPoint::new(p.x - din * ux, p.y - din * uy);
        let b = GridPoint::new(p.x + dout * vx, p.y + dout * vy);
        let l = norm(b.x - a.x, b.y - a.y);
        let seg = QuinticBezier::from_ends(
            a,
            b,
            Vector::new(kin * l * ux, kin * l * uy),
            Vector::new(kout * l * vx, kout * l * vy),
            Vector::new(0.0, 0.0),
            Vector::new(0.0, 0.0),
        );
        let angle = turn(prev, p, next).abs();
        let samples = seg.sample(((din + dout) / 0.25).max(angle / 0.08).ceil().max(4.0) as usize);
        let near = |q: GridPoint| {
            samples
                .windows(2)
                .any(|s| segment_distance(s[0], s[1], q) <= self.margin)
        };
        let covered = (0..=8).all(|k| {
            let t = k as f64 / 8.0;
            near(Point::new(a.x + t * (p.x - a.x), a.y + t * (p.y - a.y)))
                && near(Point::new(p.x + t * (b.x - p.x), p.y + t * (b.y - p.y)))
        });
        (covered && samples.windows(2).all(|s| self.clear.segment(s[0], s[1]))).then_some(samples)
    }
}

/// Item points in square buckets (payload: item, point index), for the
/// nearest item not yet driven.
struct ItemIndex(Buckets<(usize, usize)>);

impl ItemIndex {
    fn new(width: usize, height: usize, size: usize) -> Self {
        Self(Buckets::new(
            Point::new(0.0, 0.0),
            Point::new(width as f64, height as f64),
            size as f64,
        ))
    }

    fn insert(&mut self, p: GridPoint, item: usize, index: usize) {
        self.0.insert(p, (item, index));
    }

    /// The nearest point of an item not `done` (ties: lower ring level, then
    /// lower item number). Points of items done are dropped on the way.
    fn nearest(&mut self, p: GridPoint, done: &[bool], items: &[Item]) -> Option<(usize, usize)> {
        let mut best: Option<(f64, usize, usize, usize)> = None;
        self.0.search(
            p,
            &mut best,
            |best, cell| {
                cell.retain(|e| !done[e.1.0]);
                for &(q, (item, index)) in cell.iter() {
                    let key = (norm(q.x - p.x, q.y - p.y), items[item].level, item, index);
                    if best.is_none_or(|b| (key.0, key.1, key.2) < (b.0, b.1, b.2)) {
                        *best = Some(key);
                    }
                }
            },
            |best, bound| best.is_some_and(|b| b.0 < bound),
        );
        best.map(|b| (b.2, b.3))
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

/// How much closer than the tool radius a cell must be to a polyline to
/// count as covered by its contract samples (at most ¼ cell apart, so every
/// point of the line is within ⅛ cell of one).
const SAMPLE_SLACK: f64 = 0.125 + 1e-6;

/// Marks every cell whose centre lies within `r` of the polyline `pts`
/// (each segment in pieces of at most `2r`, each piece scanning its
/// bounding box grown by `r`: `O(length · r)` cells).
fn mark_stroke(grid: &mut Grid<bool>, pts: &[GridPoint], r: f64) {
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
fn turn(a: GridPoint, p: GridPoint, b: GridPoint) -> f64 {
    let (u, v) = ((p.x - a.x, p.y - a.y), (b.x - p.x, b.y - p.y));
    (u.0 * v.1 - u.1 * v.0).atan2(u.0 * v.0 + u.1 * v.1)
}

fn path_length(p: &[GridPoint]) -> f64 {
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
fn resample_loop(points: &[GridPoint], step: f64) -> Vec<GridPoint> {
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
fn smooth_loop(points: &[GridPoint], half: usize) -> Vec<GridPoint> {
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
fn simplify_loop(points: &[GridPoint], tol: f64) -> Vec<GridPoint> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::traverse::segment_clear;

    /// The plan on an ASCII map with `block`-cell coverage cells, its path in
    /// grid coordinates, and the plannable mask.
    fn plan(text: &str, block: usize) -> (SmoothPlan, Vec<GridPoint>, Grid<bool>) {
        let p = crate::testing::problem(text, block);
        let plan = Smooth::new().plan_detailed(&p.input(0)).unwrap();
        let h = p.plannable().height() as f64;
        let pts = plan
            .points
            .iter()
            .map(|q| GridPoint::new(q.x, h - q.y))
            .collect();
        (plan, pts, p.plannable().clone())
    }

    /// Exact path on a tiny map: unit cells, a reach of half a cell, so
    /// lanes one cell apart. Ring 0 is the border through the cell centres
    /// (entered at the start, driven once round in the contour's own
    /// direction, the robot having no heading yet); ring 1 is the centre
    /// cell alone, a degenerate contour the completion visits.
    #[test]
    fn three_by_three_room_exact() {
        let (p, pts, m) = plan("S..\n...\n...", 1);
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        let kinds: Vec<Behaviour> = p.pieces.iter().map(|q| q.behaviour).collect();
        assert_eq!(kinds, [Behaviour::WallFollowing, Behaviour::Transit]);
        assert_eq!(
            pts,
            [
                GridPoint::new(0.5, 0.5),
                GridPoint::new(0.5, 2.5),
                GridPoint::new(2.5, 2.5),
                GridPoint::new(2.5, 0.5),
                GridPoint::new(0.5, 0.5),
                GridPoint::new(1.5, 1.5),
            ]
        );
    }

    #[test]
    fn rings_nest_one_lane_apart_in_an_open_room() {
        // 30 x 20 free cells, tool 3 cells: reach 2.64, lanes 5.28 apart.
        let rows = [".............................."; 20].join("\n");
        let text = format!("S{}", &rows[1..]);
        let (p, pts, m) = plan(&text, 6);
        assert!(p.rings.0 >= 2, "{:?}", p.rings);
        // The first ring runs along the walls through the border cells'
        // centres, its corners rounded within the margin (0.36 cells here).
        let first = p
            .pieces
            .iter()
            .find(|q| q.behaviour == Behaviour::WallFollowing)
            .copied()
            .unwrap();
        assert!(
            pts[first.start..=first.end].iter().all(|q| q
                .x
                .min(q.y)
                .min(30.0 - q.x)
                .min(20.0 - q.y)
                < 0.5 + 0.36 * std::f64::consts::SQRT_2 + 0.1),
            "{:?}",
            &pts[first.start..=first.end]
        );
        for w in pts.windows(2) {
            assert!(
                crate::metre_path::segment_clearance(&m, w[0], w[1], CLEARANCE - 1e-9),
                "{w:?}"
            );
        }
        // PSO never made a fillet slower than its start.
        assert!(
            p.fillet_time.1 <= p.fillet_time.0 + 1e-9,
            "{:?}",
            p.fillet_time
        );
    }

    #[test]
    fn loops_resample_smooth_and_simplify() {
        let square: Vec<GridPoint> = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]
            .iter()
            .map(|&(x, y)| GridPoint::new(x, y))
            .collect();
        let dense = resample_loop(&square, 1.0);
        assert_eq!(dense.len(), 40);
        // Corners stay, sides stay straight, and thinning gives the square back.
        let smooth = smooth_loop(&dense, 3);
        assert!(smooth.contains(&GridPoint::new(10.0, 10.0)));
        let thin = simplify_loop(&smooth, 0.05);
        assert_eq!(thin.len(), 4, "{thin:?}");
    }

    #[test]
    fn buckets_find_the_nearest_live_item() {
        let items = vec![
            Item {
                points: vec![GridPoint::new(1.0, 1.0)],
                closed: false,
                level: usize::MAX,
                reps: Vec::new(),
            },
            Item {
                points: vec![GridPoint::new(30.0, 30.0), GridPoint::new(31.0, 30.0)],
                closed: true,
                level: 0,
                reps: Vec::new(),
            },
        ];
        let mut b = ItemIndex::new(40, 40, 4);
        b.insert(items[0].points[0], 0, 0);
        b.insert(items[1].points[0], 1, 0);
        b.insert(items[1].points[1], 1, 1);
        assert_eq!(
            b.nearest(GridPoint::new(2.0, 2.0), &[false, false], &items),
            Some((0, 0))
        );
        assert_eq!(
            b.nearest(GridPoint::new(2.0, 2.0), &[true, false], &items),
            Some((1, 0))
        );
        assert_eq!(
            b.nearest(GridPoint::new(39.0, 30.0), &[false, false], &items),
            Some((1, 1))
        );
        assert_eq!(
            b.nearest(GridPoint::new(2.0, 2.0), &[true, true], &items),
            None
        );
    }
}
