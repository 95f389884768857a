//! `explore`: the sensor-based planner `sensor-bcd` covering an unknown
//! polygonal world, as `oxcover explore` runs it.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::IntoPyArray;
use oxcover::explore::explore_world;
use oxcover::grid::Point;
use oxcover::world::World;
use oxcover::world::sensor_bcd::{Algorithm, Config};
use pyo3::prelude::*;

use crate::convert::{bad, detached, points_array, start_point, to_dict};
use crate::map::Map;

/// Covers the polygonal world in `world` (a RON file, see fixtures/worlds)
/// with the sensor-based planner `sensor-bcd`, which senses it with range
/// rays as it goes, as `oxcover explore WORLD.ron` does.
///
/// `robot_radius` and `tool_radius` in metres (laps are two tool radii
/// apart), `margin` the distance kept from sensed boundaries beyond the body,
/// `rays` in the sensor ring, `max_range` in metres, `noise` the range
/// noise's standard deviation (seeded by `seed`), `start` = (x, y) (default:
/// the world file's start), `algorithm` "cycles" (ours: every slab closed
/// by a cycle, the Reeb graph from what was traced) or "paper" (Demir 2018 as
/// published: no cycle algorithm, graph edges from the last visited node).
///
/// Returns a dict: `path` (the executed N×2 waypoints), `states` (a uint8
/// array, each waypoint's state code: 0 start, 1 motion to boundary, 2 border
/// following, 3 obstacle following, 4 transit), `graph` (the discovered Reeb
/// graph), `metrics` (scored on the world's raster), `report` (as `oxcover
/// explore --report` writes it) and `map` (the world's raster as a `Map`).
#[pyfunction]
#[pyo3(signature = (world, *, robot_radius = 0.2, tool_radius = 0.25, margin = 0.04, rays = 180, max_range = 3.0, noise = 0.0, seed = 0, start = None, algorithm = "cycles"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore<'py>(
    py: Python<'py>,
    world: PathBuf,
    robot_radius: f64,
    tool_radius: f64,
    margin: f64,
    rays: usize,
    max_range: f64,
    noise: f64,
    seed: u64,
    start: Option<(f64, f64)>,
    algorithm: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let start = start_point(start)?;
    let algorithm = match algorithm {
        "cycles" => Algorithm::Cycles,
        "paper" => Algorithm::Paper,
        other => return Err(bad("algorithm", other, "`cycles` or `paper`")),
    };
    let cfg = Config {
        algorithm,
        robot_radius,
        tool_radius,
        margin,
        rays,
        max_range,
        noise_sd: noise,
        seed,
        ..Config::default()
    };
    let file = world.clone();
    let (world, outcome) = detached(py, || {
        let world = World::read(&file)?;
        let outcome = explore_world(&world, &cfg, start)?;
        Ok((world, outcome))
    })?;
    let e = &outcome.exploration;
    let path: Vec<Point> = e.trace.iter().map(|t| Point::new(t.x, t.y)).collect();
    let states: Vec<u8> = e.trace.iter().map(|t| t.state.code()).collect();
    let out = pyo3::types::PyDict::new(py);
    out.set_item("path", points_array(py, &path)?)?;
    out.set_item("states", states.into_pyarray(py))?;
    out.set_item("graph", to_dict(py, &e.graph)?)?;
    out.set_item("metrics", to_dict(py, &outcome.evaluation.metrics)?)?;
    out.set_item("report", to_dict(py, &outcome.report(&world, &cfg))?)?;
    let map = Map {
        grid: Arc::new(outcome.map.clone()),
        name: world.name.clone(),
    };
    out.set_item("map", Py::new(py, map)?)?;
    Ok(out.into_any())
}
