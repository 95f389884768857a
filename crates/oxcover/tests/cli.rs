//! The command line end to end on bundled maps: plan writes what it says, eval
//! agrees with plan, the report and metrics carry the contract's keys.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{bin, root, run, scratch};

fn fixture(rel: &str) -> String {
    root(&format!("fixtures/maps/{rel}"))
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).expect("valid JSON")
}

const METRIC_KEYS: [&str; 10] = [
    "coverage",
    "collisions",
    "length_m",
    "turns",
    "rotation_rad",
    "redundancy",
    "steps",
    "est_time_s",
    "bound_time_s",
    "time_efficiency",
];

fn plan_and_eval(map: &str, extra: &[&str], dir: &Path) -> (serde_json::Value, serde_json::Value) {
    let csv = dir.join("p.csv").display().to_string();
    let report = dir.join("r.json").display().to_string();
    let mut args = vec![
        "plan",
        map,
        "--planner",
        "dtc",
        "--out",
        &csv,
        "--report",
        &report,
    ];
    args.extend_from_slice(extra);
    run(&args);
    let mut eargs = vec!["eval", map, &csv];
    // `eval` takes the robot's options, not the planning ones.
    let mut i = 0;
    while i < extra.len() {
        if matches!(extra[i], "--boundary-pass" | "--rooms") {
            i += 2;
        } else {
            eargs.push(extra[i]);
            i += 1;
        }
    }
    let (eval, _) = run(&eargs);
    (
        json(&std::fs::read_to_string(&report).expect("read report")),
        json(&eval),
    )
}

#[test]
fn plan_then_eval_agree_on_a_ros_map_with_a_real_robot() {
    let dir = scratch("ros");
    let map = fixture("turtlebot_simulator/simple_rooms.yaml");
    let extra = ["--robot-radius", "0.15", "--tool-radius", "0.15"];
    let (report, eval) = plan_and_eval(&map, &extra, &dir);
    for k in METRIC_KEYS {
        assert!(eval.get(k).is_some(), "eval lacks {k}");
        assert_eq!(report[k], eval[k], "{k}: plan report and eval differ");
    }
    assert_eq!(eval["collisions"], 0);
    assert_eq!(eval["coverage"], 1.0);
    assert_eq!(report["planner"], "dtc");
    assert!(report["plan_ms"].as_f64().unwrap() > 0.0);
    assert_eq!(report["parameters"]["robot_radius"], 0.15);
    assert!(report["coverage_without_boundary_pass"].as_f64().unwrap() < 1.0);

    assert!(report["room_units"].as_u64().unwrap() > 1);
    let share = report["boundary"]["length_share"].as_f64().unwrap();
    assert!(share > 0.0 && share < 1.0, "{share}");

    // Planning the whole map at once, the boundary pass only appends: the
    // plan without it is the plan with it, cut before the pass.
    let whole = [&extra[..], &["--rooms", "off"]].concat();
    let (with_pass, _) = plan_and_eval(&map, &whole, &dir);
    assert_eq!(with_pass["room_units"], serde_json::Value::Null);
    let (raw, raw_eval) = plan_and_eval(
        &map,
        &[&whole[..], &["--boundary-pass", "off"]].concat(),
        &dir,
    );
    assert_eq!(raw["boundary"], serde_json::Value::Null);
    assert_eq!(raw["coverage"], raw_eval["coverage"]);
    assert_eq!(raw["coverage"], with_pass["coverage_without_boundary_pass"]);
}

#[test]
fn default_radii_cover_every_cell_of_movingai_and_pgm_maps() {
    let dir = scratch("unit");
    for map in [
        "movingai/room-32-32-4.map",
        "navigation_tutorials/lse_arena.yaml",
        "pythonrobotics/test.png",
    ] {
        let (_, eval) = plan_and_eval(&fixture(map), &[], &dir);
        assert_eq!(eval["coverage"], 1.0, "{map}");
        assert_eq!(eval["collisions"], 0, "{map}");
    }
}

