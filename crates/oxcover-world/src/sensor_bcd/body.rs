//! The simulated robot: a disc that moves, scans its ring of range rays after
//! every move, and drives only on what those rays tell it.
//!
//! Motion primitives (Demir 2018's states):
//!
//! - [`Body::lap`], *motion to boundary*: straight along the slice until the
//!   disc, grown by the clearance margin, would touch a sensed point;
//! - [`Body::follow_target`], *boundary following* at distance `r + δ`: from
//!   the direction of the nearest sensed point, turn (counter-clockwise with
//!   the boundary on the right, clockwise with it on the left) to the first
//!   direction whose step keeps `r + δ` from every point sensed by the last
//!   few scans. This hugs straight walls, swings round convex corners and
//!   turns away in concave ones, with no special cases;
//! - [`Body::travel`]: along a route of the robot's own map.
//!
//! The world's exact geometry is used for one thing only: to check, after
//! every move, that the disc did not touch it (collisions are counted, not
//! prevented, so a test can demand zero).

use oxcover_grid::Point;
use std::collections::VecDeque;
use std::f64::consts::TAU;

use crate::{RangeSensor, ThreeRayDetector, WorldGeometry};

use super::robot_map::RobotMap;
use super::{Config, State, TracePoint};
use crate::error::{Error, Result};

/// Scans kept for clearance checks (the ring turns with the heading, so
/// recent scans fill the gaps between rays).
const MEMORY: usize = 4;
/// Rays of the ring used to mark free space in the robot's map (every n-th).
const MAP_RAY_STRIDE: usize = 3;
/// Scans between free-space updates of the robot's map.
const MAP_SCAN_STRIDE: usize = 3;
/// How far free space is marked along a ray (m).
const MAP_RANGE: f64 = 1.5;
/// Angular resolution of the boundary follower's search (rad).
const TURN_STEP: f64 = std::f64::consts::PI / 90.0;

/// The simulated robot.
pub(crate) struct Body<'w> {
    world: &'w WorldGeometry,
    /// Body radius (m).
    pub r: f64,
    /// Distance kept from sensed boundaries (m): `r + δ`.
    pub keep: f64,
    step: f64,
    lap_step: f64,
    /// Readings this much inside the kept distance beside a lap are noise (m).
    beside: f64,
    noise_sd: f64,
    /// Position (m).
    pub p: Point,
    heading: f64,
    ring: RangeSensor,
    ring_angles: Vec<f64>,
    /// The sensor the three-ray detector fires (same noise model).
    pub probe: RangeSensor,
    /// The detector.
    pub detector: ThreeRayDetector,
    recent: VecDeque<Vec<Point>>,
    /// Nearest sensed point of the last scan and its surface.
    pub nearest: Option<(Point, usize)>,
    /// Every position, with the state that led to it.
    pub trace: Vec<TracePoint>,
    /// Path length so far (m).
    pub length: f64,
    /// Smallest exact clearance of the disc's centre seen (m).
    pub min_clearance: f64,
    /// Moves that ended with the disc overlapping the world.
    pub collisions: usize,
    /// The robot's own map.
    pub map: RobotMap,
    scans: usize,
    max_length: f64,
}

impl<'w> Body<'w> {
    /// A robot at `start`, after its first scan.
    pub(crate) fn new(world: &'w WorldGeometry, cfg: &Config, start: Point) -> Result<Self> {
        let bad = |e: Error| Error::BadParameter {
            name: "range sensor",
            value: e.to_string(),
            expected: "a valid ring of rays",
        };
        let ring =
            RangeSensor::ring(cfg.rays, cfg.max_range, cfg.noise_sd, cfg.seed).map_err(bad)?;
        let probe = RangeSensor::ring(
            1,
            cfg.max_range,
            cfg.noise_sd,
            cfg.seed ^ 0x9e37_79b9_7f4a_7c15,
        )
        .map_err(bad)?;
        let keep = cfg.robot_radius + cfg.margin;
        let mut body = Self {
            world,
            r: cfg.robot_radius,
            keep,
            step: cfg.step,
            lap_step: (2.5 * cfg.step).min(keep / 2.0),
            beside: 3.0 * cfg.noise_sd,
            noise_sd: cfg.noise_sd,
            p: start,
            heading: 0.0,
            ring_angles: ring.angles.clone(),
            ring,
            probe,
            detector: ThreeRayDetector::for_noise(cfg.noise_sd, keep),
            recent: VecDeque::new(),
            nearest: None,
            trace: vec![TracePoint {
                x: start.x,
                y: start.y,
                state: State::Start,
            }],
            length: 0.0,
            min_clearance: world.clearance(start).0,
            collisions: 0,
            map: RobotMap::new(cfg.map_resolution, start),
            scans: 0,
            max_length: cfg.max_length,
        };
        body.map.visit(start);
        body.scan();
        Ok(body)
    }

