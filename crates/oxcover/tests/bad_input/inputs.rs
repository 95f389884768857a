//! The table of bad inputs: each exits 2 with one line naming the file,
//! field or value; and the help texts that explain names.

use std::process::Command;

use crate::{GOOD_YAML, bin, fixtures, png_header_only, real_png_path, scratch, write};

#[test]
fn bad_inputs_exit_2_with_one_line() {
    let d = scratch();
    let ok_pgm = write(
        &d,
        "ok.pgm",
        b"P5\n4 3\n255\n\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe",
    );
    let good_yaml = write(&d, "good.yaml", GOOD_YAML.as_bytes());
    let real_png = std::fs::read(fixtures().join("pythonrobotics/test.png")).unwrap();
    let truncated_png = write(&d, "truncated.png", &real_png[..real_png.len() / 2]);
    let lying_pgm = write(&d, "lying.pgm", b"P5\n100 100\n255\n\x00\x00\x00\x00");
    let huge_pgm = write(&d, "huge.pgm", b"P5\n100000 100000\n255\n\x00");
    let huge_png = write(&d, "huge.png", &png_header_only(100_000, 100_000));
    let no_res = write(
        &d,
        "nores.yaml",
        GOOD_YAML.replace("resolution: 0.05\n", "").as_bytes(),
    );
    let mut bomb = String::from("extra: &a [x, x, x, x, x, x, x, x, x]\n");
    for k in 1..10 {
        let prev = if k == 1 {
            "*a".to_string()
        } else {
            format!("*b{}", k - 1)
        };
        bomb += &format!("b{k}: &b{k} [{}]\n", vec![prev; 9].join(", "));
    }
    bomb += GOOD_YAML;
    let alias_bomb = write(&d, "bomb.yaml", bomb.as_bytes());
    let slow_spec = write(
        &d,
        "slow.ron",
        std::fs::read_to_string(fixtures().join("../robots/floor_cleaner.ron"))
            .expect("bundled robot")
            .replace("max_wheel_speed: 0.5", "max_wheel_speed: 1e-9")
            .as_bytes(),
    );
    let nan_yaw = write(
        &d,
        "nanyaw.yaml",
        GOOD_YAML
            .replace("0.0, 0.0, 0.0", "0.0, 0.0, .nan")
            .as_bytes(),
    );
    let huge_res = write(
        &d,
        "hugeres.yaml",
        GOOD_YAML
            .replace("resolution: 0.05", "resolution: 1e308")
            .as_bytes(),
    );
    let no_image = write(
        &d,
        "noimage.yaml",
        GOOD_YAML.replace("ok.pgm", "missing.pgm").as_bytes(),
    );
    let garbage_yaml = write(&d, "garbage.yaml", b"\x00\xff\x10 not yaml: [");
    let bad_ron = write(&d, "robot.ron", b"(drive: (");
    let empty_map = write(&d, "empty.map", b"");
    let ragged_map = write(
        &d,
        "ragged.map",
        b"type octile\nheight 2\nwidth 3\nmap\n...\n..\n",
    );
    let huge_map = write(
        &d,
        "huge.map",
        b"type octile\nheight 100000\nwidth 100000\nmap\n",
    );
    let walls = write(
        &d,
        "walls.pgm",
        b"P5\n3 3\n255\n\x00\x00\x00\x00\x00\x00\x00\x00\x00",
    );
    let jpeg = write(&d, "photo.png", b"\xff\xd8\xff\xe0\x00\x10JFIF\x00");
    let no_header_csv = write(&d, "nohdr.csv", b"0.1,0.1\n");
    let bad_csv = write(&d, "bad.csv", b"x,y\n0.075,abc\n");
    let wall_csv = write(&d, "wall.csv", b"x,y\n-5,-5\n");
    let ok_csv = write(&d, "ok.csv", b"x,y\n0.075,0.075\n");
    let far_csv = write(&d, "far.csv", b"x,y\n0.075,0.075\n1e12,0.075\n");
    let world =
        |body: &str| format!("(name: \"w\", width: 4.0, height: 3.0, resolution: 0.025, {body})");
    let ok_world = write(
        &d,
        "ok_world.ron",
        world("obstacles: [Rect(centre: (2.0, 1.5), size: (1.0, 1.0), angle_deg: 0.0)]").as_bytes(),
    );
    let truncated_world = write(
        &d,
        "cut.ron",
        &world("obstacles: [Polygon([(1.0, 1.0),").into_bytes(),
    );
    let bowtie_world = write(
        &d,
        "bowtie.ron",
        world("obstacles: [Polygon([(1.0, 1.0), (2.0, 2.0), (2.0, 1.0), (1.0, 1.8)])]").as_bytes(),
    );
    let nan_world = write(
        &d,
        "nan.ron",
        world("obstacles: [Circle(centre: (NaN, 1.0), radius: 0.5)]").as_bytes(),
    );
    let no_res_world = write(
        &d,
        "nores.ron",
        b"(name: \"w\", width: 4.0, height: 3.0, obstacles: [])",
    );
    let huge_world = write(
        &d,
        "huge.ron",
        b"(name: \"w\", width: 1e6, height: 1e6, resolution: 0.01, obstacles: [])",
    );
    let no_dir = d.join("no/such/dir/out.csv").display().to_string();
    let a_folder = d.display().to_string();
    let missing = d.join("does-not-exist.yaml").display().to_string();
    let _ = &ok_pgm;
    let png_map = real_png_path();
    let big_map = fixtures()
        .join("turtlebot_simulator/hospital_section.yaml")
        .display()
        .to_string();

    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["plan", &truncated_png, "--planner", "dtc"],
            "truncated",
        ),
        (
            vec!["plan", &lying_pgm, "--planner", "dtc"],
            "truncated: header says 100x100",
        ),
        (
            vec!["plan", &huge_pgm, "--planner", "dtc"],
            "exceeds the limit",
        ),
        (
            vec!["plan", &huge_png, "--planner", "dtc"],
            "exceeds the limit",
        ),
        (
            vec!["plan", &huge_map, "--planner", "dtc"],
            "exceeds the limit",
        ),
        (
            vec!["plan", &no_res, "--planner", "dtc"],
            "missing field `resolution`",
        ),
        (
            vec![
                "simulate",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-spec",
                &slow_spec,
            ],
            "robot spec max_wheel_speed is `0.000000001`, expected at least 0.3 m/s",
        ),
        (vec!["plan", &nan_yaw, "--planner", "dtc"], "field `origin`"),
        (
            vec!["info", &alias_bomb],
            "YAML aliases (`*name`, 81 of them) are not accepted",
        ),
        (
            vec!["plan", &huge_res, "--planner", "dtc"],
            "field `resolution` is 1e308, expected a number > 0 and at most 1000",
        ),
        (
            vec!["plan", &ok_pgm, "--planner", "dtc", "--resolution", "1e9"],
            "--resolution is `1000000000`, expected at most 1000",
        ),
        (vec!["plan", &no_image, "--planner", "dtc"], "missing.pgm"),
        (
            vec!["plan", &garbage_yaml, "--planner", "dtc"],
            "garbage.yaml",
        ),
        (vec!["plan", &empty_map, "--planner", "dtc"], "empty file"),
        (
            vec!["plan", &ragged_map, "--planner", "dtc"],
            "expected width 3",
        ),
        (vec!["plan", &walls, "--planner", "dtc"], "no free cell"),
        (
            vec!["plan", &jpeg, "--planner", "dtc"],
            "not a PGM, PNG, BMP or MovingAI map: it begins with ff d8",
        ),
        (vec!["plan", &missing, "--planner", "dtc"], "cannot read"),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--start", "-5,-5"],
            "outside the map",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--start", "abc"],
            "expected X,Y",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--start", "0.1,NaN"],
            "finite",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-radius",
                "-1",
            ],
            "--robot-radius is `-1`",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-radius",
                "NaN",
            ],
            "--robot-radius is `NaN`",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--tool-radius", "0"],
            "--tool-radius is `0`",
        ),
        (
            vec!["segment", &good_yaml, "--min-area", "-1"],
            "--min-area is `-1`",
        ),
        (
            vec![
                "segment",
                &good_yaml,
                "--min-area",
                "50",
                "--max-area",
                "10",
            ],
            "expected at most --max-area",
        ),
        (
            vec!["segment", &good_yaml, "--out", "rooms.txt"],
            "--out is `rooms.txt`, expected a file name ending in .json, .png or .svg",
        ),
        (
            vec!["segment", &good_yaml, "--door-width", "0"],
            "--door-width is `0`",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "lanes", "--speed", "0"],
            "--speed is `0`",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--turn-rate", "-1"],
            "--turn-rate is `-1`",
        ),
        (
            vec!["eval", &good_yaml, "nope.csv", "--speed", "inf"],
            "--speed is `inf`",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--rooms", "maybe"],
            "--rooms",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--sweep-angle",
                "30",
            ],
            "only with --planner boustrophedon or trapezoidal",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "boustrophedon",
                "--sweep-angle",
                "NaN",
            ],
            "sweep angle is `NaN`, expected a finite angle",
        ),
        (
            vec!["simulate", &good_yaml, "--planner", "dtc", "--dt", "0"],
            "--dt is `0`",
        ),
        (
            vec!["simulate", &good_yaml, "--planner", "dtc", "--dt", "1e-9"],
            "--dt is `0.000000001`, expected a step giving at most 10000000 steps",
        ),
        (
            vec![
                "simulate",
                &good_yaml,
                "--planner",
                "dtc",
                "--odometry-noise",
                "NaN",
            ],
            "--odometry-noise is `NaN`",
        ),
        (
            vec![
                "simulate",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-spec",
                &garbage_yaml,
            ],
            "garbage.yaml: cannot read",
        ),
        (
            vec![
                "simulate",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-spec",
                &bad_ron,
            ],
            "--robot-spec is",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "trapezoidal",
                "--sweep-angle",
                "abc",
            ],
            "abc",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--tool-radius",
                "inf",
            ],
            "--tool-radius is `inf`",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--robot-radius",
                "5",
            ],
            "no admissible cell",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "nope"],
            "--planner is `nope`",
        ),
        (vec!["plan", &good_yaml], "--planner"),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--out", &no_dir],
            "does not exist",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--out", &a_folder],
            "a file name, not a folder",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--out",
                "/proc/out.csv",
            ],
            "/proc is not writable",
        ),
        (
            vec!["plan", &good_yaml, "--planner", "dtc", "--svg", "p.png"],
            "--svg is `p.png`, expected a file name ending in .svg",
        ),
        (
            vec!["explore", &ok_world, "--start", "0.5,0.5", "--map", "m.pgm"],
            "--map is `m.pgm`, expected a file name ending in .yaml",
        ),
        (
            vec!["plan", &png_map, "--planner", "dtc", "--resolution", "-0.5"],
            "--resolution is `-0.5`",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--boundary-pass",
                "maybe",
            ],
            "maybe",
        ),
        (
            vec!["eval", &good_yaml, &no_header_csv],
            "expected it to start with x,y",
        ),
        (vec!["eval", &good_yaml, &bad_csv], "line 2: y is `abc`"),
        (vec!["eval", &good_yaml, &wall_csv], "outside the map"),
        (vec!["eval", &good_yaml, &far_csv], "far outside the map"),
        (
            vec!["render", &good_yaml, &ok_csv, "--out", "picture.txt"],
            "ending in .svg or .png",
        ),
        (vec!["info", &walls, "--resolution", "abc"], "abc"),
        (
            vec!["info", &walls, "--free-thresh", "1.5"],
            "--free-thresh is `1.5`, expected a number in [0, 1]",
        ),
        (
            vec!["info", &walls, "--occupied-thresh", "NaN"],
            "--occupied-thresh is `NaN`, expected a number in [0, 1]",
        ),
        (
            vec!["plan", &png_map, "--planner", "dtc", "--free-thresh", "0.7"],
            "--free-thresh is `0.7`, expected --free-thresh (0.7) at most --occupied-thresh (0.65)",
        ),
        (
            vec![
                "info",
                &walls,
                "--free-thresh",
                "0.5",
                "--occupied-thresh",
                "0.3",
            ],
            "--free-thresh is `0.5`, expected --free-thresh (0.5) at most --occupied-thresh (0.3)\n",
        ),
        (
            vec!["segment", &good_yaml, "--free-thresh", "0.01"],
            "is a map_server yaml, whose own fields place and classify its image",
        ),
        (
            vec!["render", &good_yaml, "--out", "r.png", "--negate"],
            "--negate is `on`, expected an image read without a yaml",
        ),
        (
            vec!["eval", &ragged_map, &ok_csv, "--occupied-thresh", "0.5"],
            "is a MovingAI map",
        ),
        (vec!["frobnicate"], "frobnicate"),
        (vec!["explore", &missing], "does-not-exist.yaml"),
        (vec!["explore", &truncated_world], "cut.ron"),
        (vec!["explore", &bowtie_world], "simple"),
        (vec!["explore", &nan_world], "obstacle 1"),
        (vec!["explore", &no_res_world], "resolution"),
        (vec!["explore", &huge_world], "cells"),
        (vec!["explore", &ok_world], "--start"),
        (vec!["explore", &ok_world, "--start", "2,1.5"], "obstacle"),
        (
            vec!["explore", &ok_world, "--start", "0.1,0.1"],
            "robot radius",
        ),
        (
            vec!["explore", &ok_world, "--start", "0.5,0.5", "--noise", "NaN"],
            "range noise",
        ),
        (
            vec![
                "explore",
                &ok_world,
                "--start",
                "0.5,0.5",
                "--robot-radius",
                "-1",
            ],
            "robot radius",
        ),
        (
            vec!["explore", &ok_world, "--start", "0.5,0.5", "--rays", "2"],
            "rays",
        ),
        // Used to run for hours (no bound on laps).
        (
            vec![
                "explore",
                &ok_world,
                "--start",
                "0.5,0.5",
                "--tool-radius",
                "1e-6",
            ],
            "at most 10000 lanes across it",
        ),
        (
            vec!["explore", &ok_world, "--start", "0.5,0.5", "--out", &no_dir],
            "does not exist",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--memory-limit",
                "1M",
            ],
            "needs about 64 MiB, above the memory limit of 1 MiB",
        ),
        (
            vec![
                "plan",
                &good_yaml,
                "--planner",
                "dtc",
                "--memory-limit",
                "lots",
            ],
            "--memory-limit is `lots`",
        ),
        (
            vec!["plan", &big_map, "--planner", "optimal"],
            "at most 16 cells on its shorter side",
        ),
        (
            vec!["plan", &big_map, "--planner", "full-dtc"],
            "full-dtc accepts at most 20000 coverage cells",
        ),
    ];
    assert!(cases.len() >= 20);
    for (args, want) in cases {
        let out = Command::new(bin())
            .args(&args)
            .current_dir(&d)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: stderr {stderr:?}");
        assert_eq!(
            stderr.lines().count(),
            1,
            "{args:?}: not one line: {stderr:?}"
        );
        assert!(
            stderr.contains(want),
            "{args:?}: {stderr:?} should contain {want:?}"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr:?}");
    }
}

#[test]
fn help_and_version_exit_0() {
    for args in [
        vec!["--help"],
        vec!["plan", "--help"],
        vec!["eval", "--help"],
        vec!["--version"],
    ] {
        let out = Command::new(bin()).args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        assert!(!out.stdout.is_empty());
    }
}

/// `explore --graph` refuses a name it would not write as asked, before
/// any work; `plan --planner sensor-bcd` points to `explore`.
#[test]
fn graph_names_and_the_sensor_planner_are_explained() {
    let world = fixtures()
        .join("../worlds/demir2018/fig05_polygon.ron")
        .display()
        .to_string();
    let out = Command::new(bin())
        .args(["explore", &world, "--graph", "g.txt"])
        .output()
        .expect("run oxcover");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--graph is `g.txt`, expected a file name ending in .json or .ron"),
        "{err}"
    );
    let map = fixtures()
        .join("navigation_tutorials/lse_arena.yaml")
        .display()
        .to_string();
    let out = Command::new(bin())
        .args(["plan", &map, "--planner", "sensor-bcd"])
        .output()
        .expect("run oxcover");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("oxcover explore"), "{err}");
}
