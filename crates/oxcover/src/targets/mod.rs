//! Coverage targets: what must be covered and where the robot may never be
//! (the contract's "Coverage targets").
//!
//! - zones (`--zones`, GeoJSON polygons with holes) and a spot (`--spot
//!   X,Y,R`, a disc): only coverable cells whose centre lies inside are
//!   required;
//! - keep-out areas and virtual walls (`--keep-out`, GeoJSON polygons and
//!   lines): every cell whose square meets a polygon or that a line touches
//!   counts as occupied, for planning and for the metrics alike;
//! - chosen rooms (`--rooms-only`): only coverable cells in the rooms with
//!   these labels (the labels `oxcover segment` prints with its defaults)
//!   are required, visited fastest first or in the order given;
//! - resume (`--done PATH.csv`): the cells that path covers are not
//!   required, and the robot starts where it stopped.
//!
//! Every given target narrows the required set (they intersect); the
//! pipeline builds the keep-out map and the required cells once
//! ([`Targets::blocked_map`], [`Targets::required`]) and plans the target's
//! connected parts room by room through the one pipeline.

mod geojson;
mod overlay;
mod raster;
#[cfg(test)]
mod tests;

pub use self::geojson::{
    Areas, Kinds, MAX_FILE_POSITIONS, MAX_POLYGON_POSITIONS, parse_areas, read_areas,
};
pub use self::overlay::target_overlay;
pub use self::raster::{Placement, disc_centres, line_squares, polygon_centres, polygon_squares};

use std::borrow::Cow;

use oxcover_grid::footprint::covered_cells;
use oxcover_grid::{Cell, Coverability, Grid, Occupancy, OccupancyGrid, Point, Window, admissible};

use crate::error::{Error, Result};
use crate::metrics::{Evaluation, MetricParams, evaluate, evaluate_covered};
use crate::rooms::{SegmentOptions, segment};

/// A disc to cover (`--spot X,Y,R`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    /// Centre, metres in the map frame.
    pub centre: Point,
    /// Radius in metres.
    pub radius: f64,
}

/// The order of the chosen rooms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RoomOrder {
    /// The order of least estimated transit time (default).
    #[default]
    Fastest,
    /// The order the labels were given in.
    Given,
}

/// What to cover and what never to enter. The default asks for nothing:
/// every coverable cell, no cell blocked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Targets {
    /// Zones (polygons; lines are refused when read).
    pub zones: Option<Areas>,
    /// A disc zone.
    pub spot: Option<Spot>,
    /// Keep-out areas (polygons) and virtual walls (lines).
    pub keep_out: Option<Areas>,
    /// Labels of the rooms to cover (as `oxcover segment` numbers them).
    pub rooms_only: Option<Vec<u32>>,
    /// The order of the chosen rooms.
    pub room_order: RoomOrder,
    /// The path already driven (metres, map frame).
    pub done: Option<Vec<Point>>,
}

/// The cells a target gives, with what the report says of them.
#[derive(Clone, Debug, PartialEq)]
pub struct TargetCells {
    /// Required cells (coverable and inside every target, less done).
    pub required: Grid<bool>,
    /// Coverable cells inside every target that `--done` had covered.
    pub done_cells: usize,
    /// Room label of each cell when rooms were chosen (for the room order).
    pub room_labels: Option<Grid<u32>>,
    /// Notes for the user (a zone clipped to the map).
    pub notes: Vec<String>,
}

/// What the report says of a target.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TargetSummary {
    /// Required cells.
    pub required_cells: usize,
    /// Their area in m².
    pub required_area_m2: f64,
    /// Cells inside the target that the done path had covered.
    pub done_cells: usize,
    /// Free cells the keep-out areas and virtual walls block.
    pub blocked_cells: usize,
}

