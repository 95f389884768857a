//! The exploration loop: slab cycles, the work list of untraced slab sides,
//! and travel to the nearest of them.
//!
//! A *cycle* closes one component of the free space between two slices `a`
//! and `b`. Starting at an end of a lap interval on slice `a`, the robot
//! follows the boundary into the slab, keeping it on one side for the whole
//! cycle. Whenever it reaches slice `a` or `b` it laps along that slice to
//! the next contact (covering that interval) and follows on. It stops when it
//! comes back to the other end of the interval it started from: it has then
//! been round the component's whole boundary, so every critical point on it
//! was passed by the follower, and every interval the component touches was
//! lapped.
//!
//! Critical points are the follower's turning points along x inside the
//! slab: where the followed boundary is tangent to the slice. A turning
//! point is taken when x retreats from its running extreme by more than a
//! hysteresis (range noise must not make turning points); a run that leaves
//! the slab through the slice it entered by has passed an odd number of
//! turning points, so a turning point too shallow for the hysteresis is
//! still recorded there. At the running extreme the robot fires the three-ray
//! detector along x; its class is kept when it agrees with the follower
//! about which way the boundary continues.

use crate::{CriticalKind, Detection};
use oxcover_grid::Point;

use super::Config;
use super::body::Body;
use super::reeb::{Reeb, SlabRecord};
use crate::error::{Error, Result};

/// Follower steps before a run may leave through the slice it started on.
const START_GUARD_STEPS: f64 = 3.0;
/// Boundary-following runs allowed in one cycle.
const MAX_RUNS: usize = 10_000;

/// Which slice of the slab a run left by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Exit {
    A,
    B,
}

/// A candidate turning point.
#[derive(Clone, Copy, Debug)]
struct Extreme {
    xi: f64,
    robot: Point,
    /// Side of the boundary from the robot along x (±1).
    towards: f64,
    contact: Point,
    detection: Detection,
}

/// Counters of an exploration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Counters {
    /// Cycles traced.
    pub cycles: usize,
    /// Laps (intervals traversed, repeats included).
    pub laps: usize,
    /// Turning points found (before merging repeats).
    pub turning_points: usize,
    /// Turning points the three-ray detector classified the same way.
    pub confirmed: usize,
    /// Travel length between cycles (m).
    pub travel_m: f64,
    /// Work items the robot could not reach on its own map.
    pub unreached: usize,
    /// Cycles closed because the follower came back to an exit it had
    /// already passed, not to the start interval (noise at a grazing slice).
    pub forced_closures: usize,
}

/// The exploration state.
pub(crate) struct Explorer<'w> {
    pub body: Body<'w>,
    pub reeb: Reeb,
    pub counters: Counters,
    x0: f64,
    w: f64,
    hysteresis: f64,
    close: f64,
    step: f64,
}

impl<'w> Explorer<'w> {
    pub(crate) fn new(body: Body<'w>, cfg: &Config) -> Self {
        let x0 = body.p.x;
        Self {
            body,
            reeb: Reeb::default(),
            counters: Counters::default(),
            x0,
            w: 2.0 * cfg.tool_radius,
            hysteresis: cfg.x_hysteresis(),
            close: (10.0 * cfg.noise_sd).max(0.03),
            step: cfg.step,
        }
    }

    fn slice_x(&self, j: i64) -> f64 {
        self.x0 + j as f64 * self.w
    }

    /// Explores until no slab side is left untraced.
    pub(crate) fn run(&mut self) -> Result<()> {
        // The start's own slice: down to the floor, then up to the ceiling.
        let lo = self.body.lap(-1.0)?;
        let hi = self.body.lap(1.0)?;
        self.counters.laps += 1;
        self.reeb.interval(0, lo, hi);
        while let Some((k, s, top)) = self.next_item()? {
            self.cycle(k, s, top)?;
        }
        Ok(())
    }

    /// Travels to the nearest end of an interval with an untraced side;
    /// `None` when there is none (or none the robot can reach).
    fn next_item(&mut self) -> Result<Option<(usize, f64, bool)>> {
        let mut items = Vec::new();
        for (k, iv) in self.reeb.intervals.iter().enumerate() {
            for (side, s) in [(0, -1.0), (1, 1.0)] {
                if !iv.done[side] {
                    items.push((k, s, false, iv.lo));
                    items.push((k, s, true, iv.hi));
                }
            }
        }
        if items.is_empty() {
            return Ok(None);
        }
        let map = &self.body.map;
        let pass = map.passable(self.body.keep + map.resolution());
        let targets: Vec<Point> = items.iter().map(|i| i.3).collect();
        let (dist, parent) = map.distances(&pass, self.body.p, &targets);
        let reach = |p: Point| {
            let direct = (p.x - self.body.p.x).hypot(p.y - self.body.p.y);
            if direct < 1e-9 {
                return Some(0.0);
            }
            map.cell_index(p).map(|c| dist[c]).filter(|d| d.is_finite())
        };
        let best = items
            .iter()
            .filter_map(|&(k, s, top, p)| reach(p).map(|d| (d, k, s, top, p)))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let Some((d, k, s, top, p)) = best else {
            self.counters.unreached = items.len() / 2;
            return Ok(None);
        };
        if d > 0.0 {
            let route = map.route(&pass, &parent, p);
            let before = self.body.length;
            self.body.travel(&route)?;
            self.counters.travel_m += self.body.length - before;
        }
        Ok(Some((k, s, top)))
    }