#[test]
fn plans_are_deterministic() {
    let dir = scratch("det");
    let map = fixture("nav2/turtlebot3_world.yaml");
    let mut files = Vec::new();
    for i in 0..2 {
        let csv = dir.join(format!("p{i}.csv")).display().to_string();
        run(&[
            "plan",
            &map,
            "--planner",
            "dtc",
            "--robot-radius",
            "0.1",
            "--tool-radius",
            "0.12",
            "--out",
            &csv,
        ]);
        files.push(std::fs::read(&csv).unwrap());
    }
    assert_eq!(files[0], files[1]);
}

#[test]
fn start_is_honoured_and_pictures_are_written() {
    let dir = scratch("pics");
    let map = fixture("navigation_tutorials/lse_arena.yaml");
    let csv = dir.join("p.csv").display().to_string();
    let svg = dir.join("p.svg").display().to_string();
    let png = dir.join("p.png").display().to_string();
    run(&[
        "plan",
        &map,
        "--planner",
        "dtc",
        "--start",
        "2.01,1.52",
        "--out",
        &csv,
        "--svg",
        &svg,
        "--png",
        &png,
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("x,y\n2.01,1.52\n"), "{}", &text[..40]);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let out = dir.join("r.png").display().to_string();
    run(&["render", &map, &csv, "--out", &out]);
    assert!(std::fs::read(&out).unwrap().starts_with(b"\x89PNG"));
    let out = dir.join("m.svg").display().to_string();
    run(&["render", &map, "--out", &out]);
    assert!(std::fs::read_to_string(&out).unwrap().contains("lse_arena"));
}

#[test]
fn segment_finds_the_rooms_of_the_demo_flat() {
    let dir = scratch("segment");
    let (json_f, png) = (dir.join("rooms.json"), dir.join("rooms.png"));
    let (out, _) = run(&[
        "segment",
        &fixture("turtlebot_simulator/simple_rooms.yaml"),
        "--method",
        "morphological",
        "--out",
        json_f.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
    ]);
    assert!(out.contains("7 rooms"), "{out}");
    let r = json(&std::fs::read_to_string(&json_f).unwrap());
    assert_eq!(r["seeded"], 7);
    assert_eq!(r["doors"].as_array().map(Vec::len), Some(6));
    // Six rooms of about 28 m² round a hall; every door joins the hall.
    let rooms = r["rooms"].as_array().unwrap();
    let hall = rooms
        .iter()
        .max_by(|a, b| {
            a["area_m2"]
                .as_f64()
                .unwrap()
                .total_cmp(&b["area_m2"].as_f64().unwrap())
        })
        .unwrap()["label"]
        .as_u64()
        .unwrap();
    for d in r["doors"].as_array().unwrap() {
        let pair = [
            d["rooms"][0].as_u64().unwrap(),
            d["rooms"][1].as_u64().unwrap(),
        ];
        assert!(pair.contains(&hall), "{d}");
    }
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);

    // The default method, the rooms `plan` goes by: split at the doors
    // (1.5 m openings here); `--out` may name a picture.
    let picture = dir.join("doors.png");
    let (out, _) = run(&[
        "segment",
        &fixture("turtlebot_simulator/simple_rooms.yaml"),
        "--out",
        picture.to_str().unwrap(),
    ]);
    assert!(out.contains("7 rooms") && out.contains("6 doors"), "{out}");
    assert!(std::fs::metadata(&picture).unwrap().len() > 1000);
}

#[test]
fn info_planners_and_demo() {
    let (info, _) = run(&["info", &fixture("nobleo/basement.yaml")]);
    assert!(
        info.contains("600x600") && info.contains("unknown"),
        "{info}"
    );
    let (planners, _) = run(&["planners"]);
    assert!(planners.contains("dtc"));
    // No command: the demo, written into ./oxcover-demo/.
    let cwd = scratch("demo");
    let out = Command::new(bin())
        .current_dir(&cwd)
        .output()
        .expect("run oxcover");
    assert!(out.status.success(), "{out:?}");
    let dir = cwd.join("oxcover-demo");
    for ext in ["csv", "svg", "png", "json"] {
        assert!(
            dir.join(format!("simple_rooms_lanes.{ext}")).exists(),
            "{ext}"
        );
    }
    let report = json(&std::fs::read_to_string(dir.join("simple_rooms_lanes.json")).unwrap());
    assert_eq!(report["coverage"], 1.0);
    assert_eq!(report["collisions"], 0);
}

