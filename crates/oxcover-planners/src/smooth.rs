//! Smooth coverage (Lee, Baek, Choi & Oh 2011).
//!
//! The seed's behaviours, on the plannable grid (the planner knows the map;
//! "sensing an obstacle" is leaving the plannable cells with a clearance):
//!
//! 1. **Spiral** from the start, the Archimedean spiral `r = (R/π)|θ|` of
//!    [`oxcover_robot::spiral`] (x along +x: the start pose has no heading),
//!    until its next piece would come closer than [`CLEARANCE`] cells to a
//!    non-plannable cell.
//! 2. **Wall following** back to its start: the nearest wall cell is reached
//!    and the whole boundary it lies on is followed once around by the
//!    right-hand rule, through the centres of the cells along it.
//! 3. Repeat: **coarse-to-fine CIDT** ([`oxcover_distance::CoarseToFine`]) to
//!    the nearest unexplored cell; the robot descends its path there; then the
//!    **virtual-wall path** around the unexplored region from that target:
//!    - *wall points*: the boundary of the unexplored region traced by the
//!      right-hand rule from the CIDT target (explored cells or walls on the
//!      right). We take the first unexplored cells, one cell beyond the
//!      seed's "last covered cells", so "covering a wall point" means the
//!      tool reaches it;
//!    - *tangents* from a local least-squares fit over ±2 neighbours;
//!    - *path points*: each wall point moved along its normal into the
//!      unexplored region by the covering reach less half a cell (pulled back
//!      when that point lacks clearance); at cells touching a real wall
//!      (8-neighbourhood) the path point is the wall point itself, i.e.
//!      **wall following** where the virtual path meets an obstacle;
//!    - *filtering*: of two consecutive path points whose connectors to their
//!      wall points cross (Fig. 4), the second is dropped;
//!    - *minimal covering set* (Fig. 5): greedily the farthest path point
//!      whose straight connection keeps clearance and stays within covering
//!      reach of every wall point in between;
//!    - *quintic Bézier splines* through the chosen points (eq. 13 and its
//!      control-point rules): at each point a tangent along the bisector of
//!      its chords and the curvature of the circle through it and its
//!      neighbours; each segment's end tangents have its chord's length and
//!      its end second derivatives realise those curvatures, so the spline
//!      is G² (curvature-continuous). The seed's uniform derivatives (our
//!      [`oxcover_robot::spline_through`]) loop where points are unevenly
//!      spaced, which the minimal covering set makes them;
//!    - *PSO* (Algorithm 1, [`crate::pso`]) per interior point over
//!      `x = (normal shift, tangent rotation, tangent scale, curvature
//!      scale)` (the slides do not say what their four elements are), each
//!      particle kept only while both adjacent segments keep clearance and
//!      still cover their wall points (the covering range `R_i`);
//!    - a segment that still fails is driven with its tangents halved, then
//!      quartered, then straight (the chord, which the covering set checked).
//!
//!    until CIDT finds no unexplored cell.
//!
//! **PSO cost.** The slides do not give eq. 19. Ours, per pair of segments
//! around the moved point, in cells: `C = L + R²·∫κ² ds + D/R`, with `L` the
//! arc length (time at a given speed), `∫κ² ds` the bending energy (the time
//! law caps speed by curvature, so it costs time and energy; `R²` makes it a
//! length), and `D` the summed squared distance of the curve from the
//! unfiltered path points it replaces (our stand-in for the connection gap
//! `C` of Fig. 5: it keeps the curve on the offset lane so the next ring's
//! spacing stays even; `1/R` makes it a length). `R` is the covering reach.
//! PSO skips a point whose two segments lack clearance or coverage at the start.
//!
//! **Overlap.** A cell counts as explored when a path sample passes within
//! the covering reach `R = tool − margin` (margin: 12 % of the tool radius,
//! at least 0.35 cells, but `R` never below half a cell, or the tool radius
//! when that is smaller), and a cell next to a wall only when the path passes
//! within 0.85 of a cell (so walls are followed, and the strip beyond them that
//! only the tool reaches is covered; 0.85 rather than ½ lets a straight line
//! follow a wall drawn as a staircase of cells without zigzagging). Lanes thus overlap by about the margin,
//! which is what keeps a tracked robot's coverage when it deviates; paths keep
//! [`CLEARANCE`] cells from non-plannable cells for the same reason. Sharp
//! corners left on the path (routes, wall following, straight fallbacks) are
//! rounded by Bézier fillets that stay within the margin of the corner, so
//! the robot drives through them instead of stopping to turn in place.
//!
//! Complete on the coverage grid: every iteration ends at its target, so
//! it terminates, and it stops only when no plannable cell is unexplored.

