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

/// An output a command will write: its option, its path, and the file name
/// endings its format allows (empty: any name).
pub(crate) type Output<'a> = (&'static str, &'a Path, &'static [&'static str]);

/// Any file name.
pub(crate) const ANY: &[&str] = &[];
/// An SVG picture.
pub(crate) const SVG: &[&str] = &["svg"];
/// A PNG picture.
pub(crate) const PNG: &[&str] = &["png"];
/// A picture in the format its name ends in.
pub(crate) const PICTURE: &[&str] = &["svg", "png"];
/// A ROS map (its image is written beside it).
pub(crate) const YAML: &[&str] = &["yaml"];

/// The outputs among `candidates` that were asked for.
pub(crate) fn asked<'a, const N: usize>(
    candidates: [(&'static str, Option<&'a Path>, &'static [&'static str]); N],
) -> Vec<Output<'a>> {
    candidates
        .into_iter()
        .filter_map(|(f, p, e)| p.map(|p| (f, p, e)))
        .collect()
}

/// Refuses, before any work, an output that could not be written or would
/// destroy a file: its folder missing, not writable or not a folder; the
/// path a folder; a file name ending other than its format's; one of the
/// inputs or another output (`--out f.csv --report f.csv`, `plan m.pgm
/// --out m.pgm`: the second write would silently destroy the first file).
pub(crate) fn check_outputs(inputs: &[&Path], outputs: &[Output<'_>]) -> Result<()> {
    let ins: Vec<std::path::PathBuf> = inputs.iter().map(|p| resolved(p)).collect();
    let mut seen: Vec<(&'static str, std::path::PathBuf)> = Vec::new();
    for &(flag, out, endings) in outputs {
        let bad = |expected: String| Error::BadParameter {
            name: flag,
            value: out.display().to_string(),
            expected,
        };
        let r = resolved(out);
        if let Some(i) = ins.iter().position(|x| *x == r) {
            return Err(bad(format!(
                "a file other than the input {}",
                inputs[i].display()
            )));
        }
        let stream = std::fs::metadata(out).is_ok_and(|m| !m.is_file() && !m.is_dir());
        if let Some((other, _)) = seen.iter().find(|(_, x)| *x == r && !stream) {
            return Err(bad(format!("a file other than the one {other} writes")));
        }
        let ext = out
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        if !endings.is_empty() && !endings.contains(&ext.as_str()) {
            return Err(bad(format!("a file name ending in {}", one_of(endings))));
        }
        if out.is_dir() {
            return Err(bad("a file name, not a folder".into()));
        }
        let folder = out
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or_else(|| Path::new("."));
        if !folder.is_dir() {
            return Err(bad(format!(
                "a file in an existing folder ({} does not exist)",
                folder.display()
            )));
        }
        if !writable(folder) {
            return Err(bad(format!(
                "a file in a folder this user may write ({} is not writable)",
                folder.display()
            )));
        }
        seen.push((flag, r));
    }
    Ok(())
}

/// `.a`, `.a or .b`, `.a, .b or .c`.
fn one_of(endings: &[&str]) -> String {
    let names: Vec<String> = endings.iter().map(|e| format!(".{e}")).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// Whether a file can be created in `folder` (tried with a probe file that
/// is removed at once: permission bits do not tell about read-only mounts).
fn writable(folder: &Path) -> bool {
    let probe = folder.join(format!(".oxcover-probe-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            true
        }
        // Left over by a killed run of this very process id: still writable.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => true,
        Err(_) => false,
    }
}
