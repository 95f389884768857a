//! Maps read as the command line reads them: any format, with the
//! map_server reading options for an image that comes without a yaml.

use std::path::Path;

use oxcover_grid::OccupancyGrid;
use oxcover_grid::io::{MapFormat, ReadOptions, Thresholds, map_format, read_map};
use oxcover_rosbag::MessageChoice;

use crate::error::{Error, Result};

/// Reads the map at `path` in any format the command line reads (ROS yaml
/// with its image, PGM, PNG, BMP, MovingAI `.map`); `resolution` (m/cell)
/// places an image read without a yaml (default 1.0).
///
/// # Errors
/// A resolution that is not positive or above 1000 m/cell, naming
/// `--resolution`; an unreadable or malformed map, naming the file
/// ([`oxcover_grid::Error`]).
pub fn load_map(path: &Path, resolution: Option<f64>) -> Result<OccupancyGrid> {
    let reading = MapReading {
        resolution,
        ..MapReading::default()
    };
    Ok(load_map_with(path, &reading)?.0)
}

/// How to read an image that comes without a yaml: the command line's
/// `--resolution`, `--free-thresh`, `--occupied-thresh` and `--negate`.
///
/// A map_server yaml places and classifies its own image, and a MovingAI
/// map has neither; an image without one is read with the contract's
/// defaults (1.0 m/px, negate 0, occupied 0.65, free 0.196, trinary)
/// except where this says otherwise. A floor plan drawn to its own rule,
/// say only white free (grey above 250, as the ipa floor-plan benchmark
/// reads its plans), is read with `free_thresh: Some(5.0 / 255.0)`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MapReading {
    /// Metres per pixel [default 1.0].
    pub resolution: Option<f64>,
    /// A pixel is free when its occupancy `p` is below this [default 0.196].
    pub free_thresh: Option<f64>,
    /// A pixel is occupied when `p` is above this [default 0.65].
    pub occupied_thresh: Option<f64>,
    /// Dark means free: `p = v / 255` instead of `(255 - v) / 255`.
    pub negate: bool,
    /// The OccupancyGrid topic of a bag [default: the bag's only one].
    pub topic: Option<String>,
    /// Which message of the topic [default: the last].
    pub message: Option<MessageChoice>,
}

impl MapReading {
    /// Whether anything but the resolution is set.
    fn classifies(&self) -> bool {
        self.free_thresh.is_some() || self.occupied_thresh.is_some() || self.negate
    }

    /// The first classification option set, by its command-line name.
    fn first_classifying_option(&self) -> Option<(&'static str, String)> {
        if let Some(t) = self.free_thresh {
            Some(("--free-thresh", t.to_string()))
        } else if let Some(t) = self.occupied_thresh {
            Some(("--occupied-thresh", t.to_string()))
        } else if self.negate {
            Some(("--negate", "on".into()))
        } else {
            None
        }
    }

    /// The thresholds to read an image with, checked.
    fn thresholds(&self) -> Result<Thresholds> {
        let check = |name: &'static str, value: Option<f64>, default: f64| -> Result<f64> {
            match value {
                None => Ok(default),
                Some(t) if (0.0..=1.0).contains(&t) => Ok(t),
                Some(t) => Err(Error::BadParameter {
                    name,
                    value: t.to_string(),
                    expected: "a number in [0, 1] (an occupancy probability)".into(),
                }),
            }
        };
        let defaults = Thresholds::default();
        let free_thresh = check("--free-thresh", self.free_thresh, defaults.free_thresh)?;
        let occupied_thresh = check(
            "--occupied-thresh",
            self.occupied_thresh,
            defaults.occupied_thresh,
        )?;
        if free_thresh > occupied_thresh {
            let (name, value) = if self.free_thresh.is_some() {
                ("--free-thresh", free_thresh)
            } else {
                ("--occupied-thresh", occupied_thresh)
            };
            let default = match (self.free_thresh, self.occupied_thresh) {
                (Some(_), Some(_)) => "",
                _ => "; the one not given keeps its default",
            };
            return Err(Error::BadParameter {
                name,
                value: value.to_string(),
                expected: format!(
                    "--free-thresh ({free_thresh}) at most --occupied-thresh ({occupied_thresh}){default}"
                ),
            });
        }
        Ok(Thresholds {
            negate: self.negate,
            occupied_thresh,
            free_thresh,
            ..defaults
        })
    }
}

