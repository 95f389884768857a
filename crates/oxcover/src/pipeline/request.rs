//! What to plan ([`PlanRequest`]: planner, robot, start, speeds, memory
//! budget), the planners on offer, and what planning gives back
//! ([`PlanOutcome`]) with its report.

use std::sync::Arc;

use oxcover_grid::{Cell, DiscRobot, OccupancyGrid, Point};
use oxcover_planners::{
    BoundaryRoute, CoverageProblem, Planner, PlannerOptions, Start, TimeModel, registry,
};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::metrics::Evaluation;
use crate::report::{BoundaryStats, PlanParameters, PlanReport, metric_rows};
use crate::targets::{TargetSummary, Targets};

/// A registered planner, as `oxcover planners` lists it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PlannerInfo {
    /// Name used on the command line.
    pub name: &'static str,
    /// Whether it promises to cover every coverage cell.
    pub complete: bool,
    /// One-line description with its source.
    pub summary: &'static str,
}

/// Every planner `plan --planner` accepts.
#[must_use]
pub fn planners() -> Vec<PlannerInfo> {
    registry()
        .map(|p| PlannerInfo {
            name: p.name(),
            complete: p.complete(),
            summary: p.summary(),
        })
        .collect()
}

/// The planner `name` with `options`, for the command line.
///
/// # Errors
/// [`Error::BadParameter`] naming `--planner` and listing the known names
/// (the sensor-based planner is not among them: it runs on worlds, through
/// `oxcover explore`); an option the planner does not take ([`oxcover_planners::Error::OptionNotTaken`]).
pub fn planner(name: &str, options: &PlannerOptions) -> Result<Arc<dyn Planner>> {
    oxcover_planners::build(name, options).map_err(|e| match e {
        oxcover_planners::Error::UnknownPlanner(_) if name == "sensor-bcd" => Error::BadParameter {
            name: "--planner",
            value: name.to_string(),
            expected: "a grid planner: sensor-bcd covers unknown worlds it senses, run it with `oxcover explore WORLD.ron`".into(),
        },
        oxcover_planners::Error::UnknownPlanner(_) => Error::BadParameter {
            name: "--planner",
            value: name.to_string(),
            expected: format!(
                "one of: {} (sensor-bcd runs with `oxcover explore`)",
                registry().map(|p| p.name()).collect::<Vec<_>>().join(", ")
            ),
        },
        other => other.into(),
    })
}

/// What to plan: the planner (with its options), the robot, the start, the
/// seed and whether the boundary pass runs.
#[derive(Clone)]
pub struct PlanRequest {
    /// The planner, options included.
    pub planner: Arc<dyn Planner>,
    /// Robot and tool.
    pub robot: DiscRobot,
    /// Where the robot starts (default: the contract's first admissible cell).
    pub start: Start,
    /// Seed for randomised planners (recorded for all).
    pub seed: u64,
    /// Append the boundary pass. Default on.
    pub boundary_pass: bool,
    /// Plan room by room where the map has more than one room, and make
    /// each room's boundary pass a tour or nearest-first pass tightened for
    /// time (on a map of one room too). Default on; the papers' grid
    /// experiments turn it off (map-wide plan, nearest-first pass as is).
    pub rooms: bool,
    /// Speeds for estimated time, the planners' objective and the metrics'
    /// `est_time_s` (default: the contract's 0.3 m/s and 0.52 rad/s).
    pub time: TimeModel,
    /// Memory budget in bytes: [`super::plan`] refuses a map whose estimated need
    /// ([`crate::memory::estimate`]) is above it. Default
    /// [`crate::memory::default_limit`] (3/4 of the machine's memory);
    /// `None` plans whatever the size.
    pub memory_limit: Option<u64>,
    /// What to cover and what never to enter (default: every coverable
    /// cell, nothing blocked).
    pub targets: Targets,
    /// Metres the path keeps from non-free cells beyond the robot radius
    /// (the contract's `--clearance`; default 0): admissible means at
    /// least `robot_radius + clearance` from them.
    pub clearance: f64,
}

impl std::fmt::Debug for PlanRequest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlanRequest")
            .field("planner", &self.planner.name())
            .field("options", &self.planner.options())
            .field("robot", &self.robot)
            .field("start", &self.start)
            .field("seed", &self.seed)
            .field("boundary_pass", &self.boundary_pass)
            .field("rooms", &self.rooms)
            .field("time", &self.time)
            .field("memory_limit", &self.memory_limit)
            .field("targets", &self.targets)
            .field("clearance", &self.clearance)
            .finish()
    }
}

