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
//! beyond that interval (as many cells as its class has places for), and
//! critical points between the same two slices are joined by the short
//! lap-less cells their classes call for.

use oxcover_robot::{Convexity, CriticalKind, Event};
use serde::Serialize;

/// Detections closer than this (m) are one critical point.
pub(crate) const SAME_POINT: f64 = 0.05;
/// Critical points closer than this along x (m) may be joined either way.
const SAME_X: f64 = 0.01;

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
            let (l, r) = self.sides(s);
            if l.len() == 1 && r.len() == 1 && s.criticals.is_empty() {
                let (a, b) = (find(&mut uf, l[0]), find(&mut uf, r[0]));
                uf[a.max(b)] = a.min(b);
            }
        }
        let mut classes: Vec<Vec<usize>> = Vec::new();
        let mut cell_of = vec![usize::MAX; n];
        let mut class_of_root = vec![usize::MAX; n];
        for (k, cell) in cell_of.iter_mut().enumerate() {
            let root = find(&mut uf, k);
            if class_of_root[root] == usize::MAX {
                class_of_root[root] = classes.len();
                classes.push(Vec::new());
            }
            *cell = class_of_root[root];
            classes[class_of_root[root]].push(k);
        }
        let mut edges: Vec<CellEdge> = classes
            .into_iter()
            .enumerate()
            .map(|(id, mut members)| {
                members.sort_by_key(|&k| (self.intervals[k].slice, k));
                CellEdge {
                    id,
                    from: None,
                    to: None,
                    laps: members
                        .iter()
                        .map(|&k| (self.intervals[k].lo, self.intervals[k].hi))
                        .collect(),
                    covered: members.iter().all(|&k| self.intervals[k].done == [true; 2]),
                }
            })
            .collect();
        for s in self.slabs.iter().filter(|s| !s.criticals.is_empty()) {
            self.join_slab(s, &cell_of, &mut edges);
        }
        ReebGraph {
            nodes: self.criticals.clone(),
            edges,
        }
    }

    /// A slab's intervals on its −x slice and on its +x slice.
    fn sides(&self, s: &SlabRecord) -> (Vec<usize>, Vec<usize>) {
        s.intervals
            .iter()
            .partition(|&&k| self.intervals[k].slice == s.left)
    }

    /// Ends the cells entering a slab at its critical points and starts the
    /// cells leaving it there, and adds the short lap-less cells between
    /// critical points of the same slab (closer in x than a lap spacing).
    ///
    /// A critical point's class fixes how many cells it has on each side: a
    /// split one before and two after, a birth none and one, a merge two
    /// and one, a death one and none. The cells crossing the slab's slices
    /// take these places nearest first; places left over are joined in x
    /// order, each point short of a cell after it to the next point along x
    /// short of one before it.
    fn join_slab(&self, s: &SlabRecord, cell_of: &[usize], edges: &mut Vec<CellEdge>) {
        let want = |k: CriticalKind| match (k.event, k.convexity) {
            (Event::In, Convexity::Convex) => (1usize, 2usize),
            (Event::In, Convexity::Concave) => (0, 1),
            (Event::Out, Convexity::Convex) => (2, 1),
            (Event::Out, Convexity::Concave) => (1, 0),
        };
        let ks = &s.criticals;
        let mut before: Vec<usize> = ks.iter().map(|&c| want(self.criticals[c].kind).0).collect();
        let mut after: Vec<usize> = ks.iter().map(|&c| want(self.criticals[c].kind).1).collect();
        let distance = |iv: usize, c: usize| {
            let (iv, p) = (&self.intervals[iv], self.criticals[c].at);
            let y = p.1.clamp(iv.lo.1, iv.hi.1);
            (p.0 - iv.lo.0).hypot(p.1 - y)
        };
        let (left, right) = self.sides(s);
        // Nearest first, within the places each class has; a cell left
        // without a place ends at its nearest critical point regardless.
        for (ends, places, entering) in [(&left, &mut before, true), (&right, &mut after, false)] {
            let mut pairs: Vec<(f64, usize, usize)> = ends
                .iter()
                .flat_map(|&iv| (0..ks.len()).map(move |j| (iv, j)))
                .map(|(iv, j)| (distance(iv, ks[j]), iv, j))
                .collect();
            pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
            let mut placed = vec![false; ends.len()];
            let slot = |iv: usize| ends.iter().position(|&e| e == iv).unwrap_or(0);
            for &(_, iv, j) in &pairs {
                if !placed[slot(iv)] && places[j] > 0 {
                    places[j] -= 1;
                    placed[slot(iv)] = true;
                    let e = &mut edges[cell_of[iv]];
                    if entering {
                        e.to = Some(ks[j])
                    } else {
                        e.from = Some(ks[j])
                    }
                }
            }
            for &(_, iv, j) in &pairs {
                if !placed[slot(iv)] {
                    placed[slot(iv)] = true;
                    let e = &mut edges[cell_of[iv]];
                    if entering {
                        e.to = Some(ks[j])
                    } else {
                        e.from = Some(ks[j])
                    }
                }
            }
        }
        // Points at the same x (within a centimetre: obstacles whose ends
        // line up) may be joined either way, but not both ways.
        let x = |j: usize| self.criticals[ks[j]].at.0;
        let mut pairs: Vec<(usize, usize)> = (0..ks.len())
            .flat_map(|a| (0..ks.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| a != b && x(b) >= x(a) - SAME_X)
            .collect();
        pairs.sort_by(|p, q| {
            (x(p.1) - x(p.0))
                .abs()
                .total_cmp(&(x(q.1) - x(q.0)).abs())
                .then(p.cmp(q))
        });
        let mut joined: Vec<(usize, usize)> = Vec::new();
        for (a, b) in pairs {
            if !joined.contains(&(b, a)) {
                while after[a] > 0 && before[b] > 0 {
                    joined.push((a, b));
                    edges.push(CellEdge {
                        id: edges.len(),
                        from: Some(ks[a]),
                        to: Some(ks[b]),
                        laps: Vec::new(),
                        covered: true,
                    });
                    after[a] -= 1;
                    before[b] -= 1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn two_merges_between_the_same_slices_are_joined_by_a_lapless_cell() {
        // A C opening to +x whose arms end at x = 7.1 (upper) and 7.2
        // (lower), both between slices 7.0 and 7.5: above the C, its pocket
        // and below it enter the slab; one cell leaves it.
        let mut r = Reeb::default();
        let above = r.interval(14, (7.0, 7.6), (7.0, 9.8));
        let pocket = r.interval(14, (7.0, 4.5), (7.0, 5.6));
        let below = r.interval(14, (7.0, 0.2), (7.0, 2.5));
        let after = r.interval(15, (7.5, 0.2), (7.5, 9.8));
        let upper = r.critical((7.1, 6.0), (7.34, 6.0), (6.0, 6.0), OUT_CONVEX, true, 0.01);
        let lower = r.critical((7.2, 4.0), (7.44, 4.0), (4.0, 4.0), OUT_CONVEX, true, 0.01);
        r.slabs.push(SlabRecord {
            left: 14,
            intervals: vec![above, pocket, below, after],
            criticals: vec![upper, lower],
        });
        let g = r.graph();
        let ends = |iv: usize| {
            let lap = (r.intervals[iv].lo, r.intervals[iv].hi);
            let e = g
                .edges
                .iter()
                .find(|e| e.laps.contains(&lap))
                .expect("a cell");
            (e.from, e.to)
        };
        assert_eq!(ends(above).1, Some(upper));
        assert_eq!(ends(pocket).1, Some(upper));
        assert_eq!(ends(below).1, Some(lower));
        assert_eq!(ends(after).0, Some(lower));
        let short: Vec<_> = g.edges.iter().filter(|e| e.laps.is_empty()).collect();
        assert_eq!(short.len(), 1);
        assert_eq!((short[0].from, short[0].to), (Some(upper), Some(lower)));
        // Four cells with laps and the lap-less one.
        assert_eq!(g.edges.len(), 5);
    }
}
