//! Between Rust and Python: errors, released-GIL calls, JSON values,
//! waypoint arrays.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use oxcover::Error;
use oxcover::grid::Point;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::{IntoPyObjectExt, PyErr};

/// The exception for `e`, with the command line's one-line message (without
/// its `oxcover: error: ` prefix): `OSError` for a file that cannot be read
/// or written, `RuntimeError` for an internal fault (exit status 1 on the
/// command line), `ValueError` for every other bad input (exit status 2).
pub(crate) fn error(e: &Error) -> PyErr {
    let message = e.to_string().replace('\n', " ");
    let io = matches!(
        e,
        Error::Read { .. }
            | Error::Write { .. }
            | Error::Map(oxcover::grid::Error::Io { .. } | oxcover::grid::Error::Write { .. })
    ) || matches!(
        e,
        Error::World(oxcover::world::Error::World { message, .. })
            if message.starts_with("cannot read it")
    );
    if io {
        PyOSError::new_err(message)
    } else if e.exit_code() == 1 {
        PyRuntimeError::new_err(message)
    } else {
        PyValueError::new_err(message)
    }
}

/// Runs `f` with the GIL released (other Python threads run meanwhile);
/// its error becomes the exception [`error`] names, a panic a
/// `RuntimeError` (`internal error: …`, as the command line reports it).
pub(crate) fn detached<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> oxcover::Result<T> + Send,
) -> PyResult<T> {
    match py.detach(|| catch_unwind(AssertUnwindSafe(f))) {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(e)) => Err(error(&e)),
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("a panic");
            Err(PyRuntimeError::new_err(format!("internal error: {what}")))
        }
    }
}

/// A `ValueError` naming the argument, its value and what is accepted, worded
/// as the command line's [`Error::BadParameter`].
pub(crate) fn bad(name: &str, value: impl std::fmt::Display, expected: &str) -> PyErr {
    PyValueError::new_err(format!("{name} is `{value}`, expected {expected}"))
}

/// A JSON value as the Python object `json.loads` would make of it.
pub(crate) fn json<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    match v {
        Value::Null => Ok(py.None().into_bound(py)),
        Value::Bool(b) => b.into_bound_py_any(py),
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_bound_py_any(py)
            } else if let Some(u) = n.as_u64() {
                u.into_bound_py_any(py)
            } else {
                n.as_f64().unwrap_or(f64::NAN).into_bound_py_any(py)
            }
        }
        Value::String(s) => s.into_bound_py_any(py),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json(py, item)?)?;
            }
            Ok(list.into_any())
        }
        Value::Object(fields) => {
            let dict = PyDict::new(py);
            for (k, item) in fields {
                dict.set_item(k, json(py, item)?)?;
            }
            Ok(dict.into_any())
        }
    }
}

/// Any serialisable value (a report, metrics) as a Python dict.
pub(crate) fn to_dict<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: serialisation: {e}")))?;
    json(py, &v)
}

/// Waypoints as a read-only N×2 float64 array: the coordinates are moved
/// into the array's buffer, no Python object per point.
pub(crate) fn points_array<'py>(
    py: Python<'py>,
    points: &[Point],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    let array = Array2::from_shape_vec((points.len(), 2), flat)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?
        .into_pyarray(py);
    read_only(array.as_any())?;
    Ok(array)
}

/// Marks a numpy array read-only (`array.flags.writeable = False`).
pub(crate) fn read_only(array: &Bound<'_, PyAny>) -> PyResult<()> {
    let kwargs = PyDict::new(array.py());
    kwargs.set_item("write", false)?;
    array.call_method("setflags", (), Some(&kwargs))?;
    Ok(())
}

/// Waypoints from a path argument: a file name (`str` or `os.PathLike`, a
/// CSV path file as `oxcover eval` reads it) or an array-like of shape N×2
/// (x, y in metres).
pub(crate) fn path_argument(path: &Bound<'_, PyAny>) -> PyResult<Vec<Point>> {
    let py = path.py();
    if let Ok(file) = path.extract::<PathBuf>() {
        return detached(py, move || oxcover::read_csv(&file));
    }
    let numpy = py.import("numpy")?;
    let array = numpy
        .call_method1("asarray", (path, "float64"))
        .map_err(|_| {
            bad(
                "path",
                "given",
                "a file name or an N×2 array of x, y in metres",
            )
        })?;
    let array: PyReadonlyArray2<'_, f64> = array.extract().map_err(|_| {
        bad(
            "path",
            "an array of other shape",
            "a file name or an N×2 array of x, y in metres",
        )
    })?;
    let shape = array.shape();
    if shape[1] != 2 {
        return Err(bad(
            "path",
            format!("an array of shape {}×{}", shape[0], shape[1]),
            "an N×2 array of x, y in metres",
        ));
    }
    let view = array.as_array();
    let mut points = Vec::with_capacity(shape[0]);
    for (i, row) in view.outer_iter().enumerate() {
        let (x, y) = (row[0], row[1]);
        if !(x.is_finite() && y.is_finite()) {
            return Err(bad(
                "path",
                format!("{x},{y} in row {i}"),
                "finite x, y in metres",
            ));
        }
        points.push(Point::new(x, y));
    }
    Ok(points)
}

/// A start position from `(x, y)`.
pub(crate) fn start_point(start: Option<(f64, f64)>) -> PyResult<Option<Point>> {
    match start {
        Some((x, y)) if !(x.is_finite() && y.is_finite()) => {
            Err(bad("start", format!("({x}, {y})"), "finite x, y in metres"))
        }
        Some((x, y)) => Ok(Some(Point::new(x, y))),
        None => Ok(None),
    }
}
