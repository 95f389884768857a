//! A path's estimated time split into the bound, the drive beyond it,
//! turns and bends, and its time efficiency under time models other than
//! the contract's.

use oxcover::planners::TimeModel;
use oxcover_grid::Point;
use oxcover_grid::math::wrap_angle;

/// Heading changes up to this are "gentle" (the contract's turn threshold).
const GENTLE_RAD: f64 = 30.0 * std::f64::consts::PI / 180.0;

/// Time efficiency (`bound / time`) of the polyline `points` under three
/// time models other than the contract's, which charges every heading
/// change as a stop and a turn on the spot (`length / v + rotation / w`):
/// turns of at most [`GENTLE_RAD`] taken while driving (a segment takes
/// the longer of its drive and the turn before it; sharper turns as the
/// contract charges them); every turn taken while driving; turning free
/// (the drive alone), over the path's [`legs`].
pub(super) fn other_models(points: &[Point], bound: f64, time: &TimeModel) -> [f64; 3] {
    let (v, w) = (time.linear_speed, time.angular_speed);
    let mut times = [0.0f64; 3];
    for (length, turn) in legs(points) {
        let (drive, spin) = (length / v, turn / w);
        times[0] += if turn <= GENTLE_RAD {
            drive.max(spin)
        } else {
            drive + spin
        };
        times[1] += drive.max(spin);
        times[2] += drive;
    }
    times.map(|t| if t > 0.0 { bound / t } else { 0.0 })
}

/// Each segment of the polyline `points` as its length and the heading
/// change (radians, absolute) from the segment before it (0 for the
/// first); repeated points are skipped, as the contract's rotation skips
/// them.
fn legs(points: &[Point]) -> impl Iterator<Item = (f64, f64)> + '_ {
    let mut heading: Option<f64> = None;
    let mut last: Option<Point> = None;
    points.iter().filter_map(move |&p| {
        let a = last.filter(|&a| a != p);
        last = Some(p);
        let d = p - a?;
        let h = d.y.atan2(d.x);
        let turn = heading.map_or(0.0, |g| wrap_angle(h - g).abs());
        heading = Some(h);
        Some((d.norm(), turn))
    })
}

/// A path's estimated time under the contract's model, in parts (seconds).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct TimeSplit {
    /// The contract's `bound_time_s`.
    pub(super) bound: f64,
    /// Driving beyond the bound: overlap, links, transits.
    pub(super) overlap: f64,
    /// Turning at the contract's turns (heading changes above 30°).
    pub(super) turns: f64,
    /// Turning at bends of at most 30° (along curved and ragged walls,
    /// straightened staircases).
    pub(super) bends: f64,
}

impl TimeSplit {
    /// The estimated time (seconds).
    pub(super) fn total(&self) -> f64 {
        self.bound + self.overlap + self.turns + self.bends
    }
}

/// `points`' estimated time (`length / v + rotation / w`) split into the
/// bound, the drive beyond it, and the turning at heading changes above
/// [`GENTLE_RAD`] (the contract's turns) and at or below it, over the
/// path's [`legs`]; the contract merges segments shorter than a quarter cell before it counts
/// turns, this split does not (it splits the rotation, which is summed
/// over every heading change).
pub(super) fn time_split(points: &[Point], bound: f64, time: &TimeModel) -> TimeSplit {
    let (v, w) = (time.linear_speed, time.angular_speed);
    let mut split = TimeSplit {
        bound,
        overlap: -bound,
        ..TimeSplit::default()
    };
    for (length, turn) in legs(points) {
        split.overlap += length / v;
        if turn > GENTLE_RAD {
            split.turns += turn / w;
        } else {
            split.bends += turn / w;
        }
    }
    split
}

#[cfg(test)]
mod tests {
    use super::super::ceilings::split_summary;
    use super::*;

    #[test]
    fn other_time_models_charge_turns_as_they_say() {
        let time = TimeModel::default();
        let (v, w) = (time.linear_speed, time.angular_speed);
        let pts = |xy: &[(f64, f64)]| {
            xy.iter()
                .map(|&(x, y)| Point::new(x, y))
                .collect::<Vec<_>>()
        };
        // A U-turn: 3 m, a quarter turn, 0.3 m, a quarter turn, 3 m (a
        // repeated point changes nothing).
        let u = pts(&[(0.0, 0.0), (3.0, 0.0), (3.0, 0.3), (3.0, 0.3), (0.0, 0.3)]);
        let q = std::f64::consts::FRAC_PI_2;
        let [gentle, every, free] = other_models(&u, 1.0, &time);
        // Quarter turns are sharp: charged in full but when every turn is
        // taken while driving (the link then takes the turn's time, the lane
        // its drive).
        assert!((1.0 / gentle - (6.3 / v + 2.0 * q / w)).abs() < 1e-9);
        assert!((1.0 / every - (3.0 / v + q / w + 3.0 / v)).abs() < 1e-9);
        assert!((1.0 / free - 6.3 / v).abs() < 1e-9);
        // Gentle bends along a 1 m step: each bend hides in its segment.
        let bend = pts(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.2), (3.0, 0.4)]);
        let [gentle, every, _] = other_models(&bend, 1.0, &time);
        let drive = (1.0 + 2.0 * 1.04f64.sqrt()) / v;
        assert!((1.0 / gentle - drive).abs() < 1e-9);
        assert!((1.0 / every - drive).abs() < 1e-9);
        // No path, no time: no efficiency.
        assert_eq!(other_models(&[], 1.0, &time), [0.0; 3]);
    }

    #[test]
    fn the_time_split_adds_up_to_the_estimated_time() {
        let time = TimeModel::default();
        let (v, w) = (time.linear_speed, time.angular_speed);
        let q = std::f64::consts::FRAC_PI_2;
        // A U-turn (two quarter turns: turns) then a bend of 0.2 rad.
        let (c, s) = (0.2f64.cos(), 0.2f64.sin());
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(3.0, 0.0),
            Point::new(3.0, 0.3),
            Point::new(3.0, 0.3),
            Point::new(0.0, 0.3),
            Point::new(-c, 0.3 + s),
        ];
        let t = time_split(&pts, 10.0, &time);
        let length = 6.3 + 1.0;
        assert!((t.total() - time.time(length, 2.0 * q + 0.2)).abs() < 1e-9);
        assert!((t.bound - 10.0).abs() < 1e-12);
        assert!((t.overlap - (length / v - 10.0)).abs() < 1e-9);
        assert!((t.turns - 2.0 * q / w).abs() < 1e-9);
        assert!((t.bends - 0.2 / w).abs() < 1e-9);
        // Each part free in turn.
        let text = split_summary("p", &[t]);
        let over = t.total() - t.bound;
        assert!(
            text.contains(&format!("bends {:.0} %", 100.0 * t.bends / over)),
            "{text}"
        );
        assert!(
            text.contains(&format!("bends free: {:.3}", 10.0 / (t.total() - t.bends))),
            "{text}"
        );
    }
}
