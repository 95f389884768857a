//! The `oxcover` command line (contract: `plan`, `eval`, `render`, `info`,
//! `planners`; with no command, the demo).
//!
//! Exit status: 0 success; 2 bad input or usage, with one line on stderr naming
//! the file, field or value; 1 an internal fault. Clap's multi-line usage
//! errors are folded into one line; a panic (always a bug) is reported as one
//! line and exit 1, never as a backtrace.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::{DiscRobot, OccupancyGrid, Point, components4};

use crate::demo;
use crate::error::{Error, Result};
use crate::metrics::{MetricParams, evaluate};
use crate::path::{read_csv, write_csv};
use crate::planner::{PlanRequest, plan, planners};
use crate::render::{Scene, render_to_file};
use crate::report::{PlanParameters, PlanReport, metric_rows, plan_rows, table};

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
    /// Build an occupancy grid from floor-camera images (seed 004): calibrated
    /// camera and HSV profile (RON), PNG images with robot poses (CSV
    /// image,x,y,theta), written as a ROS map that `plan` reads.
    MapFromCamera(MapFromCameraArgs),
    /// Plan, then execute the plan with a simulated differential-drive robot
    /// (time law, tracking controller, wheel limits, odometry noise) and score
    /// the EXECUTED trajectory.
    Simulate(SimulateArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ControllerArg {
    Kanayama,
    Klancar,
}

#[derive(Debug, clap::Args)]
struct SimulateArgs {
    #[command(flatten)]
    plan: PlanArgs,
    /// Robot description (RON, see fixtures/robots) [default: the bundled floor cleaner].
    #[arg(long, value_name = "F.ron")]
    robot_spec: Option<PathBuf>,
    /// Tracking controller.
    #[arg(long, value_enum, default_value_t = ControllerArg::Klancar)]
    controller: ControllerArg,
    /// Control step in seconds.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 0.02,
        allow_negative_numbers = true
    )]
    dt: f64,
    /// Odometry noise: relative wheel-speed error per step (standard deviation).
    #[arg(
        long,
        value_name = "SIGMA",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    odometry_noise: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum OnOff {
    On,
    Off,
}

#[derive(Debug, clap::Args)]
struct RobotArgs {
    /// Robot body radius in metres [default: 0].
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    robot_radius: Option<f64>,
    /// Tool (cleaning/sensing) radius in metres [default: resolution / 2].
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    tool_radius: Option<f64>,
    /// Resolution in m/cell for images read without a yaml [default: 1.0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    resolution: Option<f64>,
}

#[derive(Debug, clap::Args)]
struct PlanArgs {
    /// Map file (.yaml, .pgm, .png, .bmp or .map).
    map: PathBuf,
    /// Planner name (see `oxcover planners`).
    #[arg(long, value_name = "NAME")]
    planner: String,
    #[command(flatten)]
    robot: RobotArgs,
    /// Start position in metres [default: first admissible cell, row-major].
    #[arg(long, value_name = "X,Y", value_parser = parse_start, allow_hyphen_values = true)]
    start: Option<Point>,
    /// Seed for randomised planners.
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// Append a pass along obstacle boundaries covering what the planner missed.
    #[arg(long, value_enum, value_name = "on|off", default_value_t = OnOff::On)]
    boundary_pass: OnOff,
    /// Sweep angle in degrees for boustrophedon and trapezoidal (lanes along it,
    /// counter-clockwise from the map's x axis) [default: best of 0, 15, ..., 165].
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    sweep_angle: Option<f64>,
    /// Path file to write (CSV, header x,y).
    #[arg(long, value_name = "PATH.csv")]
    out: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    png: Option<PathBuf>,
    /// JSON report to write (metrics, planner, parameters, plan_ms).
    #[arg(long, value_name = "F.json")]
    report: Option<PathBuf>,
}

