//! What each stage of `lanes` buys: every map of both settings planned by
//! `lanes` (rooms on) with one stage turned off at a time
//! ([`LaneStages`]), beside the plan with every stage on; and the page's
//! reference section on where each stage spends and saves time.

use std::fmt::Write as _;
use std::sync::Arc;

use oxcover::grid::{DiscRobot, OccupancyGrid};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::Start;
use oxcover::planners::lanes::{LaneStages, Lanes};
use rayon::prelude::*;

use super::{Outcome, Run, Setting, mean};

/// The switchable stages in the order `plan_lanes` runs them, a line
/// each: the [`LaneStages`] field, the table's name for it, what it does.
const STAGES: &str = "\
straighten_loops | edge loops: straightening | each wall's loop straightened within half a tool radius (¼ to 0.8 of a cell); off, a waypoint in every boundary cell
inset_lines | lane layout: lines inset | the outermost lines moved in to where their reach meets the loops'; off, spread over the whole lane mask
every_angle | angles: every 15° | every 15° tried besides the walls' directions; off, the two wall directions only
build_several | angles: built to the end | the model's best few angles built to the end and compared on the finished path; off, the model's best alone
rehatch | re-hatching | chain pieces one angle does not suit (a corridor's arm hatched across) hatched again along walls or their own axis
islands | small islands and splices | lanes run past specks and table legs, and an island's loop is driven from the lane passing nearest; off, every island cuts the lanes and its loop is a node
improve_order | order: 2-opt and entries | the nearest-neighbour order improved by 2-opt, then every node's entry chosen exactly; off, nearest neighbour alone
detours | detours | cells passed just out of reach covered by the cheapest bend of a nearby segment; off, left to the last pass and the boundary pass
tighten | tightening | waypoints removed, moved or slid where that saves time and uncovers nothing; off, the path as driven and detoured
";

/// A stage of [`STAGES`]: every stage on but the one named by `field`.
struct Stage {
    name: &'static str,
    does: &'static str,
    stages: LaneStages,
}

/// The rows of [`STAGES`].
fn stages() -> Vec<Stage> {
    STAGES
        .lines()
        .filter_map(|line| {
            let mut parts = line.split(" | ");
            let (field, name, does) = (parts.next()?, parts.next()?, parts.next()?);
            let mut stages = LaneStages::ALL;
            let switch = match field {
                "straighten_loops" => &mut stages.straighten_loops,
                "inset_lines" => &mut stages.inset_lines,
                "every_angle" => &mut stages.every_angle,
                "build_several" => &mut stages.build_several,
                "rehatch" => &mut stages.rehatch,
                "islands" => &mut stages.islands,
                "improve_order" => &mut stages.improve_order,
                "detours" => &mut stages.detours,
                "tighten" => &mut stages.tighten,
                _ => return None,
            };
            *switch = false;
            Some(Stage { name, does, stages })
        })
        .collect()
}

/// `lanes` with `stages` on `map` (rooms on, the page's start and robot).
fn run_stages(stages: LaneStages, map: &OccupancyGrid, radius: f64) -> Outcome {
    let planner = Arc::new(Lanes::new().with_stages(stages));
    let request = DiscRobot::new(radius, radius).map(|robot| {
        PlanRequest::with_planner(planner, map.resolution())
            .robot(robot)
            .start(Start::LargestRegion)
            .rooms(true)
    });
    match request.map_err(anyhow::Error::from).and_then(|r| {
        let out = plan(map, &r)?;
        Ok(Run::of(&out, map, &r.time))
    }) {
        Ok(run) => Outcome::Done(run),
        Err(e) => Outcome::Failed(e.to_string()),
    }
}

/// The stage table: per setting, `lanes`' mean estimated time with every
/// stage on (`all`: each map's run, rooms on, from the page's table) and
/// with each stage off; a run with a stage off that fails, collides or
/// leaves a cell uncovered goes to `failures`.
pub(super) fn section(
    settings: &[Setting],
    all: &[Vec<Option<Run>>],
    failures: &mut Vec<String>,
) -> String {
    let all_stages = stages();
    let jobs: Vec<(usize, usize, usize)> = (0..all_stages.len())
        .flat_map(|k| {
            settings
                .iter()
                .enumerate()
                .flat_map(move |(s, set)| (0..set.maps.len()).map(move |m| (k, s, m)))
        })
        .collect();
    let bar = crate::progress(jobs.len() as u64, "lanes stages");
    let results: Vec<Outcome> = jobs
        .par_iter()
        .map(|&(k, s, m)| {
            let o = run_stages(
                all_stages[k].stages,
                &settings[s].maps[m].1,
                settings[s].radius,
            );
            bar.inc(1);
            o
        })
        .collect();
    bar.finish_and_clear();
    // Mean estimated time of each setting with every stage on, over the
    // maps every variant planned.
    let mean_time = |runs: &[&Run]| mean(&runs.iter().map(|r| r.est_time_s).collect::<Vec<_>>());
    let mut md = String::from(STAGE_INTRO);
    md += "| stage | what it does |";
    for s in settings {
        let _ = write!(md, " {} |", s.name);
    }
    md += "\n|---|---|";
    for _ in settings {
        md += "---:|";
    }
    md += "\n| every stage on | the planner as `oxcover plan --planner lanes` runs it |";
    for (s, set) in settings.iter().enumerate() {
        let on: Vec<&Run> = all[s].iter().flatten().collect();
        let eff = mean(&on.iter().map(|r| r.efficiency).collect::<Vec<_>>());
        let _ = write!(
            md,
            " {:.0} s, time eff. {eff:.3} ({} maps) |",
            mean_time(&on),
            on.len()
        );
        let _ = set;
    }
    md += "\n";
    for (k, stage) in all_stages.iter().enumerate() {
        let _ = write!(md, "| {} | {} |", stage.name, stage.does);
        for (s, set) in settings.iter().enumerate() {
            let mut on = Vec::new();
            let mut off = Vec::new();
            for (m, base) in all[s].iter().enumerate() {
                let i = jobs
                    .iter()
                    .position(|&j| j == (k, s, m))
                    .unwrap_or_default();
                match (&results[i], base) {
                    (Outcome::Done(r), Some(base)) => {
                        if r.collisions > 0 || r.coverage < 1.0 {
                            failures.push(format!(
                                "lanes without {} on {}: coverage {:.4}, {} collisions",
                                stage.name, set.maps[m].0, r.coverage, r.collisions
                            ));
                        }
                        on.push(base);
                        off.push(r);
                    }
                    (Outcome::Failed(e), _) => failures.push(format!(
                        "lanes without {} on {}: {e}",
                        stage.name, set.maps[m].0
                    )),
                    _ => {}
                }
            }
            let (t_on, t_off) = (mean_time(&on), mean_time(&off));
            let eff = mean(&off.iter().map(|r| r.efficiency).collect::<Vec<_>>());
            let _ = write!(
                md,
                " {t_off:.0} s ({:+.1} %), time eff. {eff:.3} |",
                100.0 * (t_off / t_on - 1.0)
            );
        }
        md += "\n";
    }
    md += "\n";
    md += STAGE_NOTES;
    md
}

/// The stage table's introduction.
const STAGE_INTRO: &str = "## What each stage of `lanes` buys\n\n\
`lanes` (`crates/oxcover-planners/src/lanes/`, one file per stage; `docs/architecture.md`) is the default planner. \
Each row turns one of its stages off (`oxcover_planners::lanes::LaneStages`) and gives the mean estimated time of `lanes`, rooms on, over each setting's maps, its change against every stage on, and the mean time efficiency. \
A plan with a stage off is still complete and collision-free (this run checks it), so each change is what that stage saves.\n\n";

/// What costs time in a `lanes` path, stage by stage (reference; the
/// figures are in the tables of the same run).
const STAGE_NOTES: &str = "### Where the time goes, stage by stage\n\n\
**Turning, not driving, dominates.** At the contract's speeds a quarter turn costs as much time as 0.9 m of straight driving, and a U-turn between two lanes (π rad) as much as 1.8 m. \
With the ROS maps' 0.3 m lane spacing, the U-turns of lanes 5 m long cost about a third of the lanes' time: no boustrophedon comes near a time efficiency of 1.\n\n\
**Edge loops.** With robot = tool radius, the free cells beside a ragged wall are within reach of only a few boundary cells each, so a loop must follow the wall's raster closely. \
On a wall off the grid's axes it jogs at every step of the staircase: most of the `bends` in the ceiling section below. Straightening within a fraction of a cell, then tightening, takes out what coverage allows.\n\n\
**Lane layout and angles.** Lanes fill the C-space a tool radius in from the walls; the loops cover the rest. \
Fewer lanes mean fewer U-turns, so the angle with the fewest usually wins; the time model ranks the angles, and the best few are built to the end because detours and tightening change the ranking.\n\n\
**Re-hatching.** One angle rarely suits a whole region: a corridor's arm or a strip beside a room hatched across turns every few lanes. \
Re-hatching such pieces along their walls or their own long axis replaces many short lanes by a few long ones.\n\n\
**Small islands.** A speck costs far more than its area: its loop is a full turn (12 s) and it cuts the lanes beside it. \
Lanes run past the smallest islands and drive their loops as excursions, so a speck costs little more than its loop (the synthetic rooms below).\n\n\
**Order.** Loops and chains are ordered as a small generalised TSP with estimated seconds as costs, the turns at each junction included; transits are straight lines scaled by how far the walls make the way round.\n\n\
**Detours and tightening.** The straightened loops and the lanes' ends pass some cells just out of reach; the cheapest bend of a nearby segment covers each. \
Tightening then removes or moves every waypoint that coverage allows: this, not the first straightening, takes out most of a loop's turns. \
With rooms on the pipeline tightens the whole path once more at the end, so turning off `lanes`' own tightening changes little in the table.\n\n\
**Room by room.** The pipeline plans each room unit on its own and finishes it before the robot leaves, then tightens the whole path. \
Where units are long and narrow (rows of offices on one aisle) a room's both wall runs are driven and its doorway is passed twice, so rooms on costs a little on those maps (the lists under the tables).\n\n";

#[cfg(test)]
mod tests {
    use super::*;

    /// Every line of the table turns exactly one stage off, each another.
    #[test]
    fn every_row_turns_one_stage_off() {
        let rows = stages();
        assert_eq!(rows.len(), STAGES.lines().count());
        for (i, a) in rows.iter().enumerate() {
            assert_eq!(format!("{:?}", a.stages).matches("false").count(), 1);
            assert!(rows[i + 1..].iter().all(|b| b.stages != a.stages));
        }
    }
}