/// The rows of `oxcover info` as (key, value).
fn info_rows(args: &[&str]) -> (Vec<(String, String)>, String) {
    let (out, err) = run(args);
    let rows = out
        .lines()
        .skip(1)
        .filter_map(|l| {
            let l = l.trim();
            let at = l.rfind("  ")?;
            Some((l[..at].trim().to_string(), l[at..].trim().to_string()))
        })
        .collect();
    (rows, err)
}

fn row<'a>(rows: &'a [(String, String)], key: &str) -> &'a str {
    &rows.iter().find(|(k, _)| k == key).expect(key).1
}

#[test]
fn images_without_a_yaml_are_classified_as_the_reading_options_say() {
    // Black wall, light grey (230), near-white (251), white, mid grey (128),
    // a grey just below the ipa benchmark's cut (250): one row of six pixels.
    let dir = scratch("thresholds");
    let pgm = dir.join("plan.pgm");
    let mut bytes = b"P5\n6 1\n255\n".to_vec();
    bytes.extend_from_slice(&[0, 230, 251, 255, 128, 250]);
    std::fs::write(&pgm, bytes).unwrap();
    let pgm = pgm.display().to_string();
    let counts = |extra: &[&str]| {
        let mut args = vec!["info", pgm.as_str()];
        args.extend_from_slice(extra);
        let (rows, err) = info_rows(&args);
        assert!(err.is_empty(), "{err}");
        ["free", "occupied", "unknown"].map(|k| row(&rows, k).parse::<usize>().unwrap())
    };
    // The contract's defaults: p < 0.196 free (v > 205), p > 0.65 occupied.
    assert_eq!(counts(&[]), [4, 1, 1]);
    // The ipa benchmark's rule, grey above 250 free and the rest blocked.
    assert_eq!(
        counts(&["--free-thresh", "0.018", "--occupied-thresh", "0.018"]),
        [2, 4, 0]
    );
    // Only the free threshold: the rest between it and 0.65 is unknown.
    assert_eq!(counts(&["--free-thresh", "0.0196"]), [2, 1, 3]);
    // Negated: dark is free.
    assert_eq!(counts(&["--negate"]), [1, 4, 1]);
    // The same reading reaches the planner: by default the free run is
    // columns 1 to 3 (the mid grey at 4 is unknown, so column 5 is cut
    // off); read the ipa way, only the white pair at columns 2 and 3.
    let plan = |extra: &[&str]| {
        let report = dir.join("report.json");
        let mut args = vec!["plan", pgm.as_str(), "--planner", "dtc", "--report"];
        args.push(report.to_str().unwrap());
        args.extend_from_slice(extra);
        run(&args);
        json(&std::fs::read_to_string(&report).unwrap())
    };
    let contract = plan(&[]);
    assert_eq!(contract["coverable_cells"], 3);
    assert_eq!(contract["parameters"]["start"][0], 1.5);
    let ipa = plan(&["--free-thresh", "0.018", "--occupied-thresh", "0.018"]);
    assert_eq!(ipa["coverable_cells"], 2);
    assert_eq!(ipa["parameters"]["start"][0], 2.5);
    assert_eq!(ipa["coverage"], 1.0);
}

#[test]
fn a_resolution_a_yaml_does_not_use_is_a_note() {
    let yaml = fixture("turtlebot_simulator/simple_rooms.yaml");
    let (rows, err) = info_rows(&["info", &yaml, "--resolution", "2"]);
    assert_eq!(row(&rows, "resolution"), "0.05 m");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("note: --resolution 2 is for images read without a yaml;")
            && err.contains("at 0.05 m per cell"),
        "{err}"
    );
    // Without the option, nothing is said.
    let (_, err) = info_rows(&["info", &yaml]);
    assert!(err.is_empty(), "{err}");
    // A command that fails after the map is read says only its error: the
    // note waits for success.
    let out = Command::new(bin())
        .args([
            "plan",
            &yaml,
            "--planner",
            "dtc",
            "--resolution",
            "2",
            "--start",
            "0,0",
        ])
        .output()
        .expect("run oxcover");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("oxcover: error: start (0, 0) is not admissible"),
        "{err}"
    );
}

