//! The contract's coverage problem on a map: admissible, reachable and coverable cells.
//!
//! - *Admissible*: see [`crate::admissible()`].
//! - *Reachable*: admissible cells 4-connected to the start through admissible cells.
//! - *Coverable*: free cells whose centre is within the tool radius of a
//!   reachable cell's centre (exact EDT between centres, same tolerance).
//!
//! The default start is the first admissible cell in row-major order of the
//! image (top row first); a start that is not admissible is an error, never a
//! silent move.

use crate::admissible::{TOLERANCE_CELLS, admissible};
use crate::components::{components4, reachable};
use crate::edt::center_within_sq;
use crate::error::{Error, Result, non_negative, positive};
use crate::grid::{Cell, Grid, Window};
use crate::math::Point;
use crate::occupancy::{Occupancy, OccupancyGrid};

/// A disc robot carrying a disc tool centred on it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DiscRobot {
    /// Body radius in metres (default 0: a point robot, contract).
    pub robot_radius: f64,
    /// Cleaning/sensing radius in metres (default `resolution / 2`, contract).
    pub tool_radius: f64,
}

impl DiscRobot {
    /// A robot with the given radii, checked: robot radius finite and `>= 0`,
    /// tool radius finite and `> 0`.
    ///
    /// # Errors
    /// [`Error::BadParameter`] naming `--robot-radius` or `--tool-radius`.
    pub fn new(robot_radius: f64, tool_radius: f64) -> Result<Self> {
        Ok(Self {
            robot_radius: non_negative("--robot-radius", robot_radius)?,
            tool_radius: positive("--tool-radius", tool_radius)?,
        })
    }

    /// The contract's defaults for a map of the given resolution: one cell is one
    /// footprint (robot radius 0, tool radius `resolution / 2`).
    #[must_use]
    pub fn cell_sized(resolution: f64) -> Self {
        Self {
            robot_radius: 0.0,
            tool_radius: resolution / 2.0,
        }
    }

    /// Tool radius in cells of the given resolution.
    #[must_use]
    pub fn tool_cells(&self, resolution: f64) -> f64 {
        self.tool_radius / resolution
    }
}

/// Admissible, reachable and coverable cells of a map for a robot and a start.
#[derive(Clone, Debug)]
pub struct Coverability {
    /// The robot and tool.
    pub robot: DiscRobot,
    /// Admissible cells.
    pub admissible: Grid<bool>,
    /// The start cell (admissible).
    pub start: Cell,
    /// Admissible cells reachable from `start`.
    pub reachable: Grid<bool>,
    /// Free cells the tool can cover from some reachable cell.
    pub coverable: Grid<bool>,
}

impl Coverability {
    /// Builds the problem; `start` in metres, or `None` for the default start.
    ///
    /// # Errors
    /// [`Error::NoFreeCell`], [`Error::NoAdmissibleCell`], [`Error::StartOutsideMap`],
    /// [`Error::StartNotAdmissible`].
    pub fn new(map: &OccupancyGrid, robot: DiscRobot, start: Option<Point>) -> Result<Self> {
        Self::new_within(map, robot, start, None)
    }

    /// [`Coverability::new`] with the coverable cells found only inside
    /// `within` (rows `r0..r1`, columns `c0..c1`; none outside), where
    /// only they are asked for (a zone's plan): the work costs the window,
    /// not the map. `None`: everywhere.
    ///
    /// # Errors
    /// As [`Coverability::new`].
    pub fn new_within(
        map: &OccupancyGrid,
        robot: DiscRobot,
        start: Option<Point>,
        within: Option<Window>,
    ) -> Result<Self> {
        let counts = map.counts();
        if counts.free == 0 {
            return Err(Error::NoFreeCell {
                width: map.width(),
                height: map.height(),
            });
        }
        let admissible = admissible(map, robot.robot_radius);
        let start = match start {
            None => admissible
                .true_cells()
                .next()
                .ok_or(Error::NoAdmissibleCell {
                    robot_radius: robot.robot_radius,
                })?,
            Some(p) => {
                let frame = map.frame();
                let cell = frame.cell_at(&p).ok_or_else(|| {
                    let (lo, hi) = frame.bounds();
                    // Bounds rounded to the micrometre, so messages read 0.15, not 0.15000000000000002.
                    let um = |v: f64| (v * 1e6).round() / 1e6;
                    Error::StartOutsideMap {
                        x: p.x,
                        y: p.y,
                        xmin: um(lo.x),
                        xmax: um(hi.x),
                        ymin: um(lo.y),
                        ymax: um(hi.y),
                    }
                })?;
                if !admissible[cell] {
                    let reason = match map.cells()[cell] {
                        Occupancy::Occupied => "occupied",
                        Occupancy::Unknown => "unknown",
                        Occupancy::Free => {
                            "free but closer than the robot radius to an obstacle, unknown cell or the map edge"
                        }
                    };
                    return Err(Error::StartNotAdmissible {
                        x: p.x,
                        y: p.y,
                        row: cell.row,
                        col: cell.col,
                        reason,
                    });
                }
                cell
            }
        };
        Ok(Self::from_parts(map, robot, admissible, start, within))
    }

