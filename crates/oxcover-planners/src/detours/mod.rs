//! Detours and tightening: a finished path repaired and tightened for
//! time, with coverage counted exactly as the contract's samples count it.
//! Not from the seed papers: cheapest insertion as in tour heuristics,
//! scored by the contract's estimated time. `lanes` runs both on its path;
//! the pipeline tightens every room's boundary pass and, room by room, the
//! whole plan ([`crate::CoverageProblem::tighten_from`]).
//!
//! - `reach`: which cells a segment reaches (a contract sample within the
//!   tool radius of the cell's centre), row by row over its capsule, and
//!   how many segments of a path reach each cell.
//! - `insert`: the coverable cells a path misses, each covered by the
//!   cheapest bend of a nearby segment that uncovers nothing
//!   ([`insert_detours`]).
//! - `tighten`: vertices removed, moved towards their neighbours' line or
//!   slid along a piece, whichever saves the most time while clear and
//!   uncovering nothing ([`tighten_from`], pass by pass with
//!   [`Tightening`]); a [`Zone`] keeps each vertex in its room.
//! - `geometry`: the linked polyline they edit, and the time and box
//!   helpers they share.
//!
//! What a path reaches is counted with two radii either side of the
//! metrics' own ([`metric_reach`]): a change must reach a cell within the
//! inner one, and every cell the replaced pieces reach within the outer one
//! is kept, so that rounding never decides a cell's fate.

mod geometry;
mod insert;
mod reach;
#[cfg(test)]
mod tests;
mod tighten;

use oxcover_grid::Grid;

use crate::time::TimeModel;

pub(crate) use geometry::{cell_box, heading_change, polyline_time};
pub(crate) use insert::insert_detours;
pub(crate) use reach::reach_counts;
pub(crate) use tighten::{Tightening, Zone, tighten_from};

/// The detour settings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Detours<'a> {
    /// Where the path may go.
    pub plannable: &'a Grid<bool>,
    /// What it must cover.
    pub coverable: &'a Grid<bool>,
    /// How near a cell centre one of the path's contract samples must be
    /// (cells; the tool radius).
    pub reach: f64,
    /// How much farther than `reach` a sample may still reach a cell as
    /// the metrics measure it (cells; 0 where the caller covers such cells
    /// itself). [`tighten_from`] never leaves out a cell the pieces it replaces
    /// reach within `reach + fragile`, unless another piece reaches it
    /// within `reach`: the two radii either side of the metrics' own keep
    /// rounding from deciding a cell's fate.
    pub fragile: f64,
    /// Farthest a detour's vertex may be from the segment it bends (cells).
    pub search: f64,
    /// Speeds in cells per second and radians per second.
    pub time: TimeModel,
}

/// `(reach, fragile)` of [`Detours`] for a tool of `tool_cells` scored as
/// the metrics score it: they count a cell within the tool radius and
/// their tolerance (`TOLERANCE_CELLS`) of a sample, so a change must reach
/// every cell a little inside that, and keeps every cell the old path
/// reached a little outside it (rounding of metres, and points moved off
/// cell edges, land on either side).
pub(crate) fn metric_reach(tool_cells: f64) -> (f64, f64) {
    let tolerance = oxcover_grid::TOLERANCE_CELLS;
    (tool_cells + 0.9 * tolerance, 0.2 * tolerance)
}