#[test]
fn a_fixed_sweep_angle_is_honoured_and_reported() {
    let dir = scratch("angle");
    let map = fixture("turtlebot_simulator/simple_rooms.yaml");
    let mut paths = Vec::new();
    for angle in ["0", "90"] {
        let csv = dir.join(format!("a{angle}.csv")).display().to_string();
        let report = dir.join(format!("a{angle}.json")).display().to_string();
        run(&[
            "plan",
            &map,
            "--planner",
            "boustrophedon",
            "--robot-radius",
            "0.15",
            "--tool-radius",
            "0.15",
            "--sweep-angle",
            angle,
            "--out",
            &csv,
            "--report",
            &report,
        ]);
        let r = json(&std::fs::read_to_string(&report).expect("read report"));
        assert_eq!(
            r["parameters"]["sweep_angle_deg"].as_f64(),
            angle.parse().ok()
        );
        assert_eq!(r["collisions"], 0);
        assert_eq!(r["coverage"], 1.0);
        paths.push(std::fs::read_to_string(&csv).expect("read path"));
    }
    assert_ne!(paths[0], paths[1], "0° and 90° lanes give the same path");
}

#[test]
fn simulate_executes_a_plan_and_scores_the_executed_path() {
    let dir = scratch("sim");
    let map = fixture("movingai/room-32-32-4.map");
    let csv = dir.join("ex.csv").display().to_string();
    let report = dir.join("ex.json").display().to_string();
    let png = dir.join("ex.png").display().to_string();
    run(&[
        "simulate",
        &map,
        "--planner",
        "spiral-stc",
        "--resolution",
        "0.5",
        "--out",
        &csv,
        "--report",
        &report,
        "--png",
        &png,
    ]);
    let text = std::fs::read_to_string(&csv).expect("read executed path");
    assert!(text.starts_with("x,y,theta,t,v,omega,energy\n"));
    let r = json(&std::fs::read_to_string(&report).expect("read report"));
    for k in METRIC_KEYS {
        assert!(r.get(k).is_some(), "report lacks {k}");
    }
    assert!(r["energy_j"].as_f64().unwrap() > 0.0);
    assert!(r["tracking_rms_m"].as_f64().unwrap() < 0.05);
    assert!(r["coverage"].as_f64().unwrap() > 0.9);
    // The executed path file is a contract path file: eval reads it.
    let (eval, _) = run(&["eval", &map, &csv, "--resolution", "0.5"]);
    assert_eq!(json(&eval)["coverage"], r["coverage"]);
    assert!(std::fs::metadata(&png).expect("png written").len() > 0);
    assert!(r["warning"].is_null(), "{}", r["warning"]);
}

/// A robot that cannot accelerate falls behind its reference; the run ends
/// at its time cap with little covered, and says so (it used to end with
/// exit 0 and no word).
#[test]
fn simulate_warns_when_the_time_cap_cuts_the_run_short() {
    let dir = scratch("sim-slow");
    let map = fixture("movingai/room-32-32-4.map");
    let spec = include_str!("../../../fixtures/robots/floor_cleaner.ron")
        .replace("max_wheel_accel: 1.0", "max_wheel_accel: 0.002");
    assert!(spec.contains("0.002"), "the spec's field changed form");
    let spec_file = dir.join("sluggish.ron");
    std::fs::write(&spec_file, spec).expect("write spec");
    let report = dir.join("slow.json").display().to_string();
    let out = Command::new(bin())
        .args([
            "simulate",
            &map,
            "--planner",
            "boustrophedon",
            "--resolution",
            "0.5",
        ])
        .arg("--robot-spec")
        .arg(&spec_file)
        .args(["--report", &report])
        .output()
        .expect("run");
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning: the run ended at its time cap"),
        "{err}"
    );
    let r = json(&std::fs::read_to_string(&report).expect("read report"));
    assert!(r["coverage"].as_f64().unwrap() < r["planned_coverage"].as_f64().unwrap());
    assert!(
        r["warning"]
            .as_str()
            .unwrap()
            .contains("short of the path's end")
    );
}

