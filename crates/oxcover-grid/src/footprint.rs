//! The tool's footprint along a path: which cells a polyline covers.
//!
//! Contract: the path is the polyline through the waypoints; it is sampled every
//! `resolution / 4` (each segment split into `ceil(len / step)` equal parts, all
//! waypoints included), and a cell is covered when its centre lies within the
//! tool radius of a sample. The same sampler feeds the collision count, so
//! metrics, the boundary pass and the tests agree on what "covered" means.

use crate::admissible::TOLERANCE_CELLS;
use crate::frame::MapFrame;
use crate::grid::{Cell, Grid};
use crate::math::{Point, fast_ceil, fast_floor};

/// Calls `f` on samples of the polyline `points`, at most `step` apart.
///
/// A single waypoint yields one sample; an empty path none. Non-finite
/// waypoints are passed through as they are (callers validate paths first).
pub fn for_each_sample(points: &[Point], step: f64, mut f: impl FnMut(&Point)) {
    let Some(first) = points.first() else {
        return;
    };
    f(first);
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = sample_parts(a, b, step);
        for i in 1..=n {
            let t = i as f64 / n as f64;
            f(&(a + (b - a) * t));
        }
    }
}

/// How many equal parts [`for_each_sample`] splits the segment `a → b`
/// into (at most `step` long): its samples are `a + (b − a)·i/n` for
/// `i` in `1..=n`.
#[must_use]
pub fn sample_parts(a: Point, b: Point, step: f64) -> usize {
    let len = (b - a).norm();
    // The tolerance keeps a segment of exactly m·step from getting an extra
    // sample through rounding, so samples of grid-aligned paths fall on the
    // cell centres they pass.
    if step > 0.0 && len.is_finite() {
        (len / step - 1e-9).ceil().max(1.0) as usize
    } else {
        1
    }
}

/// Sets `mask` on every cell whose centre lies within `radius` metres of `p`.
pub fn mark_disc(frame: &MapFrame, p: &Point, radius: f64, mask: &mut Grid<bool>) {
    let res = frame.resolution();
    let reach = radius / res + TOLERANCE_CELLS;
    let (row, col) = frame.fractional_cell(p);
    if !(row.is_finite() && col.is_finite()) {
        return;
    }
    let r0 = fast_ceil(row - reach).max(0.0);
    let r1 = fast_floor(row + reach).min(mask.height() as f64 - 1.0);
    let c0 = fast_ceil(col - reach).max(0.0);
    let c1 = fast_floor(col + reach).min(mask.width() as f64 - 1.0);
    if r0 > r1 || c0 > c1 {
        return;
    }
    let reach2 = reach * reach;
    for r in r0 as usize..=r1 as usize {
        let dr = r as f64 - row;
        for c in c0 as usize..=c1 as usize {
            let dc = c as f64 - col;
            if dr * dr + dc * dc <= reach2 {
                mask[Cell::new(r, c)] = true;
            }
        }
    }
}

/// Cells covered by a tool of `tool_radius` metres driven along `points`
/// (sampled every `resolution / 4`).
#[must_use]
pub fn covered_cells(frame: &MapFrame, points: &[Point], tool_radius: f64) -> Grid<bool> {
    let mut mask = Grid::new(frame.width(), frame.height(), false);
    mark_covered(frame, points, tool_radius, &mut mask);
    mask
}

/// The cells covered by a tool of `tool_radius` metres driven along each
/// of `pieces` (polylines, each marked as [`mark_covered`] marks it; no
/// move between them). Long ones are marked in two halves side by side
/// (split at a waypoint, which leaves the cells as they are: see
/// [`mark_segments`]) and joined.
#[must_use]
pub fn covered_cells_of(frame: &MapFrame, pieces: &[&[Point]], tool_radius: f64) -> Grid<bool> {
    let total: usize = pieces.iter().map(|p| p.len()).sum();
    let blank = || Grid::new(frame.width(), frame.height(), false);
    if total < SPLIT_WAYPOINTS {
        let mut mask = blank();
        for piece in pieces {
            mark_covered(frame, piece, tool_radius, &mut mask);
        }
        return mask;
    }
    // The piece holding the middle waypoint, and where in it.
    let mut i = 0;
    let mut before = 0;
    while before + pieces[i].len() <= total / 2 {
        before += pieces[i].len();
        i += 1;
    }
    let k = total / 2 - before;
    let (mut a, b) = rayon::join(
        || {
            let mut mask = blank();
            for piece in &pieces[..i] {
                mark_covered(frame, piece, tool_radius, &mut mask);
            }
            mark_covered(frame, &pieces[i][..=k], tool_radius, &mut mask);
            mask
        },
        || {
            let mut mask = blank();
            mark_segments(frame, &pieces[i][k..], tool_radius, &mut mask);
            for piece in &pieces[i + 1..] {
                mark_covered(frame, piece, tool_radius, &mut mask);
            }
            mask
        },
    );
    for (x, &y) in a.as_mut_slice().iter_mut().zip(b.as_slice()) {
        *x |= y;
    }
    a
}