#[derive(Debug, clap::Args)]
struct ExploreArgs {
    /// World file (.ron: boundary, polygons, discs, rectangles; see fixtures/worlds).
    world: PathBuf,
    /// Robot body radius in metres.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 0.2,
        allow_negative_numbers = true
    )]
    robot_radius: f64,
    /// Tool radius in metres; laps are two tool radii apart.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 0.25,
        allow_negative_numbers = true
    )]
    tool_radius: f64,
    /// Distance kept from sensed boundaries beyond the body, in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 0.04,
        allow_negative_numbers = true
    )]
    margin: f64,
    /// Range rays in the ring.
    #[arg(long, value_name = "N", default_value_t = 180)]
    rays: usize,
    /// Longest range reading in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 3.0,
        allow_negative_numbers = true
    )]
    max_range: f64,
    /// Range noise: standard deviation in metres.
    #[arg(
        long,
        value_name = "SD",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    noise: f64,
    /// Seed of the range noise.
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// Start position in metres [default: the world file's `start`].
    #[arg(long, value_name = "X,Y", value_parser = parse_start, allow_hyphen_values = true)]
    start: Option<Point>,
    /// Executed path to write (CSV: x,y,state).
    #[arg(long, value_name = "PATH.csv")]
    out: Option<PathBuf>,
    /// Discovered Reeb graph to write (.json or .ron).
    #[arg(long, value_name = "G.json|G.ron")]
    graph: Option<PathBuf>,
    /// The world rasterised as a ROS map (yaml, with its PGM beside it).
    #[arg(long, value_name = "MAP.yaml")]
    map: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    png: Option<PathBuf>,
    /// JSON report to write.
    #[arg(long, value_name = "F.json")]
    report: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum VisibilityArg {
    Product,
    Bayes,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum FusionArg {
    Paper,
    Discounted,
}

#[derive(Debug, clap::Args)]
struct MapFromCameraArgs {
    /// Calibrated camera (RON: width, height, distortion, projection).
    #[arg(long, value_name = "CAM.ron")]
    camera: PathBuf,
    /// HSV probability profile (RON: bins, free, occ).
    #[arg(long, value_name = "PROFILE.ron")]
    profile: PathBuf,
    /// Poses: CSV with header image,x,y,theta (image paths relative to it).
    #[arg(long, value_name = "POSES.csv")]
    poses: PathBuf,
    /// Map to write (ROS yaml, PGM beside it).
    #[arg(long, value_name = "MAP.yaml")]
    out: PathBuf,
    /// Cell size in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 0.05,
        allow_negative_numbers = true
    )]
    resolution: f64,
    /// Farthest floor distance read from an image, in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 3.0,
        allow_negative_numbers = true
    )]
    range: f64,
    /// How visibility is accumulated along rays from the camera.
    #[arg(long, value_enum, default_value_t = VisibilityArg::Product)]
    visibility: VisibilityArg,
    /// How visibility enters the grid: `paper` (hidden cells read occupied)
    /// or `discounted` (hidden cells tell nothing).
    #[arg(long, value_enum, default_value_t = FusionArg::Discounted)]
    fusion: FusionArg,
    /// Map extent in metres [default: the poses' box grown by the range].
    #[arg(long, value_name = "XMIN,YMIN,XMAX,YMAX", allow_hyphen_values = true)]
    extent: Option<String>,
    /// PNG picture of the map to write.
    #[arg(long, value_name = "F.png")]
    png: Option<PathBuf>,
}

#[derive(Debug, clap::Args)]
struct EvalArgs {
    /// Map file.
    map: PathBuf,
    /// Path file (CSV with header x,y).
    path: PathBuf,
    #[command(flatten)]
    robot: RobotArgs,
}

#[derive(Debug, clap::Args)]
struct RenderArgs {
    /// Map file.
    map: PathBuf,
    /// Optional path file to draw (with its coverage).
    path: Option<PathBuf>,
    /// Output picture, .svg or .png.
    #[arg(long, value_name = "F.svg|F.png")]
    out: PathBuf,
    #[command(flatten)]
    robot: RobotArgs,
}

