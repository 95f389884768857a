//! Polygonal worlds: an outer boundary and obstacles (polygons, convex or
//! not, discs and rotated rectangles), read from RON, rasterised to an
//! occupancy grid, ray-cast with parry2d, and their exact critical points.
//!
//! ```ron
//! (
//!     name: "l_room",
//!     width: 8.0, height: 6.0,      // extent [0, width] × [0, height] (m)
//!     resolution: 0.025,            // cell size of the rasterised map (m)
//!     // optional outer boundary; without it the extent is the room
//!     boundary: Some([(0.0, 0.0), (8.0, 0.0), (8.0, 3.0), (4.0, 3.0), (4.0, 6.0), (0.0, 6.0)]),
//!     obstacles: [
//!         Polygon([(1.0, 1.0), (2.0, 1.0), (1.5, 2.0)]),
//!         Circle(centre: (6.0, 1.5), radius: 0.4),
//!         Rect(centre: (2.0, 4.5), size: (1.0, 0.5), angle_deg: 30.0),
//!     ],
//!     start: Some((0.5, 0.5)),      // optional: where experiments start
//! )
//! ```
//!
//! Metres, x right, y up (the map frame of the contract). The rasterised map
//! has one cell of wall all round: its origin is `(-resolution, -resolution)`,
//! and a cell is occupied when its centre lies in an obstacle or outside the
//! boundary.
//!
//! **Critical points** ([`World::critical_points`]) are the points where a
//! boundary curve is tangent to a slice `x = const`: the x-extremal vertices
//! of the polygons (a vertical edge whose neighbours lie on one side counts
//! once, as a segment) and the left and right points of discs. They are
//! classified as the sensor-based planner classifies what it detects:
//! [`Event::In`] where sweeping towards +x adds a free interval (a split or a
//! birth), [`Event::Out`] where one goes (a merge or a death);
//! [`Convexity::Convex`] where the obstacle bulges into free space,
//! [`Convexity::Concave`] where free space bulges into the obstacle.

use std::path::Path;

use oxcover_grid::{Grid, Occupancy, OccupancyGrid, Point, Vector};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
#[cfg(test)]
use crate::geometry::{RayCaster, WorldGeometry};

/// Largest rasterised map a world may ask for (cells).
pub const MAX_CELLS: usize = 50_000_000;

/// An obstacle of a world file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    /// A simple polygon: vertices in order (either orientation), convex or not.
    Polygon(Vec<Point>),
    /// A disc.
    Circle {
        /// Centre (m).
        centre: Point,
        /// Radius (m).
        radius: f64,
    },
    /// A rotated rectangle.
    Rect {
        /// Centre (m).
        centre: Point,
        /// Side lengths (m).
        size: Vector,
        /// Rotation, counter-clockwise (degrees).
        angle_deg: f64,
    },
}

impl Shape {
    /// Whether `p` lies inside (boundary included).
    #[must_use]
    pub fn contains(&self, p: Point) -> bool {
        match self {
            Self::Polygon(v) => inside_polygon(v, p),
            Self::Circle { centre, radius } => (p.x - centre.x).hypot(p.y - centre.y) <= *radius,
            Self::Rect {
                centre,
                size,
                angle_deg,
            } => {
                let (s, c) = angle_deg.to_radians().sin_cos();
                let (dx, dy) = (p.x - centre.x, p.y - centre.y);
                let (u, v) = (c * dx + s * dy, -s * dx + c * dy);
                u.abs() <= size.x / 2.0 && v.abs() <= size.y / 2.0
            }
        }
    }

