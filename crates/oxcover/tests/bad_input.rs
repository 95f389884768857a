//! Bad input, table-driven: every case must exit with status 2 and one line on
//! stderr naming what was wrong, never a panic (contract, exit status).

use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_oxcover")
}

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/maps")
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, bytes).expect("write fixture");
    p.display().to_string()
}

fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A syntactically valid PNG whose header claims `w × h` pixels (no image data).
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = b"IHDR".to_vec();
    chunk.extend(w.to_be_bytes());
    chunk.extend(h.to_be_bytes());
    chunk.extend([8, 0, 0, 0, 0]);
    out.extend(13u32.to_be_bytes());
    out.extend(&chunk);
    out.extend(crc32(&chunk).to_be_bytes());
    out
}

const GOOD_YAML: &str = "image: ok.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

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
            "not a PGM, PNG or BMP",
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

fn real_png_path() -> String {
    fixtures()
        .join("pythonrobotics/test.png")
        .display()
        .to_string()
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

/// Output that cannot be written is an error (exit 1, one line), not a
/// silent success; a reader closing the pipe early is no error.
#[test]
fn stdout_write_errors_are_reported() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        return;
    }
    let map = fixtures()
        .join("navigation_tutorials/lse_arena.yaml")
        .display()
        .to_string();
    for args in [
        vec!["planners"],
        vec!["info", &map],
        vec!["plan", &map, "--planner", "dtc"],
    ] {
        let sink = std::fs::OpenOptions::new()
            .write(true)
            .open(full)
            .expect("/dev/full");
        let out = Command::new(bin())
            .args(&args)
            .stdout(sink)
            .output()
            .expect("run oxcover");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("could not write to standard output") && err.lines().count() == 1,
            "{args:?}: {err}"
        );
    }
    // A pipe closed by its reader: quiet success.
    let mut child = Command::new(bin())
        .arg("planners")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run oxcover");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait");
    assert_eq!(out.status.code(), Some(0));
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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

/// An output that is an input or another output is refused before any
/// work, and the file is left as it was.
#[test]
fn outputs_never_overwrite_inputs_or_each_other() {
    let d = scratch().join("clobber");
    std::fs::create_dir_all(&d).expect("scratch");
    let victim = d.join("victim.pgm");
    std::fs::copy(
        fixtures().join("navigation_tutorials/lse_arena.pgm"),
        &victim,
    )
    .expect("copy");
    let before = std::fs::read(&victim).expect("read");
    let v = victim.display().to_string();
    let csv = d.join("f.csv").display().to_string();
    for (args, expected) in [
        (
            vec!["plan", &v, "--planner", "dtc", "--out", &v],
            "expected a file other than the input",
        ),
        (
            vec!["render", &v, "--out", &v],
            "expected a file other than the input",
        ),
        (
            vec![
                "plan",
                &v,
                "--planner",
                "dtc",
                "--out",
                &csv,
                "--report",
                &csv,
            ],
            "--report is",
        ),
        (vec!["segment", &v, "--out", &v], "--out is"),
        (
            vec![
                "map-from-camera",
                "--camera",
                "c.ron",
                "--profile",
                "p.ron",
                "--poses",
                "p.csv",
                "--out",
                &v,
            ],
            "expected a map file name ending in .yaml",
        ),
    ] {
        let out = Command::new(bin())
            .args(&args)
            .output()
            .expect("run oxcover");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(expected) && err.lines().count() == 1,
            "{args:?}: {err}"
        );
        assert_eq!(
            std::fs::read(&victim).expect("read"),
            before,
            "{args:?} changed the input"
        );
        assert!(!Path::new(&csv).exists(), "{args:?} wrote {csv}");
    }
}

