//! `plan`, the `Plan` it returns, `evaluate` and `planners`: the library's
//! one plan pipeline ([`oxcover::pipeline`]), the same request and the same
//! path as `oxcover plan` with the same options.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::PyArray2;
use oxcover::grid::{DiscRobot, OccupancyGrid};
use oxcover::pipeline::{Outputs, PlanOutcome, PlanRequest, plan_pictures};
use oxcover::planners::{PlannerOptions, Start, TimeModel};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::convert::{bad, detached, error, path_argument, points_array, start_point, to_dict};
use crate::map::Map;
use crate::targets::targets_argument;

/// The memory budget argument: `"auto"` (3/4 of the machine's memory), `None`
/// or `"none"` (no limit), a size such as `"8G"`, or bytes.
pub(crate) enum MemoryLimit {
    Auto,
    Off,
    Bytes(u64),
}

impl<'a, 'py> FromPyObject<'a, 'py> for MemoryLimit {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if obj.is_none() {
            return Ok(MemoryLimit::Off);
        }
        if let Ok(text) = obj.extract::<String>() {
            return match text.as_str() {
                "auto" => Ok(MemoryLimit::Auto),
                "none" => Ok(MemoryLimit::Off),
                size => oxcover::memory::parse_size(size)
                    .map(MemoryLimit::Bytes)
                    .map_err(|e| error(&e)),
            };
        }
        match obj.extract::<u64>() {
            Ok(bytes) if bytes > 0 => Ok(MemoryLimit::Bytes(bytes)),
            _ => Err(bad(
                "memory_limit",
                obj.str().map_or_else(|_| "?".into(), |s| s.to_string()),
                "\"auto\", None, a size such as \"8G\", or a positive number of bytes",
            )),
        }
    }
}

impl MemoryLimit {
    fn bytes(&self) -> Option<u64> {
        match self {
            MemoryLimit::Auto => oxcover::memory::default_limit(),
            MemoryLimit::Off => None,
            MemoryLimit::Bytes(b) => Some(*b),
        }
    }
}

/// The robot, as the command line makes it: body radius (default 0) and
/// tool radius (default half a cell).
pub(crate) fn robot(
    map: &OccupancyGrid,
    robot_radius: f64,
    tool_radius: Option<f64>,
) -> PyResult<DiscRobot> {
    let tool = tool_radius.unwrap_or(map.resolution() / 2.0);
    DiscRobot::new(robot_radius, tool).map_err(|e| error(&e.into()))
}

/// The time model for `est_time_s` and the planners' choices.
pub(crate) fn time_model(speed: f64, turn_rate: f64) -> PyResult<TimeModel> {
    TimeModel::new(speed, turn_rate).map_err(|e| error(&e.into()))
}

/// A coverage plan: the path, its metrics, and what made it.
///
/// `path` is an N×2 float64 array of waypoints (x, y in metres, map frame),
/// read-only (take `.copy()` to change it). `to_csv()` is byte for byte the
/// file `oxcover plan --out` writes for the same request.
#[pyclass(frozen, module = "oxcover")]
pub(crate) struct Plan {
    pub(crate) map: Arc<OccupancyGrid>,
    pub(crate) map_name: String,
    pub(crate) request: PlanRequest,
    pub(crate) outcome: PlanOutcome,
    path: Py<PyArray2<f64>>,
}

impl Plan {
    /// The plan's picture in the format of `extension`, drawn with the GIL
    /// released.
    fn picture(&self, py: Python<'_>, extension: &str) -> PyResult<Vec<u8>> {
        detached(py, || {
            let file = format!("plan.{extension}");
            let mut drawn = plan_pictures(
                &self.map,
                &self.map_name,
                &self.request,
                &self.outcome,
                &[Path::new(&file)],
            )?;
            Ok(drawn.remove(0))
        })
    }
}

#[pymethods]
impl Plan {
    /// Waypoints: an N×2 float64 array (x, y in metres), read-only.
    #[getter]
    fn path(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        self.path.clone_ref(py)
    }

