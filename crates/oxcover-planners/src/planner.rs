//! The `Planner` abstraction shared by every planner.
//!
//! A planner receives the coverage problem as a [`PlannerInput`] (made by
//! [`crate::CoverageProblem::input`]): the fine
//! plannable cells (admissible and reachable), the coverage grid over them
//! (one tool diameter per coverage cell; with the default radii, the fine grid
//! itself), the start coverage cell and a seed. It returns a path over
//! coverage cells, each step a connected move of the coverage grid (four
//! neighbours, or a diagonal where [`oxcover_grid::CoarseGrid::connect`] finds a path), a
//! fine cell path, or a metre path (for planners that leave the grid, e.g.
//! smoothed paths; the caller checks such paths point by point). [`PlannerInput::expand`]
//! turns coverage paths into fine ones, so grid planners end as 4-connected
//! paths of plannable fine cells: no straight lines through walls.

use oxcover_grid::Cell;

use crate::error::Result;
use crate::problem::{PlanOutput, PlannerInput};

/// A coverage planner.
///
/// A new planner is a value implementing this trait; it sees the problem
/// only through its [`PlannerInput`] and returns a [`PlanOutput`]. Here, a
/// planner that drives the coverage grid's rows back and forth (complete on
/// an open room only), run on a problem made the one way problems are made:
///
/// ```
/// use oxcover_grid::{io::parse_ascii, Cell, DiscRobot};
/// use oxcover_planners::{CoverageProblem, PlanOutput, Planner, PlannerInput, Result, Start};
///
/// struct Rows;
///
/// impl Planner for Rows {
///     fn name(&self) -> &'static str { "rows" }
///     fn complete(&self) -> bool { false }
///     fn summary(&self) -> &'static str { "coverage-grid rows, back and forth" }
///     fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
///         let (w, h) = (input.coarse.width(), input.coarse.height());
///         let path = (0..h)
///             .flat_map(|r| {
///                 let cols: Vec<usize> = if r % 2 == 0 { (0..w).collect() } else { (0..w).rev().collect() };
///                 cols.into_iter().map(move |c| Cell::new(r, c))
///             })
///             .collect();
///         Ok(PlanOutput::Coverage(path))
///     }
/// }
///
/// let (map, _) = parse_ascii("....\n....\n....").unwrap();
/// let problem = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).unwrap();
/// let plan = Rows.plan(&problem.input(0)).unwrap();
/// let fine = problem.expand(&plan).unwrap();
/// assert_eq!(fine.len(), 12);
/// assert!(fine.windows(2).all(|s| s[0].manhattan(s[1]) == 1));
/// ```
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
    /// [`crate::Error::TooLarge`] when the problem exceeds the planner's limits;
    /// [`crate::Error::Internal`] for broken guarantees.
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput>;
    /// The user-settable options this value carries (for reports); none by default.
    fn options(&self) -> PlannerOptions {
        PlannerOptions::new()
    }
}

/// Options a user may set on a planner (the CLI's planner flags). Each is
/// `None` unless given; [`crate::build`] refuses options a planner does not take.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct PlannerOptions {
    /// Fixed sweep angle in degrees (map frame, lanes along it), for the
    /// planners that sweep; `None` = their own choice.
    pub sweep_angle_deg: Option<f64>,
}

impl PlannerOptions {
    /// No option set.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            sweep_angle_deg: None,
        }
    }

    /// The same options with a fixed sweep angle (degrees).
    #[must_use]
    pub const fn sweep_angle(mut self, deg: f64) -> Self {
        self.sweep_angle_deg = Some(deg);
        self
    }
}

/// Steps (moves) of a coverage path.
#[must_use]
pub fn steps(path: &[Cell]) -> usize {
    path.len().saturating_sub(1)
}