/// Reads the map at `path` as [`load_map`] does, an image without a yaml
/// classified by `reading`. Also returns notes for the command line: an
/// option the map does not use (`--resolution` on a yaml or a MovingAI map,
/// whose own resolution stands).
///
/// # Errors
/// As [`load_map`]; besides, a threshold outside [0, 1] or a free threshold
/// above the occupied one, and a classification option given for a map
/// that is not an image read without a yaml, each naming the option.
pub fn load_map_with(path: &Path, reading: &MapReading) -> Result<(OccupancyGrid, Vec<String>)> {
    let mut options = ReadOptions::default();
    if let Some(r) = reading.resolution {
        let r = oxcover_grid::error::positive("--resolution", r)?;
        if r > oxcover_grid::io::MAX_RESOLUTION {
            return Err(Error::BadParameter {
                name: "--resolution",
                value: r.to_string(),
                expected: "at most 1000 (metres per pixel)".into(),
            });
        }
        options = options.resolution(r);
    }
    options = options.thresholds(reading.thresholds()?);
    if oxcover_rosbag::is_bag(path) {
        return load_bag(path, reading, &options);
    }
    let bag_option = match (&reading.topic, reading.message) {
        (Some(t), _) => Some(("--topic", t.clone())),
        (None, Some(m)) => Some(("--message", m.to_string())),
        (None, None) => None,
    };
    if let Some((name, value)) = bag_option {
        return Err(Error::BadParameter {
            name,
            value,
            expected: format!(
                "a rosbag2 bag (a folder with metadata.yaml, a .mcap or a .db3 file): {} is not one",
                path.display()
            ),
        });
    }
    let format = if reading.resolution.is_some() || reading.classifies() {
        Some(map_format(path)?)
    } else {
        None
    };
    let what = match format {
        Some(MapFormat::RosYaml) => {
            Some("a map_server yaml, whose own fields place and classify its image")
        }
        Some(MapFormat::MovingAi) => Some("a MovingAI map (1 m per cell, `.`, `G`, `S` free)"),
        Some(MapFormat::Image) | None => None,
    };
    if let (Some(what), Some((name, value))) = (what, reading.first_classifying_option()) {
        return Err(Error::BadParameter {
            name,
            value,
            expected: format!("an image read without a yaml: {} is {what}", path.display()),
        });
    }
    let map = read_map(path, &options)?;
    let mut notes = Vec::new();
    if let (Some(what), Some(r)) = (what, reading.resolution) {
        notes.push(format!(
            "--resolution {r} is for images read without a yaml; {} is {what}, at {} m per cell",
            path.display(),
            map.resolution()
        ));
    }
    Ok((map, notes))
}

/// Reads the OccupancyGrid of a bag: `--free-thresh` and
/// `--occupied-thresh` classify its occupancy values; `--negate` is refused
/// and `--resolution` noted, as for a yaml (the message places its cells).
fn load_bag(
    path: &Path,
    reading: &MapReading,
    options: &ReadOptions,
) -> Result<(OccupancyGrid, Vec<String>)> {
    if reading.negate {
        return Err(Error::BadParameter {
            name: "--negate",
            value: "on".into(),
            expected: format!(
                "an image read without a yaml: {} is a rosbag2 bag, whose occupancy values 0..100 are never negated",
                path.display()
            ),
        });
    }
    let map = oxcover_rosbag::read_map(
        path,
        reading.topic.as_deref(),
        reading.message.unwrap_or_default(),
        &options.thresholds,
        options.max_cells,
    )?;
    let notes = reading
        .resolution
        .map(|r| {
            format!(
                "--resolution {r} is for images read without a yaml; {} is a rosbag2 bag, at {} m per cell",
                path.display(),
                map.resolution()
            )
        })
        .into_iter()
        .collect();
    Ok((map, notes))
}