use oxcover_distance::{BlockMap, CoarseToFine, Wavefront, cidt};
use oxcover_grid::math::norm;
use oxcover_grid::traverse::{GridPoint, cell_center, cell_of, segment_distance};
use oxcover_grid::{Cell, Dir4, Grid, Point, Vector};
use oxcover_robot::{ArchimedeanSpiral, G2Spline, QuinticBezier};

use crate::error::{Error, Result};
use crate::metre_path::{Clearance, PathBuilder, for_each_contract_sample};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};
use crate::pso::Pso;

/// Least distance (cells) the path keeps from non-plannable cells. A path
/// through cell centres keeps 0.5.
pub const CLEARANCE: f64 = 0.45;

/// Farthest look-ahead (path points) of the minimal-covering-set search.
const LOOKAHEAD: usize = 48;

/// What the robot is doing on a stretch of the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Behaviour {
    /// The initial Archimedean spiral.
    Spiral,
    /// Wall following.
    WallFollowing,
    /// Descending the CIDT path to the next target (or a detour between path points).
    Transit,
    /// A virtual-wall path.
    VirtualWall,
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

/// A smooth plan with its behaviours and PSO statistics.
#[derive(Clone, Debug)]
pub struct SmoothPlan {
    /// The metre path.
    pub points: Vec<oxcover_grid::Point>,
    /// Its stretches by behaviour.
    pub pieces: Vec<Piece>,
    /// CIDT iterations (virtual-wall paths built).
    pub iterations: usize,
    /// Bézier segments driven / driven straight instead.
    pub curved_segments: usize,
    /// Segments whose spline lacked clearance or coverage.
    pub straight_segments: usize,
    /// Summed PSO cost before and after (cells).
    pub pso_cost: (f64, f64),
}

/// The `smooth` planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    /// The PSO parameters.
    pub pso: Pso,
}

impl Smooth {
    /// The planner with the paper's PSO parameters.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            pso: Pso {
                particles: 30,
                w: 0.8,
                c1: 0.5,
                c2: 0.2,
                rounds: 12,
            },
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
        let mut run = Run::new(input, start, self.pso);
        run.spiral(start)?;
        run.first_wall_following()?;
        run.virtual_walls()?;
        let Run {
            builder,
            pieces,
            iterations,
            curved,
            straight,
            pso_cost,
            ..
        } = run;
        Ok(SmoothPlan {
            points: builder.into_metres(&input.frame),
            pieces,
            iterations,
            curved_segments: curved,
            straight_segments: straight,
            pso_cost,
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
        "Lee et al. 2011: spiral, wall following, CFCIDT and PSO-tuned quintic Bezier virtual-wall paths"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
}

/// A path point with the wall point it answers for.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Waypoint {
    /// Where the robot goes.
    p: GridPoint,
    /// The wall point (a first unexplored cell's centre).
    u: GridPoint,
    /// Largest distance of the path from `u` that still covers it.
    tol: f64,
}

/// The planner's state.
struct Run<'a> {
    plannable: &'a Grid<bool>,
    /// Clearance checks at [`CLEARANCE`].
    clear: Clearance<'a>,
    builder: PathBuilder<'a>,
    /// Cells next to a wall (a non-plannable or outside 4-neighbour).
    wall: Grid<bool>,
    /// Cells touching a wall (a non-plannable or outside 8-neighbour).
    near_wall: Grid<bool>,
    /// Explored cells, with the unexplored ones as CFCIDT targets.
    blocks: BlockMap,
    explored: Grid<bool>,
    reach: f64,
    /// Tool radius less the reach: how far the path may move from where it
    /// explored cells and still cover them.
    margin: f64,
    marked: usize,
    pieces: Vec<Piece>,
    pso: Pso,
    seed: u64,
    iterations: usize,
    curved: usize,
    straight: usize,
    pso_cost: (f64, f64),
}

