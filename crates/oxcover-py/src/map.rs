//! `Map`: an occupancy grid placed in the map frame; `load_map`,
//! `Map.from_array`, `Map.to_array`.
//!
//! Arrays are indexed `[row, column]`. By default (`rows="up"`) row 0 is the
//! row at the map origin and rows go up the map's y axis, as in ROS
//! `nav_msgs/OccupancyGrid` (`np.asarray(msg.data).reshape(h, w)`);
//! `rows="down"` takes row 0 as the top row, as an image is stored.

use oxcover::rosbag::MessageChoice;
use std::path::PathBuf;
use std::sync::Arc;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use oxcover::OccupancyGrid;
use oxcover::grid::{Cell, Grid, Occupancy, Point};
use pyo3::prelude::*;

use crate::convert::{bad, detached};

/// An occupancy grid placed in the map frame (metres, ROS conventions: the
/// origin is the lower-left corner of the bottom-left cell, optionally
/// rotated by a yaw). Unknown cells are never free.
///
/// Make one with `oxcover.load_map(path)` or `Map.from_array(array,
/// resolution, origin)`.
#[pyclass(frozen, module = "oxcover")]
pub(crate) struct Map {
    pub(crate) grid: Arc<OccupancyGrid>,
    /// The file it was read from, or `<array>`: reports and titles name it.
    pub(crate) name: String,
}

/// Where row 0 of an array lies.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Rows {
    /// At the origin, rows going up (nav_msgs/OccupancyGrid).
    Up,
    /// At the top (images).
    Down,
}

pub(crate) fn rows_of(rows: &str) -> PyResult<Rows> {
    match rows {
        "up" => Ok(Rows::Up),
        "down" => Ok(Rows::Down),
        other => Err(bad(
            "rows",
            other,
            "`up` (row 0 at the origin, as nav_msgs/OccupancyGrid) or `down` (row 0 at the top, as images)",
        )),
    }
}

/// The grid cell of array row `i` in a map of `height` rows.
pub(crate) fn grid_row(rows: Rows, i: usize, height: usize) -> usize {
    match rows {
        Rows::Up => height - 1 - i,
        Rows::Down => i,
    }
}

/// Occupancy from a value in percent (ROS: −1 unknown, 0..100), by
/// map_server's thresholds: occupied above `occupied`, free below `free`,
/// unknown between.
fn occupancy(value: i64, unknown: i64, free: f64, occupied: f64) -> Option<Occupancy> {
    if value == unknown || value == -1 {
        return Some(Occupancy::Unknown);
    }
    if !(0..=100).contains(&value) {
        return None;
    }
    let p = value as f64 / 100.0;
    Some(if p > occupied {
        Occupancy::Occupied
    } else if p < free {
        Occupancy::Free
    } else {
        Occupancy::Unknown
    })
}

/// The cells of an integer occupancy array.
fn from_values<T>(
    array: &Bound<'_, PyUntypedArray>,
    rows: Rows,
    unknown: i64,
    free: f64,
    occupied: f64,
) -> PyResult<Grid<Occupancy>>
where
    T: numpy::Element + Copy + Into<i64>,
{
    let array: PyReadonlyArray2<'_, T> = array.extract()?;
    let view = array.as_array();
    let (h, w) = view.dim();
    let mut cells = Grid::new(w, h, Occupancy::Unknown);
    for ((i, j), &v) in view.indexed_iter() {
        let v: i64 = v.into();
        let o = occupancy(v, unknown, free, occupied).ok_or_else(|| {
            bad(
                "array",
                format!("{v} at row {i}, column {j}"),
                "-1 (unknown) or an occupancy in percent, 0..100 (nav_msgs/OccupancyGrid)",
            )
        })?;
        cells[Cell::new(grid_row(rows, i, h), j)] = o;
    }
    Ok(cells)
}

/// The cells of a bool free mask.
fn from_mask(array: &Bound<'_, PyUntypedArray>, rows: Rows) -> PyResult<Grid<Occupancy>> {
    let array: PyReadonlyArray2<'_, bool> = array.extract()?;
    let view = array.as_array();
    let (h, w) = view.dim();
    let mut cells = Grid::new(w, h, Occupancy::Occupied);
    for ((i, j), &free) in view.indexed_iter() {
        if free {
            cells[Cell::new(grid_row(rows, i, h), j)] = Occupancy::Free;
        }
    }
    Ok(cells)
}

