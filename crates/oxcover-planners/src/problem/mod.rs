//! The coverage problem: made once from a map, a robot and a start, and the
//! one place where a planner's input comes from.
//!
//! [`CoverageProblem`] owns everything a planner and the pipeline around it
//! need, derived once:
//!
//! - the contract's cells ([`Coverability`]: admissible, reachable from the
//!   start, coverable by the tool) and the map frame;
//! - the coverage grid ([`CoarseGrid`]) whose cells are one tool diameter wide,
//!   `block = max(1, floor(2T / resolution + tolerance))` fine cells
//!   ([`coarse_block`]), so lanes one block apart leave no gap;
//! - the tool radius in fine cells, `T / resolution` ([`CoverageProblem::tool_cells`]),
//!   the ONE tool-radius figure planners see.
//!
//! It hands planners their [`PlannerInput`] ([`CoverageProblem::input`]) and
//! does the steps every plan shares: [`CoverageProblem::expand`] (coverage
//! steps to fine 4-connected steps), [`CoverageProblem::lead_in`] (from the
//! start cell to where a plan begins) and [`CoverageProblem::boundary_pass`]
//! (cover what a plan left). [`CoverageProblem::restricted`] narrows it to a
//! sub-region (a room), for planning region by region.
//!
//! The start is a [`Start`]: the contract's default (the first admissible cell
//! in row-major order), a position, a cell, or the first cell of the largest
//! admissible region ([`largest_region_start`]), which experiments use because
//! the contract's default start may be a speck of SLAM noise.

mod input;
#[cfg(test)]
mod tests;

pub use input::{PlanOutput, PlannerInput, Transit};

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{
    Cell, CoarseGrid, Coverability, DiscRobot, Grid, MapFrame, OccupancyGrid, Point,
    TOLERANCE_CELLS, Window, admissible, components4, coverable_cells, reachable,
};

use crate::boundary_pass::{
    BoundaryRoute, boundary_pass, boundary_pass_covered, boundary_tour, boundary_tour_to,
    boundary_tour_to_covered, covered_by,
};
use crate::detours::{Detours, Zone, metric_reach, reach_counts, tighten_from};
use crate::error::{Error, Result};
use crate::metre_path::{PathBuilder, grid_to_metres, metres_to_grid};
use crate::time::TimeModel;

/// Where the robot starts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Start {
    /// The contract's default: the first admissible cell, row-major from the
    /// image's top row.
    #[default]
    First,
    /// A position in metres (map frame); its cell must be admissible.
    At(Point),
    /// A cell of the map (row 0 at the image's top); it must be admissible.
    Cell(Cell),
    /// The first admissible cell (row-major) of the largest 4-connected
    /// admissible region (ties: the region met first).
    LargestRegion,
}

impl From<Option<Point>> for Start {
    fn from(p: Option<Point>) -> Self {
        p.map_or(Start::First, Start::At)
    }
}

/// The first admissible cell (row-major) of the largest 4-connected admissible
/// region for a robot of `robot_radius`, if any cell is admissible.
#[must_use]
pub fn largest_region_start(map: &OccupancyGrid, robot_radius: f64) -> Option<Cell> {
    largest_region_cell(&admissible(map, robot_radius))
}

/// The first set cell (row-major) of the largest 4-connected region of
/// `mask` (ties: the region met first), if any cell is set.
#[must_use]
pub fn largest_region_cell(mask: &Grid<bool>) -> Option<Cell> {
    let comps = components4(mask);
    comps.first_cell(comps.largest()?)
}

/// Coverage-cell side in fine cells for a tool radius: one tool diameter,
/// `max(1, floor(2T / resolution + tolerance))`.
#[must_use]
pub fn coarse_block(robot: &DiscRobot, resolution: f64) -> usize {
    let k = (2.0 * robot.tool_radius / resolution + TOLERANCE_CELLS).floor();
    if k.is_finite() && k >= 1.0 {
        k as usize
    } else {
        1
    }
}

