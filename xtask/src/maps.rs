//! `cargo xtask maps`: the real-map check behind the foundation's promise:
//! `plan --planner dtc` then `eval` on every ROS and MovingAI map gives zero
//! collisions and full coverage with the default radii, and at least 0.99
//! with a 0.15 m robot and tool on the ROS maps. Each map is planned from the
//! contract's default start and from the largest admissible region (the
//! default start of a SLAM map is often a speck of noise). Writes `docs/maps.md`.

use std::path::{Path, PathBuf};

use oxcover::metrics::{MetricParams, evaluate};
use oxcover::path::{read_csv, write_csv};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::Start;
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::{DiscRobot, OccupancyGrid};
use rayon::prelude::*;

/// A map, a setting name, and optional (robot, tool) radii.
type Job = (PathBuf, &'static str, Option<(f64, f64)>);

/// Scores of one plan, as `oxcover eval` gives them for the written path file.
pub(crate) struct Scores {
    pub(crate) coverable: usize,
    /// Coverage before the boundary pass.
    pub(crate) raw: f64,
    pub(crate) coverage: f64,
    pub(crate) collisions: usize,
    pub(crate) length_m: f64,
    pub(crate) turns: usize,
    pub(crate) plan_ms: f64,
}

struct Row {
    map: String,
    setting: &'static str,
    size: String,
    free: usize,
    /// With the contract's default start (first admissible cell, row-major).
    default_start: Scores,
    /// Starting in the largest admissible region.
    largest: Scores,
}

/// Plans with `planner` (and the boundary pass), writes the path file to
/// `csv`, reads it back and scores it.
pub(crate) fn plan_and_score(
    map: &OccupancyGrid,
    planner: &str,
    robot: DiscRobot,
    start: Start,
    csv: &Path,
) -> anyhow::Result<Scores> {
    let request = PlanRequest::new(planner, map.resolution())?
        .robot(robot)
        .start(start);
    let out = plan(map, &request)?;
    // Score the written file, as `oxcover eval` would.
    write_csv(csv, &out.points)?;
    let m = evaluate(map, robot, &read_csv(csv)?, &MetricParams::default())?.metrics;
    Ok(Scores {
        coverable: m.coverable_cells,
        raw: out.coverage_without_boundary_pass,
        coverage: m.coverage,
        collisions: m.collisions,
        length_m: m.length_m,
        turns: m.turns,
        plan_ms: out.plan_ms,
    })
}

fn check(
    map_path: &Path,
    root: &Path,
    setting: &'static str,
    radii: Option<(f64, f64)>,
) -> anyhow::Result<Row> {
    let map = read_map(map_path, &ReadOptions::default())?;
    let robot = match radii {
        Some((r, t)) => DiscRobot::new(r, t)?,
        None => DiscRobot::cell_sized(map.resolution()),
    };
    let rel = map_path
        .strip_prefix(root)
        .unwrap_or(map_path)
        .display()
        .to_string();
    let dir = crate::root().join("target/xtask/maps");
    std::fs::create_dir_all(&dir)?;
    let stem = format!("{}-{setting}", rel.replace(['/', '.'], "_"));
    let default_start = plan_and_score(
        &map,
        "dtc",
        robot,
        Start::First,
        &dir.join(format!("{stem}-default.csv")),
    )?;
    let largest = plan_and_score(
        &map,
        "dtc",
        robot,
        Start::LargestRegion,
        &dir.join(format!("{stem}-largest.csv")),
    )?;
    Ok(Row {
        map: rel,
        setting,
        size: format!("{}x{}", map.width(), map.height()),
        free: map.counts().free,
        default_start,
        largest,
    })
}

/// Runs the task.
///
/// # Errors
/// When a step fails (see the module docs).
pub fn run(filter: Option<&str>) -> anyhow::Result<()> {
    let Some(root) = crate::shared_maps() else {
        anyhow::bail!("../shared/maps not found next to the workspace");
    };
    let mut maps = crate::map_files(&root.join("ros"), &["yaml"]);
    maps.extend(crate::map_files(&root.join("movingai"), &["map"]));
    maps.retain(|p| filter.is_none_or(|f| p.display().to_string().contains(f)));
    let mut jobs: Vec<Job> = Vec::new();
    for m in &maps {
        jobs.push((m.clone(), "default", None));
        if m.extension().is_some_and(|e| e == "yaml") {
            jobs.push((m.clone(), "0.15 m", Some((0.15, 0.15))));
        }
    }
    let rows: Vec<(String, anyhow::Result<Row>)> = jobs
        .par_iter()
        .map(|(p, s, r)| (p.display().to_string(), check(p, &root, s, *r)))
        .collect();
    let mut md = String::from(
        "| map | radii | size | free | default start: coverable | coverage | collisions | largest region: coverable | coverage (no boundary pass) | coverage | collisions | length m | turns | plan ms |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let (mut worst_default, mut worst_robot, mut collisions, mut failures) =
        (1.0f64, 1.0f64, 0usize, 0usize);
    let mut stranded = 0;
    for (name, r) in &rows {
        match r {
            Ok(r) => {
                let (d, l) = (&r.default_start, &r.largest);
                md += &format!(
                    "| {} | {} | {} | {} | {} | {:.4} | {} | {} | {:.4} | {:.4} | {} | {:.1} | {} | {:.0} |\n",
                    r.map,
                    r.setting,
                    r.size,
                    r.free,
                    d.coverable,
                    d.coverage,
                    d.collisions,
                    l.coverable,
                    l.raw,
                    l.coverage,
                    l.collisions,
                    l.length_m,
                    l.turns,
                    l.plan_ms
                );
                collisions += d.collisions + l.collisions;
                if d.coverable * 2 < l.coverable {
                    stranded += 1;
                }
                let worst = d.coverage.min(l.coverage);
                if r.setting == "default" {
                    worst_default = worst_default.min(worst);
                } else {
                    worst_robot = worst_robot.min(worst);
                }
            }
            Err(e) => {
                failures += 1;
                md += &format!("| {name} | - | error: {e} | | | | | | | | | | | |\n");
            }
        }
    }
    let summary = format!(
        "{} settings on {} maps, each planned from the contract's default start and from the largest admissible region: {} failures, {} collisions in total, lowest coverage {:.4} (default radii) and {:.4} (robot and tool 0.15 m, ROS maps). In {} settings the default start (the first admissible cell, row-major) lies in a region less than half the size of the largest one, typically a speck of SLAM noise near the top of the image; `oxcover plan` then prints a note suggesting a `--start` in the largest region.\n\n",
        rows.len(),
        maps.len(),
        failures,
        collisions,
        worst_default,
        worst_robot,
        stranded
    );
    print!("{summary}");
    if filter.is_none() {
        let doc = crate::root().join("docs/maps.md");
        crate::replace_section(&doc, "maps", &format!("{summary}{md}"))?;
        println!("updated {}", doc.display());
    } else {
        print!("{md}");
    }
    if failures > 0 || collisions > 0 || worst_default < 1.0 || worst_robot < 0.99 {
        anyhow::bail!("the real-map check failed");
    }
    Ok(())
}
