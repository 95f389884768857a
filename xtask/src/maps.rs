//! `cargo xtask maps`: the real-map check behind the foundation's promise:
//! `plan --planner dtc` then `eval` on every ROS and MovingAI map gives zero
//! collisions and full coverage with the default radii, and at least 0.99
//! with a 0.15 m robot and tool on the ROS maps. Writes `docs/maps.md`.

use std::path::{Path, PathBuf};

use oxcover::metrics::{MetricParams, evaluate};
use oxcover::path::{read_csv, write_csv};
use oxcover::planner::{PlanRequest, plan};
use oxcover_grid::DiscRobot;
use oxcover_grid::io::{ReadOptions, read_map};
use rayon::prelude::*;

/// A map, a setting name, and optional (robot, tool) radii.
type Job = (PathBuf, &'static str, Option<(f64, f64)>);

struct Row {
    map: String,
    setting: &'static str,
    size: String,
    coverable: usize,
    raw: f64,
    coverage: f64,
    collisions: usize,
    length_m: f64,
    turns: usize,
    plan_ms: f64,
}

fn files(dir: &Path, ext: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            files(&p, ext, out);
        } else if p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| ext.contains(&e))
        {
            out.push(p);
        }
    }
}

fn check(
    map_path: &Path,
    root: &Path,
    setting: &'static str,
    robot: Option<(f64, f64)>,
) -> anyhow::Result<Row> {
    let map = read_map(map_path, &ReadOptions::default())?;
    let res = map.resolution();
    let robot = match robot {
        Some((r, t)) => DiscRobot::new(r, t)?,
        None => DiscRobot::cell_sized(res),
    };
    let request = PlanRequest {
        robot,
        ..PlanRequest::new("dtc", res)
    };
    let out = plan(&map, &request)?;
    // Score the written file, as `oxcover eval` would.
    let rel = map_path
        .strip_prefix(root)
        .unwrap_or(map_path)
        .display()
        .to_string();
    let csv = crate::root()
        .join("target/xtask/maps")
        .join(format!("{}-{setting}.csv", rel.replace(['/', '.'], "_")));
    if let Some(d) = csv.parent() {
        std::fs::create_dir_all(d)?;
    }
    write_csv(&csv, &out.points)?;
    let ev = evaluate(&map, robot, &read_csv(&csv)?, &MetricParams::default())?;
    let m = ev.metrics;
    Ok(Row {
        map: rel,
        setting,
        size: format!("{}x{}", map.width(), map.height()),
        coverable: m.coverable_cells,
        raw: out.coverage_without_boundary_pass,
        coverage: m.coverage,
        collisions: m.collisions,
        length_m: m.length_m,
        turns: m.turns,
        plan_ms: out.plan_ms,
    })
}

pub(crate) fn run(filter: Option<&str>) -> anyhow::Result<()> {
    let Some(root) = crate::shared_maps() else {
        anyhow::bail!("../shared/maps not found next to the workspace");
    };
    let mut maps = Vec::new();
    files(&root.join("ros"), &["yaml"], &mut maps);
    files(&root.join("movingai"), &["map"], &mut maps);
    maps.retain(|p| filter.is_none_or(|f| p.display().to_string().contains(f)));
    let mut jobs: Vec<Job> = Vec::new();
    for m in &maps {
        jobs.push((m.clone(), "default", None));
        if m.extension().is_some_and(|e| e == "yaml") {
            jobs.push((m.clone(), "r0.15_t0.15", Some((0.15, 0.15))));
        }
    }
    let rows: Vec<(String, anyhow::Result<Row>)> = jobs
        .par_iter()
        .map(|(p, s, r)| (p.display().to_string(), check(p, &root, s, *r)))
        .collect();
    let mut md = String::from(
        "| map | setting | size | coverable | coverage (no boundary pass) | coverage | collisions | length m | turns | plan ms |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let (mut worst_default, mut worst_robot, mut collisions, mut failures) =
        (1.0f64, 1.0f64, 0usize, 0usize);
    for (name, r) in &rows {
        match r {
            Ok(r) => {
                md += &format!(
                    "| {} | {} | {} | {} | {:.4} | {:.4} | {} | {:.1} | {} | {:.0} |\n",
                    r.map,
                    r.setting,
                    r.size,
                    r.coverable,
                    r.raw,
                    r.coverage,
                    r.collisions,
                    r.length_m,
                    r.turns,
                    r.plan_ms
                );
                collisions += r.collisions;
                if r.setting == "default" {
                    worst_default = worst_default.min(r.coverage);
                } else {
                    worst_robot = worst_robot.min(r.coverage);
                }
            }
            Err(e) => {
                failures += 1;
                md += &format!("| {name} | - | error: {e} | | | | | | | |\n");
            }
        }
    }
    let summary = format!(
        "{} runs on {} maps: {} failures, {} collisions in total, lowest coverage {:.4} (default radii) and {:.4} (robot and tool 0.15 m, ROS maps).\n\n",
        rows.len(),
        maps.len(),
        failures,
        collisions,
        worst_default,
        worst_robot
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
