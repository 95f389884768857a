//! Bounded reads and memory: endless files refused by size, a map beyond
//! the memory budget refused before planning.

use std::path::Path;
use std::process::Command;

use crate::{bin, fixtures, scratch};

/// A map, a map yaml, a bag or a path file that never ends (a link to
/// /dev/zero) is refused from its first bytes, exit 2, in a moment.
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
    let (mcap, db3, geojson) = (link("b.mcap"), link("b.db3"), link("z.geojson"));
    let map = fixtures()
        .join("navigation_tutorials/lse_arena.yaml")
        .display()
        .to_string();
    for (args, limit) in [
        (
            vec!["info", pgm.as_str()],
            "not a PGM, PNG, BMP or MovingAI map",
        ),
        (vec!["info", yaml.as_str()], "byte 0 is NUL"),
        (vec!["info", mcap.as_str()], "not an MCAP file"),
        (vec!["info", db3.as_str()], "not an SQLite 3 database"),
        (vec!["eval", map.as_str(), csv.as_str()], "byte 0 is NUL"),
        (
            vec![
                "plan",
                map.as_str(),
                "--planner",
                "lanes",
                "--zones",
                geojson.as_str(),
            ],
            "byte 0 is NUL",
        ),
    ] {
        let started = std::time::Instant::now();
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
        // Reading to the 1 GiB cap took seconds; 64 bytes take none.
        assert!(
            started.elapsed().as_secs_f64() < 2.0,
            "{args:?}: {:?}",
            started.elapsed()
        );
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
