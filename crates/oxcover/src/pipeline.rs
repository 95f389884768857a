//! The plan pipeline, the one path from a map to written outputs that the
//! command line, the demo, every experiment and every bench share:
//!
//! 1. **problem**: the map, the robot and the start make a
//!    [`CoverageProblem`] (admissible, reachable and coverable cells; the
//!    coverage grid one tool diameter wide; the tool radius in cells);
//! 2. **plan**: the planner (a value from [`oxcover_planners::build`] or any
//!    [`Planner`]) plans on the problem's input; its plan becomes a fine,
//!    collision-free cell path (coverage plans are expanded) preceded by the
//!    lead-in from the start, then the boundary pass unless turned off, then
//!    metre waypoints;
//! 3. **evaluate**: the contract's metrics of the final path, and the
//!    coverage of the planner's own path before the boundary pass;
//! 4. **outputs**: the path CSV, pictures and JSON report ([`write_outputs`]).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use oxcover_decomp::{RoomParams, Rooms, voronoi};
use oxcover_grid::footprint::covered_cells;
use oxcover_grid::io::{MapFormat, ReadOptions, Thresholds, map_format, read_map};
use oxcover_grid::{
    Cell, Coverability, DiscRobot, Grid, MapFrame, OccupancyGrid, Point, components4,
};
use oxcover_planners::{
    ANY_UNIT, BoundaryRoute, CoverageProblem, PlanOutput, Planner, PlannerOptions, RoomUnits,
    Start, TimeModel, largest_region_cell, registry, room_order, unit_claims, unit_exits,
};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::metrics::{Evaluation, coverage_of, covered_fraction, evaluate_covered};
use crate::output::write_files;
use crate::path::{cells_to_points, to_csv};
use crate::render::{Scene, render_bytes};
use crate::report::{BoundaryStats, PlanParameters, PlanReport, metric_rows};

/// Reads the map at `path` in any format the command line reads (ROS yaml
/// with its image, PGM, PNG, BMP, MovingAI `.map`); `resolution` (m/cell)
/// places an image read without a yaml (default 1.0).
///
/// # Errors
/// A resolution that is not positive or above 1000 m/cell, naming
/// `--resolution`; an unreadable or malformed map, naming the file
/// ([`oxcover_grid::Error`]).
pub fn load_map(path: &Path, resolution: Option<f64>) -> Result<OccupancyGrid> {
    let reading = MapReading {
        resolution,
        ..MapReading::default()
    };
    Ok(load_map_with(path, &reading)?.0)
}

/// How to read an image that comes without a yaml: the command line's
/// `--resolution`, `--free-thresh`, `--occupied-thresh` and `--negate`.
///
/// A map_server yaml places and classifies its own image, and a MovingAI
/// map has neither; an image without one is read with the contract's
/// defaults (1.0 m/px, negate 0, occupied 0.65, free 0.196, trinary)
/// except where this says otherwise. A floor plan drawn to its own rule,
/// say only white free (grey above 250, as the ipa floor-plan benchmark
/// reads its plans), is read with `free_thresh: Some(5.0 / 255.0)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapReading {
    /// Metres per pixel [default 1.0].
    pub resolution: Option<f64>,
    /// A pixel is free when its occupancy `p` is below this [default 0.196].
    pub free_thresh: Option<f64>,
    /// A pixel is occupied when `p` is above this [default 0.65].
    pub occupied_thresh: Option<f64>,
    /// Dark means free: `p = v / 255` instead of `(255 - v) / 255`.
    pub negate: bool,
}

impl MapReading {
    /// Whether anything but the resolution is set.
    fn classifies(&self) -> bool {
        self.free_thresh.is_some() || self.occupied_thresh.is_some() || self.negate
    }

    /// The first classification option set, by its command-line name.
    fn first_classifying_option(&self) -> Option<(&'static str, String)> {
        if let Some(t) = self.free_thresh {
            Some(("--free-thresh", t.to_string()))
        } else if let Some(t) = self.occupied_thresh {
            Some(("--occupied-thresh", t.to_string()))
        } else if self.negate {
            Some(("--negate", "on".into()))
        } else {
            None
        }
    }