impl PlanRequest {
    /// A request for the registered planner `name` with its default options
    /// and the contract's defaults for a map of `resolution` (robot radius 0,
    /// tool radius half a cell, first admissible cell, seed 0, boundary pass
    /// on, rooms on, the contract's speeds).
    ///
    /// # Errors
    /// As [`planner`].
    pub fn new(name: &str, resolution: f64) -> Result<Self> {
        Ok(Self::with_planner(
            planner(name, &PlannerOptions::new())?,
            resolution,
        ))
    }

    /// A request for any planner value, with the contract's defaults.
    #[must_use]
    pub fn with_planner(planner: Arc<dyn Planner>, resolution: f64) -> Self {
        Self {
            planner,
            robot: DiscRobot::cell_sized(resolution),
            start: Start::First,
            seed: 0,
            boundary_pass: true,
            rooms: true,
            time: TimeModel::default(),
            memory_limit: crate::memory::default_limit(),
            targets: Targets::default(),
            clearance: 0.0,
        }
    }

    /// The same request with another memory budget (`None`: no limit).
    #[must_use]
    pub fn memory_limit(mut self, bytes: Option<u64>) -> Self {
        self.memory_limit = bytes;
        self
    }

    /// Refuses a map this request could not plan within its memory budget,
    /// before anything large is allocated.
    ///
    /// # Errors
    /// [`crate::Error::MemoryLimit`] naming the map size, the estimate, the budget
    /// and what helps.
    pub fn check_memory(&self, map: &OccupancyGrid, map_name: &str) -> Result<()> {
        let Some(limit) = self.memory_limit else {
            return Ok(());
        };
        let (w, h) = (map.width() as u64, map.height() as u64);
        let block = oxcover_planners::coarse_block(&self.robot, map.resolution()) as u64;
        let coverage = w.div_ceil(block) * h.div_ceil(block);
        let name = self.planner.name();
        let need = crate::memory::estimate(name, self.rooms, w * h, coverage);
        if need <= limit {
            return Ok(());
        }
        let show = crate::memory::show;
        let mut helps = Vec::new();
        if self.rooms {
            helps.push("--rooms off");
        }
        helps.extend([
            "a larger --tool-radius",
            "the map image scaled down",
            "a higher --memory-limit if the machine has the memory",
        ]);
        Err(Error::MemoryLimit(format!(
            "{map_name}: planning {w}x{h} cells with {name} (rooms {}) needs about {}, above the memory limit of {} (what helps: {})",
            if self.rooms { "on" } else { "off" },
            show(need),
            show(limit),
            helps.join(", ")
        )))
    }

    /// The same request for another robot and tool.
    #[must_use]
    pub fn robot(mut self, robot: DiscRobot) -> Self {
        self.robot = robot;
        self
    }

    /// The same request from another start.
    #[must_use]
    pub fn start(mut self, start: Start) -> Self {
        self.start = start;
        self
    }

    /// The same request with the boundary pass on or off.
    #[must_use]
    pub fn boundary_pass(mut self, on: bool) -> Self {
        self.boundary_pass = on;
        self
    }

    /// The same request planning room by room (on) or the whole map at once (off).
    #[must_use]
    pub fn rooms(mut self, on: bool) -> Self {
        self.rooms = on;
        self
    }

    /// The same request keeping `metres` more from walls than the robot
    /// radius requires.
    #[must_use]
    pub fn clearance(mut self, metres: f64) -> Self {
        self.clearance = metres;
        self
    }

    /// The robot as planning sees it: the body radius grown by the
    /// clearance.
    ///
    /// # Errors
    /// A clearance that is negative or not finite.
    pub fn planning_robot(&self) -> Result<DiscRobot> {
        let m = self.clearance;
        if !(m.is_finite() && m >= 0.0) {
            return Err(Error::BadParameter {
                name: "--clearance",
                value: m.to_string(),
                expected: "a finite distance of at least 0 metres".into(),
            });
        }
        Ok(DiscRobot::new(
            self.robot.robot_radius + m,
            self.robot.tool_radius,
        )?)
    }

    /// The same request with coverage targets.
    #[must_use]
    pub fn targets(mut self, targets: Targets) -> Self {
        self.targets = targets;
        self
    }

    /// The same request with other speeds for estimated time.
    #[must_use]
    pub fn time(mut self, time: TimeModel) -> Self {
        self.time = time;
        self
    }

    /// The coverage problem this request poses on `map` (for the robot
    /// grown by the clearance, [`Self::planning_robot`]).
    ///
    /// # Errors
    /// Bad radii, clearance or start ([`oxcover_grid::Error`]).
    pub fn problem(&self, map: &OccupancyGrid) -> Result<CoverageProblem> {
        self.problem_within(map, None)
    }

    /// [`PlanRequest::problem`] with coverable cells only inside `within`
    /// ([`CoverageProblem::new_within`]).
    ///
    /// # Errors
    /// As [`PlanRequest::problem`].
    pub fn problem_within(
        &self,
        map: &OccupancyGrid,
        within: Option<oxcover_grid::Window>,
    ) -> Result<CoverageProblem> {
        let robot = self.planning_robot()?;
        Ok(CoverageProblem::new_within(map, robot, self.start, within)?.with_time(self.time))
    }
}

