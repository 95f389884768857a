//! Smooth coverage (after Lee, Baek, Choi & Oh 2011), built for time.
//!
//! The seed covers a room with a spiral, wall following, and then
//! "virtual-wall" paths: each one runs round the boundary of the region not
//! yet covered, one lane width inside it, and is smoothed by quintic Bézier
//! curves that a PSO tunes. Its claim is that smooth paths clean faster than
//! grid planners. This planner keeps the seed's passes (wall following, then
//! virtual walls nested inwards, Bézier curves, PSO) and lays them out for
//! the time a robot needs, the time law of [`oxcover_robot::Timing`] (speed,
//! acceleration, turn rate, stops at sharp corners) with the input's speed
//! and turn rate. Its stages, one file each:
//!
//! 1. `rings`: the virtual walls as level sets of the distance to the
//!    C-space boundary, one lane apart, ring 0 along the walls.
//! 2. `slivers`: what the rings leave (the strip at the medial axis, the
//!    pockets at inner corners), each given a spine, driven only where
//!    worth its time per covered area.
//! 3. `order`: rings and spines driven nearest first; then every coverage
//!    cell not yet passed is visited, so the plan is complete on the
//!    coverage grid like every complete planner.
//! 4. `fillets`: sharp corners rounded by G² quintic Bézier fillets, their
//!    shape tuned by the seed's PSO, where the time law drives them faster
//!    than the stop-and-turn they replace.
//!
//! `run` holds the planner's state (the path, what it covers) and the
//! steps every stage shares.
//!
//! **Overlap.** Lanes are `2R` apart with `R = T − margin`, `T` the tool
//! radius in cells and the margin 12 % of it (at least 0.35 cells), but `R`
//! never below half a cell (or the tool radius when that is smaller). The
//! margin is what keeps a tracked robot's coverage when it deviates from the
//! plan (the lee2011 reproduction measures the tracking error it must
//! absorb); paths keep [`CLEARANCE`] cells from non-plannable cells for the
//! same reason.
//!
//! **Complexity** for `N` grid cells, `P` ring points and `C` sharp corners:
//! the distance transform and the contours are `O(N + P)`; the order is a
//! nearest search per item over square buckets of a coverage cell; marking
//! what the path covers is `O(length · T)`; each fillet costs a fixed
//! number of PSO evaluations, each a time law over a few dozen points:
//! `O(C)`. The completion step is one CIDT wave per leftover.

mod fillets;
mod order;
mod rings;
mod run;
mod slivers;
#[cfg(test)]
mod tests;

use oxcover_grid::traverse::GridPoint;
use oxcover_grid::{Cell, Grid, Point};
use oxcover_robot::Limits;

use crate::error::{Error, Result};
use crate::metre_path::{Clearance, PathBuilder};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};
use crate::pso::Pso;

/// Least distance (cells) the path keeps from non-plannable cells. A path
/// through cell centres keeps 0.5.
pub const CLEARANCE: f64 = 0.45;

/// How far (cells) ring 0 is lifted off a staircase boundary (at most the
/// tool radius).
pub const STAIR_LIFT: f64 = 0.35;

/// What the robot is doing on a stretch of the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Behaviour {
    /// Ring 0: along the walls and round the obstacles.
    WallFollowing,
    /// A ring further in: a virtual wall one lane inside the last.
    VirtualWall,
    /// Along the spine of a piece left between rings.
    Sliver,
    /// Between passes, and the completion visits.
    Transit,
}

/// A stretch of the path: points `start ..= end` (indices into the path).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Piece {
    /// Behaviour.
    pub behaviour: Behaviour,
    /// First point (the end of the previous piece).
    pub start: usize,
    /// Last point.
    pub end: usize,
}

/// A smooth plan with its behaviours and statistics.
#[derive(Clone, Debug)]
pub struct SmoothPlan {
    /// The metre path.
    pub points: Vec<Point>,
    /// Its stretches by behaviour.
    pub pieces: Vec<Piece>,
    /// Rings driven / dropped (nothing new to cover).
    pub rings: (usize, usize),
    /// Sliver spines driven / left (too slow per covered area).
    pub slivers: (usize, usize),
    /// Sharp corners rounded / left to stop and turn.
    pub fillets: (usize, usize),
    /// Summed estimated time (s) of the rounded corners: the widest
    /// symmetric fillet, then after PSO.
    pub fillet_time: (f64, f64),
}

/// The `smooth` planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smooth {
    /// PSO parameters for the fillets.
    pub pso: Pso,
    /// A sliver spine is driven when its time per newly covered area is at
    /// most this many times the plan's so far.
    pub sliver_worth: f64,
}

impl Smooth {
    /// The planner with the seed's PSO weights (`w = 0.8, c₁ = 0.5,
    /// c₂ = 0.2`) on 8 particles for 6 rounds per corner, and slivers worth
    /// up to 16 times the plan's time per area.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            pso: Pso {
                particles: 8,
                w: 0.8,
                c1: 0.5,
                c2: 0.2,
                rounds: 6,
            },
            sliver_worth: 16.0,
        }
    }

    /// The plan with its behaviours.
    ///
    /// # Errors
    /// Internal faults only.
    pub fn plan_detailed(&self, input: &PlannerInput<'_>) -> Result<SmoothPlan> {
        let start = input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))?;
        let mut run = Run::new(input, start, *self);
        let items = run.items();
        run.drive_items(items)?;
        let from = run.len() - 1;
        run.builder
            .cover_leftovers(input.coarse, input.visit_radius())?;
        run.close(Behaviour::Transit, from);
        let Run {
            builder,
            pieces,
            stats,
            ..
        } = run;
        Ok(SmoothPlan {
            points: builder.into_metres(&input.frame),
            pieces,
            rings: stats.rings,
            slivers: stats.slivers,
            fillets: stats.fillets,
            fillet_time: stats.fillet_time,
        })
    }
}

impl Default for Smooth {
    fn default() -> Self {
        Self::new()
    }
}

impl Planner for Smooth {
    fn name(&self) -> &'static str {
        "smooth"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "Lee et al. 2011 for time: wall following and nested virtual-wall rings, slivers, PSO-tuned Bezier fillets"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
}

/// A ring (closed) or a sliver's spine (open) to drive.
#[derive(Clone, Debug)]
struct Item {
    points: Vec<GridPoint>,
    closed: bool,
    /// Ring level (0 = wall following); `usize::MAX` for spines.
    level: usize,
    /// Coverage cells' representatives in a sliver: it is driven, however
    /// slow, while one of them is still to visit (completeness).
    reps: Vec<Cell>,
}

#[derive(Clone, Copy, Debug, Default)]
struct Stats {
    rings: (usize, usize),
    slivers: (usize, usize),
    fillets: (usize, usize),
    fillet_time: (f64, f64),
}

/// The planner's state.
struct Run<'a> {
    plannable: &'a Grid<bool>,
    clear: Clearance<'a>,
    builder: PathBuilder<'a>,
    /// Cells whose centre a path sample passed within the tool radius (the
    /// contract's coverage).
    touched: Grid<bool>,
    /// Coverage cells' representatives, and the cells the path passed
    /// within the visit radius of.
    rep: Grid<bool>,
    visited: Grid<bool>,
    visit: f64,
    marked: usize,
    tool: f64,
    reach: f64,
    /// Tool radius less the reach.
    margin: f64,
    limits: Limits,
    resolution: f64,
    /// Bucket size (cells) of the nearest-item index.
    bucket: usize,
    smooth: Smooth,
    seed: u64,
    corners: u64,
    pieces: Vec<Piece>,
    stats: Stats,
}
