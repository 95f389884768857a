//! Critical-point detection from three range rays (Demir 2018, §2.1,
//! eqs. 1–3), for slices `x = const`.
//!
//! The robot fires a *lagging*, a *centre* and a *leading* ray at a boundary,
//! the outer two at ±`spread` from the centre one, and takes the three hit
//! points `lag`, `c`, `lead`. The seed forms `line₁ = c − lag` and
//! `line₂ = lead − c` and compares `line₁ · line₂` with `|line₁| |line₂|`
//! (eq. 2): equal means the three points are collinear, a straight piece of
//! boundary. We write "equal" as `cos ∠(line₁, line₂) ≥ cos(angle_tolerance)`
//! so range noise within the tolerance reads as straight.
//!
//! The seed adds the robot's position to the critical points whenever the
//! test fails (eq. 3), which fires at every corner. A critical point of a
//! sweep along x is a point where the boundary is tangent to the slice (its
//! normal parallel to x), so we add what that means for three points:
//!
//! - straight and parallel to the slices (a vertical wall within the angle
//!   tolerance): [`Detection::SliceParallel`], a degenerate critical segment
//!   whose class depends on how the wall ends;
//! - a corner whose centre point is x-extremal among the three (both
//!   neighbours on one side of the slice through it, within
//!   `x_tolerance`): [`Detection::Critical`], classified by where the robot is:
//!   with `e` the side of the boundary from the robot along x and `g` the
//!   side the boundary extends to, the event is IN when `g = +x` (an interval
//!   appears as the slice moves on) and OUT otherwise, and the point is
//!   convex (the obstacle bulges) when `e = g`, concave when the boundary
//!   wraps back around the robot;
//! - any other corner: [`Detection::Corner`], not critical.
//!
//! [`Detection::Critical`] is fired from a position where the centre ray
//! points along the sweep axis, which is where the sensor-based planner fires
//! it (at the x-extremum of its boundary following).

use crate::geometry::RayCaster;
use crate::sensors::RangeSensor;
use crate::world::CriticalKind;
use oxcover_grid::Point;

/// The three hit points (m, world frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Returns {
    /// Lagging ray's hit.
    pub lag: Point,
    /// Centre ray's hit.
    pub centre: Point,
    /// Leading ray's hit.
    pub lead: Point,
}

/// What three rays say about the boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Detection {
    /// A ray saw nothing, or two hits coincide: no verdict.
    Blind,
    /// Collinear, not parallel to the slices.
    Straight,
    /// Collinear and parallel to the slices (a wall along y).
    SliceParallel,
    /// Not collinear, but not x-extremal: an ordinary corner.
    Corner,
    /// A critical point, classified.
    Critical(CriticalKind),
}

/// The detector's geometry and tolerances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreeRayDetector {
    /// Angle between the centre ray and each outer ray (rad).
    pub spread: f64,
    /// Largest angle between `line₁` and `line₂` still called straight (rad).
    pub angle_tolerance: f64,
    /// Largest x offset (m) of a neighbour on the wrong side still called
    /// extremal, and smallest offset that counts as a side.
    pub x_tolerance: f64,
}

impl Default for ThreeRayDetector {
    /// 20° spread, 8° angle tolerance, 5 mm x tolerance.
    fn default() -> Self {
        Self {
            spread: 20f64.to_radians(),
            angle_tolerance: 8f64.to_radians(),
            x_tolerance: 0.005,
        }
    }
}

impl ThreeRayDetector {
    /// Tolerances for range noise of standard deviation `noise_sd` (m) at
    /// distance `range` (m): three standard deviations of the angle of a
    /// line through two hits, at least the defaults.
    #[must_use]
    pub fn for_noise(noise_sd: f64, range: f64) -> Self {
        let d = Self::default();
        let gap = (range * d.spread.tan()).max(1e-6);
        Self {
            angle_tolerance: d
                .angle_tolerance
                .max(3.0 * (2f64.sqrt() * noise_sd / gap).atan()),
            x_tolerance: d.x_tolerance.max(3.0 * noise_sd),
            ..d
        }
    }

    /// Fires the three rays from `robot` around the absolute heading
    /// `centre_angle`; `None` when a ray sees nothing within range.
    pub fn fire(
        &self,
        sensor: &mut RangeSensor,
        caster: &impl RayCaster,
        robot: Point,
        centre_angle: f64,
    ) -> Option<Returns> {
        let mut hit = |a: f64| {
            let r = sensor.read(caster, robot, a);
            r.surface
                .map(|_| Point::new(robot.x + r.range * a.cos(), robot.y + r.range * a.sin()))
        };
        Some(Returns {
            lag: hit(centre_angle - self.spread)?,
            centre: hit(centre_angle)?,
            lead: hit(centre_angle + self.spread)?,
        })
    }

