//! The outputs of a plan: its picture, the files the command line writes
//! (all or none), and the notes on what coverage was left and why.

use std::path::{Path, PathBuf};

use oxcover_grid::{Coverability, OccupancyGrid, components4};
use oxcover_planners::largest_region_cell;

use super::request::{PlanOutcome, PlanRequest};
use crate::error::{Error, Result};
use crate::output::write_files;
use crate::path::to_csv;
use crate::render::{Overlay, Scene, render_bytes};
use crate::report::metric_rows;

/// Where to write a plan's outputs (each optional).
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    /// Path file (CSV, header `x,y`).
    pub csv: Option<&'a Path>,
    /// SVG picture.
    pub svg: Option<&'a Path>,
    /// PNG picture.
    pub png: Option<&'a Path>,
    /// JSON report.
    pub report: Option<&'a Path>,
    /// ROS 2 bag (MCAP): map, stamped path, rooms, targets.
    pub bag: Option<&'a Path>,
}

/// The picture of a plan of `request` on `map` (named `map_name`), as
/// `plan --svg/--png` draws it: the map, the covered cells, the path and a
/// legend of its metrics.
#[must_use]
pub fn plan_scene<'a>(
    map: &'a OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &'a PlanOutcome,
) -> Scene<'a> {
    let ev = &outcome.evaluation;
    Scene {
        map,
        path: &outcome.points,
        planned: None,
        covered: Some(&ev.covered),
        coverable: Some(&ev.problem.coverable),
        title: format!("{} - {}", short_name(map_name), request.planner.name()),
        overlay: None,
        regions: None,
        rows: metric_rows(&ev.metrics),
    }
}

/// The pictures of a plan of `request` on `map` (named `map_name`), one
/// for each of `files` in the format its extension names: [`plan_scene`]
/// with the request's targets drawn over it
/// ([`crate::targets::target_overlay`]).
///
/// # Errors
/// A bad picture extension; as [`crate::targets::target_overlay`].
pub fn plan_pictures(
    map: &OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &PlanOutcome,
    files: &[&Path],
) -> Result<Vec<Vec<u8>>> {
    if files.is_empty() {
        return Ok(Vec::new());
    }
    let mut scene = plan_scene(map, map_name, request, outcome);
    let overlay = crate::targets::target_overlay(&request.targets, map)?;
    if overlay != Overlay::default() {
        scene.overlay = Some(&overlay);
    }
    files.iter().map(|f| render_bytes(&scene, f)).collect()
}

/// Writes the CSV, pictures and report of a plan of `request` on `map`
/// (named `map_name`), all of them or none ([`crate::output::write_files`]);
/// returns the files written.
///
/// # Errors
/// [`Error::Write`] naming the file that could not be written (then none
/// is); a bad picture extension.
pub fn write_outputs(
    map: &OccupancyGrid,
    map_name: &str,
    request: &PlanRequest,
    outcome: &PlanOutcome,
    out: &Outputs<'_>,
) -> Result<Vec<PathBuf>> {
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = out.csv {
        files.push((p.to_path_buf(), to_csv(&outcome.points).into_bytes()));
    }
    let pictures: Vec<&Path> = [out.svg, out.png].into_iter().flatten().collect();
    let drawn = plan_pictures(map, map_name, request, outcome, &pictures)?;
    files.extend(pictures.iter().map(|p| p.to_path_buf()).zip(drawn));
    if let Some(p) = out.report {
        let report = outcome.report(map, map_name, request);
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::Internal(format!("report serialisation failed: {e}")))?;
        files.push((p.to_path_buf(), (json + "\n").into_bytes()));
    }
    if let Some(p) = out.bag {
        let extras = crate::bag::BagExtras {
            rooms: Some(crate::bag::room_markers(map)?),
            targets: crate::bag::target_markers(&request.targets, map.resolution()),
            odom: Vec::new(),
        };
        let bytes = crate::bag::bag_bytes(map, &outcome.points, &request.time, extras, p)?;
        files.push((p.to_path_buf(), bytes));
    }
    write_files(files)
}

/// Hints about what a plan leaves out: free cells it cannot cover, and a
/// default start stranded in a small component (common in SLAM maps, whose
/// first free cell is often a speck of noise).
pub fn coverage_notes(
    map: &OccupancyGrid,
    problem: &Coverability,
    default_start: bool,
) -> Vec<String> {
    let mut notes = Vec::new();
    let free = map.counts().free;
    let coverable = problem.coverable_count();
    if coverable < free {
        notes.push(format!(
            "{} of {free} free cells are not coverable (not reachable from the start, or too close to obstacles for this robot and tool) and are not counted",
            free - coverable
        ));
    }
    let comps = components4(&problem.admissible);
    let mine = comps.labels[problem.start];
    if let Some(big) = comps.largest() {
        let (ours, theirs) = (
            comps.sizes[mine as usize - 1],
            comps.sizes[big as usize - 1],
        );
        if big != mine && theirs > 2 * ours {
            if let Some(cell) = largest_region_cell(&problem.admissible) {
                let p = map.frame().cell_center(cell);
                let how = if default_start {
                    "the default start (first admissible cell)"
                } else {
                    "the start"
                };
                notes.push(format!(
                    "{how} lies in a region of {ours} admissible cells; the largest has {theirs}: try --start {},{}",
                    metres(p.x),
                    metres(p.y)
                ));
            }
        }
    }
    notes
}

/// A coordinate in metres for people to read and type back (`--start`):
/// at most six decimals, trailing zeros dropped.
#[must_use]
pub fn metres(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

/// The file name of a path, for titles.
#[must_use]
pub fn short_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}