#[derive(Debug, clap::Args)]
struct InfoArgs {
    /// Map file.
    map: PathBuf,
    /// Resolution in m/cell for images read without a yaml [default: 1.0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    resolution: Option<f64>,
}

fn parse_start(s: &str) -> std::result::Result<Point, String> {
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

/// Runs the command line with the process arguments; returns the exit status.
#[must_use]
pub fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let msg = info.to_string().replace('\n', " ");
        let _ = writeln!(std::io::stderr(), "oxcover: internal error: {msg}");
    }));
    let code = std::panic::catch_unwind(|| run(std::env::args_os())).unwrap_or(1);
    ExitCode::from(code)
}

/// Runs the command line on `args` (first item: program name); returns the exit status.
pub fn run<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return clap_error(&e),
    };
    let result = match cli.command {
        None => demo::run(),
        Some(Command::Plan(a)) => cmd_plan(&a),
        Some(Command::Eval(a)) => cmd_eval(&a),
        Some(Command::Render(a)) => cmd_render(&a),
        Some(Command::Info(a)) => cmd_info(&a),
        Some(Command::Planners) => {
            cmd_planners();
            Ok(())
        }
        Some(Command::Simulate(a)) => cmd_simulate(&a),
        Some(Command::Explore(a)) => cmd_explore(&a),
        Some(Command::MapFromCamera(a)) => cmd_map_from_camera(&a),
    };
    match result {
        Ok(()) => 0,
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

fn read_options(resolution: Option<f64>) -> Result<ReadOptions> {
    let mut o = ReadOptions::default();
    if let Some(r) = resolution {
        o = o.resolution(oxcover_grid::error::positive("--resolution", r)?);
    }
    Ok(o)
}

fn load(map: &Path, resolution: Option<f64>) -> Result<OccupancyGrid> {
    Ok(read_map(map, &read_options(resolution)?)?)
}

fn robot_of(args: &RobotArgs, map: &OccupancyGrid) -> Result<DiscRobot> {
    let res = map.resolution();
    Ok(DiscRobot::new(
        args.robot_radius.unwrap_or(0.0),
        args.tool_radius.unwrap_or(res / 2.0),
    )?)
}

/// The map and the plan request the `plan` options describe.
fn map_and_request(a: &PlanArgs) -> Result<(OccupancyGrid, PlanRequest)> {
    let map = load(&a.map, a.robot.resolution)?;
    let robot = robot_of(&a.robot, &map)?;
    let request = PlanRequest {
        planner: a.planner.clone(),
        robot,
        start: a.start,
        seed: a.seed,
        boundary_pass: a.boundary_pass == OnOff::On,
        sweep_angle_deg: a.sweep_angle,
    };
    Ok((map, request))
}

fn cmd_plan(a: &PlanArgs) -> Result<()> {
    crate::planner::find_planner(&a.planner)?;
    let (map, request) = map_and_request(a)?;
    let outcome = plan(&map, &request)?;
    let name = a.map.display().to_string();
    let written = write_plan_outputs(
        &map,
        &name,
        &request,
        &outcome,
        &Outputs {
            csv: a.out.as_deref(),
            svg: a.svg.as_deref(),
            png: a.png.as_deref(),
            report: a.report.as_deref(),
        },
    )?;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{} on {} ({}x{} cells, {} m/cell): {} waypoints in {:.0} ms",
        request.planner,
        name,
        map.width(),
        map.height(),
        map.resolution(),
        outcome.points.len(),
        outcome.plan_ms
    );
    let _ = write!(out, "{}", table(&plan_rows(&outcome)));
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    for note in coverage_notes(&map, &outcome.evaluation.problem, a.start.is_none()) {
        let _ = writeln!(std::io::stderr(), "note: {note}");
    }
    Ok(())
}

