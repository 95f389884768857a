//! Room by room: the room units (the medial-axis rooms cut into connected
//! drivable parts, small ones joined to a neighbour), visited in the order
//! of least transit, each finished before the robot leaves it, and the
//! whole path tightened at the end with each room's waypoints kept in
//! their room.

use std::time::Instant;

use oxcover_decomp::{RoomParams, Rooms, voronoi};
use oxcover_distance::Wavefront;
use oxcover_grid::footprint::covered_cells_of;
use oxcover_grid::{Cell, Grid, OccupancyGrid, Point, Window};
use oxcover_planners::{
    BoundaryRoute, CoverageProblem, RoomUnits, room_order, unit_claims, unit_exits_with,
};

use super::region::{
    KnownCoverage, finish, pass_flags, pass_length, plan_region, start_prefix, tighten_plan,
};
use super::request::{PlanOutcome, PlanRequest, RoomStretch};
use crate::error::Result;

/// Plannable area (m²) below which a room unit joins a neighbour: a
/// closet or a nook cut off by furniture is covered with the room beside
/// it (planned alone, its own loop, entry and exit cost more than it
/// saves: measured on the ipa floor plans, `docs/efficiency.md`).
pub const MIN_UNIT_M2: f64 = 6.0;

/// The room units of `problem` on `map`: the medial-axis segmentation of
/// the free cells with indoor defaults ([`oxcover_decomp::voronoi`],
/// [`RoomParams::indoor`]: rooms end at doors up to 1.6 m wide), split into
/// connected plannable parts, parts smaller than [`MIN_UNIT_M2`] of
/// plannable area (and at least four coverage cells) merged into a
/// neighbour.
///
/// Not the morphological segmentation: it also cuts open halls into pieces
/// of at most 47 m², and planning such pieces one by one took longer than
/// planning the hall at once on most ROS maps (`docs/efficiency.md`).
#[must_use]
pub fn room_units(map: &OccupancyGrid, problem: &CoverageProblem) -> RoomUnits {
    units_of(problem, &room_labels(map))
}

/// The rooms [`super::room_units`] splits: the medial-axis segmentation of `map`'s
/// free cells with indoor defaults.
pub(super) fn room_labels(map: &OccupancyGrid) -> Rooms {
    voronoi(&map.free_mask(), &RoomParams::indoor(map.resolution()))
}

/// How far round a target bounded by zones or a spot its rooms are
/// segmented (m): a room's doors and walls within this of the target
/// shape its units as on the whole map. More than the widest door the
/// indoor rooms cut at (1.6 m), so a door at the target's edge is seen
/// whole. Measured on the central 10 % zone of the 30 shared maps: every
/// plan the same by waypoint hash as with the whole map's rooms for
/// margins down to 1.5 m (1 m changes one).
pub const LOCAL_ROOMS_MARGIN_M: f64 = 2.0;

/// The rooms a plan is cut into: the whole map's ([`room_labels`]), or,
/// for a target the zones or a spot bound to a window of at most half the
/// map ([`crate::targets::Targets::extent`]), those of the window
/// widened by [`LOCAL_ROOMS_MARGIN_M`] and the tool radius, segmented there
/// alone (0 beyond it): a small zone costs its neighbourhood, not the map.
pub(super) struct PlanRooms<'m> {
    pub(super) rooms: Rooms,
    /// Where `rooms` are a window's: the map and the window.
    local: Option<(&'m OccupancyGrid, Window)>,
}

impl<'m> PlanRooms<'m> {
    /// The rooms of `map` (keep-out applied) for `request`.
    pub(super) fn new(map: &'m OccupancyGrid, request: &PlanRequest) -> Self {
        let res = map.resolution();
        let margin = ((LOCAL_ROOMS_MARGIN_M + request.robot.tool_radius) / res).ceil();
        let (w, h) = (map.width(), map.height());
        let window = request.targets.extent(map).and_then(|extent| {
            // (A huge margin takes the whole map.)
            let k = if margin.is_finite() {
                margin as usize
            } else {
                usize::MAX
            };
            let win = map.cells().widen(extent, k);
            (2 * (win.1 - win.0) * (win.3 - win.2) <= w * h).then_some(win)
        });
        match window {
            Some(win) => {
                let free = map.cells().crop(win).map(|o| o.is_free());
                let part = voronoi(&free, &RoomParams::indoor(res));
                let mut labels = Grid::new(w, h, 0);
                labels.paste(Cell::new(win.0, win.2), &part.labels);
                let shift = |c: Cell| Cell::new(c.row + win.0, c.col + win.2);
                let doors = part
                    .doors
                    .into_iter()
                    .map(|d| oxcover_decomp::Door {
                        rooms: d.rooms,
                        cells: d.cells.into_iter().map(shift).collect(),
                        centre: shift(d.centre),
                    })
                    .collect();
                Self {
                    rooms: Rooms {
                        labels,
                        doors,
                        ..part
                    },
                    local: Some((map, win)),
                }
            }
            None => Self {
                rooms: room_labels(map),
                local: None,
            },
        }
    }

