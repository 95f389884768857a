//! From camera images to an occupancy grid (Pavlíček 2002, §2.1–2.2), and how
//! good the grid is against the truth.
//!
//! For every image and every grid cell within `range` of the camera, the
//! cell's centre is projected into the image ([`Camera::world_to_pixel`]);
//! if it lands inside, the pixel's colour gives `P(R | Occ)` from the
//! profile: the image "transformed into floor coordinates" of the paper's
//! Fig. 5, one reading per cell and image. Visibility is then accumulated
//! along rays from the camera ([`accumulated`]) and the result fused into
//! the grid by Bayes ([`LogOddsGrid::observe`]), either by the paper's
//! formula or with the evidence discounted by visibility ([`Fusion`]).
//!
//! Learning a profile ([`learn_profile`]) counts every pixel of labelled
//! images: floor pixels as free, wall pixels as occupied (the range finder
//! or the map gives these labels in the paper; the synthetic camera's
//! ground truth here).

use oxcover_grid::{Grid, MapFrame, Occupancy, OccupancyGrid, Point, Pose};
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::occupancy::{LogOddsGrid, Visibility, accumulated};
use crate::profile::Profile;
use crate::synthetic::{Rendered, Seen};

/// No single reading is taken as more certain than this (either way): the
/// paper's profile answers 1 for a colour it never saw, and one such pixel
/// would otherwise outvote every other view of the cell.
pub const READING_FLOOR: f64 = 0.05;

/// Cells fused below this probability of being occupied are free.
pub const FREE_BELOW: f64 = 0.35;
/// Cells fused above this probability of being occupied are occupied.
pub const OCCUPIED_ABOVE: f64 = 0.65;
/// The largest grid a run builds, in cells.
pub const MAX_CELLS: f64 = 50_000_000.0;

/// How views become a map.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MappingConfig {
    /// Farthest floor distance read from an image, in metres.
    pub range: f64,
    /// How visibility is accumulated along rays from the camera.
    pub visibility: Visibility,
    /// How visibility enters the grid.
    pub fusion: Fusion,
    /// Free below this probability of being occupied ([`FREE_BELOW`]).
    pub free_below: f64,
    /// Occupied above this probability ([`OCCUPIED_ABOVE`]); unknown between.
    pub occupied_above: f64,
}

impl Default for MappingConfig {
    /// 3 m range, product visibility, the paper's fusion, the thresholds above.
    fn default() -> Self {
        Self {
            range: 3.0,
            visibility: Visibility::Product,
            fusion: Fusion::Paper,
            free_below: FREE_BELOW,
            occupied_above: OCCUPIED_ABOVE,
        }
    }
}

impl MappingConfig {
    /// The configuration, checked.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming `--range` or the thresholds.
    pub fn checked(self) -> Result<Self> {
        crate::error::positive("--range", self.range)?;
        let in_unit = |v: f64| (0.0..=1.0).contains(&v);
        if !(in_unit(self.free_below)
            && in_unit(self.occupied_above)
            && self.free_below <= self.occupied_above)
        {
            return Err(Error::BadParameter {
                name: "thresholds",
                value: format!("{} / {}", self.free_below, self.occupied_above),
                expected: "0 <= free_below <= occupied_above <= 1",
            });
        }
        Ok(self)
    }
}

/// An RGB image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// Pixels, row-major from the top-left.
    pub rgb: Vec<[u8; 3]>,
}

impl RgbImage {
    /// An image of one colour.
    #[must_use]
    pub fn filled(width: u32, height: u32, rgb: [u8; 3]) -> Self {
        Self {
            width,
            height,
            rgb: vec![rgb; width as usize * height as usize],
        }
    }

