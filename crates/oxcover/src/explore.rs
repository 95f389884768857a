//! Sensor-based exploration of a polygonal world (`oxcover explore`): the
//! `sensor-bcd` planner run on a RON world, scored with the contract's
//! metrics on the world's rasterised map, its discovered Reeb graph compared
//! with the world's exact critical points, and drawn.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use oxcover_grid::{DiscRobot, OccupancyGrid, Point};
use oxcover_world::sensor_bcd::{self, Config, Exploration, ReebGraph, State};
use oxcover_world::{Event, TrueCriticalPoint, World, WorldGeometry};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::metrics::{Evaluation, MetricParams, evaluate};
use crate::render::{LegendMark, MarkerShape, Overlay};

/// A true critical point counts as found when a detection lies within
/// `r + δ` of it (convex), or `2 (r + δ)` (concave): the detector reports
/// the boundary point its ray along x hit from where the robot turned; the
/// robot touches a convex point, but in a concave corner of opening φ it
/// stops `(r + δ) / sin(φ/2)` from the apex and its ray lands up to
/// `(r + δ) cot(φ/2)` away (one `r + δ` for a right angle, two for 53°).
#[must_use]
pub fn found_within(kind: oxcover_world::CriticalKind, keep: f64) -> f64 {
    match kind.convexity {
        oxcover_world::Convexity::Convex => keep,
        oxcover_world::Convexity::Concave => 2.0 * keep,
    }
}

/// Everything an exploration produced, scored.
#[derive(Clone, Debug)]
pub struct ExploreOutcome {
    /// The world's rasterised map.
    pub map: OccupancyGrid,
    /// The planner's output.
    pub exploration: Exploration,
    /// The contract's metrics of the executed path on `map`.
    pub evaluation: Evaluation,
    /// The world's exact critical points (at the planner's x hysteresis).
    pub truth: Vec<TrueCriticalPoint>,
    /// Which true critical points a detection matched.
    pub found: Vec<bool>,
    /// Detections matching no true critical point.
    pub spurious: usize,
    /// Detections whose class equals that of the true point they matched.
    pub same_class: usize,
    /// Wall time of the exploration (ms).
    pub explore_ms: f64,
}

/// The report `oxcover explore --report` writes.
#[derive(Clone, Debug, Serialize)]
pub struct ExploreReport<'a> {
    /// The contract's metrics (raster).
    #[serde(flatten)]
    pub metrics: &'a crate::metrics::Metrics,
    /// World name.
    pub world: &'a str,
    /// Planner name.
    pub planner: &'static str,
    /// Robot radius (m).
    pub robot_radius: f64,
    /// Tool radius (m).
    pub tool_radius: f64,
    /// Range noise (m).
    pub noise_sd: f64,
    /// Seed.
    pub seed: u64,
    /// Graph nodes (critical points found).
    pub nodes: usize,
    /// Graph edges (cells).
    pub edges: usize,
    /// True critical points.
    pub true_critical_points: usize,
    /// True critical points found.
    pub found: usize,
    /// Detections matching none.
    pub spurious: usize,
    /// Detections the three-ray test classified itself.
    pub confirmed: usize,
    /// Cycles traced.
    pub cycles: usize,
    /// Laps.
    pub laps: usize,
    /// Transit length (m).
    pub travel_m: f64,
    /// Moves where the disc overlapped the world (exact geometry).
    pub disc_collisions: usize,
    /// Smallest exact clearance of the path (m).
    pub min_clearance_m: f64,
    /// Whether every slab side was traced.
    pub complete: bool,
    /// Exploration wall time (ms).
    pub explore_ms: f64,
}

