//! `oxcover map-from-camera`: an occupancy grid from floor-camera images.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use oxcover::grid::Point;
use oxcover::render::{Scene, render_to_file};
use oxcover::{Error, Result};

use super::args::read_ron;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum VisibilityArg {
    Product,
    Bayes,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum FusionArg {
    Paper,
    Discounted,
}

#[derive(Debug, clap::Args)]
pub(crate) struct MapFromCameraArgs {
    /// Calibrated camera (RON: width, height, distortion, projection).
    #[arg(long, value_name = "CAM.ron")]
    pub(crate) camera: PathBuf,
    /// HSV probability profile (RON: bins, free, occ).
    #[arg(long, value_name = "PROFILE.ron")]
    pub(crate) profile: PathBuf,
    /// Poses: CSV with header image,x,y,theta (image paths relative to it).
    #[arg(long, value_name = "POSES.csv")]
    pub(crate) poses: PathBuf,
    /// Map to write (ROS yaml, PGM beside it).
    #[arg(long, value_name = "MAP.yaml")]
    pub(crate) out: PathBuf,
    /// Cell size in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 0.05,
        allow_negative_numbers = true
    )]
    pub(crate) resolution: f64,
    /// Farthest floor distance read from an image, in metres.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 3.0,
        allow_negative_numbers = true
    )]
    pub(crate) range: f64,
    /// How visibility is accumulated along rays from the camera.
    #[arg(long, value_enum, default_value_t = VisibilityArg::Product)]
    pub(crate) visibility: VisibilityArg,
    /// How visibility enters the grid: `paper` (hidden cells read occupied)
    /// or `discounted` (hidden cells tell nothing).
    #[arg(long, value_enum, default_value_t = FusionArg::Discounted)]
    pub(crate) fusion: FusionArg,
    /// Map extent in metres [default: the poses' box grown by the range].
    #[arg(long, value_name = "XMIN,YMIN,XMAX,YMAX", allow_hyphen_values = true)]
    pub(crate) extent: Option<String>,
    /// PNG picture of the map to write.
    #[arg(long, value_name = "F.png")]
    pub(crate) png: Option<PathBuf>,
}

pub(crate) fn cmd_map_from_camera(a: &MapFromCameraArgs) -> Result<()> {
    use oxcover::vision::occupancy::{LogOddsGrid, Visibility};
    use oxcover::vision::{Camera, Profile, RgbImage, fuse, to_map};
    let positive = |name: &'static str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(Error::Argument {
                name,
                value: v.to_string(),
                expected: "a finite number above 0".into(),
            })
        }
    };
    let res = positive("--resolution", a.resolution)?;
    let range = positive("--range", a.range)?;
    let camera: Camera = read_ron(&a.camera, "camera")?;
    let profile: Profile = read_ron(&a.profile, "profile")?;
    let cells = (1..=256)
        .contains(&profile.bins)
        .then(|| profile.bins.pow(3));
    if cells.is_none_or(|n| profile.free.len() != n || profile.occ.len() != n) {
        return Err(Error::Argument {
            name: "profile",
            value: a.profile.display().to_string(),
            expected: "1 to 256 bins per axis and bins³ free and occ counts".into(),
        });
    }
    let text = std::fs::read_to_string(&a.poses).map_err(|e| Error::Read {
        path: a.poses.clone(),
        source: e,
    })?;
    let bad = |line: usize, message: String| Error::PathFile {
        path: a.poses.clone(),
        line,
        message,
    };
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("image,x,y,theta") {
        return Err(bad(1, "expected the header image,x,y,theta".into()));
    }
    let dir = a.poses.parent().unwrap_or(Path::new("."));
    let mut poses: Vec<(PathBuf, (f64, f64, f64))> = Vec::new();
    for (k, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 4 {
            return Err(bad(k + 2, format!("expected 4 fields, got {}", f.len())));
        }
        let num = |s: &str, name: &str| -> Result<f64> {
            s.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(k + 2, format!("{name} is `{s}`, expected a finite number")))
        };
        poses.push((
            dir.join(f[0]),
            (num(f[1], "x")?, num(f[2], "y")?, num(f[3], "theta")?),
        ));
    }
    if poses.is_empty() {
        return Err(bad(2, "no image".into()));
    }
    let (x0, y0, x1, y1) = match &a.extent {
        Some(e) => {
            let v: Vec<f64> = e.split(',').filter_map(|s| s.trim().parse().ok()).collect();
            match v.as_slice() {
                [x0, y0, x1, y1] if x1 > x0 && y1 > y0 && v.iter().all(|x| x.is_finite()) => {
                    (*x0, *y0, *x1, *y1)
                }
                _ => {
                    return Err(Error::Argument {
                        name: "--extent",
                        value: e.clone(),
                        expected: "XMIN,YMIN,XMAX,YMAX in metres with XMIN < XMAX and YMIN < YMAX"
                            .into(),
                    });
                }
            }
        }
        None => poses.iter().fold(
            (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ),
            |b, (_, p)| {
                (
                    b.0.min(p.0 - range),
                    b.1.min(p.1 - range),
                    b.2.max(p.0 + range),
                    b.3.max(p.1 + range),
                )
            },
        ),
    };
    let (w, h) = (((x1 - x0) / res).ceil(), ((y1 - y0) / res).ceil());
    if w * h > 50_000_000.0 {
        return Err(Error::Argument {
            name: "--extent",
            value: format!("{w} x {h} cells"),
            expected: "at most 50 million cells (a smaller extent or a coarser resolution)".into(),
        });
    }
    let frame = oxcover::grid::MapFrame::new(w as usize, h as usize, res, Point::new(x0, y0));
    let mut grid = LogOddsGrid::new(frame);
    let mode = match a.visibility {
        VisibilityArg::Product => Visibility::Product,
        VisibilityArg::Bayes => Visibility::Bayes,
    };
    for (file, pose) in &poses {
        let img = RgbImage::read_png(file)?;
        if (img.width, img.height) != (camera.width, camera.height) {
            return Err(Error::Argument {
                name: "image",
                value: format!("{} ({}x{})", file.display(), img.width, img.height),
                expected: format!(
                    "{}x{} pixels, the camera's size",
                    camera.width, camera.height
                ),
            });
        }
        let fusion = match a.fusion {
            FusionArg::Paper => oxcover::vision::Fusion::Paper,
            FusionArg::Discounted => oxcover::vision::Fusion::Discounted,
        };
        fuse(
            &mut grid, &camera, &profile, &img, *pose, range, mode, fusion,
        );
    }
    let map = to_map(&grid, 0.35, 0.65);
    oxcover::grid::io::write_ros_map(&map, &a.out)?;
    let mut out = std::io::stdout().lock();
    let counts = map.counts();
    let _ = writeln!(
        out,
        "{} images fused into {}x{} cells: {} free, {} occupied, {} unknown",
        poses.len(),
        map.width(),
        map.height(),
        counts.free,
        counts.occupied,
        counts.unknown
    );
    let _ = writeln!(out, "wrote {}", a.out.display());
    if let Some(f) = &a.png {
        let scene = Scene {
            map: &map,
            path: &[],
            planned: None,
            covered: None,
            coverable: None,
            title: "map from camera".into(),
            overlay: None,
            rows: Vec::new(),
        };
        render_to_file(&scene, f)?;
        let _ = writeln!(out, "wrote {}", f.display());
    }
    Ok(())
}
