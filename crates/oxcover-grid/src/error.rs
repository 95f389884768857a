//! The crate's error type: every variant names the file, field or value at fault.

use std::path::PathBuf;

/// Errors from reading maps and building coverage problems.
///
/// Each message is one line that names what was wrong and what was expected,
/// suitable for showing to a user as is.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file's content does not follow its format.
    #[error("{}: {message}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// What is malformed, and what was expected.
        message: String,
    },
    /// A required field of a map yaml is absent.
    #[error("{}: missing field `{field}`", path.display())]
    MissingField {
        /// The yaml file.
        path: PathBuf,
        /// The field name.
        field: &'static str,
    },
    /// A map yaml field has a value that cannot be used.
    #[error("{}: field `{field}` is {value}, expected {expected}", path.display())]
    InvalidField {
        /// The yaml file.
        path: PathBuf,
        /// The field name.
        field: &'static str,
        /// The value found, as written.
        value: String,
        /// What would have been accepted.
        expected: &'static str,
    },
    /// The pixel or cell data ends before the header's size is filled.
    #[error("{}: truncated: header says {width}x{height}, which needs {expected} {unit}, but the file holds {found}", path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Width from the header.
        width: usize,
        /// Height from the header.
        height: usize,
        /// Amount the header implies.
        expected: usize,
        /// Amount present.
        found: usize,
        /// What is counted ("bytes", "values", "rows").
        unit: &'static str,
    },
    /// The map is larger than the configured cell limit.
    #[error("{}: map size {width}x{height} exceeds the limit of {limit} cells", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Width from the header.
        width: u64,
        /// Height from the header.
        height: u64,
        /// The cell limit in force.
        limit: usize,
    },
    /// The map has a zero dimension.
    #[error("{}: map size {width}x{height} is empty, expected at least 1x1", path.display())]
    EmptyMap {
        /// The file.
        path: PathBuf,
        /// Width from the header.
        width: usize,
        /// Height from the header.
        height: usize,
    },
    /// The file is not in any format this crate reads.
    #[error("{}: {message}", path.display())]
    UnsupportedFormat {
        /// The file.
        path: PathBuf,
        /// What was found and what is supported.
        message: String,
    },
    /// A numeric parameter is out of range (negative radius, NaN, ...).
    #[error("{name} is `{value}`, expected {expected}")]
    BadParameter {
        /// Parameter name as the user knows it (e.g. `--robot-radius`).
        name: &'static str,
        /// The value given.
        value: String,
        /// What is accepted.
        expected: &'static str,
    },
    /// The map holds no free cell at all.
    #[error("the map has no free cell ({width}x{height} cells, all occupied or unknown)")]
    NoFreeCell {
        /// Map width.
        width: usize,
        /// Map height.
        height: usize,
    },
    /// No free cell is far enough from obstacles for the robot.
    #[error(
        "no admissible cell for robot radius {robot_radius} m: every free cell is closer than that to an obstacle, unknown cell or the map edge"
    )]
    NoAdmissibleCell {
        /// The robot radius in metres.
        robot_radius: f64,
    },
    /// The requested start lies outside the map.
    #[error("start ({x}, {y}) is outside the map, which spans x {xmin}..{xmax}, y {ymin}..{ymax}")]
    StartOutsideMap {
        /// Start x in metres.
        x: f64,
        /// Start y in metres.
        y: f64,
        /// Map bounds.
        xmin: f64,
        /// Map bounds.
        xmax: f64,
        /// Map bounds.
        ymin: f64,
        /// Map bounds.
        ymax: f64,
    },
    /// The requested start is not an admissible robot pose.
    #[error("start ({x}, {y}) is not admissible: its cell (row {row}, col {col}) is {reason}")]
    StartNotAdmissible {
        /// Start x in metres.
        x: f64,
        /// Start y in metres.
        y: f64,
        /// Its cell's row.
        row: usize,
        /// Its cell's column.
        col: usize,
        /// Why ("occupied", "unknown", "closer than the robot radius to an obstacle").
        reason: &'static str,
    },
    /// A random-map generator could not meet its constraints.
    #[error("random map: {message}")]
    Generator {
        /// What could not be met.
        message: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A parameter outside its range, as the one validation helper of the
/// workspace ([`positive`], [`non_negative`]) reports it; every crate's
/// error type turns it into its own `BadParameter` variant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BadValue {
    /// Parameter name as the user knows it (e.g. `--robot-radius`).
    pub name: &'static str,
    /// The value given.
    pub value: f64,
    /// What is accepted.
    pub expected: &'static str,
}

crate::bad_value_into!(Error);

/// `value` if it is finite and `>= 0`.
///
/// # Errors
/// [`BadValue`] naming the parameter.
pub fn non_negative(name: &'static str, value: f64) -> std::result::Result<f64, BadValue> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(BadValue {
            name,
            value,
            expected: "a finite number >= 0",
        })
    }
}

/// `value` if it is finite and `> 0`.
///
/// # Errors
/// [`BadValue`] naming the parameter.
pub fn positive(name: &'static str, value: f64) -> std::result::Result<f64, BadValue> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BadValue {
            name,
            value,
            expected: "a finite number > 0",
        })
    }
}

/// Implements `From<BadValue>` for a crate's error type whose
/// `BadParameter { name, value: String, expected: &'static str }` variant
/// carries the refusal of the workspace's one parameter check.
#[macro_export]
macro_rules! bad_value_into {
    ($error:ty) => {
        impl From<$crate::error::BadValue> for $error {
            fn from(b: $crate::error::BadValue) -> Self {
                Self::BadParameter {
                    name: b.name,
                    value: b.value.to_string(),
                    expected: b.expected,
                }
            }
        }
    };
}
