//! `oxcover render`: a map, optionally with a path, as SVG or PNG.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::Result;
use oxcover::metrics::MetricParams;
use oxcover::path::read_csv;
use oxcover::pipeline::short_name;
use oxcover::render::{Overlay, Scene, render_to_file};
use oxcover::report::metric_rows;
use oxcover::targets::{evaluate_targets, target_overlay};

use super::args::{PICTURE, RobotArgs, admissible_robot, check_outputs, load, map_rows};
use super::targets::TargetArgs;

#[derive(Debug, clap::Args)]
pub(crate) struct RenderArgs {
    /// Map: .yaml, .pgm, .png, .bmp, .map, or a rosbag2 bag (folder, .mcap, .db3).
    pub(crate) map: PathBuf,
    /// Optional path file to draw (with its coverage) [default for a bag
    /// of a plan: its /coverage_path (or /odom), /rooms and
    /// /coverage_targets, decoded from it].
    pub(crate) path: Option<PathBuf>,
    /// Output picture, .svg or .png.
    #[arg(long, value_name = "F.svg|F.png")]
    pub(crate) out: PathBuf,
    #[command(flatten)]
    pub(crate) robot: RobotArgs,
    #[command(flatten)]
    pub(crate) targets: TargetArgs,
}

pub(crate) fn cmd_render(a: &RenderArgs) -> Result<()> {
    let mut inputs = vec![a.map.as_path()];
    inputs.extend(a.path.as_deref());
    inputs.extend(a.targets.inputs());
    check_outputs(&inputs, &[("--out", &a.out, PICTURE)])?;
    let map = load(&a.map, &a.robot.map)?;
    let targets = a.targets.targets()?;
    let overlay = target_overlay(&targets, &map)?;
    let overlay = (overlay != Overlay::default()).then_some(&overlay);
    let name = short_name(&a.map.display().to_string());
    match &a.path {
        Some(path_file) => {
            let robot = admissible_robot(&a.robot, &map)?;
            let points = read_csv(path_file)?;
            let ev = evaluate_targets(&map, robot, &points, &MetricParams::default(), &targets)?;
            let scene = Scene {
                map: &map,
                path: &points,
                planned: None,
                covered: Some(&ev.covered),
                coverable: Some(&ev.problem.coverable),
                title: format!("{name} - {}", short_name(&path_file.display().to_string())),
                overlay,
                regions: None,
                rows: metric_rows(&ev.metrics),
            };
            render_to_file(&scene, &a.out)?;
        }
        None if oxcover::rosbag::is_bag(&a.map) => {
            // A bag of a plan: its own path (or executed trajectory, the
            // plan drawn under it), rooms and targets, decoded from it.
            let decoded = oxcover::bag::decode_bag(&a.map)?;
            let mut lines = decoded.overlay.clone();
            if let Some(o) = overlay {
                lines.strokes.extend(o.strokes.iter().cloned());
                lines.lines.extend(o.lines.iter().cloned());
                lines.legend.extend(o.legend.iter().cloned());
            }
            let shown = decoded.odom.as_ref().or(decoded.path.as_ref());
            match shown {
                Some(points) if !points.is_empty() => {
                    let robot = admissible_robot(&a.robot, &map)?;
                    let ev =
                        evaluate_targets(&map, robot, points, &MetricParams::default(), &targets)?;
                    let what = if decoded.odom.is_some() {
                        "/odom"
                    } else {
                        "/coverage_path"
                    };
                    let scene = Scene {
                        map: &map,
                        path: points,
                        planned: decoded.odom.as_ref().and(decoded.path.as_deref()),
                        covered: Some(&ev.covered),
                        coverable: Some(&ev.problem.coverable),
                        title: format!("{name} - {what} as decoded from the bag"),
                        overlay: Some(&lines),
                        regions: None,
                        rows: metric_rows(&ev.metrics),
                    };
                    render_to_file(&scene, &a.out)?;
                }
                _ => {
                    let mut scene = Scene::map_only(&map, name, map_rows(&map));
                    scene.overlay = Some(&lines);
                    render_to_file(&scene, &a.out)?;
                }
            }
        }
        None => {
            let mut scene = Scene::map_only(&map, name, map_rows(&map));
            scene.overlay = overlay;
            render_to_file(&scene, &a.out)?;
        }
    }
    let _ = writeln!(super::out::stdout(), "wrote {}", a.out.display());
    Ok(())
}