    /// Reads a PNG (grey, grey with alpha, RGB or RGBA; alpha ignored).
    ///
    /// # Errors
    /// [`Error::Image`] naming the file: unreadable, not a PNG, truncated,
    /// or more than 50 million pixels.
    pub fn read_png(path: &Path) -> Result<Self> {
        let fail = |message: String| Error::Image {
            path: path.display().to_string(),
            message,
        };
        let bytes = oxcover_grid::io::limited::read_limited_after(
            path,
            oxcover_grid::io::limited::MAX_MAP_BYTES,
            |head| {
                if head.is_empty() || head.starts_with(b"\x89PNG") {
                    Ok(())
                } else {
                    Err(format!(
                        "not a PNG: it begins with {}",
                        oxcover_grid::io::limited::hex_head(head)
                    ))
                }
            },
        )
        .map_err(|e| fail(format!("cannot read it: {e}")))?;
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
        reader.set_format(image::ImageFormat::Png);
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(20_000);
        limits.max_image_height = Some(20_000);
        limits.max_alloc = Some(200 * 1024 * 1024);
        reader.limits(limits);
        let img = reader
            .decode()
            .map_err(|e| fail(format!("not a readable PNG image ({e})")))?
            .to_rgb8();
        Ok(Self {
            width: img.width(),
            height: img.height(),
            rgb: img.pixels().map(|p| p.0).collect(),
        })
    }

    /// Writes the image as an RGB PNG.
    ///
    /// # Errors
    /// [`Error::Image`] when the file cannot be written.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let flat: Vec<u8> = self.rgb.iter().flatten().copied().collect();
        image::save_buffer(
            path,
            &flat,
            self.width,
            self.height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| Error::Image {
            path: path.display().to_string(),
            message: format!("cannot write it ({e})"),
        })
    }
}

impl From<&Rendered> for RgbImage {
    fn from(r: &Rendered) -> Self {
        Self {
            width: r.width,
            height: r.height,
            rgb: r.rgb.clone(),
        }
    }
}

/// Counts the pixels of labelled images into a profile.
pub fn learn_profile(profile: &mut Profile, images: &[Rendered]) {
    for img in images {
        for (px, seen) in img.rgb.iter().zip(&img.truth) {
            match seen {
                Seen::Floor(_) => profile.add(*px, false),
                Seen::Wall(_) => profile.add(*px, true),
                Seen::Background => {}
            }
        }
    }
}

/// The image laid on the floor (the paper's Fig. 5): for each cell within
/// `range` of the camera, the colour of the pixel its centre projects to,
/// `None` where it falls outside the image or out of range.
#[must_use]
pub fn on_floor(
    frame: &MapFrame,
    camera: &Camera,
    image: &RgbImage,
    robot: Pose,
    range: f64,
) -> Grid<Option<[u8; 3]>> {
    let eye = camera.projection.to_world(
        robot,
        Point::new(camera.projection.x_cam, camera.projection.y_cam),
    );
    Grid::from_fn(frame.width(), frame.height(), |c| {
        let q = frame.cell_center(c);
        if (q.x - eye.x).hypot(q.y - eye.y) > range {
            return None;
        }
        let px = camera.world_to_pixel(robot, Point::new(q.x, q.y))?;
        let (u, v) = (px.x, px.y);
        (u >= 0.0 && v >= 0.0 && u < f64::from(image.width) && v < f64::from(image.height))
            .then(|| image.rgb[(v as u32 * image.width + u as u32) as usize])
    })
}

/// One image's reading per cell (`P(R | Occ)` of [`on_floor`]'s colour,
/// NaN where unseen).
#[must_use]
pub fn readings(
    frame: &MapFrame,
    camera: &Camera,
    profile: &Profile,
    image: &RgbImage,
    robot: Pose,
    range: f64,
) -> Grid<f64> {
    let colours = on_floor(frame, camera, image, robot, range);
    Grid::from_fn(frame.width(), frame.height(), |c| {
        colours[c].map_or(f64::NAN, |rgb| profile.p_occ(rgb))
    })
}

/// How a view's readings, corrected for visibility, enter the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Fusion {
    /// The paper's `P_new(Occ) = 1 − E · E_acc`: a cell hidden behind an
    /// obstacle reads occupied.
    Paper,
    /// The reading's evidence scaled by how visible the cell is,
    /// `0.5 + (P − 0.5) · E_acc`: a hidden cell tells nothing, so views from
    /// which it is visible decide it.
    Discounted,
}

