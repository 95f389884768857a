//! Arguments and loaders shared by several commands: robot radii, on/off
//! switches, the start position, map loading.

use std::path::Path;
use std::sync::{Mutex, PoisonError};

use clap::ValueEnum;
use oxcover::grid::{DiscRobot, OccupancyGrid, Point};
use oxcover::planners::TimeModel;
use oxcover::{Error, Result};

pub(crate) use oxcover::output::{
    ANY, MCAP, Output, PICTURE, PNG, SVG, YAML, asked, check_outputs,
};
use oxcover::pipeline::{MapReading, load_map_with};
use oxcover::rosbag::MessageChoice;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum OnOff {
    On,
    Off,
}

#[derive(Debug, clap::Args)]
pub(crate) struct RobotArgs {
    /// Robot body radius in metres [default: 0].
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub(crate) robot_radius: Option<f64>,
    /// Tool (cleaning/sensing) radius in metres [default: resolution / 2].
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub(crate) tool_radius: Option<f64>,
    /// Keep the path M metres further from walls, keep-out areas and
    /// virtual walls than the robot radius requires (a real robot tracks
    /// its path within a centimetre or two) [default: 0; simulate: the
    /// robot description's tracking margin].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub(crate) clearance: Option<f64>,
    #[command(flatten)]
    pub(crate) map: MapArgs,
}

/// How an image read without a yaml is placed and classified (a yaml's own
/// fields govern its image; a MovingAI map is 1 m per cell).
#[derive(Debug, clap::Args)]
pub(crate) struct MapArgs {
    /// Resolution in m/cell for images read without a yaml [default: 1.0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub(crate) resolution: Option<f64>,
    /// For images read without a yaml: free where the occupancy
    /// p = (255 - v) / 255 is below this (map_server's free_thresh; e.g.
    /// 0.0196 reads only grey above 250 as free) [default: 0.196].
    #[arg(long, value_name = "P", allow_negative_numbers = true)]
    pub(crate) free_thresh: Option<f64>,
    /// For images read without a yaml: occupied where p is above this
    /// (map_server's occupied_thresh; between the two is unknown, never
    /// free) [default: 0.65].
    #[arg(long, value_name = "P", allow_negative_numbers = true)]
    pub(crate) occupied_thresh: Option<f64>,
    /// For images read without a yaml: dark is free, p = v / 255
    /// (map_server's negate: 1).
    #[arg(long)]
    pub(crate) negate: bool,
    /// For a rosbag2 bag: the nav_msgs/msg/OccupancyGrid topic to read
    /// [default: the bag's only one].
    #[arg(long, value_name = "NAME")]
    pub(crate) topic: Option<String>,
    /// For a rosbag2 bag: which message of the topic, `first`, `last` or
    /// its number from 0 in log-time order [default: last].
    #[arg(long, value_name = "last|first|N", value_parser = parse_message)]
    pub(crate) message: Option<MessageChoice>,
}

fn parse_message(s: &str) -> std::result::Result<MessageChoice, String> {
    s.parse()
}

impl MapArgs {
    /// The pipeline's reading options.
    pub(crate) fn reading(&self) -> MapReading {
        MapReading {
            resolution: self.resolution,
            free_thresh: self.free_thresh,
            occupied_thresh: self.occupied_thresh,
            negate: self.negate,
            topic: self.topic.clone(),
            message: self.message,
        }
    }
}

