//! The seed's own algorithm (Demir 2018 as published), run beside ours so
//! that its documented failures can be seen and measured.
//!
//! The same robot, sensing, lap and boundary-following primitives and the
//! same three-ray detector as [`super::cycle`]; what differs is what the
//! seed describes (its Sections 2.2–2.5 and 3.1):
//!
//! - **No cycle algorithm.** The robot sweeps the classic way: a lap along
//!   a slice, then boundary following from the lap's end to the next slice,
//!   then a lap the other way. Each slab is crossed once, along one of its
//!   boundaries; the boundary on the other side is never followed, so
//!   critical points there are only seen if a lap happens to meet them.
//! - **Uncovered cells are not tracked.** When a lap stops short of the
//!   previous lap's far end by more than a lap spacing, something stands in
//!   the slice: the robot keeps the previous lap's far end as the "previous
//!   node" to come back to and scan the other side of the obstacle from
//!   there (the seed: "it moves to previous node and continue scanning from
//!   the down side of the obstacle"). Nothing else is remembered: a cell that
//!   only a sweep in the other direction could enter (the pocket of a
//!   concave obstacle) is never entered. A cell ends when the robot cannot
//!   reach the next slice: the boundary turns back, or a wall stands across
//!   the sweep. The sweep runs towards +x from the start, then towards −x
//!   from the start's slice.
//! - **The graph: an edge from the last visited node.** A node is added
//!   where the seed adds one: where a lap stops short of the previous one
//!   (an obstacle's first critical point, found in motion to boundary) or
//!   runs past it, where a wall across the sweep ends a cell (the seed's
//!   border critical point), and where the three rays fired along x at a
//!   turning point of the follower find a critical point. A new node gets an
//!   edge from the last node visited, whatever cell the two belong to.
//!
//! Choices the seed leaves open, taken so that the run is a fair lapping
//! robot and terminates: between slices the robot moves straight along x
//! where the way is clear and follows the boundary only where it is not; a
//! wall closer than a lap spacing gets one last lap; a resumed side whose
//! first lap lands on ground the robot has already swept (its own visited
//! cells) is dropped; nodes closer than half a lap spacing are one; travel
//! to a kept node runs over the robot's own map, through gaps barely wider
//! than the robot if need be (keeping its body radius), backing out of a
//! corner along its own path first.

use crate::{CriticalKind, Detection};
use oxcover_grid::Point;

use super::body::Body;
use super::cycle::Counters;
use super::reeb::{CellEdge, DetectedCritical, ReebGraph};
use super::{Config, State};
use crate::error::Result;

/// Where to come back to: the far end of a lap, with the sweep's direction.
#[derive(Clone, Copy, Debug)]
struct Resume {
    /// The lap's end on slice `slice`.
    at: Point,
    slice: i64,
    /// Whether `at` is the lap's upper end.
    top: bool,
    /// Sweep direction along x (±1).
    dir: f64,
}

/// The seed's explorer.
pub(crate) struct Paper<'w> {
    pub body: Body<'w>,
    pub counters: Counters,
    nodes: Vec<DetectedCritical>,
    edges: Vec<CellEdge>,
    last: Option<usize>,
    pending: Vec<Resume>,
    x0: f64,
    w: f64,
    hysteresis: f64,
}

impl<'w> Paper<'w> {
    pub(crate) fn new(body: Body<'w>, cfg: &Config) -> Self {
        let x0 = body.p.x;
        Self {
            body,
            counters: Counters::default(),
            nodes: Vec::new(),
            edges: Vec::new(),
            last: None,
            pending: Vec::new(),
            x0,
            w: 2.0 * cfg.tool_radius,
            hysteresis: cfg.x_hysteresis(),
        }
    }

    fn slice_x(&self, j: i64) -> f64 {
        self.x0 + j as f64 * self.w
    }

    /// The graph: the nodes found, an edge from each to the node visited
    /// before it.
    pub(crate) fn graph(&self) -> ReebGraph {
        ReebGraph {
            nodes: self.nodes.clone(),
            edges: self.edges.clone(),
        }
    }

    /// Sweeps towards +x, then towards −x, each time coming back to every
    /// kept "previous node".
    pub(crate) fn run(&mut self) -> Result<()> {
        let lo = self.body.lap(-1.0)?;
        let hi = self.body.lap(1.0)?;
        self.counters.laps += 1;
        for dir in [1.0, -1.0] {
            if dir < 0.0 && !self.go_to(hi) {
                break;
            }
            self.sweep(0, lo, hi, true, dir)?;
            while let Some(r) = self.pending.pop() {
                if !self.go_to(r.at) {
                    self.counters.unreached += 1;
                    continue;
                }
                self.resume(r)?;
            }
        }
        Ok(())
    }

