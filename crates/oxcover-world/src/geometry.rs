//! Geometry for ray casting and clearances: the one module that uses parry2d.
//!
//! parry2d does the ray casts; its API changes often, so it stays behind
//! this module: callers see metres and radians only.
//!
//! - [`WorldGeometry`]: a polygonal world's boundary curves (parry polylines
//!   and balls), with exact clearances from the polygons themselves.
//! - [`Obstacles`]: an occupancy grid's blocked space. Every cell that is not
//!   free (occupied or unknown) becomes part of a box: the blocked cells of
//!   each row are merged into runs, each run one cuboid, and the map's outside
//!   is walled by four boxes along its edges. The boxes form one parry
//!   `Compound`, whose bounding-volume tree makes a cast cost about
//!   logarithmic in the number of boxes.

use oxcover_grid::traverse::segment_distance;
use oxcover_grid::{Cell, OccupancyGrid, Point};
use parry2d::math::{Pose, Vector};
use parry2d::query::{Ray, RayCast};
use parry2d::shape::{Ball, Compound, Polyline, SharedShape};

use crate::world::{Outline, World};

/// The blocked space of a map, for ray casts.
pub struct Obstacles {
    compound: Compound,
}

impl std::fmt::Debug for Obstacles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Obstacles")
            .field("boxes", &self.compound.shapes().len())
            .finish()
    }
}

impl Obstacles {
    /// The non-free cells of `map` and walls around it.
    #[must_use]
    pub fn from_map(map: &OccupancyGrid) -> Self {
        let frame = map.frame();
        let res = frame.resolution();
        let free = map.free_mask();
        let mut shapes: Vec<(Pose, SharedShape)> = Vec::new();
        let mut boxed = |cx: f64, cy: f64, hx: f64, hy: f64| {
            shapes.push((
                Pose::from_translation(Vector::new(cx as f32, cy as f32)),
                SharedShape::cuboid(hx as f32, hy as f32),
            ));
        };
        for r in 0..free.height() {
            let mut c = 0;
            while c < free.width() {
                if free[Cell::new(r, c)] {
                    c += 1;
                    continue;
                }
                let c0 = c;
                while c < free.width() && !free[Cell::new(r, c)] {
                    c += 1;
                }
                let (a, b) = (
                    frame.cell_center(Cell::new(r, c0)),
                    frame.cell_center(Cell::new(r, c - 1)),
                );
                boxed(
                    (a.x + b.x) / 2.0,
                    a.y,
                    (b.x - a.x).abs() / 2.0 + res / 2.0,
                    res / 2.0,
                );
            }
        }
        // Walls one metre thick around the map's extent.
        let (w, h) = (free.width() as f64 * res, free.height() as f64 * res);
        let o = frame.cell_center(Cell::new(free.height().saturating_sub(1), 0));
        let (x0, y0) = (o.x - res / 2.0, o.y - res / 2.0);
        let t = 1.0;
        boxed(x0 - t / 2.0, y0 + h / 2.0, t / 2.0, h / 2.0 + t);
        boxed(x0 + w + t / 2.0, y0 + h / 2.0, t / 2.0, h / 2.0 + t);
        boxed(x0 + w / 2.0, y0 - t / 2.0, w / 2.0 + t, t / 2.0);
        boxed(x0 + w / 2.0, y0 + h + t / 2.0, w / 2.0 + t, t / 2.0);
        Self {
            compound: Compound::new(shapes),
        }
    }

    /// Distance (m) from `(x, y)` along heading `angle` to the first
    /// obstacle, if one lies within `max_range`; 0 from inside an obstacle.
    #[must_use]
    pub fn cast(&self, origin: Point, angle: f64, max_range: f64) -> Option<f64> {
        let (x, y) = (origin.x, origin.y);
        let ray = Ray::new(
            Vector::new(x as f32, y as f32),
            Vector::new(angle.cos() as f32, angle.sin() as f32),
        );
        self.compound
            .cast_ray(&Pose::IDENTITY, &ray, max_range as f32, true)
            .map(f64::from)
    }
}

/// Something range rays can be cast against.
pub trait RayCaster {
    /// Distance (m) from `origin` along heading `angle` to the first surface
    /// within `max_range`, and which surface it is (0 when the caster does
    /// not tell surfaces apart).
    fn cast_surface(&self, origin: Point, angle: f64, max_range: f64) -> Option<(f64, usize)>;
}

impl RayCaster for Obstacles {
    fn cast_surface(&self, origin: Point, angle: f64, max_range: f64) -> Option<(f64, usize)> {
        self.cast(origin, angle, max_range).map(|d| (d, 0))
    }
}

/// A polygon edge and its surface.
type Edge = (Point, Point, usize);

/// A world's boundary curves for ray casts (parry2d) and exact clearances.
pub struct WorldGeometry {
    shapes: Vec<CurveShape>,
    /// Every polygon edge with its surface, for exact distances.
    segments: Vec<Edge>,
    circles: Vec<(Point, f64, usize)>,
    world: World,
}