    /// Builds the problem from an admissible start cell (e.g. the `S` of an ASCII map).
    ///
    /// # Errors
    /// As [`Coverability::new`].
    pub fn with_start_cell(map: &OccupancyGrid, robot: DiscRobot, start: Cell) -> Result<Self> {
        Self::with_start_cell_within(map, robot, start, None)
    }

    /// [`Coverability::with_start_cell`], coverable cells only inside
    /// `within` ([`Coverability::new_within`]).
    ///
    /// # Errors
    /// As [`Coverability::new`].
    pub fn with_start_cell_within(
        map: &OccupancyGrid,
        robot: DiscRobot,
        start: Cell,
        within: Option<Window>,
    ) -> Result<Self> {
        let p = map.frame().position(start.row as f64, start.col as f64);
        Self::new_within(map, robot, Some(p), within)
    }

    /// Builds the problem from the first admissible cell (row-major) of the
    /// largest 4-connected admissible region (ties: the region met first),
    /// the start experiments use on maps whose first admissible cell may
    /// lie in a speck. The admissible cells and their regions are found
    /// once: the region is the reachable set.
    ///
    /// # Errors
    /// [`Error::NoFreeCell`], or [`Error::NoAdmissibleCell`] when no cell is
    /// admissible for the robot.
    pub fn in_largest_region(map: &OccupancyGrid, robot: DiscRobot) -> Result<Self> {
        Self::in_largest_region_within(map, robot, None)
    }

    /// [`Coverability::in_largest_region`], coverable cells only inside
    /// `within` ([`Coverability::new_within`]).
    ///
    /// # Errors
    /// As [`Coverability::in_largest_region`].
    pub fn in_largest_region_within(
        map: &OccupancyGrid,
        robot: DiscRobot,
        within: Option<Window>,
    ) -> Result<Self> {
        if map.counts().free == 0 {
            return Err(Error::NoFreeCell {
                width: map.width(),
                height: map.height(),
            });
        }
        let admissible = admissible(map, robot.robot_radius);
        let regions = components4(&admissible);
        let no_cell = Error::NoAdmissibleCell {
            robot_radius: robot.robot_radius,
        };
        let big = regions.largest().ok_or(no_cell)?;
        let start = regions.first_cell(big).unwrap_or_default();
        let reachable = regions.labels.map(|&l| l == big);
        Ok(Self::with_reachable(
            map,
            robot,
            admissible,
            (start, reachable),
            within,
        ))
    }

    fn from_parts(
        map: &OccupancyGrid,
        robot: DiscRobot,
        admissible: Grid<bool>,
        start: Cell,
        within: Option<Window>,
    ) -> Self {
        let reachable = reachable(&admissible, start);
        Self::with_reachable(map, robot, admissible, (start, reachable), within)
    }

    fn with_reachable(
        map: &OccupancyGrid,
        robot: DiscRobot,
        admissible: Grid<bool>,
        (start, reachable): (Cell, Grid<bool>),
        within: Option<Window>,
    ) -> Self {
        let coverable = coverable_cells_within(
            &map.free_mask(),
            &reachable,
            robot.tool_cells(map.resolution()),
            within,
        );
        Self {
            robot,
            admissible,
            start,
            reachable,
            coverable,
        }
    }

    /// Number of coverable cells.
    #[must_use]
    pub fn coverable_count(&self) -> usize {
        self.coverable.count_true()
    }
}

/// Free cells whose centre lies within `tool_cells` (in cells) of a `centres` cell centre.
#[must_use]
pub fn coverable_cells(free: &Grid<bool>, centres: &Grid<bool>, tool_cells: f64) -> Grid<bool> {
    coverable_cells_within(free, centres, tool_cells, None)
}