    /// Closes the component of the slab on side `s` of interval `k`, starting
    /// from its upper (`top`) or lower end, where the robot is.
    fn cycle(&mut self, k: usize, s: f64, top: bool) -> Result<()> {
        self.counters.cycles += 1;
        let a = self.reeb.intervals[k].slice;
        let b = a + s as i64;
        let (xi_a, xi_b) = (s * self.slice_x(a), s * self.slice_x(b));
        let start = self.reeb.intervals[k].clone();
        // Boundary on the left (turn clockwise) from an upper end heading +x…
        let turn = if top { -s } else { s };
        let (xa, xb) = (self.slice_x(a), self.slice_x(b));
        let mut record = SlabRecord {
            left: a.min(b),
            x: (xa.min(xb), xa.max(xb)),
            intervals: vec![k],
            criticals: Vec::new(),
            boundary: Vec::new(),
        };
        let trace_from = self.body.trace.len() - 1;
        let mut from_a = true;
        let mut exits: Vec<(Exit, f64)> = Vec::new();
        for _ in 0..MAX_RUNS {
            let exit = self.follow_run(turn, s, xi_a, xi_b, from_a, &mut record)?;
            let p = self.body.p;
            // Back on the start interval's stretch of slice a: closed. (Its
            // ends, not only the one opposite the start: where the boundary
            // is steep, noise moves the crossing along the slice.)
            if exit == Exit::A && p.y >= start.lo.y - self.close && p.y <= start.hi.y + self.close {
                self.finish(record, a, s, trace_from);
                return Ok(());
            }
            // An exit seen before in this cycle: the loop is closed too (a
            // slice grazing a boundary within noise can make the follower
            // miss the start's stretch).
            if exits
                .iter()
                .any(|&(e, y)| e == exit && (y - p.y).abs() < self.close)
            {
                self.counters.forced_closures += 1;
                self.finish(record, a, s, trace_from);
                return Ok(());
            }
            exits.push((exit, p.y));
            // Lap along the slice, away from the boundary just followed.
            let dir = turn * self.body_heading_x().signum();
            let q = self.body.lap(dir)?;
            self.counters.laps += 1;
            let slice = if exit == Exit::A { a } else { b };
            let j = self.reeb.interval(slice, p, q);
            if !record.intervals.contains(&j) {
                record.intervals.push(j);
            }
            if j == k {
                self.finish(record, a, s, trace_from);
                return Ok(());
            }
            from_a = exit == Exit::A;
        }
        Err(Error::Internal(format!(
            "sensor-bcd: the cycle from slice {a} did not close in {MAX_RUNS} runs"
        )))
    }

    fn body_heading_x(&self) -> f64 {
        let n = self.body.trace.len();
        if n < 2 {
            return 1.0;
        }
        let (p, q) = (&self.body.trace[n - 2], &self.body.trace[n - 1]);
        q.x - p.x
    }

    /// Marks the slab sides traced and keeps the record, with the boundary
    /// the robot traced since `trace_from` (closed along the start interval).
    fn finish(&mut self, mut record: SlabRecord, a: i64, s: f64, trace_from: usize) {
        record.boundary = self.body.trace[trace_from..]
            .iter()
            .map(|t| Point::new(t.x, t.y))
            .collect();
        for &j in &record.intervals {
            let iv = &mut self.reeb.intervals[j];
            // The slab lies towards +s from slice a, towards −s from slice b.
            let towards = if iv.slice == a { s } else { -s };
            iv.done[usize::from(towards > 0.0)] = true;
        }
        self.reeb.slabs.push(record);
    }

