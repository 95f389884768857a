//! Plans reused in part for a target: the part of a complete plan that
//! covers the target's cells, scored as a plan of the target.
//!
//! - **Resume**: the plan the done path started (the same request, no done
//!   path, from the done path's first point), driven from the last of its
//!   waypoints after which it still covers every cell left to cover,
//!   reached from the resume start by the shortest transit: a robot that
//!   stopped half-way through a plan finishes that plan instead of
//!   starting a new one.
//! - **Most of the map**: the whole map's plan, stopped at the first
//!   waypoint by which it has covered every required cell.
//!
//! [`super::plan`] keeps such a part where it is faster than the target's
//! own plan.

use std::time::Instant;

use oxcover_grid::{Cell, OccupancyGrid};
use oxcover_planners::{CoverageProblem, Start};

use super::region::{KnownCoverage, finish, start_prefix};
use super::request::{PlanOutcome, PlanRequest, RoomStretch};
use crate::error::Result;

/// The interrupted plan's remainder on `problem` (the resumed problem: its
/// coverable cells those left to cover, its start the resume start), or
/// `None` where there is none: no done path, the uninterrupted plan failed
/// or is not complete, or its remainder cannot be reached.
///
/// # Errors
/// Only an internal fault while scoring; a plan that cannot be made is
/// `None`.
pub(super) fn continued(
    map: &OccupancyGrid,
    problem: &CoverageProblem,
    request: &PlanRequest,
    t0: Instant,
) -> Result<Option<PlanOutcome>> {
    let Some(&first) = request.targets.done.as_ref().and_then(|d| d.first()) else {
        return Ok(None);
    };
    let mut whole = request.clone();
    whole.targets.done = None;
    whole.start = Start::At(first);
    let Ok(full) = super::plan(map, &whole) else {
        return Ok(None);
    };
    covering_part(problem, request, &full, true, t0)
}

/// The shortest stretch of `full`'s waypoints that covers every coverable
/// cell of `problem`, scored as `problem`'s plan: from the last waypoint
/// after which `full` still covers them (with `resume`; else from the
/// first) to the first by which it has, reached from `problem`'s start by
/// the shortest transit. `None` where `full` does not cover them, its
/// stretch cannot be reached, or the stretch scores below full coverage or
/// with a collision.
///
/// # Errors
/// Only an internal fault while scoring.
pub(super) fn covering_part(
    problem: &CoverageProblem,
    request: &PlanRequest,
    full: &PlanOutcome,
    resume: bool,
    t0: Instant,
) -> Result<Option<PlanOutcome>> {
    let points = &full.points;
    let left = &problem.cells().coverable;
    let covers = |from: usize, to: usize| {
        let got = problem.covered_by(&points[from..to]);
        left.true_cells().all(|c| got[c])
    };
    let n = points.len();
    if n == 0 || !covers(0, n) {
        return Ok(None);
    }
    // Bisections: a stretch covers less as it starts later or ends sooner.
    let k = if resume {
        last_true(0, n, |k| covers(k, n))
    } else {
        0
    };
    // The first end that covers: one past the last that does not (the
    // empty stretch from `k` covers nothing).
    let end = 1 + last_true(k, n, |e| e == k || !covers(k, e));
    let frame = problem.frame();
    let Some(to) = frame
        .cell_at(&points[k])
        .filter(|&c| problem.plannable()[c])
    else {
        return Ok(None);
    };
    let (mut path, cells) = if k == 0 {
        (Vec::new(), Vec::new())
    } else {
        let Ok(transit) = problem.transit(problem.start_cell(), |c| c == to) else {
            return Ok(None);
        };
        let mut path = start_prefix(problem);
        path.extend(transit.points.iter().copied());
        (path, transit.cells)
    };
    if path.last() == Some(&points[k]) {
        path.pop();
    }
    let offset = path.len();
    path.extend_from_slice(&points[k..end]);
    let stretches = kept_stretches(&full.room_stretches, k..end, offset);
    let cells: Vec<Cell> = if k == 0 { full.cells.clone() } else { cells };
    let known = KnownCoverage {
        raws: None,
        path: None,
        cells: None,
    };
    let outcome = finish(
        problem,
        request,
        path.clone(),
        cells,
        (&[path], known),
        None,
        0.0,
        stretches,
        t0.elapsed().as_secs_f64() * 1e3,
    )?;
    let m = &outcome.evaluation.metrics;
    Ok((m.covered_cells == m.coverable_cells && m.collisions == 0).then_some(outcome))
}

/// The room stretches of `stretches` within the waypoints `kept`,
/// renumbered for a path holding them from `offset` on.
fn kept_stretches(
    stretches: &[RoomStretch],
    kept: std::ops::Range<usize>,
    offset: usize,
) -> Vec<RoomStretch> {
    stretches
        .iter()
        .filter(|s| s.points.end > kept.start && s.points.start < kept.end)
        .map(|s| RoomStretch {
            unit: s.unit,
            points: s.points.start.max(kept.start) - kept.start + offset
                ..s.points.end.min(kept.end) - kept.start + offset,
        })
        .collect()
}

/// The last `i` in `lo..hi` where `holds`, given that it holds at `lo` and
/// holds on a prefix of the range only.
fn last_true(lo: usize, hi: usize, holds: impl Fn(usize) -> bool) -> usize {
    let (mut lo, mut hi) = (lo, hi);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if holds(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}