fn cmd_explore(a: &ExploreArgs) -> Result<()> {
    use crate::explore::{explore_world, graph_text, trace_csv};
    use oxcover_planners::sensor_bcd::Config;
    let world = oxcover_robot::World::read(&a.world)?;
    let cfg = Config {
        robot_radius: a.robot_radius,
        tool_radius: a.tool_radius,
        margin: a.margin,
        rays: a.rays,
        max_range: a.max_range,
        noise_sd: a.noise,
        seed: a.seed,
        ..Config::default()
    };
    let outcome = explore_world(&world, &cfg, a.start)?;
    let e = &outcome.exploration;
    let report = outcome.report(&world, &cfg);
    let mut written = Vec::new();
    let mut write = |f: &Path, text: &[u8]| -> Result<()> {
        std::fs::write(f, text).map_err(|err| Error::write(f, err))?;
        written.push(f.to_path_buf());
        Ok(())
    };
    if let Some(f) = &a.out {
        write(f, trace_csv(e).as_bytes())?;
    }
    if let Some(f) = &a.graph {
        write(f, graph_text(&e.graph, f)?.as_bytes())?;
    }
    if let Some(f) = &a.report {
        let text = serde_json::to_string_pretty(&report)
            .map_err(|err| Error::Internal(format!("report serialisation failed: {err}")))?;
        write(f, text.as_bytes())?;
    }
    if let Some(f) = &a.map {
        oxcover_grid::io::write_ros_map(&outcome.map, f)?;
        written.push(f.clone());
    }
    let mut rows = metric_rows(&outcome.evaluation.metrics);
    rows.truncate(3);
    rows.push((
        "critical points".into(),
        format!("{}/{} found", report.found, report.true_critical_points),
    ));
    rows.push((
        "graph".into(),
        format!("{} nodes, {} edges", report.nodes, report.edges),
    ));
    rows.push(("disc collisions".into(), report.disc_collisions.to_string()));
    let overlay = outcome.overlay();
    let scene = Scene {
        map: &outcome.map,
        path: &[],
        planned: None,
        covered: Some(&outcome.evaluation.covered),
        coverable: Some(&outcome.evaluation.problem.coverable),
        title: format!("{} - sensor-bcd", world.name),
        overlay: Some(&overlay),
        rows: rows.clone(),
    };
    for f in [a.svg.as_deref(), a.png.as_deref()].into_iter().flatten() {
        render_to_file(&scene, f)?;
        written.push(f.to_path_buf());
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "sensor-bcd on {} ({} m x {} m): {} cycles, {} laps in {:.0} ms",
        a.world.display(),
        world.width,
        world.height,
        report.cycles,
        report.laps,
        report.explore_ms
    );
    let _ = write!(out, "{}", table(&rows));
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    Ok(())
}

fn read_ron<T: serde::de::DeserializeOwned>(path: &Path, what: &'static str) -> Result<T> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    ron::from_str(&text).map_err(|e| Error::Argument {
        name: what,
        value: path.display().to_string(),
        expected: format!("a valid {what} file ({e})"),
    })
}

