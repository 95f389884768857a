//! A mapping run from recorded views: the poses file, the grid the views
//! cover, and the [`Mapper`] that fuses one image after another into it.
//!
//! The poses file is CSV with the header `image,x,y,theta`: a PNG path
//! (relative to the poses file) and the robot's pose when it was taken
//! (metres, radians, map frame). Images are read one at a time, so a run of
//! any length needs the memory of one image and the grid.
//!
//! ```
//! use oxcover_grid::{MapFrame, Point, Pose};
//! use oxcover_vision::{Camera, Distortion, Mapper, MappingConfig, Profile, Projection, RgbImage};
//!
//! // A level pinhole camera 0.3 m above the floor, no lens distortion.
//! let camera = Camera {
//!     width: 160,
//!     height: 120,
//!     distortion: Distortion { uc: 80.0, vc: 60.0, p: [0.0; 3] },
//!     projection: Projection::pinhole(110.0, 0.3, 0.5, -2.0, 0.02, 0.10),
//! };
//! let profile = Profile::new(20).unwrap();
//! let frame = MapFrame::new(40, 40, 0.05, Point::new(-1.0, -1.0));
//! let mut mapper = Mapper::new(&camera, &profile, frame, MappingConfig::default()).unwrap();
//! let grey = RgbImage::filled(camera.width, camera.height, [128, 128, 128]);
//! mapper.add(&grey, Pose::new(0.0, 0.0, 0.0)).unwrap();
//! let map = mapper.map();
//! assert_eq!((map.width(), map.height()), (40, 40));
//! ```

use std::path::{Path, PathBuf};

use oxcover_grid::{MapFrame, OccupancyGrid, Point, Pose};

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::mapping::{MAX_CELLS, MappingConfig, RgbImage, fuse, to_map};
use crate::occupancy::LogOddsGrid;
use crate::profile::Profile;

/// One recorded view: an image file and the robot's pose when it was taken.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// The PNG image.
    pub image: PathBuf,
    /// The robot's pose (map frame).
    pub pose: Pose,
}

