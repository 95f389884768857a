//! The incremental Reeb graph: lap intervals on the slices, the slab
//! components traced between them, and the critical points found in them.
//!
//! Slices are the lines `x = x₀ + j·w` (`w` the lap spacing). An
//! *interval* is one lap: a free stretch of a slice from one boundary
//! contact to the next. A *slab record* is one traced component of the free
//! space between slices `j` and `j + 1`: the intervals on either slice its
//! boundary touches and the critical points on that boundary.
//!
//! A slab that joins exactly one interval on each side and holds no
//! critical point continues a cell; union-find over such joins gives the
//! cells. The graph's nodes are the critical points, its edges the cells:
//! each cell ends at the critical point nearest its end interval in the slab
//! beyond that interval.

use oxcover_robot::CriticalKind;
use serde::Serialize;

/// Detections closer than this (m) are one critical point.
pub(crate) const SAME_POINT: f64 = 0.05;

/// One lap interval.
#[derive(Clone, Debug)]
pub(crate) struct Interval {
    /// Slice index.
    pub slice: i64,
    /// Lower contact (robot position).
    pub lo: (f64, f64),
    /// Upper contact (robot position).
    pub hi: (f64, f64),
    /// Whether the slab towards −x (index 0) and towards +x (index 1) has been traced.
    pub done: [bool; 2],
}

/// One traced slab component.
#[derive(Clone, Debug, Default)]
pub(crate) struct SlabRecord {
    /// The slice on its −x side.
    pub left: i64,
    /// Intervals its boundary touches, on both slices.
    pub intervals: Vec<usize>,
    /// Critical points on its boundary.
    pub criticals: Vec<usize>,
}

/// A critical point the robot found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetectedCritical {
    /// Index in the list.
    pub id: usize,
    /// The boundary point the detector's centre ray hit (m).
    pub at: (f64, f64),
    /// Where the robot was (m).
    pub robot: (f64, f64),
    /// The robot's y range along the stretch it followed within the
    /// hysteresis of this extreme (a point, or a wall along y).
    pub span: (f64, f64),
    /// Class.
    pub kind: CriticalKind,
    /// Whether the three-ray detector gave this class on its own (else the
    /// class comes from the boundary follower's turn).
    pub confirmed: bool,
}

/// A cell: an edge of the Reeb graph.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CellEdge {
    /// Index in the list.
    pub id: usize,
    /// Critical point at its −x end, if found.
    pub from: Option<usize>,
    /// Critical point at its +x end, if found.
    pub to: Option<usize>,
    /// Its laps, in x order: (lower, upper) robot positions.
    pub laps: Vec<((f64, f64), (f64, f64))>,
    /// Whether the slabs on both sides of every lap have been traced.
    pub covered: bool,
}

/// The discovered graph.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ReebGraph {
    /// Critical points.
    pub nodes: Vec<DetectedCritical>,
    /// Cells.
    pub edges: Vec<CellEdge>,
}

/// The explorer's bookkeeping.
#[derive(Clone, Debug, Default)]
pub(crate) struct Reeb {
    pub intervals: Vec<Interval>,
    pub slabs: Vec<SlabRecord>,
    pub criticals: Vec<DetectedCritical>,
}

impl Reeb {
    /// The interval `(lo, hi)` on `slice`: a known one it overlaps, or a new one.
    pub(crate) fn interval(&mut self, slice: i64, a: (f64, f64), b: (f64, f64)) -> usize {
        let (lo, hi) = if a.1 <= b.1 { (a, b) } else { (b, a) };
        let len = hi.1 - lo.1;
        let found = self.intervals.iter().position(|k| {
            if k.slice != slice {
                return false;
            }
            let overlap = hi.1.min(k.hi.1) - lo.1.max(k.lo.1);
            let shorter = len.min(k.hi.1 - k.lo.1);
            overlap > 0.5 * shorter
                || ((lo.1 - k.lo.1).abs() < SAME_POINT && (hi.1 - k.hi.1).abs() < SAME_POINT)
        });
        found.unwrap_or_else(|| {
            self.intervals.push(Interval {
                slice,
                lo,
                hi,
                done: [false; 2],
            });
            self.intervals.len() - 1
        })
    }

