//! Each map's lane-and-loop ceiling ([`crate::lane_ceiling`]) beside the
//! best planner's time efficiency, and where that plan's time beyond the
//! bound goes.

use std::fmt::Write as _;

use super::runs::TimeSplit;
use super::{Setting, mean};
use crate::lane_ceiling::Ceiling;

/// A setting's name, its best planner and, per map, the map's name, its
/// lane-and-loop ceiling and the best planner's time efficiency and time
/// split (rooms on).
pub(super) type SettingCeilings<'a> = (
    &'a str,
    &'a str,
    Vec<(String, Ceiling, Option<(f64, TimeSplit)>)>,
);

/// The page's section on each map's lane-and-loop ceiling
/// ([`crate::lane_ceiling`]) beside the best planner's time efficiency.
pub(super) fn ceiling_section(ceilings: &[SettingCeilings<'_>], settings: &[Setting]) -> String {
    let mut md = String::from(
        "## What each map leaves: the lane-and-loop ceiling\n\n\
         Per map, the time efficiency of a plan of straight lanes and wall loops that wastes nothing else, under the contract's time model (`xtask/src/lane_ceiling.rs`). \
         A model of the pattern, optimistic in all it leaves out (overlap, links, transits, the corners of non-convex outlines, raster walls, the ways round islands): not a proof that no path does better. Measured by this page's run. Columns:\n\n\
         - `ceiling`: the drive is the bound itself (no overlap, no link, no transit); one full turn (2π) for each boundary of the region, its outline and each hole; lanes the tool's width apart at the angle (whole degrees) with the fewest, passing every hole for free, a half turn (π) to enter each lane after the first.\n\
         - `lanes`: that angle's lanes (a lane: a run of a line across the region, holes filled in, at least a tool width long).\n\
         - `cut lanes`, `cut`: the same with every hole cutting the lines that cross it, at the angle with the fewest such lanes (real lanes stop at a building or a rack). No bound either: a plan whose parts lie at different angles can need fewer lanes than any one angle's.\n\
         - `share`: the best planner's time efficiency (rooms on) over the ceiling.\n\
         - `overlap s`, `turns s`, `bends s`: where that plan's estimated time beyond the bound goes (below each table).\n\n",
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
            "\nMean ceiling {ceiling_mean:.3}; the target for the mean, {target:.2}, is {:.0} % of it, and {below} of {} maps have a ceiling below the target; {planner} reaches {:.3}, {:.0} % of the mean ceiling; {beaten}.",
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
pub(super) fn split_summary(planner: &str, splits: &[TimeSplit]) -> String {
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
        "Where the time of {planner} beyond the bound goes, rooms on, summed over the maps: overlap {:.0} % (driving beyond the bound: overlap, links, transits), turns {:.0} % (heading changes above 30°, the contract's turns), bends {:.0} % (30° or less: curved and ragged walls).\n\nThe mean time efficiency were the bends free: {:.3}; the overlap free: {:.3}; both: {:.3} (what is left is the turns alone).",
        share(sum(&|t| t.overlap)),
        share(sum(&|t| t.turns)),
        share(sum(&|t| t.bends)),
        without(&|t| t.bends),
        without(&|t| t.overlap),
        without(&|t| t.bends + t.overlap),
    )
}
