//! Path metrics exactly as the contract defines them (CLI, experiments, tests).
//!
//! | key | meaning |
//! |---|---|
//! | `coverage` | covered coverable cells / coverable cells (path sampled every resolution/4) |
//! | `collisions` | path samples whose cell is not admissible |
//! | `length_m` | polyline length |
//! | `turns` | vertices whose heading changes by more than 30° (segments shorter than resolution/4 merged first) |
//! | `rotation_rad` | sum of absolute heading changes (same merged polyline) |
//! | `redundancy` | `length_m · 2T / covered area` (1.0 = no overlap; `null` when nothing is covered) |
//! | `steps` | `length_m / resolution` |
//! | `est_time_s` | `length_m / v + rotation_rad / w`, v = 0.3 m/s, w = 0.52 rad/s unless set |
//! | `bound_time_s` | `max(0, covered area - pi T^2) / 2T / v`: straight lanes of the tool's width, no overlap, no turn (a disc covers pi T^2 without moving) |
//! | `time_efficiency` | `bound_time_s / est_time_s` (`null` when the path takes no time) |
//!
//! The coverable set is the contract's, built from the path's first waypoint as
//! the start. "Covered area" is the number of covered coverable cells times the
//! cell area. Merging short segments: walking the waypoints, a vertex is kept
//! only when it lies at least resolution/4 from the last kept one; the final
//! waypoint always ends the merged polyline.

use oxcover_grid::footprint::{covered_cells_of, for_each_sample, mark_covered};
use oxcover_grid::math::{heading, wrap_angle};
use oxcover_grid::{Coverability, DiscRobot, Grid, MapFrame, OccupancyGrid, Point};
use oxcover_planners::TimeModel;
use serde::Serialize;

use crate::error::Result;

/// Speeds used for `est_time_s` (the planners' [`TimeModel`]: v = 0.3 m/s,
/// w = 0.52 rad/s by default).
pub type MetricParams = TimeModel;

/// The contract's metrics of one path, plus the counts behind them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metrics {
    /// Covered coverable cells / coverable cells.
    pub coverage: f64,
    /// Samples whose cell is not admissible.
    pub collisions: usize,
    /// Polyline length in metres.
    pub length_m: f64,
    /// Vertices turning by more than 30°.
    pub turns: usize,
    /// Sum of absolute heading changes in radians.
    pub rotation_rad: f64,
    /// `length · 2T / covered area`; `None` (JSON null) when nothing is covered.
    pub redundancy: Option<f64>,
    /// `length / resolution`.
    pub steps: f64,
    /// `length / v + rotation / w` in seconds.
    pub est_time_s: f64,
    /// `max(0, covered area - pi T^2) / 2T / v` in seconds: straight lanes
    /// of the tool's width, no overlap, no turn (a lower bound in practice;
    /// a disc covers pi T^2 without moving).
    pub bound_time_s: f64,
    /// `bound_time_s / est_time_s`; `None` (JSON null) when the path takes
    /// no time (a single waypoint).
    pub time_efficiency: Option<f64>,
    /// Covered coverable cells.
    pub covered_cells: usize,
    /// Coverable cells.
    pub coverable_cells: usize,
    /// Samples taken along the path.
    pub samples: usize,
    /// Waypoints in the path.
    pub waypoints: usize,
}

/// Metrics together with the covered-cell mask (for rendering).
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// The metrics.
    pub metrics: Metrics,
    /// Cells whose centre lies within the tool radius of a sample.
    pub covered: Grid<bool>,
    /// The coverage problem the path was scored against.
    pub problem: Coverability,
}

/// Scores `points` on `map` for `robot`, the first waypoint being the start.
///
/// # Errors
/// Bad map or radii, an empty path, or a first waypoint that is outside the map
/// or not admissible (the contract's start rules).
pub fn evaluate(
    map: &OccupancyGrid,
    robot: DiscRobot,
    points: &[Point],
    params: &MetricParams,
) -> Result<Evaluation> {
    let start = points.first().copied();
    let Some(start) = start else {
        return Err(crate::Error::BadParameter {
            name: "path",
            value: "empty".into(),
            expected: "at least one waypoint".into(),
        });
    };
    let problem = Coverability::new(map, robot, Some(start))?;
    // A path is sampled every resolution/4; refuse one whose samples could not
    // be counted in reasonable time (e.g. a waypoint kilometres off the map).
    let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let samples = length / (map.resolution() / 4.0);
    if samples > MAX_SAMPLES {
        return Err(crate::Error::BadParameter {
            name: "path",
            value: format!("{length:.1} m long"),
            expected: format!(
                "a path of at most {:.0} m on this map ({MAX_SAMPLES:.0} samples at resolution/4); check for waypoints far outside the map",
                MAX_SAMPLES * map.resolution() / 4.0
            ),
        });
    }
    Ok(evaluate_problem(map.frame(), problem, points, params))
}

