//! `oxcover map-from-camera` end to end on synthetic camera images, and its
//! bad input (exit 2, one line, no panic).

use std::path::{Path, PathBuf};
use std::process::Command;

use oxcover_grid::{Grid, Occupancy, OccupancyGrid, Point, Pose};
use oxcover_vision::synthetic::{Lighting, SyntheticScene};
use oxcover_vision::{Camera, Distortion, Profile, Projection, RgbImage, learn_profile};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_oxcover")
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-camera-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// A 5 m × 4 m room with a desk, its camera and profile, and a loop of
/// images written as the command reads them.
fn write_inputs(dir: &Path) -> OccupancyGrid {
    let (w, h) = (100, 80);
    let cells = Grid::from_fn(w, h, |c| {
        let (x, y) = (
            c.col as f64 * 0.05 + 0.025,
            (h - 1 - c.row) as f64 * 0.05 + 0.025,
        );
        let wall = x < 0.1 || y < 0.1 || x > 4.9 || y > 3.9;
        let desk = (2.0..3.0).contains(&x) && (1.6..2.2).contains(&y);
        if wall || desk {
            Occupancy::Occupied
        } else {
            Occupancy::Free
        }
    });
    let truth = OccupancyGrid::new(cells, 0.05, Point::new(0.0, 0.0));
    let walls = Grid::new(w, h, [70, 80, 150]);
    let scene = SyntheticScene {
        map: &truth,
        floor: [205, 185, 150],
        walls: &walls,
        background: [128, 128, 128],
        max_range: 8.0,
    };
    let cam = Camera {
        width: 160,
        height: 120,
        distortion: Distortion {
            uc: 80.0,
            vc: 60.0,
            p: [1e-6, 0.0, 0.0],
        },
        projection: Projection::pinhole(110.0, 0.3, 0.0, -5.0, 0.0, 0.1),
    };
    let light = Lighting {
        gain: 1.0,
        tint: [1.0; 3],
        noise: 2.0,
    };
    let poses: Vec<Pose> = (0..16)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 16.0;
            Pose::new(2.5 + 1.5 * a.cos(), 2.0 + 1.1 * a.sin(), a + 1.9)
        })
        .collect();
    let images: Vec<_> = poses
        .iter()
        .enumerate()
        .map(|(k, &p)| scene.render(&cam, p, &light, k as u64))
        .collect();
    let mut profile = Profile::new(20).expect("bins");
    learn_profile(&mut profile, &images[..4]);
    std::fs::write(dir.join("camera.ron"), ron::to_string(&cam).expect("ron")).expect("write");
    std::fs::write(
        dir.join("profile.ron"),
        ron::to_string(&profile).expect("ron"),
    )
    .expect("write");
    let mut csv = String::from("image,x,y,theta\n");
    for (k, (img, p)) in images.iter().zip(&poses).enumerate() {
        let name = format!("img{k:02}.png");
        RgbImage::from(img)
            .write_png(&dir.join(&name))
            .expect("png");
        csv += &format!("{name},{},{},{}\n", p.x, p.y, p.theta);
    }
    std::fs::write(dir.join("poses.csv"), csv).expect("write");
    truth
}