/// [`coverable_cells`] inside `within` only (none outside; `None`: the
/// whole grid): the transform runs on the window widened by the reach.
#[must_use]
pub fn coverable_cells_within(
    free: &Grid<bool>,
    centres: &Grid<bool>,
    tool_cells: f64,
    within: Option<Window>,
) -> Grid<bool> {
    let (w, h) = (free.width(), free.height());
    let inside = |c: Cell| {
        within.is_none_or(|(r0, r1, c0, c1)| (r0..r1).contains(&c.row) && (c0..c1).contains(&c.col))
    };
    let reach = tool_cells + TOLERANCE_CELLS;
    if reach < 1.0 {
        // Only the centre cells themselves are within reach.
        return Grid::from_fn(w, h, |c| free[c] && centres[c] && inside(c));
    }
    if reach.is_nan() {
        return Grid::new(w, h, false);
    }
    let k = reach.ceil() as usize;
    // Only the centres' bounding box widened by the reach can hold a cell
    // within reach (a zone costs the zone), and only `within` is asked.
    let Some(reached) = centres.bounding_box(|&b| b).map(|b| free.widen(b, k)) else {
        return Grid::new(w, h, false);
    };
    let meet = |a: Window, b: Window| (a.0.max(b.0), a.1.min(b.1), a.2.max(b.2), a.3.min(b.3));
    let window = within.map_or(reached, |within| meet(reached, within));
    if window.0 >= window.1 || window.2 >= window.3 {
        return Grid::new(w, h, false);
    }
    // An integer d² is at most reach² when at most its floor.
    let limit = (reach * reach).floor() as u64;
    if window == (0, h, 0, w) {
        let near = center_within_sq(centres, limit);
        return free.zip_map(&near, |&f, &n| f && n);
    }
    // The centres that can reach the window: those of the window widened
    // (all of them when it is the whole of `reached`).
    let around = meet(free.widen(window, k), reached);
    let near = center_within_sq(&centres.crop(around), limit);
    let near = if around == window {
        near
    } else {
        let (r0, c0) = (window.0 - around.0, window.2 - around.2);
        near.crop((r0, r0 + window.1 - window.0, c0, c0 + window.3 - window.2))
    };
    let mut out = Grid::new(w, h, false);
    out.paste(
        Cell::new(window.0, window.2),
        &free.crop(window).zip_map(&near, |&f, &n| f && n),
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::parse_ascii;

    fn map(text: &str, res: f64) -> OccupancyGrid {
        let (m, _) = parse_ascii(text).unwrap();
        OccupancyGrid::new(m.cells().clone(), res, Point::origin())
    }

    #[test]
    fn default_start_is_first_admissible_cell() {
        let m = map("###\n#..\n...", 1.0);
        let p = Coverability::new(&m, DiscRobot::cell_sized(1.0), None).unwrap();
        assert_eq!(p.start, Cell::new(1, 1));
        assert_eq!(p.coverable_count(), 5);
    }

    #[test]
    fn largest_region_start_is_the_big_regions_first_cell() {
        // A speck of two cells first, then a region of six: the start is
        // the big region's first cell, and its region alone is reachable.
        let m = map("..#....\n###.##.\n###....", 1.0);
        let r = DiscRobot::cell_sized(1.0);
        let p = Coverability::in_largest_region(&m, r).unwrap();
        assert_eq!(p.start, Cell::new(0, 3));
        assert_eq!(p.reachable.count_true(), 10);
        let apart = Coverability::with_start_cell(&m, r, Cell::new(0, 3)).unwrap();
        assert_eq!(
            (&p.reachable, &p.coverable),
            (&apart.reachable, &apart.coverable)
        );
        let e = Coverability::in_largest_region(&map("##\n##", 1.0), r).unwrap_err();
        assert!(e.to_string().contains("no free cell"), "{e}");
        let big = DiscRobot::new(5.0, 0.5).unwrap();
        let e = Coverability::in_largest_region(&m, big).unwrap_err();
        assert!(e.to_string().contains("no admissible cell"), "{e}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        /// The same problem as from the largest region's first cell found
        /// apart (its admissible cells and regions computed again).
        #[test]
        fn largest_region_matches_the_start_found_apart(seed in 0u64..1000, radius in 0usize..3) {
            let m = crate::random::random_density(23, 17, 0.3, seed);
            let robot = DiscRobot::new(radius as f64 * 0.5, 1.0).unwrap();
            let regions = components4(&admissible(&m, robot.robot_radius));
            match regions.largest() {
                Some(big) => {
                    let first = regions.labels.cells().find(|&c| regions.labels[c] == big).unwrap();
                    let apart = Coverability::with_start_cell(&m, robot, first).unwrap();
                    let once = Coverability::in_largest_region(&m, robot).unwrap();
                    proptest::prop_assert_eq!(
                        (once.start, &once.admissible, &once.reachable, &once.coverable),
                        (apart.start, &apart.admissible, &apart.reachable, &apart.coverable)
                    );
                }
                None => proptest::prop_assert!(Coverability::in_largest_region(&m, robot).is_err()),
            }
        }

        /// The free cells within reach of a few centres, whatever part of
        /// the grid they hold, are those a check of every pair finds.
        #[test]
        fn coverable_cells_are_those_within_reach(seed in 0u64..1000, tool in 0.0f64..4.0, picks in proptest::collection::vec((0usize..17, 0usize..23), 0..4)) {
            let free = crate::random::random_density(23, 17, 0.3, seed).free_mask();
            let centres = Grid::from_fn(23, 17, |c: Cell| picks.contains(&(c.row, c.col)));
            let reach = tool + TOLERANCE_CELLS;
            let brute = Grid::from_fn(23, 17, |c: Cell| {
                free[c] && picks.iter().any(|&(r, q)| {
                    let (dr, dc) = (r as f64 - c.row as f64, q as f64 - c.col as f64);
                    dr * dr + dc * dc <= reach * reach
                })
            });
            proptest::prop_assert_eq!(coverable_cells(&free, &centres, tool), brute.clone());
            // Inside a window only: the same cells there, none outside.
            let (r0, c0) = (seed as usize % 17, seed as usize / 17 % 23);
            let within = (r0, (r0 + 6).min(17), c0, (c0 + 9).min(23));
            let inside = Grid::from_fn(23, 17, |c: Cell| {
                brute[c] && (within.0..within.1).contains(&c.row) && (within.2..within.3).contains(&c.col)
            });
            proptest::prop_assert_eq!(coverable_cells_within(&free, &centres, tool, Some(within)), inside);
        }
    }

    #[test]
    fn start_errors_say_why() {
        let m = map("#..\n...", 1.0);
        let r = DiscRobot::cell_sized(1.0);
        let e = Coverability::new(&m, r, Some(Point::new(0.5, 1.5))).unwrap_err();
        assert!(e.to_string().contains("occupied"), "{e}");
        let e = Coverability::new(&m, r, Some(Point::new(7.0, 1.5))).unwrap_err();
        assert!(e.to_string().contains("outside the map"), "{e}");
        let e = Coverability::new(&map("##\n##", 1.0), r, None).unwrap_err();
        assert!(e.to_string().contains("no free cell"), "{e}");
        let big = DiscRobot::new(5.0, 0.5).unwrap();
        let e = Coverability::new(&m, big, None).unwrap_err();
        assert!(e.to_string().contains("no admissible cell"), "{e}");
        assert!(DiscRobot::new(f64::NAN, 0.5).is_err());
        assert!(DiscRobot::new(-1.0, 0.5).is_err());
        assert!(DiscRobot::new(0.0, 0.0).is_err());
    }

    #[test]
    fn tool_reaches_the_wall_strip() {
        // 0.05 m cells, robot and tool 0.15 m: admissible cells are >= 3.5 cells
        // from the walls; the cells next to the wall are exactly 0.15 m from the
        // nearest admissible centre, so they are coverable. A round tool cannot
        // reach the five cells in each square corner.
        let mut rows = vec!["#".repeat(12)];
        for _ in 0..10 {
            rows.push(format!("#{}#", ".".repeat(10)));
        }
        rows.push("#".repeat(12));
        let m = map(&rows.join("\n"), 0.05);
        let r = DiscRobot::new(0.15, 0.15).unwrap();
        let p = Coverability::new(&m, r, None).unwrap();
        assert_eq!(p.reachable.count_true(), 4 * 4);
        assert_eq!(p.coverable_count(), 100 - 4 * 5);
        assert_eq!(p.start, Cell::new(4, 4));
    }
}
