//! Bad coverage targets: each exits 2 with one line naming the option, the
//! file, the feature and what is wrong, and writes nothing.

use std::process::Command;

use crate::{bin, fixtures, scratch, write};

fn polygon(ring: &str) -> String {
    format!(r#"{{"type":"Polygon","coordinates":[{ring}]}}"#)
}

#[test]
fn bad_targets_exit_2_with_one_line_and_write_nothing() {
    let d = scratch().join("targets");
    std::fs::create_dir_all(&d).unwrap();
    let map = fixtures().join("lee2011/living.yaml").display().to_string();
    let csv = write(&d, "not.geojson", b"x,y\n1,2\n");
    let line = write(
        &d,
        "line.geojson",
        br#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":null,"geometry":{"type":"LineString","coordinates":[[1,1],[2,2]]}}]}"#,
    );
    let short = write(
        &d,
        "short.geojson",
        polygon("[[1,1],[2,1],[1,1]]").as_bytes(),
    );
    let open = write(
        &d,
        "open.geojson",
        polygon("[[1,1],[2,1],[2,2],[1,2]]").as_bytes(),
    );
    let bow = write(
        &d,
        "bow.geojson",
        format!(
            r#"{{"type":"FeatureCollection","features":[{{"type":"Feature","properties":null,"geometry":{}}},{{"type":"Feature","properties":null,"geometry":{}}}]}}"#,
            polygon("[[1,1],[2,1],[2,2],[1,2],[1,1]]"),
            polygon("[[1,1],[3,3],[3,1],[1,3],[1,1]]")
        )
        .as_bytes(),
    );
    let inf = write(
        &d,
        "inf.geojson",
        polygon("[[1,1],[1e999,1],[2,2],[1,1]]").as_bytes(),
    );
    let far = write(
        &d,
        "far.geojson",
        polygon("[[50,50],[60,50],[60,60],[50,50]]").as_bytes(),
    );
    // A zone around the sofa in the living room: no coverable cell.
    let wall_zone = write(
        &d,
        "wall.geojson",
        polygon("[[-0.05,-0.05],[0.0,-0.05],[0.0,0.0],[-0.05,-0.05]]").as_bytes(),
    );
    let over_start = write(
        &d,
        "start.geojson",
        polygon("[[0.5,0.5],[1.5,0.5],[1.5,1.5],[0.5,1.5],[0.5,0.5]]").as_bytes(),
    );
    let far_done = write(&d, "done.csv", b"x,y\n1,1\n40,40\n");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--zones", &csv], "not GeoJSON"),
        (
            vec!["--zones", &line],
            "feature 0 is a LineString, expected Polygon or MultiPolygon",
        ),
        (vec!["--zones", &short], "a ring needs at least 4"),
        (vec!["--keep-out", &open], "is not closed"),
        (
            vec!["--zones", &bow],
            "feature 1 is not a valid polygon: exterior ring",
        ),
        (vec!["--zones", &bow], "self-intersection at (2.000, 2.000)"),
        (vec!["--zones", &inf], "not valid GeoJSON"),
        (
            vec!["--zones", &far],
            "--zones: no zone holds the centre of a map cell",
        ),
        (
            vec!["--keep-out", &far],
            "no keep-out area or wall meets the map",
        ),
        (
            vec!["--zones", &wall_zone],
            "no coverable cell reachable from the start",
        ),
        (
            vec!["--rooms-only", "99"],
            "no room 99 on this map: the rooms are 1 to",
        ),
        (vec!["--rooms-only", "a"], "--rooms-only"),
        (
            vec!["--done", &far_done],
            "--done: point 2 (40, 40) lies outside the map",
        ),
        (
            vec!["--keep-out", &over_start, "--start", "1,1"],
            "a keep-out area or virtual wall covers the start (1, 1)",
        ),
        (
            vec!["--room-order", "given"],
            "--room-order is `given`, expected --rooms-only",
        ),
        (vec!["--spot", "1,1"], "expected X,Y,R"),
        (vec!["--spot", "1,1,0"], "radius R above 0"),
        (
            vec!["--spot", "50,50,1"],
            "--spot: the disc holds no cell centre",
        ),
        (
            vec!["--zones", "/nonexistent.geojson"],
            "nonexistent.geojson: cannot read",
        ),
    ];
    let out_csv = d.join("out.csv");
    for (extra, want) in cases {
        for cmd in ["plan", "eval"] {
            let mut args = vec![cmd, map.as_str()];
            if cmd == "plan" {
                args.extend([
                    "--planner",
                    "boustrophedon",
                    "--out",
                    out_csv.to_str().unwrap(),
                ]);
            } else {
                args.push(&far_done);
                if extra.contains(&"--done") || extra.contains(&"--start") {
                    continue;
                }
            }
            args.extend(extra.iter().copied());
            let out = Command::new(bin()).args(&args).output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr:?}");
            assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr:?}");
            assert!(
                stderr.contains(want),
                "{args:?}: {stderr:?} should contain {want:?}"
            );
            assert!(!out_csv.exists(), "{args:?} wrote its output");
        }
    }
    // A picture of the map alone labels the chosen rooms: a room the map
    // does not have is refused there too, nothing written.
    let png = d.join("rooms.png");
    let args = [
        "render",
        map.as_str(),
        "--rooms-only",
        "2,99",
        "--out",
        png.to_str().unwrap(),
    ];
    let out = Command::new(bin()).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr:?}");
    assert_eq!(stderr.lines().count(), 1, "{stderr:?}");
    assert!(stderr.contains("no room 99 on this map"), "{stderr:?}");
    assert!(!png.exists());
}
