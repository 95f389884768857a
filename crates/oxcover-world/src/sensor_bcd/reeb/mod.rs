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
//! critical point continues a cell. In any other slab, a line swept across
//! the boundary the robot traced round the component gives the pieces of
//! free space between its critical points, which join laps and each other
//! one to one or meet at a critical point; critical points at the same x
//! share out their places by class. Union-find over all of these gives the
//! cells. The graph's nodes are the critical points, its edges the cells
//! (those between two critical points of one slab hold no lap).

use crate::{Convexity, CriticalKind, Event};
use oxcover_grid::Point;
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
    pub lo: Point,
    /// Upper contact (robot position).
    pub hi: Point,
    /// Whether the slab towards −x (index 0) and towards +x (index 1) has been traced.
    pub done: [bool; 2],
}

/// One traced slab component.
#[derive(Clone, Debug, Default)]
pub(crate) struct SlabRecord {
    /// The slice on its −x side.
    pub left: i64,
    /// The x of its two slices.
    pub x: (f64, f64),
    /// Intervals its boundary touches, on both slices.
    pub intervals: Vec<usize>,
    /// Critical points on its boundary.
    pub criticals: Vec<usize>,
    /// The robot's positions round the component's boundary (closed by the
    /// start interval's lap).
    pub boundary: Vec<Point>,
}

