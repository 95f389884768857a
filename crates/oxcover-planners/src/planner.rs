//! The `Planner` abstraction shared by every planner, and the registry.
//!
//! A planner receives the coverage problem as a [`PlannerInput`]: the fine
//! plannable cells (admissible and reachable), the coverage grid over them
//! (one tool diameter per coverage cell; with the default radii, the fine grid
//! itself), the start coverage cell and a seed. It returns a path over
//! coverage cells, each step a connected move of the coverage grid (four
//! neighbours, or a diagonal where [`CoarseGrid::connect`] finds a path), a
//! fine cell path, or a metre path (for planners that leave the grid, e.g.
//! smoothed paths; the caller checks such paths point by point). [`expand`]
//! turns coverage paths into fine ones, so grid planners end as 4-connected
//! paths of plannable fine cells: no straight lines through walls.

use oxcover_grid::{Cell, CoarseGrid, Grid, MapFrame};

use crate::error::{Error, Result};

/// The coverage problem as a planner sees it.
#[derive(Clone, Copy, Debug)]
pub struct PlannerInput<'a> {
    /// Fine cells the robot may occupy (admissible and reachable from the start).
    pub plannable: &'a Grid<bool>,
    /// The coverage grid built from `plannable`.
    pub coarse: &'a CoarseGrid,
    /// The start coverage cell (it has a representative).
    pub start: Cell,
    /// Seed for randomised planners.
    pub seed: u64,
    /// Where the grid lies in metres (for planners returning metre paths).
    pub frame: MapFrame,
    /// Tool radius in fine cells: a fine cell counts as covered when its
    /// centre passes within it (the contract). At least half a coverage cell
    /// in practice; smaller when the tool is narrower than one map cell.
    pub tool_cells: f64,
}

impl<'a> PlannerInput<'a> {
    /// An input starting at the coverage cell containing the fine `start`.
    #[must_use]
    pub fn new(plannable: &'a Grid<bool>, coarse: &'a CoarseGrid, fine_start: Cell) -> Self {
        Self {
            plannable,
            coarse,
            start: coarse.coarse_of(fine_start),
            seed: 0,
            frame: MapFrame::unit(plannable.width(), plannable.height()),
            tool_cells: coarse.block_size() as f64 / 2.0,
        }
    }

    /// Coverage cells (those with a representative).
    #[must_use]
    pub fn coverage_cells(&self) -> usize {
        self.coarse.representatives().count(Option::is_some)
    }
}

/// What a planner returns.
#[derive(Clone, Debug, PartialEq)]
pub enum PlanOutput {
    /// Coverage cells from the start; consecutive cells are connected neighbours.
    Coverage(Vec<Cell>),
    /// Fine cells from the start's representative; consecutive cells are 4-neighbours.
    Fine(Vec<Cell>),
    /// Waypoints in metres (map frame), from the start's representative's centre.
    Metres(Vec<oxcover_grid::Point>),
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

/// A coverage planner.
pub trait Planner: Send + Sync {
    /// Name used on the command line.
    fn name(&self) -> &'static str;
    /// Whether it promises to visit every coverage cell reachable in the coverage grid.
    fn complete(&self) -> bool;
    /// One line: what it does and where it comes from.
    fn summary(&self) -> &'static str;
    /// Plans a path.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when the problem exceeds the planner's limits;
    /// [`Error::Internal`] for broken guarantees.
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput>;
}

/// Every planner, in the order `oxcover planners` lists them.
#[must_use]
pub fn registry() -> &'static [&'static dyn Planner] {
    use crate::{
        border_expansion::BorderExpansionPlanner,
        bsa::Bsa,
        dtc::Dtc,
        full_dtc::FullDtc,
        grid_cover::GridCover,
        optimal::Optimal,
        rect_priority::RectPriority,
        smooth::Smooth,
        stc::{Stc, StcVariant},
        sweep::{Decomposition, Sweep},
    };
    static DTC: Dtc = Dtc::new();
    static FULL_DTC: FullDtc = FullDtc::new();
    static GRID_COVER: GridCover = GridCover::new();
    static RECT: RectPriority = RectPriority::new();
    static OPTIMAL: Optimal = Optimal::new();
    static STC: Stc = Stc::new(StcVariant::Plain);
    static SPIRAL_STC: Stc = Stc::new(StcVariant::Full);
    static BSA: Bsa = Bsa;
    static BOUSTROPHEDON: Sweep = Sweep::new(Decomposition::Boustrophedon);
    static TRAPEZOIDAL: Sweep = Sweep::new(Decomposition::Trapezoidal);
    static BORDER: BorderExpansionPlanner = BorderExpansionPlanner;
    static SMOOTH: Smooth = Smooth::new();
    static ALL: [&dyn Planner; 12] = [
        &DTC,
        &FULL_DTC,
        &GRID_COVER,
        &RECT,
        &OPTIMAL,
        &STC,
        &SPIRAL_STC,
        &BSA,
        &BOUSTROPHEDON,
        &TRAPEZOIDAL,
        &BORDER,
        &SMOOTH,
    ];
    &ALL
}

/// The registered planner with this name.
///
/// # Errors
/// [`Error::UnknownPlanner`].
pub fn find(name: &str) -> Result<&'static dyn Planner> {
    registry()
        .iter()
        .copied()
        .find(|p| p.name() == name)
        .ok_or_else(|| Error::UnknownPlanner(name.to_string()))
}

/// The fine path of a plan: coverage steps become the fine paths
/// [`CoarseGrid::connect`] gives; the result starts at the start's representative.
///
/// # Errors
/// [`Error::Internal`] if two consecutive coverage cells are not connected, or
/// for a metre path (it has no cell path; use it as it is).
pub fn expand(input: &PlannerInput<'_>, output: &PlanOutput) -> Result<Vec<Cell>> {
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
    let rep = input
        .coarse
        .representative(first)
        .ok_or_else(|| Error::Internal(format!("coverage cell {first:?} has no representative")))?;
    let mut fine = vec![rep];
    for w in path.windows(2) {
        let seg = input
            .coarse
            .connect(input.plannable, w[0], w[1])
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

/// Steps (moves) of a coverage path.
#[must_use]
pub fn steps(path: &[Cell]) -> usize {
    path.len().saturating_sub(1)
}
