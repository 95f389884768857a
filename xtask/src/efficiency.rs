//! `cargo xtask efficiency`: how long a robot needs for each complete
//! planner's path, rooms on and off, on the real floor plans; writes
//! `docs/efficiency.md`.
//!
//! Two settings: the ipa floor plans at 0.05 m/px with robot = tool radius
//! 0.3 m, and the ROS maps with robot = tool radius 0.15 m; start at the
//! first cell of the largest admissible region, boundary pass on, the
//! contract's speeds (0.3 m/s, 0.52 rad/s). Per planner and rooms setting:
//! the worst coverage, the collisions, means of length, turns per 10 m²
//! covered, estimated time and time efficiency (`bound_time_s /
//! est_time_s`), and the mean and slowest planning time. Maps it cannot
//! find are skipped, as the benches do. Quadratic planners are skipped
//! above the sizes of `cargo xtask acceptance`.

use std::fmt::Write as _;

use oxcover::pipeline::{PlanOutcome, PlanRequest, plan, planner, planners, room_units};
use oxcover::planners::{CoverageProblem, PlannerOptions, Start, TimeModel};
use oxcover::render::{Scene, render_to_file};

use crate::lane_ceiling::{Ceiling, ceiling};
use oxcover::report::metric_rows;
use oxcover_grid::math::wrap_angle;
use oxcover_grid::{DiscRobot, Occupancy, OccupancyGrid, Point};
use rayon::prelude::*;

/// One plan's figures.
#[derive(Clone, Debug)]
struct Run {
    coverage: f64,
    collisions: usize,
    length_m: f64,
    turns_per_10m2: f64,
    est_time_s: f64,
    efficiency: f64,
    plan_ms: f64,
    boundary_share: f64,
    /// Area covered and free area of the map (m²).
    covered_m2: f64,
    free_m2: f64,
    room_units: Option<usize>,
    /// Time efficiency of the same path under other time models than the
    /// contract's ([`other_models`]).
    other_models: [f64; 3],
    /// Where the estimated time goes ([`time_split`]).
    split: TimeSplit,
}

impl Run {
    fn of(out: &PlanOutcome, map: &OccupancyGrid, time: &TimeModel) -> Self {
        let res = map.resolution();
        let m = &out.evaluation.metrics;
        let area = m.covered_cells as f64 * res * res;
        Self {
            coverage: m.coverage,
            collisions: m.collisions,
            length_m: m.length_m,
            turns_per_10m2: if area > 0.0 {
                m.turns as f64 * 10.0 / area
            } else {
                0.0
            },
            est_time_s: m.est_time_s,
            efficiency: m.time_efficiency.unwrap_or(0.0),
            plan_ms: out.plan_ms,
            boundary_share: if m.length_m > 0.0 {
                out.boundary_length_m / m.length_m
            } else {
                0.0
            },
            covered_m2: area,
            free_m2: map.cells().count(|&o| o == Occupancy::Free) as f64 * res * res,
            room_units: out.room_units,
            other_models: other_models(&out.points, m.bound_time_s, time),
            split: time_split(&out.points, m.bound_time_s, time),
        }
    }
}

/// Heading changes up to this are "gentle" (the contract's turn threshold).
const GENTLE_RAD: f64 = 30.0 * std::f64::consts::PI / 180.0;

/// Time efficiency (`bound / time`) of the polyline `points` under three
/// time models other than the contract's, which charges every heading
/// change as a stop and a turn on the spot (`length / v + rotation / w`):
/// turns of at most [`GENTLE_RAD`] taken while driving (a segment takes
/// the longer of its drive and the turn before it; sharper turns as the
/// contract charges them); every turn taken while driving; turning free
/// (the drive alone), over the path's [`legs`].
fn other_models(points: &[Point], bound: f64, time: &TimeModel) -> [f64; 3] {
    let (v, w) = (time.linear_speed, time.angular_speed);
    let mut times = [0.0f64; 3];
    for (length, turn) in legs(points) {
        let (drive, spin) = (length / v, turn / w);
        times[0] += if turn <= GENTLE_RAD {
            drive.max(spin)
        } else {
            drive + spin
        };
        times[1] += drive.max(spin);
        times[2] += drive;
    }
    times.map(|t| if t > 0.0 { bound / t } else { 0.0 })
}

/// Each segment of the polyline `points` as its length and the heading
/// change (radians, absolute) from the segment before it (0 for the
/// first); repeated points are skipped, as the contract's rotation skips
/// them.
fn legs(points: &[Point]) -> impl Iterator<Item = (f64, f64)> + '_ {
    let mut heading: Option<f64> = None;
    let mut last: Option<Point> = None;
    points.iter().filter_map(move |&p| {
        let a = last.filter(|&a| a != p);
        last = Some(p);
        let d = p - a?;
        let h = d.y.atan2(d.x);
        let turn = heading.map_or(0.0, |g| wrap_angle(h - g).abs());
        heading = Some(h);
        Some((d.norm(), turn))
    })
}

/// A path's estimated time under the contract's model, in parts (seconds).
#[derive(Clone, Copy, Debug, Default)]
struct TimeSplit {
    /// The contract's `bound_time_s`.
    bound: f64,
    /// Driving beyond the bound: overlap, links, transits.
    overlap: f64,
    /// Turning at the contract's turns (heading changes above 30°).
    turns: f64,
    /// Turning at bends of at most 30° (along curved and ragged walls,
    /// straightened staircases).
    bends: f64,
}

impl TimeSplit {
    fn total(&self) -> f64 {
        self.bound + self.overlap + self.turns + self.bends
    }
}

/// `points`' estimated time (`length / v + rotation / w`) split into the
/// bound, the drive beyond it, and the turning at heading changes above
/// [`GENTLE_RAD`] (the contract's turns) and at or below it, over the
/// path's [`legs`]; the contract merges segments shorter than a quarter cell before it counts
/// turns, this split does not (it splits the rotation, which is summed
/// over every heading change).
fn time_split(points: &[Point], bound: f64, time: &TimeModel) -> TimeSplit {
    let (v, w) = (time.linear_speed, time.angular_speed);
    let mut split = TimeSplit {
        bound,
        overlap: -bound,
        ..TimeSplit::default()
    };
    for (length, turn) in legs(points) {
        split.overlap += length / v;
        if turn > GENTLE_RAD {
            split.turns += turn / w;
        } else {
            split.bends += turn / w;
        }
    }
    split
}

/// Result of one planner on one map with rooms on or off.
enum Outcome {
    Done(Run),
    Skipped,
    Failed(String),
}

struct Setting {
    name: &'static str,
    radius: f64,
    maps: Vec<(String, OccupancyGrid)>,
    /// Issue 15's target for the best mean time efficiency.
    target_efficiency: f64,
    /// Issue 15's target for turns per 10 m² covered, if any.
    target_turns: Option<f64>,
    /// Whether the maps are also read as the ipa benchmark reads them
    /// ([`crate::ipa_benchmark_reading`]) and the best planner's figures
    /// given both ways.
    benchmark_reading: bool,
}

fn request(
    name: &str,
    map: &OccupancyGrid,
    radius: f64,
    rooms: bool,
) -> anyhow::Result<PlanRequest> {
    Ok(
        PlanRequest::with_planner(planner(name, &PlannerOptions::new())?, map.resolution())
            .robot(DiscRobot::new(radius, radius)?)
            .start(Start::LargestRegion)
            .rooms(rooms),
    )
}

fn run_one(name: &str, map: &OccupancyGrid, radius: f64, rooms: bool) -> Outcome {
    if let Some(limit) = crate::acceptance::quadratic_limit(name) {
        let cells = DiscRobot::new(radius, radius)
            .ok()
            .and_then(|r| CoverageProblem::new(map, r, Start::LargestRegion).ok())
            .map_or(0, |p| p.input(0).coverage_cells());
        if cells > limit {
            return Outcome::Skipped;
        }
    }
    match request(name, map, radius, rooms).and_then(|r| Ok((plan(map, &r)?, r.time))) {
        Ok((out, time)) => Outcome::Done(Run::of(&out, map, &time)),
        Err(e)
            if e.to_string().contains("accepts at most")
                || e.to_string().contains("needs a coverage grid") =>
        {
            Outcome::Skipped
        }
        Err(e) => Outcome::Failed(e.to_string()),
    }
}

/// The target line for `s`'s maps read as the ipa benchmark reads them:
/// the best planner `name` (index `p` of the runs `at`) planned again,
/// rooms on, on each map that reads differently, and the mean time
/// efficiency with those maps so read.
fn benchmark_line<'r>(
    s: &Setting,
    p: usize,
    name: &str,
    at: &dyn Fn(usize, usize, bool) -> &'r Outcome,
    failures: &mut Vec<String>,
) -> anyhow::Result<String> {
    let mut differ = Vec::new();
    for (m, (map_name, map)) in s.maps.iter().enumerate() {
        if let Some(theirs) = crate::ipa_benchmark_reading(map_name, map)? {
            differ.push((m, theirs));
        }
    }
    let again: Vec<Outcome> = differ
        .par_iter()
        .map(|(_, map)| run_one(name, map, s.radius, true))
        .collect();
    // (time efficiency, turns per 10 m² covered) of every map, so read.
    let mut figures: Vec<Option<(f64, f64)>> = (0..s.maps.len())
        .map(|m| match at(p, m, true) {
            Outcome::Done(r) => Some((r.efficiency, r.turns_per_10m2)),
            _ => None,
        })
        .collect();
    let mut parts = Vec::new();
    for ((m, _), outcome) in differ.iter().zip(&again) {
        let map_name = short(&s.maps[*m].0);
        let (Outcome::Done(ours), Outcome::Done(theirs)) = (at(p, *m, true), outcome) else {
            if let Outcome::Failed(e) = outcome {
                failures.push(format!("{name} on {map_name} read as its benchmark: {e}"));
            }
            figures[*m] = None;
            continue;
        };
        if theirs.collisions > 0 || theirs.coverage < 0.99 {
            failures.push(format!(
                "{name} on {map_name} read as its benchmark: coverage {:.4}, {} collisions",
                theirs.coverage, theirs.collisions
            ));
        }
        figures[*m] = Some((theirs.efficiency, theirs.turns_per_10m2));
        parts.push(format!(
            "{map_name} (free {:.0} → {:.0} m², covered {:.0} → {:.0} m², time efficiency {:.3} → {:.3}, turns per 10 m² {:.1} → {:.1}, coverage {:.4}, {} collisions)",
            ours.free_m2,
            theirs.free_m2,
            ours.covered_m2,
            theirs.covered_m2,
            ours.efficiency,
            theirs.efficiency,
            ours.turns_per_10m2,
            theirs.turns_per_10m2,
            theirs.coverage,
            theirs.collisions
        ));
    }
    if differ.is_empty() {
        return Ok(String::new());
    }
    let verdict = |ok: bool| if ok { "met" } else { "**not met**" };
    let all: Option<Vec<(f64, f64)>> = figures.into_iter().collect();
    let mean_line = all.map_or_else(
        || "a map failed, so no mean".to_string(),
        |v| {
            let e = mean(&v.iter().map(|f| f.0).collect::<Vec<_>>());
            let t = mean(&v.iter().map(|f| f.1).collect::<Vec<_>>());
            let turns = s.target_turns.map_or_else(String::new, |target| {
                format!(
                    "; turns per 10 m² covered {t:.1}, {} against ≤ {target}",
                    verdict(t <= target)
                )
            });
            format!(
                "the mean time efficiency so read {e:.3}, {} against the target of {:.2}{turns}",
                verdict(e >= s.target_efficiency),
                s.target_efficiency
            )
        },
    );
    Ok(format!(
        "- the same targets with the plans read as their benchmark reads them (`../shared/maps/ipa-floorplans/SOURCE.md`: grey above 250 free, every other value an obstacle; the contract's defaults for an image without a yaml, which this page follows, call grey above 205 free): {} of {} plans read differently, {}; {mean_line} (the start again the first cell of the largest admissible region)\n",
        parts.len(),
        s.maps.len(),
        parts.join("; "),
    ))
}

