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
use oxcover::planners::{CoverageProblem, PlannerOptions, Start};
use oxcover::render::{Scene, render_to_file};
use oxcover::report::metric_rows;
use oxcover_grid::{DiscRobot, OccupancyGrid};
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
    room_units: Option<usize>,
}

impl Run {
    fn of(out: &PlanOutcome, res: f64) -> Self {
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
            room_units: out.room_units,
        }
    }
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
    match request(name, map, radius, rooms).and_then(|r| Ok(plan(map, &r)?)) {
        Ok(out) => Outcome::Done(Run::of(&out, map.resolution())),
        Err(e)
            if e.to_string().contains("accepts at most")
                || e.to_string().contains("needs a coverage grid") =>
        {
            Outcome::Skipped
        }
        Err(e) => Outcome::Failed(e.to_string()),
    }
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

/// Runs the task.
///
/// # Errors
/// When the shared maps are missing, a picture or the page cannot be
/// written, or a complete planner fails or collides.
pub fn run() -> anyhow::Result<()> {
    let maps = match crate::floor_plans() {
        Ok(m) => m,
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
        },
        Setting {
            name: "ROS maps",
            radius: 0.15,
            maps: ros,
        },
    ];
    let names: Vec<&'static str> = planners()
        .into_iter()
        .filter(|p| p.complete)
        .map(|p| p.name)
        .collect();
    let docs = crate::root().join("docs");
    let mut md = String::from(
        "# Efficiency: estimated time of every complete planner, rooms on and off\n\n\
         Command: `cargo xtask efficiency` (release, rayon over runs). Settings: the ipa floor plans of `../shared/maps/ipa-floorplans` at 0.05 m/px with robot = tool radius 0.3 m; the ROS maps of `../shared/maps/ros` with robot = tool radius 0.15 m. Start at the first cell of the largest admissible region, boundary pass on, contract speeds v = 0.3 m/s and w = 0.52 rad/s.\n\n\
         Columns: `min cov` the worst map's coverage; `coll` collisions summed over maps; then means over maps of the path length, turns per 10 m² covered, estimated time (`est_time_s`), time efficiency (`bound_time_s / est_time_s`, 1.0 = straight non-overlapping lanes with no turn) and the boundary pass's share of the length; `plan ms` mean and slowest map (the whole pipeline: problem, rooms, planner, boundary pass). `full-dtc` and `grid-cover` are skipped above the sizes `cargo xtask acceptance` skips them at; `optimal` refuses maps wider than its exact search allows.\n\n",
    );
    let mut failures = Vec::new();
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
        let mut best: Option<(f64, &str, bool)> = None;
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
                if complete_everywhere && best.is_none_or(|b| eff > b.0) {
                    best = Some((eff, name, rooms));
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
            if !slower.is_empty() {
                worse.push(format!(
                    "- {name}: {} of {} maps: {}",
                    slower.len(),
                    s.maps.len(),
                    slower.join(", ")
                ));
            }
        }
        if let Some((eff, name, rooms)) = best {
            let _ = writeln!(
                md,
                "\nBest mean time efficiency with every map planned: **{name}, rooms {}** ({eff:.3}).\n",
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
    pictures(&settings, &docs, &mut md)?;
    std::fs::write(docs.join("efficiency.md"), md)?;
    println!("wrote docs/efficiency.md");
    if !failures.is_empty() {
        anyhow::bail!("{} runs failed:\n{}", failures.len(), failures.join("\n"));
    }
    Ok(())
}

fn on_off(rooms: bool) -> &'static str {
    if rooms { "on" } else { "off" }
}

fn short(name: &str) -> &str {
    name.rsplit('/').next().unwrap_or(name)
}

/// The room units and the `lanes` path (rooms on) of three maps.
fn pictures(settings: &[Setting], docs: &std::path::Path, md: &mut String) -> anyhow::Result<()> {
    let wanted = ["lab_c.png", "freiburg_building79.png", "simple_rooms.yaml"];
    *md += "## Pictures\n\nRoom units (one colour each: rooms of the morphological segmentation, cut into connected parts of the C-space) and the `lanes` path with rooms on.\n\n";
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