/// Waypoints from which [`covered_cells_of`] marks in two halves.
const SPLIT_WAYPOINTS: usize = 1_000;

/// Adds the cells covered along `points` to `mask`.
///
/// The same cells as a disc marked round every sample ([`for_each_sample`],
/// [`mark_disc`]), found faster on long segments: each cell of a segment's
/// stroke is tested against the samples either side of its foot only (the
/// samples of a segment are collinear and evenly spaced, so the nearest is
/// among them), each sample computed exactly as the sampler computes it.
pub fn mark_covered(frame: &MapFrame, points: &[Point], tool_radius: f64, mask: &mut Grid<bool>) {
    let Some(first) = points.first() else {
        return;
    };
    mark_disc(frame, first, tool_radius, mask);
    mark_segments(frame, points, tool_radius, mask);
}

/// [`mark_covered`] without the first waypoint's own sample: the cells the
/// samples of `points`' segments cover (each segment's samples after its
/// start). A path split at a waypoint `k` is marked as `points[..=k]` with
/// [`mark_covered`] and `points[k..]` with this: together exactly the
/// cells of the whole (the sample ending a segment is not always the
/// waypoint itself, to the last bit).
pub fn mark_segments(frame: &MapFrame, points: &[Point], tool_radius: f64, mask: &mut Grid<bool>) {
    let step = frame.resolution() / 4.0;
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = sample_parts(a, b, step);
        let sample = |i: usize| a + (b - a) * (i as f64 / n as f64);
        if n <= SHORT_SEGMENT {
            for i in 1..=n {
                mark_disc(frame, &sample(i), tool_radius, mask);
            }
        } else {
            mark_segment(frame, n, &sample, tool_radius, mask);
        }
    }
}

/// Segments of at most this many samples are marked sample by sample.
const SHORT_SEGMENT: usize = 16;

