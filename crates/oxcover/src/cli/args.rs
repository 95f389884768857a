//! Arguments and loaders shared by several commands: robot radii, on/off
//! switches, the start position, map loading.

use std::path::Path;

use clap::ValueEnum;
use oxcover::grid::io::{ReadOptions, read_map};
use oxcover::grid::{DiscRobot, OccupancyGrid, Point};
use oxcover::planners::TimeModel;
use oxcover::{Error, Result};

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

pub(crate) fn read_options(resolution: Option<f64>) -> Result<ReadOptions> {
    let mut o = ReadOptions::default();
    if let Some(r) = resolution {
        let r = oxcover::grid::error::positive("--resolution", r)?;
        if r > oxcover::grid::io::MAX_RESOLUTION {
            return Err(Error::BadParameter {
                name: "--resolution",
                value: r.to_string(),
                expected: "at most 1000 (metres per pixel)".into(),
            });
        }
        o = o.resolution(r);
    }
    Ok(o)
}

pub(crate) fn load(map: &Path, resolution: Option<f64>) -> Result<OccupancyGrid> {
    Ok(read_map(map, &read_options(resolution)?)?)
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

/// A path as it will be opened: canonical when it exists, else its
/// existing folder made canonical with the file name added.
fn resolved(p: &Path) -> std::path::PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let parent = p.parent().filter(|d| !d.as_os_str().is_empty());
    let dir = parent.map_or_else(|| Path::new(".").canonicalize(), Path::canonicalize);
    match (dir, p.file_name()) {
        (Ok(d), Some(f)) => d.join(f),
        _ => p.to_path_buf(),
    }
}

/// Refuses, before any work, an output that is one of the inputs or
/// another output (`--out f.csv --report f.csv`, `plan m.pgm --out m.pgm`):
/// the second write would silently destroy the first file.
pub(crate) fn distinct_outputs(inputs: &[&Path], outputs: &[(&'static str, &Path)]) -> Result<()> {
    let ins: Vec<std::path::PathBuf> = inputs.iter().map(|p| resolved(p)).collect();
    let mut seen: Vec<(&'static str, std::path::PathBuf)> = Vec::new();
    for &(flag, out) in outputs {
        let r = resolved(out);
        if let Some(i) = ins.iter().position(|x| *x == r) {
            return Err(Error::BadParameter {
                name: flag,
                value: out.display().to_string(),
                expected: format!("a file other than the input {}", inputs[i].display()),
            });
        }
        if let Some((other, _)) = seen.iter().find(|(_, x)| *x == r) {
            return Err(Error::BadParameter {
                name: flag,
                value: out.display().to_string(),
                expected: format!("a file other than the one {other} writes"),
            });
        }
        seen.push((flag, r));
    }
    Ok(())
}