    /// The outline: a polygon's vertices, a rectangle's four corners, or a disc.
    #[must_use]
    pub fn outline(&self) -> Outline {
        match self {
            Self::Polygon(v) => Outline::Polygon(v.clone()),
            Self::Circle { centre, radius } => Outline::Circle {
                centre: *centre,
                radius: *radius,
            },
            Self::Rect {
                centre,
                size,
                angle_deg,
            } => {
                let (s, c) = angle_deg.to_radians().sin_cos();
                let (hx, hy) = (size.x / 2.0, size.y / 2.0);
                let corner =
                    |u: f64, v: f64| Point::new(centre.x + c * u - s * v, centre.y + s * u + c * v);
                Outline::Polygon(vec![
                    corner(-hx, -hy),
                    corner(hx, -hy),
                    corner(hx, hy),
                    corner(-hx, hy),
                ])
            }
        }
    }
}

/// A closed boundary curve.
#[derive(Clone, Debug, PartialEq)]
pub enum Outline {
    /// A closed polygon (the last vertex joins the first).
    Polygon(Vec<Point>),
    /// A circle.
    Circle {
        /// Centre (m).
        centre: Point,
        /// Radius (m).
        radius: f64,
    },
}

/// Even-odd rule.
fn inside_polygon(v: &[Point], p: Point) -> bool {
    let mut inside = false;
    let n = v.len();
    for i in 0..n {
        let (a, b) = (v[i], v[(i + n - 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
    }
    inside
}

/// A polygonal world (a world file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct World {
    /// Name.
    pub name: String,
    /// Width of the extent (m).
    pub width: f64,
    /// Height of the extent (m).
    pub height: f64,
    /// Cell size of the rasterised map (m).
    pub resolution: f64,
    /// Outer boundary, inside the extent; the extent itself when absent.
    #[serde(default)]
    pub boundary: Option<Vec<Point>>,
    /// Obstacles.
    pub obstacles: Vec<Shape>,
    /// A start position for experiments (m), if the file names one.
    #[serde(default)]
    pub start: Option<Point>,
}

/// Which way the free intervals of a slice change at a critical point, for a
/// sweep towards +x.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Event {
    /// A free interval appears: a cell splits around an obstacle, or one is born.
    In,
    /// A free interval goes: two cells merge past an obstacle, or one dies.
    Out,
}

/// Whether the obstacle or the free space bulges at a critical point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Convexity {
    /// The obstacle bulges into free space (an obstacle's leftmost or rightmost point).
    Convex,
    /// Free space bulges into the obstacle (the end of a pocket, a room's wall).
    Concave,
}

/// A critical point's class.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct CriticalKind {
    /// In or out.
    pub event: Event,
    /// Convex or concave.
    pub convexity: Convexity,
}

impl CriticalKind {
    /// The class of an x-extremum of a boundary: `open` is the side (+1 or
    /// −1 along x) the boundary extends to from it, `obstacle_beyond` whether
    /// the space just beyond the extremum on that side is obstacle.
    #[must_use]
    pub fn from_extremum(open: f64, obstacle_beyond: bool) -> Self {
        Self {
            event: if open > 0.0 { Event::In } else { Event::Out },
            convexity: if obstacle_beyond {
                Convexity::Convex
            } else {
                Convexity::Concave
            },
        }
    }

    /// `IN convex`, `OUT concave`, …
    #[must_use]
    pub fn label(&self) -> &'static str {
        match (self.event, self.convexity) {
            (Event::In, Convexity::Convex) => "IN convex",
            (Event::In, Convexity::Concave) => "IN concave",
            (Event::Out, Convexity::Convex) => "OUT convex",
            (Event::Out, Convexity::Concave) => "OUT concave",
        }
    }
}

/// An exact critical point of a world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrueCriticalPoint {
    /// The boundary point (m); for a vertical edge, its lower end.
    pub at: Point,
    /// For a vertical edge, its upper end; else the same as `at`.
    pub to: Point,
    /// Class.
    pub kind: CriticalKind,
    /// Which curve: 0 the outer boundary, `k` obstacle `k − 1`.
    pub surface: usize,
}

impl TrueCriticalPoint {
    /// Distance from `p` to the point (or to the vertical edge).
    #[must_use]
    pub fn distance(&self, p: Point) -> f64 {
        let (lo, hi) = (self.at.y.min(self.to.y), self.at.y.max(self.to.y));
        let y = p.y.clamp(lo, hi);
        (p.x - self.at.x).hypot(p.y - y)
    }
}

