//! The page's targets table: `lanes`, rooms on, on every shared map with
//! the coverage targets a user sets most (`docs/efficiency.md`,
//! "Coverage targets").
//!
//! Per map: the whole map; one zone (the bounding box of a room of
//! `oxcover segment`'s rooms, the largest of at most 40 m² coverable from
//! the start, else the smallest); the two largest rooms (`--rooms-only`); a resume from the
//! half-way waypoint of the whole plan (`--done`, started where it
//! stopped: the done part's time plus the rest's against the whole
//! plan's); three keep-out squares of 0.8 m at the centres of the three
//! largest rooms. Keep-out violations are path samples in cells the
//! keep-out areas block, counted independently of the planner.

use std::fmt::Write as _;

use geo::{LineString, Polygon};
use oxcover::pipeline::{PlanOutcome, PlanRequest, plan, planner};
use oxcover::planners::{CoverageProblem, PlannerOptions, Start};
use oxcover::targets::{Areas, Targets, keep_out_violations, resume_start, room_labels};
use oxcover_grid::{DiscRobot, Grid, OccupancyGrid, Point};
use rayon::prelude::*;

use super::{Setting, short};

/// Largest room (m²) taken as the zone, when there is one.
const ZONE_MAX_M2: f64 = 40.0;
/// Side of a keep-out square (m).
const KEEP_OUT_M: f64 = 0.8;
/// Most the done part and the rest may cost over the whole plan.
const RESUME_LIMIT: f64 = 1.05;

/// One row: the case, its required area, its figures.
struct Row {
    case: &'static str,
    required_m2: f64,
    coverage: f64,
    collisions: usize,
    violations: usize,
    est_time_s: f64,
    efficiency: f64,
}

/// A room: its label, its area (m²), the bounding box and centroid of its
/// cells' centres (metres).
struct Room {
    label: u32,
    area: f64,
    lo: Point,
    hi: Point,
    centre: Point,
}

/// The rooms of `labels`, each with its cells in `coverable` only (a room
/// the robot cannot reach from its start has none and is left out).
fn rooms_of(map: &OccupancyGrid, labels: &Grid<u32>, coverable: &Grid<bool>) -> Vec<Room> {
    let n = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let frame = map.frame();
    let res = map.resolution();
    let mut rooms: Vec<Room> = (1..=n as u32)
        .map(|label| Room {
            label,
            area: 0.0,
            lo: Point::new(f64::INFINITY, f64::INFINITY),
            hi: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            centre: Point::origin(),
        })
        .collect();
    let mut sums = vec![(0.0, 0.0, 0usize); n];
    for c in labels.cells() {
        let l = labels[c] as usize;
        if l == 0 || !coverable[c] {
            continue;
        }
        let p = frame.cell_center(c);
        let r = &mut rooms[l - 1];
        r.lo = Point::new(r.lo.x.min(p.x), r.lo.y.min(p.y));
        r.hi = Point::new(r.hi.x.max(p.x), r.hi.y.max(p.y));
        sums[l - 1].0 += p.x;
        sums[l - 1].1 += p.y;
        sums[l - 1].2 += 1;
    }
    for (r, s) in rooms.iter_mut().zip(&sums) {
        r.area = s.2 as f64 * res * res;
        r.centre = Point::new(s.0 / s.2.max(1) as f64, s.1 / s.2.max(1) as f64);
    }
    rooms.retain(|r| r.area > 0.0);
    rooms
}

fn rect(lo: Point, hi: Point) -> Polygon<f64> {
    Polygon::new(
        LineString::from(vec![
            (lo.x, lo.y),
            (hi.x, lo.y),
            (hi.x, hi.y),
            (lo.x, hi.y),
            (lo.x, lo.y),
        ]),
        Vec::new(),
    )
}

fn request(map: &OccupancyGrid, radius: f64, targets: Targets) -> anyhow::Result<PlanRequest> {
    Ok(
        PlanRequest::with_planner(planner("lanes", &PlannerOptions::new())?, map.resolution())
            .robot(DiscRobot::new(radius, radius)?)
            .start(Start::LargestRegion)
            .targets(targets),
    )
}

fn row(case: &'static str, out: &PlanOutcome, map: &OccupancyGrid, keep: Option<&Areas>) -> Row {
    let m = &out.evaluation.metrics;
    let res = map.resolution();
    Row {
        case,
        required_m2: m.coverable_cells as f64 * res * res,
        coverage: m.coverage,
        collisions: m.collisions,
        violations: keep.map_or(0, |k| keep_out_violations(map, k, &out.points)),
        est_time_s: m.est_time_s,
        efficiency: m.time_efficiency.unwrap_or(0.0),
    }
}

/// One map's rows, and the resume's cost over the whole plan.
type MapRows = (Vec<Row>, f64);

