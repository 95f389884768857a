//! The coverage-target keywords of `plan` and `evaluate`: the command
//! line's `--zones`, `--keep-out`, `--rooms-only`, `--room-order`,
//! `--done` and `--spot`, read by the same library functions.

use std::path::PathBuf;

use oxcover::grid::Point;
use oxcover::targets::{Kinds, RoomOrder, Spot, Targets, read_areas};
use pyo3::prelude::*;

use crate::convert::{bad, error, path_argument};

/// The targets the keywords describe (files read here).
pub(crate) fn targets_argument(
    zones: Option<PathBuf>,
    keep_out: Option<PathBuf>,
    rooms_only: Option<Vec<u32>>,
    room_order: &str,
    done: Option<&Bound<'_, PyAny>>,
    spot: Option<(f64, f64, f64)>,
) -> PyResult<Targets> {
    let room_order = match room_order {
        "fastest" => RoomOrder::Fastest,
        "given" => RoomOrder::Given,
        other => return Err(bad("room_order", other, "\"fastest\" or \"given\"")),
    };
    if room_order == RoomOrder::Given && rooms_only.is_none() {
        return Err(bad(
            "room_order",
            "given",
            "rooms_only with the rooms in the order to cover them",
        ));
    }
    Ok(Targets {
        zones: zones
            .map(|p| read_areas(&p, "--zones", Kinds::Polygons))
            .transpose()
            .map_err(|e| error(&e))?,
        spot: spot
            .map(|(x, y, r)| Spot::new(Point::new(x, y), r))
            .transpose()
            .map_err(|e| error(&e))?,
        keep_out: keep_out
            .map(|p| read_areas(&p, "--keep-out", Kinds::PolygonsAndLines))
            .transpose()
            .map_err(|e| error(&e))?,
        rooms_only,
        room_order,
        done: done.map(path_argument).transpose()?,
    })
}
