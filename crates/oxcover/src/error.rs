//! The integration crate's error type and its exit statuses.

use std::path::PathBuf;

/// Errors of planning, evaluation, rendering and the command line.
///
/// [`Error::exit_code`] follows the contract: 2 for bad input or usage (with one
/// line naming the file, field or value), 1 for an internal fault.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A map could not be read or a coverage problem could not be built.
    #[error(transparent)]
    Map(#[from] oxcover_grid::Error),
    /// A robot description or motion parameter could not be used.
    #[error(transparent)]
    Robot(#[from] oxcover_robot::Error),
    /// A world file or the sensor-based planner refused (or failed).
    #[error(transparent)]
    World(#[from] oxcover_world::Error),
    /// A camera, profile or image could not be used.
    #[error(transparent)]
    Vision(#[from] oxcover_vision::Error),
    /// A planner refused the problem or failed.
    #[error(transparent)]
    Planner(oxcover_planners::Error),
    /// A path file is malformed.
    #[error("{}: line {line}: {message}", path.display())]
    PathFile {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A command-line value cannot be used.
    #[error("{name} is `{value}`, expected {expected}")]
    BadParameter {
        /// The option.
        name: &'static str,
        /// The value given.
        value: String,
        /// What is accepted.
        expected: String,
    },
    /// An input file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A coverage target cannot be used: the option or file, and what is
    /// wrong with it.
    #[error("{what}: {message}")]
    Target {
        /// The option (and its file).
        what: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// Planning would need more memory than the budget allows: the map, its
    /// size, the planner, the estimate, the budget and what helps.
    #[error("{0}")]
    MemoryLimit(String),
    /// A planner broke one of its own guarantees: a bug, reported as exit 1.
    #[error("internal error: {0}")]
    Internal(String),
}

impl Error {
    /// Exit status for this error: 2 for bad input or usage, 1 for internal faults.
    #[must_use]
    pub fn exit_code(&self) -> u8 {
        if matches!(
            self,
            Error::Internal(_)
                | Error::Planner(oxcover_planners::Error::Internal(_))
                | Error::World(oxcover_world::Error::Internal(_))
        ) {
            1
        } else {
            2
        }
    }

    /// A file could not be written.
    pub fn write(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Write {
            path: path.into(),
            source,
        }
    }
}

impl From<oxcover_grid::error::BadValue> for Error {
    fn from(b: oxcover_grid::error::BadValue) -> Self {
        Error::BadParameter {
            name: b.name,
            value: b.value.to_string(),
            expected: b.expected.to_string(),
        }
    }
}

impl From<oxcover_planners::Error> for Error {
    /// A map, robot or start the planners' problem refused is a map error,
    /// reported as the grid crate words it.
    fn from(e: oxcover_planners::Error) -> Self {
        match e {
            oxcover_planners::Error::Map(m) => Error::Map(m),
            other => Error::Planner(other),
        }
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