    /// The thresholds to read an image with, checked.
    fn thresholds(&self) -> Result<Thresholds> {
        let check = |name: &'static str, value: Option<f64>, default: f64| -> Result<f64> {
            match value {
                None => Ok(default),
                Some(t) if (0.0..=1.0).contains(&t) => Ok(t),
                Some(t) => Err(Error::BadParameter {
                    name,
                    value: t.to_string(),
                    expected: "a number in [0, 1] (an occupancy probability)".into(),
                }),
            }
        };
        let defaults = Thresholds::default();
        let free_thresh = check("--free-thresh", self.free_thresh, defaults.free_thresh)?;
        let occupied_thresh = check(
            "--occupied-thresh",
            self.occupied_thresh,
            defaults.occupied_thresh,
        )?;
        if free_thresh > occupied_thresh {
            let (name, value) = if self.free_thresh.is_some() {
                ("--free-thresh", free_thresh)
            } else {
                ("--occupied-thresh", occupied_thresh)
            };
            let default = match (self.free_thresh, self.occupied_thresh) {
                (Some(_), Some(_)) => "",
                _ => "; the one not given keeps its default",
            };
            return Err(Error::BadParameter {
                name,
                value: value.to_string(),
                expected: format!(
                    "--free-thresh ({free_thresh}) at most --occupied-thresh ({occupied_thresh}){default}"
                ),
            });
        }
        Ok(Thresholds {
            negate: self.negate,
            occupied_thresh,
            free_thresh,
            ..defaults
        })
    }
}

/// Reads the map at `path` as [`load_map`] does, an image without a yaml
/// classified by `reading`. Also returns notes for the command line: an
/// option the map does not use (`--resolution` on a yaml or a MovingAI map,
/// whose own resolution stands).
///
/// # Errors
/// As [`load_map`]; besides, a threshold outside [0, 1] or a free threshold
/// above the occupied one, and a classification option given for a map
/// that is not an image read without a yaml, each naming the option.
pub fn load_map_with(path: &Path, reading: &MapReading) -> Result<(OccupancyGrid, Vec<String>)> {
    let mut options = ReadOptions::default();
    if let Some(r) = reading.resolution {
        let r = oxcover_grid::error::positive("--resolution", r)?;
        if r > oxcover_grid::io::MAX_RESOLUTION {
            return Err(Error::BadParameter {
                name: "--resolution",
                value: r.to_string(),
                expected: "at most 1000 (metres per pixel)".into(),
            });
        }
        options = options.resolution(r);
    }
    options = options.thresholds(reading.thresholds()?);
    let format = if reading.resolution.is_some() || reading.classifies() {
        Some(map_format(path)?)
    } else {
        None
    };
    let what = match format {
        Some(MapFormat::RosYaml) => {
            Some("a map_server yaml, whose own fields place and classify its image")
        }
        Some(MapFormat::MovingAi) => Some("a MovingAI map (1 m per cell, `.`, `G`, `S` free)"),
        Some(MapFormat::Image) | None => None,
    };
    if let (Some(what), Some((name, value))) = (what, reading.first_classifying_option()) {
        return Err(Error::BadParameter {
            name,
            value,
            expected: format!("an image read without a yaml: {} is {what}", path.display()),
        });
    }
    let map = read_map(path, &options)?;
    let mut notes = Vec::new();
    if let (Some(what), Some(r)) = (what, reading.resolution) {
        notes.push(format!(
            "--resolution {r} is for images read without a yaml; {} is {what}, at {} m per cell",
            path.display(),
            map.resolution()
        ));
    }
    Ok((map, notes))
}

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
    /// Memory budget in bytes: [`plan`] refuses a map whose estimated need
    /// ([`crate::memory::estimate`]) is above it. Default
    /// [`crate::memory::default_limit`] (3/4 of the machine's memory);
    /// `None` plans whatever the size.
    pub memory_limit: Option<u64>,
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
    /// [`Error::MemoryLimit`] naming the map size, the estimate, the budget
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

    /// The same request with other speeds for estimated time.
    #[must_use]
    pub fn time(mut self, time: TimeModel) -> Self {
        self.time = time;
        self
    }

    /// The coverage problem this request poses on `map`.
    ///
    /// # Errors
    /// Bad radii or start ([`oxcover_grid::Error`]).
    pub fn problem(&self, map: &OccupancyGrid) -> Result<CoverageProblem> {
        Ok(CoverageProblem::new(map, self.robot, self.start)?.with_time(self.time))
    }
}

/// Where one room unit's work lies in a plan's waypoints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RoomStretch {
    /// The unit ([`room_units`] label).
    pub unit: u32,
    /// Its waypoints: `points[range]`, the transit into it excluded.
    pub points: std::ops::Range<usize>,
}

/// The result of [`plan`].
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
            metrics: self.evaluation.metrics.clone(),
        }
    }
}

