//! Metre-space types shared by the whole workspace.
//!
//! Every quantity in metres (waypoints, origins, offsets) uses these aliases on
//! nalgebra, so algorithms are written once and callers never convert between
//! point types. Cell-space quantities use [`crate::Cell`] instead.

/// The scalar used for metre-space quantities.
pub type Real = f64;

/// A point in the map frame, in metres.
pub type Point = nalgebra::Point2<Real>;

/// A displacement in the map frame, in metres.
pub type Vector = nalgebra::Vector2<Real>;

/// A planar pose: position in metres, heading in radians (counter-clockwise
/// from the x axis), in the map frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pose {
    /// x (m).
    pub x: Real,
    /// y (m).
    pub y: Real,
    /// Heading (rad).
    pub theta: Real,
}

impl Pose {
    /// A pose.
    #[must_use]
    pub const fn new(x: Real, y: Real, theta: Real) -> Self {
        Self { x, y, theta }
    }

    /// The position.
    #[must_use]
    pub fn position(&self) -> Point {
        Point::new(self.x, self.y)
    }

    /// Euclidean distance between the positions.
    #[must_use]
    pub fn distance(&self, other: &Self) -> Real {
        (self.x - other.x).hypot(self.y - other.y)
    }
}

/// Builds a [`Point`] from its coordinates.
#[must_use]
pub fn point(x: Real, y: Real) -> Point {
    Point::new(x, y)
}

/// `√(x² + y²)`, without `hypot`'s care for overflow (for hot paths on
/// coordinates that are metres or cells, far from overflow).
#[must_use]
#[inline]
pub fn norm(x: Real, y: Real) -> Real {
    (x * x + y * y).sqrt()
}

/// Heading of a displacement in radians, in `(-pi, pi]`, measured from +x towards +y.
#[must_use]
pub fn heading(v: &Vector) -> Real {
    v.y.atan2(v.x)
}

/// Wraps an angle to `(-pi, pi]`.
#[must_use]
pub fn wrap_angle(a: Real) -> Real {
    use std::f64::consts::PI;
    let mut a = a % (2.0 * PI);
    if a <= -PI {
        a += 2.0 * PI;
    } else if a > PI {
        a -= 2.0 * PI;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn wrap_angle_stays_in_half_open_interval() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(0.5) - 0.5).abs() < 1e-12);
        assert!((wrap_angle(-0.5 - 2.0 * PI) + 0.5).abs() < 1e-12);
    }

    #[test]
    fn heading_of_axes() {
        assert!((heading(&Vector::new(0.0, 1.0)) - PI / 2.0).abs() < 1e-12);
        assert!((heading(&Vector::new(-1.0, 0.0)) - PI).abs() < 1e-12);
    }
}
