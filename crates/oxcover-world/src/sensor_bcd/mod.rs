//! `sensor-bcd`: online coverage of an unknown polygonal world by a disc
//! robot with range rays, growing a boustrophedon (Morse) decomposition and
//! its Reeb graph as it covers (Demir 2018; Acar & Choset 2002).
//!
//! The robot knows nothing of the world but what its ring of rays returns
//! (seeded noise optional) and its own position (perfect odometry, as in the
//! seed). It sweeps along x: slices are the lines `x = x₀ + j·w` through the
//! start, `w` = the tool diameter (the lap spacing).
//!
//! **States** (the seed's state machine, Fig. 2): *motion to boundary* (a
//! lap along a slice, [`State::MotionToBoundary`]), *boundary following* on
//! the outer border or on an obstacle ([`State::BorderFollowing`],
//! [`State::ObstacleFollowing`]) and *transit* to the next piece of work.
//! Border and obstacle following are the same behaviour; the label, for
//! pictures only, is the surface the nearest ray hit.
//!
//! **Cells closed by cycles.** Acar & Choset's cycle algorithm covers a cell
//! with a forward lapping phase along one boundary and a return along the
//! other, so no critical point on either side is missed; Demir 2018 skipped it
//! and lost the space around concave obstacles and between stacked ones. We
//! apply the same idea to each slab between two neighbouring slices: the
//! robot goes once round the whole boundary of the slab's free component
//! (following the boundary inside the slab, lapping along the slices where it
//! meets them, see [`cycle`](self)), which
//!
//! - covers every lap interval the component touches on both slices,
//! - passes every point of its boundary with the detector running, so every
//!   critical point inside the slab is found, whatever the shape (concave
//!   pockets, obstacles stacked above each other, narrow gaps),
//! - tells which intervals of the two slices are joined through the slab:
//!   one on each side and no critical point means the same cell goes on,
//!   anything else ends cells at the critical points found.
//!
//! In an ordinary stretch this is the boustrophedon pattern plus one return
//! along the opposite boundary per lap: about `3w` of boundary per lap
//! instead of `w`.
//!
//! **Critical points** are the follower's turning points along x (the
//! boundary's normal parallel to the sweep), classified by Demir 2018's
//! three-ray test fired along x at the turning point
//! ([`crate::ThreeRayDetector`]); when the test does not give a
//! class that agrees with the follower about which way the boundary goes on,
//! the follower's own geometry classifies it and the point is marked
//! unconfirmed.
//!
//! **Incremental Reeb graph** ([`ReebGraph`]): nodes are the critical points,
//! edges the cells (chains of laps, and the short lap-less cells between
//! critical points closer in x than a lap spacing, read off the boundary the
//! robot traced round each slab). Every lap interval has two sides; a side
//! whose slab has not been traced is an open end of an uncovered edge. After
//! each cycle the robot travels, over its own map (what its rays saw free and
//! where it has been, never unknown space), to the nearest such open end,
//! and traces that slab. It stops when no open end is left.
//!
//! **The seed's own algorithm** ([`Algorithm::Paper`], module `paper`): the
//! same robot and primitives without the cycle algorithm and the Reeb graph,
//! as Demir 2018 publishes it, to show its documented failures.

mod body;
mod cycle;
mod paper;
mod reeb;
mod robot_map;

use crate::WorldGeometry;
use oxcover_grid::Point;
use serde::Serialize;

pub use cycle::Counters;
pub use reeb::{CellEdge, DetectedCritical, ReebGraph};

use crate::error::{Error, Result, positive};

/// What the robot was doing on the way to a trace point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum State {
    /// The start position.
    Start,
    /// A lap along a slice until the next contact.
    MotionToBoundary,
    /// Following the outer border.
    BorderFollowing,
    /// Following an obstacle.
    ObstacleFollowing,
    /// Travelling over explored space to the next open end.
    Transit,
}

impl State {
    /// Every state, in code order.
    pub const ALL: [Self; 5] = [
        Self::Start,
        Self::MotionToBoundary,
        Self::BorderFollowing,
        Self::ObstacleFollowing,
        Self::Transit,
    ];

