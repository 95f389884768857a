//! A synthetic camera: RGB images of a floor plan seen from robot poses,
//! with exact ground truth, so the pipeline can be tested end to end without
//! hardware.
//!
//! The scene is an occupancy grid (the truth) whose occupied cells are
//! walls taller than the camera, each cell with its own colour, on a floor
//! of one colour with a faint per-cell texture. The camera is the level
//! pinhole the paper's model describes ([`crate::camera::Projection::pinhole`]:
//! height `H = −X`, focal length `f = Y / X`), behind the lens distortion of
//! [`Distortion`](crate::camera::Distortion). For each pixel the renderer
//! undistorts it, casts its ray over the grid in steps of a quarter cell,
//! and shows the first wall it meets or else the floor where the ray comes
//! down (or a grey background beyond `max_range`). Lighting scales and tints
//! the whole image; seeded Gaussian noise is added per channel.

use oxcover_grid::{Cell, Grid, OccupancyGrid, Point, Pose};
use serde::{Deserialize, Serialize};

use crate::camera::Camera;

/// What a pixel shows (the ground truth).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Seen {
    /// The floor, at this cell.
    Floor(Cell),
    /// A wall (an occupied cell).
    Wall(Cell),
    /// Nothing within range.
    Background,
}

/// Lighting of one image.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lighting {
    /// Overall brightness factor.
    pub gain: f64,
    /// Per-channel tint factors (RGB).
    pub tint: [f64; 3],
    /// Standard deviation of the additive pixel noise (0–255 scale).
    pub noise: f64,
}

impl Default for Lighting {
    fn default() -> Self {
        Self {
            gain: 1.0,
            tint: [1.0; 3],
            noise: 0.0,
        }
    }
}

/// The scene and the renderer's settings.
#[derive(Clone, Debug)]
pub struct SyntheticScene<'a> {
    /// The floor plan (occupied cells are walls).
    pub map: &'a OccupancyGrid,
    /// Floor colour.
    pub floor: [u8; 3],
    /// Colour of each occupied cell.
    pub walls: &'a Grid<[u8; 3]>,
    /// Background colour (beyond range).
    pub background: [u8; 3],
    /// Longest distance rendered (m).
    pub max_range: f64,
}

/// An RGB image with its ground truth.
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// Pixels, row-major from the top-left.
    pub rgb: Vec<[u8; 3]>,
    /// What each pixel shows.
    pub truth: Vec<Seen>,
}

impl Rendered {
    /// The pixel at `(u, v)` (column, row).
    #[must_use]
    pub fn at(&self, u: u32, v: u32) -> [u8; 3] {
        self.rgb[(v * self.width + u) as usize]
    }
}

impl SyntheticScene<'_> {
    /// Renders what `camera` sees from `robot = (x, y, ω)`; `seed` drives
    /// the noise.
    #[must_use]
    pub fn render(&self, camera: &Camera, robot: Pose, light: &Lighting, seed: u64) -> Rendered {
        let p = camera.projection;
        let h = -p.big_x;
        let f = p.big_y / p.big_x;
        let frame = self.map.frame();
        let step = frame.resolution() / 4.0;
        let origin = p.to_world(robot, Point::new(p.x_cam, p.y_cam));
        let mut rng = SplitMix(seed);
        let (w, ht) = (camera.width, camera.height);
        let mut rgb = Vec::with_capacity((w * ht) as usize);
        let mut truth = Vec::with_capacity((w * ht) as usize);
        for v in 0..ht {
            for u in 0..w {
                let q = camera
                    .distortion
                    .undistort(f64::from(u) + 0.5, f64::from(v) + 0.5);
                let (up, vp) = (q.x, q.y);
                // The ray per metre ahead: lateral and down.
                let (lat, down) = ((up - p.du) / f, (vp - p.dv) / f);
                let ground = if down > 0.0 { h / down } else { f64::INFINITY };
                // Its direction on the floor, in the world.
                let ahead = p.to_world(robot, Point::new(p.x_cam + lat, p.y_cam + 1.0));
                let (dx, dy) = (ahead.x - origin.x, ahead.y - origin.y);
                let norm = dx.hypot(dy);
                let limit = ground.min(self.max_range);
                let dt = step / norm.max(1e-9);
                let mut t = 0.0f64;
                let mut seen = Seen::Background;
                loop {
                    let tt = t.min(limit);
                    let q = oxcover_grid::Point::new(origin.x + dx * tt, origin.y + dy * tt);
                    let Some(c) = frame.cell_at(&q) else {
                        break;
                    };
                    if !self.map.is_free(c) {
                        seen = Seen::Wall(c);
                        break;
                    }
                    if tt >= ground {
                        seen = Seen::Floor(c);
                        break;
                    }
                    if tt >= limit {
                        break;
                    }
                    t += dt;
                }
                let base = match seen {
                    Seen::Floor(c) => texture(self.floor, c),
                    Seen::Wall(c) => self.walls[c],
                    Seen::Background => self.background,
                };
                let mut px = [0u8; 3];
                for k in 0..3 {
                    let x = f64::from(base[k]) * light.gain * light.tint[k]
                        + light.noise * rng.normal();
                    px[k] = x.round().clamp(0.0, 255.0) as u8;
                }
                rgb.push(px);
                truth.push(seen);
            }
        }
        Rendered {
            width: w,
            height: ht,
            rgb,
            truth,
        }
    }
}

