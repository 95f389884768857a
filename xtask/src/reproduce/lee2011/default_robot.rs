//! The `lee2011` runs with the default robot: the bundled floor cleaner
//! under the contract's speeds (0.52 rad/s, a third of the page's turn
//! rate), as the page's runs are made and as `oxcover simulate` makes them
//! without options.

use oxcover::closed_loop::{ClosedLoop, execute};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::TimeModel;
use oxcover_grid::{OccupancyGrid, Point};
use oxcover_robot::Limits;
use rayon::prelude::*;

use super::{Measured, World, closed_loop, mean_std, measure, robot, run_with, starts};

/// The room the default-robot runs use.
const DEFAULT_ROBOT_ROOM: &str = "living";

/// The planners the default-robot runs compare (the seed's comparison).
const DEFAULT_ROBOT_PLANNERS: [&str; 3] = ["smooth", "bsa", "spiral-stc"];

/// The default-robot runs of [`DEFAULT_ROBOT_ROOM`]: the bundled floor
/// cleaner under the default limits (the contract's 0.3 m/s and
/// 0.52 rad/s) with the planners scoring time at those speeds. First as
/// the page runs (the ten starts, no boundary pass, rooms off); then as
/// `oxcover simulate` runs without options (the contract's start, the
/// boundary pass and rooms on).
pub(super) struct DefaultRobot {
    page: Vec<Measured>,
    cli: Vec<Measured>,
    /// As `cli`, with rooms off.
    cli_rooms_off: Vec<Measured>,
}

pub(super) fn run(worlds: &[World], maps: &[OccupancyGrid]) -> anyhow::Result<DefaultRobot> {
    let e = worlds
        .iter()
        .position(|w| w.name == DEFAULT_ROBOT_ROOM)
        .ok_or_else(|| anyhow::anyhow!("no {DEFAULT_ROBOT_ROOM} world"))?;
    let map = &maps[e];
    let cfg = ClosedLoop {
        limits: Limits::default(),
        ..closed_loop()?
    };
    let jobs: Vec<(usize, Point, &'static str)> = starts(map, e)?
        .into_iter()
        .enumerate()
        .flat_map(|(s, p)| DEFAULT_ROBOT_PLANNERS.map(|planner| (s, p, planner)))
        .collect();
    let page = jobs
        .par_iter()
        .map(|&(s, p, planner)| {
            Ok(run_with(map, (e, s, p), planner, &cfg, TimeModel::default())?.0)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let cli = |rooms: bool| {
        DEFAULT_ROBOT_PLANNERS
            .par_iter()
            .map(|&planner| {
                let req = PlanRequest::new(planner, map.resolution())?
                    .robot(robot())
                    .rooms(rooms);
                let planned = plan(map, &req)?;
                let run = execute(map, robot(), &planned.points, &cfg)?;
                measure(map, (e, 0, planner), &run)
            })
            .collect::<anyhow::Result<Vec<_>>>()
    };
    Ok(DefaultRobot {
        page,
        cli: cli(true)?,
        cli_rooms_off: cli(false)?,
    })
}

/// The page's section on the default-robot runs.
pub(super) fn section(runs: &DefaultRobot) -> String {
    let time = |runs: &[Measured], planner: &str| {
        let v: Vec<f64> = runs
            .iter()
            .filter(|m| m.planner == planner)
            .map(|m| m.normalized_time)
            .collect();
        mean_std(&v).0
    };
    let fastest = |runs: &[Measured]| {
        let [smooth, bsa, spiral] = DEFAULT_ROBOT_PLANNERS.map(|p| time(runs, p));
        smooth < bsa && smooth < spiral
    };
    let collisions = |runs: &[Measured]| runs.iter().map(|m| m.collisions).sum::<usize>();
    let verdict = |runs: &[Measured]| {
        let [smooth, bsa, spiral] = DEFAULT_ROBOT_PLANNERS.map(|p| time(runs, p));
        let verdict = if fastest(runs) {
            "`smooth` is the fastest of the three"
        } else if smooth < bsa || smooth < spiral {
            "`smooth` is not faster than both BSA and Spiral-STC"
        } else {
            "`smooth` is faster than neither BSA nor Spiral-STC"
        };
        format!(
            "normalized time smooth / BSA / Spiral-STC {smooth:.1} / {bsa:.1} / {spiral:.1} s/m², {} collisions: {verdict}",
            collisions(runs)
        )
    };
    let claim = match (fastest(&runs.page), fastest(&runs.cli)) {
        (true, true) => "The seed's claim that the proposed method needs the least time holds with this robot too.".to_string(),
        (false, false) => "With this robot the seed's claim that the proposed method needs the least time does not hold.".to_string(),
        (page, _) => format!(
            "The seed's claim that the proposed method needs the least time holds under {} and not under {}: it depends on how the paths are planned (the boundary pass, rooms, the start), not on the method alone; which of those decides it was not measured.",
            if page { "the conditions of the runs above" } else { "the command line's defaults" },
            if page { "the command line's defaults" } else { "the conditions of the runs above" },
        ),
    };
    let collided = if collisions(&runs.cli) > 0 && collisions(&runs.cli_rooms_off) == 0 {
        " The collisions come with rooms on only: the whole path's tightening moves waypoints up to the edge of the plannable cells, where a millimetre of tracking error takes the disc into a cell it may not enter."
    } else {
        ""
    };
    format!(
        "\n## With the default robot\n\n\
         The runs above give the robot a turn rate of 1.5 rad/s (a third of what its wheels allow). `oxcover simulate` without options drives the same bundled floor cleaner under the default limits instead: the contract's 0.3 m/s and 0.52 rad/s, with the planners scoring their choices at those speeds. Measured by this command in the {DEFAULT_ROBOT_ROOM} room, robot 0.17 m, brush 0.16 m:\n\n\
         - as the runs above (the same ten starts, no boundary pass, rooms off): {}.\n\
         - as `oxcover simulate fixtures/maps/lee2011/{DEFAULT_ROBOT_ROOM}.yaml --planner NAME --robot-radius 0.17 --tool-radius 0.16` runs (the contract's start, the boundary pass and rooms on, one run each): {}.\n\
         - the same command with `--rooms off`: {}.\n\n\
         {claim}{collided}\n",
        verdict(&runs.page),
        verdict(&runs.cli),
        verdict(&runs.cli_rooms_off)
    )
}