    /// The number written in the `state` column of path files.
    #[must_use]
    pub fn code(self) -> u8 {
        self as u8
    }

    /// A short name.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Start => "start",
            Self::MotionToBoundary => "motion to boundary",
            Self::BorderFollowing => "border following",
            Self::ObstacleFollowing => "obstacle following",
            Self::Transit => "transit",
        }
    }
}

/// A position of the executed path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TracePoint {
    /// x (m).
    pub x: f64,
    /// y (m).
    pub y: f64,
    /// What led here.
    pub state: State,
}

/// Which algorithm explores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Algorithm {
    /// Ours: every slab closed by a cycle round its boundary, the Reeb graph
    /// from the boundary traced, the nearest open end next.
    #[default]
    Cycles,
    /// The seed's own (Demir 2018 as published): lapping without a cycle
    /// algorithm, back to the "previous node" when a lap stops short, graph
    /// edges from the last visited node (`paper` module).
    Paper,
}

impl Algorithm {
    /// Its name on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Cycles => "cycles",
            Algorithm::Paper => "paper",
        }
    }
}

/// The robot and the planner's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// The algorithm (default: ours, [`Algorithm::Cycles`]).
    pub algorithm: Algorithm,
    /// Body radius `r` (m).
    pub robot_radius: f64,
    /// Tool radius `T` (m); laps are `2T` apart.
    pub tool_radius: f64,
    /// Margin `δ` kept beyond the body from sensed boundaries (m).
    pub margin: f64,
    /// Rays in the ring.
    pub rays: usize,
    /// Longest range reading (m).
    pub max_range: f64,
    /// Standard deviation of the range noise (m).
    pub noise_sd: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// Boundary-following step (m).
    pub step: f64,
    /// Cell size of the robot's own map (m).
    pub map_resolution: f64,
    /// Path length at which the run is abandoned (m).
    pub max_length: f64,
}

impl Default for Config {
    /// A 0.2 m robot with a 0.25 m tool (laps 0.5 m apart), 4 cm margin,
    /// 180 rays of 3 m, no noise, 2 cm following steps, a 2.5 cm map.
    fn default() -> Self {
        Self {
            algorithm: Algorithm::Cycles,
            robot_radius: 0.2,
            tool_radius: 0.25,
            margin: 0.04,
            rays: 180,
            max_range: 3.0,
            noise_sd: 0.0,
            seed: 0,
            step: 0.02,
            map_resolution: 0.025,
            max_length: 100_000.0,
        }
    }
}

impl Config {
    /// The hysteresis along x of turning-point detection (m): four standard
    /// deviations of the range noise, at least 1 cm (the follower wavers by
    /// a few millimetres round corners even without noise). Features of the
    /// boundary shallower than this along x are not told from noise; compare
    /// with [`crate::World::critical_points`] at this tolerance.
    #[must_use]
    pub fn x_hysteresis(&self) -> f64 {
        (4.0 * self.noise_sd).max(0.01)
    }

    /// Checks every setting.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming the first bad one.
    pub fn check(&self) -> Result<()> {
        let bad = |name: &'static str, value: f64, expected: &'static str| {
            Err(Error::BadParameter {
                name,
                value: value.to_string(),
                expected,
            })
        };
        positive("robot radius", self.robot_radius)?;
        positive("tool radius", self.tool_radius)?;
        let keep = self.robot_radius + self.margin;
        if !(self.margin.is_finite() && self.margin >= 0.0 && self.margin < self.robot_radius) {
            return bad("margin", self.margin, "0 or more, below the robot radius");
        }
        if self.rays < 16 || self.rays > 100_000 {
            return bad("rays", self.rays as f64, "16 to 100000 rays");
        }
        if !(self.max_range.is_finite() && self.max_range >= 3.0 * keep) {
            return bad(
                "max range",
                self.max_range,
                "a finite range of at least 3 (robot radius + margin)",
            );
        }
        if !(self.noise_sd.is_finite() && self.noise_sd >= 0.0 && self.noise_sd <= keep / 10.0) {
            return bad(
                "range noise",
                self.noise_sd,
                "a standard deviation from 0 to a tenth of (robot radius + margin)",
            );
        }
        if !(positive("step", self.step).is_ok() && self.step <= keep / 4.0) {
            return bad(
                "step",
                self.step,
                "above 0 and at most a quarter of (robot radius + margin)",
            );
        }
        if !(positive("map resolution", self.map_resolution).is_ok()
            && self.map_resolution <= keep / 4.0)
        {
            return bad(
                "map resolution",
                self.map_resolution,
                "above 0 and at most a quarter of (robot radius + margin)",
            );
        }
        if positive("max length", self.max_length).is_err() {
            return bad("max length", self.max_length, "a finite length above 0");
        }
        Ok(())
    }
}

