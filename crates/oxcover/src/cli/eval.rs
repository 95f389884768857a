//! `oxcover eval`: the contract's metrics of a path file.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::path::read_csv;
use oxcover::targets::evaluate_targets;
use oxcover::{Error, Result};

use super::args::{RobotArgs, TimeArgs, admissible_robot, load};
use super::targets::TargetArgs;

#[derive(Debug, clap::Args)]
pub(crate) struct EvalArgs {
    /// Map: .yaml, .pgm, .png, .bmp, .map, or a rosbag2 bag (folder, .mcap, .db3).
    pub(crate) map: PathBuf,
    /// Path file (CSV with header x,y).
    pub(crate) path: PathBuf,
    #[command(flatten)]
    pub(crate) robot: RobotArgs,
    #[command(flatten)]
    pub(crate) time: TimeArgs,
    #[command(flatten)]
    pub(crate) targets: TargetArgs,
}

pub(crate) fn cmd_eval(a: &EvalArgs) -> Result<()> {
    let map = load(&a.map, &a.robot.map)?;
    let robot = admissible_robot(&a.robot, &map)?;
    let time = a.time.model()?;
    let points = read_csv(&a.path)?;
    let targets = a.targets.targets()?;
    let ev = evaluate_targets(&map, robot, &points, &time, &targets)?;
    let json = serde_json::to_string_pretty(&ev.metrics)
        .map_err(|e| Error::Internal(format!("metrics serialisation failed: {e}")))?;
    let _ = writeln!(super::out::stdout(), "{json}");
    Ok(())
}