/// Fuses one image taken at `robot` into `grid`: its readings within
/// `config.range`, visibility accumulated by `config.visibility` and
/// entered by `config.fusion` ([`crate::Mapper`] runs this per view).
pub fn fuse(
    grid: &mut LogOddsGrid,
    camera: &Camera,
    profile: &Profile,
    image: &RgbImage,
    robot: Pose,
    config: &MappingConfig,
) {
    let frame = *grid.frame();
    let seen = readings(&frame, camera, profile, image, robot, config.range);
    let eye = camera.projection.to_world(
        robot,
        Point::new(camera.projection.x_cam, camera.projection.y_cam),
    );
    let acc = accumulated(&seen, &frame, Point::new(eye.x, eye.y), config.visibility);
    for c in acc.cells() {
        let (p, v) = (seen[c], acc[c]);
        if p.is_nan() || v.is_nan() {
            continue;
        }
        let p = match config.fusion {
            Fusion::Paper => 1.0 - (1.0 - p) * v,
            Fusion::Discounted => 0.5 + (p - 0.5) * v,
        };
        grid.observe(c, p.clamp(READING_FLOOR, 1.0 - READING_FLOOR));
    }
}

/// The grid as a map: free below `free_below`, occupied above
/// `occupied_above`, unknown between (never free, as the contract says).
#[must_use]
pub fn to_map(grid: &LogOddsGrid, free_below: f64, occupied_above: f64) -> OccupancyGrid {
    let f = grid.frame();
    let cells = Grid::from_fn(f.width(), f.height(), |c| {
        let p = grid.probability(c);
        if p < free_below {
            Occupancy::Free
        } else if p > occupied_above {
            Occupancy::Occupied
        } else {
            Occupancy::Unknown
        }
    });
    OccupancyGrid::new(cells, f.resolution(), f.origin())
}

/// A built map scored against the truth.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scores {
    /// Free space: |built free ∩ true free| / |built free ∪ true free|.
    pub iou_free: f64,
    /// Obstacles: the same for occupied.
    pub iou_occupied: f64,
    /// True free cells the map calls free, of those it decided (free or occupied).
    pub accuracy_free: f64,
    /// True occupied cells the map calls occupied, of those it decided.
    pub accuracy_occupied: f64,
    /// Cells decided, of all cells.
    pub decided: f64,
}

/// Scores `built` against `truth` (same frame), over the cells of `region`
/// (e.g. the part of the plan the robot could see), or all cells.
#[must_use]
pub fn score(built: &OccupancyGrid, truth: &OccupancyGrid, region: Option<&Grid<bool>>) -> Scores {
    let (mut tp_f, mut fp_f, mut fn_f) = (0usize, 0usize, 0usize);
    let (mut tp_o, mut fp_o, mut fn_o) = (0usize, 0usize, 0usize);
    let (mut free_ok, mut free_decided, mut occ_ok, mut occ_decided) = (0, 0, 0, 0);
    let (mut decided, mut total) = (0usize, 0usize);
    for c in truth.cells().cells() {
        if region.is_some_and(|r| !r[c]) {
            continue;
        }
        total += 1;
        let (t, b) = (truth.cells()[c], built.cells()[c]);
        let t_free = t == Occupancy::Free;
        let (b_free, b_occ) = (b == Occupancy::Free, b == Occupancy::Occupied);
        if b_free || b_occ {
            decided += 1;
            if t_free {
                free_decided += 1;
                free_ok += usize::from(b_free);
            } else {
                occ_decided += 1;
                occ_ok += usize::from(b_occ);
            }
        }
        match (t_free, b_free) {
            (true, true) => tp_f += 1,
            (false, true) => fp_f += 1,
            (true, false) => fn_f += 1,
            _ => {}
        }
        match (!t_free, b_occ) {
            (true, true) => tp_o += 1,
            (false, true) => fp_o += 1,
            (true, false) => fn_o += 1,
            _ => {}
        }
    }
    let ratio = |a: usize, b: usize| if b == 0 { 1.0 } else { a as f64 / b as f64 };
    Scores {
        iou_free: ratio(tp_f, tp_f + fp_f + fn_f),
        iou_occupied: ratio(tp_o, tp_o + fp_o + fn_o),
        accuracy_free: ratio(free_ok, free_decided),
        accuracy_occupied: ratio(occ_ok, occ_decided),
        decided: ratio(decided, total),
    }
}