/// A map, a map yaml or a path file that never ends (a link to /dev/zero)
/// is refused with the size limit, exit 2, without reading past it.
#[cfg(unix)]
#[test]
fn endless_files_are_refused_by_size() {
    let zero = Path::new("/dev/zero");
    if !zero.exists() {
        return;
    }
    let d = scratch().join("endless");
    std::fs::create_dir_all(&d).expect("scratch");
    let link = |name: &str| {
        let p = d.join(name);
        let _ = std::fs::remove_file(&p);
        std::os::unix::fs::symlink(zero, &p).expect("symlink");
        p.display().to_string()
    };
    let (pgm, yaml, csv) = (link("m.pgm"), link("m.yaml"), link("p.csv"));
    let map = fixtures()
        .join("navigation_tutorials/lse_arena.yaml")
        .display()
        .to_string();
    for (args, limit) in [
        (vec!["info", pgm.as_str()], "larger than 1 GiB"),
        (vec!["info", yaml.as_str()], "larger than 1 MiB"),
        (
            vec!["eval", map.as_str(), csv.as_str()],
            "larger than 1 GiB",
        ),
    ] {
        let out = Command::new(bin())
            .args(&args)
            .output()
            .expect("run oxcover");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(limit) && err.lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}

/// A failed output leaves none of the others behind (plan writes its files
/// as one set), and no temporary file either.
#[test]
fn outputs_are_whole_or_absent() {
    let d = scratch().join("whole");
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch");
    let map = fixtures()
        .join("navigation_tutorials/lse_arena.yaml")
        .display()
        .to_string();
    let csv = d.join("p.csv").display().to_string();
    let json = d.join("r.json").display().to_string();
    let png = d.join("missing/x.png").display().to_string();
    let out = Command::new(bin())
        .args([
            "plan",
            &map,
            "--planner",
            "dtc",
            "--out",
            &csv,
            "--report",
            &json,
            "--png",
            &png,
        ])
        .output()
        .expect("run oxcover");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("x.png") && err.lines().count() == 1, "{err}");
    let left: Vec<_> = std::fs::read_dir(&d)
        .expect("read scratch")
        .filter_map(|e| e.ok().map(|e| e.file_name()))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
    // The same command with a writable picture writes all three.
    let png = d.join("x.png").display().to_string();
    let out = Command::new(bin())
        .args([
            "plan",
            &map,
            "--planner",
            "dtc",
            "--out",
            &csv,
            "--report",
            &json,
            "--png",
            &png,
        ])
        .output()
        .expect("run oxcover");
    assert!(out.status.success());
    for f in [&csv, &json, &png] {
        assert!(Path::new(f).exists(), "{f}");
    }
    assert_eq!(std::fs::read_dir(&d).expect("read scratch").count(), 3);
    std::fs::remove_dir_all(&d).expect("clear");
    std::fs::create_dir_all(&d).expect("scratch");
    let world = fixtures()
        .join("../worlds/demir2018/fig05_polygon.ron")
        .display()
        .to_string();
    let f = |n: &str| d.join(n).display().to_string();
    let mut cases = vec![
        // A missing folder for the map: found before exploring.
        vec![
            "explore".to_string(),
            world.clone(),
            "--out".into(),
            f("e.csv"),
            "--map".into(),
            f("nodir/m.yaml"),
        ],
    ];
    if Path::new("/dev/full").exists() {
        // A device that refuses the bytes at write time: the report staged
        // beside it is withdrawn.
        cases.push(vec![
            "plan".into(),
            map.clone(),
            "--planner".into(),
            "dtc".into(),
            "--report".into(),
            f("r.json"),
            "--out".into(),
            "/dev/full".into(),
        ]);
        cases.push(vec![
            "explore".into(),
            world.clone(),
            "--report".into(),
            f("r.json"),
            "--out".into(),
            "/dev/full".into(),
        ]);
    }
    for args in cases {
        let out = Command::new(bin())
            .args(&args)
            .output()
            .expect("run oxcover");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        let why = if args.contains(&"/dev/full".to_string()) {
            "/dev/full: cannot write"
        } else {
            "does not exist"
        };
        assert!(err.contains(why), "{args:?}: {err}");
        let left: Vec<_> = std::fs::read_dir(&d)
            .expect("read scratch")
            .filter_map(|e| e.ok().map(|e| e.file_name()))
            .collect();
        assert!(left.is_empty(), "{args:?} left behind: {left:?}");
    }
}

/// A map too large for the memory budget is refused at once, naming its
/// size, the estimate and what helps, before anything large is allocated
/// (a 16384² map used to abort after 33 s at 9 GiB).
#[test]
fn a_map_beyond_the_memory_budget_is_refused_before_planning() {
    let d = scratch().join("memory");
    std::fs::create_dir_all(&d).expect("folder");
    // 8192 x 8192 free cells in a plain PGM of 64 MiB.
    let n = 8192usize;
    let mut pgm = format!("P5\n{n} {n}\n255\n").into_bytes();
    pgm.resize(pgm.len() + n * n, 254);
    let map = d.join("big.pgm");
    std::fs::write(&map, pgm).expect("map");
    let started = std::time::Instant::now();
    let out = Command::new(bin())
        .arg("plan")
        .arg(&map)
        .args(["--planner", "rect-priority", "--memory-limit", "2G"])
        .args(["--out", "never.csv"])
        .current_dir(&d)
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    for part in [
        "8192x8192 cells",
        "needs about",
        "above the memory limit of 2.0 GiB",
        "--rooms off",
    ] {
        assert!(err.contains(part), "{part}: {err}");
    }
    assert!(
        started.elapsed().as_secs() < 10,
        "took {:?}",
        started.elapsed()
    );
    assert!(!d.join("never.csv").exists());
    let _ = std::fs::remove_dir_all(&d);
}
