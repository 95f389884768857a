//! `oxcover map-from-camera`: an occupancy grid from floor-camera images.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use oxcover::grid::Point;
use oxcover::render::{Scene, render_bytes};
use oxcover::{Error, Result};

use super::args::{ANY, PNG, YAML, asked, check_outputs, read_ron};

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
    use oxcover::vision::occupancy::Visibility;
    use oxcover::vision::{
        Camera, Fusion, Mapper, MappingConfig, Profile, extent, grid_frame, read_views,
    };
    let config = MappingConfig {
        range: a.range,
        visibility: match a.visibility {
            VisibilityArg::Product => Visibility::Product,
            VisibilityArg::Bayes => Visibility::Bayes,
        },
        fusion: match a.fusion {
            FusionArg::Paper => Fusion::Paper,
            FusionArg::Discounted => Fusion::Discounted,
        },
        ..MappingConfig::default()
    }
    .checked()?;
    // The image is written beside the yaml under the yaml's name: an `--out`
    // that is not a yaml would be overwritten by that image's yaml.
    if a.out.extension().and_then(|e| e.to_str()) != Some("yaml") {
        return Err(Error::BadParameter {
            name: "--out",
            value: a.out.display().to_string(),
            expected: "a map file name ending in .yaml (its image is written beside it as .pgm)"
                .into(),
        });
    }
    let image = a.out.with_extension("pgm");
    let outs = asked([
        ("--out", Some(a.out.as_path()), YAML),
        ("--out's image", Some(image.as_path()), ANY),
        ("--png", a.png.as_deref(), PNG),
    ]);
    check_outputs(&[&a.camera, &a.profile, &a.poses], &outs)?;
    let camera: Camera = read_ron(&a.camera, "camera")?;
    camera.check().map_err(|e| in_file(&a.camera, &e))?;
    let profile: Profile = read_ron(&a.profile, "profile")?;
    profile.check().map_err(|e| in_file(&a.profile, &e))?;
    let views = read_views(&a.poses)?;
    let (lo, hi) = match &a.extent {
        Some(e) => parse_extent(e)?,
        None => extent(&views, config.range),
    };
    let frame = grid_frame(lo, hi, a.resolution)?;
    let mut mapper = Mapper::new(&camera, &profile, frame, config)?;
    for view in &views {
        mapper.add_view(view)?;
    }
    let map = mapper.map();
    // The map and its picture are written as one set.
    let mut files: Vec<(PathBuf, Vec<u8>)> = oxcover::grid::io::ros_map_files(&map, &a.out)?.into();
    if let Some(f) = &a.png {
        let scene = Scene::map_only(&map, "map from camera".into(), Vec::new());
        files.push((f.clone(), render_bytes(&scene, f)?));
    }
    let written = oxcover::output::write_files(files)?;
    let mut out = super::out::stdout();
    let counts = map.counts();
    let _ = writeln!(
        out,
        "{} images fused into {}x{} cells: {} free, {} occupied, {} unknown",
        mapper.views(),
        map.width(),
        map.height(),
        counts.free,
        counts.occupied,
        counts.unknown
    );
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    Ok(())
}

/// A camera or profile file's own check, naming the file.
fn in_file(path: &Path, e: &oxcover::vision::Error) -> Error {
    Error::BadParameter {
        name: "file",
        value: path.display().to_string(),
        expected: format!("a usable description ({e})"),
    }
}

/// `XMIN,YMIN,XMAX,YMAX` in metres.
fn parse_extent(text: &str) -> Result<(Point, Point)> {
    let v: Vec<f64> = text
        .split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect();
    match v.as_slice() {
        [x0, y0, x1, y1] if x1 > x0 && y1 > y0 && v.iter().all(|x| x.is_finite()) => {
            Ok((Point::new(*x0, *y0), Point::new(*x1, *y1)))
        }
        _ => Err(Error::BadParameter {
            name: "--extent",
            value: text.to_string(),
            expected: "XMIN,YMIN,XMAX,YMAX in metres with XMIN < XMAX and YMIN < YMAX".into(),
        }),
    }
}