#[pymethods]
impl Map {
    /// A map from a 2-D numpy array placed at `origin` = (x, y, yaw) with
    /// `resolution` metres per cell.
    ///
    /// The array is a bool free mask (True = free, False = occupied), or
    /// integer occupancy in the ROS nav_msgs/OccupancyGrid convention: -1
    /// unknown (255 in a uint8 array), 0..100 occupancy in percent; a value
    /// above `occupied_thresh` (as a fraction) is occupied, below
    /// `free_thresh` free, between them unknown (map_server's defaults).
    /// Row 0 is at the origin and rows go up the y axis (`rows="up"`, as
    /// `np.asarray(msg.data, np.int8).reshape(msg.info.height,
    /// msg.info.width)`); `rows="down"` takes row 0 as the top row (images).
    /// The array is copied.
    ///
    /// Raises ValueError naming what is wrong: an array that is not 2-D or
    /// is empty, a dtype other than bool or integer, a value outside -1..100,
    /// a resolution that is not positive, an origin that is not finite.
    #[staticmethod]
    #[pyo3(signature = (array, resolution, origin = (0.0, 0.0, 0.0), *, rows = "up", free_thresh = 0.196, occupied_thresh = 0.65))]
    fn from_array(
        array: &Bound<'_, PyAny>,
        resolution: f64,
        origin: (f64, f64, f64),
        rows: &str,
        free_thresh: f64,
        occupied_thresh: f64,
    ) -> PyResult<Self> {
        let rows = rows_of(rows)?;
        let array = array
            .cast::<PyUntypedArray>()
            .map_err(|_| bad("array", "not a numpy array", "a 2-D numpy array"))?;
        if array.ndim() != 2 {
            return Err(bad(
                "array",
                format!("{}-dimensional", array.ndim()),
                "a 2-D numpy array (rows, columns)",
            ));
        }
        let (h, w) = (array.shape()[0], array.shape()[1]);
        if h == 0 || w == 0 {
            return Err(bad("array", format!("{h}×{w}"), "at least one cell"));
        }
        if h.saturating_mul(w) > oxcover::grid::io::DEFAULT_MAX_CELLS {
            return Err(bad(
                "array",
                format!("{h}×{w}"),
                "at most 2^28 cells, as the map readers accept",
            ));
        }
        let resolution = oxcover::grid::error::positive("resolution", resolution)
            .map_err(|e| bad(e.name, e.value, e.expected))?;
        if resolution > oxcover::grid::io::MAX_RESOLUTION {
            return Err(bad(
                "resolution",
                resolution,
                "at most 1000 (metres per cell)",
            ));
        }
        let (x, y, yaw) = origin;
        if ![x, y, yaw].iter().all(|v| v.is_finite()) {
            return Err(bad(
                "origin",
                format!("({x}, {y}, {yaw})"),
                "finite (x, y, yaw)",
            ));
        }
        if !(0.0..=1.0).contains(&free_thresh)
            || !(0.0..=1.0).contains(&occupied_thresh)
            || free_thresh > occupied_thresh
        {
            return Err(bad(
                "free_thresh, occupied_thresh",
                format!("{free_thresh}, {occupied_thresh}"),
                "fractions with 0 <= free_thresh <= occupied_thresh <= 1",
            ));
        }
        let dtype = array.dtype().to_string();
        let (f, o) = (free_thresh, occupied_thresh);
        let cells = match dtype.as_str() {
            "bool" => from_mask(array, rows)?,
            "int8" => from_values::<i8>(array, rows, -1, f, o)?,
            "uint8" => from_values::<u8>(array, rows, 255, f, o)?,
            "int16" => from_values::<i16>(array, rows, -1, f, o)?,
            "int32" => from_values::<i32>(array, rows, -1, f, o)?,
            "int64" => from_values::<i64>(array, rows, -1, f, o)?,
            other => {
                return Err(bad(
                    "array",
                    format!("dtype {other}"),
                    "dtype bool (free mask) or int8, uint8, int16, int32, int64 (occupancy, -1..100)",
                ));
            }
        };
        let grid = OccupancyGrid::new(cells, resolution, Point::new(x, y)).with_yaw(yaw);
        Ok(Map {
            grid: Arc::new(grid),
            name: "<array>".into(),
        })
    }