impl World {
    /// Reads and checks a world file.
    ///
    /// # Errors
    /// [`Error::World`] naming the file and what is wrong with it.
    pub fn read(path: &Path) -> Result<Self> {
        let text = oxcover_grid::io::limited::read_limited_string(
            path,
            oxcover_grid::io::limited::MAX_TEXT_BYTES,
        )
        .map_err(|e| Error::World {
            file: path.display().to_string(),
            message: format!("cannot read it: {e}"),
        })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and checks a world from RON text; `source` names it in errors.
    ///
    /// # Errors
    /// [`Error::World`] for malformed RON or a world that fails [`World::check`].
    pub fn parse(text: &str, source: &str) -> Result<Self> {
        let world: Self = ron::from_str(text).map_err(|e| Error::World {
            file: source.to_string(),
            message: e.to_string(),
        })?;
        world.check().map_err(|message| Error::World {
            file: source.to_string(),
            message,
        })?;
        Ok(world)
    }

    /// Checks sizes, coordinates and shapes.
    ///
    /// # Errors
    /// A message naming the field and what was expected.
    pub fn check(&self) -> std::result::Result<(), String> {
        // The workspace's one check, with names built from the shape.
        let positive = |name: &str, v: f64| {
            oxcover_grid::error::positive("", v)
                .map(|_| ())
                .map_err(|b| format!("{name} is `{v}`, expected {}", b.expected))
        };
        positive("width", self.width)?;
        positive("height", self.height)?;
        positive("resolution", self.resolution)?;
        if let Some(p) = self.start {
            finite_point(p).map_err(|m| format!("start: {m}"))?;
        }
        let cells = (self.width / self.resolution + 2.0) * (self.height / self.resolution + 2.0);
        if cells > MAX_CELLS as f64 {
            return Err(format!(
                "{} m x {} m at {} m per cell is {cells:.0} cells, more than {MAX_CELLS}",
                self.width, self.height, self.resolution
            ));
        }
        if let Some(b) = &self.boundary {
            check_polygon(b).map_err(|m| format!("boundary: {m}"))?;
            let eps = 1e-9 * (self.width + self.height);
            if let Some(p) = b.iter().find(|p| {
                p.x < -eps || p.y < -eps || p.x > self.width + eps || p.y > self.height + eps
            }) {
                return Err(format!(
                    "boundary vertex ({}, {}) lies outside the extent [0, {}] x [0, {}]",
                    p.x, p.y, self.width, self.height
                ));
            }
        }
        for (k, s) in self.obstacles.iter().enumerate() {
            let name = format!("obstacle {}", k + 1);
            match s {
                Shape::Polygon(v) => check_polygon(v).map_err(|m| format!("{name}: {m}"))?,
                Shape::Circle { centre, radius } => {
                    finite_point(*centre).map_err(|m| format!("{name}: {m}"))?;
                    positive(&format!("{name} radius"), *radius)?;
                }
                Shape::Rect {
                    centre,
                    size,
                    angle_deg,
                } => {
                    finite_point(*centre).map_err(|m| format!("{name}: {m}"))?;
                    positive(&format!("{name} width"), size.x)?;
                    positive(&format!("{name} height"), size.y)?;
                    if !angle_deg.is_finite() {
                        return Err(format!("{name}: angle_deg is {angle_deg}"));
                    }
                }
            }
        }
        Ok(())
    }

    /// The outer boundary polygon (the extent's rectangle when none is given).
    #[must_use]
    pub fn boundary_polygon(&self) -> Vec<Point> {
        self.boundary.clone().unwrap_or_else(|| {
            vec![
                Point::new(0.0, 0.0),
                Point::new(self.width, 0.0),
                Point::new(self.width, self.height),
                Point::new(0.0, self.height),
            ]
        })
    }

    /// Whether `p` is free: inside the boundary and in no obstacle.
    #[must_use]
    pub fn is_free(&self, p: Point) -> bool {
        let inside = match &self.boundary {
            Some(b) => inside_polygon(b, p),
            None => p.x >= 0.0 && p.y >= 0.0 && p.x <= self.width && p.y <= self.height,
        };
        inside && !self.obstacles.iter().any(|s| s.contains(p))
    }

    /// The occupancy grid: a cell is occupied when its centre is not free;
    /// one cell of wall all round (origin `(-resolution, -resolution)`).
    #[must_use]
    pub fn rasterise(&self) -> OccupancyGrid {
        let r = self.resolution;
        let w = (self.width / r).round() as usize + 2;
        let h = (self.height / r).round() as usize + 2;
        let mut map = OccupancyGrid::new(Grid::new(w, h, Occupancy::Free), r, Point::new(-r, -r));
        let frame = *map.frame();
        for cell in Grid::<()>::new(w, h, ()).cells() {
            let c = frame.cell_center(cell);
            let p = c;
            let outside = p.x < 0.0 || p.y < 0.0 || p.x > self.width || p.y > self.height;
            if outside || !self.is_free(p) {
                map.cells_mut()[cell] = Occupancy::Occupied;
            }
        }
        map
    }

    /// Every boundary curve: the outer boundary first, then the obstacles in order.
    #[must_use]
    pub fn outlines(&self) -> Vec<Outline> {
        std::iter::once(Outline::Polygon(self.boundary_polygon()))
            .chain(self.obstacles.iter().map(Shape::outline))
            .collect()
    }

    /// The exact critical points for slices `x = const`, on the free space's
    /// boundary (parts of obstacles outside the room or inside other
    /// obstacles are skipped). Consecutive vertices whose x differ by at
    /// most `x_tolerance` (m) form one stretch parallel to the slices: a
    /// critical segment when the curve goes on to the same side at both
    /// ends, nothing otherwise. With a tolerance of 0 only exactly vertical
    /// edges are such stretches; a sensor with a hysteresis along x cannot
    /// tell shallower features apart, so it is compared with that tolerance.
    #[must_use]
    pub fn critical_points(&self, x_tolerance: f64) -> Vec<TrueCriticalPoint> {
        let scale = self.width.max(self.height);
        let eps = (1e-6 * scale).max(x_tolerance);
        let nudge = 1e-5 * scale;
        let mut out = Vec::new();
        for (surface, outline) in self.outlines().into_iter().enumerate() {
            let candidates: Vec<Extremum> = match &outline {
                Outline::Circle { centre, radius } => [1.0, -1.0]
                    .iter()
                    .map(|&open| {
                        let p = Point::new(centre.x - open * radius, centre.y);
                        Extremum {
                            lo: p,
                            hi: p,
                            open,
                            convex: true,
                            free_probe: Point::new(p.x - open * nudge, p.y),
                        }
                    })
                    .collect(),
                Outline::Polygon(v) => polygon_extrema(v, eps, surface != 0, nudge),
            };
            for e in candidates {
                // Only points on the free space's boundary count.
                if self.is_free(e.free_probe) {
                    out.push(TrueCriticalPoint {
                        at: e.lo,
                        to: e.hi,
                        kind: CriticalKind::from_extremum(e.open, e.convex),
                        surface,
                    });
                }
            }
        }
        out
    }
}

/// An x-extremal stretch of a boundary curve.
struct Extremum {
    /// Lower end.
    lo: Point,
    /// Upper end.
    hi: Point,
    /// The side (±1 in x) the curve extends to.
    open: f64,
    /// Whether the obstacle bulges there.
    convex: bool,
    /// A point just off the extreme vertex on the free side.
    free_probe: Point,
}

/// The x-extremal stretches of a closed polygon: runs of consecutive
/// vertices within `eps` in x whose neighbours both lie on one side.
/// `obstacle` says whether the polygon's interior is an obstacle (else it is
/// the outer boundary, its interior free).
fn polygon_extrema(v: &[Point], eps: f64, obstacle: bool, nudge: f64) -> Vec<Extremum> {
    let n = v.len();
    let same = |a: Point, b: Point| (a.x - b.x).abs() <= eps;
    let orientation = (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        .signum();
    let at = |k: usize| v[k % n];
    // Normal of the edge `a → b` pointing into free space.
    let free_normal = |a: Point, b: Point| {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let l = dx.hypot(dy);
        // Right of the edge is outside a counter-clockwise polygon.
        let out = if orientation > 0.0 {
            (dy / l, -dx / l)
        } else {
            (-dy / l, dx / l)
        };
        if obstacle { out } else { (-out.0, -out.1) }
    };
    // Start at a vertex whose predecessor has a different x, so no stretch
    // wraps around the start.
    let Some(start) = (0..n).find(|&i| !same(v[i], v[(i + n - 1) % n])) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut k = 0;
    while k < n {
        let i = start + k;
        let mut j = k;
        while j + 1 < n && same(at(start + j + 1), at(i)) {
            j += 1;
        }
        let last = start + j;
        let (prev, next) = (at(i + n - 1), at(last + 1));
        let x = at(i).x;
        let open = if prev.x > x && next.x > x {
            1.0
        } else if prev.x < x && next.x < x {
            -1.0
        } else {
            k = j + 1;
            continue;
        };
        // Total turn along prev → stretch → next: about ±π; a turn the
        // polygon's own way is a convex corner of the polygon.
        let turn: f64 = (i..=last)
            .map(|m| {
                let (p, c, q) = (at(m + n - 1), at(m), at(m + 1));
                let (d1, d2) = ((c.x - p.x, c.y - p.y), (q.x - c.x, q.y - c.y));
                (d1.0 * d2.1 - d1.1 * d2.0).atan2(d1.0 * d2.0 + d1.1 * d2.1)
            })
            .sum();
        let polygon_convex = turn * orientation > 0.0;
        // The stretch's extreme vertex, and a probe off it into free space.
        let e = (i..=last)
            .min_by(|&a, &b| (open * at(a).x).total_cmp(&(open * at(b).x)))
            .unwrap_or(i);
        let (n1, n2) = (
            free_normal(at(e + n - 1), at(e)),
            free_normal(at(e), at(e + 1)),
        );
        let (sx, sy) = (n1.0 + n2.0, n1.1 + n2.1);
        let l = sx.hypot(sy);
        let dir = if l > 1e-9 { (sx / l, sy / l) } else { n1 };
        let (a, b) = (at(i), at(last));
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        out.push(Extremum {
            lo,
            hi,
            open,
            convex: polygon_convex == obstacle,
            free_probe: Point::new(at(e).x + nudge * dir.0, at(e).y + nudge * dir.1),
        });
        k = j + 1;
    }
    out
}

fn finite_point(p: Point) -> std::result::Result<(), String> {
    if p.x.is_finite() && p.y.is_finite() {
        Ok(())
    } else {
        Err(format!("point ({}, {}) is not finite", p.x, p.y))
    }
}

/// At least three finite vertices, a non-zero area, no edge crossing another.
fn check_polygon(v: &[Point]) -> std::result::Result<(), String> {
    if v.len() < 3 {
        return Err(format!(
            "a polygon needs 3 vertices or more, got {}",
            v.len()
        ));
    }
    for &p in v {
        finite_point(p)?;
    }
    let n = v.len();
    let area: f64 = (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        / 2.0;
    if area.abs() < 1e-12 {
        return Err("the polygon has no area".into());
    }
    for i in 0..n {
        for j in i + 1..n {
            // Neighbouring edges share a vertex; skip them.
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let (a, b) = (v[i], v[(i + 1) % n]);
            let (c, d) = (v[j], v[(j + 1) % n]);
            if segments_cross(a, b, c, d) {
                return Err(format!(
                    "edge {} crosses edge {} (the polygon must be simple)",
                    i + 1,
                    j + 1
                ));
            }
        }
    }
    Ok(())
}

fn orient(a: Point, b: Point, c: Point) -> f64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

pub(crate) fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    (d1 * d2 < 0.0) && (d3 * d4 < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world(text: &str) -> World {
        World::parse(text, "test").unwrap()
    }

    #[test]
    fn parses_rasterises_and_checks() {
        let w = world(
            "(name: \"t\", width: 4.0, height: 2.0, resolution: 0.5,
              obstacles: [Rect(centre: (1.0, 1.0), size: (1.0, 1.0), angle_deg: 0.0)])",
        );
        let map = w.rasterise();
        assert_eq!((map.width(), map.height()), (10, 6));
        let free = map.free_mask();
        assert_eq!(free.as_slice().iter().filter(|&&f| f).count(), 8 * 4 - 4);
        for (text, needle) in [
            (
                "(name: \"t\", width: -1.0, height: 2.0, resolution: 0.5, obstacles: [])",
                "width",
            ),
            (
                "(name: \"t\", width: 1.0, height: 2.0, resolution: 0.0, obstacles: [])",
                "resolution",
            ),
            (
                "(name: \"t\", width: 1e9, height: 1e9, resolution: 0.01, obstacles: [])",
                "cells",
            ),
            (
                "(name: \"t\", width: 1.0, height: 2.0, obstacles: [])",
                "resolution",
            ),
            (
                "(name: \"t\", width: 4.0, height: 2.0, resolution: 0.5, obstacles: [Polygon([(0.0, 0.0), (1.0, 1.0)])])",
                "obstacle 1",
            ),
            (
                "(name: \"t\", width: 4.0, height: 2.0, resolution: 0.5, obstacles: [Polygon([(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 1.0)])])",
                "simple",
            ),
            (
                "(name: \"t\", width: 4.0, height: 2.0, resolution: 0.5, obstacles: [Circle(centre: (1.0, 1.0), radius: NaN)])",
                "radius",
            ),
            (
                "(name: \"t\", width: 4.0, height: 2.0, resolution: 0.5, boundary: Some([(0.0, 0.0), (5.0, 0.0), (0.0, 2.0)]), obstacles: [])",
                "outside the extent",
            ),
        ] {
            let e = World::parse(text, "bad.ron").unwrap_err().to_string();
            assert!(e.contains("bad.ron") && e.contains(needle), "{e}");
        }
    }

    #[test]
    fn critical_points_of_a_diamond_a_disc_and_a_room() {
        let w = world(
            "(name: \"t\", width: 10.0, height: 6.0, resolution: 0.1, obstacles: [
                Polygon([(2.0, 3.0), (3.0, 2.0), (4.0, 3.0), (3.0, 4.0)]),
                Circle(centre: (7.0, 3.0), radius: 1.0),
            ])",
        );
        let cps = w.critical_points(0.0);
        let find = |x: f64, y: f64| {
            cps.iter()
                .find(|c| c.distance(Point::new(x, y)) < 1e-9)
                .unwrap_or_else(|| panic!("no critical point at ({x}, {y}): {cps:?}"))
                .kind
                .label()
        };
        assert_eq!(cps.len(), 6, "{cps:?}");
        assert_eq!(find(2.0, 3.0), "IN convex");
        assert_eq!(find(4.0, 3.0), "OUT convex");
        assert_eq!(find(6.0, 3.0), "IN convex");
        assert_eq!(find(8.0, 3.0), "OUT convex");
        // A thin spike whose wedge lies wholly below its tip is still convex.
        let spike = world(
            "(name: \"t\", width: 4.0, height: 4.0, resolution: 0.1, obstacles: [
                Polygon([(1.0, 2.0), (3.0, 1.5), (3.0, 1.0)])])",
        );
        let tip = spike.critical_points(0.0);
        let tip = tip
            .iter()
            .find(|c| c.surface == 1 && c.at == Point::new(1.0, 2.0))
            .unwrap();
        assert_eq!(tip.kind.label(), "IN convex");
        // A nearly vertical edge is one stretch within a tolerance.
        let bent = world(
            "(name: \"t\", width: 6.0, height: 6.0, resolution: 0.1, obstacles: [
                Polygon([(1.0, 1.0), (3.0, 1.0), (3.0, 2.0), (2.0, 2.0), (2.003, 3.0), (2.0, 4.0), (3.0, 4.0), (3.0, 5.0), (1.0, 5.0)])])",
        );
        let on_obstacle = |tol: f64| {
            bent.critical_points(tol)
                .iter()
                .filter(|c| c.surface == 1)
                .count()
        };
        // Exactly: the U's back and its two arm ends, and the back wall's
        // 3 mm wiggle (x-min, x-max, x-min); within 5 mm the wall is one
        // stretch, one critical point.
        assert_eq!(on_obstacle(0.0), 6);
        assert_eq!(on_obstacle(0.005), 4);
        // The room's walls are vertical edges: one critical segment each.
        assert_eq!(find(0.0, 1.0), "IN concave");
        assert_eq!(find(10.0, 5.0), "OUT concave");
    }

    #[test]
    fn a_concave_obstacle_has_concave_critical_points() {
        // A C opening to +x: outer left side (IN convex), the pocket's back
        // (a vertical edge, IN concave: free space is born there), and the
        // arms' right ends (vertical edges, OUT convex).
        let w = world(
            "(name: \"t\", width: 10.0, height: 10.0, resolution: 0.1, obstacles: [
                Polygon([(2.0, 2.0), (6.0, 2.5), (6.0, 4.0), (4.0, 4.0), (4.0, 6.0), (6.0, 6.0), (6.0, 7.5), (2.0, 8.0)]),
            ])",
        );
        let cps: Vec<_> = w
            .critical_points(0.0)
            .into_iter()
            .filter(|c| c.surface == 1)
            .collect();
        let labels: Vec<_> = cps.iter().map(|c| (c.at, c.kind.label())).collect();
        assert_eq!(cps.len(), 4, "{labels:?}");
        assert!(
            labels.contains(&(Point::new(4.0, 4.0), "IN concave")),
            "{labels:?}"
        );
        assert!(
            labels.contains(&(Point::new(6.0, 2.5), "OUT convex")),
            "{labels:?}"
        );
        assert!(
            labels.contains(&(Point::new(6.0, 6.0), "OUT convex")),
            "{labels:?}"
        );
    }

    #[test]
    fn rays_and_clearance_are_exact() {
        let w = world(
            "(name: \"t\", width: 10.0, height: 6.0, resolution: 0.1, obstacles: [
                Polygon([(2.0, 3.0), (3.0, 2.0), (4.0, 3.0), (3.0, 4.0)]),
                Circle(centre: (7.0, 3.0), radius: 1.0),
            ])",
        );
        let g = WorldGeometry::new(&w);
        let (d, s) = g.cast_surface(Point::new(0.5, 3.0), 0.0, 20.0).unwrap();
        assert!((d - 1.5).abs() < 1e-5 && s == 1, "{d} {s}");
        let (d, s) = g.cast_surface(Point::new(5.0, 3.0), 0.0, 20.0).unwrap();
        assert!((d - 1.0).abs() < 1e-5 && s == 2, "{d} {s}");
        let (d, s) = g
            .cast_surface(Point::new(5.0, 3.0), std::f64::consts::FRAC_PI_2, 20.0)
            .unwrap();
        assert!((d - 3.0).abs() < 1e-5 && s == 0, "{d} {s}");
        assert!(
            g.cast_surface(Point::new(5.0, 3.0), std::f64::consts::FRAC_PI_2, 2.0)
                .is_none()
        );
        let (c, s) = g.clearance(Point::new(5.2, 3.0));
        assert!((c - 0.8).abs() < 1e-12 && s == 2);
        assert!(g.clearance(Point::new(3.0, 3.0)).0 < 0.0);
        assert!(g.clearance(Point::new(-1.0, 3.0)).0 < 0.0);
    }
}