impl<'a> Run<'a> {
    fn new(input: &PlannerInput<'a>, start: Cell, pso: Pso) -> Self {
        let plannable = input.plannable;
        let wall = Grid::from_fn(plannable.width(), plannable.height(), |c| {
            plannable[c]
                && Dir4::ALL
                    .iter()
                    .any(|&d| !plannable.step(c, d).is_some_and(|n| plannable[n]))
        });
        let near_wall = Grid::from_fn(plannable.width(), plannable.height(), |c| {
            plannable[c]
                && (plannable.neighbours8(c).count() < 8
                    || plannable.neighbours8(c).any(|(_, n)| !plannable[n]))
        });
        let mut blocks = BlockMap::new(plannable, input.coarse.block_size().max(4));
        for c in plannable.true_cells() {
            blocks.set_target(c, true);
        }
        let t = input.tool_cells;
        let margin = (0.12 * t).max(0.35);
        let reach = (t - margin).max(t.min(0.5));
        let mut run = Self {
            plannable,
            clear: Clearance::new(plannable, CLEARANCE),
            builder: PathBuilder::new(plannable, start).with_clearance(CLEARANCE),
            wall,
            near_wall,
            blocks,
            explored: Grid::new(plannable.width(), plannable.height(), false),
            reach,
            margin: t - reach,
            marked: 0,
            pieces: Vec::new(),
            pso,
            seed: input.seed,
            iterations: 0,
            curved: 0,
            straight: 0,
            pso_cost: (0.0, 0.0),
        };
        run.mark();
        run
    }

    fn len(&self) -> usize {
        self.builder.points().len()
    }