impl Targets {
    /// Whether nothing is asked (the whole map, nothing blocked).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.keep_out.is_none() && !self.narrows()
    }

    /// Whether the required set is narrower than the coverable cells.
    #[must_use]
    pub fn narrows(&self) -> bool {
        self.zones.is_some()
            || self.spot.is_some()
            || self.rooms_only.is_some()
            || self.done.is_some()
    }

    /// The window of `map` (rows `r0..r1`, columns `c0..c1`) that holds
    /// every cell centre the zones and the spot take in (the intersection
    /// of their bounding boxes), `None` where neither is given: the
    /// required cells lie there, whatever else narrows them.
    #[must_use]
    pub fn extent(&self, map: &OccupancyGrid) -> Option<Window> {
        use geo::BoundingRect;
        let frame = map.frame();
        let (w, h) = (map.width() as f64, map.height() as f64);
        // A box in metres as the window of cells round it (the frame may
        // be turned: its four corners' rows and columns).
        let window = |lo: Point, hi: Point| {
            let corners = [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)]
                .map(|(x, y)| frame.fractional_cell(&Point::new(x, y)));
            let (mut r0, mut r1, mut c0, mut c1) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for (r, c) in corners {
                (r0, r1, c0, c1) = (r0.min(r), r1.max(r), c0.min(c), c1.max(c));
            }
            // Every cell whose centre may lie inside, and one more round.
            let clamp = |v: f64, top: f64| v.clamp(0.0, top) as usize;
            (
                clamp(r0.floor() - 1.0, h),
                clamp(r1.ceil() + 1.0, h),
                clamp(c0.floor() - 1.0, w),
                clamp(c1.ceil() + 1.0, w),
            )
        };
        let mut boxes = Vec::new();
        if let Some(zones) = &self.zones {
            let rect = zones
                .polygons
                .iter()
                .filter_map(BoundingRect::bounding_rect)
                .reduce(|a, b| {
                    geo::Rect::new(
                        (a.min().x.min(b.min().x), a.min().y.min(b.min().y)),
                        (a.max().x.max(b.max().x), a.max().y.max(b.max().y)),
                    )
                });
            let (lo, hi) = rect.map_or((Point::origin(), Point::origin()), |r| {
                (
                    Point::new(r.min().x, r.min().y),
                    Point::new(r.max().x, r.max().y),
                )
            });
            boxes.push(window(lo, hi));
        }
        if let Some(spot) = self.spot {
            let r = Point::new(spot.radius, spot.radius);
            boxes.push(window(spot.centre - r.coords, spot.centre + r.coords));
        }
        boxes.into_iter().reduce(|a, b| {
            let (r0, c0) = (a.0.max(b.0), a.2.max(b.2));
            (r0, a.1.min(b.1).max(r0), c0, a.3.min(b.3).max(c0))
        })
    }

    /// `map` with every cell the keep-out areas meet and the virtual walls
    /// touch made occupied, and how many free cells that blocked (the map
    /// itself when there is no keep-out).
    ///
    /// # Errors
    /// [`Error::Target`] when no keep-out area or wall touches the map.
    pub fn blocked_map<'a>(
        &self,
        map: &'a OccupancyGrid,
    ) -> Result<(Cow<'a, OccupancyGrid>, usize)> {
        let Some(areas) = &self.keep_out else {
            return Ok((Cow::Borrowed(map), 0));
        };
        let mark = keep_out_cells(map, areas)?;
        let mut out = map.clone();
        let mut blocked = 0;
        for c in mark.true_cells() {
            let cell = &mut out.cells_mut()[c];
            blocked += usize::from(cell.is_free());
            *cell = Occupancy::Occupied;
        }
        Ok((Cow::Owned(out), blocked))
    }

    /// The required cells on `cells` (the coverage problem of the map with
    /// keep-out applied): coverable, inside every zone, the spot and the
    /// chosen rooms of `map` (the map as read), not covered by the done
    /// path. `None` when nothing narrows the coverable cells.
    ///
    /// # Errors
    /// [`Error::Target`]: a zone or spot outside the map, an unknown room
    /// label (the valid ones listed), a done path leaving the map, or no
    /// required cell left reachable from the start.
    pub fn required(
        &self,
        map: &OccupancyGrid,
        cells: &Coverability,
    ) -> Result<Option<TargetCells>> {
        if !self.narrows() {
            return Ok(None);
        }
        let frame = map.frame();
        let (w, h) = (map.width(), map.height());
        let mut required = cells.coverable.clone();
        let mut notes = Vec::new();
        if let Some(zones) = &self.zones {
            let mut inside = Grid::new(w, h, false);
            let mut placed = Placement::default();
            for p in &zones.polygons {
                placed += polygon_centres(frame, p, &mut inside);
            }
            if placed.cells == 0 {
                return Err(target(
                    "--zones",
                    "no zone holds the centre of a map cell (is it outside the map, or in another frame?)",
                ));
            }
            if placed.clipped {
                notes.push(
                    "--zones: a zone reaches outside the map; it is clipped to the map".into(),
                );
            }
            required = required.zip_map(&inside, |&r, &i| r && i);
        }
        if let Some(spot) = self.spot {
            let mut inside = Grid::new(w, h, false);
            let placed = disc_centres(frame, spot.centre, spot.radius, &mut inside);
            if placed.cells == 0 {
                return Err(target("--spot", "the disc holds no cell centre of the map"));
            }
            if placed.clipped {
                notes.push(
                    "--spot: the disc reaches outside the map; it is clipped to the map".into(),
                );
            }
            required = required.zip_map(&inside, |&r, &i| r && i);
        }
        let room_labels = match &self.rooms_only {
            Some(chosen) => {
                let labels = room_labels(map)?;
                let n = labels.as_slice().iter().copied().max().unwrap_or(0);
                check_rooms(chosen, n)?;
                required = required.zip_map(&labels, |&r, l| r && chosen.contains(l));
                Some(labels)
            }
            None => None,
        };
        let mut done_cells = 0;
        if let Some(done) = &self.done {
            done_on_map(frame, done)?;
            let covered = covered_cells(frame, done, cells.robot.tool_radius);
            for c in required.cells() {
                if required[c] && covered[c] {
                    required[c] = false;
                    done_cells += 1;
                }
            }
        }
        if required.count_true() == 0 {
            let msg = if done_cells > 0 {
                "the done path already covers every required cell: nothing is left to cover"
            } else {
                "the target holds no coverable cell reachable from the start"
            };
            return Err(target("target", msg));
        }
        Ok(Some(TargetCells {
            required,
            done_cells,
            room_labels,
            notes,
        }))
    }
}