/// A setting's name, its best planner and, per map, the map's name, its
/// lane-and-loop ceiling and the best planner's time efficiency and time
/// split (rooms on).
type SettingCeilings<'a> = (
    &'a str,
    &'a str,
    Vec<(String, Ceiling, Option<(f64, TimeSplit)>)>,
);

/// The page's section on each map's lane-and-loop ceiling
/// ([`crate::lane_ceiling`]) beside the best planner's time efficiency.
fn ceiling_section(ceilings: &[SettingCeilings<'_>], settings: &[Setting]) -> String {
    let mut md = String::from(
        "## What each map leaves: the lane-and-loop ceiling\n\n\
         Per map, the time efficiency of a plan of straight lanes and wall loops that wastes nothing else, under the contract's time model (`xtask/src/lane_ceiling.rs`): the drive is the bound itself (no overlap, no link, no transit); one full turn (2π) for each boundary of the region the robot drives in, its outline and each hole (with robot radius = tool radius the cells along an obstacle are within reach only from the region's edge beside them, so every edge is traced); lanes the tool's width apart at the angle (whole degrees) with the fewest, passing every hole for free, a half turn (π) to enter each lane after the first (a lane: a run of a line across the region, holes filled in, at least a tool width long). A model of the pattern, optimistic in all it leaves out (overlap, links, transits, the corners of non-convex outlines, raster walls, the ways round islands), not a proof that no path does better. `cut lanes` and `cut`: the same with every hole cutting the lines that cross it (a lane is a run of a line across the region as it is), at the angle with the fewest such lanes: real lanes stop at a building or a rack (the planner's pass only small islands, bending round them, which costs turning too); optimistic in the same terms, and no bound either, since a plan whose parts lie at different angles can need fewer lanes than any one angle's. `share`: the best planner's time efficiency (rooms on) over the ceiling; `overlap s`, `turns s` and `bends s`: where that plan's estimated time beyond the bound goes (below each table). Measured by this page's run.\n\n",
    );
    for (setting, planner, rows) in ceilings {
        let target = settings
            .iter()
            .find(|s| s.name == *setting)
            .map_or(0.0, |s| s.target_efficiency);
        let _ = write!(
            md,
            "### {setting}\n\n| map | bound s | holes | lanes | angle ° | ceiling | cut lanes | cut | {planner} | share | overlap s | turns s | bends s |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
        );
        for (name, c, planned) in rows {
            let cols = planned.map_or_else(
                || " | | | | ".to_string(),
                |(e, t)| {
                    format!(
                        "{e:.3} | {:.2} | {:.0} | {:.0} | {:.0}",
                        e / c.efficiency,
                        t.overlap,
                        t.turns,
                        t.bends
                    )
                },
            );
            let _ = writeln!(
                md,
                "| {name} | {:.0} | {} | {} | {} | {:.3} | {} | {:.3} | {cols} |",
                c.bound_s,
                c.holes,
                c.lanes,
                c.angle_deg,
                c.efficiency,
                c.cut_lanes,
                c.cut_efficiency
            );
        }
        let splits: Vec<TimeSplit> = rows.iter().filter_map(|r| r.2.map(|p| p.1)).collect();
        let planned: Vec<f64> = rows.iter().filter_map(|r| r.2.map(|p| p.0)).collect();
        // Per ceiling: its mean, the maps below the target, and (the model
        // is no bound) the maps whose plan beats it.
        let summary = |of: fn(&Ceiling) -> f64| {
            let beaten: Vec<&str> = rows
                .iter()
                .filter(|r| r.2.is_some_and(|(e, _)| e > of(&r.1)))
                .map(|r| r.0.as_str())
                .collect();
            (
                mean(&rows.iter().map(|r| of(&r.1)).collect::<Vec<_>>()),
                rows.iter().filter(|r| of(&r.1) < target).count(),
                beaten,
            )
        };
        let (ceiling_mean, below, beaten) = summary(|c| c.efficiency);
        let beaten = if beaten.is_empty() {
            "no map's plan beats its ceiling".to_string()
        } else {
            format!("the plans of {} beat their ceilings", beaten.join(", "))
        };
        let _ = writeln!(
            md,
            "\nMean ceiling {ceiling_mean:.3}; issue 15's target for the mean, {target:.2}, is {:.0} % of it, and {below} of {} maps have a ceiling below the target; {planner} reaches {:.3}, {:.0} % of the mean ceiling; {beaten}.",
            100.0 * target / ceiling_mean,
            rows.len(),
            mean(&planned),
            100.0 * mean(&planned) / ceiling_mean
        );
        let (cut_mean, cut_below, cut_beaten) = summary(|c| c.cut_efficiency);
        let cut_beaten = match cut_beaten.as_slice() {
            [] => "no map's plan beats it".to_string(),
            [one] => format!("the plan of {one} beats it"),
            many => format!("the plans of {} beat it", many.join(", ")),
        };
        let _ = writeln!(
            md,
            "With the holes cutting the lanes, the mean cut ceiling is {cut_mean:.3}; the target is {:.0} % of it, {cut_below} of {} maps have a cut ceiling below the target, {planner} reaches {:.0} % of the mean, and {cut_beaten}.",
            100.0 * target / cut_mean,
            rows.len(),
            100.0 * mean(&planned) / cut_mean
        );
        let _ = writeln!(md, "\n{}\n", split_summary(planner, &splits));
    }
    md
}

/// What the plans' time beyond the bound is made of, summed over `splits`,
/// and the mean time efficiency were each part free.
fn split_summary(planner: &str, splits: &[TimeSplit]) -> String {
    let sum = |f: &dyn Fn(&TimeSplit) -> f64| splits.iter().map(f).sum::<f64>();
    let over = sum(&|t| t.total() - t.bound).max(f64::MIN_POSITIVE);
    let share = |part: f64| 100.0 * part / over;
    let without = |f: &dyn Fn(&TimeSplit) -> f64| {
        mean(
            &splits
                .iter()
                .map(|t| t.bound / (t.total() - f(t)).max(f64::MIN_POSITIVE))
                .collect::<Vec<_>>(),
        )
    };
    format!(
        "Where the time of {planner} beyond the bound goes (rooms on, summed over the maps; `overlap s`: driving beyond the bound, that is overlap, links and transits; `turns s`: turning at heading changes above 30°, the contract's turns; `bends s`: turning at heading changes of 30° or less, along curved and ragged walls): overlap {:.0} %, turns {:.0} %, bends {:.0} %. The mean time efficiency were the bends free: {:.3}; the overlap free: {:.3}; both: {:.3} (what is left is the turns alone).",
        share(sum(&|t| t.overlap)),
        share(sum(&|t| t.turns)),
        share(sum(&|t| t.bends)),
        without(&|t| t.bends),
        without(&|t| t.overlap),
        without(&|t| t.bends + t.overlap),
    )
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

/// Runs the task; with `only` (comma-separated planner names), just those
/// planners, and with `filter`, just the maps whose name contains it: then
/// the tables are printed instead of written.
///
/// # Errors
/// When the shared maps are missing, a picture or the page cannot be
/// written, or a complete planner fails or collides.
pub fn run(only: Option<&str>, filter: Option<&str>) -> anyhow::Result<()> {
    let maps = match crate::floor_plans() {
        Ok(m) => m
            .into_iter()
            .filter(|(n, _)| filter.is_none_or(|f| n.contains(f)))
            .collect::<Vec<_>>(),
        Err(e) => {
            eprintln!("efficiency: skipped ({e})");
            return Ok(());
        }
    };
    let (ipa, ros): (Vec<_>, Vec<_>) = maps.into_iter().partition(|(n, _)| n.starts_with("ipa"));
    let settings = [
        Setting {
            name: "ipa floor plans",
            radius: 0.3,
            maps: ipa,
            target_efficiency: 0.40,
            target_turns: Some(20.0),
            benchmark_reading: true,
        },
        Setting {
            name: "ROS maps",
            radius: 0.15,
            maps: ros,
            target_efficiency: 0.65,
            target_turns: None,
            benchmark_reading: false,
        },
    ];
    let only = if filter.is_some() && only.is_none() {
        Some("")
    } else {
        only
    };
    let names: Vec<&'static str> = planners()
        .into_iter()
        .filter(|p| p.complete)
        .filter(|p| only.is_none_or(|o| o.is_empty() || o.split(',').any(|n| n.trim() == p.name)))
        .map(|p| p.name)
        .collect();
    let docs = crate::root().join("docs");
    let mut md = String::from(
        "# Efficiency: estimated time of every complete planner, rooms on and off\n\n\
         Command: `cargo xtask efficiency` (release, rayon over runs). Settings: the ipa floor plans of `../shared/maps/ipa-floorplans` at 0.05 m/px with robot = tool radius 0.3 m; the ROS maps of `../shared/maps/ros` with robot = tool radius 0.15 m. Start at the first cell of the largest admissible region, boundary pass on, contract speeds v = 0.3 m/s and w = 0.52 rad/s.\n\n\
         Columns: `min cov` the worst map's coverage; `coll` collisions summed over maps; then means over maps of the path length, turns per 10 m² covered, estimated time (`est_time_s`), time efficiency (`bound_time_s / est_time_s`, 1.0 = straight non-overlapping lanes with no turn) and the boundary pass's share of the length (of the finished path: the segments that end at one of the pass's waypoints); `plan ms` mean and slowest map (the whole pipeline: problem, rooms, planner, boundary pass). `full-dtc` and `grid-cover` are skipped above the sizes `cargo xtask acceptance` skips them at; `optimal` refuses maps wider than its exact search allows.\n\n",
    );
    let mut failures = Vec::new();
    let mut ceilings: Vec<SettingCeilings<'_>> = Vec::new();
    for s in &settings {
        if s.maps.is_empty() {
            continue;
        }
        let jobs: Vec<(usize, usize, bool)> = (0..names.len())
            .flat_map(|p| (0..s.maps.len()).flat_map(move |m| [(p, m, false), (p, m, true)]))
            .collect();
        let bar = crate::progress(jobs.len() as u64, s.name);
        let results: Vec<Outcome> = jobs
            .par_iter()
            .map(|&(p, m, rooms)| {
                let o = run_one(names[p], &s.maps[m].1, s.radius, rooms);
                bar.inc(1);
                o
            })
            .collect();
        bar.finish_and_clear();
        let at = |p: usize, m: usize, rooms: bool| {
            let i = jobs.iter().position(|&j| j == (p, m, rooms)).unwrap_or(0);
            &results[i]
        };
        let _ = write!(
            md,
            "## {} ({} maps, robot = tool radius {} m)\n\n| planner | rooms | maps | min cov | coll | length m | turns / 10 m² | est. time s | time eff. | boundary share | plan ms (mean / max) |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
            s.name,
            s.maps.len(),
            s.radius
        );
        let mut worse: Vec<String> = Vec::new();
        // (time efficiency, planner, rooms, turns / 10 m², worst coverage,
        // collisions, slowest plan ms) of the best row with rooms on (the
        // issue's targets are for the default, rooms on).
        let mut best: Option<(f64, &str, bool, f64, f64, usize, f64)> = None;
        // The best row's mean time efficiency under other time models.
        let mut best_models = [0.0f64; 3];
        let mut rooms_ok: Vec<(&str, usize)> = Vec::new();
        for (p, name) in names.iter().enumerate() {
            for rooms in [false, true] {
                let runs: Vec<&Run> = (0..s.maps.len())
                    .filter_map(|m| match at(p, m, rooms) {
                        Outcome::Done(r) => Some(r),
                        _ => None,
                    })
                    .collect();
                for m in 0..s.maps.len() {
                    if let Outcome::Failed(e) = at(p, m, rooms) {
                        failures.push(format!("{name} (rooms {rooms}) on {}: {e}", s.maps[m].0));
                    }
                }
                if runs.is_empty() {
                    let _ = writeln!(md, "| {name} | {} | 0 | | | | | | | | |", on_off(rooms));
                    continue;
                }
                let f =
                    |g: &dyn Fn(&Run) -> f64| mean(&runs.iter().map(|r| g(r)).collect::<Vec<_>>());
                let eff = f(&|r| r.efficiency);
                let complete_everywhere = runs.len() == s.maps.len();
                if rooms && complete_everywhere && best.is_none_or(|b| eff > b.0) {
                    best = Some((
                        eff,
                        name,
                        rooms,
                        f(&|r| r.turns_per_10m2),
                        runs.iter().map(|r| r.coverage).fold(1.0, f64::min),
                        runs.iter().map(|r| r.collisions).sum::<usize>(),
                        runs.iter().map(|r| r.plan_ms).fold(0.0, f64::max),
                    ));
                    best_models = [0, 1, 2].map(|k| f(&|r| r.other_models[k]));
                }
                let _ = writeln!(
                    md,
                    "| {name} | {} | {} | {:.4} | {} | {:.0} | {:.1} | {:.0} | {:.3} | {:.3} | {:.0} / {:.0} |",
                    on_off(rooms),
                    runs.len(),
                    runs.iter().map(|r| r.coverage).fold(1.0, f64::min),
                    runs.iter().map(|r| r.collisions).sum::<usize>(),
                    f(&|r| r.length_m),
                    f(&|r| r.turns_per_10m2),
                    f(&|r| r.est_time_s),
                    eff,
                    f(&|r| r.boundary_share),
                    f(&|r| r.plan_ms),
                    runs.iter().map(|r| r.plan_ms).fold(0.0, f64::max),
                );
                if only.is_some() {
                    // Some planners only: every map's figures too.
                    for m in 0..s.maps.len() {
                        if let Outcome::Done(r) = at(p, m, rooms) {
                            let _ = writeln!(
                                md,
                                "|   {} | {} | | {:.4} | {} | {:.0} | {:.1} | {:.0} | {:.3} | {:.3} | {:.0} |",
                                short(&s.maps[m].0),
                                on_off(rooms),
                                r.coverage,
                                r.collisions,
                                r.length_m,
                                r.turns_per_10m2,
                                r.est_time_s,
                                r.efficiency,
                                r.boundary_share,
                                r.plan_ms,
                            );
                        }
                    }
                }
                for r in &runs {
                    if r.collisions > 0 || r.coverage < 0.99 {
                        failures.push(format!(
                            "{name} (rooms {rooms}) on {}: coverage {:.4}, {} collisions",
                            s.name, r.coverage, r.collisions
                        ));
                    }
                }
            }
            // Maps where rooms on takes longer than rooms off.
            let mut slower = Vec::new();
            for m in 0..s.maps.len() {
                if let (Outcome::Done(off), Outcome::Done(on)) = (at(p, m, false), at(p, m, true))
                    && on.est_time_s > off.est_time_s * 1.0001
                {
                    slower.push(format!(
                        "{} (+{:.1} %, {} units)",
                        short(&s.maps[m].0),
                        100.0 * (on.est_time_s / off.est_time_s - 1.0),
                        on.room_units.map_or_else(|| "1".into(), |u| u.to_string())
                    ));
                }
            }
            rooms_ok.push((name, slower.len()));
            if !slower.is_empty() {
                worse.push(format!(
                    "- {name}: {} of {} maps: {}",
                    slower.len(),
                    s.maps.len(),
                    slower.join(", ")
                ));
            }
        }
        if let Some((_, name, ..)) = best {
            let p = names.iter().position(|n| *n == name).unwrap_or(0);
            let time = TimeModel::default();
            let rows = s
                .maps
                .par_iter()
                .enumerate()
                .map(|(m, (map_name, map))| -> anyhow::Result<_> {
                    let planned = match at(p, m, true) {
                        Outcome::Done(r) => Some((r.efficiency, r.split)),
                        _ => None,
                    };
                    Ok((
                        short(map_name).to_string(),
                        ceiling(map, s.radius, &time)?,
                        planned,
                    ))
                })
                .collect::<anyhow::Result<Vec<_>>>()?;
            ceilings.push((s.name, name, rows));
        }
        if let Some((eff, name, rooms, turns, cov, coll, slowest)) = best {
            let verdict = |ok: bool| if ok { "met" } else { "**not met**" };
            let _ = writeln!(
                md,
                "\nBest mean time efficiency with rooms on (the default) and every map planned: **{name}, rooms {}** ({eff:.3}).\n\nIssue 15's targets for this setting:\n",
                on_off(rooms)
            );
            let _ = writeln!(
                md,
                "- mean time efficiency ≥ {:.2}: {eff:.3}, {}",
                s.target_efficiency,
                verdict(eff >= s.target_efficiency)
            );
            if let Some(t) = s.target_turns {
                let _ = writeln!(
                    md,
                    "- turns ≤ {t} per 10 m² covered: {turns:.1}, {}",
                    verdict(turns <= t)
                );
            }
            let _ = writeln!(
                md,
                "- coverage 1.0 and no collision on every map: worst coverage {cov:.4}, {coll} collisions, {}",
                verdict(cov >= 1.0 && coll == 0)
            );
            // The runs above share the machine; planning time is judged on
            // each map planned alone (the mean of two runs, one map at a
            // time), as a user would run it.
            let alone_ms = |planner: &str, map: &OccupancyGrid, rooms: bool| {
                (0..2)
                    .map(|_| match run_one(planner, map, s.radius, rooms) {
                        Outcome::Done(r) => r.plan_ms,
                        _ => f64::NAN,
                    })
                    .sum::<f64>()
                    / 2.0
            };
            let alone = s
                .maps
                .iter()
                .map(|(map_name, map)| (alone_ms(name, map, true), map_name, map))
                // A map that failed to plan has no time (its row says so).
                .filter(|(ms, _, _)| !ms.is_nan())
                .fold(None, |a: Option<(f64, &String, &OccupancyGrid)>, b| {
                    if a.is_none_or(|a| b.0 > a.0) {
                        Some(b)
                    } else {
                        a
                    }
                });
            if let Some((ms, map_name, map)) = alone {
                // This machine's speed varies from run to run by more than
                // the margin: the reference, planned alone right after on
                // the same map, puts the figure in proportion.
                let reference = alone_ms("boustrophedon", map, false);
                let _ = writeln!(
                    md,
                    "- planning under 1 s on the slowest map: {ms:.0} ms ({}, planned alone: the mean of two runs, one map at a time; the criterion bench's reference, `boustrophedon` rooms off, planned alone right after on the same map: {reference:.0} ms, a ratio of {:.2}), {} (with the other runs in parallel, as in the table: {slowest:.0} ms; the criterion figure for `lab_b` is in `docs/benchmarks.md`)",
                    short(map_name),
                    ms / reference,
                    verdict(ms < 1000.0)
                );
            }
            let limit = s.maps.len() / 10;
            let within: Vec<&str> = rooms_ok
                .iter()
                .filter(|(_, n)| *n <= limit)
                .map(|(p, _)| *p)
                .collect();
            let _ = writeln!(
                md,
                "- rooms on worse than off on at most {limit} of {} maps, for every planner: {}; met by {} of {} planners{}",
                s.maps.len(),
                verdict(within.len() == rooms_ok.len()),
                within.len(),
                rooms_ok.len(),
                if within.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", within.join(", "))
                }
            );
            if s.benchmark_reading {
                let p = names.iter().position(|n| *n == name).unwrap_or(0);
                md += &benchmark_line(s, p, name, &at, &mut failures)?;
            }
            let [gentle, every, free] = best_models;
            let _ = writeln!(
                md,
                "\nThe same paths under time models other than the contract's (which charges every heading change as a stop and a turn on the spot), mean time efficiency of {name}, rooms {}: turns of at most 30° taken while driving (a segment takes the longer of its drive and the turn before it) {gentle:.3}; every turn taken while driving {every:.3}; turning free (the drive alone: what overlap leaves) {free:.3}.",
                on_off(rooms)
            );
        }
        md += "\nMaps where rooms on makes the estimated time worse than rooms off:\n\n";
        if worse.is_empty() {
            md += "- none\n";
        } else {
            for w in &worse {
                md += w;
                md += "\n";
            }
        }
        md += "\n";
    }
    if only.is_some() {
        // Some planners only: the tables are printed, the page is kept.
        md += &ceiling_section(&ceilings, &settings);
        println!("{md}");
    } else {
        md += &crate::bare_rooms::section()?;
        md += "\n";
        md += &ceiling_section(&ceilings, &settings);
        md += DISCUSSION;
        pictures(&settings, &docs, &mut md)?;
        std::fs::write(docs.join("efficiency.md"), md)?;
        println!("wrote docs/efficiency.md");
    }
    if !failures.is_empty() {
        anyhow::bail!("{} runs failed:\n{}", failures.len(), failures.join("\n"));
    }
    Ok(())
}

/// What the tables show and where the time goes (no figure here: the
/// figures are in the tables above, measured by the same run).
const DISCUSSION: &str = "## Where the time goes\n\n\
- **Turning, not driving, dominates.** At the contract's speeds a quarter turn costs as much time as 0.9 m of straight driving, and a U-turn between two lanes (π rad) as much as 1.8 m. With the ROS maps' 0.3 m lane spacing, the U-turns alone of lanes 5 m long cost about a third of the lanes' time: a boustrophedon there cannot come near a time efficiency of 1, whatever else it does right.\n\
- **The strip along the walls is what costs on the ipa plans.** The contract counts a free cell covered when its centre is within the tool radius of the path, and lets the robot only into cells whose centre clears every wall by the robot radius. With robot = tool radius, the free cells next to a ragged wall are within reach of only a few boundary cells each. `lanes` drives a loop along every wall, straightened only within 0.8 of a cell (a staircase's steps sit a whole cell off the line that cuts them: a tolerance of 1.0 skipped them, left much of the strip out of reach, and the repairs cost more than the straightening saved; measured when changed, rooms off: 0.345 → 0.395, and 0.399 with eight tightening passes instead of four), covers what the loop and the lanes' ends still pass just out of reach by **detours** (the cheapest new vertex, or shallow V, on a nearby segment that uncovers nothing), then **tightens** the path over eight passes (at each vertex the removal, move towards its neighbours' line or slide along a piece that saves the most time while every cell stays covered; taking the first that saved any instead measured 0.406 against 0.414, rooms off). Tightening, not the first straightening, is what takes the loop's turns out. The boundary pass is left almost nothing (its share of the length is the table's column).\n\
- **The outermost lanes keep off the loops' strip.** Lanes fill the C-space at least a tool radius inside its walls; the loop along a wall covers a tool radius either side of a line 0.45 of a cell off the boundary cells' centres. Lines spread over the whole mask put the first lane almost a tool radius into the loop's reach; the first and last lines now lie half a cell less than a tool radius further in, where the two reaches just meet (no line at the ends of a lane moves: the loops still cover the scallops there). Measured when introduced, rooms on, ipa plans / ROS maps: time efficiency 0.406 → 0.412 / 0.512 → 0.526 (the pillar arenas −9 to −12 %, robocup −6 %; slower on 5 of 31 maps, grid.yaml +2.3 %, mines +1.0 %, lab_b +0.5 %), and rooms on slower than off on 4 ipa plans instead of 6 and 2 ROS maps instead of 4. The margin was measured in steps (ROS / ipa): the lines spread over the whole mask 0.512 / 0.406; the first line's reach overlapping the loop's by 0.8 of a cell 0.523 / 0.410, by 0.3 0.526 / 0.412, by 0.05 0.527 / 0.412 (kept; 0.526 / 0.412 as finally built, the offset taken from the tool radius instead of half the spacing); a gap of 0.2 of a cell 0.524 / 0.411, of 0.45 0.527 / 0.409, of 0.95 0.515 / 0.409 (what the gap leaves is covered by detours). Shortening the lanes at their ends in the same way (their ends, too, reach into the loops' strip) was slower: ends moved in by half a cell less than a tool radius (as the lines) 0.491 / 0.395, by a cell less 0.509 / 0.400, by 2.5 cells less 0.516 / 0.408 (lanes near corners and ragged walls vanish or split, and detours cover their strips); shortened only where a wall, not a room cut, ends them, and only lanes at least two spacings long: 0.525 / 0.413 by half the lines' offset, 0.523 / 0.412 by all of it, no gain.
- **Lane angles are chosen on the finished path.** A time model of lanes, links and U-turns picks the candidates; the two best, with their ordered transits, are both built to the end (detours and tightening included, in parallel) and the faster path is kept (measured when introduced: 0.399 → 0.405 rooms off, 0.390 → 0.397 rooms on, for about 1.5× the CPU time). A plan of fewer than 100,000 plannable cells builds more of its angles, 200,000 cells' worth (every angle below about 14,000 cells; room by room the whole map's count decides, so that more rooms cost no more angles). Measured when introduced with a budget of 300,000, rooms on: 0.404 → 0.406 on the ipa plans and 0.509 → 0.512 on the ROS maps (lse_arena −7 %, map.yaml and map_circular −2 %, mines −2 %; no map slower by more than 0.4 %), the slowest map planned alone unchanged on the ipa plans and 859 ms on the ROS maps (mines, was 765 ms); 600,000 gained 0.002 more and took mines to 1.9 s. Once the outermost lanes moved in (above) mines took 941 ms alone with 300,000, too near the 1 s target: with 200,000 it builds two angles again, at 0.411 instead of 0.412 on the ipa plans and the same 0.526 on the ROS maps, the slowest map 794 ms (warehouse). Later, the margin by which another angle must beat the wall directions in the model, 10 %, was measured again on the finished paths, mean estimated time of `lanes` rooms on, ipa plans / ROS maps: 10 % 5824 / 4868 s, 7 % 5824 / 4858, 5 % 5822 / 4858 (kept: the middle of the margins that gain), 3 % 5822 / 4850, none 5830 / 4869 (warehouse +2.2 %, lab_d rooms off +3.0 %); at 5 %, coverage 1.0 and 0 collisions throughout, turns per 10 m² covered rooms on unchanged (13.6 on the ipa plans, 28.6 on the ROS maps), depot −2.0 %, basement rooms off −1.6 %, smoothers_world −0.9 %, map.pgm rooms on −0.3 %, and lab_c rooms off +0.6 %, every other plan the same; basement's faster plan with rooms off makes it slower with rooms on than off again (+1.5 %: 2 of 21 ROS maps with simple_rooms, the target's limit). Measured at the same time and not kept (rooms on, ipa plans / ROS maps, against 5822 / 4858 s): three angles built to the end instead of two, 5820 / 4845 s, but the slowest maps planned alone over 1 s (lab_b 1009 ms, warehouse 1104 ms); twelve tightening passes instead of eight, 5821 / 4858 s (one plan changed by more than 0.3 %); the loops straightened within 0.7 or 0.9 of a cell instead of 0.8, 6062 / 4900 and 5887 / 4950 s.\n\
- **A part of a region that one angle does not suit is hatched again.** A region's lanes lie at one angle, so a corridor's arm or a strip beside a room hatched across turns every few lanes. Each chain whose links and U-turns take a fifth of its modelled time or more has its area (the lane-mask cells within half a line step of its lanes) hatched again at the two wall directions, and where the model finds that at least 20 % faster the new chains replace it; the order then places them like any other chain. Measured when introduced, mean estimated time of `lanes`, rooms off / on: ipa plans 5918 → 5889 s / 5906 → 5887 s (time efficiency rooms on 0.415 → 0.417), ROS maps 4966 → 4928 s / 4937 → 4902 s (0.528 → 0.537), coverage 1.0 and 0 collisions throughout; faster on grid.yaml (−15 %: the ring round its central block is driven in four straight bands instead of lanes across two of them), maze (−6 % rooms on), smoothers_world, mines, lab_a, lab_d (−2 to −3 %); slower on freiburg_building79 rooms on and sparse_obstacles rooms on (+1.0 %), lab_c rooms off (+0.7 %), basement and frieburg (≤ 0.2 %). Rooms on slower than off for `lanes`: 2 ipa plans instead of 3 (freiburg_building52 +0.7 %, lab_a +1.4 %; lab_c no longer). The slowest maps planned alone, over this change's runs: intel_map 763–782 ms and warehouse 802–910 ms (before: 754–812 and 826–837 ms; the machine is noisy). Variants measured on the way and not kept, the first two in an earlier form of the change (each area's cells given to one chain only, and angles ranked for building without the modelled saving); all within 0.002 of each other in mean time efficiency, and each changing which of lab_a, lab_c, freiburg_building52 and freiburg_building79 lose with rooms on, 1 to 4 ipa plans (their margins are within 2 %): a 10 % or 5 % gain required instead of 20 % (slower on more maps: map.yaml +1.2 % and +3.1 %, lab_a rooms off +2.7 %); every one of the fourteen candidate angles tried instead of the two wall directions (rooms on 5896 s / 4881 s, but the slowest map 1206 ms alone: warehouse); in the final form, each area's cells given to one chain only (the same means to 0.001, with a map-sized grid more); and ordering each angle both as hatched and as re-hatched and keeping the cheaper with its transits (the same paths here, the ordering's time twice: intel_map 1.15 s alone). Then **chains cut where their lanes' extent jumps**: a band and the arm that leaves it are one chain when each line's run overlaps the next one to one (an L-shaped room hatched along its long side), so neither angle suits the chain as a whole; a chain is now cut where a lane overlaps its neighbour by less than half the longer of the two, each piece is re-hatched (or not) as above, and the pieces replace the chain where together they beat it by 20 %. Measured when introduced, rooms off / on: ipa plans 5889 → 5844 s / 5887 → 5834 s (time efficiency rooms on 0.417 → 0.419), ROS maps 4928 → 4920 s / 4902 → 4898 s (0.537 both; rooms off 4919 s since a review made the area's bounding box the tightening's own, which moved a lane of sparse_obstacles, −0.6 %); lab_b and lab_c rooms off −2 %, freiburg_building79 rooms on −1 %; slower: lab_a rooms off +0.7 %, lab_e +0.6 %, map_circular +0.7 %, map.yaml +0.3 %. Rooms on slower than off for `lanes`: still 2 ipa plans, now freiburg_building52 (+0.4 %) and lab_c (+0.2 %); lab_a no longer. A cut below a third of the longer lane instead of a half: 5838 s / 4907 s rooms on, 2 ipa plans slower with rooms on; below 0.7 of it: 5833 s / 4896 s, but map.yaml +2.6 % and 3 ipa plans slower with rooms on. The slowest maps planned alone (intel_map and warehouse) stay at about 0.8 s, as before; this page's own run is in the targets above. Then **the area's own long axis**: the wall directions of a region are two at right angles, so an arm that leaves the building's grid at a slant (a hall's wing, a tunnel) was re-hatched only across or obliquely. Each piece's area is now also hatched along its long axis (its cells' principal axis), where that lies more than half a degree from both wall directions, and that hatching competes as the others do. Measured when introduced, mean estimated time of `lanes`, rooms on / off: ipa plans 5816 / 5835 → 5815 / 5832 s, ROS maps 4847 / 4886 → 4844 / 4857 s (time efficiency rooms on unchanged at 0.420 and 0.541, rooms off on the ROS maps 0.539 → 0.540), coverage 1.0 and 0 collisions; hospital_section rooms off −3.3 %, lab_a rooms off −0.5 %, mines and robopark −0.4 %, freiburg_building79 rooms on −0.3 %, robocup −0.2 %; slower: freiburg_building79 rooms off +0.1 %, every other plan within 0.05 %. Rooms on against off: lab_a +0.8 → +1.3 % (its plan rooms off gained), basement +0.2 → +0.3 %, still 1 of 10 ipa plans and 2 of 21 ROS maps. The gain is small because an area is the strips of its chain's lanes, so its border, hatched at a new slant, is a sawtooth that cuts the new lines into short runs (levinelobby's slanted wing, hatched across in chains of up to 16 lanes, is not re-hatched: the axes of its pieces lie about 15° off the wing's own). Measured and not kept: the axis only where it lies more than 2° or 5° from the wall directions (ROS maps rooms on / off 4845 / 4858 s and 4846 / 4884 s); areas grown to the lane-mask cells within a whole line step of the lanes, to smooth that border (rooms on, ipa plans 5830 s, ROS maps 4859 s: grid.yaml −2.5 % and hospital_section rooms off −3.0 %, but lab_c rooms on +1.9 %, warehouse +1.4 %, intel_map +1.2 %), or along each lane's own band only, up to two line steps beyond its ends where the mask holds the way back (the cells a slanted wall leaves between two lanes' ends; rooms on, ipa plans 5826 s, ROS maps 4858 s, whether or not the model counts the added cells as the chain's to cover: grid.yaml −3.1 %, sparse_obstacles rooms off −1.6 %, but hospital_section rooms off +3.6 %, robocup and warehouse +1.3 %, the pillar arenas +1.2 %); each piece re-hatched where it alone gains 20 %, instead of the pieces together beating their chain by 20 % (with the axis tried beyond 2°, rooms on, ipa plans 5813 s, ROS maps 4850 s: sparse_obstacles rooms off −1.5 %, but mines +0.7 %, lab_a rooms off +0.9 %, basement rooms on +0.5 %). Then **the walls' own directions**: a region's wall direction is the mean of its loops' directions (on the quarter-turn circle), which lands between two wall systems, and a hexagonal arena has three. Each piece is now also re-hatched at the strongest direction of a histogram of its region's walls (1° bins of 16-cell steps along the loops, smoothed over ±2°) and at a second peak at least 8° from it with at least a tenth of its weight, each with its right angle, where they lie more than 1° from the mean. Measured when introduced, mean estimated time of `lanes`, rooms on / off: ipa plans 5815 / 5832 → 5802 / 5822 s, ROS maps 4844 / 4857 → 4840 / 4853 s (time efficiency rooms on 0.420 → 0.421 and 0.541 → 0.542; turns per 10 m² covered 13.6 / 28.5 → 13.5 / 28.1), coverage 1.0 and 0 collisions; map.yaml −5.1 %, lab_e −1.6 %, lab_a rooms on −1.0 %, map.pgm rooms off −0.9 %, the pillar arenas −0.7 to −0.9 %, intel_map and basement rooms on −0.3 %; no plan slower. Rooms on against off: lab_a +1.3 → +0.3 %, basement +0.3 → +0.0 %. Planned alone, the previous binary and this one alternating, three runs each (median `plan_ms`): hospital_section 480 → 484 ms, `lab_b` 529 → 516 ms, warehouse 521 → 527 ms. A second peak needing a quarter or half of the first's weight gained less (rooms on 5811 / 4841 s and 5814 / 4842 s; lab_a rooms off +0.5 % at a half), a twentieth the same as a tenth (5802 / 4839 s); a first version on 4-cell steps, which take only a few directions on the raster (0°, 14°, 27°, 37°, 45°, …) and so make peaks of their own, 5812 / 4843 s at a quarter. The peaks offered as whole-region lane angles as well (after the wall directions, before the 15° steps): 5801 / 4840 s (freiburg_building101 −1.6 %, but lab_d rooms off +0.8 % and lab_c rooms on +0.3 %), not kept. Then **a looser margin where an area is laid anew**: warehouse's aisles between its racks, about 5 m wide and 12 m long, were hatched across in 40-lane chains, and along them the model finds only 15 % less time (the drive is the same; only the U-turns go), under the 20 % asked. A re-hatch is now also taken at 10 % where it lays at most four fifths of the chain's lanes and two fewer at least, and a chain whose links and U-turns are a tenth of its time may be re-hatched. Fewer lanes are fewer U-turns whatever the model leaves out; a chain only cut into its pieces, or re-laid with about as many lanes, gains what the model counts and pays for the transits between the new chains, which it does not count. Measured when introduced, mean estimated time of `lanes`, rooms on / off: ipa plans 5802 / 5822 → 5804 / 5822 s, ROS maps 4840 / 4853 → 4808 / 4828 s (time efficiency rooms on 0.542 → 0.544), coverage 1.0 and 0 collisions; warehouse −1.9 %, hospital_section −1.7 % rooms on (its alcoves off the corridor, now hatched along their length) and −0.8 % rooms off, smoothers_world −0.5 %; slower: lab_a rooms on +0.3 % (now slower with rooms on than off, +0.6 %: 1 of 10 ipa plans, the target's limit), freiburg_building52 and lab_d rooms off +0.1 %. Planned alone, the previous binary and this one alternating, seven runs each on warehouse: medians 675 and 671 ms. Measured and not kept: the 10 % margin for every re-hatch, 5824 / 4811 s rooms on (lab_b +1.2 %, map.yaml +2.2 %: mostly chains cut into their own pieces, each then a chain with transits of its own); with one lane fewer enough, 5806 / 4809 s (map_circular +2.3 %, intel_map +0.3 %); with at most 70 % or 90 % of the lanes, 5804 / 4809 s (hospital_section rooms off +2.6 %) and 5807 / 4809 s; a 5 % margin or none at all with four fifths of the lanes, 5804 / 4813 s both; building every ordered angle hatched at both margins and keeping the faster path, 5796 / 4807 s with no plan slower, but warehouse planned alone 473 → 864 ms; only the best angle built at both, 5796 / 4835 s (warehouse 620 ms alone).\n\
- **Lanes run past small islands and drive their loops.** A speck, a table leg or a thin pillar in the open leaves a hole in the lane mask a loop's strip wide, so the two or three lines through it stopped there, the room fell into chains on either side, and the island's loop was a node of the order of its own, reached by a transit (in an 8 × 6 m room one 10 cm speck cost 49 s, four cost 35 s each, sixteen 28 s each, against about 17 s for the loop itself; measured before this change, the table above after it). Now the runs of a line on either side of a small island (a blocked component of the C-space of at most (2 tool radii + 4 cells)² cells, touching no wall even at a corner) are one lane, driven round the island where it blocks the line, and the island's loop is driven from the lane passing nearest: left at its nearest point, round the loop the way the lane runs, back to that point. Measured when introduced, `lanes`: the synthetic rooms with 1, 4 and 16 specks 745 / 836 / 1149 → 715 / 782 / 1089 s; mean estimated time rooms on / off, ipa plans 5839 / 5846 → 5836 / 5843 s, ROS maps 4889 / 4924 → 4888 / 4917 s (time efficiency unchanged at three decimals), coverage 1.0 and 0 collisions; depot −1.5 %, intel_map −0.6 %, lab_a −0.2 %; slower: basement +0.6 % (now slower with rooms on than off, +0.8 %: 2 of 21 ROS maps, the target's limit), warehouse and lab_b +0.2 %; warehouse planned alone about 20 ms slower (the islands' labelling). The shared maps' specks lie mostly along walls, where the wall's loop passes them anyway. Measured and not kept: larger islands, up to (3 or 4 tool radii + 4 cells)², which take in the pillar arenas' pillars: those arenas +8 to +11 % (their lanes bend round pillars a corridor apart); the loops alone driven from the nearest lane, lanes still cut: ipa plans 5856 s, ROS maps 4879 s (frieburg −1.6 %, but the pillar arenas +1 to +3 %); round the loop always the way it was traced rather than the way the lane runs: basement 7390 s instead of 7366 s. Then **larger islands' loops driven from a lane as well**: an island up to twice as wide (at most (4 tool radii + 4 cells)² cells: a pillar, a small table) still cuts the lanes beside it, but its loop, too, is left and rejoined at the lane passing nearest instead of being a node of the order reached by a transit. Measured when introduced, mean estimated time rooms on / off, ipa plans 5836 / 5843 → 5824 / 5833 s, ROS maps 4888 / 4917 → 4868 / 4900 s (time efficiency rooms on 0.419 → 0.419 and 0.537 → 0.539), coverage 1.0 and 0 collisions; frieburg −2.0 %, the pillar arenas tb3_sandbox and turtlebot3_world −1.9 %, map_circular −1.6 % rooms on, basement −1.1 % rooms on (no longer slower than rooms off: 1 of 21 ROS maps), lab_b −0.5 %, warehouse −0.4 %; slower: map.yaml +0.5 %, freiburg_building52 rooms off +0.3 %, freiburg_building79 +0.1 to +0.2 %. Limits of 3, 5 and 6 tool radii instead of 4: rooms on, ipa plans / ROS maps 5827 / 4882, 5830 / 4874 and 5829 / 4874 s; with it, the islands that lanes pass up to 1.5, 2.5 or 3 tool radii instead of 2: 5885 / 4868, 5839 / 4870 and 5848 / 4882 s. Measured and not kept: splicing a larger island's loop only where the order model, with the way out and back counted, finds the order faster (each near-tie angle ordered both ways): with a full turn counted for the way out and back it never spliced (every plan as before), with the drive alone it spliced almost always (freiburg_building52 rooms on −0.1 %, every other plan the same); it does not mend the two bundled maps this change slows (lee2011's office 701 → 721 s and turtlebot3_world at 0.1 m 861 → 871 s, rooms off).\n\
- **Where a room is left matters.** Room by room the pipeline hands each room's planner the room's cell nearest the next room. `lanes` ends its order there; `dtc` takes it as its goal (DTC enters its goal last), and `full-dtc` keeps, of its DTC runs towards every goal, the one whose path plus the moves on to that cell takes least estimated time (measured when introduced, rooms on: `dtc` 16705 → 16639 s on the ipa plans and 10311 → 10281 s on the ROS maps; `full-dtc` 16233 → 16125 s and 9967 → 9841 s, slower than rooms off on 1 ROS map instead of 3; `full-dtc` scoring by moves instead of time did worse on the ipa plans, 16318 s). The other grid planners follow their papers' own orders and end wherever those do; the room's boundary pass, run after any planner, is a tour that ends towards that cell (of the open tour from the plan's end and the open tour from the exit driven backwards, the shorter with the way on; measured when introduced, rooms on: the mean of every planner that leaves it cells fell on the ipa plans, by 3–42 s, and moved by −18 to +3 s on the ROS maps; `smooth` went from 3 ROS maps slower with rooms on to 1).\n\
- **With rooms on, the boundary pass is tightened as well.** Rooms off keeps the papers' boundary pass: nearest first through cell centres, with a turn at almost every anchor. With rooms on (the default) each room's pass is built both ways, as the tour above and nearest first; both are tightened for time exactly as `lanes` tightens its own path (a waypoint is removed, moved or slid where that saves time, stays clear and leaves no cell out of reach of the contract's samples), and the faster, with the way on, is kept. Measured when introduced, mean estimated time rooms on, ipa plans / ROS maps, before → after: boustrophedon 13270 → 10208 s / 8826 → 7584 s, trapezoidal 13025 → 10093 / 8819 → 7592, grid-cover 16000 → 12890 / 10472 → 9141, dtc 16633 → 13696 / 10284 → 9013, smooth 17946 → 13178 / 10926 → 8802, border-expansion 25575 → 25164 / 25450 → 25292 (its roads leave the pass little), with 0 collisions and coverage 1.0 throughout. Tightening only the route that was faster untightened gave most of this (82–95 % of the gain for boustrophedon and grid-cover); choosing after tightening costs a second tightening, run in parallel. For the grid planners this tightening, not the segmentation, is most of what rooms on gains in the tables above. It is also what brings border-expansion (3 → 2 ROS maps slower with rooms on), bsa (2 → 0), dtc (2 → 1) and grid-cover (3 → 2) within the rooms target.\n\
- **Large regions' transit tables are searched in blocks.** `lanes` orders its loops and chains by estimated transit, each straight-line time scaled by a detour ratio (the 4-connected route's length over the Manhattan distance), one breadth-first search per distinct end point. On a region of over 40,000 plannable cells the searches now run over blocks of about half a tool radius (3 × 3 cells on the ipa plans, 2 × 2 on the ROS maps at 0.05 m/px), a move between two blocks allowed only where plannable cells border each other across them, so that no search passes through a wall as thick as a block less a cell (the C-space's walls are much thicker). Smaller regions keep the cell-by-cell search, whose ratios the four small arenas needed (there blocks made them up to 1.9 % slower). Measured when introduced: criterion, `intel_map` (planned as one region) `lanes` rooms on 2263 → 1331 ms, 6.85 → 4.01 times the `boustrophedon` reference in the same run; `lab_b` unchanged (its regions exceed the table's budget either way); hospital_section about 2.4 → 1.85 s. Plans: the same on most maps; lab_c rooms off +0.7 %, basement rooms on −0.5 %, every other map within 0.5 %; mean estimated time rooms on, ipa plans 5834 → 5838 s, ROS maps 4898 → 4895 s. (This session's machine ran the reference 2.9 times slower than the last one, 748 against 259 ms on `lab_b`: the absolute planning times on this page are this machine's.) Measured on the way: blocks on every region (the pillar arenas +0.9 to +1.9 %); a budget counted in blocks instead of cells (tables on more regions: lab_b −2 %, but 3.8 s alone; a budget between the two cost mines its table, +6.4 %).\n\
- **Planning time, every plan unchanged.** A later session took time out of the pipeline without changing a single waypoint: the path files of `lanes` on all 31 maps, of `boustrophedon`, `dtc` and `smooth` on six of them, and the room segmentation of every map (both methods) are byte for byte what they were. The tightening's strokes find the cells they surely reach as an interval per row (not a distance test per cell) and try a vertex's moves without allocating; coordinates are floored without the software routine that x86-64's baseline calls for `f64::floor` (5 % of `lab_b`'s instructions); the medial-axis segmentation, which runs beside the problem's construction and was the longer of the two, reads neighbours by index and tests a door candidate against the nearby doors only; the room units are labelled by index; `lanes` finds a direction's extent from each row's first and last cells and samples each line only inside the lane mask's box; a region's boundary tour and nearest-first pass are found in parallel; and `lanes` no longer searches the whole region to learn that no leftover cell remains. Instructions (callgrind, one thread), `lanes` rooms on: `lab_b` 19.38·10⁹ → 16.32·10⁹, lab_c 4.60·10⁹ → 4.15·10⁹. Planned alone on one machine, old and new binaries alternating, four runs each (fastest / median): `lab_b` 1745 / 1930 → 1532 / 1567 ms, intel_map 1249 / 1284 → 1038 / 1060 ms, warehouse 2201 / 2419 → 1724 / 1820 ms, hospital_section 1619 / 1707 → 1586 / 1603 ms. On that machine the target of 1 s is still not met. Criterion, with the `boustrophedon` reference in the same run (`docs/benchmarks.md`): `lab_b` `lanes` rooms on 2.84 → 2.32 times the reference, intel_map 4.01 → 3.68; the reference itself shares the faster metrics and floors (2.7 % fewer instructions), so the ratios understate the gain. Tried and not kept: one walk over the rows for a move's four strokes instead of four (3.6 % more instructions on lab_c: each cell then tests every stroke), and a summed-area table answering the tightening's clearance tests where a box round the segment holds no blocked cell (no gain: the vertices that move lie along walls, where the box always holds one).\n\
- **Planning time, a second round, every plan unchanged.** The next session went on the same way, each change checked against the path files and reports (all but `plan_ms`) of `lanes` on all 31 maps and of `lanes`, `boustrophedon`, `dtc` and `smooth` rooms on and off on six maps, and the segmentation of every map: all byte for byte as before. The plan's covered cells are found once and shared: the boundary tour and the nearest-first pass take them from the pipeline instead of each marking the plan again, the report's coverage before the pass reuses them, and the final path's coverage comes from the tightening's own check; the metrics mark coverage segment by segment (the same cells as a disc round every sample, property-tested) instead of sample by sample, and a long path is marked in two halves side by side. The tightening tries first the cell that sank the previous move (494,000 of 543,000 coverage tests on `lab_b` fail, after 12 cells each on average), tests a vertex's moves for clearance at once where every cell of the triangle of the vertex and its neighbours is plannable (each move's point lies in it), keeps a stroke's per-segment terms for its rows and counts a row's surely reached cells without a test each. `lanes` orders its near-tie angles in parallel and reads its lane mask by index; the medial-axis segmentation fills its regions by index. Instructions (callgrind, one thread), `lanes` rooms on: `lab_b` 16.32·10⁹ → 12.90·10⁹, lab_c 4.15·10⁹ → 3.52·10⁹. Planned alone on one machine, old and new binaries alternating, five runs each (fastest / median `plan_ms`): `lab_b` 1351 / 1510 → 1139 / 1244 ms, intel_map 1031 / 1067 → 833 / 861 ms, warehouse 1487 / 1765 → 1376 / 1595 ms, hospital_section 1312 / 1547 → 1021 / 1197 ms; the metrics after planning (not in `plan_ms`, in the criterion bench) took about 220 ms on `lab_b` and now about 9 (both coverages come from grids found on the way). The target of 1 s: this page's own run put `lab_b` alone at 927 ms (the mean of two runs, one map at a time), under it, but the alternating runs above put its median at 1244 ms on the same machine, so the machine's noise is as large as the margin; warehouse, the slowest ROS map, is over it either way (1680 ms here). The slowest maps spend about half their time in the tightening, whose remaining cost is spread over many small parts (the cells only a vertex's pieces reach, about a third; the time of each move's stretch, with its `atan2`s, a sixth; the recounts after a move, a seventh). Tried and not kept: the three column ranges of a stroke's row walked as three loops in the tightening's at-risk scan (more instructions there; kept only for counting).\n\
- **Planning time, a third round: passes in parallel, angles stopped early.** The tightening now runs pass by pass, and a pass over 512 vertices or more is split into four bands of rows (at the quantiles of its vertices' rows), tightened in parallel: a band tries only the vertices whose change stays within its rows (the box round the vertex and its neighbours, widened by the reach) and whose neighbours' neighbours, which the time of a change counts, lie in its rows too; the rest (10–15 % of them on warehouse) are tried one by one after, in path order. Two bands' changes then share no cell and no vertex and each is decided as the one-by-one pass would decide it from the same path; only the order differs, so plans change a little. A fixed number of bands keeps the path the same on any thread count (property-tested with 1 and 3 threads, with no cell lost). Mean estimated time rooms on, ipa plans / ROS maps, before → after: `lanes` 5838 → 5839 s / 4895 → 4896 s (time efficiency 0.419 → 0.418 / 0.537), dtc 8427 → 8453 / 6619 → 6623, smooth 7975 → 7964 / 6349 → 6354, trapezoidal 8131 → 8142 / 6403 → 6443 and boustrophedon 8213 → 8222 / 6409 → 6448 (the largest changes, +0.6 % on the ROS maps), every other planner within 0.3 %; coverage 1.0 and 0 collisions throughout, and the rooms targets met as before. (A first version let a band judge a change's time with a neighbour's neighbour as the pass began: about the same means, but `lanes` rooms on fell 0.1 % behind rooms off on lab_c, a second ipa plan.) Then `lanes`, which builds its two best angles to the end, stops an angle whose path after its detours and first tightening pass is more than 5 % slower than the fastest's: measured first on `lanes` rooms on and off over the 31 maps, 136 of 410 angle builds stop early and none of them would have won (a margin of 2 % would have lost 3 s over all maps, 1 % 14 s), so no path changes. Each angle goes on as soon as its own first pass is done and stops once every angle's time after that pass is known; which angles are kept depends on those times only. Three exact changes (the same paths): the cells only a vertex's pieces reach are walked once, not once per piece (the two capsules overlap near the vertex), and a cell a piece surely reaches, counted once in all, needs no sample test (instructions, `lanes` lab_c, one thread: 3.59·10⁹ → 3.47·10⁹); the leftover visits look only at the coverage blocks within reach of a sample; the edge loops and the lane mask are found side by side. Planned alone, old (the session's start) and new binaries alternating, five runs each (fastest / median `plan_ms`): `lab_b` 1199 / 1204 → 904 / 998 ms (its second angle stops after one pass), warehouse 1630 / 1668 → 1146 / 1490 ms (its fast angle no longer waits, and its slow one's passes use the second core once the fast one is done), intel_map 792 / 845 → 748 / 831 ms and hospital_section 1087 / 1212 → 1216 / 1222 ms (unchanged: their angles are within 5 % and keep both cores busy; seven more runs of hospital_section, medians 1071 → 1095 ms). This machine's speed varied by more than the target's margin within the hour: this page's own runs put warehouse alone at 922, 1455, 1162 and 1505 ms, so the target lines now also give the criterion bench's reference, `boustrophedon` rooms off, planned alone on the same map right after (this run: `lab_b` 2.11 times it, warehouse 2.18 times). One such run found a latent fault: a `smooth` plan on robocup whose final tightening removed the vertex between two points on a cell border, leaving a segment along the border that the clearance test's traversal (one row only) passed but whose samples, rounded to metres and back, fell in the blocked row beside it (244 collisions); a segment that ends on or runs along a border now counts the cells on both sides (robocup's `smooth` plan has no collision now; every mean in these tables is as it was to the second).\n\
- **Planning time, a fourth round: detours from the far side, lines that skip what is surely inside.** `lanes` lays one family of lines over a region, so beside an obstacle that runs along the lanes the last lane may stop a few cells short of the obstacle's loop; the detours then covered that strip row by row from its near side, one bend per row (warehouse's slower angle: 5384 detours, about 250 ms). The cells a path misses are now taken farthest from it first: the first bend goes into the strip's far row and reaches the nearer rows on its way (warehouse: 2268 detours, about 100 ms). Plans change a little: mean estimated time of `lanes`, rooms on / off, ipa plans 5839 / 5853 → 5839 / 5846 s (time efficiency rooms on 0.418 → 0.419), ROS maps 4896 / 4917 → 4889 / 4924 s (0.537); coverage 1.0 and 0 collisions; per map (rooms on, the CLI's start) smoothers_world +1.6 % and lab_a +0.7 %, robopark −1.5 %, freiburg_building101 −1.2 % and hospital_section −0.9 %, the rest within 0.7 %; lab_a is now slower with rooms on than off (+1.0 %, the one ipa plan in ten the target allows). Only `lanes` inserts detours: no other planner's row moved. Then exact changes, each checked against the path files and reports of `lanes` on the 31 maps and of four planners rooms on and off on six maps, and against the segmentations of every map (all byte for byte the same): each line of a lane angle skips the samples that the lane mask's clearance (an exact distance transform, found beside the edge loops) shows to be inside, so a line reads the mask near its runs' ends only (warehouse's angle scoring about 140 → 60 ms); a map whose plannable cells all lie in one room is planned whole without labelling room units (warehouse: one room and 322 specks, about 60 ms); the largest-region start (this page's) finds the admissible cells and their regions once; the distance transforms run their column and row passes in parallel; components are labelled a row's run at a time, and the segmentation's relabelling, the reachable set and the admissibility thresholds read their grids by index (warehouse's segmentation 0.26 → 0.20 s); two coarse blocks whose cells are all plannable are linked without a search; and the room units' exits are searched in parallel. And `lanes`' transit table (one search per loop or chain end over the region, for each of the near-tie angles) takes its rows side by side and uses the distances' symmetry: the search from a point fills its row and column and stops once it has reached the points after it (hospital_section, whose large unit spent about 330 ms on three angles' tables: median 1002 → 898 ms, alternating five runs each). Planned alone with the CLI, the session's starting binary and the final one alternating, five runs each (fastest / median `plan_ms`): warehouse 949 / 1135 → 760 / 1127 ms, hospital_section 1177 / 1218 → 866 / 1038 ms, `lab_b` 989 / 1079 → 839 / 991 ms, intel_map 659 / 804 → 534 / 733 ms; the medians move with this machine's speed from run to run (two earlier rounds put warehouse at 1466 → 1119 and 1356 → 1073 ms). Criterion (`docs/benchmarks.md`, measured before the table change): `lab_b` `lanes` rooms on, run alone, old and new alternating, means 904 → 840 ms; intel_map 712 → 675 ms; the reference itself got faster too (the problem's construction it shares).\n\
- **Planning time, a fifth round, every plan unchanged.** The path files and reports (all but `plan_ms`) of `lanes` on the 31 maps and of `lanes`, `boustrophedon`, `dtc` and `smooth` rooms on and off on six maps, and both segmentations of every map, are byte for byte as before. `lanes`' last check for coverage cells left unvisited marks the cells near the path segment by segment (each piece of a segment looks at the blocks its box, grown by the reach, touches, and tests a cell against the samples nearest its foot only) instead of sample by sample: about 31 → 5 ms per lane angle on warehouse. Admissibility, the coverable cells and the lane mask only ask whether a wall or a cell lies within a few cells, so their distance transforms now look no further (a column pass up to the threshold, then each cell the least sum over the few columns round it; property-tested against the full transforms): about 23 → 7 ms per transform on warehouse, 10 → 3 ms on `lab_b`. The medial axis's crests are found row blocks side by side, and the room units are labelled by the components' run-by-run fill (neighbours joined within one room). Planned alone with the CLI, the session's starting binary and the final one alternating, seven runs each (fastest / median `plan_ms`): warehouse 555 / 565 → 493 / 520 ms, hospital_section 475 / 487 → 446 / 470 ms, `lab_b` 490 / 506 → 475 / 486 ms, intel_map 386 / 391 → 375 / 382 ms. This session's machine ran about twice as fast as the last one (the criterion reference on `lab_b` 392 ms then, 169 ms now), so the targets' lines above (this page's own run) are met with room to spare. The ratio to the reference planned right after on the same map moves less with the machine: this session's first run of this page put warehouse alone at 564 ms, 2.77 times its reference (last session's page: 1004 ms, 2.87 times), which at last session's reference (350 ms) would still be about 970 ms; on this machine hospital_section and warehouse now take turns as the slowest ROS map. The slowest map's remaining time (warehouse, about 0.5 s here) is spread out: the segmentation (which here only tells that the map is one room) about 0.1 s, the two lane angles built side by side about 0.3 s (each: ordering and driving 70 ms, of which two A* routes round the long racks touch 1.1 million cells, detours 50–70 ms, the tightening passes 140–180 ms), the final whole-path tightening and its coverage check about 50 ms. Tried and not kept: a different allocator (mimalloc: no gain, `lab_b` slower), and the A* heuristic's coordinates taken once per expanded cell instead of per neighbour (no gain: the search is bound by memory).\n\
- **With rooms on, the whole plan is tightened at the end.** After every room is planned, its pass built and the transits laid, the whole path is tightened once more, exactly as above, against every coverable cell of the map, each room's waypoints kept in their room (a move may not take a waypoint out of its unit; removing it is always allowed), so that the rooms are still finished one by one: a transit that already covers part of the next room, a room's plan that the pass after it makes partly redundant, the junctions between planner, pass and transit, and the grid planners' own staircases are straightened or dropped. Should rounding leave a cell the plan covered uncovered, the untightened plan is kept (it happened on none of the plans in the tables). Measured when introduced, mean estimated time rooms on, ipa plans / ROS maps, before → after: dtc 13696 → 8427 s / 9013 → 6619 s, full-dtc 13077 → 8145 / 8586 → 6396, grid-cover 12890 → 7976 / 9141 → 6802, spiral-stc 16896 → 9152 / 8581 → 6303, bsa 13603 → 7998 / 8973 → 6441, boustrophedon 10208 → 8213 / 7584 → 6409, trapezoidal 10093 → 8131 / 7592 → 6403, border-expansion 25164 → 7158 / 25292 → 6099 (its roads turn at every cell), smooth 13178 → 7975 / 8802 → 6349, lanes 5954 → 5905 / 4977 → 4951 (its path is tightened already; what is left are the junctions between rooms: rooms on slower than off on 3 ipa plans instead of 4, map.pgm no longer), with coverage 1.0 and 0 collisions throughout; no planner but `lanes` is now slower with rooms on than off on any map of either set (before: `dtc`, `grid-cover`, `spiral-stc` and `border-expansion` on one or two ROS maps each). It costs planning time: the slowest map planned alone with `lanes` 729 → 759 ms (intel_map) and 769 → 847 ms (warehouse). Tightening the whole path first showed that the tightening's own count of what the path reaches disagreed with the metrics' at the very edge of the tool's reach: it counted a cell within the tool radius plus a tenth of the metrics' tolerance, so a cell that a sample reached within the metrics' tolerance but not a tenth of it was invisible and could be left out (83 cells on map.pgm with `boustrophedon`); counting to the full tolerance and beyond instead let it believe cells reached that the metrics did not (a waypoint nudged 10⁻⁴ of a cell off a cell's edge puts samples 1.6·10⁻⁹ cells beyond a tool radius: 745 cells on grid.yaml). It now keeps every cell the old pieces reach within the tool radius plus 1.1 times the tolerance, and counts a new piece as reaching only within 0.9 times it; `lanes` now counts its own detours and tightening with the same two radii (before: a hair, 10⁻⁶ of a cell, inside the tool radius, leaving the cells exactly a tool radius away to its leftover pass): rooms off / on, ipa plans 5920 → 5918 / 5905 → 5906 s, ROS maps 4983 → 4966 / 4951 → 4937 s. The rooms' own pass tightening (above) still pays its time: leaving it out and relying on the final tightening alone (the faster route untightened) planned about 15 % faster and drove slower, ipa plans / ROS maps dtc 8427 → 8748 s / 6619 → 6701 s, boustrophedon 8213 → 8355 / 6409 → 6473, grid-cover 7976 → 8452 / 6802 → 6922. Measured and not kept: a second whole-path tightening after the first (0.3 % more, e.g. dtc 8427 → 8397 s on the ipa plans, lanes 5905 → 5902 s, for a second pass's time); `lanes` counting, when it orders a room's loops and chains, the turn off the transit's last leg into the room (the means unchanged, 5905 → 5904 s on the ipa plans and the same on the ROS maps; it only changed which maps lose, freiburg_building52 −0.5 %, lab_c +0.3 %: the order model's choice of the first entry is not what decides once detours and tightening have run, and from 128 starts × 4 ways in on a bare 20 × 12 room the plans knowing the way in were faster 55 times, slower 50 times and 62 s slower in all).\n\
- **Room by room costs `lanes` a little, and why.** Each coverable cell is claimed by the room unit of its nearest plannable cell, so a strip by a room cut is covered once, and units under 6 m² join a neighbour. Where rooms on was slower, the units it paid for were mostly long and narrow: on lab_a (slower with rooms on until chains were cut where their lanes' extent jumps, above), rows of small offices (each under 6 m² of C-space, so joined to its neighbours) open onto a shared aisle, and the unit they form is entered at one end of the aisle and left at the other; both its wall runs must be driven, so the aisle's length is driven three times, where the whole-map plan drives those walls as part of one loop. Measured and not taken: ordering the rooms by the gap between them instead of between their centres (no change); larger units (10, 25 m²) or a door test that asks 0.4 m more clearance on both sides instead of 2 cells (rooms on 0.397 → 0.403 before the last tightening change) close part of the gap only by no longer planning rooms on their own: the latter finds 7 rooms on lab_a instead of 31, offices merged with the corridor. The cost is structural, not the per-room choice of angle: with the lane angle fixed for every room and the whole map alike, rooms on is still slower (lab_c at 90°: 3881 against 3654 s; lab_a at 0°: 6233 against 5895 s; freiburg_building79 at 0°: 4653 against 4367 s). On lab_c at 90° the rooms' plans lay 102 lanes in 32 chains against the whole map's 90 in 29, and drive 12 open wall runs where the whole map drives closed loops: every lane line and wall loop that passed through a door is cut at the room cut, and each piece needs its own turn. On ROS's simple_rooms the corridor that joins the rooms costs more with rooms on in every planner (lanes +76 s, grid-cover +47 s, smooth +117 s, border-expansion +159 s, by segment midpoints, before the pass was tightened): the transits between rooms cross it without covering it, where a whole-map plan covers it on those crossings.\n\
- **A doorway belongs to the room it leads into.** The medial-axis segmentation cuts a door at the narrowest point of a passage, and a doorway of even width is narrowest all along its length: the first of its equally narrow cells in row-major order was cut, so the doorway went to whichever space lay below it. On simple_rooms the corridor took the doorways of the three rooms above it, which left it a strip with three stubs to be covered from inside it. Of equally narrow candidates, the one nearest where the doorway opens into the narrower of its two spaces is now cut first. The space's width is where a climb to ever wider cells from the opening stops. So an office keeps its doorway and the corridor stays a plain strip (unit-tested on a hand-drawn office and corridor, both ways up). Exact ties only: with clearances rounded down to whole cells before the comparison, map.pgm was 0.7 % slower and nothing else gained. Measured when introduced, mean estimated time rooms on, ipa plans / ROS maps: `lanes` 5822 → 5816 s / 4858 → 4847 s (time efficiency 0.420 / 0.540 → 0.541; turns per 10 m² covered 13.6 / 28.6 → 13.6 / 28.5); lab_c −1.9 %, basement −1.2 %, hospital_section −1.1 %, lab_a −0.3 %; freiburg_building52 +0.8 %, simple_rooms +0.2 %, sparse_obstacles +0.2 %; every other plan the same, with coverage 1.0 and 0 collisions. Rooms on against off for `lanes`: lab_a +1.1 → +0.8 %, basement +1.5 → +0.2 %, simple_rooms +4.2 → +4.5 %. With its doorways the corridor is hatched along its length, where the stubs had made a slanted angle the faster, and the plan gains nothing there. Each room is left by the doorway it was entered through, so the way back from the room's last lane is what rooms on still pays. The other planners move by at most 0.5 % in the mean (grid-cover on the ROS maps 6803 → 6836 s, bsa on the ipa plans 8007 → 8024 s; full-dtc and boustrophedon a little faster on both sets), and all of them still meet the rooms target. Of the 31 maps' segmentations, 18 changed. Most changes only moved a door along its doorway. Five maps changed their count of rooms or doors: depot, map_circular, map.yaml and freiburg_building52 gained a room and a door each, and lab_e lost three of its 1109 regions (most of them specks) and five of its 29 doors. The run of this page that measured the change put warehouse planned alone at 1014 ms, over the 1 s target, with its reference at 460 ms (2.21 times it, where earlier pages had 2.8). Warehouse is one room, and neither its segmentation nor its plan changed. The session's starting binary and this one, alternating five runs each on the same machine, gave medians of 876 and 941 ms on warehouse and 788 and 752 ms on `lab_b`: the machine, slower than in earlier sessions, moved the figure, not the change.\n\
- **The contract's coverable cells make every loop follow the raster of a slanted wall.** A free cell is coverable when its centre lies within the tool radius of a reachable admissible cell's centre, and with robot radius = tool radius the outermost coverable cells lie exactly a tool radius beyond the last admissible centres. Along a wall that is neither axis-parallel nor diagonal those centres form a staircase, and the cell a tool radius beyond each step's last centre is within reach only of points that hug that step: no straight line inside the admissible cells reaches them all, so the loop jogs at every step (about 0.9 rad, 1.8 s, per jog: on a wall of slope 1:20, one per metre, more than half the time of driving that metre). The cost was measured by changing the definition in an experiment only (coverable within the tool radius less half a cell; not the contract, not kept), `lanes` rooms on: ipa plans 0.419 → 0.476 mean time efficiency, ROS maps 0.537 → 0.553; mines 0.399 → 0.486 (its rotation 1609 → 690 rad: its tunnels' walls are long gentle slopes), basement 0.435 → 0.458, the pillar arenas 0.36 → 0.37–0.39. Even so the ROS mean stays far below 0.65: the pillar arenas and basement are bound by U-turns and loops round furniture, not by the raster.
- **Two ipa plans are read as the contract reads an image, not as their benchmark does.** An image without a yaml is read with the ROS defaults (contract), which call every grey above 205 free; the ipa benchmark reads its plans as grey above 250 free and every other value an obstacle (`../shared/maps/ipa-floorplans/SOURCE.md`). Two plans hold large areas of grey 230: lab_b's ground round the building (about 1540 m², read as free and reachable from its start, so its plan covers the building's surroundings, 1812 m², where its floor is 452 m²) and intel_map's unexplored centre (its long lanes there are some of that map's easiest). The issue measured its baseline as a user would, with the contract's defaults, and so does this page; the line under the ipa targets gives the same targets with every plan read the benchmark's way. Measured when introduced, `lanes` rooms on: intel_map 0.369 → 0.332 (307 m² less to cover), lab_b 0.533 → 0.288 (its white floor is cut by scanner specks into pieces, the largest a 0.3 m robot can reach 44 m²), lab_a, lab_c and map.pgm within 0.017 (their thin grey lines and spots close a few passages), the mean 0.421 → 0.391, under the target of 0.40. Which reading the target means is the issue's to say; the library reads a plan either way (`ReadOptions::thresholds`).
- **What the maps leave, per map.** The section above sets each map's time efficiency beside the ceiling of a lane-and-loop plan that wastes nothing else. Measured when introduced: on the ROS maps the mean ceiling is 0.714, so the target of 0.65 asks for 91 % of it on average, where `lanes` reaches 76 % (0.539; from 66 % on basement to 96 % on grid.yaml) and, on bare rectangular rooms, 83 to 98 % of their U-turn ceiling (the synthetic rooms above). Six of the 21 ROS maps have a ceiling below 0.65: the four pillar arenas (about 0.51: nine holes, so nine loops, in a floor of 211 s), mines (0.55) and lse_arena (0.63); even with those six at their ceilings the other fifteen would need a mean of 0.70, 89 % of their own mean ceiling of 0.79, where `lanes` reaches 0.60 on them. On the ipa plans the ceiling is 0.782 and `lanes` reaches 54 % of it: their loops follow raster walls (above) and their rooms' lanes are short. The ceiling lets every hole pass the lanes for free; where the holes cut the lanes instead (the table's `cut` columns, measured when introduced), the ROS maps' mean falls to 0.650, the target itself: a plan at one angle per map whose lanes stop at every hole, with no overlap, link, transit or bend, would just meet it, and 8 of the 21 maps' cut ceilings lie below 0.65 (frieburg's buildings cut its 91 lanes into 370, depot's racks 55 into 161, grid.yaml's block 49 into 84; grid.yaml's plan beats its cut ceiling, 0.784 against 0.725, by hatching the ring round its block in four bands at two angles). `lanes` reaches 83 % of that mean, and 58 % of the ipa plans' (0.723).
- **What would close the gap** (not done): lanes that end on the wall where the wall is straight, so that no loop runs there; and turning while driving (curves) in the contract's time, which charges every heading change as a stop-and-turn. The lines under each setting's targets give the same paths' time efficiency under such models (measured when introduced, `lanes` rooms on, ROS maps / ipa plans: the contract's 0.537 / 0.419; turns of at most 30° taken while driving 0.559 / 0.475; every turn taken while driving 0.679 / 0.546; turning free 0.838 / 0.742): a contract that let gentle turns overlap the drive would not bring the ROS maps to 0.65, one that let every turn overlap it would, without a change to a single path, and what overlap leaves (the turning-free figure) is the ceiling of today's paths under any turn model. Measured and not kept: **passes along an area** as a third way to re-hatch a chain's area (its contours, shrunk by the outermost lines' inset and then by one spacing more each time while any is left, driven as loops: a curved tunnel's band becomes one loop out along it and back): mean estimated time rooms on, ipa plans 5834 → 5846 s, ROS maps 4898 → 4896 s (frieburg −1.1 %, grid.yaml −2.0 %, sparse_obstacles −0.9 %; robocup +1.5 %, intel_map +0.7 %, lab_c +0.5 %), and only −0.2 % on mines, whose time is in its loops (above), not in hatching across its tunnels; with one contour only (bands under two spacings wide) 5845 s / 4890 s. **Or-opt on the order of loops and chains** (after 2-opt, a stretch of one to three nodes moved, either way round, to the gap beside one of the eight nodes nearest its ends, counting the turns at the junctions as the exact choice of entries does): ROS maps 4898 → 4879 s (hospital_section −1.9 %, robocup −1.8 %, maze −2.0 %; smoothers_world +1.6 %) but ipa plans 5834 → 5866 s (lab_b +2.1 %: the order model finds 110 s less transit, the finished path is 400 s slower), and rooms on slower than off on 3 ipa plans and 2 ROS maps; alternating with 2-opt, counting transit only, 5846 s / 4884 s (and about 50 % more planning time on lab_b). **Both wall directions in one region** (a later session; each lane of one wall direction whose strip the other direction's lanes cross longer, on average, goes to the other; each part so formed, at least 16 spacings² and faster by the model than its share of the first direction's chains, is hatched at the other direction and the rest again at the first, so that a band and the arm that leaves it are each hatched along their own length), as one more candidate of the region's order and builds: built in place of the second angle, ROS maps rooms on 4808 → 4839 s (columbia +5.0 %, frieburg +2.0 %: the model prefers it, the finished path does not); built besides the two angles, mean estimated time rooms on, ipa plans / ROS maps, 5804 → 5799 s / 4808 → 4804 s, rooms off 5822 → 5830 s / 4828 → 4814 s (sparse_obstacles rooms off −4.6 %, maze −3.7 %, levinelobby −0.7 %; freiburg_building79 rooms off +1.9 %, where the extra build's fast first pass stopped the winner early), with this page's parallel runs' mean planning time on the ROS maps 457 → 551 ms rooms on; not kept. The parts' edges cut the lanes of both directions again (short runs along ragged walls, islands that cut the new lanes), which takes most of what the longer lanes save. Tried and not kept earlier: a loop chosen as the fastest subsequence of its dense points that keeps every cell in reach (slower than straightening plus tightening: lab_c 3902 against 3872 s, freiburg_building79 4602 against 4367 s); no loops round small islands (slower on both map sets); lanes over the whole C-space up to the walls, measured before the outermost lanes moved in (rooms on, ROS / ipa, against 0.509 / 0.404): without any loop 0.363 / 0.228 (the strips along ragged walls then cost detours and the boundary pass), with the loops kept 0.501 / 0.366; small islands left out of the lane mask, so that lanes bend round them instead of a loop (tb3_sandbox 647 → 747 s); room by room, leaving out of each room's claim the cells that the transits and earlier rooms already covered (every planner within 0.2 %, `lanes` slightly slower: 0.511 / 0.405 against 0.512 / 0.406, ROS / ipa). At 0.3 m lanes a U-turn costs as much as 1.8 m of driving, so the four small ROS arenas (about 4.5 m across, nine pillars each) stay below 0.4 and a mean of 0.65 over the ROS maps would need most maps above today's best single map (about 0.7, warehouse).\n\n";

