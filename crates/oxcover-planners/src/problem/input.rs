//! What a planner is given ([`PlannerInput`], made only by
//! [`super::CoverageProblem::input`]) and what it returns ([`PlanOutput`]),
//! with the ways between places the problem finds ([`Transit`]).

use oxcover_grid::{Cell, CoarseGrid, Grid, MapFrame, Point};

use crate::error::{Error, Result};
use crate::time::TimeModel;

/// A way between two places ([`super::CoverageProblem::transit`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Transit {
    /// The 4-connected plannable cells, both ends included.
    pub cells: Vec<Cell>,
    /// The straightened waypoints (metres, map frame), from the first
    /// cell's centre to the last's.
    pub points: Vec<Point>,
}

/// What a planner returns.
#[derive(Clone, Debug, PartialEq)]
pub enum PlanOutput {
    /// Coverage cells from the start; consecutive cells are connected neighbours.
    Coverage(Vec<Cell>),
    /// Fine cells from the start's representative; consecutive cells are 4-neighbours.
    Fine(Vec<Cell>),
    /// Waypoints in metres (map frame), from the start's representative's centre.
    Metres(Vec<Point>),
}

impl PlanOutput {
    /// The coverage-cell path, if that is what was returned.
    #[must_use]
    pub fn coverage(&self) -> Option<&[Cell]> {
        match self {
            PlanOutput::Coverage(v) => Some(v),
            PlanOutput::Fine(_) | PlanOutput::Metres(_) => None,
        }
    }
}

/// The coverage problem as a planner sees it; made by [`super::CoverageProblem::input`].
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub struct PlannerInput<'a> {
    /// Fine cells the robot may occupy (admissible and reachable from the start).
    pub plannable: &'a Grid<bool>,
    /// Fine cells to cover (the contract's coverable cells: free, within the
    /// tool radius of a plannable cell).
    pub coverable: &'a Grid<bool>,
    /// Every admissible cell of the map (plannable or not: a region's
    /// neighbours across a room cut are admissible, a wall is not).
    pub admissible: &'a Grid<bool>,
    /// The coverage grid built from `plannable`.
    pub coarse: &'a CoarseGrid,
    /// The start coverage cell (it has a representative).
    pub start: Cell,
    /// The fine cell the robot starts in (plannable), inside `start`; the
    /// pipeline's lead-in reaches a coverage plan's first cell from here.
    pub start_cell: Cell,
    /// Seed for randomised planners.
    pub seed: u64,
    /// Where the grid lies in metres (for planners returning metre paths).
    pub frame: MapFrame,
    /// Tool radius in fine cells, `T / resolution`: a fine cell counts as
    /// covered when its centre passes within it (the contract).
    pub tool_cells: f64,
    /// Speeds to score choices with (estimated time, the objective).
    pub time: TimeModel,
    /// Where the robot goes next, if known (room by room: the cell of this
    /// room nearest the next room): a planner may end its path near it.
    /// `None` from [`super::CoverageProblem::input`]; the pipeline sets it.
    pub exit: Option<Cell>,
    /// Plannable cells of the whole plan this input is part of: its own
    /// when planned alone, the map's when the pipeline plans room by room.
    /// A planner that searches more widely on small plans sizes its effort
    /// by this, so that a map's planning time does not grow with its number
    /// of rooms.
    pub plan_cells: usize,
}

impl PlannerInput<'_> {
    /// Coverage cells (those with a representative).
    #[must_use]
    pub fn coverage_cells(&self) -> usize {
        self.coarse.representatives().count(Option::is_some)
    }

    /// The radius (fine cells) within which a coverage cell's representative
    /// counts as visited by a metre path: half a coverage cell, or the tool
    /// radius when the tool is narrower than one fine cell.
    #[must_use]
    pub fn visit_radius(&self) -> f64 {
        (self.coarse.block_size() as f64 / 2.0).min(self.tool_cells)
    }

    /// See [`super::CoverageProblem::expand`].
    ///
    /// # Errors
    /// As [`super::CoverageProblem::expand`].
    pub fn expand(&self, output: &PlanOutput) -> Result<Vec<Cell>> {
        let path = match output {
            PlanOutput::Fine(v) => return Ok(v.clone()),
            PlanOutput::Metres(_) => {
                return Err(Error::Internal(
                    "a metre path has no cell path to expand".into(),
                ));
            }
            PlanOutput::Coverage(v) => v,
        };
        let Some(&first) = path.first() else {
            return Ok(Vec::new());
        };
        let rep = self.coarse.representative(first).ok_or_else(|| {
            Error::Internal(format!("coverage cell {first:?} has no representative"))
        })?;
        let mut fine = vec![rep];
        for w in path.windows(2) {
            let seg = self
                .coarse
                .connect(self.plannable, w[0], w[1])
                .ok_or_else(|| {
                    Error::Internal(format!(
                        "coverage step {:?} -> {:?} is not connected",
                        w[0], w[1]
                    ))
                })?;
            fine.extend_from_slice(&seg[1..]);
        }
        Ok(fine)
    }
}