/// Plans a coverage path on `map`.
///
/// Coverage and fine cell paths are expanded to collision-free fine paths;
/// a metre path is used as given after the lead-in from the start, so its
/// collisions are whatever the planner made (the metrics count them).
///
/// With [`PlanRequest::rooms`] on and more than one room unit on the map
/// ([`room_units`]), the planner plans each unit on its own
/// ([`CoverageProblem::restricted`]), the boundary pass runs per unit (the
/// straightened tour or the nearest-first pass, whichever has the lower
/// estimated time), and
/// the units are visited in the order of [`room_order`], joined by
/// straightened shortest transits ([`CoverageProblem::transit`]): every room
/// is finished before the robot leaves it. With rooms on (one unit or
/// more) the finished path is then tightened for time as a whole, each
/// unit's waypoints kept in their unit ([`CoverageProblem::tighten_within`]);
/// rooms off, the planner's path and the nearest-first pass stay as they are
/// (the papers' experiments).
///
/// # Errors
/// A map too large for [`PlanRequest::memory_limit`] ([`Error::MemoryLimit`]),
/// bad radii or start ([`oxcover_grid::Error`]), a planner's refusal
/// ([`oxcover_planners::Error::TooLarge`]) or an internal fault.
pub fn plan(map: &OccupancyGrid, request: &PlanRequest) -> Result<PlanOutcome> {
    request.check_memory(map, "map")?;
    let t0 = Instant::now();
    // The segmentation needs only the map: found while the problem is
    // built (same result whatever the thread count).
    let (problem, rooms) = rayon::join(
        || request.problem(map),
        || request.rooms.then(|| room_labels(map)),
    );
    let problem = problem?;
    // The plannable cells are one 4-connected region: all in one room,
    // they are one unit, planned whole (no units to find).
    let units = rooms
        .filter(|rooms| in_several_rooms(problem.plannable(), &rooms.labels))
        .map(|rooms| units_of(&problem, &rooms));
    match units.filter(|u| u.count() > 1) {
        Some(units) => plan_rooms(&problem, &units, request, t0),
        None => plan_whole(&problem, request, t0),
    }
}

/// Plannable area (m²) below which a room unit joins a neighbour: a
/// closet or a nook cut off by furniture is covered with the room beside
/// it (planned alone, its own loop, entry and exit cost more than it
/// saves: measured on the ipa floor plans, `docs/efficiency.md`).
pub const MIN_UNIT_M2: f64 = 6.0;

/// The room units of `problem` on `map`: the medial-axis segmentation of
/// the free cells with indoor defaults ([`oxcover_decomp::voronoi`],
/// [`RoomParams::indoor`]: rooms end at doors up to 1.6 m wide), split into
/// connected plannable parts, parts smaller than [`MIN_UNIT_M2`] of
/// plannable area (and at least four coverage cells) merged into a
/// neighbour.
///
/// Not the morphological segmentation: it also cuts open halls into pieces
/// of at most 47 m², and planning such pieces one by one took longer than
/// planning the hall at once on most ROS maps (`docs/efficiency.md`).
#[must_use]
pub fn room_units(map: &OccupancyGrid, problem: &CoverageProblem) -> RoomUnits {
    units_of(problem, &room_labels(map))
}

/// The rooms [`room_units`] splits: the medial-axis segmentation of `map`'s
/// free cells with indoor defaults.
fn room_labels(map: &OccupancyGrid) -> Rooms {
    voronoi(&map.free_mask(), &RoomParams::indoor(map.resolution()))
}

/// Whether the `plannable` cells carry more than one room label.
fn in_several_rooms(plannable: &Grid<bool>, labels: &Grid<u32>) -> bool {
    let mut seen = None;
    plannable
        .as_slice()
        .iter()
        .zip(labels.as_slice())
        .filter(|&(&p, _)| p)
        .any(|(_, &l)| *seen.get_or_insert(l) != l)
}

/// The units of `rooms` for `problem` (see [`room_units`]).
fn units_of(problem: &CoverageProblem, rooms: &Rooms) -> RoomUnits {
    let block = problem.block();
    let res = problem.frame().resolution();
    let min = ((MIN_UNIT_M2 / (res * res)) as usize).max(4 * block * block);
    RoomUnits::new(problem.plannable(), &rooms.labels, min)
}

/// One region's plan: the planner's path from the region's start (after
/// `prefix`), then its boundary pass.
struct RegionPlan {
    /// Fine cells (lead-in and plan; the pass's cells after them).
    cells: Vec<Cell>,
    /// `prefix`, then the plan's waypoints, before the boundary pass.
    raw: Vec<Point>,
    /// `raw`, then the boundary pass.
    points: Vec<Point>,
    /// The cells `raw` covers, where the boundary pass worked them out.
    raw_covered: Option<Grid<bool>>,
    boundary: Option<BoundaryRoute>,
    /// The plannable cell the region's path ends in.
    end: Cell,
}

