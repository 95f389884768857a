//! `simulate`: a `Plan` executed by a simulated differential-drive robot, as
//! `oxcover simulate` runs it after planning.

use std::path::PathBuf;

use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use oxcover::Error;
use oxcover::closed_loop::{ClosedLoop, ControllerKind, FLOOR_CLEANER, execute_plan};
use oxcover::robot::{Limits, RobotSpec};
use pyo3::prelude::*;

use crate::convert::{bad, detached, error, read_only, to_dict};
use crate::plan::Plan;

/// The columns of `samples`, as in `oxcover simulate --out`.
const COLUMNS: [&str; 7] = ["x", "y", "theta", "t", "v", "omega", "energy"];

/// Executes `plan` with a simulated differential-drive robot (time law,
/// tracking controller, wheel limits, odometry noise) and scores the
/// executed trajectory, as `oxcover simulate` does after planning
/// (`oxcover simulate` plans with the robot's tracking margin plus half a
/// cell as `clearance`: give `plan` the same to get its run).
///
/// `robot_spec` is a robot description file (RON, see fixtures/robots;
/// default: the bundled floor cleaner), `controller` "klancar" or
/// "kanayama", `dt` the control step in seconds, `odometry_noise` the
/// relative wheel-speed error per step (standard deviation), drawn from the
/// plan's seed as the command line does.
///
/// Returns a dict: `samples` (an N×7 float64 array with the columns in
/// `columns`: x, y, theta, t, v, omega, energy), `metrics` (of the executed
/// trajectory), `report` (as `oxcover simulate --report` writes it) and
/// `warning` (None, or why the run stopped short of the path's end).
#[pyfunction]
#[pyo3(signature = (plan, *, robot_spec = None, controller = "klancar", dt = 0.02, odometry_noise = 0.0))]
pub(crate) fn simulate<'py>(
    py: Python<'py>,
    plan: &Plan,
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
    let request = &plan.request;
    let cfg = ClosedLoop {
        spec,
        controller,
        limits: Limits::default(),
        dt,
        odometry_noise,
        seed: request.seed,
    };
    let run = detached(py, || execute_plan(&plan.map, request, &plan.outcome, &cfg))?;
    let planned_coverage = plan.outcome.evaluation.metrics.coverage;
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
    read_only(samples.as_any())?;
    let out = pyo3::types::PyDict::new(py);
    out.set_item("samples", samples)?;
    out.set_item("columns", COLUMNS.to_vec())?;
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