    /// Reads the ring and updates the memory and the map.
    fn scan(&mut self) {
        let mut hits = Vec::with_capacity(self.ring_angles.len());
        let mut nearest: Option<(Point, usize, f64)> = None;
        let mark_free = self.scans % MAP_SCAN_STRIDE == 0;
        for (k, &a) in self.ring_angles.iter().enumerate() {
            let angle = self.heading + a;
            let reading = self.ring.read(self.world, self.p, angle);
            let end = Point::new(
                self.p.x + reading.range * angle.cos(),
                self.p.y + reading.range * angle.sin(),
            );
            if let Some(s) = reading.surface {
                hits.push(end);
                self.map.occupied(end);
                if nearest.is_none_or(|n| reading.range < n.2) {
                    nearest = Some((end, s, reading.range));
                }
            }
            if mark_free && k % MAP_RAY_STRIDE == 0 {
                let t = reading.range.min(MAP_RANGE);
                let to = Point::new(self.p.x + t * angle.cos(), self.p.y + t * angle.sin());
                self.map
                    .ray(self.p, to, reading.surface.is_some() && t >= reading.range);
            }
        }
        self.scans += 1;
        self.nearest = nearest.map(|n| (n.0, n.1));
        self.recent.push_front(hits);
        self.recent.truncate(MEMORY);
    }

    /// Sensed points within `radius` of the robot.
    fn near(&self, radius: f64) -> Vec<Point> {
        let r2 = radius * radius;
        self.recent
            .iter()
            .flatten()
            .filter(|h| (h.x - self.p.x).powi(2) + (h.y - self.p.y).powi(2) <= r2)
            .copied()
            .collect()
    }

    /// Moves to `q` in `state`: counts length, checks the exact clearance,
    /// records the position and scans.
    pub(crate) fn advance(&mut self, q: Point, state: State) -> Result<()> {
        let d = (q.x - self.p.x).hypot(q.y - self.p.y);
        if d < 1e-12 {
            return Ok(());
        }
        let mid = Point::new((q.x + self.p.x) / 2.0, (q.y + self.p.y) / 2.0);
        let c = self.world.clearance(q).0.min(self.world.clearance(mid).0);
        self.min_clearance = self.min_clearance.min(c);
        if c < self.r - 1e-9 {
            self.collisions += 1;
        }
        self.heading = (q.y - self.p.y).atan2(q.x - self.p.x);
        self.length += d;
        self.p = q;
        self.trace.push(TracePoint {
            x: q.x,
            y: q.y,
            state,
        });
        self.map.visit(q);
        self.scan();
        if self.length > self.max_length {
            return Err(Error::Internal(format!(
                "sensor-bcd: path longer than the limit of {} m",
                self.max_length
            )));
        }
        Ok(())
    }

    /// The boundary-following state for the nearest surface (border or obstacle).
    pub(crate) fn following_state(&self) -> State {
        match self.nearest {
            Some((_, 0)) => State::BorderFollowing,
            _ => State::ObstacleFollowing,
        }
    }

