//! `simulate`: a plan executed by a simulated differential-drive robot, as
//! `oxcover simulate` runs it.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use oxcover::closed_loop::{ClosedLoop, ControllerKind, FLOOR_CLEANER, execute};
use oxcover::robot::{Limits, RobotSpec};
use oxcover::{Error, plan};
use pyo3::prelude::*;

use crate::convert::{bad, detached, error, points_array, to_dict};
use crate::map::Map;
use crate::plan::{MemoryLimit, request};

/// The columns of `samples`, as in `oxcover simulate --out`.
const COLUMNS: [&str; 7] = ["x", "y", "theta", "t", "v", "omega", "energy"];

/// Plans as `plan` does, then executes the plan with a simulated
/// differential-drive robot (time law, tracking controller, wheel limits,
/// odometry noise) and scores the executed trajectory, as `oxcover simulate`.
///
/// `robot_spec` is a robot description file (RON, see fixtures/robots;
/// default: the bundled floor cleaner), `controller` "klancar" or
/// "kanayama", `dt` the control step in seconds, `odometry_noise` the
/// relative wheel-speed error per step (standard deviation; seeded by
/// `seed`).
///
/// Returns a dict: `samples` (an N×7 float64 array with the columns in
/// `columns`: x, y, theta, t, v, omega, energy), `planned` (the plan's N×2
/// waypoints), `metrics` (of the executed trajectory), `report` (as
/// `oxcover simulate --report` writes it) and `warning` (None, or why the run
/// stopped short of the path's end).
#[pyfunction]
#[pyo3(
    signature = (map, planner, *, robot_radius = 0.0, tool_radius = None, start = None, seed = 0, boundary_pass = true, rooms = true, speed = 0.3, turn_rate = 0.52, sweep_angle = None, memory_limit = MemoryLimit::Auto, robot_spec = None, controller = "klancar", dt = 0.02, odometry_noise = 0.0),
    text_signature = "(map, planner, *, robot_radius=0.0, tool_radius=None, start=None, seed=0, boundary_pass=True, rooms=True, speed=0.3, turn_rate=0.52, sweep_angle=None, memory_limit='auto', robot_spec=None, controller='klancar', dt=0.02, odometry_noise=0.0)"
)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn simulate<'py>(
    py: Python<'py>,
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
    robot_spec: Option<PathBuf>,
    controller: &str,
    dt: f64,
    odometry_noise: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let controller = match controller {
        "klancar" => ControllerKind::Klancar,
        "kanayama" => ControllerKind::Kanayama,
        other => return Err(bad("controller", other, "`klancar` or `kanayama`")),
    };
    let spec_text = match &robot_spec {
        Some(f) => {
            let f = f.clone();
            detached(py, move || {
                oxcover::grid::io::limited::read_limited_string(
                    &f,
                    oxcover::grid::io::limited::MAX_TEXT_BYTES,
                )
                .map_err(|e| Error::Read { path: f, source: e })
            })?
        }
        None => FLOOR_CLEANER.to_string(),
    };
    let spec = RobotSpec::from_ron(&spec_text).map_err(|e| {
        error(&Error::BadParameter {
            name: "--robot-spec",
            value: robot_spec
                .as_ref()
                .map_or_else(|| "bundled".into(), |f| f.display().to_string()),
            expected: format!("a valid robot description ({e})"),
        })
    })?;
    let request = request(
        map,
        planner,
        robot_radius,
        tool_radius,
        start,
        seed,
        boundary_pass,
        rooms,
        speed,
        turn_rate,
        sweep_angle,
        &memory_limit,
    )?;
    let grid = Arc::clone(&map.grid);
    let cfg = ClosedLoop {
        spec,
        controller,
        limits: Limits::default(),
        dt,
        odometry_noise,
        seed,
    };
    let (outcome, run) = detached(py, || {
        let outcome = plan(&grid, &request)?;
        let run = execute(&grid, request.robot, &outcome.points, &cfg)?;
        Ok((outcome, run))
    })?;
    let planned_coverage = outcome.evaluation.metrics.coverage;
    let flat: Vec<f64> = run
        .samples
        .iter()
        .flat_map(|s| {
            [
                s.pose.x,
                s.pose.y,
                s.pose.theta,
                s.t,
                s.v,
                s.omega,
                s.energy,
            ]
        })
        .collect();
    let samples = Array2::from_shape_vec((run.samples.len(), COLUMNS.len()), flat)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal error: {e}")))?
        .into_pyarray(py);
    let out = pyo3::types::PyDict::new(py);
    out.set_item("samples", samples)?;
    out.set_item("columns", COLUMNS.to_vec())?;
    out.set_item("planned", points_array(py, &outcome.points)?)?;
    out.set_item("metrics", to_dict(py, &run.evaluation.metrics)?)?;
    out.set_item(
        "report",
        to_dict(
            py,
            &run.report(request.planner.name(), &cfg, planned_coverage),
        )?,
    )?;
    out.set_item(
        "warning",
        run.cut_short(planned_coverage, request.robot.tool_radius),
    )?;
    Ok(out.into_any())
}