/// Where one room unit's work lies in a plan's waypoints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RoomStretch {
    /// The unit ([`super::room_units`] label).
    pub unit: u32,
    /// Its waypoints: `points[range]`, the transit into it excluded.
    pub points: std::ops::Range<usize>,
}

/// The result of [`super::plan`].
#[derive(Clone, Debug)]
pub struct PlanOutcome {
    /// Metre waypoints (the path file).
    pub points: Vec<Point>,
    /// The fine cell path behind them (for a metre plan: its lead-in and the
    /// boundary pass only; with rooms on, the boundary pass's cells before
    /// its waypoints were tightened).
    pub cells: Vec<Cell>,
    /// Scores of the final path.
    pub evaluation: Evaluation,
    /// Coverage of the planner's own path, before the boundary pass.
    pub coverage_without_boundary_pass: f64,
    /// What the boundary pass did, if it ran (summed over room units).
    pub boundary: Option<BoundaryRoute>,
    /// Length of the path the boundary pass added (m; the segments that end
    /// at one of its waypoints, after the whole path's last tightening
    /// where there is one).
    pub boundary_length_m: f64,
    /// Room units planned one after another, when the plan went room by
    /// room (`None`: the whole map at once).
    pub room_units: Option<usize>,
    /// Each room unit's own stretch of `points`, in the order driven (after
    /// the transit into it; empty when the whole map was planned at once).
    pub room_stretches: Vec<RoomStretch>,
    /// Fine cells per coverage-cell side.
    pub coarse_block: usize,
    /// Planning time in milliseconds (problem, rooms, planner, boundary pass).
    pub plan_ms: f64,
    /// The coverage target's cells, when targets were given.
    pub targets: Option<TargetSummary>,
    /// Notes on the targets for the user (a zone clipped to the map).
    pub notes: Vec<String>,
    /// Cells coverable without the clearance that it puts out of the
    /// tool's reach (`None` without a clearance).
    pub clearance_lost_cells: Option<usize>,
}

impl PlanOutcome {
    /// The rows of a plan for tables and legends: its metrics with the
    /// coverage before the boundary pass second.
    #[must_use]
    pub fn rows(&self) -> Vec<(String, String)> {
        let mut rows = metric_rows(&self.evaluation.metrics);
        rows.insert(
            1,
            (
                "coverage (no boundary pass)".into(),
                format!("{:.4}", self.coverage_without_boundary_pass),
            ),
        );
        if let Some(n) = self.clearance_lost_cells {
            rows.push(("out of reach (clearance)".into(), n.to_string()));
        }
        if let Some(t) = &self.targets {
            rows.extend([
                ("required cells".into(), t.required_cells.to_string()),
                (
                    "required area".into(),
                    format!("{:.2} m2", t.required_area_m2),
                ),
                ("done cells".into(), t.done_cells.to_string()),
                ("keep-out cells".into(), t.blocked_cells.to_string()),
            ]);
        }
        rows
    }

    /// The `plan --report` object of this plan of `request` on `map`
    /// (named `map_name`).
    #[must_use]
    pub fn report(&self, map: &OccupancyGrid, map_name: &str, request: &PlanRequest) -> PlanReport {
        let start = self.points.first().copied().unwrap_or_else(Point::origin);
        let parameters = PlanParameters {
            map: map_name.to_string(),
            robot_radius: request.robot.robot_radius,
            tool_radius: request.robot.tool_radius,
            resolution: map.resolution(),
            start: [start.x, start.y],
            seed: request.seed,
            boundary_pass: request.boundary_pass,
            rooms: request.rooms,
            speed: request.time.linear_speed,
            turn_rate: request.time.angular_speed,
            sweep_angle_deg: request.planner.options().sweep_angle_deg,
            coverage_cell_m: self.coarse_block as f64 * map.resolution(),
        };
        PlanReport {
            planner: request.planner.name().to_string(),
            parameters,
            plan_ms: self.plan_ms,
            coverage_without_boundary_pass: self.coverage_without_boundary_pass,
            boundary: self.boundary.as_ref().map(|b| BoundaryStats {
                pending_cells: b.pending,
                anchors: b.anchors,
                appended_cells: b.cells.len(),
                length_m: self.boundary_length_m,
                length_share: if self.evaluation.metrics.length_m > 0.0 {
                    self.boundary_length_m / self.evaluation.metrics.length_m
                } else {
                    0.0
                },
            }),
            room_units: self.room_units,
            targets: self.targets,
            metrics: self.evaluation.metrics.clone(),
        }
    }
}
