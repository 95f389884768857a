//! Coverage targets and clearance through the command line on bundled
//! maps: the README's target commands run; `eval` with the same options
//! scores a plan as `plan` did; a resume finishes what was left; the
//! clearance is kept and what it costs reported; `simulate` plans with the
//! robot's tracking margin and then collides nowhere, where without it the
//! executed run grazes walls.

use std::path::PathBuf;

mod common;

use common::{root, run, scratch};

/// The value of a row of the printed table.
fn row(table: &str, key: &str) -> f64 {
    table
        .lines()
        .find_map(|l| {
            let l = l.trim();
            l.strip_prefix(key)
                .filter(|rest| rest.starts_with(' '))
                .map(|rest| rest.split_whitespace().next().unwrap_or("").parse::<f64>())
        })
        .unwrap_or_else(|| panic!("no row {key} in {table}"))
        .expect("a number")
}

const ROBOT: [&str; 4] = ["--robot-radius", "0.15", "--tool-radius", "0.15"];

#[test]
fn every_target_plans_complete_and_eval_agrees() {
    let map = root("fixtures/maps/turtlebot_simulator/simple_rooms.yaml");
    let (zone, keep) = (
        root("fixtures/targets/simple_rooms_zone.geojson"),
        root("fixtures/targets/simple_rooms_keep_out.geojson"),
    );
    let d = scratch("all");
    let csv = d.join("p.csv").display().to_string();
    let (whole, _) = run(&[&["plan", &map, "--planner", "lanes"][..], &ROBOT].concat());
    let whole_time = row(&whole, "est_time_s");
    let cases: Vec<Vec<&str>> = vec![
        vec!["--zones", &zone],
        vec!["--keep-out", &keep],
        vec!["--rooms-only", "5,2", "--room-order", "given"],
        vec!["--spot", "16,3.3,1.0"],
        vec!["--zones", &zone, "--keep-out", &keep],
    ];
    for extra in cases {
        let args = [
            &["plan", &map, "--planner", "lanes", "--out", &csv][..],
            &ROBOT,
            &extra,
        ]
        .concat();
        let (out, _) = run(&args);
        assert_eq!(row(&out, "coverage"), 1.0, "{extra:?}");
        assert_eq!(row(&out, "collisions"), 0.0, "{extra:?}");
        assert!(
            row(&out, "est_time_s") < whole_time,
            "{extra:?}: not less than the whole map"
        );
        let (ev, _) = run(&[&["eval", &map, &csv][..], &ROBOT, &extra].concat());
        let ev: serde_json::Value = serde_json::from_str(&ev).unwrap();
        assert_eq!(ev["coverage"], 1.0, "{extra:?}");
        assert_eq!(ev["collisions"], 0, "{extra:?}");
        assert_eq!(
            ev["coverable_cells"].as_f64(),
            Some(row(&out, "required cells")),
            "{extra:?}"
        );
    }
}

#[test]
fn a_resumed_plan_finishes_the_rest() {
    let map = root("fixtures/maps/turtlebot_simulator/simple_rooms.yaml");
    let d = scratch("resume");
    let (full, done, rest) = (d.join("full.csv"), d.join("done.csv"), d.join("rest.csv"));
    let s = |p: &PathBuf| p.display().to_string();
    let (whole, _) = run(&[
        &["plan", &map, "--planner", "lanes", "--out", &s(&full)][..],
        &ROBOT,
    ]
    .concat());
    let text = std::fs::read_to_string(&full).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    std::fs::write(&done, lines[..lines.len() / 2].join("\n") + "\n").unwrap();
    let (out, _) = run(&[
        &[
            "plan",
            &map,
            "--planner",
            "lanes",
            "--done",
            &s(&done),
            "--out",
            &s(&rest),
        ][..],
        &ROBOT,
    ]
    .concat());
    assert_eq!(row(&out, "coverage"), 1.0);
    assert!(row(&out, "done cells") > 0.0);
    // Resumed from the done path's last point.
    let last = lines[lines.len() / 2 - 1];
    let first_rest = std::fs::read_to_string(&rest).unwrap();
    assert_eq!(first_rest.lines().nth(1), Some(last));
    // The rest takes less than the whole plan.
    assert!(row(&out, "est_time_s") < row(&whole, "est_time_s"));
}

#[test]
fn the_clearance_is_kept_and_its_cost_reported() {
    let map = root("fixtures/maps/lee2011/living.yaml");
    let d = scratch("clear");
    let csv = d.join("p.csv").display().to_string();
    let (_, err) = run(&[
        &[
            "plan",
            &map,
            "--planner",
            "lanes",
            "--clearance",
            "0.1",
            "--out",
            &csv,
        ][..],
        &ROBOT,
    ]
    .concat());
    assert!(err.contains("the clearance of 0.1 m puts"), "{err}");
    // Scored with the clearance (admissible at R + M): no collision.
    let (ev, _) = run(&[&["eval", &map, &csv, "--clearance", "0.1"][..], &ROBOT].concat());
    let ev: serde_json::Value = serde_json::from_str(&ev).unwrap();
    assert_eq!(ev["collisions"], 0);
    assert_eq!(ev["coverage"], 1.0);
}

#[test]
fn simulate_keeps_the_tracking_margin_and_collides_nowhere() {
    let map = root("fixtures/maps/nav2/turtlebot3_world.yaml");
    let robot = ["--robot-radius", "0.12", "--tool-radius", "0.12"];
    let (with, _) = run(&[&["simulate", &map, "--planner", "lanes"][..], &robot].concat());
    assert_eq!(row(&with, "collisions"), 0.0);
    // Without the margin the executed run grazes the walls.
    let (without, _) = run(&[
        &["simulate", &map, "--planner", "lanes", "--clearance", "0"][..],
        &robot,
    ]
    .concat());
    assert!(row(&without, "collisions") > 0.0);
}

#[test]
fn a_zone_partly_off_the_map_is_clipped_with_a_note() {
    let map = root("fixtures/maps/turtlebot_simulator/simple_rooms.yaml");
    let d = scratch("clip");
    let zone = d.join("zone.geojson");
    // Room 1's corner and beyond the map's left and top edges.
    std::fs::write(
        &zone,
        r#"{"type":"Polygon","coordinates":[[[-5,12],[3,12],[3,20],[-5,20],[-5,12]]]}"#,
    )
    .unwrap();
    let (out, err) = run(&[
        &[
            "plan",
            &map,
            "--planner",
            "boustrophedon",
            "--zones",
            &zone.display().to_string(),
        ][..],
        &ROBOT,
    ]
    .concat());
    assert!(
        err.contains("--zones: a zone reaches outside the map; it is clipped to the map"),
        "{err}"
    );
    assert_eq!(row(&out, "coverage"), 1.0);
}