#[test]
fn explore_writes_path_graph_map_pictures_and_report() {
    let d = scratch("explore");
    let world = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/worlds/demir2018/fig15_stacked.ron")
        .display()
        .to_string();
    let f = |n: &str| d.join(n).display().to_string();
    let (out, _) = run(&[
        "explore",
        &world,
        "--out",
        &f("p.csv"),
        "--graph",
        &f("g.json"),
        "--map",
        &f("m.yaml"),
        "--svg",
        &f("f.svg"),
        "--png",
        &f("f.png"),
        "--report",
        &f("r.json"),
    ]);
    assert!(out.contains("6/6 found"), "{out}");
    let csv = std::fs::read_to_string(d.join("p.csv")).expect("path file");
    assert!(csv.starts_with("x,y,state\n0.5,9,0\n"), "{}", &csv[..40]);
    let report = json(&std::fs::read_to_string(d.join("r.json")).expect("report"));
    for key in METRIC_KEYS {
        assert!(report.get(key).is_some(), "{key}");
    }
    assert!(report["coverage"].as_f64().expect("coverage") >= 0.99);
    assert_eq!(report["collisions"], 0);
    assert_eq!(report["disc_collisions"], 0);
    assert_eq!(report["found"], report["true_critical_points"]);
    let graph = json(&std::fs::read_to_string(d.join("g.json")).expect("graph"));
    assert_eq!(graph["nodes"].as_array().expect("nodes").len(), 6);
    // The path file and the map it wrote are scored the same by `eval`
    // (extra CSV columns are allowed by the contract).
    let (eval, _) = run(&[
        "eval",
        &f("m.yaml"),
        &f("p.csv"),
        "--robot-radius",
        "0.2",
        "--tool-radius",
        "0.25",
    ]);
    let eval = json(&eval);
    assert_eq!(eval["coverage"], report["coverage"]);
    assert_eq!(eval["collisions"], 0);
    assert!(
        std::fs::read_to_string(d.join("f.svg"))
            .expect("svg")
            .contains("Reeb graph edge")
    );
    assert!(std::fs::metadata(d.join("f.png")).expect("png").len() > 1000);
}

/// A map whose origin has a yaw (map_server's pose of the lower-left pixel)
/// plans the same path as the unrotated map, turned about the origin:
/// same metrics, every waypoint rotated.
#[test]
fn a_yawed_origin_turns_the_plan_with_the_map() {
    let dir = scratch("yaw");
    let src = fixture("navigation_tutorials/lse_arena.yaml");
    let text = std::fs::read_to_string(&src).expect("yaml");
    let image = Path::new(&src).with_file_name("lse_arena.pgm");
    let plain = text.replace("lse_arena.pgm", image.to_str().expect("utf-8"));
    let turned = plain.replace(
        "origin: [0.000000, 0.000000, 0.000000]",
        "origin: [1.5, -2.0, 0.7]",
    );
    assert_ne!(plain, turned, "the fixture's origin line changed");
    let (a, b) = (dir.join("plain.yaml"), dir.join("turned.yaml"));
    std::fs::write(&a, plain).expect("write");
    std::fs::write(&b, turned).expect("write");
    let mut runs = Vec::new();
    for (map, csv) in [(&a, dir.join("a.csv")), (&b, dir.join("b.csv"))] {
        let (m, c) = (map.to_str().expect("utf-8"), csv.to_str().expect("utf-8"));
        let radii = ["--robot-radius", "0.1", "--tool-radius", "0.1"];
        run(&[
            &["plan", m, "--planner", "lanes", "--out", c][..],
            &radii[..],
        ]
        .concat());
        let (eval, _) = run(&[&["eval", m, c][..], &radii[..]].concat());
        let points = oxcover::path::read_csv(&csv).expect("path");
        runs.push((json(&eval), points));
    }
    let ((ea, pa), (eb, pb)) = (&runs[0], &runs[1]);
    for k in [
        "coverage",
        "collisions",
        "turns",
        "covered_cells",
        "coverable_cells",
    ] {
        assert_eq!(ea[k], eb[k], "{k}");
    }
    assert_eq!(eb["collisions"], 0);
    assert_eq!(pa.len(), pb.len());
    let (s, c) = 0.7f64.sin_cos();
    for (p, q) in pa.iter().zip(pb) {
        let r = (1.5 + c * p.x - s * p.y, -2.0 + s * p.x + c * p.y);
        assert!(
            (r.0 - q.x).abs() < 1e-9 && (r.1 - q.y).abs() < 1e-9,
            "{p:?} -> {q:?}"
        );
    }
}
