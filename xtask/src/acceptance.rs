//! `cargo xtask acceptance`: every planner that promises complete coverage,
//! on every real map, judged as `oxcover eval` judges a path file.
//!
//! Two settings:
//! - **floor plans**: every ROS map and every ipa floor plan
//!   ([`crate::floor_plans`]) with robot and tool radius 0.3 m;
//! - **unit grids**: every MovingAI map and every ROS map with the contract's
//!   default radii (robot 0, tool half a cell: the coverage grid is the map).
//!
//! The MovingAI maps (cities, game maps, mazes, random, rooms) played no part
//! in developing the sweep and border-expansion planners: they are the
//! "maps nobody here has seen".
//!
//! Each run plans with the boundary pass from the first cell of the largest
//! admissible region, writes the path file, reads it back and scores it. The
//! task fails when a complete planner errors, collides, or covers less than
//! 0.99 of the coverable set. A documented refusal (a planner's size limit,
//! like `optimal`'s) is listed, not failed. Writes `docs/acceptance.md`.

use std::collections::BTreeMap;

use oxcover::pipeline::planners;
use oxcover::planners::{CoverageProblem, Start};
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::{DiscRobot, OccupancyGrid};
use rayon::prelude::*;

use crate::maps::{Scores, plan_and_score};

/// Lowest acceptable coverage.
const MIN_COVERAGE: f64 = 0.99;

/// Planners whose time grows with the square of the coverage cells, and the
/// problem size (coverage cells) above which this task does not run them:
/// `full-dtc` runs a DTC per goal (O(n²)); `grid-cover` re-plans over a
/// quadtree at every move (about two minutes at 96k cells). Skipped runs are
/// listed, neither passed nor failed.
const QUADRATIC: [(&str, usize); 2] = [("full-dtc", 20_000), ("grid-cover", 50_000)];

/// The coverage-cell count above which this task skips `planner`, if it
/// is one of the quadratic ones (`full-dtc` and `grid-cover`).
#[must_use]
pub fn quadratic_limit(planner: &str) -> Option<usize> {
    QUADRATIC.iter().find(|q| q.0 == planner).map(|q| q.1)
}

/// A setting: its name, the maps and the radii (`None`: contract defaults).
struct Setting {
    name: &'static str,
    maps: Vec<(String, OccupancyGrid)>,
    radii: Option<(f64, f64)>,
}

enum Outcome {
    Scored(Scores),
    /// The planner's documented size limit.
    Refused(String),
    /// Not run: a quadratic planner on a large problem ([`QUADRATIC`]).
    Skipped(usize),
    Failed(String),
}

fn run_one(
    setting: &Setting,
    map_name: &str,
    map: &OccupancyGrid,
    planner: &str,
) -> anyhow::Result<Outcome> {
    let robot = match setting.radii {
        Some((r, t)) => DiscRobot::new(r, t)?,
        None => DiscRobot::cell_sized(map.resolution()),
    };
    let start = Start::LargestRegion;
    if let Some(&(_, limit)) = QUADRATIC.iter().find(|q| q.0 == planner) {
        let problem = CoverageProblem::new(map, robot, start)?;
        let cells = problem.input(0).coverage_cells();
        if cells > limit {
            return Ok(Outcome::Skipped(cells));
        }
    }
    let dir = crate::root().join("target/xtask/acceptance");
    std::fs::create_dir_all(&dir)?;
    let csv = dir.join(format!(
        "{}-{}-{planner}.csv",
        setting.name.replace(' ', "_"),
        map_name.replace(['/', '.'], "_")
    ));
    Ok(match plan_and_score(map, planner, robot, start, &csv) {
        Ok(s) => Outcome::Scored(s),
        Err(e) => match e.downcast_ref::<oxcover::Error>() {
            Some(oxcover::Error::Planner(
                p @ (oxcover_planners::Error::TooLarge { .. }
                | oxcover_planners::Error::TooWide { .. }),
            )) => Outcome::Refused(p.to_string()),
            _ => Outcome::Failed(format!("{e:#}")),
        },
    })
}

fn settings(filter: Option<&str>) -> anyhow::Result<Vec<Setting>> {
    let Some(root) = crate::shared_maps() else {
        anyhow::bail!("../shared/maps not found next to the workspace");
    };
    let keep = |n: &String| filter.is_none_or(|f| n.contains(f));
    let floor: Vec<(String, OccupancyGrid)> = crate::floor_plans()?
        .into_iter()
        .filter(|(n, _)| keep(n))
        .collect();
    let mut unit = Vec::new();
    let mut paths = crate::map_files(&root.join("movingai"), &["map"]);
    paths.extend(crate::map_files(&root.join("ros"), &["yaml"]));
    for p in paths {
        let name = p.strip_prefix(&root).unwrap_or(&p).display().to_string();
        if keep(&name) {
            unit.push((name, read_map(&p, &ReadOptions::default())?));
        }
    }
    Ok(vec![
        Setting {
            name: "floor plans",
            maps: floor,
            radii: Some((0.3, 0.3)),
        },
        Setting {
            name: "unit grids",
            maps: unit,
            radii: None,
        },
    ])
}

/// Per-planner summary of one setting.
#[derive(Default)]
struct Summary {
    runs: usize,
    refused: usize,
    failed: usize,
    skipped: usize,
    collisions: usize,
    below: usize,
    min_coverage: f64,
    min_raw: f64,
    plan_ms: Vec<f64>,
}