fn plan_region(
    problem: &CoverageProblem,
    request: &PlanRequest,
    prefix: Vec<Point>,
    exit: Option<Cell>,
    plan_cells: Option<usize>,
) -> Result<RegionPlan> {
    let frame = problem.frame();
    let mut input = problem.input(request.seed);
    input.exit = exit;
    if let Some(n) = plan_cells {
        input.plan_cells = n;
    }
    let output = request.planner.plan(&input)?;
    let (planned, tail) = match &output {
        PlanOutput::Metres(points) => {
            let first = points.first().and_then(|p| frame.cell_at(p));
            (
                first.into_iter().collect::<Vec<_>>(),
                points.get(1..).unwrap_or_default().to_vec(),
            )
        }
        _ => (problem.expand(&output)?, Vec::new()),
    };
    let mut cells = problem.lead_in(planned.first().copied())?;
    cells.extend(planned.into_iter().skip(1));
    // A metre plan continues after the lead-in's cells; the boundary pass
    // then starts from the cell of its last point.
    let mut raw = prefix;
    raw.extend(cells_to_points(frame, &cells));
    raw.extend(tail);
    let last_cell = raw
        .last()
        .and_then(|p| frame.cell_at(p))
        .filter(|&c| problem.plannable()[c]);
    let end = last_cell
        .or_else(|| cells.last().copied())
        .unwrap_or(problem.start_cell());
    let mut points = raw.clone();
    // What the plan covers: found once, for the boundary pass (both its
    // routes) and the report's coverage before it.
    let raw_covered = request.boundary_pass.then(|| problem.covered_by(&raw));
    let boundary = if let Some(covered) = &raw_covered {
        // The pass starts from `end`'s centre; a metre plan may stop elsewhere
        // in that cell, so go to the centre first (a move inside one cell).
        let off_centre = raw.last() != Some(&frame.cell_center(end));
        // The points a route appends, as a tour (straightened metres) or as
        // the nearest-first pass (collinear cells merged, as every cell path
        // is written); and its cells.
        let appended = |route: &BoundaryRoute, tour: bool| {
            let mut extra = Vec::new();
            if off_centre && route.pending > 0 {
                extra.push(end);
            }
            extra.extend_from_slice(&route.cells);
            let pts = if tour {
                let mut v = Vec::new();
                if off_centre && route.pending > 0 {
                    v.push(frame.cell_center(end));
                }
                v.extend(route.points.iter().copied());
                v
            } else {
                cells_to_points(frame, &extra)
            };
            (pts, extra)
        };
        // Rooms on, the pass is a straightened tour ending towards the next
        // room or the nearest-first pass, whichever is faster once both are
        // tightened; rooms off keeps the nearest-first pass as it is (the
        // papers' experiments).
        let (route, whole, extra) = if request.rooms {
            // Independent: found in parallel (each works out what `raw`
            // leaves uncovered).
            let (tour, pass) = rayon::join(
                || problem.boundary_tour_to_covered(covered.clone(), end, exit),
                || problem.boundary_pass_covered(covered.clone(), end),
            );
            let (tour, pass) = (tour?, pass?);
            let (a, b) = (appended(&tour, true), appended(&pass, false));
            // Each tightened for time (as `lanes` tightens its path; the
            // two in parallel), then the faster kept, with the way on to the
            // next room where there is one.
            let tightened = |tail: &[Point]| {
                problem.tighten_from(&[points.as_slice(), tail].concat(), points.len())
            };
            let (ta, tb) = rayon::join(|| tightened(&a.0), || tightened(&b.0));
            let onward: Vec<Point> = exit.map(|c| frame.cell_center(c)).into_iter().collect();
            let time = |whole: &[Point]| {
                let from = points.len().saturating_sub(1);
                request
                    .time
                    .polyline(&[&whole[from.min(whole.len())..], onward.as_slice()].concat())
            };
            if time(&tb) < time(&ta) {
                (pass, tb, b.1)
            } else {
                (tour, ta, a.1)
            }
        } else {
            let pass = problem.boundary_pass_covered(covered.clone(), end)?;
            let (pts, extra) = appended(&pass, false);
            let mut whole = points.clone();
            whole.extend(pts);
            (pass, whole, extra)
        };
        points = whole;
        cells.extend(extra);
        Some(route)
    } else {
        None
    };
    // Where the region's path stops (the next transit starts there).
    let end = points
        .last()
        .and_then(|p| frame.cell_at(p))
        .filter(|&c| problem.plannable()[c])
        .or_else(|| cells.last().copied())
        .unwrap_or(end);
    Ok(RegionPlan {
        cells,
        raw,
        points,
        raw_covered,
        boundary,
        end,
    })
}

/// The start position when it is not its cell's centre (the path's first
/// waypoint then).
fn start_prefix(problem: &CoverageProblem) -> Vec<Point> {
    problem
        .start_point()
        .filter(|&s| problem.frame().cell_center(problem.start_cell()) != s)
        .into_iter()
        .collect()
}