    /// The contract's metrics of the path (coverage, collisions, length_m,
    /// turns, est_time_s, bound_time_s, time_efficiency, …) as a dict.
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_dict(py, &self.outcome.evaluation.metrics)
    }

    /// Planning time in milliseconds (problem, rooms, planner, boundary pass),
    /// as `plan_ms` in the command line's report.
    #[getter]
    fn plan_ms(&self) -> f64 {
        self.outcome.plan_ms
    }

    /// The planner's name.
    #[getter]
    fn planner(&self) -> &'static str {
        self.request.planner.name()
    }

    /// Coverage of the planner's own path, before the boundary pass.
    #[getter]
    fn coverage_without_boundary_pass(&self) -> f64 {
        self.outcome.coverage_without_boundary_pass
    }

    /// Rooms planned one after another (None: the whole map at once).
    #[getter]
    fn room_units(&self) -> Option<usize> {
        self.outcome.room_units
    }

    /// The report `oxcover plan --report` writes (planner, parameters,
    /// plan_ms, boundary pass, rooms, metrics) as a dict.
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_dict(
            py,
            &self
                .outcome
                .report(&self.map, &self.map_name, &self.request),
        )
    }

    /// The path file (CSV, header `x,y`), as `oxcover plan --out` writes it.
    fn to_csv(&self) -> String {
        oxcover::path::to_csv(&self.outcome.points)
    }

    /// The picture `oxcover plan --png` draws (map, covered cells, path,
    /// the targets, metrics legend), as PNG bytes.
    fn to_png<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let bytes = self.picture(py, "png")?;
        Ok(PyBytes::new(py, &bytes))
    }

    /// The picture as SVG text.
    fn to_svg(&self, py: Python<'_>) -> PyResult<String> {
        let bytes = self.picture(py, "svg")?;
        String::from_utf8(bytes).map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Writes the path CSV, pictures and JSON report, as `oxcover plan
    /// --out/--svg/--png/--report` do: every path checked first (folder
    /// exists and is writable, name ends as the format needs, no file twice,
    /// not the map), then all files written whole or none. `bag` writes a
    /// ROS 2 bag (MCAP) as `--bag` does: /map, /coverage_path stamped by the
    /// time model, /rooms and /coverage_targets. Returns the paths written.
    #[pyo3(signature = (*, out = None, svg = None, png = None, report = None, bag = None))]
    fn write(
        &self,
        py: Python<'_>,
        out: Option<PathBuf>,
        svg: Option<PathBuf>,
        png: Option<PathBuf>,
        report: Option<PathBuf>,
        bag: Option<PathBuf>,
    ) -> PyResult<Vec<PathBuf>> {
        use oxcover::output::{ANY, MCAP, PNG, SVG, asked, check_outputs};
        detached(py, || {
            let outputs = asked([
                ("--out", out.as_deref(), ANY),
                ("--svg", svg.as_deref(), SVG),
                ("--png", png.as_deref(), PNG),
                ("--report", report.as_deref(), ANY),
                ("--bag", bag.as_deref(), MCAP),
            ]);
            let map_file = Path::new(&self.map_name);
            let inputs: Vec<&Path> = if map_file.is_file() {
                vec![map_file]
            } else {
                Vec::new()
            };
            check_outputs(&inputs, &outputs)?;
            oxcover::pipeline::write_outputs(
                &self.map,
                &self.map_name,
                &self.request,
                &self.outcome,
                &Outputs {
                    csv: out.as_deref(),
                    svg: svg.as_deref(),
                    png: png.as_deref(),
                    report: report.as_deref(),
                    bag: bag.as_deref(),
                },
            )
        })
    }

    fn __len__(&self) -> usize {
        self.outcome.points.len()
    }

    fn __repr__(&self) -> String {
        let m = &self.outcome.evaluation.metrics;
        format!(
            "Plan({} on {}: {} waypoints, coverage {:.4}, {} collisions, {:.1} m, est. {:.0} s)",
            self.request.planner.name(),
            self.map_name,
            self.outcome.points.len(),
            m.coverage,
            m.collisions,
            m.length_m,
            m.est_time_s
        )
    }
}

/// Every planner `plan` accepts: a list of dicts with `name`, `complete`
/// (whether it promises to cover every coverable cell) and `summary`.
#[pyfunction]
pub(crate) fn planners<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    oxcover::pipeline::planners()
        .into_iter()
        .map(|p| {
            let d = PyDict::new(py);
            d.set_item("name", p.name)?;
            d.set_item("complete", p.complete)?;
            d.set_item("summary", p.summary)?;
            Ok(d)
        })
        .collect()
}

