//! `oxcover plan`: a coverage path written as CSV, pictures and a JSON report.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::Result;
use oxcover::grid::{OccupancyGrid, Point};
use oxcover::pipeline::{Outputs, PlanRequest, coverage_notes, plan, planner, write_outputs};
use oxcover::planners::{PlannerOptions, Start};
use oxcover::report::table;

use super::args::{
    ANY, MCAP, OnOff, Output, PNG, RobotArgs, SVG, TimeArgs, asked, check_outputs, clearance_of,
    load, note_later, parse_start, robot_of,
};
use super::targets::TargetArgs;

#[derive(Debug, clap::Args)]
pub(crate) struct PlanArgs {
    /// Map: .yaml, .pgm, .png, .bmp, .map, or a rosbag2 bag (folder, .mcap, .db3).
    pub(crate) map: PathBuf,
    /// Planner name (see `oxcover planners`).
    #[arg(long, value_name = "NAME")]
    pub(crate) planner: String,
    #[command(flatten)]
    pub(crate) robot: RobotArgs,
    /// Start position in metres [default: first admissible cell, row-major].
    #[arg(long, value_name = "X,Y", value_parser = parse_start, allow_hyphen_values = true)]
    pub(crate) start: Option<Point>,
    /// Seed for randomised planners.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub(crate) seed: u64,
    /// Append a pass along obstacle boundaries covering what the planner missed.
    #[arg(long, value_enum, value_name = "on|off", default_value_t = OnOff::On)]
    pub(crate) boundary_pass: OnOff,
    /// Plan room by room (the rooms of `oxcover segment`, cut at doors; each
    /// finished before the next, in the order of least transit time); off
    /// plans the whole map at once with the papers' nearest-first boundary pass
    /// (on, each room's pass is a straightened tour ending towards the next
    /// room or the nearest-first pass, both tightened for time, whichever is
    /// faster, and then the whole path is tightened for time, each room's
    /// waypoints kept in their room; a map with one room is planned at once).
    #[arg(long, value_enum, value_name = "on|off", default_value_t = OnOff::On)]
    pub(crate) rooms: OnOff,
    #[command(flatten)]
    pub(crate) time: TimeArgs,
    #[command(flatten)]
    pub(crate) targets: TargetArgs,
    /// Sweep angle in degrees for boustrophedon, trapezoidal and lanes (lanes
    /// along it, counter-clockwise from the map's x axis) [default: the
    /// fastest of 0, 15, ..., 165; for lanes also the walls' directions, per
    /// region].
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub(crate) sweep_angle: Option<f64>,
    /// Path file to write (CSV, header x,y).
    #[arg(long, value_name = "PATH.csv")]
    pub(crate) out: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    pub(crate) png: Option<PathBuf>,
    /// JSON report to write (metrics, planner, parameters, plan_ms).
    #[arg(long, value_name = "F.json")]
    pub(crate) report: Option<PathBuf>,
    /// ROS 2 bag to write (MCAP: /map, /coverage_path stamped by the time
    /// model, /rooms, /coverage_targets), for `ros2 bag play` and Foxglove.
    #[arg(long, value_name = "F.mcap")]
    pub(crate) bag: Option<PathBuf>,
    /// Refuse a map whose plan is estimated to need more memory than this
    /// (e.g. 8G, 512M; `none` for no limit) [default: 3/4 of the machine's
    /// memory].
    #[arg(long, value_name = "SIZE")]
    pub(crate) memory_limit: Option<String>,
}

/// The outputs `plan` would write, with their options.
pub(crate) fn plan_outputs(a: &PlanArgs) -> Vec<Output<'_>> {
    asked([
        ("--out", a.out.as_deref(), ANY),
        ("--svg", a.svg.as_deref(), SVG),
        ("--png", a.png.as_deref(), PNG),
        ("--report", a.report.as_deref(), ANY),
        ("--bag", a.bag.as_deref(), MCAP),
    ])
}