/// The coverage problem on a map for a robot and a start.
#[derive(Clone, Debug)]
pub struct CoverageProblem {
    frame: MapFrame,
    cells: Coverability,
    coarse: CoarseGrid,
    tool_cells: f64,
    /// The start position asked for, when it was a position.
    start_point: Option<Point>,
    /// Speeds planners score their choices with.
    time: TimeModel,
    /// This problem's cell (0, 0) in the original map.
    offset: Cell,
}

impl CoverageProblem {
    /// Builds the problem.
    ///
    /// # Errors
    /// [`Error::Map`]: no free or admissible cell, a start outside the map or
    /// not admissible (the grid crate's messages).
    pub fn new(map: &OccupancyGrid, robot: DiscRobot, start: Start) -> Result<Self> {
        Self::new_within(map, robot, start, None)
    }

    /// [`CoverageProblem::new`] with coverable cells only inside `within`
    /// (rows `r0..r1`, columns `c0..c1`; [`Coverability::new_within`]): for
    /// a target known to lie there, the rest of the map is still driven
    /// through but not looked at for coverage. `None`: everywhere.
    ///
    /// # Errors
    /// As [`CoverageProblem::new`].
    pub fn new_within(
        map: &OccupancyGrid,
        robot: DiscRobot,
        start: Start,
        within: Option<Window>,
    ) -> Result<Self> {
        let (cells, start_point) = match start {
            Start::First => (Coverability::new_within(map, robot, None, within)?, None),
            Start::At(p) => (
                Coverability::new_within(map, robot, Some(p), within)?,
                Some(p),
            ),
            Start::Cell(c) => (
                Coverability::with_start_cell_within(map, robot, c, within)?,
                None,
            ),
            Start::LargestRegion => (
                Coverability::in_largest_region_within(map, robot, within)?,
                None,
            ),
        };
        let frame = *map.frame();
        let coarse = CoarseGrid::new(&cells.reachable, coarse_block(&robot, frame.resolution()));
        Ok(Self {
            frame,
            cells,
            coarse,
            tool_cells: robot.tool_cells(frame.resolution()),
            start_point,
            time: TimeModel::default(),
            offset: Cell::new(0, 0),
        })
    }

    /// The same problem with the speeds planners score their choices with
    /// (default: the contract's 0.3 m/s and 0.52 rad/s).
    #[must_use]
    pub fn with_time(mut self, time: TimeModel) -> Self {
        self.time = time;
        self
    }

    /// The same problem with only the coverable cells set in `required`
    /// (the map's size) left to cover: a coverage target. Plannable cells
    /// stay as they are (the robot may drive anywhere to reach the target).
    ///
    /// # Errors
    /// [`Error::BadParameter`] when `required` is not the map's size.
    pub fn with_required(mut self, required: &Grid<bool>) -> Result<Self> {
        let c = &mut self.cells.coverable;
        if (required.width(), required.height()) != (c.width(), c.height()) {
            return Err(Error::BadParameter {
                name: "required cells",
                value: format!("{}x{}", required.width(), required.height()),
                expected: "the map's size",
            });
        }
        *c = c.zip_map(required, |&a, &b| a && b);
        Ok(self)
    }

    /// This problem started at its plannable cell `start` instead. Its
    /// plannable cells are those connected to its start, the same from
    /// any of them, and so are its coverable cells and coverage grid: only
    /// the start moves.
    ///
    /// # Errors
    /// [`Error::BadParameter`] when `start` is not one of its plannable
    /// cells, or its start was asked for as a position.
    pub fn with_start_cell(mut self, start: Cell) -> Result<Self> {
        if !self.plannable().is_set(start) || self.start_point.is_some() {
            return Err(Error::BadParameter {
                name: "start",
                value: format!("{start:?}"),
                expected: "a plannable cell of a problem started at a cell",
            });
        }
        self.cells.start = start;
        Ok(self)
    }

    /// The speeds planners score their choices with.
    #[must_use]
    pub fn time(&self) -> TimeModel {
        self.time
    }