/// Plans a coverage path on `map` with `planner` (see `planners()`).
///
/// The same pipeline, defaults and path as `oxcover plan MAP --planner
/// NAME`: `robot_radius` and `tool_radius` in metres (defaults 0 and half a
/// cell), `start` = (x, y) in metres (default: the first admissible cell),
/// `seed` for randomised planners, `boundary_pass` (cover what the planner
/// missed along obstacles), `rooms` (plan room by room where the map has
/// several), `speed` (m/s) and `turn_rate` (rad/s) for the estimated time
/// the planners minimise, `sweep_angle` (degrees) for the sweeping planners,
/// `memory_limit` ("auto" = 3/4 of the machine's memory, None = no limit, a
/// size such as "8G", or bytes). Coverage targets as the command line
/// takes them: `zones` and `keep_out` (GeoJSON files), `rooms_only` (room
/// labels) with `room_order` ("fastest" or "given"), `done` (a path file or
/// an N×2 array: resume, starting where it stopped unless `start` is
/// given), `spot` ((x, y, r) in metres), `clearance` (metres).
///
/// The GIL is released while planning. Raises ValueError with the command
/// line's message for a bad argument, an unknown planner, a start outside
/// the free space or a map above the memory limit.
#[pyfunction]
#[pyo3(
    signature = (map, planner, *, robot_radius = 0.0, tool_radius = None, start = None, seed = 0, boundary_pass = true, rooms = true, speed = 0.3, turn_rate = 0.52, sweep_angle = None, memory_limit = MemoryLimit::Auto, zones = None, keep_out = None, rooms_only = None, room_order = "fastest", done = None, spot = None, clearance = 0.0),
    text_signature = "(map, planner, *, robot_radius=0.0, tool_radius=None, start=None, seed=0, boundary_pass=True, rooms=True, speed=0.3, turn_rate=0.52, sweep_angle=None, memory_limit='auto', zones=None, keep_out=None, rooms_only=None, room_order='fastest', done=None, spot=None, clearance=0.0)"
)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn plan(
    py: Python<'_>,
    map: &Map,
    planner: &str,
    robot_radius: f64,
    tool_radius: Option<f64>,
    start: Option<(f64, f64)>,
    seed: u64,
    boundary_pass: bool,
    rooms: bool,
    speed: f64,
    turn_rate: f64,
    sweep_angle: Option<f64>,
    memory_limit: MemoryLimit,
    zones: Option<PathBuf>,
    keep_out: Option<PathBuf>,
    rooms_only: Option<Vec<u32>>,
    room_order: &str,
    done: Option<&Bound<'_, PyAny>>,
    spot: Option<(f64, f64, f64)>,
    clearance: f64,
) -> PyResult<Plan> {
    let grid = Arc::clone(&map.grid);
    let mut options = PlannerOptions::new();
    options.sweep_angle_deg = sweep_angle;
    let targets = targets_argument(zones, keep_out, rooms_only, room_order, done, spot)?;
    let robot = robot(&grid, robot_radius, tool_radius)?;
    // A resume starts where the done path stopped, as `oxcover plan` does.
    let start = match start_point(start)? {
        Some(p) => Start::At(p),
        None => match targets
            .default_start(&grid, robot.robot_radius + clearance.max(0.0))
            .map_err(|e| error(&e))?
        {
            Some((p, _)) => Start::At(p),
            None => Start::First,
        },
    };
    // The request `oxcover plan` makes of the same options.
    let request = PlanRequest {
        planner: oxcover::pipeline::planner(planner, &options).map_err(|e| error(&e))?,
        robot,
        start,
        seed,
        boundary_pass,
        rooms,
        time: time_model(speed, turn_rate)?,
        memory_limit: memory_limit.bytes(),
        targets,
        clearance,
    };
    request
        .check_memory(&grid, &map.name)
        .map_err(|e| error(&e))?;
    let outcome = detached(py, || oxcover::plan(&grid, &request))?;
    let path = points_array(py, &outcome.points)?.unbind();
    Ok(Plan {
        map: grid,
        map_name: map.name.clone(),
        request,
        outcome,
        path,
    })
}

/// Scores a path on `map` with the contract's metrics, as `oxcover eval`
/// prints them: `path` is a path file (CSV with header x,y) or an N×2
/// array-like of x, y in metres (a `Plan.path`, a list of pairs).
#[pyfunction]
#[pyo3(signature = (map, path, *, robot_radius = 0.0, tool_radius = None, speed = 0.3, turn_rate = 0.52, zones = None, keep_out = None, rooms_only = None, done = None, spot = None, clearance = 0.0))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate<'py>(
    py: Python<'py>,
    map: &Map,
    path: &Bound<'py, PyAny>,
    robot_radius: f64,
    tool_radius: Option<f64>,
    speed: f64,
    turn_rate: f64,
    zones: Option<PathBuf>,
    keep_out: Option<PathBuf>,
    rooms_only: Option<Vec<u32>>,
    done: Option<&Bound<'py, PyAny>>,
    spot: Option<(f64, f64, f64)>,
    clearance: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let grid = Arc::clone(&map.grid);
    let robot = robot(&grid, robot_radius, tool_radius)?;
    if !(clearance.is_finite() && clearance >= 0.0) {
        return Err(bad(
            "clearance",
            clearance,
            "a finite distance of at least 0 metres",
        ));
    }
    // Judged as `oxcover eval` judges: admissible at R + clearance.
    let robot = DiscRobot::new(robot.robot_radius + clearance, robot.tool_radius)
        .map_err(|e| error(&e.into()))?;
    let time = time_model(speed, turn_rate)?;
    let points = path_argument(path)?;
    let targets = targets_argument(zones, keep_out, rooms_only, "fastest", done, spot)?;
    let evaluation = detached(py, || {
        oxcover::targets::evaluate_targets(&grid, robot, &points, &time, &targets)
    })?;
    to_dict(py, &evaluation.metrics)
}
