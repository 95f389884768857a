//! Coverage targets on seeded random maps, for every complete planner:
//! a zone (a rectangle, sometimes with a hole), a keep-out rectangle and a
//! virtual wall, and a resume from half-way. The checks use their own
//! geometry (axis-aligned rectangles and walls, cell squares by interval
//! overlap), not the crate's rasteriser:
//!
//! - no path sample lies in a cell the keep-out area or the wall blocks,
//!   and no segment passes through one (exact traversal);
//! - every coverable cell whose centre is in the zone (not inside the
//!   hole) is covered, coverage reported 1.0;
//! - the done prefix and the resumed plan together cover every cell the
//!   uninterrupted plan had to cover.

use geo::{LineString, Polygon, polygon};
use oxcover::grid::footprint::covered_cells;
use oxcover::grid::traverse::segment_clear;
use oxcover::grid::{Cell, DiscRobot, Grid, Occupancy, OccupancyGrid, Point};
use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::{CoverageProblem, Start};
use oxcover::targets::{Areas, Targets, resume_start};
use oxcover_grid::random::{blobs, rectangles};
use proptest::prelude::*;

const ORIGIN: (f64, f64) = (-3.0, 1.5);

fn random_map(kind: u8, w: usize, h: usize, seed: u64, res: f64) -> OccupancyGrid {
    let m = match kind {
        0 => rectangles(w, h, w * h / 300 + 1, 10, seed),
        _ => blobs(w, h, w * h / 400 + 1, 5, seed),
    };
    OccupancyGrid::new(m.cells().clone(), res, Point::new(ORIGIN.0, ORIGIN.1))
}

/// An axis-aligned rectangle in metres: `[x0, x1] x [y0, y1]`.
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Rect {
    /// The rectangle at fractions `f` (each 0..1) of the map's extent.
    fn of(map: &OccupancyGrid, f: [f64; 4]) -> Self {
        let (w, h) = (
            map.width() as f64 * map.resolution(),
            map.height() as f64 * map.resolution(),
        );
        let (a, b) = (f[0].min(f[1]), f[0].max(f[1]));
        let (c, d) = (f[2].min(f[3]), f[2].max(f[3]));
        Rect {
            x0: ORIGIN.0 + a * w,
            x1: ORIGIN.0 + b * w,
            y0: ORIGIN.1 + c * h,
            y1: ORIGIN.1 + d * h,
        }
    }

    /// A rectangle strictly inside this one, at fractions `f` of its sides
    /// (kept between 0.1 and 0.9).
    fn inner(&self, f: [f64; 4]) -> Self {
        let at = |lo: f64, hi: f64, t: f64| lo + (0.1 + 0.8 * t) * (hi - lo);
        let (a, b) = (f[0].min(f[1]), f[0].max(f[1]));
        let (c, d) = (f[2].min(f[3]), f[2].max(f[3]));
        Rect {
            x0: at(self.x0, self.x1, a),
            x1: at(self.x0, self.x1, b),
            y0: at(self.y0, self.y1, c),
            y1: at(self.y0, self.y1, d),
        }
    }

    fn ring(&self) -> LineString<f64> {
        polygon![
            (x: self.x0, y: self.y0), (x: self.x1, y: self.y0),
            (x: self.x1, y: self.y1), (x: self.x0, y: self.y1),
        ]
        .exterior()
        .clone()
    }

    /// Whether the closed rectangle meets the closed square of `cell`.
    fn meets_square(&self, map: &OccupancyGrid, cell: Cell) -> bool {
        let res = map.resolution();
        let (cx0, cy0) = (
            ORIGIN.0 + cell.col as f64 * res,
            ORIGIN.1 + (map.height() - 1 - cell.row) as f64 * res,
        );
        cx0 <= self.x1 && cx0 + res >= self.x0 && cy0 <= self.y1 && cy0 + res >= self.y0
    }

    fn holds(&self, p: Point) -> bool {
        (self.x0..=self.x1).contains(&p.x) && (self.y0..=self.y1).contains(&p.y)
    }

    fn holds_strictly(&self, p: Point) -> bool {
        p.x > self.x0 && p.x < self.x1 && p.y > self.y0 && p.y < self.y1
    }
}

/// The targets: a zone (with a hole when `hole`), a keep-out rectangle and
/// a vertical virtual wall (the rectangle `wall` squashed to its left
/// edge).
struct Case {
    zone: Rect,
    hole: Option<Rect>,
    keep_out: Rect,
    wall: Rect,
}

impl Case {
    fn targets(&self) -> Targets {
        let zone = Polygon::new(self.zone.ring(), self.hole.iter().map(Rect::ring).collect());
        let wall = LineString::from(vec![
            (self.wall.x0, self.wall.y0),
            (self.wall.x0, self.wall.y1),
        ]);
        Targets {
            zones: Some(Areas {
                polygons: vec![zone],
                lines: Vec::new(),
            }),
            keep_out: Some(Areas {
                polygons: vec![Polygon::new(self.keep_out.ring(), Vec::new())],
                lines: vec![wall],
            }),
            ..Targets::default()
        }
    }

    /// The cells the keep-out rectangle and the wall block, worked out here.
    fn blocked(&self, map: &OccupancyGrid) -> Grid<bool> {
        let wall = Rect {
            x1: self.wall.x0,
            ..self.wall
        };
        Grid::from_fn(map.width(), map.height(), |c| {
            self.keep_out.meets_square(map, c) || wall.meets_square(map, c)
        })
    }