    /// The problem on a sub-region: plannable cells are those of this problem
    /// inside `mask` and 4-connected to `start` there; coverable cells are
    /// this problem's coverable cells the tool reaches from them.
    ///
    /// The new problem is cropped to the region's bounding box, widened by
    /// the tool's reach: its grids, frame and cells are the crop's
    /// ([`CoverageProblem::offset`] gives the crop's first cell in the
    /// original map; metre positions are the same in both frames). Work on
    /// a room thus costs the room's size, not the map's.
    ///
    /// # Errors
    /// [`Error::BadParameter`] when `mask` is not the map's size or `start`
    /// is not a plannable cell inside it.
    pub fn restricted(&self, mask: &Grid<bool>, start: Cell) -> Result<Self> {
        self.restricted_claiming(mask, start, None)
    }

    /// [`CoverageProblem::restricted`], with only the cells set in `claim`
    /// (the map's size) left to cover: room by room, a cell within reach of
    /// two rooms is covered by the one that claims it.
    ///
    /// # Errors
    /// As [`CoverageProblem::restricted`], and when `claim` is not the
    /// map's size.
    pub fn restricted_claiming(
        &self,
        mask: &Grid<bool>,
        start: Cell,
        claim: Option<&Grid<bool>>,
    ) -> Result<Self> {
        let plannable = self.plannable();
        let (w, h) = (plannable.width(), plannable.height());
        if (mask.width(), mask.height()) != (w, h) {
            return Err(Error::BadParameter {
                name: "region mask",
                value: format!("{}x{}", mask.width(), mask.height()),
                expected: "the map's size",
            });
        }
        if let Some(c) = claim
            && (c.width(), c.height()) != (w, h)
        {
            return Err(Error::BadParameter {
                name: "claimed cells",
                value: format!("{}x{}", c.width(), c.height()),
                expected: "the map's size",
            });
        }
        if !(plannable.is_set(start) && mask.is_set(start)) {
            return Err(Error::BadParameter {
                name: "region start",
                value: format!("{start:?}"),
                expected: "a plannable cell inside the region",
            });
        }
        let (mut r0, mut r1, mut c0, mut c1) = (start.row, start.row, start.col, start.col);
        for c in mask.true_cells() {
            if plannable[c] {
                r0 = r0.min(c.row);
                r1 = r1.max(c.row);
                c0 = c0.min(c.col);
                c1 = c1.max(c.col);
            }
        }
        Ok(self.cropped(
            (r0, r1, c0, c1),
            start,
            |c| mask[c],
            |c| claim.is_none_or(|k| k[c]),
        ))
    }

    /// The problem on the cells `inside` accepts (all within rows r0..=r1
    /// and columns c0..=c1 of `window`, with `start` among them), those
    /// `claim` accepts left to cover: cropped to the window widened by
    /// the tool's reach.
    pub(crate) fn cropped(
        &self,
        (r0, r1, c0, c1): (usize, usize, usize, usize),
        start: Cell,
        inside: impl Fn(Cell) -> bool,
        claim: impl Fn(Cell) -> bool,
    ) -> Self {
        let plannable = self.plannable();
        let (w, h) = (plannable.width(), plannable.height());
        let margin = self.tool_cells.ceil().min((w + h) as f64) as usize + 2;
        let (r0, c0) = (r0.saturating_sub(margin), c0.saturating_sub(margin));
        let (r1, c1) = ((r1 + 1 + margin).min(h), (c1 + 1 + margin).min(w));
        let (cw, ch) = (c1 - c0, r1 - r0);
        let at = |c: Cell| Cell::new(c.row + r0, c.col + c0);
        let region = Grid::from_fn(cw, ch, |c| plannable[at(c)] && inside(at(c)));
        let local_start = Cell::new(start.row - r0, start.col - c0);
        let reach = reachable(&region, local_start);
        let parent_coverable =
            Grid::from_fn(cw, ch, |c| self.cells.coverable[at(c)] && claim(at(c)));
        let coverable = coverable_cells(&parent_coverable, &reach, self.tool_cells);
        let cells = Coverability {
            robot: self.cells.robot,
            admissible: Grid::from_fn(cw, ch, |c| self.cells.admissible[at(c)]),
            start: local_start,
            reachable: reach,
            coverable,
        };
        let frame = self.frame.crop(Cell::new(r0, c0), cw, ch);
        let coarse = CoarseGrid::new(&cells.reachable, self.coarse.block_size());
        Self {
            frame,
            cells,
            coarse,
            tool_cells: self.tool_cells,
            start_point: None,
            time: self.time,
            offset: Cell::new(self.offset.row + r0, self.offset.col + c0),
        }
    }