    /// The window the rooms were segmented on, if not the whole map.
    #[cfg(test)]
    pub(super) fn local(&self) -> Option<Window> {
        self.local.map(|(_, win)| win)
    }

    /// The whole map's rooms (segmented now where these are a window's).
    pub(super) fn whole(&self) -> std::borrow::Cow<'_, Rooms> {
        match self.local {
            Some((map, _)) => std::borrow::Cow::Owned(room_labels(map)),
            None => std::borrow::Cow::Borrowed(&self.rooms),
        }
    }
}

/// Whether the `plannable` cells carry more than one room label.
pub(super) fn in_several_rooms(plannable: &Grid<bool>, labels: &Grid<u32>) -> bool {
    let mut seen = None;
    plannable
        .as_slice()
        .iter()
        .zip(labels.as_slice())
        .filter(|&(&p, _)| p)
        .any(|(_, &l)| *seen.get_or_insert(l) != l)
}

/// The units of `rooms` for `problem` (see [`super::room_units`]).
pub(super) fn units_of(problem: &CoverageProblem, rooms: &Rooms) -> RoomUnits {
    RoomUnits::new(problem.plannable(), &rooms.labels, min_unit_cells(problem))
}

/// The fewest plannable cells a unit keeps alone: [`MIN_UNIT_M2`], and at
/// least four coverage cells.
pub(super) fn min_unit_cells(problem: &CoverageProblem) -> usize {
    let block = problem.block();
    let res = problem.frame().resolution();
    ((MIN_UNIT_M2 / (res * res)) as usize).max(4 * block * block)
}

/// The wavefronts a room-by-room plan's searches reuse
/// ([`CoverageProblem::transit_wavefront`]): one for the exits and the
/// transits between units, and one for the way from a start outside every
/// unit to the first. Each costs a pass over the map to build: a target's
/// are built while the rooms are segmented.
pub(super) struct TransitWaves {
    shared: Wavefront,
    first: Option<Wavefront>,
}

impl TransitWaves {
    /// Those of a target of `problem` whose units lie in `region`: the
    /// second only where the start lies outside `region` (so outside
    /// every unit).
    pub(super) fn for_target(problem: &CoverageProblem, region: &Grid<bool>) -> Self {
        let outside = !region.get(problem.start_cell()).copied().unwrap_or(false);
        let (shared, first) = rayon::join(
            || problem.transit_wavefront(),
            || outside.then(|| problem.transit_wavefront()),
        );
        Self { shared, first }
    }
}