    /// Follows the boundary inside the slab until it leaves by slice `a` or
    /// `b`; records the turning points on the way.
    fn follow_run(
        &mut self,
        turn: f64,
        s: f64,
        xi_a: f64,
        xi_b: f64,
        from_a: bool,
        record: &mut SlabRecord,
    ) -> Result<Exit> {
        let mut trend = if from_a { 1.0 } else { -1.0 };
        let mut ext = self.extreme(s);
        // (ξ, y) of the positions since the last turning point.
        let mut since = vec![Point::new(ext.xi, ext.robot.y)];
        let mut moved = 0.0;
        let guard = START_GUARD_STEPS * self.step;
        loop {
            let q = self.body.follow_target(turn).ok_or_else(|| {
                Error::Internal(format!(
                    "sensor-bcd: lost the boundary at ({:.3}, {:.3})",
                    self.body.p.x, self.body.p.y
                ))
            })?;
            let p = self.body.p;
            let (xi_p, xi_q) = (s * p.x, s * q.x);
            let exit = if xi_q >= xi_b && (from_a || moved > guard) {
                Some((Exit::B, xi_b))
            } else if xi_q <= xi_a && (!from_a || moved > guard) {
                Some((Exit::A, xi_a))
            } else {
                None
            };
            let target = match exit {
                Some((_, bound)) => {
                    let t = if (xi_q - xi_p).abs() > 1e-15 {
                        ((bound - xi_p) / (xi_q - xi_p)).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    Point::new(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y))
                }
                None => q,
            };
            let state = self.body.following_state();
            self.body.advance(target, state)?;
            moved += self.step;
            let xi = s * self.body.p.x;
            since.push(Point::new(xi, self.body.p.y));
            if trend > 0.0 {
                if xi > ext.xi {
                    ext = self.extreme(s);
                } else if ext.xi - xi > self.hysteresis {
                    self.turning_point(ext, &since, true, s, record);
                    trend = -1.0;
                    ext = self.extreme(s);
                    since = vec![Point::new(xi, self.body.p.y)];
                }
            } else if xi < ext.xi {
                ext = self.extreme(s);
            } else if xi - ext.xi > self.hysteresis {
                self.turning_point(ext, &since, false, s, record);
                trend = 1.0;
                ext = self.extreme(s);
                since = vec![Point::new(xi, self.body.p.y)];
            }
            if let Some((e, _)) = exit {
                // Leaving by slice a means going −ξ, by b going +ξ; a missing
                // turn was shallower than the hysteresis.
                let want = if e == Exit::A { -1.0 } else { 1.0 };
                if trend != want {
                    self.turning_point(ext, &since, trend > 0.0, s, record);
                }
                return Ok(e);
            }
        }
    }

    /// The current position as a candidate turning point, with the
    /// detector fired along x towards the boundary.
    fn extreme(&mut self, s: f64) -> Extreme {
        let p = self.body.p;
        let nearest = self.body.nearest.map_or(p, |n| n.0);
        let dx = nearest.x - p.x;
        let towards = if dx.abs() > 1e-6 { dx.signum() } else { s };
        // Fired along x; when that ray grazes past a thin tip (it returns
        // much farther than the nearest point), aimed at the nearest point.
        let keep = self.body.keep;
        let far = |r: &crate::Returns| (r.centre.x - p.x).hypot(r.centre.y - p.y) > 2.0 * keep;
        let mut returns = self.body.detect(if towards > 0.0 {
            0.0
        } else {
            std::f64::consts::PI
        });
        if returns.as_ref().is_none_or(far) {
            returns = self.body.detect((nearest.y - p.y).atan2(nearest.x - p.x));
        }
        let detection = returns.map_or(Detection::Blind, |r| self.body.detector.classify(p, &r));
        Extreme {
            xi: s * p.x,
            robot: p,
            towards,
            contact: returns.map_or(nearest, |r| r.centre),
            detection,
        }
    }

    /// Records a turning point: a maximum of ξ = s·x when `is_max`.
    /// `since` holds (ξ, y) of the run since the last turning point: the
    /// stretch within the hysteresis of the extreme around it is the
    /// critical stretch (a wall along y gives a long one).
    fn turning_point(
        &mut self,
        e: Extreme,
        since: &[Point],
        is_max: bool,
        s: f64,
        record: &mut SlabRecord,
    ) {
        let at = since
            .iter()
            .position(|q| q.x == e.xi && q.y == e.robot.y)
            .unwrap_or(0);
        let near = |k: &usize| (since[*k].x - e.xi).abs() <= self.hysteresis;
        let first = (0..=at).rev().take_while(near).last().unwrap_or(at);
        let last = (at..since.len()).take_while(near).last().unwrap_or(at);
        let ys = since[first..=last].iter().map(|p| p.y);
        let span = (
            ys.clone().fold(f64::INFINITY, f64::min),
            ys.fold(f64::NEG_INFINITY, f64::max),
        );
        // The boundary continues towards −ξ from a maximum.
        let open = if is_max { -s } else { s };
        let follower = CriticalKind::from_extremum(open, e.towards == open);
        // A wall along y is the detector's degenerate critical segment: it
        // confirms the point, and the follower tells how the wall ends.
        let (kind, confirmed) = match e.detection {
            Detection::Critical(k) if k.event == follower.event => (k, k == follower),
            Detection::SliceParallel => (follower, true),
            _ => (follower, false),
        };
        self.counters.turning_points += 1;
        if confirmed {
            self.counters.confirmed += 1;
        }
        let id = self
            .reeb
            .critical(e.contact, e.robot, span, kind, confirmed, self.hysteresis);
        if !record.criticals.contains(&id) {
            record.criticals.push(id);
        }
    }
}