/// Most samples [`evaluate`] takes (about a minute of work); longer paths are refused.
pub const MAX_SAMPLES: f64 = 5e8;

/// Scores `points` against an existing coverage problem (its start should be
/// the cell of the first waypoint).
///
/// The covered cells are found by [`mark_covered`]: the same cells as a disc
/// round every sample ([`for_each_sample`],
/// [`mark_disc`](oxcover_grid::footprint::mark_disc); property-tested in
/// `oxcover-grid`), found segment by segment.
#[must_use]
pub fn evaluate_problem(
    frame: &MapFrame,
    problem: Coverability,
    points: &[Point],
    params: &MetricParams,
) -> Evaluation {
    let mut covered = Grid::new(frame.width(), frame.height(), false);
    mark_covered(frame, points, problem.robot.tool_radius, &mut covered);
    evaluate_covered(frame, problem, points, covered, params)
}

/// [`evaluate_problem`] given the cells `points` covers (`covered`, as
/// [`mark_covered`] marks them on an empty grid of `frame`'s size with the
/// problem's tool radius), for a caller that has them already.
pub(crate) fn evaluate_covered(
    frame: &MapFrame,
    problem: Coverability,
    points: &[Point],
    covered: Grid<bool>,
    params: &MetricParams,
) -> Evaluation {
    let res = frame.resolution();
    let tool = problem.robot.tool_radius;
    let mut samples = 0usize;
    let mut collisions = 0usize;
    for_each_sample(points, res / 4.0, |p| {
        samples += 1;
        if !frame.cell_at(p).is_some_and(|c| problem.admissible[c]) {
            collisions += 1;
        }
    });
    let coverable_cells = problem.coverable_count();
    let covered_cells = covered.count_both(&problem.coverable);
    let shape = PathShape::of(points, res);
    let covered_area = covered_cells as f64 * res * res;
    let est_time_s = params.time(shape.length_m, shape.rotation_rad);
    // A disc covers pi T^2 without moving.
    let swept = (covered_area - std::f64::consts::PI * tool * tool).max(0.0);
    let bound_time_s = swept / (2.0 * tool) / params.linear_speed;
    let metrics = Metrics {
        coverage: if coverable_cells == 0 {
            0.0
        } else {
            covered_cells as f64 / coverable_cells as f64
        },
        collisions,
        length_m: shape.length_m,
        turns: shape.turns,
        rotation_rad: shape.rotation_rad,
        redundancy: (covered_area > 0.0).then(|| shape.length_m * 2.0 * tool / covered_area),
        steps: shape.length_m / res,
        est_time_s,
        bound_time_s,
        time_efficiency: (est_time_s > 0.0).then(|| bound_time_s / est_time_s),
        covered_cells,
        coverable_cells,
        samples,
        waypoints: points.len(),
    };
    Evaluation {
        metrics,
        covered,
        problem,
    }
}

/// Coverage (covered coverable cells / coverable cells) of several
/// polylines together, each sampled as the metrics sample a path (no move
/// between them is counted).
#[must_use]
pub fn coverage_of(frame: &MapFrame, problem: &Coverability, pieces: &[Vec<Point>]) -> f64 {
    let pieces: Vec<&[Point]> = pieces.iter().map(Vec::as_slice).collect();
    let covered = covered_cells_of(frame, &pieces, problem.robot.tool_radius);
    covered_fraction(problem, &covered)
}

/// Covered coverable cells / coverable cells, the cells covered being
/// `covered` (0 when nothing is coverable).
pub(crate) fn covered_fraction(problem: &Coverability, covered: &Grid<bool>) -> f64 {
    let coverable = problem.coverable_count();
    if coverable == 0 {
        return 0.0;
    }
    let hit = covered.count_both(&problem.coverable);
    hit as f64 / coverable as f64
}