fn cmd_map_from_camera(a: &MapFromCameraArgs) -> Result<()> {
    use oxcover_vision::occupancy::{LogOddsGrid, Visibility};
    use oxcover_vision::{Camera, Profile, RgbImage, fuse, to_map};
    let positive = |name: &'static str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(Error::Argument {
                name,
                value: v.to_string(),
                expected: "a finite number above 0".into(),
            })
        }
    };
    let res = positive("--resolution", a.resolution)?;
    let range = positive("--range", a.range)?;
    let camera: Camera = read_ron(&a.camera, "camera")?;
    let profile: Profile = read_ron(&a.profile, "profile")?;
    let cells = (1..=256)
        .contains(&profile.bins)
        .then(|| profile.bins.pow(3));
    if cells.is_none_or(|n| profile.free.len() != n || profile.occ.len() != n) {
        return Err(Error::Argument {
            name: "profile",
            value: a.profile.display().to_string(),
            expected: "1 to 256 bins per axis and bins³ free and occ counts".into(),
        });
    }
    let text = std::fs::read_to_string(&a.poses).map_err(|e| Error::Read {
        path: a.poses.clone(),
        source: e,
    })?;
    let bad = |line: usize, message: String| Error::PathFile {
        path: a.poses.clone(),
        line,
        message,
    };
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("image,x,y,theta") {
        return Err(bad(1, "expected the header image,x,y,theta".into()));
    }
    let dir = a.poses.parent().unwrap_or(Path::new("."));
    let mut poses: Vec<(PathBuf, (f64, f64, f64))> = Vec::new();
    for (k, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 4 {
            return Err(bad(k + 2, format!("expected 4 fields, got {}", f.len())));
        }
        let num = |s: &str, name: &str| -> Result<f64> {
            s.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(k + 2, format!("{name} is `{s}`, expected a finite number")))
        };
        poses.push((
            dir.join(f[0]),
            (num(f[1], "x")?, num(f[2], "y")?, num(f[3], "theta")?),
        ));
    }
    if poses.is_empty() {
        return Err(bad(2, "no image".into()));
    }
    let (x0, y0, x1, y1) = match &a.extent {
        Some(e) => {
            let v: Vec<f64> = e.split(',').filter_map(|s| s.trim().parse().ok()).collect();
            match v.as_slice() {
                [x0, y0, x1, y1] if x1 > x0 && y1 > y0 && v.iter().all(|x| x.is_finite()) => {
                    (*x0, *y0, *x1, *y1)
                }
                _ => {
                    return Err(Error::Argument {
                        name: "--extent",
                        value: e.clone(),
                        expected: "XMIN,YMIN,XMAX,YMAX in metres with XMIN < XMAX and YMIN < YMAX"
                            .into(),
                    });
                }
            }
        }
        None => poses.iter().fold(
            (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ),
            |b, (_, p)| {
                (
                    b.0.min(p.0 - range),
                    b.1.min(p.1 - range),
                    b.2.max(p.0 + range),
                    b.3.max(p.1 + range),
                )
            },
        ),
    };
    let (w, h) = (((x1 - x0) / res).ceil(), ((y1 - y0) / res).ceil());
    if w * h > 50_000_000.0 {
        return Err(Error::Argument {
            name: "--extent",
            value: format!("{w} x {h} cells"),
            expected: "at most 50 million cells (a smaller extent or a coarser resolution)".into(),
        });
    }
    let frame = oxcover_grid::MapFrame::new(w as usize, h as usize, res, Point::new(x0, y0));
    let mut grid = LogOddsGrid::new(frame);
    let mode = match a.visibility {
        VisibilityArg::Product => Visibility::Product,
        VisibilityArg::Bayes => Visibility::Bayes,
    };
    for (file, pose) in &poses {
        let img = RgbImage::read_png(file)?;
        if (img.width, img.height) != (camera.width, camera.height) {
            return Err(Error::Argument {
                name: "image",
                value: format!("{} ({}x{})", file.display(), img.width, img.height),
                expected: format!(
                    "{}x{} pixels, the camera's size",
                    camera.width, camera.height
                ),
            });
        }
        let fusion = match a.fusion {
            FusionArg::Paper => oxcover_vision::Fusion::Paper,
            FusionArg::Discounted => oxcover_vision::Fusion::Discounted,
        };
        fuse(
            &mut grid, &camera, &profile, &img, *pose, range, mode, fusion,
        );
    }
    let map = to_map(&grid, 0.35, 0.65);
    oxcover_grid::io::write_ros_map(&map, &a.out)?;
    let mut out = std::io::stdout().lock();
    let counts = map.counts();
    let _ = writeln!(
        out,
        "{} images fused into {}x{} cells: {} free, {} occupied, {} unknown",
        poses.len(),
        map.width(),
        map.height(),
        counts.free,
        counts.occupied,
        counts.unknown
    );
    let _ = writeln!(out, "wrote {}", a.out.display());
    if let Some(f) = &a.png {
        let scene = Scene {
            map: &map,
            path: &[],
            planned: None,
            covered: None,
            coverable: None,
            title: "map from camera".into(),
            overlay: None,
            rows: Vec::new(),
        };
        render_to_file(&scene, f)?;
        let _ = writeln!(out, "wrote {}", f.display());
    }
    Ok(())
}

