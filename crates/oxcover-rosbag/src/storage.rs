//! What the storage readers share: a topic's description, one-line errors
//! naming the file, and a file's first bytes.

use std::path::Path;

use oxcover_grid::Error;

/// One line naming `path` and what is wrong with it.
pub(crate) fn bad(path: &Path, message: &str) -> Error {
    Error::Format {
        path: path.to_path_buf(),
        message: message.to_string(),
    }
}

/// The first `n` bytes of `path` (fewer if it is shorter); nothing more is read.
pub(crate) fn head(path: &Path, n: usize) -> Result<Vec<u8>, Error> {
    use std::io::Read as _;
    let mut out = Vec::with_capacity(n);
    std::fs::File::open(path)
        .and_then(|f| f.take(n as u64).read_to_end(&mut out))
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    Ok(out)
}

/// A topic of a bag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TopicInfo {
    /// Topic name (`/map`).
    pub name: String,
    /// ROS 2 type (`nav_msgs/msg/OccupancyGrid`).
    pub type_name: String,
    /// Messages on it.
    pub count: u64,
}