    /// Adds a detection, or returns the known critical point it repeats:
    /// one whose contact lies within [`SAME_POINT`], or one of the same class
    /// whose stretch lies on the same wall along y (robot x within twice the
    /// hysteresis, y ranges overlapping).
    pub(crate) fn critical(
        &mut self,
        at: (f64, f64),
        robot: (f64, f64),
        span: (f64, f64),
        kind: CriticalKind,
        confirmed: bool,
        hysteresis: f64,
    ) -> usize {
        if let Some(c) = self.criticals.iter().find(|c| {
            (c.at.0 - at.0).hypot(c.at.1 - at.1) < SAME_POINT
                || ((c.robot.0 - robot.0).abs() <= 2.0 * hysteresis
                    && c.span.0 <= span.1 + SAME_POINT
                    && span.0 <= c.span.1 + SAME_POINT
                    && c.kind == kind)
        }) {
            return c.id;
        }
        let id = self.criticals.len();
        self.criticals.push(DetectedCritical {
            id,
            at,
            robot,
            span,
            kind,
            confirmed,
        });
        id
    }

    /// The graph as it stands.
    pub(crate) fn graph(&self) -> ReebGraph {
        let n = self.intervals.len();
        let mut uf: Vec<usize> = (0..n).collect();
        fn find(uf: &mut [usize], mut k: usize) -> usize {
            while uf[k] != k {
                uf[k] = uf[uf[k]];
                k = uf[k];
            }
            k
        }
        for s in &self.slabs {
            let (l, r): (Vec<usize>, Vec<usize>) = s
                .intervals
                .iter()
                .partition(|&&k| self.intervals[k].slice == s.left);
            if l.len() == 1 && r.len() == 1 && s.criticals.is_empty() {
                let (a, b) = (find(&mut uf, l[0]), find(&mut uf, r[0]));
                uf[a.max(b)] = a.min(b);
            }
        }
        let mut classes: Vec<Vec<usize>> = Vec::new();
        let mut class_of = vec![usize::MAX; n];
        for k in 0..n {
            let root = find(&mut uf, k);
            if class_of[root] == usize::MAX {
                class_of[root] = classes.len();
                classes.push(Vec::new());
            }
            classes[class_of[root]].push(k);
        }
        let edges = classes
            .into_iter()
            .enumerate()
            .map(|(id, mut members)| {
                members.sort_by_key(|&k| (self.intervals[k].slice, k));
                let first = members[0];
                let last = members[members.len() - 1];
                CellEdge {
                    id,
                    from: self.end_node(first, self.intervals[first].slice - 1),
                    to: self.end_node(last, self.intervals[last].slice),
                    laps: members
                        .iter()
                        .map(|&k| (self.intervals[k].lo, self.intervals[k].hi))
                        .collect(),
                    covered: members.iter().all(|&k| self.intervals[k].done == [true; 2]),
                }
            })
            .collect();
        ReebGraph {
            nodes: self.criticals.clone(),
            edges,
        }
    }