    /// Records a piece from `from` to the current end and marks what it explored.
    fn close(&mut self, behaviour: Behaviour, from: usize) {
        if behaviour != Behaviour::Spiral && self.len() > from + 2 {
            let pts = self.builder.points()[from..].to_vec();
            let rounded = fillet_corners(&self.clear, &pts, self.margin);
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

    /// Marks cells explored by the path's new samples (the contract's
    /// samples: segments split into pieces of at most ¼ cell).
    fn mark(&mut self) {
        let pts = self.builder.points()[self.marked..].to_vec();
        self.marked = self.len().saturating_sub(1);
        for_each_contract_sample(&pts, |p| self.mark_point(p));
    }

    fn mark_point(&mut self, p: GridPoint) {
        let r = self.reach;
        let (w, h) = (
            self.plannable.width() as f64,
            self.plannable.height() as f64,
        );
        let (c0, c1) = ((p.x - r).floor().max(0.0), (p.x + r).ceil().min(w));
        let (r0, r1) = ((p.y - r).floor().max(0.0), (p.y + r).ceil().min(h));
        for row in r0 as usize..r1 as usize {
            for col in c0 as usize..c1 as usize {
                let c = Cell::new(row, col);
                if !self.plannable[c] || self.explored[c] {
                    continue;
                }
                let need = if self.wall[c] { self.wall_reach() } else { r };
                let (x, y) = {
                    let c = cell_center(c);
                    (c.x, c.y)
                };
                if norm(x - p.x, y - p.y) <= need + 1e-9 {
                    self.explored[c] = true;
                    self.blocks.set_target(c, false);
                }
            }
        }
    }

    fn here(&self) -> Result<Cell> {
        cell_of(self.plannable, self.builder.last())
            .ok_or_else(|| Error::Internal("path left the grid".into()))
    }

    /// Step 1: the spiral until it would lose clearance.
    fn spiral(&mut self, start: Cell) -> Result<()> {
        let radius = (self.reach - 0.25).max(0.5);
        let spiral =
            ArchimedeanSpiral::new(radius).map_err(|e| Error::Internal(format!("spiral: {e}")))?;
        let size = self.plannable.width().max(self.plannable.height()) as f64;
        let turns = size / (2.0 * radius) + 1.0;
        let (cx, cy) = {
            let c = cell_center(start);
            (c.x, c.y)
        };
        let from = self.len() - 1;
        for s in spiral
            .points(turns * std::f64::consts::TAU, 0.5)
            .into_iter()
            .skip(1)
        {
            let q = GridPoint::new(cx + s.x, cy + s.y);
            if !self.builder.clear(self.builder.last(), q) {
                break;
            }
            self.builder.push(q);
        }
        self.close(Behaviour::Spiral, from);
        Ok(())
    }

    /// Step 2: to the nearest wall, then once around the boundary it lies on.
    fn first_wall_following(&mut self) -> Result<()> {
        let here = self.here()?;
        let mut wave = Wavefront::new(self.plannable);
        let wall = &self.wall;
        let Some(near) = cidt(&mut wave, &[here], |c| wall[c]) else {
            return Ok(()); // no wall cell at all
        };
        let route = wave
            .retrace(near.first())
            .ok_or_else(|| Error::Internal("wall retrace failed".into()))?;
        let from = self.len() - 1;
        self.builder.follow(&route[1..], f64::INFINITY);
        self.close(Behaviour::Transit, from);
        let plannable = self.plannable;
        let mut loop_cells = trace(plannable, near.first(), |c| plannable[c]);
        loop_cells.push(near.first()); // back to where wall following began
        let waypoints = self.waypoints(&loop_cells, true);
        self.drive(&waypoints, Behaviour::WallFollowing, false)
    }

    /// How close the path must pass to a cell next to a wall to explore it:
    /// 0.85 of a cell (so a wall drawn as a staircase of cells can
    /// be followed along a straight line that keeps clearance), at most the reach.
    fn wall_reach(&self) -> f64 {
        self.reach.min(0.85)
    }

    fn wall_tolerance(&self) -> f64 {
        (self.wall_reach() - 0.125).max(0.0)
    }

    /// Step 3: CFCIDT targets and virtual-wall paths until nothing is unexplored.
    fn virtual_walls(&mut self) -> Result<()> {
        let mut search = CoarseToFine::new();
        let cap = self.plannable.count_true() + 2;
        for _ in 0..cap {
            let here = self.here()?;
            let Some(found) = search.nearest(&self.blocks, here) else {
                return Ok(());
            };
            self.iterations += 1;
            let target = found.target;
            let explored = &self.explored;
            let plannable = self.plannable;
            let boundary = trace(plannable, target, |c| plannable[c] && !explored[c]);
            let waypoints = self.waypoints(&boundary, false);
            let from = self.len() - 1;
            self.builder.follow(&found.path[1..], f64::INFINITY);
            self.close(Behaviour::Transit, from);
            self.drive(&waypoints, Behaviour::VirtualWall, true)?;
        }
        Err(Error::Internal(
            "smooth: more CIDT iterations than plannable cells".into(),
        ))
    }

    /// Path points for a traced boundary of the unexplored region.
    fn waypoints(&self, boundary: &[Cell], wall_loop: bool) -> Vec<Waypoint> {
        let n = boundary.len();
        let closed = n > 2 && boundary[0].manhattan(boundary[n - 1]) <= 1;
        let at = |i: isize| -> GridPoint {
            let j = if closed {
                i.rem_euclid(n as isize) as usize
            } else {
                i.clamp(0, n as isize - 1) as usize
            };
            cell_center(boundary[j])
        };
        let offset = self.reach - 0.5;
        let virtual_tol = (self.reach - 0.25).max(0.0);
        let clear = |u: GridPoint, q: GridPoint| self.clear.point(q) && self.clear.segment(u, q);
        let mut out: Vec<Waypoint> = Vec::with_capacity(n);
        for (i, &c) in boundary.iter().enumerate() {
            let u = cell_center(c);
            // Least-squares tangent over ±2 neighbours; the unexplored side
            // (the free side, for a wall loop) is on the left.
            let mut t = (0.0, 0.0);
            for k in 1..=2_isize {
                let (a, b) = (at(i as isize + k), at(i as isize - k));
                t.0 += k as f64 * (a.x - b.x);
                t.1 += k as f64 * (a.y - b.y);
            }
            let norm = norm(t.0, t.1);
            let normal = (norm > 1e-9).then(|| (t.1 / norm, -t.0 / norm));
            if wall_loop || self.near_wall[c] || offset <= 0.0 {
                // Wall following: through the cell.
                let p = u;
                out.push(Waypoint {
                    p,
                    u,
                    tol: if self.wall[c] {
                        self.wall_tolerance()
                    } else {
                        virtual_tol
                    },
                });
                continue;
            }
            let mut p = u;
            if let Some(nrm) = normal {
                for f in [1.0, 0.75, 0.5, 0.25] {
                    let q = GridPoint::new(u.x + nrm.0 * offset * f, u.y + nrm.1 * offset * f);
                    if clear(u, q) {
                        p = q;
                        break;
                    }
                }
            }
            let wp = Waypoint {
                p,
                u,
                tol: virtual_tol,
            };
            // Fig. 4: drop a path point whose connector crosses the previous one's.
            if let Some(prev) = out.last()
                && crosses(prev.u, prev.p, wp.u, wp.p)
            {
                out.push(Waypoint { p: prev.p, ..wp });
                continue;
            }
            out.push(wp);
        }
        out
    }

    /// Drives the waypoints: the minimal covering set of path points, joined
    /// by (optionally PSO-tuned Bézier) curves where they keep clearance and
    /// coverage, by routes where not even a straight piece does.
    fn drive(&mut self, wps: &[Waypoint], behaviour: Behaviour, curves: bool) -> Result<()> {
        let Some(first) = wps.first() else {
            return Ok(());
        };
        let from = self.len() - 1;
        self.builder.go_to(first.p)?;
        self.close(Behaviour::Transit, from);
        // Minimal covering set, split into runs joined by straight pieces.
        let mut runs: Vec<Vec<usize>> = vec![vec![0]];
        let mut a = 0;
        while a + 1 < wps.len() {
            let mut best = None;
            for b in a + 1..wps.len().min(a + 1 + LOOKAHEAD) {
                if wps[b].p == wps[a].p {
                    best = Some(b);
                    continue;
                }
                if self.straight_ok(wps, a, b) {
                    best = Some(b);
                } else {
                    break;
                }
            }
            match best {
                Some(b) => {
                    if wps[b].p != wps[a].p {
                        runs.last_mut().expect("a run").push(b);
                    }
                    a = b;
                }
                None => {
                    a += 1;
                    runs.push(vec![a]);
                }
            }
        }
        for (k, run) in runs.iter().enumerate() {
            let from = self.len() - 1;
            if k > 0 {
                self.builder.go_to(wps[run[0]].p)?;
                self.close(Behaviour::Transit, from);
            }
            let from = self.len() - 1;
            self.drive_run(wps, run, curves);
            self.close(behaviour, from);
        }
        Ok(())
    }

    /// Whether the straight piece from path point `a` to `b` keeps clearance
    /// and covers every wall point from `a` to `b`.
    fn straight_ok(&self, wps: &[Waypoint], a: usize, b: usize) -> bool {
        let (p, q) = (wps[a].p, wps[b].p);
        wps[a + 1..=b]
            .iter()
            .all(|w| segment_distance(p, q, w.u) <= w.tol)
            && self.builder.clear(p, q)
    }

    /// Drives one run of chosen path points (each straight piece known good).
    fn drive_run(&mut self, wps: &[Waypoint], run: &[usize], curves: bool) {
        let pts: Vec<GridPoint> = run.iter().map(|&i| wps[i].p).collect();
        if !curves || pts.len() < 3 {
            for &p in &pts[1..] {
                self.builder.push(p);
            }
            return;
        }
        let mut spline = G2Spline::through(&pts);
        // Wall points each segment answers for, and the unfiltered path points it replaces.
        let covers: Vec<&[Waypoint]> = run.windows(2).map(|w| &wps[w[0] + 1..=w[1]]).collect();
        let originals: Vec<Vec<GridPoint>> = run
            .windows(2)
            .map(|w| wps[w[0]..=w[1]].iter().map(|x| x.p).collect())
            .collect();
        let (clear, reach) = (&self.clear, self.reach);
        let ok = |sp: &G2Spline, i: usize| {
            let seg = sp.segment(i, 1.0);
            let samples = sample(&seg);
            curve_ok(clear, &samples, covers[i]).then(|| cost(&seg, &samples, &originals[i], reach))
        };
        // PSO per interior point whose two segments are good at the start.
        for i in 1..pts.len() - 1 {
            if ok(&spline, i - 1).is_none() || ok(&spline, i).is_none() {
                continue;
            }
            let base = spline.clone();
            let mut trial = spline.clone();
            let s = 0.5 * self.reach.max(0.5);
            let result = self.pso.minimise(
                [0.0; 4],
                [-s, -0.3, -0.6, -1.0],
                [s, 0.3, 0.4, 1.0],
                self.seed ^ ((self.iterations as u64) << 20) ^ (i as u64),
                |x| {
                    trial.adjust(&base, i, x);
                    Some(ok(&trial, i - 1)? + ok(&trial, i)?)
                },
            );
            if let Some(r) = result {
                self.pso_cost.0 += r.start_cost;
                self.pso_cost.1 += r.cost;
                spline.adjust(&base, i, &r.x);
            }
        }
        // Drive: each segment as the spline, or with shorter tangents, or straight.
        for (i, cover) in covers.iter().enumerate() {
            let curve = [1.0, 0.5, 0.25].into_iter().find_map(|k| {
                let seg = spline.segment(i, k);
                let samples = sample(&seg);
                curve_ok(clear, &samples, cover).then_some(samples)
            });
            if let Some(samples) = curve {
                self.curved += 1;
                for q in samples.into_iter().skip(1) {
                    self.builder.push(q);
                }
            } else {
                // The chord between the unmoved ends is known good; PSO may
                // have moved an end, so check and route if needed.
                self.straight += 1;
                let q = spline.point(i + 1);
                if self.builder.clear(self.builder.last(), q) {
                    self.builder.push(q);
                } else {
                    let _ = self.builder.go_to(q);
                }
            }
        }
    }
}

/// Whether the sampled curve keeps clearance and covers `covers`.
///
/// Wall points come in path order, so each search starts at the piece that
/// covered the previous one (same answer as a scan from the start, usually
/// after one or two pieces).
fn curve_ok(clear: &Clearance<'_>, samples: &[GridPoint], covers: &[Waypoint]) -> bool {
    let pieces = samples.len().saturating_sub(1);
    let mut from = 0;
    for w in covers {
        let hit = (0..pieces)
            .map(|k| (from + k) % pieces)
            .find(|&j| segment_distance(samples[j], samples[j + 1], w.u) <= w.tol);
        match hit {
            Some(j) => from = j,
            None => return false,
        }
    }
    samples.windows(2).all(|s| clear.segment(s[0], s[1]))
}

/// Points of a Bézier segment about half a cell apart (ends included).
fn sample(seg: &QuinticBezier) -> Vec<GridPoint> {
    let c = &seg.control;
    let poly: f64 = c
        .windows(2)
        .map(|w| norm(w[1].x - w[0].x, w[1].y - w[0].y))
        .sum();
    seg.sample((poly / 0.5).ceil().clamp(2.0, 200.0) as usize)
}

/// The PSO cost of a segment (see the module docs).
fn cost(seg: &QuinticBezier, samples: &[GridPoint], originals: &[GridPoint], reach: f64) -> f64 {
    let length = seg.length();
    let n = 16;
    let bending: f64 = (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) / n as f64;
            let d = seg.derivative(u);
            seg.curvature(u).powi(2) * norm(d.x, d.y) / n as f64
        })
        .sum();
    let gap: f64 = originals
        .iter()
        .map(|&o| {
            samples
                .windows(2)
                .map(|s| segment_distance(s[0], s[1], o))
                .fold(f64::INFINITY, f64::min)
                .powi(2)
        })
        .sum();
    let r = reach.max(0.5);
    length + r * r * bending + gap / r
}

