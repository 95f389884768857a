//! The robot crate's error type.

/// Errors of the robot models.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A model or controller parameter is out of range.
    #[error("{name} is `{value}`, expected {expected}")]
    BadParameter {
        /// Parameter name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is accepted.
        expected: &'static str,
    },
    /// A robot description file could not be parsed.
    #[error("robot description: {0}")]
    Spec(String),
}

impl From<oxcover_grid::error::BadValue> for Error {
    fn from(b: oxcover_grid::error::BadValue) -> Self {
        Error::BadParameter {
            name: b.name,
            value: b.value,
            expected: b.expected,
        }
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

pub(crate) use oxcover_grid::error::{non_negative, positive};