/// Plans the whole problem at once.
fn plan_whole(
    problem: &CoverageProblem,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let region = plan_region(problem, request, start_prefix(problem), None, None)?;
    let in_pass = pass_flags(&region);
    let (points, _, covered, in_pass) = if request.rooms {
        tighten_plan(problem, None, region.points, Vec::new(), in_pass)
    } else {
        (region.points, Vec::new(), None, in_pass)
    };
    let boundary_length_m = pass_length(&points, &in_pass);
    // The final path's cells, if known: from the tightening's check, or
    // the plan's own where the path is the plan (nothing appended, moved).
    let covered = covered.or_else(|| {
        (points == region.raw)
            .then(|| region.raw_covered.clone())
            .flatten()
    });
    let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    let known = KnownCoverage {
        raws: region.raw_covered,
        path: covered,
    };
    finish(
        problem,
        request,
        points,
        region.cells,
        (&[region.raw], known),
        region.boundary,
        boundary_length_m,
        Vec::new(),
        plan_ms,
    )
}

/// Plans unit by unit in the order of [`room_order`].
fn plan_rooms(
    problem: &CoverageProblem,
    units: &RoomUnits,
    request: &PlanRequest,
    t0: Instant,
) -> Result<PlanOutcome> {
    let order = room_order(problem, units);
    let exits = unit_exits(problem, units, &order);
    let claims = unit_claims(problem, units);
    let plan_cells = problem.plannable().count_true();
    let mut points: Vec<Point> = Vec::new();
    let mut cells: Vec<Cell> = Vec::new();
    let mut raws = Vec::new();
    let mut boundary: Option<BoundaryRoute> = None;
    let mut in_pass: Vec<bool> = Vec::new();
    let mut here = problem.start_cell();
    let mut stretches = Vec::with_capacity(order.len());
    let mut wave = problem.transit_wavefront();
    for (i, &u) in order.iter().enumerate() {
        let (entry, prefix) = if i == 0 {
            (here, start_prefix(problem))
        } else {
            let t = problem.transit_reusing(&mut wave, here, |c| units.labels[c] == u)?;
            let entry = t.cells.last().copied().unwrap_or(here);
            cells.extend(t.cells.iter().skip(1).copied());
            let mut prefix = t.points;
            prefix.pop();
            (entry, prefix)
        };
        let prefix_len = prefix.len();
        let claimed = claims.map(|&l| l == u || l == ANY_UNIT);
        let sub = problem.restricted_claiming(&units.mask(u), entry, Some(&claimed))?;
        let exit = exits[i].and_then(|c| sub.from_map_cell(c));
        let mut region = plan_region(&sub, request, prefix, exit, Some(plan_cells))?;
        for c in &mut region.cells {
            *c = sub.to_map_cell(*c);
        }
        region.end = sub.to_map_cell(region.end);
        for (p, pass) in region.points.iter().zip(pass_flags(&region)) {
            if points.last() != Some(p) {
                points.push(*p);
                in_pass.push(pass);
            }
        }
        // The unit's own work: the last points, after its transit.
        let work = region.points.len() - prefix_len.min(region.points.len());
        stretches.push(RoomStretch {
            unit: u,
            points: points.len().saturating_sub(work)..points.len(),
        });
        cells.extend(region.cells.iter().skip(usize::from(i > 0)).copied());
        raws.push(region.raw);
        if let Some(b) = region.boundary {
            let total = boundary.get_or_insert(BoundaryRoute {
                cells: Vec::new(),
                points: Vec::new(),
                pending: 0,
                anchors: 0,
            });
            total.pending += b.pending;
            total.anchors += b.anchors;
            total.cells.extend(b.cells);
            total.points.extend(b.points);
        }
        here = region.end;
    }
    let (points, stretches, covered, in_pass) =
        tighten_plan(problem, Some(units), points, stretches, in_pass);
    let boundary_length_m = pass_length(&points, &in_pass);
    let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    // Each room's own coverage is on its room's grid: the map's is found
    // afresh.
    let known = KnownCoverage {
        raws: None,
        path: covered,
    };
    finish(
        problem,
        request,
        points,
        cells,
        (&raws, known),
        boundary,
        boundary_length_m,
        stretches,
        plan_ms,
    )
}