/// Largest turn (rad) the time law drives through without stopping; sharper
/// vertices are rounded when they can be.
const GENTLE: f64 = 0.33;

/// Rounds the sharp vertices of a polyline by quintic Bézier fillets
/// (tangent to both segments, zero curvature at both ends, so G²), each as
/// wide as clearance allows, up to 3 cells along either segment (and half of
/// it), and no farther than `margin` cells from any point of the corner it
/// replaces (so what the corner covered with the reach, the fillet covers
/// with the tool). Sharp corners are where a tracked robot stops and turns in
/// place; a fillet is driven through.
fn fillet_corners(clear: &Clearance<'_>, pts: &[GridPoint], margin: f64) -> Vec<GridPoint> {
    let mut out = vec![pts[0]];
    if margin <= 0.0 {
        out.extend_from_slice(&pts[1..]);
        return out;
    }
    let unit = |a: GridPoint, b: GridPoint| {
        let l = norm(b.x - a.x, b.y - a.y);
        ((b.x - a.x) / l, (b.y - a.y) / l, l)
    };
    for i in 1..pts.len() - 1 {
        let (prev, p, next) = (*out.last().expect("a point"), pts[i], pts[i + 1]);
        let (ux, uy, lin) = unit(prev, p);
        let (vx, vy, lout) = unit(p, next);
        let turn = (ux * vy - uy * vx).atan2(ux * vx + uy * vy).abs();
        if !(lin > 1e-9 && lout > 1e-9) || turn <= GENTLE {
            out.push(p);
            continue;
        }
        let mut d = (0.5 * lin).min(0.5 * lout).min(3.0);
        let mut done = false;
        while d >= 0.05 {
            let a = GridPoint::new(p.x - d * ux, p.y - d * uy);
            let b = GridPoint::new(p.x + d * vx, p.y + d * vy);
            let l = norm(b.x - a.x, b.y - a.y);
            let seg = QuinticBezier::from_ends(
                a,
                b,
                Vector::new(l * ux, l * uy),
                Vector::new(l * vx, l * vy),
                Vector::new(0.0, 0.0),
                Vector::new(0.0, 0.0),
            );
            let samples = seg.sample(((2.0 * d) / 0.25).max(turn / 0.08).ceil().max(4.0) as usize);
            let near = |q: GridPoint| {
                samples
                    .windows(2)
                    .any(|s| segment_distance(s[0], s[1], q) <= margin)
            };
            let corner_covered = (0..=8).all(|k| {
                let t = k as f64 / 8.0;
                near(Point::new(a.x + t * (p.x - a.x), a.y + t * (p.y - a.y)))
                    && near(Point::new(p.x + t * (b.x - p.x), p.y + t * (b.y - p.y)))
            });
            if corner_covered && samples.windows(2).all(|s| clear.segment(s[0], s[1])) {
                out.extend_from_slice(&samples);
                done = true;
                break;
            }
            d /= 2.0;
        }
        if !done {
            out.push(p);
        }
    }
    out.push(pts[pts.len() - 1]);
    out
}

