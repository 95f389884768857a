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

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `value` if it is finite and strictly positive, else a [`Error::BadParameter`].
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::BadParameter {
            name,
            value: value.to_string(),
            expected: "a finite number above 0",
        })
    }
}
