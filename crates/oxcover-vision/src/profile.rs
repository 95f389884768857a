//! HSV probability profiles (Pavlíček 2002, §2.1): `free` and `occ` count
//! matrices over a discretised HSV cube, learned from labelled pixels, and
//! `P(R | Occ) = occ / (free + occ)`, or 1 where no sample fell.
//!
//! The paper indexes a reading `(h, s, v) ∈ [0, 1]³` by
//! `(⌈20h⌉, ⌈20s⌉, ⌈20v⌉)`; `⌈0⌉ = 0` would make a 21st bin, so 0 goes to the
//! first bin with the values up to 1/20.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// HSV of an RGB colour, each in `[0, 1]` (hue as a fraction of a turn; 0
/// for greys).
#[must_use]
pub fn hsv([r, g, b]: [u8; 3]) -> (f64, f64, f64) {
    let (r, g, b) = (
        f64::from(r) / 255.0,
        f64::from(g) / 255.0,
        f64::from(b) / 255.0,
    );
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let c = max - min;
    let h = if c == 0.0 {
        0.0
    } else if max == r {
        ((g - b) / c).rem_euclid(6.0) / 6.0
    } else if max == g {
        ((b - r) / c + 2.0) / 6.0
    } else {
        ((r - g) / c + 4.0) / 6.0
    };
    let s = if max == 0.0 { 0.0 } else { c / max };
    (h, s, max)
}

/// The learned counts.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Profile {
    /// Bins per axis (the paper: 20).
    pub bins: usize,
    /// Free samples per bin, `h` slowest, `v` fastest.
    pub free: Vec<u32>,
    /// Occupied samples per bin.
    pub occ: Vec<u32>,
}

impl Profile {
    /// An empty profile of `bins³` bins.
    ///
    /// # Errors
    /// [`Error::BadParameter`] for 0 or more than 256 bins.
    pub fn new(bins: usize) -> Result<Self> {
        if bins == 0 || bins > 256 {
            return Err(Error::BadParameter {
                name: "profile bins",
                value: bins.to_string(),
                expected: "1 to 256 bins per axis",
            });
        }
        Ok(Self {
            bins,
            free: vec![0; bins.pow(3)],
            occ: vec![0; bins.pow(3)],
        })
    }

    /// Checks a profile read from a file: 1 to 256 bins per axis and
    /// `bins³` free and occupied counts.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming `profile`.
    pub fn check(&self) -> Result<()> {
        let cells = (1..=256).contains(&self.bins).then(|| self.bins.pow(3));
        if cells.is_none_or(|n| self.free.len() != n || self.occ.len() != n) {
            return Err(Error::BadParameter {
                name: "profile",
                value: format!(
                    "{} bins, {} free and {} occ counts",
                    self.bins,
                    self.free.len(),
                    self.occ.len()
                ),
                expected: "1 to 256 bins per axis and bins³ free and occ counts",
            });
        }
        Ok(())
    }

    /// The bin of a reading: `⌈n·x⌉` per axis (0 in the first bin).
    #[must_use]
    pub fn index(&self, (h, s, v): (f64, f64, f64)) -> usize {
        let n = self.bins;
        let bin = |x: f64| ((x * n as f64).ceil() as usize).clamp(1, n) - 1;
        (bin(h) * n + bin(s)) * n + bin(v)
    }

    /// Counts one labelled pixel.
    pub fn add(&mut self, rgb: [u8; 3], occupied: bool) {
        let k = self.index(hsv(rgb));
        let counts = if occupied {
            &mut self.occ
        } else {
            &mut self.free
        };
        counts[k] = counts[k].saturating_add(1);
    }

    /// `P(R | Occ)` for a colour: `occ / (free + occ)`, 1 where no sample fell.
    #[must_use]
    pub fn p_occ(&self, rgb: [u8; 3]) -> f64 {
        let k = self.index(hsv(rgb));
        let (f, o) = (f64::from(self.free[k]), f64::from(self.occ[k]));
        if f + o > 0.0 { o / (f + o) } else { 1.0 }
    }

    /// Samples counted.
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.free
            .iter()
            .chain(&self.occ)
            .map(|&c| u64::from(c))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hsv_of_known_colours() {
        let close = |a: (f64, f64, f64), b: (f64, f64, f64)| {
            (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9 && (a.2 - b.2).abs() < 1e-9
        };
        assert!(close(hsv([255, 0, 0]), (0.0, 1.0, 1.0)));
        assert!(close(hsv([0, 255, 0]), (1.0 / 3.0, 1.0, 1.0)));
        assert!(close(hsv([0, 0, 255]), (2.0 / 3.0, 1.0, 1.0)));
        assert!(close(hsv([255, 0, 255]), (5.0 / 6.0, 1.0, 1.0)));
        assert!(close(hsv([128, 128, 128]), (0.0, 0.0, 128.0 / 255.0)));
        assert!(close(hsv([0, 0, 0]), (0.0, 0.0, 0.0)));
    }

    #[test]
    fn profiles_count_and_give_the_paper_s_probability() {
        let mut p = Profile::new(20).unwrap();
        assert_eq!(p.free.len(), 8000);
        // The paper's bins: 0.05 → ⌈1⌉ = bin 1 (index 0), 0.051 → bin 2.
        assert_eq!(p.index((0.0, 0.0, 0.05)), 0);
        assert_eq!(p.index((0.0, 0.0, 0.051)), 1);
        assert_eq!(p.index((1.0, 1.0, 1.0)), 7999);
        let (floor, wall) = ([200, 180, 150], [40, 60, 140]);
        for _ in 0..3 {
            p.add(floor, false);
        }
        p.add(floor, true);
        p.add(wall, true);
        assert!((p.p_occ(floor) - 0.25).abs() < 1e-12);
        assert_eq!(p.p_occ(wall), 1.0);
        // A colour never seen counts as occupied.
        assert_eq!(p.p_occ([0, 255, 0]), 1.0);
        assert_eq!(p.samples(), 5);
        let text = ron::to_string(&p).unwrap();
        assert_eq!(ron::from_str::<Profile>(&text).unwrap(), p);
        assert!(Profile::new(0).is_err());
    }
}
