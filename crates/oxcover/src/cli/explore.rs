//! `oxcover explore`: the sensor-based planner on a polygonal world.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::grid::Point;
use oxcover::render::{Scene, render_bytes};
use oxcover::report::{metric_rows, table};
use oxcover::{Error, Result};

use super::args::{ANY, PNG, SVG, YAML, asked, check_outputs, parse_start};

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum AlgorithmArg {
    Cycles,
    Paper,
}

#[derive(Debug, clap::Args)]
pub(crate) struct ExploreArgs {
    /// World file (.ron: boundary, polygons, discs, rectangles; see fixtures/worlds).
    pub(crate) world: PathBuf,
    /// Robot body radius in metres.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 0.2,
        allow_negative_numbers = true
    )]
    pub(crate) robot_radius: f64,
    /// Tool radius in metres; laps are two tool radii apart.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 0.25,
        allow_negative_numbers = true
    )]
    pub(crate) tool_radius: f64,
    /// Distance kept from sensed boundaries beyond the body, in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 0.04,
        allow_negative_numbers = true
    )]
    pub(crate) margin: f64,
    /// Range rays in the ring.
    #[arg(long, value_name = "N", default_value_t = 180)]
    pub(crate) rays: usize,
    /// Longest range reading in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 3.0,
        allow_negative_numbers = true
    )]
    pub(crate) max_range: f64,
    /// Range noise: standard deviation in metres.
    #[arg(
        long,
        value_name = "SD",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub(crate) noise: f64,
    /// Seed of the range noise.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub(crate) seed: u64,
    /// Algorithm: `cycles` (ours: every slab closed by a cycle, the Reeb
    /// graph from what was traced) or `paper` (Demir 2018 as published: no
    /// cycle algorithm, graph edges from the last visited node).
    #[arg(long, value_enum, default_value_t = AlgorithmArg::Cycles)]
    pub(crate) algorithm: AlgorithmArg,
    /// Start position in metres [default: the world file's `start`].
    #[arg(long, value_name = "X,Y", value_parser = parse_start, allow_hyphen_values = true)]
    pub(crate) start: Option<Point>,
    /// Executed path to write (CSV: x,y,state).
    #[arg(long, value_name = "PATH.csv")]
    pub(crate) out: Option<PathBuf>,
    /// Discovered Reeb graph to write (.json or .ron).
    #[arg(long, value_name = "G.json|G.ron")]
    pub(crate) graph: Option<PathBuf>,
    /// The world rasterised as a ROS map (yaml, with its PGM beside it).
    #[arg(long, value_name = "MAP.yaml")]
    pub(crate) map: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    pub(crate) png: Option<PathBuf>,
    /// JSON report to write.
    #[arg(long, value_name = "F.json")]
    pub(crate) report: Option<PathBuf>,
}

pub(crate) fn cmd_explore(a: &ExploreArgs) -> Result<()> {
    use oxcover::explore::{explore_world, graph_format, graph_text, trace_csv};
    use oxcover::world::sensor_bcd::Config;
    // Refuse a graph file name, or outputs that would overwrite the world
    // or each other, before any work.
    if let Some(f) = &a.graph {
        graph_format(f)?;
    }
    let map_image = a.map.as_ref().map(|m| m.with_extension("pgm"));
    let outs = asked([
        ("--out", a.out.as_deref(), ANY),
        ("--graph", a.graph.as_deref(), &["json", "ron"]),
        ("--map", a.map.as_deref(), YAML),
        ("--map's image", map_image.as_deref(), ANY),
        ("--svg", a.svg.as_deref(), SVG),
        ("--png", a.png.as_deref(), PNG),
        ("--report", a.report.as_deref(), ANY),
    ]);
    check_outputs(&[&a.world], &outs)?;
    let world = oxcover::world::World::read(&a.world)?;
    let cfg = Config {
        algorithm: match a.algorithm {
            AlgorithmArg::Cycles => oxcover::world::sensor_bcd::Algorithm::Cycles,
            AlgorithmArg::Paper => oxcover::world::sensor_bcd::Algorithm::Paper,
        },
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
    // Every output is made first and written as one set: a failure leaves
    // none of them behind.
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(f) = &a.out {
        files.push((f.clone(), trace_csv(e).into_bytes()));
    }
    if let Some(f) = &a.graph {
        files.push((f.clone(), graph_text(&e.graph, f)?.into_bytes()));
    }
    if let Some(f) = &a.report {
        let text = serde_json::to_string_pretty(&report)
            .map_err(|err| Error::Internal(format!("report serialisation failed: {err}")))?;
        files.push((f.clone(), text.into_bytes()));
    }
    if let Some(f) = &a.map {
        files.extend(oxcover::grid::io::ros_map_files(&outcome.map, f)?);
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
        regions: None,
        rows: rows.clone(),
    };
    for f in [a.svg.as_deref(), a.png.as_deref()].into_iter().flatten() {
        files.push((f.to_path_buf(), render_bytes(&scene, f)?));
    }
    let written = oxcover::output::write_files(files)?;
    let mut out = super::out::stdout();
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