/// Explores `world` from `start` (the world's own start when `None`).
///
/// # Errors
/// [`Error::BadParameter`] without a start, planner errors (bad settings, a
/// start in a wall), and map errors from scoring.
pub fn explore_world(world: &World, cfg: &Config, start: Option<Point>) -> Result<ExploreOutcome> {
    let start = match (start, world.start) {
        (Some(p), _) => p,
        (None, Some(p)) => p,
        (None, None) => {
            return Err(Error::BadParameter {
                name: "--start",
                value: "none".into(),
                expected: format!("X,Y: the world `{}` names no start", world.name),
            });
        }
    };
    let geometry = WorldGeometry::new(world);
    let t0 = Instant::now();
    let exploration = sensor_bcd::explore(&geometry, start, cfg)?;
    let explore_ms = t0.elapsed().as_secs_f64() * 1e3;
    let map = world.rasterise();
    let points: Vec<Point> = exploration
        .trace
        .iter()
        .map(|t| Point::new(t.x, t.y))
        .collect();
    let robot = DiscRobot::new(cfg.robot_radius, cfg.tool_radius)?;
    let evaluation = evaluate(&map, robot, &points, &MetricParams::default())?;
    let truth = world.critical_points(cfg.x_hysteresis());
    let keep = cfg.robot_radius + cfg.margin;
    let nodes = &exploration.graph.nodes;
    let nearest = |t: &TrueCriticalPoint| {
        nodes
            .iter()
            .map(|n| (t.distance(n.at), n))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .filter(|(d, _)| *d <= found_within(t.kind, keep))
    };
    let found: Vec<bool> = truth.iter().map(|t| nearest(t).is_some()).collect();
    let same_class = truth
        .iter()
        .filter(|t| nearest(t).is_some_and(|(_, n)| n.kind == t.kind))
        .count();
    let spurious = nodes
        .iter()
        .filter(|n| {
            truth
                .iter()
                .all(|t| t.distance(n.at) > found_within(t.kind, keep))
        })
        .count();
    Ok(ExploreOutcome {
        map,
        exploration,
        evaluation,
        truth,
        found,
        spurious,
        same_class,
        explore_ms,
    })
}

impl ExploreOutcome {
    /// The report.
    #[must_use]
    pub fn report<'a>(&'a self, world: &'a World, cfg: &Config) -> ExploreReport<'a> {
        let e = &self.exploration;
        ExploreReport {
            metrics: &self.evaluation.metrics,
            world: &world.name,
            planner: "sensor-bcd",
            robot_radius: cfg.robot_radius,
            tool_radius: cfg.tool_radius,
            noise_sd: cfg.noise_sd,
            seed: cfg.seed,
            nodes: e.graph.nodes.len(),
            edges: e.graph.edges.len(),
            true_critical_points: self.truth.len(),
            found: self.found.iter().filter(|&&f| f).count(),
            spurious: self.spurious,
            confirmed: e.graph.nodes.iter().filter(|n| n.confirmed).count(),
            cycles: e.counters.cycles,
            laps: e.counters.laps,
            travel_m: e.counters.travel_m,
            disc_collisions: e.collisions,
            min_clearance_m: e.min_clearance,
            complete: e.complete,
            explore_ms: self.explore_ms,
        }
    }

    /// The state colours, graph and critical points as a picture overlay.
    #[must_use]
    pub fn overlay(&self) -> Overlay {
        overlay(&self.exploration, &self.truth)
    }
}

/// Colour of a state's stroke.
#[must_use]
pub fn state_rgb(state: State) -> [u8; 3] {
    match state {
        State::Start | State::MotionToBoundary => [205, 45, 45],
        State::BorderFollowing => [40, 80, 200],
        State::ObstacleFollowing => [25, 145, 60],
        State::Transit => [235, 150, 25],
    }
}

const GRAPH_RGB: [u8; 3] = [95, 35, 125];
const IN_RGB: [u8; 3] = [200, 0, 160];
const OUT_RGB: [u8; 3] = [0, 140, 150];
const TRUE_RGB: [u8; 3] = [0, 0, 0];