    /// Travels over the robot's own map to `p`; false when it cannot. A
    /// robot pressed into a corner closer than its map's routes keep (after a
    /// lap against a wall) first backs out along the way it came, up to a
    /// metre.
    fn go_to(&mut self, p: Point) -> bool {
        let d = (p.x - self.body.p.x).hypot(p.y - self.body.p.y);
        if d < 1e-9 || self.route_to(p) {
            return true;
        }
        let mut back = self.body.trace.len().saturating_sub(1);
        let mut walked = 0.0;
        while back > 0 && walked < 1.0 {
            back -= 1;
            let t = self.body.trace[back];
            let q = Point::new(t.x, t.y);
            let here = self.body.p;
            walked += (q.x - here.x).hypot(q.y - here.y);
            if self.body.advance(q, State::Transit).is_err() {
                return false;
            }
            if back % 5 == 0 && self.route_to(p) {
                return true;
            }
        }
        self.route_to(p)
    }

    /// A route over the robot's own map to `p`, travelled; false when there
    /// is none. Routes keep one map cell more than the robot's distance from
    /// anything not seen free; where none does (a gap barely wider than the
    /// robot), that distance, then the body radius and half a cell.
    fn route_to(&mut self, p: Point) -> bool {
        let res = self.body.map.resolution();
        [
            self.body.keep + res,
            self.body.keep,
            self.body.r + res / 2.0,
        ]
        .into_iter()
        .any(|keep_out| self.route_keeping(p, keep_out))
    }

    fn route_keeping(&mut self, p: Point, keep_out: f64) -> bool {
        let map = &self.body.map;
        let pass = map.passable(keep_out);
        let (dist, parent) = map.distances(&pass, self.body.p, &[p]);
        if map.cell_index(p).is_none_or(|c| !dist[c].is_finite()) {
            return false;
        }
        let route = map.route(&pass, &parent, p);
        let before = self.body.length;
        let ok = self.body.travel(&route).is_ok();
        self.counters.travel_m += self.body.length - before;
        ok
    }

    /// Scans the other side from a kept lap end: on to the next slice, and
    /// on from there unless that lap lands on ground already swept.
    fn resume(&mut self, r: Resume) -> Result<()> {
        let before = self.body.map.visit_count();
        let Some((nlo, nhi)) = self.step_slice(r.slice, r.top, r.dir, r.at, r.at)? else {
            return Ok(());
        };
        let mid = Point::new(nlo.x, (nlo.y + nhi.y) / 2.0);
        if self.body.map.first_visit(mid).is_some_and(|k| k < before) {
            return Ok(());
        }
        self.sweep(r.slice + r.dir as i64, nlo, nhi, !r.top, r.dir)
    }

    /// From the end (`top` or bottom) of lap `[lo, hi]` on slice `j`,
    /// boustrophedon towards `dir` until a cell ends.
    fn sweep(
        &mut self,
        mut j: i64,
        mut lo: Point,
        mut hi: Point,
        mut top: bool,
        dir: f64,
    ) -> Result<()> {
        while let Some((nlo, nhi)) = self.step_slice(j, top, dir, lo, hi)? {
            j += dir as i64;
            (lo, hi, top) = (nlo, nhi, !top);
        }
        Ok(())
    }

    /// Follows the boundary from the lap end to slice `j + dir`, then laps
    /// the other way; the new lap, or `None` when the follower could not
    /// reach the next slice (the cell ends). Keeps the previous lap's far
    /// end when the new lap stops short of it.
    fn step_slice(
        &mut self,
        j: i64,
        top: bool,
        dir: f64,
        lo: Point,
        hi: Point,
    ) -> Result<Option<(Point, Point)>> {
        let target = self.slice_x(j + dir as i64);
        // Boundary on the left (clockwise) from an upper end heading +x.
        let turn = if top { -dir } else { dir };
        if !self.follow_to(target, turn, dir)? {
            // Something in the moving direction: for the seed, a critical
            // point of the border (or of the obstacle) that ends the cell.
            let p = self.body.p;
            let at = Point::new(p.x + dir * self.body.keep, p.y);
            self.add_node(at, p, CriticalKind::from_extremum(-dir, true), false);
            // Short of the next slice but well past this one (a wall closer
            // than a lap spacing): one last lap there, as any lapping robot
            // ends against a wall.
            if dir * (p.x - self.slice_x(j)) > self.w / 4.0 {
                self.body.lap(if top { -1.0 } else { 1.0 })?;
                self.counters.laps += 1;
            }
            return Ok(None);
        }
        let e = self.body.p;
        let c = self.body.lap(if top { -1.0 } else { 1.0 })?;
        self.counters.laps += 1;
        let (nlo, nhi) = if top { (c, e) } else { (e, c) };
        // A lap that stops short of the previous one's far end has met an
        // obstacle: the seed's first critical point of the obstacle (found in
        // motion to boundary); the far end is the node to come back to. A lap
        // that runs past it has passed the end of one.
        let (short, far) = if top {
            (nlo.y > lo.y + self.w, lo)
        } else {
            (nhi.y < hi.y - self.w, hi)
        };
        let past = if top {
            nlo.y < lo.y - self.w
        } else {
            nhi.y > hi.y + self.w
        };
        if short {
            self.add_node(c, c, CriticalKind::from_extremum(dir, true), false);
            self.pending.push(Resume {
                at: far,
                slice: j,
                top: !top,
                dir,
            });
        } else if past {
            self.add_node(far, far, CriticalKind::from_extremum(-dir, true), false);
        }
        Ok(Some((nlo, nhi)))
    }

