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
//! The `oxcover map-from-camera` command and `cargo xtask reproduce
//! pavlicek2002-camera` are built on these.

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
