//! `oxcover eval`: the contract's metrics of a path file.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::metrics::evaluate;
use oxcover::path::read_csv;
use oxcover::{Error, Result};

use super::args::{RobotArgs, TimeArgs, load, robot_of};

#[derive(Debug, clap::Args)]
pub(crate) struct EvalArgs {
    /// Map file.
    pub(crate) map: PathBuf,
    /// Path file (CSV with header x,y).
    pub(crate) path: PathBuf,
    #[command(flatten)]
    pub(crate) robot: RobotArgs,
    #[command(flatten)]
    pub(crate) time: TimeArgs,
}

pub(crate) fn cmd_eval(a: &EvalArgs) -> Result<()> {
    let map = load(&a.map, &a.robot.map)?;
    let robot = robot_of(&a.robot, &map)?;
    let time = a.time.model()?;
    let points = read_csv(&a.path)?;
    let ev = evaluate(&map, robot, &points, &time)?;
    let json = serde_json::to_string_pretty(&ev.metrics)
        .map_err(|e| Error::Internal(format!("metrics serialisation failed: {e}")))?;
    let _ = writeln!(super::out::stdout(), "{json}");
    Ok(())
}