/// Notes of the command under way (an option the map does not use), kept
/// until it has succeeded: a failed command's stderr stays its one error
/// line.
static NOTES: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Takes the notes kept so far ([`load`]'s), leaving none.
pub(crate) fn take_notes() -> Vec<String> {
    std::mem::take(&mut *NOTES.lock().unwrap_or_else(PoisonError::into_inner))
}

/// Reads the map as `args` say; the reader's notes (an option the map does
/// not use) are kept for the end of a command that succeeds.
pub(crate) fn load(path: &Path, args: &MapArgs) -> Result<OccupancyGrid> {
    let (map, notes) = load_map_with(path, &args.reading())?;
    NOTES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .extend(notes);
    Ok(map)
}

/// Keeps `note` (if any) for the end of a command that succeeds.
pub(crate) fn note_later(note: Option<String>) {
    NOTES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .extend(note);
}

/// Speeds for the estimated time (`est_time_s`, and what planners optimise).
#[derive(Debug, clap::Args)]
pub(crate) struct TimeArgs {
    /// Linear speed in m/s for estimated time.
    #[arg(
        long,
        value_name = "V",
        default_value_t = 0.3,
        allow_negative_numbers = true
    )]
    pub(crate) speed: f64,
    /// Turning rate in rad/s for estimated time.
    #[arg(
        long,
        value_name = "W",
        default_value_t = 0.52,
        allow_negative_numbers = true
    )]
    pub(crate) turn_rate: f64,
}

impl TimeArgs {
    pub(crate) fn model(&self) -> Result<TimeModel> {
        Ok(TimeModel::new(self.speed, self.turn_rate)?)
    }
}

pub(crate) fn parse_start(s: &str) -> std::result::Result<Point, String> {
    let err = || format!("expected X,Y in metres (e.g. 1.5,-2), got `{s}`");
    let (x, y) = s.split_once(',').ok_or_else(err)?;
    let x: f64 = x.trim().parse().map_err(|_| err())?;
    let y: f64 = y.trim().parse().map_err(|_| err())?;
    if x.is_finite() && y.is_finite() {
        Ok(Point::new(x, y))
    } else {
        Err(format!("expected finite X,Y in metres, got `{s}`"))
    }
}

pub(crate) fn robot_of(args: &RobotArgs, map: &OccupancyGrid) -> Result<DiscRobot> {
    let res = map.resolution();
    Ok(DiscRobot::new(
        args.robot_radius.unwrap_or(0.0),
        args.tool_radius.unwrap_or(res / 2.0),
    )?)
}

/// The robot whose admissible cells the metrics judge: the body radius
/// grown by `--clearance` (the contract: admissible means at least R + M).
pub(crate) fn admissible_robot(args: &RobotArgs, map: &OccupancyGrid) -> Result<DiscRobot> {
    let r = robot_of(args, map)?;
    let m = clearance_of(args, 0.0)?;
    Ok(DiscRobot::new(r.robot_radius + m, r.tool_radius)?)
}

/// `--clearance`, or `default` when not given.
pub(crate) fn clearance_of(args: &RobotArgs, default: f64) -> Result<f64> {
    let m = args.clearance.unwrap_or(default);
    if m.is_finite() && m >= 0.0 {
        Ok(m)
    } else {
        Err(Error::BadParameter {
            name: "--clearance",
            value: m.to_string(),
            expected: "a finite distance of at least 0 metres".into(),
        })
    }
}

pub(crate) fn map_rows(map: &OccupancyGrid) -> Vec<(String, String)> {
    let c = map.counts();
    vec![
        ("size".into(), format!("{}x{}", map.width(), map.height())),
        ("resolution".into(), format!("{} m", map.resolution())),
        ("free".into(), c.free.to_string()),
        ("occupied".into(), c.occupied.to_string()),
        ("unknown".into(), c.unknown.to_string()),
    ]
}

pub(crate) fn read_ron<T: serde::de::DeserializeOwned>(
    path: &Path,
    what: &'static str,
) -> Result<T> {
    let text = oxcover::grid::io::limited::read_limited_string(
        path,
        oxcover::grid::io::limited::MAX_TEXT_BYTES,
    )
    .map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    ron::from_str(&text).map_err(|e| Error::BadParameter {
        name: what,
        value: path.display().to_string(),
        expected: format!("a valid {what} file ({e})"),
    })
}