/// The map and the plan request the `plan` options describe.
pub(crate) fn map_and_request(a: &PlanArgs) -> Result<(OccupancyGrid, PlanRequest)> {
    map_and_request_with(a, |_, _| 0.0)
}

/// [`map_and_request`] with the clearance `default` gives for the map
/// (and the robot radius) when `--clearance` is not given.
pub(crate) fn map_and_request_with(
    a: &PlanArgs,
    default: impl FnOnce(&OccupancyGrid, f64) -> f64,
) -> Result<(OccupancyGrid, PlanRequest)> {
    let mut inputs = vec![a.map.as_path()];
    inputs.extend(a.targets.inputs());
    check_outputs(&inputs, &plan_outputs(a))?;
    let map = load(&a.map, &a.robot.map)?;
    let robot = robot_of(&a.robot, &map)?;
    let clearance = match a.robot.clearance {
        Some(_) => clearance_of(&a.robot, 0.0)?,
        None => default(&map, robot.robot_radius),
    };
    let time = a.time.model()?;
    let targets = a.targets.targets()?;
    let start = match a.start {
        Some(p) => Start::At(p),
        None => match targets.default_start(&map, robot.robot_radius + clearance)? {
            Some((p, note)) => {
                note_later(note);
                Start::At(p)
            }
            None => Start::First,
        },
    };
    let mut options = PlannerOptions::new();
    options.sweep_angle_deg = a.sweep_angle;
    let request = PlanRequest {
        planner: planner(&a.planner, &options)?,
        robot,
        start,
        seed: a.seed,
        boundary_pass: a.boundary_pass == OnOff::On,
        rooms: a.rooms == OnOff::On,
        time,
        memory_limit: match a.memory_limit.as_deref() {
            None => oxcover::memory::default_limit(),
            Some("none") => None,
            Some(size) => Some(oxcover::memory::parse_size(size)?),
        },
        targets,
        clearance,
    };
    request.check_memory(&map, &a.map.display().to_string())?;
    Ok((map, request))
}

pub(crate) fn cmd_plan(a: &PlanArgs) -> Result<()> {
    let (map, request) = map_and_request(a)?;
    let outcome = plan(&map, &request)?;
    let name = a.map.display().to_string();
    let written = write_outputs(
        &map,
        &name,
        &request,
        &outcome,
        &Outputs {
            csv: a.out.as_deref(),
            svg: a.svg.as_deref(),
            png: a.png.as_deref(),
            report: a.report.as_deref(),
            bag: a.bag.as_deref(),
        },
    )?;
    let mut out = super::out::stdout();
    let _ = writeln!(
        out,
        "{} on {} ({}x{} cells, {} m/cell{}): {} waypoints in {:.0} ms",
        request.planner.name(),
        name,
        map.width(),
        map.height(),
        map.resolution(),
        outcome.room_units.map_or_else(String::new, |n| format!(
            ", {n} room{}",
            if n == 1 { "" } else { "s" }
        )),
        outcome.points.len(),
        outcome.plan_ms
    );
    let _ = write!(out, "{}", table(&outcome.rows()));
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    let default_start = a.start.is_none() && a.targets.done.is_none();
    // With a target, the coverable cells outside it are not missing.
    let notes = if request.targets.narrows() {
        Vec::new()
    } else {
        coverage_notes(&map, &outcome.evaluation.problem, default_start)
    };
    let lost = outcome.clearance_lost_cells.filter(|&n| n > 0).map(|n| {
        let res = map.resolution();
        format!(
            "the clearance of {} m puts {n} coverable cells ({:.2} m2) out of the tool's reach; they are not counted",
            request.clearance,
            n as f64 * res * res
        )
    });
    for note in outcome.notes.iter().cloned().chain(lost).chain(notes) {
        let _ = writeln!(std::io::stderr(), "note: {note}");
    }
    Ok(())
}
