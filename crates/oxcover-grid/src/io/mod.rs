//! Map readers and writers: ROS map_server yaml + PGM/PNG/BMP, plain images,
//! MovingAI `.map`, and an ASCII format for tests.
//!
//! [`read_map`] picks the reader from the file extension (`.yaml`/`.yml`,
//! `.pgm`/`.png`/`.bmp`, `.map`) and otherwise from the content. Every reader
//! checks the declared size against [`ReadOptions::max_cells`] before it
//! allocates, and reports malformed input as an [`Error`] naming the file and
//! what was expected, never a panic.

mod ascii;
pub mod limited;
mod movingai;
mod pgm;
mod raster;
mod ros;

pub use ascii::{ascii_mask, parse_ascii, to_ascii};
pub use movingai::{parse_movingai, read_movingai};
pub use ros::{
    MAX_ORIGIN, MAX_RESOLUTION, MapYaml, Mode, Thresholds, parse_map_yaml, read_ros_yaml,
    read_ros_yaml_from_bytes, ros_map_files, write_ros_map,
};

use std::io::Read as _;
use std::path::Path;

use crate::error::{Error, Result, positive};
use crate::math::Point;
use crate::occupancy::OccupancyGrid;

/// Default cap on the number of cells a reader will allocate (2^28, i.e. 16384²).
pub const DEFAULT_MAX_CELLS: usize = 1 << 28;

/// Options shared by the readers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReadOptions {
    /// Resolution (m/cell) for images read without a yaml. Default 1.0 (contract).
    pub resolution: f64,
    /// Largest map accepted, in cells. Default [`DEFAULT_MAX_CELLS`].
    pub max_cells: usize,
    /// How the pixels of an image read without a yaml are classified.
    /// Default the ROS defaults (contract); a yaml's own fields govern
    /// its image. A floor plan drawn to another rule (say, only white is
    /// free) is read by setting its thresholds here.
    pub thresholds: Thresholds,
}

impl Default for ReadOptions {
    fn default() -> Self {
        Self {
            resolution: 1.0,
            max_cells: DEFAULT_MAX_CELLS,
            thresholds: Thresholds::default(),
        }
    }
}

impl ReadOptions {
    /// Default options.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the resolution used for images without a yaml.
    #[must_use]
    pub fn resolution(mut self, resolution: f64) -> Self {
        self.resolution = resolution;
        self
    }

    /// Sets the largest map accepted, in cells.
    #[must_use]
    pub fn max_cells(mut self, max_cells: usize) -> Self {
        self.max_cells = max_cells;
        self
    }

    /// Sets how the pixels of images without a yaml are classified.
    #[must_use]
    pub fn thresholds(mut self, thresholds: Thresholds) -> Self {
        self.thresholds = thresholds;
        self
    }
}

/// Reads any map input of the contract, choosing the reader by extension, then by content.
///
/// # Errors
/// [`Error`] naming the file and what was wrong: unreadable file, malformed
/// header or yaml field, truncated data, a map larger than the cell limit.
pub fn read_map(path: &Path, options: &ReadOptions) -> Result<OccupancyGrid> {
    match MapFormat::by_extension(path) {
        Some(MapFormat::RosYaml) => read_ros_yaml(path, options),
        Some(MapFormat::MovingAi) => read_movingai(path, options),
        Some(MapFormat::Image) | None => {
            let bytes = read_bytes(path)?;
            if looks_like_movingai(&bytes) {
                return parse_movingai(path, &bytes, options);
            }
            read_image_bytes(path, &bytes, options)
        }
    }
}

/// Which reader [`read_map`] hands a file to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapFormat {
    /// A ROS map_server yaml (`.yaml`, `.yml`): its own fields place and
    /// classify its image.
    RosYaml,
    /// A MovingAI `.map` (by extension, or any file that starts `type `).
    MovingAi,
    /// A plain PGM, PNG or BMP image, read with [`ReadOptions`]'
    /// resolution and thresholds.
    Image,
}

impl MapFormat {
    /// The format a file's extension names; `None` where only its content
    /// can tell (anything but `.yaml`, `.yml` and `.map` is an image unless
    /// it starts as a MovingAI map).
    fn by_extension(path: &Path) -> Option<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        match ext.as_str() {
            "yaml" | "yml" => Some(Self::RosYaml),
            "map" => Some(Self::MovingAi),
            _ => None,
        }
    }
}

