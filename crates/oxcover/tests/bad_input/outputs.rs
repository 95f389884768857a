//! Outputs are whole or absent: never an input or another output
//! overwritten, nothing left by a failed command, write errors reported.

use std::path::Path;
use std::process::Command;

use crate::{bin, fixtures, scratch};

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