/// A critical point the robot found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetectedCritical {
    /// Index in the list.
    pub id: usize,
    /// The boundary point the detector's centre ray hit (m).
    pub at: Point,
    /// Where the robot was (m).
    pub robot: Point,
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
    pub laps: Vec<(Point, Point)>,
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
    pub(crate) fn interval(&mut self, slice: i64, a: Point, b: Point) -> usize {
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        let len = hi.y - lo.y;
        let found = self.intervals.iter().position(|k| {
            if k.slice != slice {
                return false;
            }
            let overlap = hi.y.min(k.hi.y) - lo.y.max(k.lo.y);
            let shorter = len.min(k.hi.y - k.lo.y);
            overlap > 0.5 * shorter
                || ((lo.y - k.lo.y).abs() < SAME_POINT && (hi.y - k.hi.y).abs() < SAME_POINT)
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
        at: Point,
        robot: Point,
        span: (f64, f64),
        kind: CriticalKind,
        confirmed: bool,
        hysteresis: f64,
    ) -> usize {
        if let Some(c) = self.criticals.iter().find(|c| {
            (c.at.x - at.x).hypot(c.at.y - at.y) < SAME_POINT
                || ((c.robot.x - robot.x).abs() <= 2.0 * hysteresis
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
    ///
    /// Cells are chains of pieces joined one to one: the lap intervals, and
    /// inside every slab whose component holds critical points, the pieces
    /// of free space between its critical points (see [`Reeb::sweep_slab`]).
    pub(crate) fn graph(&self) -> ReebGraph {
        let n = self.intervals.len();
        let mut uf = UnionFind::new(n);
        // (piece, critical point, whether the piece's cell ends there)
        let mut ends: Vec<(usize, usize, bool)> = Vec::new();
        let mut short: Vec<(usize, usize)> = Vec::new();
        for s in &self.slabs {
            let (l, r) = self.sides(s);
            if l.len() == 1 && r.len() == 1 && s.criticals.is_empty() {
                uf.union(l[0], r[0]);
            } else if !self.sweep_slab(s, &mut uf, &mut ends, &mut short) {
                self.join_slab(s, &mut ends, &mut short);
            }
        }
        let mut class_of = vec![usize::MAX; uf.len()];
        let mut members: Vec<Vec<usize>> = Vec::new();
        for k in 0..uf.len() {
            let root = uf.find(k);
            if class_of[root] == usize::MAX {
                class_of[root] = members.len();
                members.push(Vec::new());
            }
            members[class_of[root]].push(k);
        }
        let mut from = vec![None; members.len()];
        let mut to = vec![None; members.len()];
        for &(piece, c, ends_there) in &ends {
            let cell = class_of[uf.find(piece)];
            let slot = if ends_there {
                &mut to[cell]
            } else {
                &mut from[cell]
            };
            slot.get_or_insert(c);
        }
        let mut edges: Vec<CellEdge> = Vec::new();
        for (cell, mut m) in members.into_iter().enumerate() {
            m.retain(|&k| k < n);
            // Pieces that never met a lap form a cell only between two
            // critical points (the short cells inside one slab).
            if m.is_empty() && (from[cell].is_none() || to[cell].is_none()) {
                continue;
            }
            m.sort_by_key(|&k| (self.intervals[k].slice, k));
            edges.push(CellEdge {
                id: edges.len(),
                from: from[cell],
                to: to[cell],
                laps: m
                    .iter()
                    .map(|&k| (self.intervals[k].lo, self.intervals[k].hi))
                    .collect(),
                covered: m.iter().all(|&k| self.intervals[k].done == [true; 2]),
            });
        }
        for (a, b) in short {
            edges.push(CellEdge {
                id: edges.len(),
                from: Some(a),
                to: Some(b),
                laps: Vec::new(),
                covered: true,
            });
        }
        ReebGraph {
            nodes: self.criticals.clone(),
            edges,
        }
    }

    /// The cells through a slab from the boundary the robot traced round
    /// its component: sweeping a line x = const from slice to slice, the
    /// free pieces of the line (between crossings of the traced boundary)
    /// change only at the critical points. Between two neighbouring
    /// critical points, a piece that overlaps exactly one piece on the
    /// other side (and that one only it) is the same cell; anything else
    /// (a split, a merge, a birth, a death) meets at the critical point
    /// between them. The pieces next to the slices join the laps there.
    /// `false` when the traced boundary cannot be read this way (an odd
    /// number of crossings); the caller then falls back on the classes.
    fn sweep_slab(
        &self,
        s: &SlabRecord,
        uf: &mut UnionFind,
        ends: &mut Vec<(usize, usize, bool)>,
        short: &mut Vec<(usize, usize)>,
    ) -> bool {
        let b = &s.boundary;
        if b.len() < 3 {
            return false;
        }
        let (xa, xb) = s.x;
        // Critical points by x, those closer than a millimetre as one event.
        let mut events: Vec<(f64, Vec<usize>)> = Vec::new();
        let mut cs: Vec<(f64, usize)> = s
            .criticals
            .iter()
            .map(|&c| (self.criticals[c].robot.x.clamp(xa, xb), c))
            .collect();
        cs.sort_by(|p, q| p.0.total_cmp(&q.0));
        for (x, c) in cs {
            match events.last_mut() {
                Some((ex, group)) if x - *ex < 1e-3 => group.push(c),
                _ => events.push((x, vec![c])),
            }
        }
        // One line in each gap between events (and between the slices and
        // the first and last), placed where the traced boundary is least
        // close to running along it.
        let mut bounds = vec![xa];
        bounds.extend(events.iter().map(|e| e.0));
        bounds.push(xb);
        let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut line_x: Vec<f64> = Vec::new();
        for w in bounds.windows(2) {
            let x = quiet_line(b, w[0], w[1]);
            line_x.push(x);
            let mut ys: Vec<f64> = (0..b.len())
                .filter_map(|i| {
                    let (p, q) = (b[i], b[(i + 1) % b.len()]);
                    ((p.x < x) != (q.x < x)).then(|| p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x))
                })
                .collect();
            if ys.len() % 2 == 1 {
                return false;
            }
            ys.sort_by(f64::total_cmp);
            lines.push(ys.chunks(2).map(|c| (c[0], c[1])).collect());
        }
        let ids: Vec<Vec<usize>> = lines
            .iter()
            .map(|line| line.iter().map(|_| uf.add()).collect())
            .collect();
        // The slices' laps join the pieces next to them.
        let (left, right) = self.sides(s);
        for (ivs, k) in [(&left, 0), (&right, lines.len() - 1)] {
            for &iv in ivs {
                let (lo, hi) = (self.intervals[iv].lo.y, self.intervals[iv].hi.y);
                let best = lines[k]
                    .iter()
                    .enumerate()
                    .map(|(j, p)| (hi.min(p.1) - lo.max(p.0), j))
                    .max_by(|a, b| a.0.total_cmp(&b.0));
                if let Some((overlap, j)) = best {
                    if overlap > -SAME_POINT {
                        uf.union(iv, ids[k][j]);
                    }
                }
            }
        }
        // Across each event.
        for (g, (_, group)) in events.iter().enumerate() {
            let (l, r) = (&lines[g], &lines[g + 1]);
            let mut local = UnionFind::new(l.len() + r.len());
            for (i, p) in l.iter().enumerate() {
                for (j, q) in r.iter().enumerate() {
                    if p.1.min(q.1) > p.0.max(q.0) {
                        local.union(i, l.len() + j);
                    }
                }
            }
            let mut parts: Vec<(usize, Vec<usize>, Vec<usize>)> = Vec::new();
            for k in 0..l.len() + r.len() {
                let root = local.find(k);
                let part = match parts.iter().position(|p| p.0 == root) {
                    Some(i) => i,
                    None => {
                        parts.push((root, Vec::new(), Vec::new()));
                        parts.len() - 1
                    }
                };
                if k < l.len() {
                    parts[part].1.push(k);
                } else {
                    parts[part].2.push(k - l.len());
                }
            }
            // Each critical point of the event goes with the part nearest it.
            let span = |ls: &[usize], rs: &[usize]| {
                ls.iter()
                    .map(|&i| l[i])
                    .chain(rs.iter().map(|&j| r[j]))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
                        (a.0.min(p.0), a.1.max(p.1))
                    })
            };
            let gap = |c: usize, (lo, hi): (f64, f64)| {
                let y = self.criticals[c].robot.y;
                (y - y.clamp(lo, hi)).abs()
            };
            let mut owned: Vec<Vec<usize>> = vec![Vec::new(); parts.len()];
            for &c in group {
                let best = (0..parts.len()).min_by(|&i, &j| {
                    let (pi, pj) = (&parts[i], &parts[j]);
                    gap(c, span(&pi.1, &pi.2)).total_cmp(&gap(c, span(&pj.1, &pj.2)))
                });
                if let Some(i) = best {
                    owned[i].push(c);
                }
            }
            for ((_, ls, rs), mut cs) in parts.into_iter().zip(owned) {
                if cs.is_empty() {
                    if ls.len() == 1 && rs.len() == 1 {
                        uf.union(ids[g][ls[0]], ids[g + 1][rs[0]]);
                        continue;
                    }
                    let sp = span(&ls, &rs);
                    match group
                        .iter()
                        .min_by(|&&a, &&b| gap(a, sp).total_cmp(&gap(b, sp)))
                    {
                        Some(&c) => cs.push(c),
                        None => continue,
                    }
                }
                let (xl, xr) = (line_x[g], line_x[g + 1]);
                let left: Vec<Item> = ls.iter().map(|&i| (ids[g][i], xl, l[i])).collect();
                let right: Vec<Item> = rs.iter().map(|&j| (ids[g + 1][j], xr, r[j])).collect();
                self.assign_places(&left, &right, &cs, ends, short);
            }
        }
        true
    }

    /// A slab's intervals on its −x slice and on its +x slice.
    fn sides(&self, s: &SlabRecord) -> (Vec<usize>, Vec<usize>) {
        s.intervals
            .iter()
            .partition(|&&k| self.intervals[k].slice == s.left)
    }

    /// The fallback of [`Reeb::sweep_slab`]: the slab's intervals on both
    /// slices take the places of all its critical points.
    fn join_slab(
        &self,
        s: &SlabRecord,
        ends: &mut Vec<(usize, usize, bool)>,
        short: &mut Vec<(usize, usize)>,
    ) {
        let (left, right) = self.sides(s);
        let item = |iv: usize| {
            let i = &self.intervals[iv];
            (iv, i.lo.x, (i.lo.y, i.hi.y))
        };
        let left: Vec<Item> = left.into_iter().map(item).collect();
        let right: Vec<Item> = right.into_iter().map(item).collect();
        self.assign_places(&left, &right, &s.criticals, ends, short);
    }

    /// Ends the cells of `left` (pieces or laps on the −x side) at the
    /// critical points `cs`, starts those of `right` there, and joins the
    /// critical points by the short lap-less cells their classes call for.
    ///
    /// A critical point's class fixes how many cells it has on each side: a
    /// split one before and two after, a birth none and one, a merge two
    /// and one, a death one and none. The cells take these places, and the
    /// places left over are joined in x order: a point short of a cell after
    /// it to the next point along x short of one before it (points within a
    /// centimetre in x either way, not both). Among the ways to place the
    /// cells (when they are few), the nearest whose leftovers all join up
    /// is taken; otherwise cells go nearest first.
    fn assign_places(
        &self,
        left: &[Item],
        right: &[Item],
        cs: &[usize],
        ends: &mut Vec<(usize, usize, bool)>,
        short: &mut Vec<(usize, usize)>,
    ) {
        let want = |k: CriticalKind| match (k.event, k.convexity) {
            (Event::In, Convexity::Convex) => (1usize, 2usize),
            (Event::In, Convexity::Concave) => (0, 1),
            (Event::Out, Convexity::Convex) => (2, 1),
            (Event::Out, Convexity::Concave) => (1, 0),
        };
        let want_before: Vec<usize> = cs.iter().map(|&c| want(self.criticals[c].kind).0).collect();
        let want_after: Vec<usize> = cs.iter().map(|&c| want(self.criticals[c].kind).1).collect();
        let distance = |&(_, x, (lo, hi)): &Item, c: usize| {
            let p = self.criticals[c].robot;
            (p.x - x).hypot(p.y - p.y.clamp(lo, hi))
        };
        let x = |j: usize| self.criticals[cs[j]].robot.x;
        // Joins the places left over: `after[a]` to `before[b]`, nearest in
        // x first, never both ways; what it could not join stays.
        let join = |after: &mut [usize], before: &mut [usize]| {
            let mut pairs: Vec<(usize, usize)> = (0..cs.len())
                .flat_map(|a| (0..cs.len()).map(move |b| (a, b)))
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
                        after[a] -= 1;
                        before[b] -= 1;
                    }
                }
            }
            joined
        };
        // Few enough choices: the nearest assignment (summed distance) whose
        // leftover places all join up, as a Reeb graph's must.
        let items = left.len() + right.len();
        let m = cs.len();
        if m >= 2 && (m as f64).powi(items as i32) <= 50_000.0 {
            let mut choice = vec![0usize; items];
            let mut best: Option<(f64, Vec<usize>)> = None;
            loop {
                let (mut before, mut after) = (want_before.clone(), want_after.clone());
                let mut fits = true;
                let mut cost = 0.0;
                for (k, &j) in choice.iter().enumerate() {
                    let (item, places) = if k < left.len() {
                        (&left[k], &mut before)
                    } else {
                        (&right[k - left.len()], &mut after)
                    };
                    if places[j] == 0 {
                        fits = false;
                        break;
                    }
                    places[j] -= 1;
                    cost += distance(item, cs[j]);
                }
                if fits && best.as_ref().is_none_or(|b| cost < b.0) {
                    join(&mut after, &mut before);
                    if after.iter().chain(&before).all(|&p| p == 0) {
                        best = Some((cost, choice.clone()));
                    }
                }
                // Next choice (odometer).
                let mut k = 0;
                while k < items && choice[k] + 1 == m {
                    choice[k] = 0;
                    k += 1;
                }
                if k == items {
                    break;
                }
                choice[k] += 1;
            }
            if let Some((_, choice)) = best {
                let (mut before, mut after) = (want_before.clone(), want_after.clone());
                for (k, &j) in choice.iter().enumerate() {
                    if k < left.len() {
                        before[j] -= 1;
                        ends.push((left[k].0, cs[j], true));
                    } else {
                        after[j] -= 1;
                        ends.push((right[k - left.len()].0, cs[j], false));
                    }
                }
                for (a, b) in join(&mut after, &mut before) {
                    short.push((cs[a], cs[b]));
                }
                return;
            }
        }
        // Otherwise nearest first within the places; a cell left without a
        // place ends at its nearest critical point regardless.
        let (mut before, mut after) = (want_before, want_after);
        for (side, places, entering) in [(left, &mut before, true), (right, &mut after, false)] {
            let mut pairs: Vec<(f64, usize, usize)> = (0..side.len())
                .flat_map(|i| (0..cs.len()).map(move |j| (i, j)))
                .map(|(i, j)| (distance(&side[i], cs[j]), i, j))
                .collect();
            pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
            let mut placed = vec![false; side.len()];
            for &(_, i, j) in &pairs {
                if !placed[i] && places[j] > 0 {
                    places[j] -= 1;
                    placed[i] = true;
                    ends.push((side[i].0, cs[j], entering));
                }
            }
            for &(_, i, j) in &pairs {
                if !placed[i] {
                    placed[i] = true;
                    ends.push((side[i].0, cs[j], entering));
                }
            }
        }
        for (a, b) in join(&mut after, &mut before) {
            short.push((cs[a], cs[b]));
        }
    }
}