/// The rows of one map, and the resume's cost over the whole plan.
fn map_rows(map: &OccupancyGrid, radius: f64) -> anyhow::Result<MapRows> {
    let whole = plan(map, &request(map, radius, Targets::default())?)?;
    let mut rows = vec![row("whole map", &whole, map, None)];
    let reach = CoverageProblem::new(map, DiscRobot::new(radius, radius)?, Start::LargestRegion)?;
    let mut rooms = rooms_of(map, &room_labels(map)?, &reach.cells().coverable);
    rooms.sort_by(|a, b| b.area.total_cmp(&a.area).then(a.label.cmp(&b.label)));
    // The zone: a room's bounding box.
    let zone_room = rooms
        .iter()
        .find(|r| r.area <= ZONE_MAX_M2)
        .or_else(|| rooms.last());
    if let Some(z) = zone_room {
        let t = Targets {
            zones: Some(Areas {
                polygons: vec![rect(z.lo, z.hi)],
                lines: Vec::new(),
            }),
            ..Targets::default()
        };
        let out = plan(map, &request(map, radius, t)?)?;
        rows.push(row("zone (a room's box)", &out, map, None));
    }
    if rooms.len() >= 2 {
        let t = Targets {
            rooms_only: Some(vec![rooms[0].label, rooms[1].label]),
            ..Targets::default()
        };
        let out = plan(map, &request(map, radius, t)?)?;
        rows.push(row("two largest rooms", &out, map, None));
    }
    // Resume from half-way.
    let half = whole.points.len().div_ceil(2);
    let done = whole.points[..half].to_vec();
    let (at, _) = resume_start(map, radius, &done)?;
    let t = Targets {
        done: Some(done.clone()),
        ..Targets::default()
    };
    let rest = plan(map, &request(map, radius, t)?.start(Start::At(at)))?;
    let time = whole.evaluation.metrics.est_time_s;
    let done_time = oxcover::planners::TimeModel::default().polyline(&done);
    let resume_ratio = (done_time + rest.evaluation.metrics.est_time_s) / time;
    rows.push(row("resume from half-way (the rest)", &rest, map, None));
    // Three keep-out squares.
    let h = KEEP_OUT_M / 2.0;
    let keep = Areas {
        polygons: rooms
            .iter()
            .take(3)
            .map(|r| {
                rect(
                    Point::new(r.centre.x - h, r.centre.y - h),
                    Point::new(r.centre.x + h, r.centre.y + h),
                )
            })
            .collect(),
        lines: Vec::new(),
    };
    let t = Targets {
        keep_out: Some(keep.clone()),
        ..Targets::default()
    };
    let out = plan(map, &request(map, radius, t)?)?;
    rows.push(row("three keep-out squares", &out, map, Some(&keep)));
    Ok((rows, resume_ratio))
}

/// The section: a table per setting, and whether the targets hold.
pub(super) fn section(settings: &[Setting], failures: &mut Vec<String>) -> String {
    let mut md = String::from(
        "## Coverage targets\n\n`lanes`, rooms on, with the targets users set most:\n\n- the whole map;\n- one zone: the bounding box of a room of `oxcover segment` (the largest of at most 40 m² coverable from the start, else the smallest);\n- the two largest rooms (`--rooms-only`);\n- a resume from the whole plan's half-way waypoint (`--done`, from where it stopped): `vs whole` is the done part's time plus the rest's over the whole plan's;\n- three keep-out squares of 0.8 m at the centres of the three largest rooms: `keep-out` counts path samples in the cells they block, found independently of the plan.\n\nTargets: coverage 1, no collision or keep-out violation, resume at most 5 % over the whole plan, zones and rooms at most the whole map's time (a map of one room is its own zone)\n\n",
    );
    for s in settings {
        if s.maps.is_empty() {
            continue;
        }
        let results: Vec<(String, anyhow::Result<MapRows>)> = s
            .maps
            .par_iter()
            .map(|(name, map)| (name.clone(), map_rows(map, s.radius)))
            .collect();
        let _ = write!(
            md,
            "### {} (robot = tool radius {} m)\n\n| map | case | required m² | coverage | coll | keep-out | est. time s | time eff. | vs whole |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n",
            s.name, s.radius
        );
        let mut ratios = Vec::new();
        let mut over: Vec<String> = Vec::new();
        for (name, result) in results {
            let (rows, ratio) = match result {
                Ok(r) => r,
                Err(e) => {
                    failures.push(format!("targets on {name}: {e}"));
                    continue;
                }
            };
            ratios.push(ratio);
            let whole = rows[0].est_time_s;
            for r in &rows {
                let vs = if r.case.starts_with("resume") {
                    ratio
                } else {
                    r.est_time_s / whole
                };
                let _ = writeln!(
                    md,
                    "| {} | {} | {:.1} | {:.4} | {} | {} | {:.0} | {:.3} | {:.3} |",
                    short(&name),
                    r.case,
                    r.required_m2,
                    r.coverage,
                    r.collisions,
                    r.violations,
                    r.est_time_s,
                    r.efficiency,
                    vs
                );
                if r.coverage < 1.0 || r.collisions > 0 || r.violations > 0 {
                    failures.push(format!(
                        "targets on {name}, {}: coverage {}, collisions {}, keep-out violations {}",
                        r.case, r.coverage, r.collisions, r.violations
                    ));
                }
                if (r.case.starts_with("zone") || r.case.starts_with("two")) && r.est_time_s > whole
                {
                    over.push(format!(
                        "- {}, {}: {:.3} of the whole map's time ({:.0} % of its area)",
                        short(&name),
                        r.case,
                        r.est_time_s / whole,
                        100.0 * r.required_m2 / rows[0].required_m2.max(f64::MIN_POSITIVE)
                    ));
                }
            }
        }
        let worst = ratios.iter().copied().fold(0.0, f64::max);
        let mean = ratios.iter().sum::<f64>() / ratios.len().max(1) as f64;
        let _ = writeln!(
            md,
            "\nResume: done + rest over the whole plan, mean {mean:.3}, worst {worst:.3} (target at most {RESUME_LIMIT:.2}: {}).\n",
            if worst <= RESUME_LIMIT {
                "met"
            } else {
                "NOT met"
            }
        );
        md += "Zones and chosen rooms taking longer than the whole map (target: none):\n\n";
        if over.is_empty() {
            md += "- none\n";
        }
        for o in &over {
            md += o;
            md += "\n";
        }
        md += "\n";
    }
    md
}
