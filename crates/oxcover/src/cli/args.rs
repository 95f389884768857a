//! Arguments and loaders shared by several commands: robot radii, on/off
//! switches, the start position, map loading.

use std::path::Path;

use clap::ValueEnum;
use oxcover::grid::{DiscRobot, OccupancyGrid, Point};
use oxcover::planners::TimeModel;
use oxcover::{Error, Result};

pub(crate) use oxcover::output::{ANY, Output, PICTURE, PNG, SVG, YAML, asked, check_outputs};
pub(crate) use oxcover::pipeline::load_map as load;

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
    /// Resolution in m/cell for images read without a yaml [default: 1.0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub(crate) resolution: Option<f64>,
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