/// Most lanes (one tool width apart) across a world that [`explore`] takes on.
pub const MAX_LANES: f64 = 10_000.0;

/// The result of an exploration.
#[derive(Clone, Debug)]
pub struct Exploration {
    /// The executed path, every position with its state.
    pub trace: Vec<TracePoint>,
    /// The discovered Reeb graph.
    pub graph: ReebGraph,
    /// Counters.
    pub counters: Counters,
    /// Path length (m).
    pub length_m: f64,
    /// Moves that ended with the disc overlapping the world (must be 0).
    pub collisions: usize,
    /// Smallest exact distance from the path to the world's boundary (m).
    pub min_clearance: f64,
    /// Points the robot sensed as occupied (its map's occupied cells).
    pub sensed: Vec<Point>,
    /// Whether every slab side was traced (nothing left unreachable).
    pub complete: bool,
}

/// Explores `world` from `start` (m).
///
/// # Errors
/// [`Error::BadParameter`] for bad settings or a start the robot cannot
/// stand at; [`Error::Internal`] when the robot loses the boundary, a cycle
/// does not close or the path exceeds `max_length` (bugs, or a world the
/// method cannot handle).
pub fn explore(world: &WorldGeometry, start: Point, cfg: &Config) -> Result<Exploration> {
    cfg.check()?;
    if !(start.x.is_finite() && start.y.is_finite()) {
        return Err(Error::BadParameter {
            name: "start",
            value: format!("({}, {})", start.x, start.y),
            expected: "finite coordinates",
        });
    }
    // Lanes one tool width apart across the world: each costs ray casts
    // along its whole length, so a tool far narrower than the world would
    // run for hours. Refuse it up front.
    let lanes = world.world().width / (2.0 * cfg.tool_radius);
    if !lanes.is_finite() || lanes > MAX_LANES {
        return Err(Error::BadParameter {
            name: "tool radius",
            value: cfg.tool_radius.to_string(),
            expected: "at least the world's width / 20000 (at most 10000 lanes across it)",
        });
    }
    let (clear, _) = world.clearance(start);
    let keep = cfg.robot_radius + cfg.margin;
    if clear < keep {
        return Err(Error::BadParameter {
            name: "start",
            value: format!("({}, {})", start.x, start.y),
            expected: if clear < 0.0 {
                "a point in free space (this one is in an obstacle or outside the boundary)"
            } else {
                "a point at least robot radius + margin from every boundary"
            },
        });
    }
    let body = body::Body::new(world, cfg, start)?;
    let (body, graph, counters) = match cfg.algorithm {
        Algorithm::Cycles => {
            let mut explorer = cycle::Explorer::new(body, cfg);
            explorer.run()?;
            (explorer.body, explorer.reeb.graph(), explorer.counters)
        }
        Algorithm::Paper => {
            let mut explorer = paper::Paper::new(body, cfg);
            explorer.run()?;
            let graph = explorer.graph();
            (explorer.body, graph, explorer.counters)
        }
    };
    Ok(Exploration {
        complete: counters.unreached == 0,
        trace: body.trace,
        graph,
        counters,
        length_m: body.length,
        collisions: body.collisions,
        min_clearance: body.min_clearance,
        sensed: body.map.occupied_points(),
    })
}
