//! `plan` killed while it writes its outputs: every output is whole (byte
//! for byte the uninterrupted run's) or absent, never cut; SIGTERM and
//! SIGINT leave no temporary file either.
//!
//! Each run is watched until its first temporary file appears in the output
//! folder (the write has begun), then signalled; a run that finished first
//! is retried, and the test insists that some signals landed mid-write.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const OUTPUTS: [&str; 4] = ["path.csv", "plan.png", "plan.svg", "report.json"];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-interrupt-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// A 240 x 180 room with pillars: outputs of about a MB, written in a few ms.
fn map(dir: &Path) -> PathBuf {
    let (w, h) = (240usize, 180usize);
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    for r in 0..h {
        for c in 0..w {
            let wall = r == 0 || c == 0 || r == h - 1 || c == w - 1;
            let pillar = r % 60 >= 25 && r % 60 < 32 && c % 50 >= 20 && c % 50 < 26;
            pgm.push(if wall || pillar { 0 } else { 254 });
        }
    }
    let p = dir.join("room.pgm");
    std::fs::write(&p, pgm).expect("map");
    p
}

fn plan(map: &Path, out: &Path) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_oxcover"));
    cmd.arg("plan")
        .arg(map)
        .args([
            "--planner",
            "boustrophedon",
            "--rooms",
            "off",
            "--resolution",
            "0.05",
        ])
        .args(["--tool-radius", "0.05"])
        .arg("--out")
        .arg(out.join(OUTPUTS[0]))
        .arg("--png")
        .arg(out.join(OUTPUTS[1]))
        .arg("--svg")
        .arg(out.join(OUTPUTS[2]))
        .arg("--report")
        .arg(out.join(OUTPUTS[3]))
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    cmd
}

/// The file without its `plan_ms` line (the only part that differs between runs).
fn timeless(bytes: Vec<u8>) -> Vec<u8> {
    let text = String::from_utf8_lossy(&bytes);
    if !text.contains("\"plan_ms\"") {
        return bytes;
    }
    text.lines()
        .filter(|l| !l.contains("\"plan_ms\""))
        .collect::<Vec<_>>()
        .join("\n")
        .into_bytes()
}

fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.contains(".oxcover-"))
                .collect()
        })
        .unwrap_or_default()
}

/// Runs `plan` into `out` and sends `signal` once its first temporary file
/// shows; returns whether the signal came before the run ended by itself.
fn interrupt(map: &Path, out: &Path, signal: &str) -> bool {
    let mut child = plan(map, out).spawn().expect("spawn plan");
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            assert!(status.success(), "plan failed on its own: {status:?}");
            return false;
        }
        if !temporaries(out).is_empty() {
            let _ = Command::new("kill")
                .args([signal, &child.id().to_string()])
                .status();
            let status = child.wait().expect("wait");
            return !status.success();
        }
        assert!(started.elapsed() < Duration::from_secs(120), "plan hung");
        std::thread::yield_now();
    }
}

fn check(signal: &str, temporaries_allowed: bool) {
    let dir = scratch(signal.trim_start_matches('-'));
    let map = map(&dir);
    let reference = dir.join("reference");
    std::fs::create_dir_all(&reference).expect("folder");
    assert!(plan(&map, &reference).status().expect("run").success());
    let whole: Vec<Vec<u8>> = OUTPUTS
        .iter()
        .map(|f| timeless(std::fs::read(reference.join(f)).expect("reference output")))
        .collect();
    let mut landed = 0;
    let mut attempt = 0;
    while landed < 3 && attempt < 20 {
        attempt += 1;
        let out = dir.join(format!("run{attempt}"));
        std::fs::create_dir_all(&out).expect("folder");
        if interrupt(&map, &out, signal) {
            landed += 1;
        }
        for (name, bytes) in OUTPUTS.iter().zip(&whole) {
            if let Ok(found) = std::fs::read(out.join(name)).map(timeless) {
                assert!(
                    found == *bytes,
                    "{signal}: {name} is {} bytes, not the whole {} bytes",
                    found.len(),
                    bytes.len()
                );
            }
        }
        if !temporaries_allowed {
            assert_eq!(
                temporaries(&out),
                Vec::<String>::new(),
                "{signal}: left behind"
            );
        }
    }
    assert!(
        landed >= 3,
        "{signal} landed mid-write only {landed} times in 20"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sigterm_during_the_write_leaves_whole_files_or_none() {
    check("-TERM", false);
}

#[test]
fn sigint_during_the_write_leaves_whole_files_or_none() {
    check("-INT", false);
}

/// SIGKILL cannot be caught: a hidden temporary file may stay, but every
/// output is still whole or absent.
#[test]
fn sigkill_during_the_write_leaves_whole_files_or_none() {
    check("-KILL", true);
}
