//! The vision crate's error type.

/// Errors of the camera pipeline.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A calibration could not be set up or did not converge.
    #[error("calibration: {0}")]
    Calibration(String),
    /// An image file could not be read or written.
    #[error("{path}: {message}")]
    Image {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// A file could not be read.
    #[error("{path}: cannot read: {message}")]
    Read {
        /// The file.
        path: String,
        /// The operating system's reason.
        message: String,
    },
    /// A line of a text file (the poses CSV) is malformed.
    #[error("{path}: line {line}: {message}")]
    Line {
        /// The file.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// An image is not the camera's size.
    #[error(
        "{width}x{height} pixels, expected {camera_width}x{camera_height} pixels, the camera's size"
    )]
    ImageSize {
        /// The image's width.
        width: u32,
        /// The image's height.
        height: u32,
        /// The camera's width.
        camera_width: u32,
        /// The camera's height.
        camera_height: u32,
    },
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
}

oxcover_grid::bad_value_into!(Error);

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

pub(crate) use oxcover_grid::error::positive;
