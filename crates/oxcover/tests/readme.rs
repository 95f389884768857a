//! The README's library example, kept in step: the same lines run here, and
//! the test fails if the README no longer shows them.

#[test]
fn readme_library_example_runs_and_is_current() {
    use oxcover::{PlanRequest, parse_ascii, plan};
    let (map, _) = parse_ascii("......\n.##...\n......").unwrap();
    let outcome = plan(&map, &PlanRequest::new("dtc", map.resolution()).unwrap()).unwrap();
    assert_eq!(outcome.evaluation.metrics.coverage, 1.0);

    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md"))
        .expect("README");
    for line in [
        "use oxcover::{parse_ascii, plan, PlanRequest};",
        r#"let (map, _) = parse_ascii("......\n.##...\n......").unwrap();"#,
        r#"let outcome = plan(&map, &PlanRequest::new("dtc", map.resolution()).unwrap()).unwrap();"#,
        "assert_eq!(outcome.evaluation.metrics.coverage, 1.0);",
    ] {
        assert!(
            readme.contains(line),
            "README lost the example line `{line}`"
        );
    }
}

/// The README's ROS 2 picture is what its commands draw today: the plan
/// written as a bag, then drawn by `render` from the decoded bag.
#[test]
fn readme_bag_picture_is_what_its_commands_draw() {
    let root = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let m = "fixtures/maps/turtlebot_simulator/simple_rooms.yaml";
    let k = "fixtures/targets/simple_rooms_keep_out.geojson";
    for line in [
        "oxcover plan map_bag/ --planner lanes --bag plan.mcap",
        "ros2 bag play plan.mcap",
        "cargo run --release -- plan fixtures/bags/turtlebot3_world_map/ --planner lanes --bag plan.mcap",
        &format!("M={m}"),
        &format!("K={k}"),
        "cargo run --release -- plan $M --planner lanes $R --keep-out $K --bag rooms.mcap",
        "cargo run --release -- render rooms.mcap $R --keep-out $K --out docs/ros_bag.png",
    ] {
        assert!(readme.contains(line), "README lost `{line}`");
    }
    let dir = std::env::temp_dir().join(format!("oxcover-readme-bag-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let (bag, png) = (dir.join("rooms.mcap"), dir.join("ros_bag.png"));
    let robot = ["--robot-radius", "0.15", "--tool-radius", "0.15"];
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_oxcover"))
            .current_dir(&root)
            .args(args)
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let (bag_s, png_s) = (bag.display().to_string(), png.display().to_string());
    let mut plan = vec!["plan", m, "--planner", "lanes"];
    plan.extend(robot);
    plan.extend(["--keep-out", k, "--bag", &bag_s]);
    run(&plan);
    let mut render = vec!["render", &bag_s];
    render.extend(robot);
    render.extend(["--keep-out", k, "--out", &png_s]);
    run(&render);
    let want = std::fs::read(root.join("docs/ros_bag.png")).expect("docs/ros_bag.png");
    assert!(
        std::fs::read(&png).expect("png") == want,
        "docs/ros_bag.png is not what the README's commands draw: run them again"
    );
}

/// The README's four target pictures are what its target commands draw
/// today (each command's `--png NAME.png` is `docs/targets_NAME.png`).
#[test]
fn readme_target_pictures_are_what_their_commands_draw() {
    let root = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let m = "fixtures/maps/turtlebot_simulator/simple_rooms.yaml";
    let r = [
        "--planner",
        "lanes",
        "--robot-radius",
        "0.15",
        "--tool-radius",
        "0.15",
    ];
    for line in [
        format!("M={m}"),
        format!("R=\"{}\"", r.join(" ")),
        "cargo run --release -- plan $M $R --zones fixtures/targets/simple_rooms_zone.geojson --png zone.png".into(),
        "cargo run --release -- plan $M $R --keep-out fixtures/targets/simple_rooms_keep_out.geojson --png keep_out.png".into(),
        "cargo run --release -- plan $M $R --rooms-only 5,2 --room-order given --png rooms.png".into(),
        "cargo run --release -- plan $M $R --out full.csv".into(),
        "head -n 150 full.csv > done.csv".into(),
        "cargo run --release -- plan $M $R --done done.csv --png resume.png".into(),
    ] {
        assert!(readme.contains(&line), "README lost `{line}`");
    }
    let dir = std::env::temp_dir().join(format!("oxcover-readme-targets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let file = |name: &str| dir.join(name).display().to_string();
    let run = |extra: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_oxcover"))
            .current_dir(&root)
            .args(["plan", m])
            .args(r)
            .args(extra)
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let (full, done) = (file("full.csv"), file("done.csv"));
    run(&["--out", &full]);
    let text = std::fs::read_to_string(&full).expect("full.csv");
    let head: Vec<&str> = text.lines().take(150).collect();
    std::fs::write(&done, head.join("\n") + "\n").expect("done.csv");
    for (name, extra) in [
        (
            "zone",
            vec!["--zones", "fixtures/targets/simple_rooms_zone.geojson"],
        ),
        (
            "keep_out",
            vec![
                "--keep-out",
                "fixtures/targets/simple_rooms_keep_out.geojson",
            ],
        ),
        (
            "rooms",
            vec!["--rooms-only", "5,2", "--room-order", "given"],
        ),
        ("resume", vec!["--done", done.as_str()]),
    ] {
        let png = file(&format!("{name}.png"));
        let mut args = extra.clone();
        args.extend(["--png", png.as_str()]);
        run(&args);
        let want = std::fs::read(root.join(format!("docs/targets_{name}.png"))).expect("picture");
        assert!(
            std::fs::read(&png).expect("png") == want,
            "docs/targets_{name}.png is not what the README's command draws: run it again"
        );
    }
}