/// Refuses a done path with a point off the map, naming the first.
fn done_on_map(frame: &oxcover_grid::MapFrame, done: &[Point]) -> Result<()> {
    match done
        .iter()
        .enumerate()
        .find(|(_, p)| frame.cell_at(p).is_none())
    {
        Some((i, p)) => Err(target(
            "--done",
            &format!("point {} ({}, {}) lies outside the map", i + 1, p.x, p.y),
        )),
        None => Ok(()),
    }
}

/// The `chosen` room labels refused unless each is one of the `n` rooms of
/// the map, by the first that is not.
pub(crate) fn check_rooms(chosen: &[u32], n: u32) -> Result<()> {
    match chosen.iter().find(|&&l| l == 0 || l > n) {
        Some(bad) => Err(target(
            "--rooms-only",
            &format!(
                "no room {bad} on this map: the rooms are 1 to {n} (`oxcover segment` lists them)"
            ),
        )),
        None => Ok(()),
    }
}

fn target(what: &str, message: &str) -> Error {
    Error::Target {
        what: what.to_string(),
        message: message.to_string(),
    }
}

/// The cells the keep-out `areas` block on `map`.
fn keep_out_cells(map: &OccupancyGrid, areas: &Areas) -> Result<Grid<bool>> {
    let frame = map.frame();
    let mut mark = Grid::new(map.width(), map.height(), false);
    let mut placed = Placement::default();
    for p in &areas.polygons {
        placed += polygon_squares(frame, p, &mut mark);
    }
    for l in &areas.lines {
        placed += line_squares(frame, l, &mut mark);
    }
    if placed.cells == 0 {
        return Err(target(
            "--keep-out",
            "no keep-out area or wall meets the map (is it in another frame?)",
        ));
    }
    Ok(mark)
}

/// The room labels `oxcover segment` gives `map` with its defaults.
///
/// # Errors
/// As [`segment`] (not with the defaults).
pub fn room_labels(map: &OccupancyGrid) -> Result<Grid<u32>> {
    Ok(segment(map, &SegmentOptions::default())?.labels)
}