    /// The critical point nearest interval `k` in the slab (left slice
    /// `left`) that touched it.
    fn end_node(&self, k: usize, left: i64) -> Option<usize> {
        let iv = &self.intervals[k];
        let slab = self
            .slabs
            .iter()
            .find(|s| s.left == left && s.intervals.contains(&k))?;
        slab.criticals
            .iter()
            .map(|&c| {
                let p = self.criticals[c].at;
                let y = p.1.clamp(iv.lo.1, iv.hi.1);
                ((p.0 - iv.lo.0).hypot(p.1 - y), c)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, c)| c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_robot::{Convexity, Event};

    const IN_CONVEX: CriticalKind = CriticalKind {
        event: Event::In,
        convexity: Convexity::Convex,
    };
    const OUT_CONVEX: CriticalKind = CriticalKind {
        event: Event::Out,
        convexity: Convexity::Convex,
    };

    #[test]
    fn intervals_match_on_their_slice_only() {
        let mut r = Reeb::default();
        let a = r.interval(0, (0.0, 0.2), (0.0, 3.0));
        assert_eq!(r.interval(0, (0.0, 2.9), (0.0, 0.25)), a);
        assert_ne!(r.interval(1, (0.5, 0.2), (0.5, 3.0)), a);
        // Another interval of the same slice, past an obstacle.
        assert_ne!(r.interval(0, (0.0, 3.5), (0.0, 5.0)), a);
        assert_eq!(r.intervals.len(), 3);
    }

    #[test]
    fn repeats_merge_and_walls_along_y_are_one_point() {
        let mut r = Reeb::default();
        let a = r.critical((1.0, 1.0), (0.76, 1.0), (1.0, 1.0), IN_CONVEX, true, 0.01);
        assert_eq!(
            r.critical(
                (1.02, 1.01),
                (0.78, 1.01),
                (1.01, 1.01),
                IN_CONVEX,
                true,
                0.01
            ),
            a
        );
        // One wall along y found at two heights: the same critical stretch.
        let w = r.critical((5.0, 1.0), (4.76, 1.0), (0.5, 2.0), OUT_CONVEX, true, 0.01);
        assert_eq!(
            r.critical((5.0, 1.8), (4.765, 1.8), (1.5, 2.5), OUT_CONVEX, true, 0.01),
            w
        );
        // Facing walls of a narrow gap at nearly the same x stay apart.
        assert_ne!(
            r.critical(
                (5.5, 1.5),
                (4.77, 1.5),
                (1.0, 2.0),
                CriticalKind {
                    convexity: Convexity::Concave,
                    ..OUT_CONVEX
                },
                true,
                0.01
            ),
            w
        );
        assert_eq!(r.criticals.len(), 3);
    }

    #[test]
    fn a_split_and_a_merge_make_four_cells() {
        // Slices 0 to 3 and an obstacle from x = 1.5 to 2.5, laid out by
        // hand: slab 0–1 plain, slab 1–2 holds the split (one interval on
        // slice 1, two on slice 2), slab 2–3 the merge.
        let mut r = Reeb::default();
        let i0 = r.interval(0, (0.0, 0.0), (0.0, 4.0));
        let i1 = r.interval(1, (1.0, 0.0), (1.0, 4.0));
        let lo2 = r.interval(2, (2.0, 0.0), (2.0, 1.5));
        let hi2 = r.interval(2, (2.0, 2.5), (2.0, 4.0));
        let i3 = r.interval(3, (3.0, 0.0), (3.0, 4.0));
        let split = r.critical((1.5, 2.0), (1.26, 2.0), (2.0, 2.0), IN_CONVEX, true, 0.01);
        let merge = r.critical((2.5, 2.0), (2.74, 2.0), (2.0, 2.0), OUT_CONVEX, true, 0.01);
        let slab = |left, intervals: Vec<usize>, criticals: Vec<usize>| SlabRecord {
            left,
            intervals,
            criticals,
        };
        r.slabs = vec![
            slab(0, vec![i0, i1], vec![]),
            slab(1, vec![i1, lo2, hi2], vec![split]),
            slab(2, vec![lo2, hi2, i3], vec![merge]),
        ];
        for iv in &mut r.intervals {
            iv.done = [true; 2];
        }
        let g = r.graph();
        assert_eq!(g.edges.len(), 4);
        let ends: Vec<_> = g
            .edges
            .iter()
            .map(|e| (e.from, e.to, e.laps.len()))
            .collect();
        assert!(ends.contains(&(None, Some(split), 2)));
        assert_eq!(
            ends.iter()
                .filter(|e| **e == (Some(split), Some(merge), 1))
                .count(),
            2
        );
        assert!(ends.contains(&(Some(merge), None, 1)));
        assert!(g.edges.iter().all(|e| e.covered));
    }
}