/// Marks the cells within the tool's reach of samples `1..=n` of one
/// segment (`sample(i)`, as [`for_each_sample`] makes them).
fn mark_segment(
    frame: &MapFrame,
    n: usize,
    sample: &impl Fn(usize) -> Point,
    tool_radius: f64,
    mask: &mut Grid<bool>,
) {
    let reach = tool_radius / frame.resolution() + TOLERANCE_CELLS;
    let reach2 = reach * reach;
    let at = |i: usize| frame.fractional_cell(&sample(i));
    let (p0, p1) = (at(0), at(n));
    if !(p0.0.is_finite() && p0.1.is_finite() && p1.0.is_finite() && p1.1.is_finite()) {
        return;
    }
    let (dr, dc) = (p1.0 - p0.0, p1.1 - p0.1);
    let len2 = dr * dr + dc * dc;
    // The sample index nearest the foot of (r, c), in 1..=n.
    let foot = |r: f64, c: f64| {
        let t = if len2 > 0.0 {
            (((r - p0.0) * dr + (c - p0.1) * dc) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        t * n as f64
    };
    let within = |i: usize, r: f64, c: f64| {
        let (sr, sc) = at(i);
        let (er, ec) = (r - sr, c - sc);
        er * er + ec * ec <= reach2
    };
    let (h, w) = (mask.height() as f64, mask.width() as f64);
    // Pieces of at most 2·reach (in samples), each scanning its box grown
    // by the reach; a cell is tested by the piece its foot falls in.
    let per_piece = ((2.0 * reach) / (len2.sqrt() / n as f64).max(1e-12))
        .floor()
        .max(1.0) as usize;
    let mut k0 = 0;
    while k0 < n {
        let k1 = (k0 + per_piece).min(n);
        let (a, b) = (at(k0), at(k1));
        let r0 = fast_ceil(a.0.min(b.0) - reach).max(0.0);
        let r1 = fast_floor(a.0.max(b.0) + reach).min(h - 1.0);
        let c0 = fast_ceil(a.1.min(b.1) - reach).max(0.0);
        let c1 = fast_floor(a.1.max(b.1) + reach).min(w - 1.0);
        if r0 <= r1 && c0 <= c1 {
            for r in r0 as usize..=r1 as usize {
                for c in c0 as usize..=c1 as usize {
                    if mask[Cell::new(r, c)] {
                        continue;
                    }
                    let (rf, cf) = (r as f64, c as f64);
                    let s = foot(rf, cf);
                    // This piece's cells: feet in [k0, k1) (the last piece
                    // also takes its end).
                    if s < k0 as f64 || (s >= k1 as f64 && k1 < n) {
                        continue;
                    }
                    let i = s.round() as usize;
                    let lo = i.saturating_sub(1).max(1);
                    let hi = (i + 1).min(n);
                    if (lo..=hi).any(|i| within(i, rf, cf)) {
                        mask[Cell::new(r, c)] = true;
                    }
                }
            }
        }
        k0 = k1;
    }
}

/// [`mark_covered`] the plain way: a disc round every sample (the
/// definition; for tests).
#[cfg(test)]
fn mark_covered_reference(
    frame: &MapFrame,
    points: &[Point],
    tool_radius: f64,
    mask: &mut Grid<bool>,
) {
    let step = frame.resolution() / 4.0;
    for_each_sample(points, step, |p| mark_disc(frame, p, tool_radius, mask));
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        /// The fast marking finds exactly the cells of a disc round every
        /// sample, on rotated and offset frames and any radius.
        #[test]
        fn fast_marking_is_the_definition(
            pts in prop::collection::vec((-1.0..13.0f64, -1.0..9.0f64), 1..6),
            res in prop::sample::select(vec![0.05, 0.1, 1.0]),
            yaw in prop::sample::select(vec![0.0, 0.3, -1.2]),
            radius_cells in 0.1..7.0f64,
        ) {
            let frame = MapFrame::new(60, 40, res, Point::new(-0.3, 0.7)).with_yaw(yaw);
            let points: Vec<Point> = pts
                .iter()
                .map(|&(x, y)| Point::new(x * res * 4.0, y * res * 4.0))
                .collect();
            let radius = radius_cells * res;
            let mut fast = Grid::new(60, 40, false);
            let mut slow = Grid::new(60, 40, false);
            mark_covered(&frame, &points, radius, &mut fast);
            mark_covered_reference(&frame, &points, radius, &mut slow);
            prop_assert_eq!(fast, slow);
        }
    }

    #[test]
    fn pieces_marked_in_halves_are_marked_alike() {
        let frame = MapFrame::new(80, 60, 0.05, Point::new(0.1, -0.2)).with_yaw(0.3);
        // Pieces of a zigzag, 2,400 waypoints in all, split unevenly.
        let zigzag: Vec<Point> = (0..2_400)
            .map(|i| Point::new(0.2 + (i % 37) as f64 * 0.1, 0.1 + (i % 29) as f64 * 0.09))
            .collect();
        for cuts in [
            vec![0, 2_400],
            vec![0, 700, 1_300, 1_301, 2_400],
            vec![0, 1_200, 2_400],
        ] {
            let pieces: Vec<&[Point]> = cuts.windows(2).map(|c| &zigzag[c[0]..c[1]]).collect();
            let mut want = Grid::new(80, 60, false);
            for piece in &pieces {
                mark_covered(&frame, piece, 0.11, &mut want);
            }
            assert_eq!(covered_cells_of(&frame, &pieces, 0.11), want, "{cuts:?}");
        }
    }

    #[test]
    fn a_path_split_at_a_waypoint_marks_the_same_cells() {
        let frame = MapFrame::new(50, 40, 0.05, Point::new(0.1, -0.2)).with_yaw(0.7);
        let pts: Vec<Point> = [(0.3, 0.1), (1.9, 0.4), (0.4, 1.3), (2.2, 1.5), (1.0, 0.2)]
            .map(|(x, y)| Point::new(x, y))
            .to_vec();
        let mut whole = Grid::new(50, 40, false);
        mark_covered(&frame, &pts, 0.11, &mut whole);
        for k in 0..pts.len() {
            let mut split = Grid::new(50, 40, false);
            mark_covered(&frame, &pts[..=k], 0.11, &mut split);
            mark_segments(&frame, &pts[k..], 0.11, &mut split);
            assert_eq!(split, whole, "split at {k}");
        }
    }

    #[test]
    fn samples_include_vertices_and_respect_the_step() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 0.1),
        ];
        let mut s = Vec::new();
        for_each_sample(&pts, 0.25, |p| s.push(*p));
        assert_eq!(s.len(), 1 + 4 + 1);
        assert_eq!(s[4], Point::new(1.0, 0.0));
        assert!(s.windows(2).all(|w| (w[1] - w[0]).norm() <= 0.25 + 1e-12));
        let mut one = 0;
        for_each_sample(&pts[..1], 0.25, |_| one += 1);
        assert_eq!(one, 1);
    }

    #[test]
    fn half_cell_tool_covers_exactly_the_cells_visited() {
        let f = MapFrame::unit(5, 3);
        let path = [
            f.cell_center(Cell::new(1, 0)),
            f.cell_center(Cell::new(1, 4)),
        ];
        let m = covered_cells(&f, &path, 0.5);
        assert_eq!(
            m.true_cells().collect::<Vec<_>>(),
            (0..5).map(|c| Cell::new(1, c)).collect::<Vec<_>>()
        );
        let m = covered_cells(&f, &path, 1.0);
        assert_eq!(m.count_true(), 15);
    }
}