    /// Where this problem's cell (0, 0) lies in the original map (not (0, 0)
    /// for a [`CoverageProblem::restricted`] crop).
    #[must_use]
    pub fn offset(&self) -> Cell {
        self.offset
    }

    /// The original map's `cell` in this problem's cells, if inside it.
    #[must_use]
    pub fn from_map_cell(&self, cell: Cell) -> Option<Cell> {
        let (r, c) = (
            cell.row.checked_sub(self.offset.row)?,
            cell.col.checked_sub(self.offset.col)?,
        );
        let local = Cell::new(r, c);
        self.plannable().get(local).is_some().then_some(local)
    }

    /// This problem's `cell` in the original map's cells.
    #[must_use]
    pub fn to_map_cell(&self, cell: Cell) -> Cell {
        Cell::new(cell.row + self.offset.row, cell.col + self.offset.col)
    }

    /// What a planner sees, with `seed` for randomised planners.
    #[must_use]
    pub fn input(&self, seed: u64) -> PlannerInput<'_> {
        PlannerInput {
            plannable: &self.cells.reachable,
            coverable: &self.cells.coverable,
            admissible: &self.cells.admissible,
            coarse: &self.coarse,
            start: self.coarse.coarse_of(self.cells.start),
            start_cell: self.cells.start,
            seed,
            frame: self.frame,
            tool_cells: self.tool_cells,
            time: self.time,
            exit: None,
            plan_cells: self.cells.reachable.count_true(),
        }
    }

    /// The map frame.
    #[must_use]
    pub fn frame(&self) -> &MapFrame {
        &self.frame
    }

    /// The robot and tool.
    #[must_use]
    pub fn robot(&self) -> DiscRobot {
        self.cells.robot
    }

    /// The contract's cells (admissible, reachable, coverable) and the start cell.
    #[must_use]
    pub fn cells(&self) -> &Coverability {
        &self.cells
    }

    /// Fine cells a planner may use: admissible and reachable from the start.
    #[must_use]
    pub fn plannable(&self) -> &Grid<bool> {
        &self.cells.reachable
    }

    /// The start cell.
    #[must_use]
    pub fn start_cell(&self) -> Cell {
        self.cells.start
    }

    /// The start position asked for, if the start was given in metres.
    #[must_use]
    pub fn start_point(&self) -> Option<Point> {
        self.start_point
    }

    /// The coverage grid.
    #[must_use]
    pub fn coarse(&self) -> &CoarseGrid {
        &self.coarse
    }

    /// Fine cells per coverage-cell side ([`coarse_block`]).
    #[must_use]
    pub fn block(&self) -> usize {
        self.coarse.block_size()
    }

    /// Tool radius in fine cells, `T / resolution`.
    #[must_use]
    pub fn tool_cells(&self) -> f64 {
        self.tool_cells
    }

    /// The fine path of a plan: coverage steps become the fine paths
    /// [`CoarseGrid::connect`] gives, from the start's representative.
    ///
    /// # Errors
    /// [`Error::Internal`] if two consecutive coverage cells are not
    /// connected, or for a metre path (it has no cell path).
    pub fn expand(&self, output: &PlanOutput) -> Result<Vec<Cell>> {
        self.input(0).expand(output)
    }

    /// The fine path from the start cell to `to` (where a plan begins): a
    /// shortest 4-connected path over plannable cells; just the start when
    /// `to` is `None` or the start itself.
    ///
    /// # Errors
    /// [`Error::Internal`] when `to` is not reachable from the start.
    pub fn lead_in(&self, to: Option<Cell>) -> Result<Vec<Cell>> {
        let start = self.cells.start;
        let Some(to) = to.filter(|&t| t != start) else {
            return Ok(vec![start]);
        };
        let mut wave = Wavefront::new(&self.cells.reachable);
        let near = cidt(&mut wave, &[start], |c| c == to).ok_or_else(|| {
            Error::Internal(format!("plan starts at {to:?}, unreachable from the start"))
        })?;
        wave.retrace(near.first())
            .ok_or_else(|| Error::Internal("lead-in retrace failed".into()))
    }

    /// The shortest way from the plannable cell `from` to the nearest
    /// plannable cell where `is_target` holds (ties: row-major first): its
    /// 4-connected cells, and its waypoints straightened into an any-angle
    /// path (string pulling over the cell route, each shortcut checked by
    /// exact traversal, so it never cuts a corner of a wall).
    ///
    /// # Errors
    /// [`Error::Internal`] when no target is reachable from `from`.
    pub fn transit(&self, from: Cell, is_target: impl FnMut(Cell) -> bool) -> Result<Transit> {
        self.transit_reusing(&mut self.transit_wavefront(), from, is_target)
    }

    /// A wavefront for [`Self::transit_reusing`].
    #[must_use]
    pub fn transit_wavefront(&self) -> Wavefront {
        Wavefront::new(&self.cells.reachable)
    }

    /// [`Self::transit`] with a wavefront from [`Self::transit_wavefront`]
    /// kept between calls: each search then costs the cells it touches, not
    /// the map's size (a tour of hundreds of rooms makes hundreds).
    ///
    /// # Errors
    /// As [`Self::transit`].
    pub fn transit_reusing(
        &self,
        wave: &mut Wavefront,
        from: Cell,
        is_target: impl FnMut(Cell) -> bool,
    ) -> Result<Transit> {
        let plannable = &self.cells.reachable;
        let near = cidt(wave, &[from], is_target)
            .ok_or_else(|| Error::Internal(format!("no target reachable from {from:?}")))?;
        let cells = wave
            .retrace(near.first())
            .ok_or_else(|| Error::Internal("transit retrace failed".into()))?;
        let mut path = PathBuilder::new(plannable, from);
        path.follow(cells.get(1..).unwrap_or_default(), f64::INFINITY);
        Ok(Transit {
            points: path.into_metres(&self.frame),
            cells,
        })
    }

    /// The route covering what `points` leaves uncovered, from the plannable
    /// cell `end` ([`boundary_pass`]).
    ///
    /// # Errors
    /// As [`boundary_pass`].
    pub fn boundary_pass(&self, points: &[Point], end: Cell) -> Result<BoundaryRoute> {
        boundary_pass(&self.frame, &self.cells, points, end)
    }

    /// The cells the polyline `points` (metres, map frame) covers with this
    /// problem's tool, as the metrics find them ([`covered_by`]).
    #[must_use]
    pub fn covered_by(&self, points: &[Point]) -> Grid<bool> {
        covered_by(&self.frame, &self.cells, points)
    }

    /// [`Self::boundary_pass`] given the cells the plan covers (`covered`,
    /// as [`Self::covered_by`] finds them; [`boundary_pass_covered`]).
    ///
    /// # Errors
    /// As [`boundary_pass_covered`].
    pub fn boundary_pass_covered(&self, covered: Grid<bool>, end: Cell) -> Result<BoundaryRoute> {
        boundary_pass_covered(&self.frame, &self.cells, covered, end)
    }

    /// The route covering what `points` leaves uncovered, from the plannable
    /// cell `end`, as a straightened tour ([`boundary_tour`]).
    ///
    /// # Errors
    /// As [`boundary_pass`].
    pub fn boundary_tour(&self, points: &[Point], end: Cell) -> Result<BoundaryRoute> {
        boundary_tour(&self.frame, &self.cells, points, end)
    }

    /// `points` (metres, map frame) with the waypoints from index `first`
    /// on tightened for time, as `lanes` tightens its own path: each
    /// removed, moved towards the line of its neighbours or slid along a
    /// piece where that saves estimated time, stays clear of non-plannable
    /// cells and leaves no coverable cell the whole path reached out of
    /// reach of the contract's samples. The waypoints before `first` stay
    /// as they are. Room by room the pipeline tightens each room's
    /// boundary pass with it.
    #[must_use]
    pub fn tighten_from(&self, points: &[Point], first: usize) -> Vec<Point> {
        self.tighten_within(points, first, None).0
    }

    /// [`Self::tighten_from`] with each waypoint `i` that has a label
    /// `zones.1[i]` other than 0 moved only within the cells of that label
    /// in `zones.0` (a grid of this problem's size; removed freely). Also
    /// returns, for each waypoint kept, its index in `points`.
    ///
    /// The pipeline tightens a whole room-by-room plan with it, every
    /// room's waypoints kept in their room.
    #[must_use]
    pub fn tighten_within(
        &self,
        points: &[Point],
        first: usize,
        zones: Option<(&Grid<u32>, &[u32])>,
    ) -> (Vec<Point>, Vec<usize>) {
        self.tighten_within_beside(points, first, zones, || ()).0
    }

    /// [`Self::tighten_within`], running `beside` while it tightens: in
    /// parallel with its passes after the first (the first looks at every
    /// waypoint, in parallel where there are many; the later ones at the
    /// few next to a change). The same path, and `beside`'s result.
    pub fn tighten_within_beside<R: Send>(
        &self,
        points: &[Point],
        first: usize,
        zones: Option<(&Grid<u32>, &[u32])>,
        beside: impl FnOnce() -> R + Send,
    ) -> ((Vec<Point>, Vec<usize>), R) {
        if first + 1 >= points.len() {
            return ((points.to_vec(), (0..points.len()).collect()), beside());
        }
        let frame = &self.frame;
        let grid = metres_to_grid(frame, points);
        let res = frame.resolution();
        let tool = self.tool_cells().max(0.5);
        let (reach, fragile) = metric_reach(self.tool_cells());
        let d = Detours {
            plannable: self.plannable(),
            coverable: &self.cells.coverable,
            reach,
            fragile,
            search: 5.0 * tool,
            time: TimeModel {
                linear_speed: self.time.linear_speed / res,
                angular_speed: self.time.angular_speed,
            },
        };
        let count = reach_counts(&grid, &d);
        let zone = zones.map(|(labels, of_vertex)| Zone { labels, of_vertex });
        let ((tight, kept, _), beside) =
            tighten_from(&grid, &d, count, first, zone.as_ref(), beside);
        ((grid_to_metres(frame, &tight), kept), beside)
    }

    /// [`Self::boundary_tour`] ending towards the plannable cell `exit`
    /// ([`boundary_tour_to`]).
    ///
    /// # Errors
    /// As [`boundary_pass`].
    pub fn boundary_tour_to(
        &self,
        points: &[Point],
        end: Cell,
        exit: Option<Cell>,
    ) -> Result<BoundaryRoute> {
        boundary_tour_to(&self.frame, &self.cells, points, end, exit)
    }

    /// [`Self::boundary_tour_to`] given the cells the plan covers
    /// (`covered`, as [`Self::covered_by`] finds them;
    /// [`boundary_tour_to_covered`]).
    ///
    /// # Errors
    /// As [`boundary_pass_covered`].
    pub fn boundary_tour_to_covered(
        &self,
        covered: Grid<bool>,
        end: Cell,
        exit: Option<Cell>,
    ) -> Result<BoundaryRoute> {
        boundary_tour_to_covered(&self.frame, &self.cells, covered, end, exit)
    }
}