/// The bundled robot description (`fixtures/robots/floor_cleaner.ron`).
const FLOOR_CLEANER: &str = include_str!("../../../fixtures/robots/floor_cleaner.ron");

fn cmd_simulate(a: &SimulateArgs) -> Result<()> {
    use crate::closed_loop::{ClosedLoop, ControllerKind, execute, to_csv};
    let p = &a.plan;
    crate::planner::find_planner(&p.planner)?;
    let spec_text = match &a.robot_spec {
        Some(f) => std::fs::read_to_string(f).map_err(|e| Error::Read {
            path: f.clone(),
            source: e,
        })?,
        None => FLOOR_CLEANER.to_string(),
    };
    let spec = oxcover_robot::RobotSpec::from_ron(&spec_text).map_err(|e| Error::Argument {
        name: "--robot-spec",
        value: a
            .robot_spec
            .as_ref()
            .map_or_else(|| "bundled".into(), |f| f.display().to_string()),
        expected: format!("a valid robot description ({e})"),
    })?;
    let (map, request) = map_and_request(p)?;
    let robot = request.robot;
    let outcome = plan(&map, &request)?;
    let cfg = ClosedLoop {
        spec,
        controller: match a.controller {
            ControllerArg::Kanayama => ControllerKind::Kanayama,
            ControllerArg::Klancar => ControllerKind::Klancar,
        },
        limits: oxcover_robot::Limits::default(),
        dt: a.dt,
        odometry_noise: a.odometry_noise,
        seed: p.seed,
    };
    let run = execute(&map, robot, &outcome.points, &cfg)?;
    let mut written = Vec::new();
    if let Some(f) = &p.out {
        std::fs::write(f, to_csv(&run.samples)).map_err(|e| Error::write(f, e))?;
        written.push(f.clone());
    }
    let executed: Vec<Point> = run
        .samples
        .iter()
        .map(|s| Point::new(s.pose.x, s.pose.y))
        .collect();
    let ev = &run.evaluation;
    let last = run.samples.last().copied();
    let duration = last.map_or(0.0, |s| s.t);
    let energy = last.map_or(0.0, |s| s.energy);
    let mut rows = metric_rows(&ev.metrics);
    rows.push(("duration_s".into(), format!("{duration:.1}")));
    rows.push(("energy_j".into(), format!("{energy:.0}")));
    rows.push(("tracking_rms_m".into(), format!("{:.4}", run.tracking_rms)));
    rows.push(("tracking_max_m".into(), format!("{:.4}", run.tracking_max)));
    let scene = Scene {
        map: &map,
        path: &executed,
        planned: Some(&outcome.points),
        covered: Some(&ev.covered),
        coverable: Some(&ev.problem.coverable),
        title: format!(
            "{} - {} executed (plan in orange)",
            short_name(&p.map.display().to_string()),
            p.planner
        ),
        overlay: None,
        rows: rows.clone(),
    };
    for f in [p.svg.as_deref(), p.png.as_deref()].into_iter().flatten() {
        render_to_file(&scene, f)?;
        written.push(f.to_path_buf());
    }
    if let Some(f) = &p.report {
        let mut v = serde_json::to_value(&ev.metrics)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        if let Some(o) = v.as_object_mut() {
            o.insert("planner".into(), p.planner.clone().into());
            o.insert(
                "controller".into(),
                format!("{:?}", a.controller).to_lowercase().into(),
            );
            o.insert("dt".into(), a.dt.into());
            o.insert("odometry_noise".into(), a.odometry_noise.into());
            o.insert("duration_s".into(), duration.into());
            o.insert("energy_j".into(), energy.into());
            o.insert("tracking_rms_m".into(), run.tracking_rms.into());
            o.insert("tracking_max_m".into(), run.tracking_max.into());
            o.insert(
                "planned_coverage".into(),
                outcome.evaluation.metrics.coverage.into(),
            );
        }
        let json = serde_json::to_string_pretty(&v)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        std::fs::write(f, json + "\n").map_err(|e| Error::write(f, e))?;
        written.push(f.clone());
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{} on {} executed by the {:?} controller: {} samples over {duration:.1} s",
        p.planner,
        p.map.display(),
        a.controller,
        run.samples.len()
    );
    let _ = write!(out, "{}", table(&rows));
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    Ok(())
}

