//! The demo `oxcover` runs with no arguments: `lanes` (room by room, wall
//! loops and straight lanes, the fastest planner by estimated time) on a
//! bundled ROS map (`fixtures/maps/turtlebot_simulator/simple_rooms`, 20 × 15 m
//! at 0.05 m/cell) for a 30 cm robot with a 30 cm tool, written to
//! `./oxcover-demo/` as CSV, SVG, PNG and a JSON report.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use oxcover::grid::io::{ReadOptions, read_ros_yaml_from_bytes};
use oxcover::pipeline::{Outputs, PlanRequest, plan, write_outputs};
use oxcover::report::table;
use oxcover::{DiscRobot, Error, Result};

const YAML: &str = include_str!("../../assets/simple_rooms.yaml");
const IMAGE: &[u8] = include_bytes!("../../assets/simple_rooms.png");
const NAME: &str = "fixtures/maps/turtlebot_simulator/simple_rooms.yaml";

/// Runs the demo, writing into `./oxcover-demo/`.
///
/// # Errors
/// When the output directory or files cannot be written.
pub(crate) fn run() -> Result<()> {
    run_into(Path::new("oxcover-demo"))
}

/// Runs the demo, writing into `dir`.
///
/// # Errors
/// When `dir` or the files cannot be written.
fn run_into(dir: &Path) -> Result<()> {
    let map = read_ros_yaml_from_bytes(Path::new(NAME), YAML, IMAGE, &ReadOptions::default())?;
    let request = PlanRequest::new("lanes", map.resolution())?.robot(DiscRobot::new(0.15, 0.15)?);
    let outcome = plan(&map, &request)?;
    std::fs::create_dir_all(dir).map_err(|e| Error::write(dir, e))?;
    let file = |ext: &str| -> PathBuf { dir.join(format!("simple_rooms_lanes.{ext}")) };
    let (csv, svg, png, json) = (file("csv"), file("svg"), file("png"), file("json"));
    let written = write_outputs(
        &map,
        NAME,
        &request,
        &outcome,
        &Outputs {
            csv: Some(&csv),
            svg: Some(&svg),
            png: Some(&png),
            report: Some(&json),
            bag: None,
        },
    )?;
    let mut out = super::out::stdout();
    let _ = writeln!(
        out,
        "oxcover demo: lanes, room by room, on {NAME}\n  {}x{} cells at {} m, robot radius 0.15 m, tool radius 0.15 m, planned in {:.0} ms\n",
        map.width(),
        map.height(),
        map.resolution(),
        outcome.plan_ms
    );
    let _ = write!(out, "{}", table(&outcome.rows()));
    let _ = writeln!(out);
    for w in written {
        let shown = std::fs::canonicalize(&w).unwrap_or(w);
        let _ = writeln!(out, "wrote {}", shown.display());
    }
    let _ = writeln!(
        out,
        "\nnext: `oxcover --help`, or `oxcover plan <map.yaml> --planner lanes --png plan.png` (`oxcover planners` lists the others)"
    );
    Ok(())
}