/// The executed path coloured by state, the Reeb graph's edges (through the
/// middles of each cell's laps), detected critical points (IN magenta, OUT
/// teal; squares where the three-ray test did not classify on its own) and
/// the true ones (black rings).
#[must_use]
pub fn overlay(e: &Exploration, truth: &[TrueCriticalPoint]) -> Overlay {
    let mut o = Overlay::default();
    let mut run: Vec<Point> = Vec::new();
    let mut state = None;
    for w in e.trace.windows(2) {
        let s = w[1].state;
        if state != Some(s) {
            if let Some(prev) = state.filter(|_| run.len() >= 2) {
                o.strokes.push((std::mem::take(&mut run), state_rgb(prev)));
            }
            run = vec![Point::new(w[0].x, w[0].y)];
            state = Some(s);
        }
        run.push(Point::new(w[1].x, w[1].y));
    }
    if let Some(s) = state.filter(|_| run.len() >= 2) {
        o.strokes.push((run, state_rgb(s)));
    }
    let g = &e.graph;
    for edge in &g.edges {
        let mut pts: Vec<Point> = Vec::new();
        if let Some(f) = edge.from {
            pts.push(Point::new(g.nodes[f].at.x, g.nodes[f].at.y));
        }
        pts.extend(
            edge.laps
                .iter()
                .map(|(lo, hi)| Point::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0)),
        );
        if let Some(t) = edge.to {
            pts.push(Point::new(g.nodes[t].at.x, g.nodes[t].at.y));
        }
        for w in pts.windows(2) {
            o.lines.push((w[0], w[1], GRAPH_RGB));
        }
    }
    for t in truth {
        let p = Point::new((t.at.x + t.to.x) / 2.0, (t.at.y + t.to.y) / 2.0);
        o.markers.push((p, TRUE_RGB, MarkerShape::Ring, 9.0));
    }
    for n in &g.nodes {
        let rgb = if n.kind.event == Event::In {
            IN_RGB
        } else {
            OUT_RGB
        };
        let shape = if n.confirmed {
            MarkerShape::Disc
        } else {
            MarkerShape::Square
        };
        o.markers
            .push((Point::new(n.at.x, n.at.y), rgb, shape, 5.0));
    }
    if let (Some(a), Some(b)) = (e.trace.first(), e.trace.last()) {
        o.markers
            .push((Point::new(a.x, a.y), [30, 160, 60], MarkerShape::Disc, 7.0));
        o.markers.push((
            Point::new(b.x, b.y),
            [210, 40, 40],
            MarkerShape::Square,
            6.0,
        ));
    }
    for s in [
        State::MotionToBoundary,
        State::BorderFollowing,
        State::ObstacleFollowing,
        State::Transit,
    ] {
        o.legend
            .push((s.label().to_string(), state_rgb(s), LegendMark::Stroke));
    }
    o.legend
        .push(("Reeb graph edge".into(), GRAPH_RGB, LegendMark::Line));
    o.legend.push((
        "IN critical point".into(),
        IN_RGB,
        LegendMark::Marker(MarkerShape::Disc),
    ));
    o.legend.push((
        "OUT critical point".into(),
        OUT_RGB,
        LegendMark::Marker(MarkerShape::Disc),
    ));
    o.legend.push((
        "class from follower".into(),
        [90, 90, 90],
        LegendMark::Marker(MarkerShape::Square),
    ));
    o.legend.push((
        "true critical point".into(),
        TRUE_RGB,
        LegendMark::Marker(MarkerShape::Ring),
    ));
    o
}

/// The executed path as a contract path file with a `state` column
/// ([`State::code`]: 0 start, 1 motion to boundary, 2 border following,
/// 3 obstacle following, 4 transit).
#[must_use]
pub fn trace_csv(e: &Exploration) -> String {
    let mut s = String::with_capacity(e.trace.len() * 28 + 16);
    s.push_str("x,y,state\n");
    for t in &e.trace {
        let _ = writeln!(s, "{},{},{}", t.x, t.y, t.state.code());
    }
    s
}

/// The graph as JSON (`.json`) or RON (anything else) text, by `path`'s extension.
///
/// # Errors
/// [`Error::Internal`] if serialisation fails.
pub fn graph_text(graph: &ReebGraph, path: &Path) -> Result<String> {
    match graph_format(path)? {
        GraphFormat::Json => serde_json::to_string_pretty(graph)
            .map_err(|e| Error::Internal(format!("graph serialisation failed: {e}"))),
        GraphFormat::Ron => ron::ser::to_string_pretty(graph, ron::ser::PrettyConfig::default())
            .map_err(|e| Error::Internal(format!("graph serialisation failed: {e}"))),
    }
}

/// How a graph file is written, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GraphFormat {
    /// `.json`.
    Json,
    /// `.ron`.
    Ron,
}

/// The format of a graph file named `path`.
///
/// # Errors
/// [`Error::BadParameter`] naming `--graph` unless the name ends in `.json`
/// or `.ron` (any case).
pub fn graph_format(path: &Path) -> Result<GraphFormat> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("json") => Ok(GraphFormat::Json),
        Some(e) if e.eq_ignore_ascii_case("ron") => Ok(GraphFormat::Ron),
        _ => Err(Error::BadParameter {
            name: "--graph",
            value: path.display().to_string(),
            expected: "a file name ending in .json or .ron".into(),
        }),
    }
}
