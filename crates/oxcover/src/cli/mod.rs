//! The `oxcover` command line (contract: `plan`, `eval`, `render`, `info`,
//! `planners`; beyond it: `simulate`, `explore`, `map-from-camera`; with no
//! command, the demo). One module per command, each a thin layer over the
//! library: it parses arguments, calls one library function and prints.
//!
//! Exit status: 0 success; 2 bad input or usage, with one line on stderr naming
//! the file, field or value; 1 an internal fault. Clap's multi-line usage
//! errors are folded into one line; a panic (always a bug) is reported as one
//! line and exit 1, never as a backtrace.

mod args;
mod camera;
mod demo;
mod eval;
mod explore;
mod info;
mod out;
mod plan;
mod render;
mod segment;
mod simulate;
mod targets;

use std::io::Write as _;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use camera::MapFromCameraArgs;
use eval::EvalArgs;
use explore::ExploreArgs;
use info::InfoArgs;
use plan::PlanArgs;
use render::RenderArgs;
use segment::SegmentArgs;
use simulate::SimulateArgs;

#[derive(Debug, Parser)]
#[command(
    name = "oxcover",
    version,
    about = "Complete coverage path planning on occupancy grids.",
    long_about = "Complete coverage path planning on occupancy grids.\n\n\
        Maps: ROS map_server yaml (+ PGM/PNG/BMP), plain PGM/PNG/BMP images, MovingAI .map.\n\
        Units are metres in the ROS map frame. Run without a command for a demo on a bundled map.\n\
        Exit status: 0 ok, 2 bad input or usage, 1 internal fault."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Plan a coverage path and write it as CSV, pictures and a JSON report.
    Plan(PlanArgs),
    /// Score a path file: print the contract's metrics as one JSON object.
    Eval(EvalArgs),
    /// Draw a map, optionally with a path, as SVG or PNG.
    Render(RenderArgs),
    /// Describe a map: size, frame, cell counts, components, default start.
    Info(InfoArgs),
    /// List the planners.
    Planners,
    /// Cover an unknown polygonal world (RON) with the sensor-based planner
    /// `sensor-bcd`: range rays, critical points, an incremental Reeb graph.
    /// Writes the executed path (CSV with a state column), the graph (JSON or
    /// RON), the rasterised map, pictures and a JSON report.
    Explore(ExploreArgs),
    /// Build an occupancy grid from floor-camera images (Pavlíček 2002): calibrated
    /// camera and HSV profile (RON), PNG images with robot poses (CSV
    /// image,x,y,theta), written as a ROS map that `plan` reads.
    MapFromCamera(MapFromCameraArgs),
    /// Segment a map into rooms: room labels, the doors between rooms, a
    /// picture with one colour per room, JSON with room areas and door
    /// positions in metres.
    Segment(SegmentArgs),
    /// Plan, then execute the plan with a simulated differential-drive robot
    /// (time law, tracking controller, wheel limits, odometry noise) and score
    /// the EXECUTED trajectory.
    Simulate(SimulateArgs),
}

/// Runs the command line with the process arguments; returns the exit status.
#[must_use]
pub(crate) fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let msg = info.to_string().replace('\n', " ");
        let _ = writeln!(std::io::stderr(), "oxcover: internal error: {msg}");
    }));
    // SIGINT, SIGTERM or SIGHUP: remove the outputs being written (none is
    // left half-written), then exit as a process killed by the signal would
    // report it (128 + 2; the handler cannot tell the signals apart).
    let _ = ctrlc::set_handler(|| {
        oxcover::output::abandon();
        let _ = writeln!(std::io::stderr(), "oxcover: interrupted, no output written");
        std::process::exit(130);
    });
    let code = std::panic::catch_unwind(|| run(std::env::args_os())).unwrap_or(1);
    ExitCode::from(code)
}

/// Runs the command line on `args` (first item: program name); returns the exit status.
pub(crate) fn run<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return clap_error(&e),
    };
    let _ = args::take_notes();
    let result = match cli.command {
        None => demo::run(),
        Some(Command::Plan(a)) => plan::cmd_plan(&a),
        Some(Command::Eval(a)) => eval::cmd_eval(&a),
        Some(Command::Render(a)) => render::cmd_render(&a),
        Some(Command::Info(a)) => info::cmd_info(&a),
        Some(Command::Planners) => {
            info::cmd_planners();
            Ok(())
        }
        Some(Command::Simulate(a)) => simulate::cmd_simulate(&a),
        Some(Command::Segment(a)) => segment::cmd_segment(&a),
        Some(Command::Explore(a)) => explore::cmd_explore(&a),
        Some(Command::MapFromCamera(a)) => camera::cmd_map_from_camera(&a),
    };
    let notes = args::take_notes();
    match result {
        Ok(()) => match out::failure() {
            None => {
                for note in notes {
                    let _ = writeln!(std::io::stderr(), "note: {note}");
                }
                0
            }
            Some(e) => {
                let _ = writeln!(
                    std::io::stderr(),
                    "oxcover: error: could not write to standard output: {e}"
                );
                1
            }
        },
        Err(e) => {
            let _ = writeln!(
                std::io::stderr(),
                "oxcover: error: {}",
                e.to_string().replace('\n', " ")
            );
            e.exit_code()
        }
    }
}

fn clap_error(e: &clap::Error) -> u8 {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = write!(std::io::stdout(), "{e}");
            0
        }
        _ => {
            let text = e.render().to_string();
            let line: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .filter(|l| !l.is_empty())
                .collect();
            let line = line.join(" ");
            let line = line.strip_prefix("error: ").unwrap_or(&line);
            let _ = writeln!(std::io::stderr(), "oxcover: error: {line} (see --help)");
            2
        }
    }
}
