//! The Archimedean spiral of Lee 2011's spiral path: `r = (R/π)|θ|`, so that
//! successive turns lie `2R` apart (one tool diameter, `R` the tool radius).
//! In the robot's start frame (origin at the start, x along its heading):
//! `x = r cos θ`, `y = r sin θ`.

use crate::error::{Result, positive};
use oxcover_grid::Point;

/// An outward Archimedean spiral for a tool of radius `R`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArchimedeanSpiral {
    /// Tool radius `R` (m).
    pub tool_radius: f64,
}

impl ArchimedeanSpiral {
    /// A spiral for a tool of radius `tool_radius` (finite, positive).
    ///
    /// # Errors
    /// [`crate::Error::BadParameter`] for a bad radius.
    pub fn new(tool_radius: f64) -> Result<Self> {
        Ok(Self {
            tool_radius: positive("tool radius", tool_radius)?,
        })
    }

    /// `R / π`: the radius gained per radian.
    fn a(&self) -> f64 {
        self.tool_radius / std::f64::consts::PI
    }

    /// The point at accumulated angle `theta` (start frame).
    #[must_use]
    pub fn point(&self, theta: f64) -> Point {
        let r = self.a() * theta.abs();
        Point::new(r * theta.cos(), r * theta.sin())
    }

    /// Arc length from the centre to `theta` (closed form:
    /// `(a/2)(θ√(1+θ²) + asinh θ)`).
    #[must_use]
    pub fn length(&self, theta: f64) -> f64 {
        let t = theta.abs();
        self.a() / 2.0 * (t * (1.0 + t * t).sqrt() + t.asinh())
    }

    /// Points from the centre out to `theta_max`, no two more than `step`
    /// metres of arc apart.
    #[must_use]
    pub fn points(&self, theta_max: f64, step: f64) -> Vec<Point> {
        let theta_max = if theta_max.is_finite() {
            theta_max.abs()
        } else {
            0.0
        };
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            self.tool_radius / 4.0
        };
        let mut out = vec![Point::origin()];
        let mut theta: f64 = 0.0;
        while theta < theta_max {
            // ds/dθ = a√(1+θ²) grows with θ: taken at the step's far end,
            // it bounds the arc (and so the chord) by `step`.
            let guess = step / (self.a() * (1.0 + theta * theta).sqrt());
            let far = theta + guess;
            let dtheta = (step / (self.a() * (1.0 + far * far).sqrt())).min(0.5);
            theta = (theta + dtheta).min(theta_max);
            out.push(self.point(theta));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn turns_are_one_tool_diameter_apart() {
        let s = ArchimedeanSpiral::new(0.15).unwrap();
        for theta in [0.5, 2.0, 7.0] {
            let (a, b) = (s.point(theta), s.point(theta + 2.0 * PI));
            let gap = b.x.hypot(b.y) - a.x.hypot(a.y);
            assert!((gap - 0.3).abs() < 1e-12, "{gap}");
        }
        assert_eq!(s.point(0.0), Point::new(0.0, 0.0));
        assert!(ArchimedeanSpiral::new(-1.0).is_err());
    }

    #[test]
    fn sampled_length_matches_the_closed_form() {
        let s = ArchimedeanSpiral::new(0.15).unwrap();
        let pts = s.points(6.0 * PI, 0.005);
        let poly: f64 = pts
            .windows(2)
            .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
            .sum();
        let exact = s.length(6.0 * PI);
        assert!((poly - exact).abs() / exact < 1e-4, "{poly} vs {exact}");
        assert!(
            pts.windows(2)
                .all(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y) <= 0.005 + 1e-9)
        );
    }
}