/// Length and turning of a polyline, as the metrics define them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathShape {
    /// Polyline length in metres.
    pub length_m: f64,
    /// Vertices turning by more than 30° after merging short segments.
    pub turns: usize,
    /// Sum of absolute heading changes after merging short segments.
    pub rotation_rad: f64,
}

impl PathShape {
    /// Measures `points` with short segments (< `resolution / 4`) merged.
    #[must_use]
    pub fn of(points: &[Point], resolution: f64) -> Self {
        // Folded from +0.0: an f64 `sum` starts at -0.0, which a path of one
        // waypoint would report (and print) as a length of "-0".
        let length_m = points
            .windows(2)
            .map(|w| (w[1] - w[0]).norm())
            .fold(0.0, |a, b| a + b);
        let merged: Vec<Point> = merged_indices(points, resolution)
            .into_iter()
            .map(|i| points[i])
            .collect();
        let mut turns = 0;
        let mut rotation_rad = 0.0;
        let headings: Vec<f64> = merged.windows(2).map(|w| heading(&(w[1] - w[0]))).collect();
        for h in headings.windows(2) {
            let d = wrap_angle(h[1] - h[0]).abs();
            rotation_rad += d;
            if d > std::f64::consts::FRAC_PI_6 + 1e-12 {
                turns += 1;
            }
        }
        Self {
            length_m,
            turns,
            rotation_rad,
        }
    }
}

/// The waypoints the metrics keep (indices into `points`): each at least
/// `resolution / 4` from the previous one kept, and the last waypoint always
/// ending the merged polyline.
fn merged_indices(points: &[Point], resolution: f64) -> Vec<usize> {
    let min_seg = resolution / 4.0;
    let mut kept: Vec<usize> = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        match kept.last() {
            None => kept.push(i),
            Some(&j) if (p - points[j]).norm() >= min_seg => kept.push(i),
            Some(_) => {}
        }
    }
    if let (Some(&end), Some(&last)) = (points.last(), kept.last()) {
        let n = kept.len();
        let end_index = points.len() - 1;
        if n > 1 && points[last] != end {
            kept[n - 1] = end_index;
        } else if n == 1 && (end - points[last]).norm() > 0.0 {
            kept.push(end_index);
        }
    }
    kept
}