    /// A map from a ROS `nav_msgs/msg/OccupancyGrid` message as `rclpy`
    /// delivers it (or any object with the same fields: `info.resolution`,
    /// `info.width`, `info.height`, `info.origin.position.x/.y`,
    /// `info.origin.orientation.z/.w`, and `data`, a sequence of `width ×
    /// height` values in -1..100, row 0 at the origin). The yaw is taken from
    /// the origin's quaternion (a rotation about z). Thresholds as
    /// `from_array`.
    #[staticmethod]
    #[pyo3(signature = (msg, *, free_thresh = 0.196, occupied_thresh = 0.65))]
    fn from_ros(msg: &Bound<'_, PyAny>, free_thresh: f64, occupied_thresh: f64) -> PyResult<Self> {
        let py = msg.py();
        let field = |path: &str| -> PyResult<Bound<'_, PyAny>> {
            let mut v = msg.clone();
            for name in path.split('.') {
                v = v.getattr(name).map_err(|_| {
                    bad(
                        "msg",
                        format!("without `{path}`"),
                        "a nav_msgs/msg/OccupancyGrid (info.resolution, info.width, info.height, info.origin, data)",
                    )
                })?;
            }
            Ok(v)
        };
        let width: usize = field("info.width")?.extract()?;
        let height: usize = field("info.height")?.extract()?;
        let resolution: f64 = field("info.resolution")?.extract()?;
        let x: f64 = field("info.origin.position.x")?.extract()?;
        let y: f64 = field("info.origin.position.y")?.extract()?;
        let qz: f64 = field("info.origin.orientation.z")?.extract()?;
        let qw: f64 = field("info.origin.orientation.w")?.extract()?;
        let yaw = 2.0 * qz.atan2(qw);
        let numpy = py.import("numpy")?;
        let flat = numpy.call_method1("asarray", (field("data")?, "int64"))?;
        let n: usize = flat.getattr("size")?.extract()?;
        if n != width.saturating_mul(height) {
            return Err(bad(
                "msg.data",
                format!("{n} values"),
                &format!("info.width × info.height = {width} × {height} values"),
            ));
        }
        let grid = flat.call_method1("reshape", ((height, width),))?;
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("rows", "up")?;
        kwargs.set_item("free_thresh", free_thresh)?;
        kwargs.set_item("occupied_thresh", occupied_thresh)?;
        let map = py.get_type::<Map>().call_method(
            "from_array",
            (grid, resolution, (x, y, yaw)),
            Some(&kwargs),
        )?;
        let map: PyRef<'_, Map> = map.extract()?;
        Ok(Map {
            grid: Arc::clone(&map.grid),
            name: "<nav_msgs/OccupancyGrid>".into(),
        })
    }

    /// The map as an int8 array in the nav_msgs/OccupancyGrid convention:
    /// 0 free, 100 occupied, -1 unknown; rows as `from_array` takes them.
    #[pyo3(signature = (*, rows = "up"))]
    fn to_array<'py>(&self, py: Python<'py>, rows: &str) -> PyResult<Bound<'py, PyArray2<i8>>> {
        let rows = rows_of(rows)?;
        let (w, h) = (self.grid.width(), self.grid.height());
        let cells = self.grid.cells();
        let array = Array2::from_shape_fn((h, w), |(i, j)| {
            match cells[Cell::new(grid_row(rows, i, h), j)] {
                Occupancy::Free => 0,
                Occupancy::Occupied => 100,
                Occupancy::Unknown => -1,
            }
        });
        Ok(array.into_pyarray(py))
    }

    /// The free cells as a bool array (True = free); rows as `to_array`.
    #[pyo3(signature = (*, rows = "up"))]
    fn free_mask<'py>(&self, py: Python<'py>, rows: &str) -> PyResult<Bound<'py, PyArray2<bool>>> {
        let rows = rows_of(rows)?;
        let (w, h) = (self.grid.width(), self.grid.height());
        let cells = self.grid.cells();
        let array = Array2::from_shape_fn((h, w), |(i, j)| {
            cells[Cell::new(grid_row(rows, i, h), j)].is_free()
        });
        Ok(array.into_pyarray(py))
    }

    /// Columns (cells along x).
    #[getter]
    fn width(&self) -> usize {
        self.grid.width()
    }

    /// Rows (cells along y).
    #[getter]
    fn height(&self) -> usize {
        self.grid.height()
    }

    /// (rows, columns), as numpy's `shape` of `to_array()`.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.grid.height(), self.grid.width())
    }

    /// Metres per cell.
    #[getter]
    fn resolution(&self) -> f64 {
        self.grid.resolution()
    }

    /// (x, y, yaw): the lower-left corner of the bottom-left cell in metres,
    /// and the map's rotation about it in radians.
    #[getter]
    fn origin(&self) -> (f64, f64, f64) {
        let f = self.grid.frame();
        (f.origin().x, f.origin().y, f.yaw())
    }

    /// The file the map was read from, or `<array>`.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Cell counts: `{"free": …, "occupied": …, "unknown": …}`.
    fn counts(&self) -> std::collections::BTreeMap<&'static str, usize> {
        let c = self.grid.counts();
        [
            ("free", c.free),
            ("occupied", c.occupied),
            ("unknown", c.unknown),
        ]
        .into_iter()
        .collect()
    }

    /// The centre of cell (row, column) in metres, rows as `to_array`.
    #[pyo3(signature = (row, column, *, rows = "up"))]
    fn cell_center(&self, row: usize, column: usize, rows: &str) -> PyResult<(f64, f64)> {
        let rows = rows_of(rows)?;
        let (w, h) = (self.grid.width(), self.grid.height());
        if row >= h || column >= w {
            return Err(bad(
                "cell",
                format!("({row}, {column})"),
                &format!("a cell of this {h}×{w} map"),
            ));
        }
        let p = self
            .grid
            .frame()
            .cell_center(Cell::new(grid_row(rows, row, h), column));
        Ok((p.x, p.y))
    }

    fn __repr__(&self) -> String {
        let (x, y, yaw) = self.origin();
        format!(
            "Map({}, {}×{} cells, resolution={}, origin=({x}, {y}, {yaw}))",
            self.name,
            self.grid.height(),
            self.grid.width(),
            self.grid.resolution()
        )
    }
}

