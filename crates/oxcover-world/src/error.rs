//! The world crate's error type.

/// Errors of worlds, sensing and the sensor-based planner.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is out of range.
    #[error("{name} is `{value}`, expected {expected}")]
    BadParameter {
        /// Parameter name.
        name: &'static str,
        /// The value given.
        value: String,
        /// What is accepted.
        expected: &'static str,
    },
    /// A world file could not be read, or describes an impossible world.
    #[error("{file}: {message}")]
    World {
        /// The file (or what the text came from).
        file: String,
        /// What is wrong.
        message: String,
    },
    /// The sensor-based planner broke one of its own guarantees (a bug).
    #[error("{0}")]
    Internal(String),
}

oxcover_grid::bad_value_into!(Error);

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

pub(crate) use oxcover_grid::error::positive;