/// A finished plan (rooms on) tightened for time as a whole, as `lanes`
/// tightens its own path ([`CoverageProblem::tighten_within`]): the
/// planner's waypoints, the transits and the boundary passes together, so
/// that what a transit or the next room already covers is not driven
/// twice and every junction between them is straightened. Each room's
/// waypoints stay in their room (`units`); `stretches` are renumbered for
/// the waypoints kept. Should rounding leave a cell the plan covered
/// uncovered, the plan is returned as it was.
fn tighten_plan(
    problem: &CoverageProblem,
    units: Option<&RoomUnits>,
    points: Vec<Point>,
    stretches: Vec<RoomStretch>,
    in_pass: Vec<bool>,
) -> (Vec<Point>, Vec<RoomStretch>, Option<Grid<bool>>, Vec<bool>) {
    let mut of_vertex = vec![0u32; points.len()];
    for s in &stretches {
        for z in &mut of_vertex[s.points.clone()] {
            *z = s.unit;
        }
    }
    let zones = units.map(|u| (&u.labels, of_vertex.as_slice()));
    let (tight, kept) = problem.tighten_within(&points, 0, zones);
    if tight == points {
        return (points, stretches, None, in_pass);
    }
    let reached = problem.covered_by(&tight);
    let tool = problem.robot().tool_radius;
    let (frame, coverable) = (problem.frame(), &problem.cells().coverable);
    if loses_coverage(frame, coverable, tool, &points, &reached) {
        return (points, stretches, None, in_pass);
    }
    let in_pass = kept.iter().map(|&k| in_pass[k]).collect();
    let at = |i: usize| kept.partition_point(|&k| k < i);
    let stretches = stretches
        .into_iter()
        .map(|s| RoomStretch {
            unit: s.unit,
            points: at(s.points.start)..at(s.points.end),
        })
        .collect();
    (tight, stretches, Some(reached), in_pass)
}

/// Which of a region's waypoints its boundary pass added: those after its
/// planner's own path (`raw`, which `points` begins with).
fn pass_flags(region: &RegionPlan) -> Vec<bool> {
    let own = region.raw.len().min(region.points.len());
    (0..region.points.len()).map(|i| i >= own).collect()
}

/// The length of the segments of `points` that end at a waypoint the
/// boundary pass added (`in_pass`, one flag per waypoint): the pass's
/// share of the path, the way to its first waypoint included.
fn pass_length(points: &[Point], in_pass: &[bool]) -> f64 {
    points
        .windows(2)
        .zip(in_pass.iter().skip(1))
        .filter(|(_, pass)| **pass)
        // From +0.0: an empty `sum` of floats is -0.0.
        .fold(0.0, |total, (w, _)| total + (w[1] - w[0]).norm())
}

/// Whether a path that covers the cells `reached` leaves a coverable cell
/// uncovered that the path `before` covered (a tool of `tool` metres, the
/// metrics' own coverage, [`covered_cells`]). `before`'s cells are only
/// worked out where `reached` misses a coverable cell: a complete plan
/// costs one coverage test, not two.
fn loses_coverage(
    frame: &MapFrame,
    coverable: &Grid<bool>,
    tool: f64,
    before: &[Point],
    reached: &Grid<bool>,
) -> bool {
    let missed: Vec<Cell> = coverable.true_cells().filter(|&c| !reached[c]).collect();
    if missed.is_empty() {
        return false;
    }
    let was = covered_cells(frame, before, tool);
    missed.into_iter().any(|c| was[c])
}

/// Coverage a plan has worked out on the way, each `None` where it has not
/// (then [`finish`] finds it).
struct KnownCoverage {
    /// The cells all the planners' paths cover before the boundary pass,
    /// on the map's grid.
    raws: Option<Grid<bool>>,
    /// The cells the final path covers.
    path: Option<Grid<bool>>,
}

/// Scores a finished plan.
#[allow(clippy::too_many_arguments)]
fn finish(
    problem: &CoverageProblem,
    request: &PlanRequest,
    points: Vec<Point>,
    cells: Vec<Cell>,
    (raws, known): (&[Vec<Point>], KnownCoverage),
    boundary: Option<BoundaryRoute>,
    boundary_length_m: f64,
    room_stretches: Vec<RoomStretch>,
    plan_ms: f64,
) -> Result<PlanOutcome> {
    let frame = problem.frame();
    // The two coverages, where not known yet, side by side.
    let (coverage_without_boundary_pass, covered) = rayon::join(
        || match &known.raws {
            Some(g) => covered_fraction(problem.cells(), g),
            None => coverage_of(frame, problem.cells(), raws),
        },
        || known.path.unwrap_or_else(|| problem.covered_by(&points)),
    );
    let evaluation = evaluate_covered(
        frame,
        problem.cells().clone(),
        &points,
        covered,
        &request.time,
    );
    Ok(PlanOutcome {
        points,
        cells,
        evaluation,
        coverage_without_boundary_pass,
        boundary,
        boundary_length_m,
        room_units: (!room_stretches.is_empty()).then_some(room_stretches.len()),
        room_stretches,
        coarse_block: problem.block(),
        plan_ms,
    })
}

