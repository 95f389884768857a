//! # oxcover for Python
//!
//! The Python module `oxcover` (built with maturin; `pip install
//! ./crates/oxcover-py`): the library's one plan pipeline and its
//! companions, with numpy arrays in and out.
//!
//! - `map`: `load_map` (every format the command line reads) and
//!   `Map.from_array` (a bool free mask, or occupancy values in the ROS
//!   `nav_msgs/OccupancyGrid` convention), `Map.to_array`.
//! - `plan`: `plan` (the same pipeline and the same path as `oxcover plan`),
//!   the `Plan` it returns (path as an N×2 array, metrics, CSV, pictures,
//!   files written whole or not at all), `evaluate`, `planners`.
//! - `targets`: the coverage-target keywords of `plan` and `evaluate`
//!   (`zones`, `keep_out`, `rooms_only`, `room_order`, `done`, `spot`).
//! - `segment`: `segment`, rooms as a label array and the doors between them.
//! - `simulate`: `simulate`, a `Plan` executed in closed loop.
//! - `explore`: `explore`, the sensor-based planner on a polygonal world.
//!
//! Errors are Python exceptions carrying the command line's one-line message:
//! `OSError` for files that cannot be read or written, `ValueError` for bad
//! input, `RuntimeError` for an internal fault (a panic included: none
//! crosses into Python). Every call that plans or reads releases the GIL.

mod convert;
mod explore;
mod map;
mod plan;
mod segment;
mod simulate;
mod targets;

use pyo3::prelude::*;

/// The Python module `oxcover`.
#[pymodule]
#[pyo3(name = "oxcover")]
fn oxcover_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<map::Map>()?;
    m.add_class::<plan::Plan>()?;
    m.add_function(wrap_pyfunction!(map::load_map, m)?)?;
    m.add_function(wrap_pyfunction!(plan::planners, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(segment::segment, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(explore::explore, m)?)?;
    Ok(())
}
