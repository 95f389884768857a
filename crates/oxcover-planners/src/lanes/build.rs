//! The best few angles built to the end, the fastest path kept.
//!
//! Each ordered angle is driven: its loops ([`drive_loop`]) and chains
//! ([`drive_chain`], with the island loops its lanes drive) in the order's
//! sequence, every transit by the shortest clear route. What the
//! straightened loops and the lanes' ends pass just out of reach is then
//! covered by the cheapest detours, and the path is tightened pass by pass
//! (both shared with the pipeline: [`crate::detours`]). The angles are
//! built in parallel; one whose path after its first tightening pass is
//! [`LAST_PASSES_GAIN`] slower than the fastest's stops there. A last pass
//! visits any coverage cell still uncovered, nearest first.
//!
//! Measured (`docs/efficiency.md`, stage table, rooms on): without the
//! detours 23.5 % (ipa) / 10.7 % (ROS) slower. Without `lanes`' own
//! tightening the figure hardly moves with rooms on, where the pipeline
//! tightens the whole path again at the end.

use std::sync::OnceLock;

use rayon::prelude::*;

use oxcover_grid::traverse::GridPoint;
use oxcover_grid::{Cell, Point};

use super::LaneStages;
use super::islands::{Splice, drive_chain};
use super::loops::{EdgeLoop, drive_loop, loop_tolerance};
use super::nodes::{Node, nodes_of};
use super::order::Ordered;
use crate::detours::{
    Detours, Tightening, insert_detours, metric_reach, polyline_time, reach_counts,
};
use crate::error::{Error, Result};
use crate::metre_path::PathBuilder;
use crate::problem::PlannerInput;
use crate::time::TimeModel;

/// How much slower than the fastest an angle's path may be after its
/// first tightening pass and still be built to the end (the later passes
/// never made up more on the shared maps; a third of the builds stop).
const LAST_PASSES_GAIN: f64 = 0.05;

/// An angle built: its path's estimated time after its detours and first
/// tightening pass, and the finished path with its estimated time (none
/// where it stopped then, too slow to be kept).
type Built<'a> = (f64, Option<(f64, PathBuilder<'a>)>);

/// What building an angle's path needs.
pub(super) struct Builder<'a, 'r> {
    input: &'r PlannerInput<'a>,
    loops: &'r [EdgeLoop],
    /// Where the robot stands.
    start: Cell,
    /// Where the path should end, if given.
    exit: Option<GridPoint>,
    detours: Detours<'a>,
    loop_tolerance: f64,
    /// Speeds in cells per second.
    time: TimeModel,
    stages: LaneStages,
}

impl<'a, 'r> Builder<'a, 'r> {
    /// Builds paths over `input`'s region with its edge loops `loops`, from
    /// `start` towards `exit`, for a tool of `tool` cells at the speeds of
    /// `time` (cells per second). Detours bend segments by at most five
    /// tool radii, and count coverage with the metrics' own radius
    /// ([`metric_reach`]).
    pub(super) fn new(
        input: &'r PlannerInput<'a>,
        loops: &'r [EdgeLoop],
        start: Cell,
        exit: Option<GridPoint>,
        tool: f64,
        time: TimeModel,
        stages: LaneStages,
    ) -> Self {
        let (reach, fragile) = metric_reach(input.tool_cells);
        let detours = Detours {
            plannable: input.plannable,
            coverable: input.coverable,
            reach,
            fragile,
            search: 5.0 * tool,
            time,
        };
        Self {
            input,
            loops,
            start,
            exit,
            detours,
            loop_tolerance: if stages.straighten_loops {
                loop_tolerance(tool)
            } else {
                0.0
            },
            time,
            stages,
        }
    }