/// The reader [`read_map`] would choose for `path`: by extension, else by
/// the file's first bytes (only those are read).
///
/// # Errors
/// [`Error::Io`] naming the file where it cannot be opened or read.
pub fn map_format(path: &Path) -> Result<MapFormat> {
    if let Some(format) = MapFormat::by_extension(path) {
        return Ok(format);
    }
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut head = Vec::with_capacity(MOVINGAI_MAGIC.len());
    std::fs::File::open(path)
        .map_err(io)?
        .take(MOVINGAI_MAGIC.len() as u64)
        .read_to_end(&mut head)
        .map_err(io)?;
    Ok(if looks_like_movingai(&head) {
        MapFormat::MovingAi
    } else {
        MapFormat::Image
    })
}

/// Reads a plain image (PGM/PNG/BMP) with the thresholds of `options` (by
/// default the ROS defaults), its resolution and origin (0, 0).
///
/// # Errors
/// As [`read_map`].
pub fn read_image(path: &Path, options: &ReadOptions) -> Result<OccupancyGrid> {
    let bytes = read_bytes(path)?;
    read_image_bytes(path, &bytes, options)
}

fn read_image_bytes(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<OccupancyGrid> {
    let resolution = positive("--resolution", options.resolution)?;
    let cells = decode_image(path, bytes, options.max_cells, &options.thresholds)?;
    Ok(OccupancyGrid::new(cells, resolution, Point::origin()))
}

/// Decodes image bytes (PGM P2/P5, PNG, BMP) into occupancy with `thresholds`.
pub(crate) fn decode_image(
    path: &Path,
    bytes: &[u8],
    max_cells: usize,
    thresholds: &Thresholds,
) -> Result<crate::Grid<crate::Occupancy>> {
    if bytes.is_empty() {
        return Err(Error::Format {
            path: path.to_path_buf(),
            message: "empty file, expected a PGM, PNG or BMP image".into(),
        });
    }
    if bytes[0] == b'P' {
        pgm::decode(path, bytes, max_cells, |v| thresholds.classify(v))
    } else {
        raster::decode(path, bytes, max_cells, |v| thresholds.classify(v))
    }
}

/// Accepts the first bytes of a map image or MovingAI map: `P1`..`P6`
/// (netpbm), PNG's signature, `BM` or `type ` (an empty file is left to
/// the decoders, which say so).
///
/// # Errors
/// What the file begins with and what was expected.
pub fn map_head(head: &[u8]) -> std::result::Result<(), String> {
    let netpbm = head.len() >= 2 && head[0] == b'P' && (b'1'..=b'6').contains(&head[1]);
    if head.is_empty()
        || netpbm
        || head.starts_with(b"\x89PNG")
        || head.starts_with(b"BM")
        || looks_like_movingai(head)
        || MOVINGAI_MAGIC.starts_with(head)
    {
        Ok(())
    } else {
        Err(format!(
            "not a PGM, PNG, BMP or MovingAI map: it begins with {}, expected P2/P5, \\x89PNG, BM or `type `",
            limited::hex_head(head)
        ))
    }
}

pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    limited::read_limited_after(path, limited::MAX_MAP_BYTES, map_head).map_err(|source| {
        Error::Io {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// How a MovingAI map begins.
const MOVINGAI_MAGIC: &[u8] = b"type ";

fn looks_like_movingai(bytes: &[u8]) -> bool {
    bytes.starts_with(MOVINGAI_MAGIC)
}

/// Checks a declared `width × height` against the cell limit before allocating.
pub(crate) fn check_size(path: &Path, width: u64, height: u64, max_cells: usize) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(Error::EmptyMap {
            path: path.to_path_buf(),
            width: width as usize,
            height: height as usize,
        });
    }
    match width.checked_mul(height) {
        Some(n) if n <= max_cells as u64 => Ok(()),
        _ => Err(Error::TooLarge {
            path: path.to_path_buf(),
            width,
            height,
            limit: max_cells,
        }),
    }
}