impl Targets {
    /// Where a plan with these targets starts by default: with a done path,
    /// where it stopped ([`resume_start`] on the map with keep-out applied,
    /// for a robot of `radius` metres, clearance included); `None` without
    /// one (the contract's default start).
    ///
    /// # Errors
    /// As [`Targets::blocked_map`] and [`resume_start`].
    pub fn default_start(
        &self,
        map: &OccupancyGrid,
        radius: f64,
    ) -> Result<Option<(Point, Option<String>)>> {
        let Some(done) = &self.done else {
            return Ok(None);
        };
        let (work, _) = self.blocked_map(map)?;
        resume_start(&work, radius, done).map(Some)
    }
}

impl Spot {
    /// A spot, checked: a finite centre and a finite radius above 0.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming `--spot`.
    pub fn new(centre: Point, radius: f64) -> Result<Self> {
        if centre.x.is_finite() && centre.y.is_finite() && radius.is_finite() && radius > 0.0 {
            Ok(Self { centre, radius })
        } else {
            Err(Error::BadParameter {
                name: "--spot",
                value: format!("{},{},{}", centre.x, centre.y, radius),
                expected: "a finite centre X,Y and a finite radius R above 0".into(),
            })
        }
    }

    /// The spot's circle as a closed polyline of 48 segments, for pictures
    /// and markers.
    #[must_use]
    pub fn outline(&self) -> Vec<Point> {
        let n = 48;
        (0..=n)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
                self.centre + self.radius * oxcover_grid::Vector::new(a.cos(), a.sin())
            })
            .collect()
    }
}

/// Where a resumed plan starts: the done path's last point when the robot
/// may stand there on `map` (keep-out applied) with `robot_radius`, else
/// the nearest admissible cell centre, with a note saying how far it moved.
///
/// # Errors
/// [`Error::Target`] for an empty done path or one with a point off the
/// map, or a map with no admissible cell.
pub fn resume_start(
    map: &OccupancyGrid,
    robot_radius: f64,
    done: &[Point],
) -> Result<(Point, Option<String>)> {
    let Some(&last) = done.last() else {
        return Err(target("--done", "the path has no point"));
    };
    let frame = map.frame();
    done_on_map(frame, done)?;
    let Some(cell) = frame.cell_at(&last) else {
        return Err(target("--done", "its last point lies outside the map"));
    };
    let ok = admissible(map, robot_radius);
    if ok[cell] {
        return Ok((last, None));
    }
    let nearest = ok
        .true_cells()
        .map(|c: Cell| ((frame.cell_center(c) - last).norm(), c))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .ok_or_else(|| target("--done", "the map has no cell the robot may stand in"))?;
    let p = frame.cell_center(nearest.1);
    Ok((
        p,
        Some(format!(
            "--done: the robot cannot stand at the path's last point ({:.3}, {:.3}); resuming from ({:.3}, {:.3}), {:.3} m away",
            last.x, last.y, p.x, p.y, nearest.0
        )),
    ))
}

/// Scores `points` on `map` against `targets` (`oxcover eval` with target
/// options): keep-out cells count as occupied (a sample there is a
/// collision) and `coverage` is that of the required cells.
///
/// # Errors
/// As [`evaluate`], [`Targets::blocked_map`] and [`Targets::required`].
pub fn evaluate_targets(
    map: &OccupancyGrid,
    robot: oxcover_grid::DiscRobot,
    points: &[Point],
    params: &MetricParams,
    targets: &Targets,
) -> Result<Evaluation> {
    let (work, _) = targets.blocked_map(map)?;
    let ev = evaluate(&work, robot, points, params)?;
    match targets.required(map, &ev.problem)? {
        None => Ok(ev),
        Some(t) => {
            let mut problem = ev.problem;
            problem.coverable = t.required;
            Ok(evaluate_covered(
                map.frame(),
                problem,
                points,
                ev.covered,
                params,
            ))
        }
    }
}

/// Which of a path's points lie in cells `blocked` (keep-out) marks, and
/// whether a segment crosses a blocked cell: the keep-out violations of a
/// path (metres, map frame), its samples every resolution / 4.
#[must_use]
pub fn keep_out_violations(map: &OccupancyGrid, areas: &Areas, points: &[Point]) -> usize {
    let Ok(mark) = keep_out_cells(map, areas) else {
        return 0;
    };
    let frame = map.frame();
    let mut n = 0;
    oxcover_grid::footprint::for_each_sample(points, map.resolution() / 4.0, |p| {
        if frame.cell_at(p).is_some_and(|c| mark[c]) {
            n += 1;
        }
    });
    n
}