fn run(args: &[&str], dir: &Path) -> (Option<i32>, String, String) {
    let out = Command::new(bin())
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn images_and_poses_become_a_map_that_plan_reads() {
    let d = scratch();
    let truth = write_inputs(&d);
    let args = [
        "map-from-camera",
        "--camera",
        "camera.ron",
        "--profile",
        "profile.ron",
        "--poses",
        "poses.csv",
        "--out",
        "built.yaml",
        "--extent",
        "0,0,5,4",
        "--png",
        "built.png",
    ];
    let (code, out, err) = run(&args, &d);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("16 images"), "{out}");
    let built =
        oxcover_grid::io::read_map(&d.join("built.yaml"), &Default::default()).expect("a ROS map");
    assert_eq!(
        (built.width(), built.height()),
        (truth.width(), truth.height())
    );
    let s = oxcover_vision::score(&built, &truth, None);
    assert!(s.accuracy_free > 0.9, "{s:?}");
    assert!(s.iou_free > 0.6, "{s:?}");
    let (code, _, err) = run(
        &[
            "plan",
            "built.yaml",
            "--planner",
            "boustrophedon",
            "--robot-radius",
            "0.1",
            "--tool-radius",
            "0.1",
        ],
        &d,
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(std::fs::metadata(d.join("built.png")).expect("png").len() > 1000);
}

#[test]
fn bad_camera_inputs_exit_2_with_one_line() {
    let d = scratch().join("bad");
    std::fs::create_dir_all(&d).expect("dir");
    write_inputs(&d);
    let w = |name: &str, text: &[u8]| std::fs::write(d.join(name), text).expect("write");
    w("noheader.csv", b"img00.png,1,1,0\n");
    w("nan.csv", b"image,x,y,theta\nimg00.png,NaN,1,0\n");
    w("short.csv", b"image,x,y,theta\nimg00.png,1,1\n");
    w("missing.csv", b"image,x,y,theta\nnope.png,1,1,0\n");
    w("corrupt.png", b"\x89PNG\r\n\x1a\n not really");
    w("corrupt.csv", b"image,x,y,theta\ncorrupt.png,1,1,0\n");
    RgbImage {
        width: 4,
        height: 3,
        rgb: vec![[0, 0, 0]; 12],
    }
    .write_png(&d.join("small.png"))
    .expect("png");
    w("small.csv", b"image,x,y,theta\nsmall.png,1,1,0\n");
    w("bad.ron", b"(width: 3,");
    // A camera of no pixels: the camera file is to blame, not the images.
    let cam = std::fs::read_to_string(d.join("camera.ron")).expect("camera");
    let zero = cam
        .replacen("width:160", "width:0", 1)
        .replacen("height:120", "height:0", 1);
    assert_ne!(zero, cam, "the camera file's size fields changed form");
    w("zero.ron", zero.as_bytes());
    let base = |poses: &'static str| {
        vec![
            "map-from-camera",
            "--camera",
            "camera.ron",
            "--profile",
            "profile.ron",
            "--poses",
            poses,
            "--out",
            "o.yaml",
        ]
    };
    let with = |mut v: Vec<&'static str>, extra: &[&'static str]| {
        v.extend_from_slice(extra);
        v
    };
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (base("noheader.csv"), "header"),
        (base("nan.csv"), "line 2"),
        (base("short.csv"), "4 fields"),
        (base("missing.csv"), "nope.png"),
        (base("corrupt.csv"), "corrupt.png"),
        (base("small.csv"), "160x120"),
        (base("absent.csv"), "absent.csv"),
        (
            with(base("poses.csv"), &["--resolution", "0"]),
            "--resolution",
        ),
        (with(base("poses.csv"), &["--range", "NaN"]), "--range"),
        (
            with(base("poses.csv"), &["--extent", "5,0,0,4"]),
            "--extent",
        ),
        (
            with(base("poses.csv"), &["--extent", "0,0,1e6,1e6"]),
            "million",
        ),
        (
            vec![
                "map-from-camera",
                "--camera",
                "bad.ron",
                "--profile",
                "profile.ron",
                "--poses",
                "poses.csv",
                "--out",
                "o.yaml",
            ],
            "bad.ron",
        ),
        (
            vec![
                "map-from-camera",
                "--camera",
                "zero.ron",
                "--profile",
                "profile.ron",
                "--poses",
                "poses.csv",
                "--out",
                "o.yaml",
            ],
            "file is `zero.ron`, expected a usable description (camera is `0x0`",
        ),
        (
            vec![
                "map-from-camera",
                "--camera",
                "camera.ron",
                "--profile",
                "profile.ron",
                "--poses",
                "poses.csv",
                "--out",
                "o.pgm",
            ],
            "expected a map file name ending in .yaml",
        ),
        (
            vec![
                "map-from-camera",
                "--camera",
                "camera.ron",
                "--profile",
                "camera.ron",
                "--poses",
                "poses.csv",
                "--out",
                "o.yaml",
            ],
            "profile",
        ),
    ];
    for (args, want) in cases {
        let (code, _, err) = run(&args, &d);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err} should contain {want}");
        assert!(!err.contains("panicked"), "{err}");
    }
}