/// Where to write a plan's outputs (each optional).
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    /// Path file (CSV, header `x,y`).
    pub csv: Option<&'a Path>,
    /// SVG picture.
    pub svg: Option<&'a Path>,
    /// PNG picture.
    pub png: Option<&'a Path>,
    /// JSON report.
    pub report: Option<&'a Path>,
}

/// The picture of a plan of `request` on `map` (named `map_name`), as
/// `plan --svg/--png` draws it: the map, the covered cells, the path and a
/// legend of its metrics.
#[must_use]
pub fn plan_scene<'a>(
    map: &'a OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &'a PlanOutcome,
) -> Scene<'a> {
    let ev = &outcome.evaluation;
    Scene {
        map,
        path: &outcome.points,
        planned: None,
        covered: Some(&ev.covered),
        coverable: Some(&ev.problem.coverable),
        title: format!("{} - {}", short_name(map_name), request.planner.name()),
        overlay: None,
        regions: None,
        rows: metric_rows(&ev.metrics),
    }
}

/// Writes the CSV, pictures and report of a plan of `request` on `map`
/// (named `map_name`), all of them or none ([`crate::output::write_files`]);
/// returns the files written.
///
/// # Errors
/// [`Error::Write`] naming the file that could not be written (then none
/// is); a bad picture extension.
pub fn write_outputs(
    map: &OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &PlanOutcome,
    out: &Outputs<'_>,
) -> Result<Vec<PathBuf>> {
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = out.csv {
        files.push((p.to_path_buf(), to_csv(&outcome.points).into_bytes()));
    }
    let scene = plan_scene(map, map_name, request, outcome);
    for p in [out.svg, out.png].into_iter().flatten() {
        files.push((p.to_path_buf(), render_bytes(&scene, p)?));
    }
    if let Some(p) = out.report {
        let report = outcome.report(map, map_name, request);
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        files.push((p.to_path_buf(), (json + "\n").into_bytes()));
    }
    write_files(files)
}

/// Hints about what a plan leaves out: free cells it cannot cover, and a
/// default start stranded in a small component (common in SLAM maps, whose
/// first free cell is often a speck of noise).
pub fn coverage_notes(
    map: &OccupancyGrid,
    problem: &Coverability,
    default_start: bool,
) -> Vec<String> {
    let mut notes = Vec::new();
    let free = map.counts().free;
    let coverable = problem.coverable_count();
    if coverable < free {
        notes.push(format!(
            "{} of {free} free cells are not coverable (not reachable from the start, or too close to obstacles for this robot and tool) and are not counted",
            free - coverable
        ));
    }
    let comps = components4(&problem.admissible);
    let mine = comps.labels[problem.start];
    if let Some(big) = comps.largest() {
        let (ours, theirs) = (
            comps.sizes[mine as usize - 1],
            comps.sizes[big as usize - 1],
        );
        if big != mine && theirs > 2 * ours {
            if let Some(cell) = largest_region_cell(&problem.admissible) {
                let p = map.frame().cell_center(cell);
                let how = if default_start {
                    "the default start (first admissible cell)"
                } else {
                    "the start"
                };
                notes.push(format!(
                    "{how} lies in a region of {ours} admissible cells; the largest has {theirs}: try --start {},{}",
                    metres(p.x),
                    metres(p.y)
                ));
            }
        }
    }
    notes
}