    /// Moves on to x = `target`: straight along x where the way is clear,
    /// along the boundary (on the `turn` side) where it is not. True when it
    /// gets there; false when the cell ends: the follower falls back more than
    /// half a lap spacing behind where it started, runs along a wall across
    /// the sweep (x constant over twice the kept distance), or makes no
    /// headway over four lap spacings and a turn round a corner of boundary.
    /// Turning points of the follower along x are offered to the graph.
    fn follow_to(&mut self, target: f64, turn: f64, dir: f64) -> Result<bool> {
        let start = dir * self.body.p.x;
        let goal = dir * target;
        let wall = 2.0 * self.body.keep;
        let stall = 4.0 * self.w + std::f64::consts::TAU * self.body.keep;
        let mut flat = (start, 0.0);
        let mut mark = (start, 0.0);
        let mut moved = 0.0;
        let mut ext = (start, self.body.p);
        let mut trend = 1.0;
        loop {
            let p = self.body.p;
            let ahead = Point::new(dir * (dir * p.x + self.body.step()).min(goal), p.y);
            let q = if self.body.clear_step(ahead) {
                ahead
            } else {
                let Some(q) = self.body.follow_target(turn) else {
                    return Ok(false);
                };
                q
            };
            let (xp, xq) = (dir * p.x, dir * q.x);
            let arrive = if xq >= goal {
                let t = if (xq - xp).abs() > 1e-15 {
                    ((goal - xp) / (xq - xp)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                Some(Point::new(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)))
            } else {
                None
            };
            let state = self.body.following_state();
            self.body.advance(arrive.unwrap_or(q), state)?;
            moved += (q.x - p.x).hypot(q.y - p.y);
            if arrive.is_some() {
                return Ok(true);
            }
            let xi = dir * self.body.p.x;
            // Turning points along x: where the follower's x reverses.
            if (trend > 0.0 && xi > ext.0) || (trend < 0.0 && xi < ext.0) {
                ext = (xi, self.body.p);
            } else if (xi - ext.0).abs() > self.hysteresis {
                self.node_at(ext.1, trend * dir);
                trend = -trend;
                ext = (xi, self.body.p);
            }
            if xi < start - self.w / 2.0 {
                return Ok(false);
            }
            if xi > mark.0 + self.hysteresis {
                mark = (xi, moved);
            } else if moved - mark.1 > stall {
                return Ok(false);
            }
            if (xi - flat.0).abs() > 2.0 * self.hysteresis {
                flat = (xi, moved);
            } else if moved - flat.1 > wall {
                return Ok(false);
            }
        }
    }

    /// Fires the three rays along x from `robot` towards `towards` (±1); a
    /// node when they are not collinear (the seed's eq. 3), with an edge from
    /// the last node visited.
    fn node_at(&mut self, robot: Point, towards: f64) {
        self.counters.turning_points += 1;
        let angle = if towards > 0.0 {
            0.0
        } else {
            std::f64::consts::PI
        };
        self.node_at_angle(robot, angle);
    }

    /// Fires the three rays from `robot`, the centre one at `angle`; a node
    /// when they find a critical point.
    fn node_at_angle(&mut self, robot: Point, angle: f64) {
        let Some(returns) = self.body.detect_from(robot, angle) else {
            return;
        };
        if let Detection::Critical(kind) = self.body.detector.classify(robot, &returns) {
            self.counters.confirmed += 1;
            self.add_node(returns.centre, robot, kind, true);
        }
    }

    /// A node at `at` (one already within half a lap spacing is the same),
    /// with an edge from the last node visited; it becomes the last visited.
    fn add_node(&mut self, at: Point, robot: Point, kind: CriticalKind, confirmed: bool) {
        let same = self
            .nodes
            .iter()
            .find(|n| (n.at.x - at.x).hypot(n.at.y - at.y) < self.w / 2.0)
            .map(|n| n.id);
        let id = same.unwrap_or_else(|| {
            let id = self.nodes.len();
            self.nodes.push(DetectedCritical {
                id,
                at,
                robot,
                span: (robot.y, robot.y),
                kind,
                confirmed,
            });
            if let Some(from) = self.last {
                self.edges.push(CellEdge {
                    id: self.edges.len(),
                    from: Some(from),
                    to: Some(id),
                    laps: Vec::new(),
                    covered: true,
                });
            }
            id
        });
        self.last = Some(id);
    }
}
