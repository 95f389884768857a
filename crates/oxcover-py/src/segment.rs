//! `segment`: the rooms of a map and the doors between them, as
//! `oxcover segment` finds them.

use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use oxcover::grid::Cell;
use oxcover::rooms::{Method, SegmentOptions, report};
use pyo3::prelude::*;

use crate::convert::{bad, detached, to_dict};
use crate::map::{Map, grid_row, rows_of};

/// Segments the free space of `map` into rooms, as `oxcover segment` does.
///
/// `method` is "doorways" (the default: split where a wall has a gap,
/// doors up to `door_width` metres wide, walls continued across a room's
/// open side), "voronoi" (split at the narrow points of the medial axis) or
/// "morphological" (erode until the free space splits into seeds between
/// `min_area` and `max_area` m², grow them back).
///
/// Returns a dict: `labels`, a uint32 array of the map's shape (0 = not free,
/// else the 1-based room label; rows as `Map.to_array`), and the keys of
/// `oxcover segment --out rooms.json`: `method`, the limits, `seeded` (rooms
/// grown from seeds), `rooms` (label, area_m2, centroid and label_at in
/// metres, seeded) and `doors` (the two rooms, centre in metres, cells).
#[pyfunction]
#[pyo3(signature = (map, *, method = "doorways", min_area = 1.0, max_area = 47.0, door_width = 1.6, rows = "up"))]
pub(crate) fn segment<'py>(
    py: Python<'py>,
    map: &Map,
    method: &str,
    min_area: f64,
    max_area: f64,
    door_width: f64,
    rows: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let rows = rows_of(rows)?;
    let method = match method {
        "doorways" => Method::Doorways,
        "voronoi" => Method::Voronoi,
        "morphological" => Method::Morphological,
        other => {
            return Err(bad(
                "method",
                other,
                "`doorways`, `voronoi` or `morphological`",
            ));
        }
    };
    let options = SegmentOptions {
        method,
        min_area_m2: min_area,
        max_area_m2: max_area,
        door_width_m: door_width,
    };
    let grid = &map.grid;
    let (rooms, rep) = detached(py, || {
        let rooms = oxcover::rooms::segment(grid, &options)?;
        let rep = report(grid, &rooms, &options);
        Ok((rooms, rep))
    })?;
    let (w, h) = (grid.width(), grid.height());
    let labels = Array2::from_shape_fn((h, w), |(i, j)| {
        rooms.labels[Cell::new(grid_row(rows, i, h), j)]
    });
    let out = to_dict(py, &rep)?;
    out.set_item("labels", labels.into_pyarray(py))?;
    Ok(out)
}