/// A coordinate in metres for people to read and type back (`--start`):
/// at most six decimals, trailing zeros dropped.
#[must_use]
pub fn metres(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

/// The file name of a path, for titles.
#[must_use]
pub fn short_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::random::rectangles;
    use oxcover_planners::PlannerInput;

    /// One label under every plannable cell (whatever the others carry) is
    /// one room; a second label is several.
    #[test]
    fn several_rooms_need_two_labels_under_the_plannable_cells() {
        let plannable = Grid::from_fn(4, 2, |c| c.col < 3);
        let mut labels = Grid::from_fn(4, 2, |c| if c.col < 3 { 2 } else { 5 });
        assert!(!in_several_rooms(&plannable, &labels));
        labels[Cell::new(1, 2)] = 0;
        assert!(in_several_rooms(&plannable, &labels));
        assert!(!in_several_rooms(&Grid::new(4, 2, false), &labels));
    }

    #[test]
    fn unknown_planner_lists_the_known_ones() {
        let e = planner("nope", &PlannerOptions::new())
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.contains("--planner is `nope`") && e.contains("grid-cover"),
            "{e}"
        );
    }

    /// A planner that returns a metre path: the start's centre, then a point
    /// half a cell to its east.
    struct Metric;

    impl Planner for Metric {
        fn name(&self) -> &'static str {
            "metric"
        }
        fn complete(&self) -> bool {
            false
        }
        fn summary(&self) -> &'static str {
            "test"
        }
        fn plan(&self, input: &PlannerInput<'_>) -> oxcover_planners::Result<PlanOutput> {
            let rep = input.coarse.representative(input.start).unwrap_or_default();
            let p = input.frame.cell_center(rep);
            Ok(PlanOutput::Metres(vec![p, Point::new(p.x + 0.5, p.y)]))
        }
    }

    #[test]
    fn metre_plans_pass_through_and_get_the_boundary_pass() {
        let (map, _) = oxcover_grid::io::parse_ascii("....\n....").unwrap();
        let req = PlanRequest::with_planner(Arc::new(Metric), 1.0);
        let out = plan(&map, &req.clone().rooms(false)).unwrap();
        assert_eq!(out.points[0], Point::new(0.5, 1.5));
        assert_eq!(out.points[1], Point::new(1.0, 1.5));
        let m = &out.evaluation.metrics;
        assert_eq!((m.coverage, m.collisions), (1.0, 0));
        assert!(out.coverage_without_boundary_pass < 1.0);
        // Rooms on, the whole path is tightened afterwards: from the same
        // start, as complete, never slower.
        let on = plan(&map, &req).unwrap();
        assert_eq!(on.points[0], out.points[0]);
        let n = &on.evaluation.metrics;
        assert_eq!((n.coverage, n.collisions), (1.0, 0));
        assert!(n.est_time_s <= m.est_time_s + 1e-9);
        // The pass's length: every segment but those ending at the
        // planner's own waypoint (the half cell east of the start). Rooms
        // on, that is measured on the tightened path, which here drops the
        // planner's waypoint: the pass is the whole of it.
        let own = |points: &[Point]| -> f64 {
            points
                .windows(2)
                .filter(|w| w[1] == Point::new(1.0, 1.5))
                .map(|w| (w[1] - w[0]).norm())
                .sum()
        };
        assert!((out.boundary_length_m - (m.length_m - own(&out.points))).abs() < 1e-9);
        assert!((own(&out.points) - 0.5).abs() < 1e-9);
        assert!((on.boundary_length_m - (n.length_m - own(&on.points))).abs() < 1e-9);
    }

    #[test]
    fn a_tightening_that_uncovers_a_cell_is_caught() {
        // A 1 × 6 corridor, tool radius 0.5 (a cell's centre within half a
        // cell of the path, as sampled, is covered).
        let (map, _) = oxcover_grid::io::parse_ascii("......").unwrap();
        let frame = map.frame();
        let coverable = Grid::new(6, 1, true);
        let along = |x0: f64, x1: f64| vec![Point::new(x0, 0.5), Point::new(x1, 0.5)];
        let whole = along(0.5, 5.5);
        let loses_coverage = |frame, coverable, tool, before: &[Point], after: &[Point]| {
            loses_coverage(
                frame,
                coverable,
                tool,
                before,
                &covered_cells(frame, after, tool),
            )
        };
        // Nothing lost: the same cells, or a path that covers them all.
        assert!(!loses_coverage(frame, &coverable, 0.5, &whole, &whole));
        assert!(!loses_coverage(
            frame,
            &coverable,
            0.5,
            &along(1.5, 5.5),
            &whole
        ));
        // The last cell dropped, which `before` covered.
        assert!(loses_coverage(
            frame,
            &coverable,
            0.5,
            &whole,
            &along(0.5, 4.5)
        ));
        // A cell `before` missed too is not a loss.
        assert!(!loses_coverage(
            frame,
            &coverable,
            0.5,
            &along(0.5, 4.5),
            &along(0.5, 4.5)
        ));
        assert!(loses_coverage(
            frame,
            &coverable,
            0.5,
            &along(0.5, 4.5),
            &along(0.5, 3.5)
        ));
    }

    #[test]
    fn wide_tool_plan_is_complete_and_collision_free() {
        let base = rectangles(80, 60, 6, 12, 11);
        let map = OccupancyGrid::new(base.cells().clone(), 0.05, Point::new(-1.0, 2.0));
        let req = PlanRequest::new("dtc", 0.05)
            .unwrap()
            .robot(DiscRobot::new(0.15, 0.15).unwrap());
        let out = plan(&map, &req).unwrap();
        let m = &out.evaluation.metrics;
        assert_eq!(m.collisions, 0);
        assert_eq!(m.coverage, 1.0);
        assert!(out.coverage_without_boundary_pass < 1.0);
        assert_eq!(out.coarse_block, 6);
        // The planner's own coverage (rooms off: no tightening after it).
        let off = req.rooms(false);
        let out = plan(&map, &off).unwrap();
        let raw = plan(&map, &off.boundary_pass(false)).unwrap();
        assert_eq!(
            raw.evaluation.metrics.coverage,
            out.coverage_without_boundary_pass
        );
    }
}