/// `message=`: a number or a name.
#[derive(FromPyObject)]
pub(crate) enum MessageArg {
    /// A message number from 0.
    Index(u64),
    /// `first` or `last`.
    Name(String),
}

/// Reads a map in any format the command line reads: a ROS map_server yaml
/// (with its PGM/PNG/BMP image), a plain PGM, PNG or BMP image, or a
/// MovingAI `.map`, or a rosbag2 bag (a folder with `metadata.yaml`, a
/// `.mcap` or a `.db3` file) whose `nav_msgs/msg/OccupancyGrid` message is
/// picked by `topic` (default: the bag's only OccupancyGrid topic) and
/// `message` (`"last"` (default), `"first"`, or its number from 0 in
/// log-time order), as `--topic` and `--message`. An image read without a yaml is placed by `resolution`
/// (metres per cell, default 1.0) and classified by `free_thresh`,
/// `occupied_thresh` and `negate` (map_server's fields, defaults 0.196,
/// 0.65 and False), as the command line's `--resolution`, `--free-thresh`,
/// `--occupied-thresh` and `--negate`.
///
/// Raises OSError if the file cannot be read, ValueError if it is malformed
/// or a classification option is given for a yaml or MovingAI map, with the
/// command line's message naming the file and what is wrong. A resolution
/// the map does not use (a yaml's own stands) is a UserWarning.
#[pyfunction]
#[pyo3(signature = (path, *, resolution = None, free_thresh = None, occupied_thresh = None, negate = false, topic = None, message = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn load_map(
    py: Python<'_>,
    path: PathBuf,
    resolution: Option<f64>,
    free_thresh: Option<f64>,
    occupied_thresh: Option<f64>,
    negate: bool,
    topic: Option<String>,
    message: Option<MessageArg>,
) -> PyResult<Map> {
    let name = path.display().to_string();
    let message = match message {
        None => None,
        Some(MessageArg::Index(k)) => Some(MessageChoice::Index(k)),
        Some(MessageArg::Name(s)) => Some(s.parse().map_err(|e: String| {
            pyo3::exceptions::PyValueError::new_err(format!("message is {e}"))
        })?),
    };
    let reading = oxcover::pipeline::MapReading {
        resolution,
        free_thresh,
        occupied_thresh,
        negate,
        topic,
        message,
    };
    let (grid, notes) = detached(py, move || {
        oxcover::pipeline::load_map_with(&path, &reading)
    })?;
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    for note in notes {
        // A note is plain text from our own messages: no NUL inside.
        let message = std::ffi::CString::new(note).unwrap_or_default();
        PyErr::warn(py, &category, &message, 1)?;
    }
    Ok(Map {
        grid: Arc::new(grid),
        name,
    })
}