fn on_off(rooms: bool) -> &'static str {
    if rooms { "on" } else { "off" }
}

fn short(name: &str) -> &str {
    name.rsplit('/').next().unwrap_or(name)
}

/// The room units and the `lanes` path (rooms on) of three maps.
fn pictures(settings: &[Setting], docs: &std::path::Path, md: &mut String) -> anyhow::Result<()> {
    let wanted = ["lab_c.png", "freiburg_building79.png", "simple_rooms.yaml"];
    *md += "## Pictures\n\nRoom units (one colour each: rooms of the medial-axis (voronoi) segmentation that `plan` uses, cut into connected parts of the C-space) and the `lanes` path with rooms on.\n\n";
    for s in settings {
        for (name, map) in &s.maps {
            let Some(w) = wanted.iter().find(|w| name.ends_with(*w)) else {
                continue;
            };
            let stem = w.split('.').next().unwrap_or(w);
            let req = request("lanes", map, s.radius, true)?;
            let problem = req.problem(map)?;
            let units = room_units(map, &problem);
            let seg = docs.join(format!("efficiency_{stem}_rooms.png"));
            let mut scene = Scene::map_only(
                map,
                format!("{} - room units", short(name)),
                vec![("units".into(), units.count().to_string())],
            );
            scene.regions = Some(&units.labels);
            render_to_file(&scene, &seg)?;
            let out = plan(map, &req)?;
            let ev = &out.evaluation;
            let path_png = docs.join(format!("efficiency_{stem}_lanes.png"));
            let scene = Scene {
                map,
                path: &out.points,
                planned: None,
                covered: Some(&ev.covered),
                coverable: Some(&ev.problem.coverable),
                title: format!("{} - lanes, rooms on", short(name)),
                overlay: None,
                regions: None,
                rows: metric_rows(&ev.metrics),
            };
            render_to_file(&scene, &path_png)?;
            let _ = writeln!(
                md,
                "![room units of {name}](efficiency_{stem}_rooms.png)\n\n![lanes on {name}](efficiency_{stem}_lanes.png)\n"
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn other_time_models_charge_turns_as_they_say() {
        let time = TimeModel::default();
        let (v, w) = (time.linear_speed, time.angular_speed);
        let pts = |xy: &[(f64, f64)]| {
            xy.iter()
                .map(|&(x, y)| Point::new(x, y))
                .collect::<Vec<_>>()
        };
        // A U-turn: 3 m, a quarter turn, 0.3 m, a quarter turn, 3 m (a
        // repeated point changes nothing).
        let u = pts(&[(0.0, 0.0), (3.0, 0.0), (3.0, 0.3), (3.0, 0.3), (0.0, 0.3)]);
        let q = std::f64::consts::FRAC_PI_2;
        let [gentle, every, free] = other_models(&u, 1.0, &time);
        // Quarter turns are sharp: charged in full but when every turn is
        // taken while driving (the link then takes the turn's time, the lane
        // its drive).
        assert!((1.0 / gentle - (6.3 / v + 2.0 * q / w)).abs() < 1e-9);
        assert!((1.0 / every - (3.0 / v + q / w + 3.0 / v)).abs() < 1e-9);
        assert!((1.0 / free - 6.3 / v).abs() < 1e-9);
        // Gentle bends along a 1 m step: each bend hides in its segment.
        let bend = pts(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.2), (3.0, 0.4)]);
        let [gentle, every, _] = other_models(&bend, 1.0, &time);
        let drive = (1.0 + 2.0 * 1.04f64.sqrt()) / v;
        assert!((1.0 / gentle - drive).abs() < 1e-9);
        assert!((1.0 / every - drive).abs() < 1e-9);
        // No path, no time: no efficiency.
        assert_eq!(other_models(&[], 1.0, &time), [0.0; 3]);
    }

    #[test]
    fn the_time_split_adds_up_to_the_estimated_time() {
        let time = TimeModel::default();
        let (v, w) = (time.linear_speed, time.angular_speed);
        let q = std::f64::consts::FRAC_PI_2;
        // A U-turn (two quarter turns: turns) then a bend of 0.2 rad.
        let (c, s) = (0.2f64.cos(), 0.2f64.sin());
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(3.0, 0.0),
            Point::new(3.0, 0.3),
            Point::new(3.0, 0.3),
            Point::new(0.0, 0.3),
            Point::new(-c, 0.3 + s),
        ];
        let t = time_split(&pts, 10.0, &time);
        let length = 6.3 + 1.0;
        assert!((t.total() - time.time(length, 2.0 * q + 0.2)).abs() < 1e-9);
        assert!((t.bound - 10.0).abs() < 1e-12);
        assert!((t.overlap - (length / v - 10.0)).abs() < 1e-9);
        assert!((t.turns - 2.0 * q / w).abs() < 1e-9);
        assert!((t.bends - 0.2 / w).abs() < 1e-9);
        // Each part free in turn.
        let text = split_summary("p", &[t]);
        let over = t.total() - t.bound;
        assert!(
            text.contains(&format!("bends {:.0} %", 100.0 * t.bends / over)),
            "{text}"
        );
        assert!(
            text.contains(&format!("bends free: {:.3}", 10.0 / (t.total() - t.bends))),
            "{text}"
        );
    }
}
