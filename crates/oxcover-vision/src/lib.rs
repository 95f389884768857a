//! # oxcover-vision
//!
//! Occupancy grids from a single floor-facing camera (Pavlíček, Mázl,
//! Štěpán & Přeučil 2002, §2).
//!
//! - [`camera`]: the paper's camera model: radial distortion about
//!   `(u_c, v_c)` with `p₁..p₃` (and its inverse), the floor projection with
//!   `x_cam, y_cam, Δu, Δv, X, Y`, and the rotation by `α + ω_rob` into the
//!   world frame.
//! - [`calibration`]: least-squares calibration (Levenberg–Marquardt on
//!   nalgebra) of the distortion from points on straight lines and of the
//!   projection from pixel–floor pairs, with residuals.
//! - [`profile`]: HSV conversion and the `free`/`occ` count matrices with
//!   `P(R | Occ)` (serialisable).
//! - [`occupancy`]: the paper's Bayes update (log-odds internally) and the
//!   accumulation of visibility along rays from the robot, by product and
//!   by recursive Bayes.
//!
//! - [`synthetic`]: a synthetic camera rendering RGB images of a floor plan
//!   (wall colours, floor texture, lighting, noise, lens distortion) from
//!   robot poses, with the ground truth of every pixel.
//!
//! - [`mapping`]: images to an occupancy grid (one reading per cell and
//!   image, visibility, Bayes fusion by the paper's formula or discounted by
//!   visibility), profile learning from labelled images, the grid as a
//!   contract map, scores against the truth (IoU and per-class accuracy),
//!   PNG input and output.
//!
//! - [`views`]: a mapping run from recorded views (the poses file, the grid
//!   they cover, a [`Mapper`] fusing one image at a time).
//!
//! The `oxcover map-from-camera` command and `cargo xtask reproduce
//! pavlicek2002-camera` are built on these.
//!
//! ```
//! use oxcover_grid::{MapFrame, Occupancy, Point, Pose};
//! use oxcover_vision::{Camera, Distortion, Mapper, MappingConfig, Profile, Projection, RgbImage};
//!
//! // A level pinhole camera 0.3 m above the floor, no lens distortion.
//! let camera = Camera {
//!     width: 160,
//!     height: 120,
//!     distortion: Distortion { uc: 80.0, vc: 60.0, p: [0.0; 3] },
//!     projection: Projection::pinhole(110.0, 0.3, 0.5, -2.0, 0.02, 0.10),
//! };
//! // A profile that has seen this grey only on the floor.
//! let grey = [120, 120, 120];
//! let mut profile = Profile::new(20).unwrap();
//! for _ in 0..100 {
//!     profile.add(grey, false);
//! }
//! // One grey view from the origin, facing +x.
//! let frame = MapFrame::new(60, 60, 0.05, Point::new(-1.5, -1.5));
//! let mut mapper = Mapper::new(&camera, &profile, frame, MappingConfig::default()).unwrap();
//! mapper.add(&RgbImage::filled(160, 120, grey), Pose::new(0.0, 0.0, 0.0)).unwrap();
//! let map = mapper.map();
//! // The floor ahead of the camera is free; what it never saw stays unknown.
//! let ahead = map.frame().cell_at(&Point::new(0.8, 0.0)).unwrap();
//! let behind = map.frame().cell_at(&Point::new(-1.0, 0.0)).unwrap();
//! assert_eq!(map.cells()[ahead], Occupancy::Free);
//! assert_eq!(map.cells()[behind], Occupancy::Unknown);
//! ```

pub mod calibration;
pub mod camera;
pub mod error;
pub mod mapping;
pub mod occupancy;
pub mod profile;
pub mod synthetic;
pub mod views;

pub use calibration::{Fit, FloorPair, calibrate_distortion, calibrate_projection};
pub use camera::{Camera, Distortion, Projection};
pub use error::{Error, Result};
pub use mapping::{
    Fusion, MappingConfig, RgbImage, Scores, fuse, learn_profile, on_floor, readings, score,
    seen_region, to_map,
};
pub use occupancy::{LogOddsGrid, Visibility, accumulated, bayes, with_visibility};
pub use profile::{Profile, hsv};
pub use synthetic::{Lighting, Rendered, Seen, SyntheticScene};
pub use views::{Mapper, View, extent, grid_frame, read_views};
