//! Seeded random polygonal worlds for property tests and sweeps.
//!
//! A rectangular room with up to `obstacles` polygons, each convex (3 to 7
//! vertices at random angles) or concave (a star, an L or a U, turned by a
//! random angle). Every obstacle keeps at least `min_gap` from the walls and
//! from every other obstacle, so with `min_gap` above the robot's diameter
//! (plus its margin) the robot's free space is one connected piece with a
//! passage all round each obstacle. The start is a random point at least
//! `start_clearance` from everything. Same seed, same world.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use oxcover_grid::Point;
use oxcover_grid::traverse::segment_distance;

use crate::geometry::WorldGeometry;
use crate::world::{Shape, World, segments_cross};

/// What to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct RandomWorldSpec {
    /// Room width (m).
    pub width: f64,
    /// Room height (m).
    pub height: f64,
    /// Raster cell size (m).
    pub resolution: f64,
    /// Obstacles to place (fewer when they do not fit).
    pub obstacles: usize,
    /// Smallest distance between obstacles and from the walls (m).
    pub min_gap: f64,
    /// Obstacle size range: the radius of the circle they are drawn in (m).
    pub size: (f64, f64),
    /// Share of concave obstacles.
    pub concave_share: f64,
    /// Smallest clearance of the start (m).
    pub start_clearance: f64,
}

impl Default for RandomWorldSpec {
    /// A 7 m × 6 m room, 4 obstacles of radius 0.5–1.2 m, half concave,
    /// 0.5 m gaps, 2.5 cm cells, the start 0.25 m clear.
    fn default() -> Self {
        Self {
            width: 7.0,
            height: 6.0,
            resolution: 0.025,
            obstacles: 4,
            min_gap: 0.5,
            size: (0.5, 1.2),
            concave_share: 0.5,
            start_clearance: 0.25,
        }
    }
}

/// A random world (its `start` set).
#[must_use]
pub fn random_world(seed: u64, spec: &RandomWorldSpec) -> World {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut placed: Vec<Vec<Point>> = Vec::new();
    for _ in 0..400 {
        if placed.len() >= spec.obstacles {
            break;
        }
        let radius = rng.random_range(spec.size.0..=spec.size.1);
        let local = if rng.random::<f64>() < spec.concave_share {
            concave(&mut rng, radius)
        } else {
            convex(&mut rng, radius)
        };
        let angle = rng.random_range(0.0..std::f64::consts::TAU);
        let centre = (
            rng.random_range(0.0..spec.width),
            rng.random_range(0.0..spec.height),
        );
        let (s, c) = angle.sin_cos();
        let poly: Vec<Point> = local
            .iter()
            .map(|p| Point::new(centre.0 + c * p.x - s * p.y, centre.1 + s * p.x + c * p.y))
            .collect();
        let g = spec.min_gap;
        let inside = poly
            .iter()
            .all(|p| p.x >= g && p.y >= g && p.x <= spec.width - g && p.y <= spec.height - g);
        if inside && placed.iter().all(|q| polygon_distance(&poly, q) >= g) {
            placed.push(poly);
        }
    }
    let mut world = World {
        name: format!("random-{seed}"),
        width: spec.width,
        height: spec.height,
        resolution: spec.resolution,
        boundary: None,
        obstacles: placed.into_iter().map(Shape::Polygon).collect(),
        start: None,
    };
    let geometry = WorldGeometry::new(&world);
    for _ in 0..10_000 {
        let p = Point::new(
            rng.random_range(0.0..spec.width),
            rng.random_range(0.0..spec.height),
        );
        if geometry.clearance(p).0 >= spec.start_clearance {
            world.start = Some(p);
            break;
        }
    }
    world
}

fn convex(rng: &mut ChaCha8Rng, radius: f64) -> Vec<Point> {
    let n = rng.random_range(3..=7);
    let mut angles: Vec<f64> = (0..n)
        .map(|k| (k as f64 + rng.random_range(0.1..0.9)) * std::f64::consts::TAU / n as f64)
        .collect();
    angles.sort_by(f64::total_cmp);
    angles
        .iter()
        .map(|a| Point::new(radius * a.cos(), radius * a.sin()))
        .collect()
}

fn concave(rng: &mut ChaCha8Rng, radius: f64) -> Vec<Point> {
    match rng.random_range(0..3) {
        // A star: spikes at `radius`, notches at about half of it.
        0 => {
            let k = rng.random_range(3..=5);
            let inner = rng.random_range(0.35..0.6) * radius;
            (0..2 * k)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::PI / k as f64;
                    let r = if i % 2 == 0 { radius } else { inner };
                    Point::new(r * a.cos(), r * a.sin())
                })
                .collect()
        }
        // An L.
        1 => {
            let t = rng.random_range(0.25..0.45) * radius;
            let (a, b) = (radius * 0.7, radius * 0.7);
            vec![
                Point::new(-a, -b),
                Point::new(a, -b),
                Point::new(a, -b + t),
                Point::new(-a + t, -b + t),
                Point::new(-a + t, b),
                Point::new(-a, b),
            ]
        }
        // A U.
        _ => {
            let t = rng.random_range(0.2..0.3) * radius;
            let (a, b) = (radius * 0.75, radius * 0.65);
            vec![
                Point::new(-a, -b),
                Point::new(a, -b),
                Point::new(a, b),
                Point::new(a - t, b),
                Point::new(a - t, -b + t),
                Point::new(-a + t, -b + t),
                Point::new(-a + t, b),
                Point::new(-a, b),
            ]
        }
    }
}

/// Smallest distance between two polygons (0 when they overlap).
fn polygon_distance(p: &[Point], q: &[Point]) -> f64 {
    let inside = |v: &[Point], pt: Point| Shape::Polygon(v.to_vec()).contains(pt);
    if inside(p, q[0]) || inside(q, p[0]) {
        return 0.0;
    }
    let edges = |v: &[Point]| -> Vec<(Point, Point)> {
        (0..v.len()).map(|i| (v[i], v[(i + 1) % v.len()])).collect()
    };
    let mut best = f64::INFINITY;
    for (a, b) in edges(p) {
        for (c, d) in edges(q) {
            if segments_cross(a, b, c, d) {
                return 0.0;
            }
            let p = |v: Point| v;
            let (a, b, c, d) = (p(a), p(b), p(c), p(d));
            best = best
                .min(segment_distance(c, d, a))
                .min(segment_distance(c, d, b))
                .min(segment_distance(a, b, c))
                .min(segment_distance(a, b, d));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worlds_are_seeded_valid_and_spaced() {
        let spec = RandomWorldSpec::default();
        for seed in 0..20 {
            let w = random_world(seed, &spec);
            assert_eq!(w, random_world(seed, &spec));
            w.check().unwrap();
            assert!(!w.obstacles.is_empty());
            let g = WorldGeometry::new(&w);
            assert!(g.clearance(w.start.unwrap()).0 >= spec.start_clearance);
            let polys: Vec<_> = w
                .obstacles
                .iter()
                .map(|s| match s {
                    Shape::Polygon(v) => v.clone(),
                    _ => unreachable!(),
                })
                .collect();
            for i in 0..polys.len() {
                for j in i + 1..polys.len() {
                    assert!(polygon_distance(&polys[i], &polys[j]) >= spec.min_gap);
                }
            }
        }
        assert_ne!(random_world(1, &spec), random_world(2, &spec));
    }
}