/// When the robot reaches each waypoint, in seconds from the first, by the
/// time model of `est_time_s`: each segment driven at `v`, and each turn of
/// the merged polyline (as `rotation_rad` counts it) taken at `w` on the
/// spot before driving on. The last time is `est_time_s` (up to rounding).
#[must_use]
pub fn arrival_times(points: &[Point], resolution: f64, time: &TimeModel) -> Vec<f64> {
    let kept = merged_indices(points, resolution);
    // The turn made at each kept interior vertex, by its waypoint index.
    let mut turn_at = vec![0.0; points.len()];
    let headings: Vec<f64> = kept
        .windows(2)
        .map(|w| heading(&(points[w[1]] - points[w[0]])))
        .collect();
    for (k, h) in headings.windows(2).enumerate() {
        turn_at[kept[k + 1]] += wrap_angle(h[1] - h[0]).abs();
    }
    let mut out = Vec::with_capacity(points.len());
    let (mut length, mut rotation) = (0.0, 0.0);
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            length += (p - points[i - 1]).norm();
            rotation += turn_at[i - 1];
        }
        out.push(time.time(length, rotation));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::Cell;
    use oxcover_grid::io::parse_ascii;
    use std::f64::consts::PI;

    #[test]
    fn one_waypoint_has_no_negative_zero() {
        let s = PathShape::of(&[Point::new(0.5, 0.5)], 1.0);
        assert_eq!(s.length_m, 0.0);
        assert!(s.length_m.is_sign_positive(), "length {:?}", s.length_m);
        assert_eq!(format!("{:.2}", s.length_m), "0.00");
    }

    #[test]
    fn shape_of_a_u_turn() {
        let pts = [
            Point::new(0.5, 0.5),
            Point::new(3.5, 0.5),
            Point::new(3.5, 1.5),
            Point::new(0.5, 1.5),
        ];
        let s = PathShape::of(&pts, 1.0);
        assert_eq!(s.length_m, 7.0);
        assert_eq!(s.turns, 2);
        assert!((s.rotation_rad - PI).abs() < 1e-12);
        // A jog shorter than resolution/4 is merged away.
        let jog = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 0.1),
            Point::new(2.0, 0.1),
        ];
        assert_eq!(PathShape::of(&jog, 1.0).turns, 0);
    }

    #[test]
    fn metrics_of_a_complete_boustrophedon() {
        let (map, _) = parse_ascii(
            "
            ....
            ....",
        )
        .unwrap();
        let f = *map.frame();
        let cells = [(0, 0), (0, 3), (1, 3), (1, 0)].map(Cell::from);
        let pts: Vec<Point> = cells.iter().map(|&c| f.cell_center(c)).collect();
        let e = evaluate(
            &map,
            DiscRobot::cell_sized(1.0),
            &pts,
            &MetricParams::default(),
        )
        .unwrap();
        let m = e.metrics;
        assert_eq!(m.coverage, 1.0);
        assert_eq!(m.collisions, 0);
        assert_eq!(m.length_m, 7.0);
        assert_eq!(m.steps, 7.0);
        assert_eq!(m.turns, 2);
        assert_eq!(m.redundancy, Some(7.0 / 8.0));
        assert!((m.est_time_s - (7.0 / 0.3 + PI / 0.52)).abs() < 1e-9);
        // 8 covered cells of 1 m², less the disc of radius 0.5 m the tool
        // covers standing still, a tool 1 m wide, at 0.3 m/s.
        assert!((m.bound_time_s - (8.0 - PI * 0.25) / 0.3).abs() < 1e-9);
        let eff = m.time_efficiency.unwrap_or_default();
        assert!((eff - m.bound_time_s / m.est_time_s).abs() < 1e-12);
        let slow = evaluate(
            &map,
            DiscRobot::cell_sized(1.0),
            &pts,
            &MetricParams::new(0.1, 1.0).unwrap(),
        )
        .unwrap()
        .metrics;
        assert!((slow.est_time_s - (7.0 / 0.1 + PI)).abs() < 1e-9);
        assert!((slow.bound_time_s - (8.0 - PI * 0.25) / 0.1).abs() < 1e-9);
        assert_eq!(m.samples, 1 + 12 + 4 + 12);
    }

    #[test]
    fn covered_cells_are_a_disc_round_every_sample() {
        // A slanted zig-zag over a rotated, offset frame: the cells the
        // metrics count are those of the definition, a disc round each
        // sample (the cells are found segment by segment).
        let (map, _) = parse_ascii(&vec![".".repeat(40); 30].join("\n")).unwrap();
        let map =
            OccupancyGrid::new(map.cells().clone(), 0.05, Point::new(-0.4, 0.3)).with_yaw(0.4);
        let f = *map.frame();
        let pts: Vec<Point> = [(2, 2), (3, 37), (9, 5), (15, 30), (27, 33), (28, 1)]
            .map(|(r, c)| f.cell_center(Cell::new(r, c)))
            .to_vec();
        let robot = DiscRobot::new(0.0, 0.13).unwrap();
        let e = evaluate(&map, robot, &pts, &MetricParams::default()).unwrap();
        let mut disc = Grid::new(40, 30, false);
        for_each_sample(&pts, 0.05 / 4.0, |p| {
            oxcover_grid::footprint::mark_disc(&f, p, 0.13, &mut disc);
        });
        assert_eq!(e.covered, disc);
        assert!(e.metrics.coverage > 0.5 && e.metrics.coverage < 1.0);
    }

    #[test]
    fn collisions_count_samples_in_walls() {
        let (map, _) = parse_ascii("...\n.#.\n...").unwrap();
        let f = *map.frame();
        let pts = [
            f.cell_center(Cell::new(1, 0)),
            f.cell_center(Cell::new(1, 2)),
        ];
        let m = evaluate(
            &map,
            DiscRobot::cell_sized(1.0),
            &pts,
            &MetricParams::default(),
        )
        .unwrap()
        .metrics;
        // Samples at 0.5 + k/4 for k = 0..=8; those with x in [1, 2) are in the wall.
        assert_eq!(m.collisions, 4);
        assert!(
            evaluate(
                &map,
                DiscRobot::cell_sized(1.0),
                &[],
                &MetricParams::default()
            )
            .is_err()
        );
        let wall = [f.cell_center(Cell::new(1, 1))];
        assert!(
            evaluate(
                &map,
                DiscRobot::cell_sized(1.0),
                &wall,
                &MetricParams::default()
            )
            .is_err()
        );
    }
}