/// Runs the task.
///
/// # Errors
/// When `../shared/maps` is missing or a complete planner fails the check.
pub fn run(filter: Option<&str>, only: Option<&str>) -> anyhow::Result<()> {
    let names: Vec<&'static str> = planners()
        .into_iter()
        .filter(|p| p.complete && only.is_none_or(|o| o.split(',').any(|n| n == p.name)))
        .map(|p| p.name)
        .collect();
    let settings = settings(filter)?;
    let jobs: Vec<(usize, usize, &'static str)> = settings
        .iter()
        .enumerate()
        .flat_map(|(s, set)| {
            let names = &names;
            (0..set.maps.len()).flat_map(move |m| names.iter().map(move |&p| (s, m, p)))
        })
        .collect();
    let bar = crate::progress(jobs.len() as u64, "acceptance");
    let results: Vec<Outcome> = jobs
        .par_iter()
        .map(|&(s, m, p)| {
            let set = &settings[s];
            let (name, map) = &set.maps[m];
            let out = run_one(set, name, map, p).unwrap_or_else(|e| Outcome::Failed(e.to_string()));
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();

    let mut md = String::new();
    let mut failures = Vec::new();
    for (s, set) in settings.iter().enumerate() {
        let radii = set.radii.map_or(
            "contract defaults (robot 0, tool half a cell)".to_string(),
            |(r, t)| format!("robot {r} m, tool {t} m"),
        );
        md += &format!("\n## {}: {} maps, {radii}\n\n", set.name, set.maps.len());
        let mut sums: BTreeMap<&str, Summary> = BTreeMap::new();
        let mut table = format!(
            "| map | size | {} |\n|---|---|{}\n",
            names.join(" | "),
            "---:|".repeat(names.len())
        );
        for (m, (map_name, map)) in set.maps.iter().enumerate() {
            table += &format!("| {map_name} | {}x{} |", map.width(), map.height());
            for &p in &names {
                let i = jobs
                    .iter()
                    .position(|&j| j == (s, m, p))
                    .unwrap_or_default();
                let sum = sums.entry(p).or_insert_with(|| Summary {
                    min_coverage: 1.0,
                    min_raw: 1.0,
                    ..Summary::default()
                });
                match &results[i] {
                    Outcome::Scored(sc) => {
                        sum.runs += 1;
                        sum.collisions += sc.collisions;
                        sum.min_coverage = sum.min_coverage.min(sc.coverage);
                        sum.min_raw = sum.min_raw.min(sc.raw);
                        sum.plan_ms.push(sc.plan_ms);
                        let bad = sc.collisions > 0 || sc.coverage < MIN_COVERAGE;
                        if bad {
                            sum.below += 1;
                            failures.push(format!(
                                "{} / {map_name} / {p}: coverage {:.4}, {} collisions",
                                set.name, sc.coverage, sc.collisions
                            ));
                        }
                        table += &format!(
                            " {:.4}{} |",
                            sc.coverage,
                            if sc.collisions > 0 {
                                format!(" ({} coll.)", sc.collisions)
                            } else {
                                String::new()
                            }
                        );
                    }
                    Outcome::Refused(_) => {
                        sum.refused += 1;
                        table += " refused |";
                    }
                    Outcome::Skipped(n) => {
                        sum.skipped += 1;
                        table += &format!(" skipped ({n}) |");
                    }
                    Outcome::Failed(e) => {
                        sum.failed += 1;
                        failures.push(format!("{} / {map_name} / {p}: {e}", set.name));
                        table += " **error** |";
                    }
                }
            }
            table += "\n";
        }
        md += "| planner | runs | refused | skipped | errors | collisions | below 0.99 | lowest coverage | lowest coverage without the boundary pass | median plan ms | slowest plan ms |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (p, sum) in &mut sums {
            sum.plan_ms.sort_by(f64::total_cmp);
            let median = sum
                .plan_ms
                .get(sum.plan_ms.len() / 2)
                .copied()
                .unwrap_or(0.0);
            let slowest = sum.plan_ms.last().copied().unwrap_or(0.0);
            md += &format!(
                "| {p} | {} | {} | {} | {} | {} | {} | {:.4} | {:.4} | {median:.0} | {slowest:.0} |\n",
                sum.runs,
                sum.refused,
                sum.skipped,
                sum.failed,
                sum.collisions,
                sum.below,
                sum.min_coverage,
                sum.min_raw
            );
        }
        md += &format!(
            "\nCoverage of each run (`refused`: the planner's documented size limit; `skipped (n)`: a quadratic planner not run on n coverage cells, see the introduction):\n\n{table}"
        );
    }
    let refusals: Vec<String> = results
        .iter()
        .zip(&jobs)
        .filter_map(|(r, &(s, m, p))| match r {
            Outcome::Refused(e) => Some(format!(
                "{} / {} / {p}: {e}",
                settings[s].name, settings[s].maps[m].0
            )),
            _ => None,
        })
        .take(3)
        .collect();
    if !refusals.is_empty() {
        md += &format!(
            "\nExamples of refusals:\n\n{}\n",
            refusals
                .iter()
                .map(|r| format!("- {r}\n"))
                .collect::<String>()
        );
    }
    let head = format!(
        "{} runs ({} complete planners); {} failures.\n",
        results.len(),
        names.len(),
        failures.len()
    );
    print!("{head}");
    for f in &failures {
        println!("FAIL {f}");
    }
    if filter.is_none() && only.is_none() {
        let doc = crate::root().join("docs/acceptance.md");
        crate::replace_section(&doc, "acceptance", &format!("{head}{md}"))?;
        println!("updated {}", doc.display());
    } else {
        // Some maps or planners only: the tables are printed, the page kept.
        print!("{md}");
    }
    if !failures.is_empty() {
        anyhow::bail!("{} runs failed the acceptance check", failures.len());
    }
    Ok(())
}