/// Whether segments `a1 a2` and `b1 b2` cross properly.
fn crosses(a1: GridPoint, a2: GridPoint, b1: GridPoint, b2: GridPoint) -> bool {
    let orient = |p: GridPoint, q: GridPoint, r: GridPoint| {
        (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)
    };
    let (d1, d2) = (orient(b1, b2, a1), orient(b1, b2, a2));
    let (d3, d4) = (orient(a1, a2, b1), orient(a1, a2, b2));
    d1 * d2 < -1e-12 && d3 * d4 < -1e-12
}

/// The boundary of the set `inside` through `start` (a member with a
/// non-member 4-neighbour), traced by the right-hand rule: non-members kept on
/// the right, 4-connected, until the trace returns to its start state.
fn trace(grid: &Grid<bool>, start: Cell, inside: impl Fn(Cell) -> bool) -> Vec<Cell> {
    let member = |c: Option<Cell>| c.is_some_and(&inside);
    let right = |d: Dir4| Dir4::from_index((d.index() + 1) % 4);
    let left = |d: Dir4| Dir4::from_index((d.index() + 3) % 4);
    let Some(d0) = Dir4::ALL
        .iter()
        .copied()
        .find(|&d| !member(grid.step(start, right(d))))
    else {
        return vec![start];
    };
    let mut out = vec![start];
    let (mut c, mut d) = (start, d0);
    let cap = 4 * grid.len() + 8;
    for _ in 0..cap {
        let r = right(d);
        if let Some(n) = grid.step(c, r).filter(|&n| inside(n)) {
            d = r;
            c = n;
            out.push(c);
        } else if let Some(n) = grid.step(c, d).filter(|&n| inside(n)) {
            c = n;
            out.push(c);
        } else {
            d = left(d);
        }
        if c == start && d == d0 {
            break;
        }
    }
    if out.len() > 1 && out.last() == Some(&start) {
        out.pop();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::ascii_mask;
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

    #[test]
    fn trace_keeps_the_outside_on_the_right() {
        let m = ascii_mask(&["...", "...", "..."]).unwrap();
        let t = trace(&m, Cell::new(0, 0), |c| m[c]);
        let rc: Vec<(usize, usize)> = t.iter().map(|c| (c.row, c.col)).collect();
        // Outside kept on the right: south down the west column, east, north, west.
        assert_eq!(
            rc,
            [
                (0, 0),
                (1, 0),
                (2, 0),
                (2, 1),
                (2, 2),
                (1, 2),
                (0, 2),
                (0, 1)
            ]
        );
    }

    #[test]
    fn trace_goes_round_a_hole() {
        let m = ascii_mask(&["....", ".##.", "...."]).unwrap();
        let t = trace(&m, Cell::new(0, 0), |c| m[c]);
        // The outer boundary: all ten free cells, once each.
        assert_eq!(t.len(), 10);
        let mut seen = t.clone();
        seen.sort_unstable_by_key(|c| (c.row, c.col));
        seen.dedup();
        assert_eq!(seen.len(), 10);
    }

    #[test]
    fn fillets_round_corners_within_the_margin() {
        let m = ascii_mask(&[".........."; 10]).unwrap();
        let pts = [
            GridPoint::new(1.5, 1.5),
            GridPoint::new(8.5, 1.5),
            GridPoint::new(8.5, 8.5),
        ];
        let clear = Clearance::new(&m, CLEARANCE);
        let out = fillet_corners(&clear, &pts, 0.5);
        assert!(out.len() > 3 && out.first() == pts.first() && out.last() == pts.last());
        for w in out.windows(3) {
            let (a, b) = (
                (w[1].x - w[0].x, w[1].y - w[0].y),
                (w[2].x - w[1].x, w[2].y - w[1].y),
            );
            let turn = (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1).abs();
            assert!(turn <= GENTLE + 1e-9, "{turn} at {:?}", w[1]);
        }
        // The corner point is still within the margin of the rounded path.
        assert!(
            out.windows(2)
                .any(|s| segment_distance(s[0], s[1], Point::new(8.5, 1.5)) <= 0.5)
        );
        // No margin, no rounding.
        assert_eq!(fillet_corners(&clear, &pts, 0.0), pts.to_vec());
    }

    #[test]
    fn crossing_connectors_are_detected() {
        assert!(crosses(
            Point::new(0.0, 0.0),
            Point::new(2.0, 2.0),
            Point::new(0.0, 2.0),
            Point::new(2.0, 0.0)
        ));
        assert!(!crosses(
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(0.0, 1.0),
            Point::new(1.0, 1.0)
        ));
    }

    /// Exact path on a tiny map: with unit cells the reach is half a cell;
    /// wall following goes once round the border (outside on the right)
    /// back to the start, and the centre cell is the one CIDT target left.
    #[test]
    fn three_by_three_room_exact() {
        let (p, pts, m) = plan("S..\n...\n...", 1);
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        // A stub of spiral (turns one cell apart) until it would leave the
        // start cell's clearance, back to the corner, round the border.
        let kinds: Vec<Behaviour> = p.pieces.iter().map(|q| q.behaviour).collect();
        use Behaviour::*;
        assert_eq!(kinds, [Spiral, Transit, WallFollowing, Transit]);
        let wall = p.pieces[2];
        assert_eq!(
            &pts[wall.start..],
            &[
                GridPoint::new(0.5, 0.5),
                GridPoint::new(0.5, 2.5),
                GridPoint::new(2.5, 2.5),
                GridPoint::new(2.5, 0.5),
                GridPoint::new(0.5, 0.5),
                GridPoint::new(1.5, 1.5)
            ]
        );
        assert_eq!(p.iterations, 1);
    }

    #[test]
    fn open_room_spirals_first_then_follows_the_wall() {
        let rows = ["..............."; 11].join("\n");
        let text = format!("{}S{}", &rows[..16 * 5 + 7], &rows[16 * 5 + 8..]);
        let (p, pts, m) = plan(&text, 3);
        assert_eq!(p.pieces[0].behaviour, Behaviour::Spiral);
        assert!(p.pieces[0].end > 10, "{:?}", p.pieces);
        assert!(
            p.pieces
                .iter()
                .any(|q| q.behaviour == Behaviour::WallFollowing)
        );
        for w in pts.windows(2) {
            assert!(
                crate::metre_path::segment_clearance(&m, w[0], w[1], CLEARANCE - 1e-9),
                "{w:?}"
            );
        }
        // PSO never raised the summed cost.
        assert!(p.pso_cost.1 <= p.pso_cost.0 + 1e-9, "{:?}", p.pso_cost);
    }
}