/// Hints about what a plan leaves out: free cells it cannot cover, and a
/// default start stranded in a small component (common in SLAM maps, whose
/// first free cell is often a speck of noise).
fn coverage_notes(
    map: &OccupancyGrid,
    problem: &oxcover_grid::Coverability,
    default_start: bool,
) -> Vec<String> {
    let mut notes = Vec::new();
    let free = map.counts().free;
    let coverable = problem.coverable_count();
    if coverable < free {
        notes.push(format!(
            "{} of {free} free cells are not coverable (not reachable from the start, or too close to obstacles for this robot and tool) and are not counted",
            free - coverable
        ));
    }
    let comps = components4(&problem.admissible);
    let mine = comps.labels[problem.start];
    if let Some(big) = comps.largest() {
        let (ours, theirs) = (
            comps.sizes[mine as usize - 1],
            comps.sizes[big as usize - 1],
        );
        if big != mine && theirs > 2 * ours {
            if let Some(cell) = problem
                .admissible
                .true_cells()
                .find(|&c| comps.labels[c] == big)
            {
                let p = map.frame().cell_center(cell);
                let how = if default_start {
                    "the default start (first admissible cell)"
                } else {
                    "the start"
                };
                notes.push(format!(
                    "{how} lies in a region of {ours} admissible cells; the largest has {theirs}: try --start {},{}",
                    metres(p.x),
                    metres(p.y)
                ));
            }
        }
    }
    notes
}

/// Where to write a plan's outputs (each optional).
pub(crate) struct Outputs<'a> {
    pub(crate) csv: Option<&'a Path>,
    pub(crate) svg: Option<&'a Path>,
    pub(crate) png: Option<&'a Path>,
    pub(crate) report: Option<&'a Path>,
}

/// Writes the CSV, pictures and report of a plan; returns the files written.
pub(crate) fn write_plan_outputs(
    map: &OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &crate::planner::PlanOutcome,
    out: &Outputs<'_>,
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    if let Some(p) = out.csv {
        write_csv(p, &outcome.points)?;
        written.push(p.to_path_buf());
    }
    let ev = &outcome.evaluation;
    let title = format!("{} - {}", short_name(map_name), request.planner);
    let scene = Scene {
        map,
        path: &outcome.points,
        planned: None,
        covered: Some(&ev.covered),
        coverable: Some(&ev.problem.coverable),
        title,
        overlay: None,
        rows: metric_rows(&ev.metrics),
    };
    for p in [out.svg, out.png].into_iter().flatten() {
        render_to_file(&scene, p)?;
        written.push(p.to_path_buf());
    }
    if let Some(p) = out.report {
        let start = outcome
            .points
            .first()
            .copied()
            .unwrap_or_else(Point::origin);
        let params = PlanParameters {
            map: map_name.to_string(),
            robot_radius: request.robot.robot_radius,
            tool_radius: request.robot.tool_radius,
            resolution: map.resolution(),
            start: [start.x, start.y],
            seed: request.seed,
            boundary_pass: request.boundary_pass,
            sweep_angle_deg: request.sweep_angle_deg,
            coverage_cell_m: outcome.coarse_block as f64 * map.resolution(),
        };
        let report = PlanReport::new(&request.planner, params, outcome);
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        std::fs::write(p, json + "\n").map_err(|e| Error::write(p, e))?;
        written.push(p.to_path_buf());
    }
    Ok(written)
}