/// The cells a camera could see along a drive: within `range`, in the
/// image, not behind a wall (the truth's visibility), for scoring.
#[must_use]
pub fn seen_region(truth: &OccupancyGrid, rendered: &[Rendered]) -> Grid<bool> {
    let mut seen = Grid::new(truth.width(), truth.height(), false);
    for img in rendered {
        for s in &img.truth {
            if let Seen::Floor(c) | Seen::Wall(c) = *s {
                seen[c] = true;
            }
        }
    }
    seen
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Distortion, Projection};
    use crate::occupancy::Visibility;
    use crate::synthetic::{Lighting, SyntheticScene};

    #[test]
    fn a_drive_through_a_room_builds_its_map() {
        // A 6 m × 4 m room at 5 cm: walls round it, a pillar and a desk.
        let (w, h) = (120, 80);
        let truth_cells = Grid::from_fn(w, h, |c| {
            let (x, y) = (
                c.col as f64 * 0.05 + 0.025,
                (h - 1 - c.row) as f64 * 0.05 + 0.025,
            );
            let wall = x < 0.1 || y < 0.1 || x > 5.9 || y > 3.9;
            let pillar = (x - 2.0).hypot(y - 2.5) < 0.3;
            let desk = (3.5..4.5).contains(&x) && (0.8..1.4).contains(&y);
            if wall || pillar || desk {
                Occupancy::Occupied
            } else {
                Occupancy::Free
            }
        });
        let truth = OccupancyGrid::new(truth_cells, 0.05, Point::new(0.0, 0.0));
        let walls = Grid::from_fn(w, h, |c| {
            if c.col % 7 < 3 {
                [60, 70, 150]
            } else {
                [150, 60, 50]
            }
        });
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
        // Learn on a few views, then map from a loop round the room.
        let poses: Vec<(f64, f64, f64)> = (0..24)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 24.0;
                (3.0 + 1.6 * a.cos(), 2.0 + 1.0 * a.sin(), a + 1.9)
            })
            .collect();
        let light = Lighting {
            gain: 1.0,
            tint: [1.0; 3],
            noise: 2.0,
        };
        let rendered: Vec<Rendered> = poses
            .iter()
            .enumerate()
            .map(|(k, &(x, y, t))| scene.render(&cam, Pose::new(x, y, t), &light, k as u64))
            .collect();
        let mut profile = Profile::new(20).unwrap();
        learn_profile(&mut profile, &rendered[..6]);
        let region = seen_region(&truth, &rendered);
        for mode in [Visibility::Product, Visibility::Bayes] {
            let build = |fusion: Fusion| {
                let config = crate::MappingConfig {
                    visibility: mode,
                    fusion,
                    ..crate::MappingConfig::default()
                };
                let mut mapper =
                    crate::Mapper::new(&cam, &profile, *truth.frame(), config).unwrap();
                for (img, &(x, y, t)) in rendered.iter().zip(&poses) {
                    mapper
                        .add(&RgbImage::from(img), Pose::new(x, y, t))
                        .unwrap();
                }
                score(&mapper.map(), &truth, Some(&region))
            };
            // The paper's fusion: hidden cells read occupied, which keeps
            // obstacles but also darkens free floor seen past them.
            let paper = build(Fusion::Paper);
            assert!(paper.iou_free > 0.6, "{mode:?}: {paper:?}");
            assert!(paper.accuracy_occupied > 0.8, "{mode:?}: {paper:?}");
            // Discounted: hidden cells tell nothing; free space is better.
            let s = build(Fusion::Discounted);
            assert!(
                s.iou_free > 0.9 && s.iou_free > paper.iou_free,
                "{mode:?}: {s:?}"
            );
            assert!(s.accuracy_free > 0.95, "{mode:?}: {s:?}");
            // PNG round trip of a camera image.
            let file =
                std::env::temp_dir().join(format!("oxcover-vision-{}.png", std::process::id()));
            let img = RgbImage::from(&rendered[0]);
            img.write_png(&file).unwrap();
            assert_eq!(RgbImage::read_png(&file).unwrap(), img);
            std::fs::write(&file, b"\x89PNG\r\n\x1a\n truncated").unwrap();
            let e = RgbImage::read_png(&file).unwrap_err().to_string();
            assert!(e.contains("oxcover-vision") && e.contains("PNG"), "{e}");
            let _ = std::fs::remove_file(&file);
        }
    }
}