    /// Motion to boundary along `dir_y` (+1 up, −1 down); returns the contact.
    pub(crate) fn lap(&mut self, dir_y: f64) -> Result<Point> {
        loop {
            let near = self.near(self.keep + self.lap_step + 0.5);
            let mut free = f64::INFINITY;
            for h in &near {
                let along = (h.y - self.p.y) * dir_y;
                let lat = (h.x - self.p.x).abs();
                // A wall beside the lap, read short by noise, is not ahead.
                if along > 0.0 && lat < self.keep - self.beside {
                    free = free.min(along - (self.keep * self.keep - lat * lat).sqrt());
                }
            }
            if free <= 1e-4 {
                return Ok(self.p);
            }
            let s = free.min(self.lap_step);
            self.advance(
                Point::new(self.p.x, self.p.y + dir_y * s),
                State::MotionToBoundary,
            )?;
        }
    }

    /// The next boundary-following position with the boundary on the right
    /// (`turn` = +1) or on the left (`turn` = −1), or `None` when lost or
    /// boxed in. Where noise leaves no step that keeps `r + δ` from every
    /// sensed point (a gap within noise of the robot's width), the distance
    /// kept is relaxed in steps of one noise deviation, never below `r`
    /// plus a third of `δ`.
    pub(crate) fn follow_target(&self, turn: f64) -> Option<Point> {
        let near = self.near(self.keep + self.step + 0.15);
        let nearest = near.iter().min_by(|a, b| {
            let da = (a.x - self.p.x).powi(2) + (a.y - self.p.y).powi(2);
            let db = (b.x - self.p.x).powi(2) + (b.y - self.p.y).powi(2);
            da.total_cmp(&db)
        })?;
        let phi0 = (nearest.y - self.p.y).atan2(nearest.x - self.p.x);
        let steps = (TAU / TURN_STEP) as usize;
        let floor = self.r + (self.keep - self.r) / 3.0;
        let mut keep = self.keep;
        loop {
            let keep2 = keep * keep - 1e-12;
            let found = (0..steps).find_map(|k| {
                let phi = phi0 + turn * k as f64 * TURN_STEP;
                let q = Point::new(
                    self.p.x + self.step * phi.cos(),
                    self.p.y + self.step * phi.sin(),
                );
                near.iter()
                    .all(|h| (h.x - q.x).powi(2) + (h.y - q.y).powi(2) >= keep2)
                    .then_some(q)
            });
            if found.is_some() || self.noise_sd == 0.0 || keep <= floor {
                return found;
            }
            keep = (keep - self.noise_sd).max(floor);
        }
    }

    /// Fires the three-ray detector from the current position, the centre
    /// ray at the absolute heading `angle`.
    pub(crate) fn detect(&mut self, angle: f64) -> Option<crate::Returns> {
        let det = self.detector;
        det.fire(&mut self.probe, self.world, self.p, angle)
    }

    /// Whether a step to `q` keeps `r + δ` from every point sensed by the
    /// last few scans.
    pub(crate) fn clear_step(&self, q: Point) -> bool {
        let keep2 = self.keep * self.keep - 1e-12;
        self.near(self.keep + self.step + 0.15)
            .iter()
            .all(|h| (h.x - q.x).powi(2) + (h.y - q.y).powi(2) >= keep2)
    }

    /// The step length of boundary following (m).
    pub(crate) fn step(&self) -> f64 {
        self.step
    }

    /// Fires the three-ray detector from `robot` (a position the robot has
    /// passed), the centre ray at the absolute heading `angle`.
    pub(crate) fn detect_from(&mut self, robot: Point, angle: f64) -> Option<crate::Returns> {
        let det = self.detector;
        det.fire(&mut self.probe, self.world, robot, angle)
    }

    /// Travels along `route` (metre waypoints) in steps no longer than the
    /// lap step.
    pub(crate) fn travel(&mut self, route: &[Point]) -> Result<()> {
        for &q in route {
            loop {
                let d = (q.x - self.p.x).hypot(q.y - self.p.y);
                if d < 1e-9 {
                    break;
                }
                let s = d.min(self.lap_step) / d;
                let next = Point::new(
                    self.p.x + s * (q.x - self.p.x),
                    self.p.y + s * (q.y - self.p.y),
                );
                self.advance(next, State::Transit)?;
            }
        }
        Ok(())
    }
}
