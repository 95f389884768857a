//! The planners' error type.

/// Errors of the planners.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The problem is larger than this planner accepts.
    #[error("{planner} accepts at most {limit} coverage cells, this map has {cells}{hint}")]
    TooLarge {
        /// Planner name.
        planner: &'static str,
        /// Coverage cells in the problem.
        cells: usize,
        /// The planner's limit.
        limit: usize,
        /// What to do instead.
        hint: &'static str,
    },
    /// The coverage grid is wider than this planner accepts on its shorter side.
    #[error(
        "{planner} needs a coverage grid at most {limit} cells on its shorter side, this one is {width}x{height}{hint}"
    )]
    TooWide {
        /// Planner name.
        planner: &'static str,
        /// Coverage-grid width.
        width: usize,
        /// Coverage-grid height.
        height: usize,
        /// The planner's limit.
        limit: usize,
        /// What to do instead.
        hint: &'static str,
    },
    /// A planner parameter is out of range.
    #[error("{name} is `{value}`, expected {expected}")]
    BadParameter {
        /// Parameter name.
        name: &'static str,
        /// The value given.
        value: String,
        /// What is accepted.
        expected: &'static str,
    },
    /// An option given to a planner that does not take it.
    #[error("{option} is `{value}`, expected {option} only with --planner {takers}")]
    OptionNotTaken {
        /// The option.
        option: &'static str,
        /// The value given, with the planner.
        value: String,
        /// The planners that take it.
        takers: String,
    },
    /// The map, robot or start does not make a coverage problem.
    #[error(transparent)]
    Map(#[from] oxcover_grid::Error),
    /// No planner by that name.
    #[error("no planner named `{0}`")]
    UnknownPlanner(String),
    /// A planner broke one of its own guarantees (a bug).
    #[error("{0}")]
    Internal(String),
}

oxcover_grid::bad_value_into!(Error);

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
