//! Metre-space types shared by the whole workspace.
//!
//! Also [`fast_floor`] and [`fast_ceil`]: `f64::floor` and `f64::ceil` for
//! the hot paths that floor grid coordinates per cell or per sample.
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

/// Magnitude from which every `f64` is an integer (2⁵²).
const INTEGRAL: Real = 4_503_599_627_370_496.0;

/// `v.floor()` without a library call, for hot paths that floor grid
/// coordinates millions of times per plan: on x86-64's baseline (no
/// SSE4.1) `f64::floor` is a software routine. The same value for every
/// `v` (infinite and NaN through `f64::floor`), except that `-0.0` gives
/// `0.0`.
#[must_use]
#[inline]
pub fn fast_floor(v: Real) -> Real {
    if v.abs() < INTEGRAL {
        // Truncation, then one down for a negative fraction: exact, since
        // every integer below 2⁵³ is an `f64`.
        let t = v as i64 as Real;
        if t > v { t - 1.0 } else { t }
    } else {
        v.floor()
    }
}

/// `v.ceil()` as [`fast_floor`] gives `v.floor()` (`0.0` gives `-0.0`).
#[must_use]
#[inline]
pub fn fast_ceil(v: Real) -> Real {
    -fast_floor(-v)
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

    #[test]
    fn fast_floor_and_ceil_match_the_library() {
        let mut values = vec![
            0.0,
            0.5,
            1.0,
            1.5,
            -0.5,
            -1.0,
            -1.5,
            2.999_999_999_999_999_6,
            -2.000_000_000_000_000_4,
            1e-300,
            -1e-300,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            9.1e15,
            -9.1e15,
            1e300,
            -1e300,
        ];
        // Seeded: a fixed linear congruential sequence over many scales.
        let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..10_000 {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let mantissa = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let scale = 10f64.powi(((s >> 3) % 20) as i32 - 4);
            values.push(mantissa * scale);
        }
        for v in values {
            assert_eq!(fast_floor(v), v.floor(), "floor {v}");
            assert_eq!(fast_ceil(v), v.ceil(), "ceil {v}");
        }
        assert!(fast_floor(Real::NAN).is_nan());
        assert_eq!(fast_floor(Real::INFINITY), Real::INFINITY);
        assert_eq!(fast_ceil(Real::NEG_INFINITY), Real::NEG_INFINITY);
    }
}