/// Reads a poses file (`image,x,y,theta`; image paths relative to it).
///
/// # Errors
/// [`Error::Read`] when it cannot be read; [`Error::Line`] naming the line
/// of a missing header, a short row or a non-finite number, or no view.
pub fn read_views(path: &Path) -> Result<Vec<View>> {
    let text = oxcover_grid::io::limited::read_limited_string(
        path,
        oxcover_grid::io::limited::MAX_TEXT_BYTES,
    )
    .map_err(|e| Error::Read {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    let bad = |line: usize, message: String| Error::Line {
        path: path.display().to_string(),
        line,
        message,
    };
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("image,x,y,theta") {
        return Err(bad(1, "expected the header image,x,y,theta".into()));
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut views = Vec::new();
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
        views.push(View {
            image: dir.join(f[0]),
            pose: Pose::new(num(f[1], "x")?, num(f[2], "y")?, num(f[3], "theta")?),
        });
    }
    if views.is_empty() {
        return Err(bad(2, "no image".into()));
    }
    Ok(views)
}

/// The box `range` around every view's position: `(lower left, upper right)`.
#[must_use]
pub fn extent(views: &[View], range: f64) -> (Point, Point) {
    views.iter().fold(
        (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |(lo, hi), v| {
            (
                Point::new(lo.x.min(v.pose.x - range), lo.y.min(v.pose.y - range)),
                Point::new(hi.x.max(v.pose.x + range), hi.y.max(v.pose.y + range)),
            )
        },
    )
}

/// The grid over `lo..hi` at `resolution`.
///
/// # Errors
/// [`Error::BadParameter`] naming `--resolution` or `--extent` (empty,
/// inverted, not finite, or above [`MAX_CELLS`]).
pub fn grid_frame(lo: Point, hi: Point, resolution: f64) -> Result<MapFrame> {
    let res = crate::error::positive("--resolution", resolution)?;
    let finite = [lo.x, lo.y, hi.x, hi.y].iter().all(|v| v.is_finite());
    if !(finite && hi.x > lo.x && hi.y > lo.y) {
        return Err(Error::BadParameter {
            name: "--extent",
            value: format!("{},{},{},{}", lo.x, lo.y, hi.x, hi.y),
            expected: "XMIN,YMIN,XMAX,YMAX in metres with XMIN < XMAX and YMIN < YMAX",
        });
    }
    let (w, h) = (((hi.x - lo.x) / res).ceil(), ((hi.y - lo.y) / res).ceil());
    if w * h > MAX_CELLS {
        return Err(Error::BadParameter {
            name: "--extent",
            value: format!("{w} x {h} cells"),
            expected: "at most 50 million cells (a smaller extent or a coarser resolution)",
        });
    }
    Ok(MapFrame::new(w as usize, h as usize, res, lo))
}

/// Fuses views into a grid, one image at a time.
#[derive(Debug)]
pub struct Mapper<'a> {
    camera: &'a Camera,
    profile: &'a Profile,
    config: MappingConfig,
    grid: LogOddsGrid,
    views: usize,
}

impl<'a> Mapper<'a> {
    /// A mapper over `frame`, every cell unknown (probability 0.5).
    ///
    /// # Errors
    /// A configuration [`MappingConfig::checked`] refuses; a camera without
    /// pixels; a profile whose counts do not match its bins.
    pub fn new(
        camera: &'a Camera,
        profile: &'a Profile,
        frame: MapFrame,
        config: MappingConfig,
    ) -> Result<Self> {
        camera.check()?;
        profile.check()?;
        Ok(Self {
            camera,
            profile,
            config: config.checked()?,
            grid: LogOddsGrid::new(frame),
            views: 0,
        })
    }

    /// Fuses one image taken at `pose`.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming `image` when its size is not the camera's.
    pub fn add(&mut self, image: &RgbImage, pose: Pose) -> Result<()> {
        if (image.width, image.height) != (self.camera.width, self.camera.height) {
            return Err(Error::ImageSize {
                width: image.width,
                height: image.height,
                camera_width: self.camera.width,
                camera_height: self.camera.height,
            });
        }
        fuse(
            &mut self.grid,
            self.camera,
            self.profile,
            image,
            pose,
            &self.config,
        );
        self.views += 1;
        Ok(())
    }

    /// Reads the view's PNG and fuses it.
    ///
    /// # Errors
    /// The image cannot be read or decoded (naming it), or is not the camera's size.
    pub fn add_view(&mut self, view: &View) -> Result<()> {
        let image = RgbImage::read_png(&view.image)?;
        self.add(&image, view.pose).map_err(|e| match e {
            Error::ImageSize { .. } => Error::Image {
                path: view.image.display().to_string(),
                message: e.to_string(),
            },
            other => other,
        })
    }

    /// Views fused so far.
    #[must_use]
    pub fn views(&self) -> usize {
        self.views
    }

    /// The fused grid (log odds).
    #[must_use]
    pub fn grid(&self) -> &LogOddsGrid {
        &self.grid
    }

    /// The grid as a map: free below, occupied above the configured
    /// thresholds, unknown between.
    #[must_use]
    pub fn map(&self) -> OccupancyGrid {
        to_map(
            &self.grid,
            self.config.free_below,
            self.config.occupied_above,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("oxcover-views-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn poses_are_read_relative_to_their_file() {
        let d = scratch("ok");
        let f = d.join("poses.csv");
        std::fs::write(&f, "image,x,y,theta\na.png,1,2,0.5\n\nb.png, -1 ,0,0\n").unwrap();
        let v = read_views(&f).unwrap();
        assert_eq!(v.len(), 2);
        assert_eq!(v[0].image, d.join("a.png"));
        assert_eq!(v[1].pose, Pose::new(-1.0, 0.0, 0.0));
        let (lo, hi) = extent(&v, 3.0);
        assert_eq!((lo, hi), (Point::new(-4.0, -3.0), Point::new(4.0, 5.0)));
    }

    #[test]
    fn bad_poses_name_the_line() {
        let d = scratch("bad");
        for (text, want) in [
            ("x,y\n", "line 1: expected the header"),
            ("image,x,y,theta\na.png,1,2\n", "line 2: expected 4 fields"),
            ("image,x,y,theta\na.png,1,NaN,0\n", "line 2: y is `NaN`"),
            ("image,x,y,theta\n", "line 2: no image"),
        ] {
            let f = d.join("p.csv");
            std::fs::write(&f, text).unwrap();
            let e = read_views(&f).unwrap_err().to_string();
            assert!(e.contains(want), "{e}");
        }
        let e = read_views(&d.join("absent.csv")).unwrap_err().to_string();
        assert!(e.contains("absent.csv: cannot read"), "{e}");
    }

    #[test]
    fn frames_are_checked() {
        let f = grid_frame(Point::new(0.0, 0.0), Point::new(1.0, 0.5), 0.1).unwrap();
        assert_eq!((f.width(), f.height()), (10, 5));
        assert!(grid_frame(Point::new(1.0, 0.0), Point::new(0.0, 1.0), 0.1).is_err());
        assert!(grid_frame(Point::new(0.0, 0.0), Point::new(1e6, 1e6), 0.1).is_err());
        assert!(grid_frame(Point::new(0.0, 0.0), Point::new(1.0, 1.0), 0.0).is_err());
    }

    #[test]
    fn a_mapper_refuses_images_of_another_size() {
        let camera = crate::camera::test_camera();
        let profile = Profile::new(4).unwrap();
        let frame = MapFrame::new(10, 10, 0.1, Point::origin());
        let mut m = Mapper::new(&camera, &profile, frame, MappingConfig::default()).unwrap();
        let small = RgbImage::filled(3, 3, [0, 0, 0]);
        let e = m.add(&small, Pose::default()).unwrap_err().to_string();
        assert!(e.contains("3x3") && e.contains("the camera's size"), "{e}");
        assert_eq!(m.views(), 0);
        let mut bad = camera;
        bad.width = 0;
        bad.height = 0;
        let e = Mapper::new(&bad, &profile, frame, MappingConfig::default()).unwrap_err();
        assert!(e.to_string().contains("camera is `0x0`"), "{e}");
    }
}