fn short_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// A coordinate in metres with at most six decimals, trailing zeros dropped.
fn metres(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

fn cmd_eval(a: &EvalArgs) -> Result<()> {
    let map = load(&a.map, a.robot.resolution)?;
    let robot = robot_of(&a.robot, &map)?;
    let points = read_csv(&a.path)?;
    let ev = evaluate(&map, robot, &points, &MetricParams::default())?;
    let json = serde_json::to_string_pretty(&ev.metrics)
        .map_err(|e| Error::Internal(format!("metrics serialisation failed: {e}")))?;
    let _ = writeln!(std::io::stdout(), "{json}");
    Ok(())
}

fn cmd_render(a: &RenderArgs) -> Result<()> {
    let map = load(&a.map, a.robot.resolution)?;
    let name = short_name(&a.map.display().to_string());
    match &a.path {
        Some(path_file) => {
            let robot = robot_of(&a.robot, &map)?;
            let points = read_csv(path_file)?;
            let ev = evaluate(&map, robot, &points, &MetricParams::default())?;
            let scene = Scene {
                map: &map,
                path: &points,
                planned: None,
                covered: Some(&ev.covered),
                coverable: Some(&ev.problem.coverable),
                title: format!("{name} - {}", short_name(&path_file.display().to_string())),
                overlay: None,
                rows: metric_rows(&ev.metrics),
            };
            render_to_file(&scene, &a.out)?;
        }
        None => {
            let scene = Scene {
                map: &map,
                path: &[],
                planned: None,
                covered: None,
                coverable: None,
                title: name,
                overlay: None,
                rows: map_rows(&map),
            };
            render_to_file(&scene, &a.out)?;
        }
    }
    let _ = writeln!(std::io::stdout(), "wrote {}", a.out.display());
    Ok(())
}

fn map_rows(map: &OccupancyGrid) -> Vec<(String, String)> {
    let c = map.counts();
    vec![
        ("size".into(), format!("{}x{}", map.width(), map.height())),
        ("resolution".into(), format!("{} m", map.resolution())),
        ("free".into(), c.free.to_string()),
        ("occupied".into(), c.occupied.to_string()),
        ("unknown".into(), c.unknown.to_string()),
    ]
}

fn cmd_info(a: &InfoArgs) -> Result<()> {
    let map = load(&a.map, a.resolution)?;
    let f = map.frame();
    let (lo, hi) = f.bounds();
    let free = map.free_mask();
    let comps = components4(&free);
    let mut rows = map_rows(&map);
    rows.push(("origin".into(), format!("({}, {})", lo.x, lo.y)));
    rows.push((
        "extent".into(),
        format!("x {}..{}, y {}..{}", lo.x, hi.x, lo.y, hi.y),
    ));
    rows.push(("free components".into(), comps.count().to_string()));
    if let Some(l) = comps.largest() {
        rows.push((
            "largest component".into(),
            comps.sizes[l as usize - 1].to_string(),
        ));
    }
    if let Some(s) = free.true_cells().next() {
        let p = f.cell_center(s);
        rows.push(("default start".into(), format!("{},{}", p.x, p.y)));
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{}", a.map.display());
    let _ = write!(out, "{}", table(&rows));
    Ok(())
}

fn cmd_planners() {
    let mut out = std::io::stdout().lock();
    let list = planners();
    let w = list.iter().map(|p| p.name.len()).max().unwrap_or(4);
    let _ = writeln!(out, "{:<w$}  complete  description", "name");
    for p in &list {
        let _ = writeln!(
            out,
            "{:<w$}  {:<8}  {}",
            p.name,
            if p.complete { "yes" } else { "no" },
            p.summary
        );
    }
    let _ = writeln!(
        out,
        "\n{:<w$}  {:<8}  online sensor-based boustrophedon coverage of unknown polygonal worlds (seed 003): `oxcover explore WORLD.ron`",
        "sensor-bcd", "yes"
    );
}