/// Plans unit by unit in `order` (default: [`oxcover_planners::room_order`]),
/// with `waves` if built ahead ([`TransitWaves`]).
pub(super) fn plan_rooms(
    problem: &CoverageProblem,
    units: &RoomUnits,
    order: Option<Vec<u32>>,
    request: &PlanRequest,
    t0: Instant,
    waves: Option<TransitWaves>,
) -> Result<PlanOutcome> {
    let (order, (mut wave, first_wave)) = rayon::join(
        || order.unwrap_or_else(|| room_order(problem, units)),
        || match waves {
            Some(w) => (w.shared, w.first),
            None => (problem.transit_wavefront(), None),
        },
    );
    let mut here = problem.start_cell();
    // The way from the start to the first unit, when it lies outside it.
    let first = order.first().copied().filter(|&u| units.labels[here] != u);
    // (Side by side: none needs another. The exits' searches reuse `wave`,
    // the first transit has one of its own.)
    let ((exits, claims), mut first_transit) = rayon::join(
        || {
            rayon::join(
                || unit_exits_with(&mut wave, units, &order),
                || unit_claims(problem, units),
            )
        },
        || {
            first.map(|u| {
                let mut own = first_wave.unwrap_or_else(|| problem.transit_wavefront());
                problem.transit_reusing(&mut own, here, |c| units.labels[c] == u)
            })
        },
    );
    let bounds = units.bounds();
    let plan_cells = problem.plannable().count_true();
    let mut points: Vec<Point> = Vec::new();
    let mut cells: Vec<Cell> = Vec::new();
    let mut raws = Vec::new();
    let mut boundary: Option<BoundaryRoute> = None;
    let mut in_pass: Vec<bool> = Vec::new();
    let mut stretches = Vec::with_capacity(order.len());
    for (i, &u) in order.iter().enumerate() {
        // The start may lie outside every unit (a coverage target).
        let transit = i > 0 || units.labels[here] != u;
        let b = bounds[u as usize - 1];
        let (entry, prefix, ahead) = if !transit {
            (here, start_prefix(problem), None)
        } else {
            // The unit's problem from its first cell while the way into it
            // is searched, moved to where that way ends below.
            let (t, ahead) = rayon::join(
                || match first_transit.take() {
                    Some(t) => t,
                    None => problem.transit_reusing(&mut wave, here, |c| units.labels[c] == u),
                },
                || {
                    units
                        .first_cell(u, b)
                        .and_then(|c| units.restricted(problem, u, b, c, &claims).ok())
                },
            );
            let t = t?;
            let entry = t.cells.last().copied().unwrap_or(here);
            if i == 0 {
                cells.push(here);
            }
            cells.extend(t.cells.iter().skip(1).copied());
            let mut prefix = t.points;
            if i == 0 {
                prefix.splice(0..0, start_prefix(problem));
            }
            prefix.pop();
            (entry, prefix, ahead)
        };
        let prefix_len = prefix.len();
        // (From any cell connected to the entry, the same problem.)
        let moved = ahead.and_then(|p| {
            let local = p.from_map_cell(entry)?;
            p.with_start_cell(local).ok()
        });
        let sub = match moved {
            Some(p) => p,
            None => units.restricted(problem, u, b, entry, &claims)?,
        };
        let exit = exits[i].and_then(|c| sub.from_map_cell(c));
        let mut region = plan_region(&sub, request, prefix, exit, Some(plan_cells))?;
        for c in &mut region.cells {
            *c = sub.to_map_cell(*c);
        }
        region.end = sub.to_map_cell(region.end);
        for (p, pass) in region.points.iter().zip(pass_flags(&region)) {
            if points.last() != Some(p) {
                points.push(*p);
                in_pass.push(pass);
            }
        }
        // The unit's own work: the last points, after its transit.
        let work = region.points.len() - prefix_len.min(region.points.len());
        stretches.push(RoomStretch {
            unit: u,
            points: points.len().saturating_sub(work)..points.len(),
        });
        cells.extend(region.cells.iter().skip(usize::from(transit)).copied());
        raws.push(region.raw);
        if let Some(b) = region.boundary {
            let total = boundary.get_or_insert(BoundaryRoute {
                cells: Vec::new(),
                points: Vec::new(),
                pending: 0,
                anchors: 0,
            });
            total.pending += b.pending;
            total.anchors += b.anchors;
            total.cells.extend(b.cells);
            total.points.extend(b.points);
        }
        here = region.end;
    }
    // The cells the units' own paths cover (before their boundary
    // passes), found while the whole path is tightened (beside its later
    // passes: the first has both cores).
    // (And the copy of the cells the evaluation keeps.)
    let ((points, stretches, covered, in_pass), (raw_covered, cells_copy)) =
        tighten_plan(problem, Some(units), points, (stretches, in_pass), || {
            let pieces: Vec<&[Point]> = raws.iter().map(Vec::as_slice).collect();
            let tool = problem.robot().tool_radius;
            (
                covered_cells_of(problem.frame(), &pieces, tool),
                problem.cells().clone(),
            )
        });
    let boundary_length_m = pass_length(&points, &in_pass);
    let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    // (Each room's own coverage is on its room's grid: the map's is found
    // afresh, above.)
    let known = KnownCoverage {
        raws: Some(raw_covered),
        path: covered,
        cells: Some(cells_copy),
    };
    finish(
        problem,
        request,
        points,
        cells,
        (&raws, known),
        boundary,
        boundary_length_m,
        stretches,
        plan_ms,
    )
}
