//! `oxcover simulate`: a plan executed by a simulated differential-drive robot.

use std::io::Write as _;
use std::path::PathBuf;

use clap::ValueEnum;
use oxcover::grid::Point;
use oxcover::pipeline::{plan, short_name};
use oxcover::render::{Scene, render_bytes};
use oxcover::report::table;
use oxcover::{Error, Result};

use super::plan::{PlanArgs, map_and_request_with};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ControllerArg {
    Kanayama,
    Klancar,
}

#[derive(Debug, clap::Args)]
pub(crate) struct SimulateArgs {
    #[command(flatten)]
    pub(crate) plan: PlanArgs,
    /// Robot description (RON, see fixtures/robots) [default: the bundled floor cleaner].
    #[arg(long, value_name = "F.ron")]
    pub(crate) robot_spec: Option<PathBuf>,
    /// Tracking controller.
    #[arg(long, value_enum, default_value_t = ControllerArg::Klancar)]
    pub(crate) controller: ControllerArg,
    /// Control step in seconds.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 0.02,
        allow_negative_numbers = true
    )]
    pub(crate) dt: f64,
    /// Odometry noise: relative wheel-speed error per step (standard deviation).
    #[arg(
        long,
        value_name = "SIGMA",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub(crate) odometry_noise: f64,
}

pub(crate) fn cmd_simulate(a: &SimulateArgs) -> Result<()> {
    use oxcover::closed_loop::{ClosedLoop, ControllerKind, to_csv};
    let p = &a.plan;
    if let Some(spec) = &a.robot_spec {
        super::args::check_outputs(&[spec], &super::plan::plan_outputs(p))?;
    }
    let spec_text = match &a.robot_spec {
        Some(f) => oxcover::grid::io::limited::read_limited_string(
            f,
            oxcover::grid::io::limited::MAX_TEXT_BYTES,
        )
        .map_err(|e| Error::Read {
            path: f.clone(),
            source: e,
        })?,
        None => oxcover::closed_loop::FLOOR_CLEANER.to_string(),
    };
    let spec =
        oxcover::robot::RobotSpec::from_ron(&spec_text).map_err(|e| Error::BadParameter {
            name: "--robot-spec",
            value: a
                .robot_spec
                .as_ref()
                .map_or_else(|| "bundled".into(), |f| f.display().to_string()),
            expected: format!("a valid robot description ({e})"),
        })?;
    // Planned with the robot's tracking margin as clearance unless
    // `--clearance` says otherwise: kept from the edges of the path's
    // cells (a path may run half a cell off its cells' centres), where
    // the map's cells are fine enough for it: where it keeps at least half
    // the cells the robot may stand in.
    let (map, request) = map_and_request_with(p, |map, radius| {
        let margin = spec.tracking_margin + map.resolution() / 2.0;
        let stand = |r: f64| oxcover::grid::admissible(map, r).count_true();
        if 2 * stand(radius + margin) >= stand(radius) {
            margin
        } else {
            super::args::note_later(Some(format!(
                "the map's cells ({} m) are too coarse for the tracking margin of {} m: planned without a clearance",
                map.resolution(),
                spec.tracking_margin
            )));
            0.0
        }
    })?;
    let robot = request.robot;
    let outcome = plan(&map, &request)?;
    let cfg = ClosedLoop {
        spec,
        controller: match a.controller {
            ControllerArg::Kanayama => ControllerKind::Kanayama,
            ControllerArg::Klancar => ControllerKind::Klancar,
        },
        limits: oxcover::robot::Limits::default(),
        dt: a.dt,
        odometry_noise: a.odometry_noise,
        seed: p.seed,
    };
    let run = oxcover::closed_loop::execute_plan(&map, &request, &outcome, &cfg)?;
    let targets = &request.targets;
    // (Segments the map with --rooms-only: only for a picture.)
    let overlay = if p.svg.is_some() || p.png.is_some() {
        oxcover::targets::target_overlay(targets, &map)?
    } else {
        oxcover::render::Overlay::default()
    };
    // Every output is made first and written as one set.
    let mut files: Vec<(std::path::PathBuf, Vec<u8>)> = Vec::new();
    if let Some(f) = &p.out {
        files.push((f.clone(), to_csv(&run.samples).into_bytes()));
    }
    let executed: Vec<Point> = run
        .samples
        .iter()
        .map(|s| Point::new(s.pose.x, s.pose.y))
        .collect();
    let ev = &run.evaluation;
    let duration = run.duration_s();
    let rows = run.rows();
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
        overlay: (overlay != oxcover::render::Overlay::default()).then_some(&overlay),
        regions: None,
        rows: rows.clone(),
    };
    for f in [p.svg.as_deref(), p.png.as_deref()].into_iter().flatten() {
        files.push((f.to_path_buf(), render_bytes(&scene, f)?));
    }
    if let Some(f) = &p.report {
        let report = run.report(
            request.planner.name(),
            &cfg,
            outcome.evaluation.metrics.coverage,
        );
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        files.push((f.clone(), (json + "\n").into_bytes()));
    }
    if let Some(f) = &p.bag {
        let extras = oxcover::bag::BagExtras {
            rooms: Some(oxcover::bag::room_markers(&map)?),
            targets: oxcover::bag::target_markers(targets, map.resolution()),
            odom: run
                .samples
                .iter()
                .map(|s| oxcover::rosbag::OdomSample {
                    t: s.t,
                    x: s.pose.x,
                    y: s.pose.y,
                    yaw: s.pose.theta,
                    v: s.v,
                    w: s.omega,
                })
                .collect(),
        };
        let bytes = oxcover::bag::bag_bytes(&map, &outcome.points, &request.time, extras, f)?;
        files.push((f.clone(), bytes));
    }
    let written = oxcover::output::write_files(files)?;
    let mut out = super::out::stdout();
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
    if let Some(w) = run.cut_short(outcome.evaluation.metrics.coverage, robot.tool_radius) {
        let _ = writeln!(std::io::stderr(), "warning: {w}");
    }
    Ok(())
}