    /// Each of `ordered` built (in parallel, the first of equal times
    /// winning), the fastest path in metres. An angle stops as soon as
    /// every angle's time after its first tightening pass is known and its
    /// own is over [`LAST_PASSES_GAIN`] behind the fastest (which ones stop
    /// does not depend on which angle got there first).
    pub(super) fn fastest(&self, ordered: &[Ordered]) -> Result<Vec<Point>> {
        let first_pass: Vec<OnceLock<f64>> = ordered.iter().map(|_| OnceLock::new()).collect();
        let behind = |time: f64| {
            let known: Option<Vec<f64>> = first_pass.iter().map(|t| t.get().copied()).collect();
            known.is_some_and(|t| {
                time > (1.0 + LAST_PASSES_GAIN) * t.into_iter().fold(f64::INFINITY, f64::min)
            })
        };
        let built: Vec<Result<Built<'a>>> = ordered
            .par_iter()
            .enumerate()
            .map(|(i, o)| self.build(o, &first_pass[i], &behind))
            .collect();
        let built = built.into_iter().collect::<Result<Vec<_>>>()?;
        let lead = built.iter().map(|b| b.0).fold(f64::INFINITY, f64::min);
        let mut best: Option<(f64, PathBuilder<'_>)> = None;
        for (first, b) in built {
            let Some(b) = b.filter(|_| first <= (1.0 + LAST_PASSES_GAIN) * lead) else {
                continue;
            };
            if best.as_ref().is_none_or(|x| b.0 < x.0) {
                best = Some(b);
            }
        }
        let (_, path) = best.ok_or_else(|| Error::Internal("no lane angle was built".into()))?;
        Ok(path.into_metres(&self.input.frame))
    }

    /// One angle's path: driven, detoured, tightened until done or
    /// `behind` its first pass's time; that time is set in `first_pass`.
    fn build(
        &self,
        o: &Ordered,
        first_pass: &OnceLock<f64>,
        behind: &(impl Fn(f64) -> bool + Sync),
    ) -> Result<Built<'a>> {
        let mut path = self.drive(o)?;
        let (points, count) = if self.stages.detours {
            insert_detours(path.points(), &self.detours)
        } else {
            let points = path.points().to_vec();
            let count = reach_counts(&points, &self.detours);
            (points, count)
        };
        // Then the vertices detours made unneeded go, and the rest move
        // towards the line of their neighbours, where coverage allows.
        let mut tightening = Tightening::new(&points, count, 0);
        if self.stages.tighten {
            tightening.pass(&self.detours, None);
        }
        let first = polyline_time(&tightening.points(), &self.time);
        // Set once, here only.
        let _ = first_pass.set(first);
        loop {
            if behind(first) {
                return Ok((first, None));
            }
            if !self.stages.tighten || !tightening.pass(&self.detours, None) {
                break;
            }
        }
        path.replace(tightening.finish().0);
        path.cover_leftovers(self.input.coarse, self.input.visit_radius())?;
        let to_exit = self
            .exit
            .map_or(0.0, |e| self.time.time((e - path.last()).norm(), 0.0));
        Ok((
            first,
            Some((polyline_time(path.points(), &self.time) + to_exit, path)),
        ))
    }

    /// The loops and chains of `o` driven in its order from the start.
    fn drive(&self, o: &Ordered) -> Result<PathBuilder<'a>> {
        let nodes = nodes_of(self.loops, &o.chains, &o.splices);
        let first_chain = nodes.len() - o.chains.len();
        let mut path = PathBuilder::new(self.input.plannable, self.start);
        for &(node, option) in &o.tour {
            match nodes[node] {
                Node::Loop(l) => drive_loop(&mut path, l, option, self.loop_tolerance)?,
                Node::Chain(c) => {
                    let here: Vec<&Splice> = o
                        .splices
                        .iter()
                        .filter(|s| s.chain == node - first_chain)
                        .collect();
                    drive_chain(&mut path, c, option, &here, self.loops, self.loop_tolerance)?;
                }
            }
        }
        Ok(path)
    }
}