enum CurveShape {
    Polyline(Polyline),
    Ball(Point, Ball),
}

impl std::fmt::Debug for WorldGeometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WorldGeometry")
            .field("world", &self.world.name)
            .field("curves", &self.shapes.len())
            .finish()
    }
}

impl WorldGeometry {
    /// The curves of `world`.
    #[must_use]
    pub fn new(world: &World) -> Self {
        let mut shapes = Vec::new();
        let mut segments = Vec::new();
        let mut circles = Vec::new();
        for (surface, outline) in world.outlines().into_iter().enumerate() {
            match outline {
                Outline::Polygon(v) => {
                    let n = v.len();
                    for i in 0..n {
                        segments.push((v[i], v[(i + 1) % n], surface));
                    }
                    let vertices = v
                        .iter()
                        .map(|p| Vector::new(p.x as f32, p.y as f32))
                        .collect();
                    let indices = (0..n as u32).map(|i| [i, (i + 1) % n as u32]).collect();
                    shapes.push(CurveShape::Polyline(Polyline::new(vertices, Some(indices))));
                }
                Outline::Circle { centre, radius } => {
                    circles.push((centre, radius, surface));
                    shapes.push(CurveShape::Ball(centre, Ball::new(radius as f32)));
                }
            }
        }
        Self {
            shapes,
            segments,
            circles,
            world: world.clone(),
        }
    }

    /// The world.
    #[must_use]
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Exact distance from `p` to the nearest boundary curve, and that
    /// curve (0 the outer boundary, `k` obstacle `k − 1`); negative when `p`
    /// is not free.
    #[must_use]
    pub fn clearance(&self, p: Point) -> (f64, usize) {
        let mut best = (f64::INFINITY, 0);
        for &(a, b, s) in &self.segments {
            let d = segment_distance(Point::new(a.x, a.y), Point::new(b.x, b.y), p);
            if d < best.0 {
                best = (d, s);
            }
        }
        for &(c, r, s) in &self.circles {
            let d = ((p.x - c.x).hypot(p.y - c.y) - r).abs();
            if d < best.0 {
                best = (d, s);
            }
        }
        if !self.world.is_free(p) {
            best.0 = -best.0;
        }
        best
    }
}

impl RayCaster for WorldGeometry {
    fn cast_surface(&self, origin: Point, angle: f64, max_range: f64) -> Option<(f64, usize)> {
        let dir = Vector::new(angle.cos() as f32, angle.sin() as f32);
        let mut best: Option<(f64, usize)> = None;
        for (surface, shape) in self.shapes.iter().enumerate() {
            let hit = match shape {
                CurveShape::Polyline(p) => {
                    let ray = Ray::new(Vector::new(origin.x as f32, origin.y as f32), dir);
                    p.cast_ray(&Pose::IDENTITY, &ray, max_range as f32, false)
                }
                CurveShape::Ball(c, b) => {
                    let ray = Ray::new(
                        Vector::new((origin.x - c.x) as f32, (origin.y - c.y) as f32),
                        dir,
                    );
                    b.cast_ray(&Pose::IDENTITY, &ray, max_range as f32, true)
                }
            };
            if let Some(t) = hit {
                let t = f64::from(t);
                if best.is_none_or(|(d, _)| t < d) {
                    best = Some((t, surface));
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn rays_hit_known_geometry() {
        // 10×5 cells of 1 m; a wall block at columns 6..=7 of rows 1..=3.
        let (map, _) = parse_ascii(
            "
            ..........
            ......##..
            ......##..
            ......##..
            ..........
            ",
        )
        .unwrap();
        let obs = Obstacles::from_map(&map);
        // Row 2 is y ∈ [2, 3] (rows count down from the top; the map is 5 m tall).
        let d = obs.cast(Point::new(1.5, 2.5), 0.0, 20.0).unwrap();
        assert!((d - 4.5).abs() < 1e-4, "{d}");
        // Backwards to the left map edge.
        let d = obs.cast(Point::new(1.5, 2.5), PI, 20.0).unwrap();
        assert!((d - 1.5).abs() < 1e-4, "{d}");
        // Up to the top edge, and nothing within a short range.
        let d = obs.cast(Point::new(1.5, 2.5), FRAC_PI_2, 20.0).unwrap();
        assert!((d - 2.5).abs() < 1e-4, "{d}");
        assert_eq!(obs.cast(Point::new(1.5, 2.5), FRAC_PI_2, 1.0), None);
        // Diagonal: 45° from Point::new(4.0, 0.5) meets the block's left face (x = 6,
        // y ∈ [1, 4]) at y = 2.5.
        let d = obs
            .cast(Point::new(4.0, 0.5), std::f64::consts::FRAC_PI_4, 20.0)
            .unwrap();
        assert!((d - 2.0 * 2f64.sqrt()).abs() < 1e-3, "{d}");
        // From inside an obstacle: 0.
        assert_eq!(obs.cast(Point::new(6.5, 2.5), 0.0, 5.0), Some(0.0));
    }
}