/// A piece of a slice line or a lap: its id in the union-find, its x and
/// its y range.
type Item = (usize, f64, (f64, f64));

/// A plain union-find that can grow.
struct UnionFind(Vec<usize>);

impl UnionFind {
    fn new(n: usize) -> Self {
        Self((0..n).collect())
    }

    fn len(&self) -> usize {
        self.0.len()
    }

    fn add(&mut self) -> usize {
        self.0.push(self.0.len());
        self.0.len() - 1
    }

    fn find(&mut self, mut k: usize) -> usize {
        while self.0[k] != k {
            self.0[k] = self.0[self.0[k]];
            k = self.0[k];
        }
        k
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        self.0[a.max(b)] = a.min(b);
    }
}

/// An x in `(lo, hi)` where the closed polyline `b` runs least along
/// x = const: of a few candidates, the one farthest from every vertex's x.
fn quiet_line(b: &[Point], lo: f64, hi: f64) -> f64 {
    [0.5, 0.35, 0.65, 0.2, 0.8]
        .iter()
        .map(|f| lo + f * (hi - lo))
        .map(|x| {
            let gap = b
                .iter()
                .map(|p| (p.x - x).abs())
                .fold(f64::INFINITY, f64::min);
            (gap, x)
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map_or((lo + hi) / 2.0, |(_, x)| x)
}

#[cfg(test)]
mod tests;