    /// Whether the cell centre `p` lies in the zone (holes excluded).
    fn in_zone(&self, p: Point) -> bool {
        self.zone.holds(p) && !self.hole.is_some_and(|h| h.holds_strictly(p))
    }
}

fn grid_point(map: &OccupancyGrid, p: &Point) -> Point {
    let (row, col) = map.frame().fractional_cell(p);
    Point::new(col + 0.5, row + 0.5)
}

fn check(
    map: &OccupancyGrid,
    robot: DiscRobot,
    case: &Case,
    name: &str,
) -> Result<(), TestCaseError> {
    let targets = case.targets();
    let req = PlanRequest::new(name, map.resolution())
        .map_err(|e| TestCaseError::fail(e.to_string()))?
        .robot(robot)
        .targets(targets.clone());
    let out = match plan(map, &req) {
        Ok(o) => o,
        // No room for the robot, no required cell left, a planner's size
        // limit: clear refusals, nothing to check.
        Err(oxcover::Error::Map(_) | oxcover::Error::Target { .. }) => return Ok(()),
        Err(oxcover::Error::Planner(
            oxcover_planners::Error::TooLarge { .. } | oxcover_planners::Error::TooWide { .. },
        )) => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(format!("{name}: {e}"))),
    };
    let blocked = case.blocked(map);
    let clear = blocked.map(|&b| !b);
    let frame = map.frame();
    oxcover::grid::footprint::for_each_sample(&out.points, map.resolution() / 4.0, |p| {
        let c = frame.cell_at(p).expect("a sample off the map");
        assert!(!blocked[c], "{name}: a sample in keep-out cell {c:?}");
    });
    for s in out.points.windows(2) {
        let (a, b) = (grid_point(map, &s[0]), grid_point(map, &s[1]));
        prop_assert!(
            segment_clear(&clear, a, b),
            "{}: a segment crosses a keep-out cell",
            name
        );
    }
    let m = &out.evaluation.metrics;
    prop_assert_eq!(m.collisions, 0, "{}", name);
    prop_assert_eq!(
        m.coverage,
        1.0,
        "{}: {}/{}",
        name,
        m.covered_cells,
        m.coverable_cells
    );
    // The required cells, worked out here: coverable on the map with the
    // blocked cells made occupied, from the plan's start, centre in zone.
    let mut work = map.clone();
    for c in blocked.true_cells() {
        work.cells_mut()[c] = Occupancy::Occupied;
    }
    let start = out.points[0];
    let problem = CoverageProblem::new(&work, robot, Start::At(start))
        .map_err(|e| TestCaseError::fail(e.to_string()))?;
    let cells = problem.cells();
    let required: Vec<Cell> = cells
        .coverable
        .true_cells()
        .filter(|&c| case.in_zone(frame.cell_center(c)))
        .collect();
    prop_assert_eq!(
        required.len(),
        m.coverable_cells,
        "{}: required cells",
        name
    );
    let tool = robot.tool_radius;
    let covered = covered_cells(frame, &out.points, tool);
    prop_assert!(
        required.iter().all(|&c| covered[c]),
        "{}: a required cell missed",
        name
    );
    // Resume from half-way: the done part and the rest cover it all.
    let half = out.points.len().div_ceil(2);
    let done = out.points[..half].to_vec();
    let (resume_at, _) = resume_start(&work, robot.robot_radius, &done)
        .map_err(|e| TestCaseError::fail(e.to_string()))?;
    let mut rest_targets = targets;
    rest_targets.done = Some(done.clone());
    let rest = match plan(
        map,
        &req.clone()
            .targets(rest_targets)
            .start(Start::At(resume_at)),
    ) {
        Ok(r) => r.points,
        // The first half covered everything: nothing left.
        Err(oxcover::Error::Target { .. }) => Vec::new(),
        Err(e) => return Err(TestCaseError::fail(format!("{name} resumed: {e}"))),
    };
    let before = covered_cells(frame, &done, tool);
    let after = covered_cells(frame, &rest, tool);
    prop_assert!(
        required.iter().all(|&c| before[c] || after[c]),
        "{}: done + resumed plan miss a required cell",
        name
    );
    Ok(())
}

fn fractions() -> impl Strategy<Value = [f64; 4]> {
    [0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn complete_planners_cover_the_target_and_never_enter_keep_out(
        kind in 0u8..2, w in 16usize..70, h in 16usize..70, seed in any::<u64>(),
        res in prop::sample::select(vec![0.05, 1.0]),
        robot_cells in 0.0f64..2.0, tool_cells in 0.5f64..2.5,
        zone in fractions(), hole in prop::option::of(fractions()),
        keep_out in fractions(), wall in fractions(),
    ) {
        let map = random_map(kind, w, h, seed, res);
        let robot = DiscRobot::new(robot_cells * res, tool_cells * res).unwrap();
        let case = Case {
            zone: Rect::of(&map, zone),
            hole: hole.map(|f| Rect::of(&map, zone).inner(f)),
            keep_out: Rect::of(&map, [keep_out[0], keep_out[0] + 0.2 * keep_out[1], keep_out[2], keep_out[2] + 0.2 * keep_out[3]]),
            wall: Rect::of(&map, wall),
        };
        for name in oxcover::pipeline::planners().iter().filter(|p| p.complete).map(|p| p.name) {
            check(&map, robot, &case, name)?;
        }
    }
}