    /// The verdict on three returns seen from `robot`.
    #[must_use]
    pub fn classify(&self, robot: Point, r: &Returns) -> Detection {
        let line1 = (r.centre.x - r.lag.x, r.centre.y - r.lag.y);
        let line2 = (r.lead.x - r.centre.x, r.lead.y - r.centre.y);
        let (n1, n2) = (line1.0.hypot(line1.1), line2.0.hypot(line2.1));
        if n1 < 1e-9 || n2 < 1e-9 {
            return Detection::Blind;
        }
        // Eqs. 1–3: result = line₁ · line₂ against |line₁| |line₂|.
        let result = line1.0 * line2.0 + line1.1 * line2.1;
        if result >= self.angle_tolerance.cos() * n1 * n2 {
            let (dx, dy) = (r.lead.x - r.lag.x, r.lead.y - r.lag.y);
            return if dx.abs() <= self.angle_tolerance.sin() * dx.hypot(dy) {
                Detection::SliceParallel
            } else {
                Detection::Straight
            };
        }
        let tol = self.x_tolerance;
        let (dx1, dx2) = (r.lag.x - r.centre.x, r.lead.x - r.centre.x);
        let g = (dx1 + dx2).signum();
        let extremal = dx1 * g >= -tol && dx2 * g >= -tol && dx1.abs().max(dx2.abs()) > tol;
        let ahead = r.centre.x - robot.x;
        if !extremal || ahead.abs() <= tol {
            return Detection::Corner;
        }
        Detection::Critical(CriticalKind::from_extremum(g, ahead.signum() == g))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::WorldGeometry;
    use crate::world::{Convexity, Event, World};

    /// The hit of a ray from `p` at `angle` on the polyline `v` (closed).
    fn hit(p: Point, angle: f64, v: &[Point]) -> Point {
        let d = (angle.cos(), angle.sin());
        let mut best = f64::INFINITY;
        for i in 0..v.len() {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let e = (b.x - a.x, b.y - a.y);
            let den = d.0 * e.1 - d.1 * e.0;
            if den.abs() < 1e-12 {
                continue;
            }
            let w = (a.x - p.x, a.y - p.y);
            let t = (w.0 * e.1 - w.1 * e.0) / den;
            let s = (w.0 * d.1 - w.1 * d.0) / den;
            if t > 0.0 && (0.0..=1.0).contains(&s) {
                best = best.min(t);
            }
        }
        Point::new(p.x + best * d.0, p.y + best * d.1)
    }

    fn returns(p: Point, centre: f64, v: &[Point]) -> Returns {
        let s = ThreeRayDetector::default().spread;
        Returns {
            lag: hit(p, centre - s, v),
            centre: hit(p, centre, v),
            lead: hit(p, centre + s, v),
        }
    }

    fn kind(event: Event, convexity: Convexity) -> Detection {
        Detection::Critical(CriticalKind { event, convexity })
    }

    #[test]
    fn a_straight_wall_is_not_critical() {
        let det = ThreeRayDetector::default();
        // A wall at 30° to the slices, seen square on and obliquely.
        let t = 30f64.to_radians().tan();
        let w = [
            Point::new(-20.0, -20.0 * t),
            Point::new(20.0, 20.0 * t),
            Point::new(20.0, -20.0),
            Point::new(-20.0, -20.0),
        ];
        for centre in [-95f64, -120.0, -60.0] {
            let r = returns(Point::new(5.0, 5.0), centre.to_radians(), &w);
            assert_eq!(
                det.classify(Point::new(5.0, 5.0), &r),
                Detection::Straight,
                "{centre}"
            );
        }
        // A wall along y is parallel to the slices.
        let w = [
            Point::new(2.0, -5.0),
            Point::new(2.0, 5.0),
            Point::new(3.0, 5.0),
            Point::new(3.0, -5.0),
        ];
        let r = returns(Point::new(1.7, 0.3), 0.0, &w);
        assert_eq!(
            det.classify(Point::new(1.7, 0.3), &r),
            Detection::SliceParallel
        );
    }

    #[test]
    fn convex_corners_are_critical_when_extremal() {
        let det = ThreeRayDetector::default();
        let diamond = [
            Point::new(1.0, 0.0),
            Point::new(2.0, -1.0),
            Point::new(3.0, 0.0),
            Point::new(2.0, 1.0),
        ];
        // Left vertex seen from the left: the obstacle appears, IN convex.
        let r = returns(Point::new(0.7, 0.0), 0.0, &diamond);
        assert_eq!(r.centre, Point::new(1.0, 0.0));
        assert_eq!(
            det.classify(Point::new(0.7, 0.0), &r),
            kind(Event::In, Convexity::Convex)
        );
        // Right vertex seen from the right: the obstacle ends, OUT convex.
        let r = returns(Point::new(3.3, 0.0), std::f64::consts::PI, &diamond);
        assert_eq!(
            det.classify(Point::new(3.3, 0.0), &r),
            kind(Event::Out, Convexity::Convex)
        );
        // The top vertex seen from above is a corner, not critical.
        let r = returns(Point::new(2.0, 1.3), -std::f64::consts::FRAC_PI_2, &diamond);
        assert_eq!(det.classify(Point::new(2.0, 1.3), &r), Detection::Corner);
        // A staircase corner: one edge goes back in x, the other on.
        let stair = [
            Point::new(-0.5, 1.0),
            Point::new(0.0, 0.0),
            Point::new(1.0, -0.2),
            Point::new(1.0, -2.0),
            Point::new(-2.0, -2.0),
            Point::new(-2.0, 1.0),
        ];
        let r = returns(
            Point::new(0.5, 0.5),
            -3.0 * std::f64::consts::FRAC_PI_4,
            &stair,
        );
        assert!((r.centre.x.abs() + r.centre.y.abs()) < 1e-9, "{r:?}");
        assert_eq!(det.classify(Point::new(0.5, 0.5), &r), Detection::Corner);
    }

    #[test]
    fn concave_corners_are_classified_concave() {
        let det = ThreeRayDetector::default();
        // The end of a pocket opening to -x: apex at Point::new(1.0, 0.0). Free space dies
        // there: OUT concave.
        let pocket = [
            Point::new(1.0, 0.0),
            Point::new(-3.0, 2.0),
            Point::new(-3.0, 5.0),
            Point::new(5.0, 5.0),
            Point::new(5.0, -5.0),
            Point::new(-3.0, -2.0),
        ];
        let r = returns(Point::new(0.6, 0.0), 0.0, &pocket);
        assert_eq!(
            det.classify(Point::new(0.6, 0.0), &r),
            kind(Event::Out, Convexity::Concave)
        );
        // Mirrored, a pocket opening to +x: free space is born, IN concave.
        let mirrored: Vec<_> = pocket.iter().map(|p| Point::new(-p.x, p.y)).collect();
        let r = returns(Point::new(-0.6, 0.0), std::f64::consts::PI, &mirrored);
        assert_eq!(
            det.classify(Point::new(-0.6, 0.0), &r),
            kind(Event::In, Convexity::Concave)
        );
    }

    #[test]
    fn noise_within_the_tolerance_keeps_the_verdict() {
        let det = ThreeRayDetector::for_noise(0.002, 0.25);
        let diamond = [
            Point::new(1.0, 0.0),
            Point::new(2.0, -1.0),
            Point::new(3.0, 0.0),
            Point::new(2.0, 1.0),
        ];
        let wall = [
            Point::new(0.0, -5.0),
            Point::new(4.0, 5.0),
            Point::new(9.0, 5.0),
            Point::new(9.0, -5.0),
        ];
        // Every combination of ±2 mm along the rays (one standard deviation
        // is 2 mm: these are the ±1σ corners of the noise box).
        for signs in 0..27 {
            let s = |k: u32| f64::from((signs / 3u32.pow(k)) % 3) - 1.0;
            let push = |p: Point, from: Point, e: f64| {
                let (dx, dy) = (p.x - from.x, p.y - from.y);
                let n = dx.hypot(dy);
                Point::new(p.x + e * dx / n, p.y + e * dy / n)
            };
            let noisy = |r: Returns, from: Point| Returns {
                lag: push(r.lag, from, 0.002 * s(0)),
                centre: push(r.centre, from, 0.002 * s(1)),
                lead: push(r.lead, from, 0.002 * s(2)),
            };
            let p = Point::new(0.75, 0.0);
            let r = noisy(returns(p, 0.0, &diamond), p);
            assert_eq!(
                det.classify(p, &r),
                kind(Event::In, Convexity::Convex),
                "{signs}"
            );
            let p = Point::new(1.0, -1.0);
            let r = noisy(returns(p, 0.3, &wall), p);
            assert!(
                matches!(det.classify(p, &r), Detection::Straight),
                "{signs}: {:?}",
                det.classify(p, &r)
            );
        }
    }

    #[test]
    fn fires_through_a_sensor_on_a_world() {
        let w = World::parse(
            "(name: \"t\", width: 6.0, height: 4.0, resolution: 0.1, obstacles: [
                Polygon([(2.0, 2.0), (3.0, 1.0), (4.0, 2.0), (3.0, 3.0)])])",
            "t",
        )
        .unwrap();
        let g = WorldGeometry::new(&w);
        let det = ThreeRayDetector::default();
        let mut s = RangeSensor::ring(1, 5.0, 0.0, 0).unwrap();
        let r = det.fire(&mut s, &g, Point::new(1.75, 2.0), 0.0).unwrap();
        assert_eq!(
            det.classify(Point::new(1.75, 2.0), &r),
            kind(Event::In, Convexity::Convex)
        );
        assert!(det.fire(&mut s, &g, Point::new(1.0, 2.0), 0.0).is_some());
        let mut short = RangeSensor::ring(1, 0.5, 0.0, 0).unwrap();
        assert!(
            det.fire(&mut short, &g, Point::new(1.0, 2.0), 0.0)
                .is_none()
        );
    }
}
