//! What a target costs against the whole map's plan, on bundled maps:
//!
//! - a robot stopped half-way through a plan and resumed (`--done`) drives
//!   at most 5 % longer in all (the done part plus the rest) than the
//!   uninterrupted plan, for several complete planners;
//! - rooms covering most of the map (the two largest, every room but the
//!   smallest) cost no more than the whole map.

use oxcover::grid::{DiscRobot, OccupancyGrid};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::{Start, TimeModel};
use oxcover::targets::{Targets, resume_start, room_labels};
use oxcover::{ReadOptions, read_map};

fn map(rel: &str) -> OccupancyGrid {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/maps")
        .join(rel);
    read_map(&path, &ReadOptions::default()).expect("a bundled map")
}

fn request(name: &str, map: &OccupancyGrid, radius: f64) -> PlanRequest {
    PlanRequest::new(name, map.resolution())
        .expect("a registered planner")
        .robot(DiscRobot::new(radius, radius).expect("a robot"))
}

#[test]
fn resuming_from_half_way_costs_at_most_five_percent_more() {
    for (rel, radius) in [
        ("turtlebot_simulator/simple_rooms.yaml", 0.15),
        ("nav2/turtlebot3_world.yaml", 0.12),
        ("navigation_tutorials/lse_arena.yaml", 0.15),
    ] {
        let map = map(rel);
        for name in ["lanes", "boustrophedon", "stc"] {
            let whole = plan(&map, &request(name, &map, radius)).expect("the whole plan");
            let done = whole.points[..whole.points.len().div_ceil(2)].to_vec();
            let (at, _) = resume_start(&map, radius, &done).expect("a resume start");
            let req = request(name, &map, radius)
                .targets(Targets {
                    done: Some(done.clone()),
                    ..Targets::default()
                })
                .start(Start::At(at));
            let rest = plan(&map, &req).expect("the rest");
            let m = &rest.evaluation.metrics;
            assert_eq!(m.covered_cells, m.coverable_cells, "{rel} {name}");
            assert_eq!(m.collisions, 0, "{rel} {name}");
            let ratio = (TimeModel::default().polyline(&done) + m.est_time_s)
                / whole.evaluation.metrics.est_time_s;
            assert!(
                ratio <= 1.05,
                "{rel} {name}: done + rest = {ratio:.3} of the whole plan"
            );
        }
    }
}

#[test]
fn rooms_covering_most_of_the_map_cost_no_more_than_it() {
    for (rel, radius) in [
        ("turtlebot_simulator/simple_rooms.yaml", 0.15),
        ("nobleo/basement.yaml", 0.15),
        ("turtlebot_simulator/hospital_section.yaml", 0.15),
        ("navigation_tutorials/lse_arena.yaml", 0.15),
        ("f1tenth/levinelobby.yaml", 0.15),
    ] {
        let map = map(rel);
        let labels = room_labels(&map).expect("rooms");
        let mut sizes = std::collections::BTreeMap::<u32, usize>::new();
        for &l in labels.as_slice() {
            if l > 0 {
                *sizes.entry(l).or_default() += 1;
            }
        }
        let mut by_size: Vec<(usize, u32)> = sizes.iter().map(|(&l, &n)| (n, l)).collect();
        by_size.sort_by(|a, b| b.cmp(a));
        let whole = plan(&map, &request("lanes", &map, radius)).expect("the whole plan");
        let total: usize = sizes.values().sum();
        // The two largest rooms, and every room but the smallest.
        for k in [2, by_size.len().saturating_sub(1)] {
            let chosen: Vec<u32> = by_size.iter().take(k).map(|&(_, l)| l).collect();
            let share: usize = by_size.iter().take(k).map(|&(n, _)| n).sum();
            if chosen.len() < 2 || 2 * share <= total {
                continue;
            }
            let req = request("lanes", &map, radius).targets(Targets {
                rooms_only: Some(chosen),
                ..Targets::default()
            });
            let rooms = plan(&map, &req).expect("the rooms");
            let m = &rooms.evaluation.metrics;
            assert_eq!(m.covered_cells, m.coverable_cells, "{rel}");
            assert!(
                m.est_time_s <= whole.evaluation.metrics.est_time_s,
                "{rel}, {k} largest rooms: {:.0} s, the whole map {:.0} s",
                m.est_time_s,
                whole.evaluation.metrics.est_time_s
            );
        }
    }
}