/// The floor colour with a faint fixed texture per cell (±4 levels).
fn texture(c: [u8; 3], cell: Cell) -> [u8; 3] {
    let hsh =
        (cell.row as u64).wrapping_mul(0x9E37_79B9) ^ (cell.col as u64).wrapping_mul(0x85EB_CA6B);
    let d = (hsh % 9) as i32 - 4;
    c.map(|x| (i32::from(x) + d).clamp(0, 255) as u8)
}

/// A small seeded generator (SplitMix64) with Box–Muller normals: the
/// renderer's noise, and the experiments' (same seed, same numbers on any
/// machine).
#[derive(Clone, Debug)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// A uniform number in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal number.
    pub fn normal(&mut self) -> f64 {
        let (a, b) = (self.uniform(), self.uniform());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Distortion, Projection};
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn the_floor_below_and_the_wall_ahead_are_where_the_model_says() {
        // A corridor 10 m long at 0.1 m cells, a wall across it at x = 4 m.
        let mut rows = vec![".".repeat(100); 11];
        for r in &mut rows {
            r.replace_range(40..41, "#");
        }
        let (map, _) = parse_ascii(&rows.join("\n")).unwrap();
        let map = OccupancyGrid::new(map.cells().clone(), 0.1, oxcover_grid::Point::new(0.0, 0.0));
        let walls = Grid::new(map.width(), map.height(), [40, 60, 140]);
        let scene = SyntheticScene {
            map: &map,
            floor: [200, 180, 150],
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
            projection: Projection::pinhole(110.0, 0.3, 0.0, -5.0, 0.0, 0.0),
        };
        // Robot at (1, 0.55) heading +x: the wall is 3 m ahead.
        let robot = Pose::new(1.0, 0.55, 0.0);
        let img = scene.render(&cam, robot, &Lighting::default(), 1);
        assert_eq!(img.rgb.len(), 160 * 120);
        // Every floor pixel's cell is where the camera model puts its centre.
        let mut floors = 0;
        for v in 0..120 {
            for u in 0..160 {
                if let Seen::Floor(c) = img.truth[(v * 160 + u) as usize] {
                    floors += 1;
                    let w = cam
                        .pixel_to_world(robot, f64::from(u) + 0.5, f64::from(v) + 0.5)
                        .expect("below the horizon");
                    let q = map.frame().cell_at(&oxcover_grid::Point::new(w.x, w.y));
                    assert_eq!(q, Some(c), "pixel {u},{v}");
                }
            }
        }
        assert!(floors > 3000, "{floors}");
        // Straight ahead at the horizon row: the wall, coloured as given.
        let (u, v) = {
            let p = cam.world_to_pixel(robot, Point::new(3.5, 0.55)).unwrap();
            (p.x, p.y)
        };
        assert!(matches!(
            img.truth[(v as u32 * 160 + u as u32) as usize],
            Seen::Floor(_)
        ));
        let row = (cam.distortion.vc + cam.projection.dv) as u32;
        assert!(matches!(
            img.truth[(row * 160 + 80) as usize],
            Seen::Wall(_)
        ));
        assert_eq!(img.at(80, row), [40, 60, 140]);
        // Lighting and noise change colours, seeded.
        let dim = Lighting {
            gain: 0.7,
            tint: [1.0, 0.95, 0.9],
            noise: 3.0,
        };
        let a = scene.render(&cam, robot, &dim, 5);
        assert_eq!(a, scene.render(&cam, robot, &dim, 5));
        assert_ne!(a.rgb, scene.render(&cam, robot, &dim, 6).rgb);
        assert_eq!(a.truth, img.truth);
    }
}
