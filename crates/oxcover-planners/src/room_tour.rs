//! Room by room: the parts of rooms a robot covers one at a time, and the
//! order it visits them in.
//!
//! A room of a segmentation ([`oxcover_decomp::rooms`]) may fall apart for a
//! robot (furniture or a narrow spot closes a passage in its C-space), so
//! the places visited are **units**: 4-connected plannable cells of one
//! room. Units smaller than a few tool footprints (slivers where a room
//! boundary crosses the C-space) join the neighbouring unit they share the
//! longest border with, so the tour does not stop for them.
//!
//! [`room_order`] orders the units from the start's unit by the time the
//! robot needs between them ([`crate::TimeModel`]): geodesic distances over
//! the coverage grid between each unit's anchor (its cell nearest to its
//! centroid), then an open tour ([`crate::tour::open_tour`]: exact up to a
//! dozen units, nearest neighbour with 2-opt and Or-opt beyond).

use rayon::prelude::*;

use oxcover_decomp::merge_small_regions;
use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::grid::nearest_first;
use oxcover_grid::{Cell, Components, Dir4, Grid, Window, components4_by_class};

use crate::error::{Error, Result};
use crate::problem::CoverageProblem;
use crate::tour::open_tour;

/// Units: connected plannable parts of rooms.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomUnits {
    /// Unit of each cell, 1-based; 0 where the cell is not plannable.
    pub labels: Grid<u32>,
    /// Cells per unit (`sizes[u - 1]` for unit `u`).
    pub sizes: Vec<usize>,
}

impl RoomUnits {
    /// The units of `plannable` under the room labels `rooms` (0 = no
    /// room: such cells form units of their own), units below `min_cells`
    /// merged into a neighbour. Units are numbered in row-major order of
    /// their first cell.
    ///
    /// # Panics
    /// If `rooms` is not the size of `plannable` (the cells are read by
    /// index: labels of another grid would be read at the wrong cells).
    #[must_use]
    pub fn new(plannable: &Grid<bool>, rooms: &Grid<u32>, min_cells: usize) -> Self {
        let (w, h) = (plannable.width(), plannable.height());
        assert_eq!(
            (rooms.width(), rooms.height()),
            (w, h),
            "room labels must cover the plannable grid cell for cell"
        );
        // Found on the plannable cells' bounding box only (a coverage
        // target's units may hold a small part of the map): the same units
        // in the same order.
        let window = plannable.bounding_box(|&b| b);
        match window {
            Some(window) if window != (0, h, 0, w) => {
                let part = Self::new(&plannable.crop(window), &rooms.crop(window), min_cells);
                let mut labels = Grid::new(w, h, 0);
                labels.paste(Cell::new(window.0, window.2), &part.labels);
                Self {
                    labels,
                    sizes: part.sizes,
                }
            }
            _ => {
                // Connected plannable parts of one room each.
                let Components { labels, sizes } = components4_by_class(plannable, rooms);
                let mut units = Self { labels, sizes };
                units.merge_small(min_cells);
                units
            }
        }
    }

    /// Number of units.
    #[must_use]
    pub fn count(&self) -> usize {
        self.sizes.len()
    }

    /// The cells of unit `u`.
    #[must_use]
    pub fn mask(&self, u: u32) -> Grid<bool> {
        self.labels.map(|&l| l == u)
    }

    /// The unit of `cell` (0 when it is in none).
    #[must_use]
    pub fn unit_of(&self, cell: Cell) -> u32 {
        self.labels.get(cell).copied().unwrap_or(0)
    }

    fn merge_small(&mut self, min_cells: usize) {
        merge_small_regions(&mut self.labels, min_cells as f64);
        // Renumber compactly in row-major order of first cells.
        let n = self.sizes.len();
        let mut fresh = vec![0u32; n + 1];
        let mut sizes = Vec::new();
        for c in self.labels.cells() {
            let l = self.labels[c] as usize;
            if l == 0 {
                continue;
            }
            if fresh[l] == 0 {
                sizes.push(0);
                fresh[l] = sizes.len() as u32;
            }
            let id = fresh[l];
            sizes[id as usize - 1] += 1;
            self.labels[c] = id;
        }
        self.sizes = sizes;
    }

    /// Each unit's cells' bounding box: first and last row, first and last
    /// column (`bounds()[u - 1]` for unit `u`).
    #[must_use]
    pub fn bounds(&self) -> Vec<(usize, usize, usize, usize)> {
        let mut b = vec![(usize::MAX, 0, usize::MAX, 0); self.count()];
        // Read within the units' bounding box only (a coverage target's
        // units may hold a small part of the map).
        let Some((r0, r1, c0, c1)) = self.labels.bounding_box(|&l| l != 0) else {
            return b;
        };
        let w = self.labels.width();
        for r in r0..r1 {
            for (c, &l) in (c0..c1).zip(&self.labels.as_slice()[r * w + c0..r * w + c1]) {
                if let Some(x) = (l as usize).checked_sub(1).and_then(|i| b.get_mut(i)) {
                    *x = (x.0.min(r), x.1.max(r), x.2.min(c), x.3.max(c));
                }
            }
        }
        b
    }

    /// [`CoverageProblem::restricted_claiming`] of `problem` to unit `u`,
    /// the claim the cells `claims` ([`unit_claims`]) gives to `u` or to
    /// every unit, reading only the unit's cells' bounding box `bounds`
    /// (as [`RoomUnits::bounds`] gives it): the same problem, at the
    /// unit's cost rather than the map's.
    ///
    /// # Errors
    /// As [`CoverageProblem::restricted_claiming`].
    pub fn restricted(
        &self,
        problem: &CoverageProblem,
        u: u32,
        bounds: (usize, usize, usize, usize),
        start: Cell,
        claims: &Grid<u32>,
    ) -> Result<CoverageProblem> {
        let plannable = problem.plannable();
        let size = (plannable.width(), plannable.height());
        for (name, w, h) in [
            ("region mask", self.labels.width(), self.labels.height()),
            ("claimed cells", claims.width(), claims.height()),
        ] {
            if (w, h) != size {
                return Err(Error::BadParameter {
                    name,
                    value: format!("{w}x{h}"),
                    expected: "the map's size",
                });
            }
        }
        if !(plannable.is_set(start) && self.unit_of(start) == u) {
            return Err(Error::BadParameter {
                name: "region start",
                value: format!("{start:?}"),
                expected: "a plannable cell inside the region",
            });
        }
        let (r0, r1, c0, c1) = bounds;
        let window = (
            r0.min(start.row),
            r1.max(start.row),
            c0.min(start.col),
            c1.max(start.col),
        );
        Ok(problem.cropped(
            window,
            start,
            |c| self.labels[c] == u,
            |c| claims[c] == u || claims[c] == ANY_UNIT,
        ))
    }

    /// The first cell of unit `u` in row-major order within its cells'
    /// bounding box `bounds` (as [`RoomUnits::bounds`] gives it), if it has
    /// one.
    #[must_use]
    pub fn first_cell(
        &self,
        u: u32,
        (r0, r1, c0, c1): (usize, usize, usize, usize),
    ) -> Option<Cell> {
        (r0..=r1).find_map(|r| {
            (c0..=c1)
                .map(|c| Cell::new(r, c))
                .find(|&c| self.labels.get(c) == Some(&u))
        })
    }

    /// Each unit's cells in row-major order (`cells_by_unit()[u - 1]` for
    /// unit `u`), read row by row within the units' bounding box.
    #[must_use]
    pub fn cells_by_unit(&self) -> Vec<Vec<Cell>> {
        let mut cells: Vec<Vec<Cell>> = self.sizes.iter().map(|&n| Vec::with_capacity(n)).collect();
        let w = self.labels.width();
        let Some((r0, r1, c0, c1)) = self.labels.bounding_box(|&l| l != 0) else {
            return cells;
        };
        for r in r0..r1 {
            let row = &self.labels.as_slice()[r * w + c0..r * w + c1];
            for (c, &l) in row.iter().enumerate() {
                if let Some(v) = (l as usize).checked_sub(1).and_then(|i| cells.get_mut(i)) {
                    v.push(Cell::new(r, c0 + c));
                }
            }
        }
        cells
    }

    /// Each unit's anchor: its cell nearest to the unit's centroid.
    #[must_use]
    pub fn anchors(&self) -> Vec<Cell> {
        self.cells_by_unit()
            .iter()
            .map(|cells| {
                let k = cells.len().max(1) as f64;
                let (sr, sc) = cells
                    .iter()
                    .fold((0.0, 0.0), |(a, b), c| (a + c.row as f64, b + c.col as f64));
                let centre = (sr / k, sc / k);
                let mut best = (f64::INFINITY, Cell::default());
                for &c in cells {
                    let d = (c.row as f64 - centre.0).powi(2) + (c.col as f64 - centre.1).powi(2);
                    if d < best.0 {
                        best = (d, c);
                    }
                }
                best.1
            })
            .collect()
    }
}

/// The order (unit numbers) in which to cover `units`, starting with the
/// unit of the problem's start cell (or, when the start lies in no unit,
/// with the unit the tour from the start makes best), minimising
/// estimated transit time.
#[must_use]
pub fn room_order(problem: &CoverageProblem, units: &RoomUnits) -> Vec<u32> {
    let n = units.count();
    if n == 0 {
        return Vec::new();
    }
    let coarse = problem.coarse();
    let res = problem.frame().resolution();
    let block = coarse.block_size() as f64;
    let mut anchors = units.anchors();
    let start_unit = units.unit_of(problem.start_cell());
    // A start outside every unit is one more stop, the tour's first.
    if start_unit == 0 {
        anchors.push(problem.start_cell());
    }
    let (units_n, n) = (n, anchors.len());
    // Each anchor's coverage cell, if it has a representative (tiny units
    // may lie in a coverage cell represented elsewhere: same cell then).
    let passable = coarse.passable();
    let at: Vec<Cell> = anchors.iter().map(|&a| coarse.coarse_of(a)).collect();
    // One wavefront per unit, in parallel (rows of the matrix in order,
    // whatever the thread count).
    let mut dist = vec![f64::INFINITY; n * n];
    dist.par_chunks_mut(n).enumerate().for_each_init(
        || Wavefront::with_moves(&passable, coarse.moves()),
        |wave, (i, row)| {
            if !passable[at[i]] {
                return;
            }
            wave.propagate(&[at[i]]);
            for (j, d) in row.iter_mut().enumerate() {
                if let Some(k) = wave.distance(at[j]) {
                    *d = f64::from(k) * block * res;
                }
            }
        },
    );
    let straight = |i: usize, j: usize| {
        let (a, b) = (anchors[i], anchors[j]);
        (a.row as f64 - b.row as f64).hypot(a.col as f64 - b.col as f64) * res
    };
    let v = problem.time().linear_speed;
    let cost = |i: usize, j: usize| {
        let d = dist[i * n + j].min(dist[j * n + i]);
        // Geodesic where known, else a detour-sized guess.
        let d = if d.is_finite() {
            d.max(straight(i, j))
        } else {
            1.5 * straight(i, j)
        };
        d / v
    };
    let first = if start_unit == 0 {
        units_n
    } else {
        start_unit as usize - 1
    };
    open_tour(n, first, &cost)
        .into_iter()
        .filter(|&i| i < units_n)
        .map(|i| i as u32 + 1)
        .collect()
}

/// The unit that covers each coverable cell (0 for the others; [`ANY_UNIT`]
/// where no plannable cell is found within reach, which the definition
/// of coverable rules out): a
/// plannable cell's own unit; a cell beyond the plannable cells (the strip
/// along walls) that of the nearest plannable cell within the tool's
/// reach, ties to the lower unit. A cell next to a room cut is thus left
/// to the unit on its side, not covered by both.
#[must_use]
pub fn unit_claims(problem: &CoverageProblem, units: &RoomUnits) -> Grid<u32> {
    let coverable = &problem.cells().coverable;
    // The coverable cells' own test: within the tool radius, with the
    // grid's tolerance.
    let tool = problem.tool_cells() + oxcover_grid::TOLERANCE_CELLS;
    let k = tool.ceil() as isize;
    let labels = &units.labels;
    let k_cells = k.max(0) as usize;
    // Beyond the units' cells' bounding box widened by `k` no cell has a
    // unit's cell within reach (a coverage target's units may hold a small
    // part of the map): every unit may cover those.
    let every = || coverable.map(|&c| if c { ANY_UNIT } else { 0 });
    let Some((r0, r1, c0, c1)) = labels.bounding_box(|&l| l != 0) else {
        return every();
    };
    let window = coverable.widen((r0, r1, c0, c1), k_cells);
    // Where every coverable cell lies in the window (a target's do), the
    // cells beyond it are all 0: no pass over the map to write them.
    let within = |(a0, a1, b0, b1): Window| {
        window.0 <= a0 && a1 <= window.1 && window.2 <= b0 && b1 <= window.3
    };
    let mut claims = match coverable.bounding_box(|&c| c) {
        Some(b) if within(b) => Grid::new(coverable.width(), coverable.height(), 0),
        _ => every(),
    };
    // The offsets within reach, nearest first.
    let offsets: Vec<(isize, isize, isize)> = nearest_first(k_cells)
        .into_iter()
        .map(|(dr, dc)| (dr, dc, dr * dr + dc * dc))
        .filter(|&(_, _, d2)| d2 as f64 <= tool * tool)
        .collect();
    let near = Grid::par_from_fn(window.3 - window.2, window.1 - window.0, |at: Cell| {
        let c = Cell::new(at.row + window.0, at.col + window.2);
        if !coverable[c] {
            return 0;
        }
        if labels[c] != 0 {
            return labels[c];
        }
        // The nearest unit cell within reach, of equally near ones the
        // lowest unit: offsets nearest first, up to the first distance
        // that finds one.
        let mut best: Option<(isize, u32)> = None;
        for &(dr, dc, d2) in &offsets {
            if best.is_some_and(|(d, _)| d2 > d) {
                break;
            }
            let (r, q) = (c.row as isize + dr, c.col as isize + dc);
            if r < 0 || q < 0 {
                continue;
            }
            if let Some(&l) = labels.get(Cell::new(r as usize, q as usize))
                && l != 0
                && best.is_none_or(|(_, b)| l < b)
            {
                best = Some((d2, l));
            }
        }
        // None found (cannot happen for a coverable cell): every unit.
        best.map_or(ANY_UNIT, |(_, l)| l)
    });
    claims.paste(Cell::new(window.0, window.2), &near);
    claims
}

/// The claim of a cell every unit covers.
pub const ANY_UNIT: u32 = u32::MAX;

/// For each unit of `order` but the last, its plannable cell nearest the
/// next unit (by 4-connected route over the plannable cells): where its
/// plan had best end. `None` for the last unit, or when no route joins
/// the two.
#[must_use]
pub fn unit_exits(
    problem: &CoverageProblem,
    units: &RoomUnits,
    order: &[u32],
) -> Vec<Option<Cell>> {
    unit_exits_with(&mut problem.transit_wavefront(), units, order)
}

/// [`unit_exits`] with a wavefront over the problem's plannable cells
/// ([`CoverageProblem::transit_wavefront`]) at hand, reused search after
/// search (building or copying one costs a pass over the map, more than
/// the searches between neighbouring units).
#[must_use]
pub fn unit_exits_with(
    wave: &mut Wavefront,
    units: &RoomUnits,
    order: &[u32],
) -> Vec<Option<Cell>> {
    // Each unit's edge cells (a 4-neighbour in another unit or none): a
    // route out of a unit leaves it from one, so searching from them finds
    // the same distances outside it as from all its cells.
    let labels = &units.labels;
    let edge = |c: Cell| {
        Dir4::ALL
            .into_iter()
            .any(|d| labels.step(c, d).is_some_and(|n| labels[n] != labels[c]))
    };
    let cells_of: Vec<Vec<Cell>> = units
        .cells_by_unit()
        .into_iter()
        .map(|cells| cells.into_iter().filter(|&c| edge(c)).collect())
        .collect();
    // Each step of the order in turn, on the one wavefront.
    let mut exits: Vec<Option<Cell>> = order
        .windows(2)
        .map(|step| {
            let (here, next) = (step[0], step[1]);
            let sources = (next as usize)
                .checked_sub(1)
                .and_then(|i| cells_of.get(i))
                .map_or(&[][..], Vec::as_slice);
            let found = cidt(wave, sources, |c| units.labels[c] == here);
            found.map(|f| f.first())
        })
        .collect();
    exits.push(None);
    exits
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::DiscRobot;
    use oxcover_grid::io::parse_ascii;

    use crate::Start;

    #[test]
    fn units_split_rooms_and_merge_slivers() {
        let (map, _) = parse_ascii("....#....\n.........\n....#....").unwrap();
        let free = map.free_mask();
        // Rooms: left (cols 0-3), right (cols 5-8), the door cell (1, 4) a
        // room of its own, too small to stand alone.
        let rooms = Grid::from_fn(9, 3, |c: Cell| match c.col {
            0..=3 => 1,
            4 => 3,
            _ => 2,
        });
        let u = RoomUnits::new(&free, &rooms, 2);
        assert_eq!(u.count(), 2);
        assert_eq!(u.sizes, vec![13, 12]);
        assert_eq!(u.unit_of(Cell::new(1, 4)), 1);
        let p = CoverageProblem::new(
            &map,
            DiscRobot::cell_sized(1.0),
            Start::Cell(Cell::new(0, 8)),
        )
        .unwrap();
        assert_eq!(room_order(&p, &u), vec![2, 1]);
    }

    /// Two rooms joined by a door, a tool of 1.5 cells: every coverable
    /// cell is claimed by the room of its nearest plannable cell, the door
    /// column's neighbours by their own side; the exit of the first room
    /// is its cell next to the door.
    #[test]
    fn claims_go_to_the_nearest_unit_and_exits_to_the_door() {
        let text = "#########\n....#....\n.........\n....#....\n#########";
        let (map, _) = parse_ascii(text).unwrap();
        let free = map.free_mask();
        let rooms = Grid::from_fn(9, 5, |c: Cell| if c.col <= 4 { 1 } else { 2 });
        let u = RoomUnits::new(&free, &rooms, 1);
        assert_eq!(u.count(), 2);
        let p = CoverageProblem::new(
            &map,
            DiscRobot::new(0.0, 1.5).unwrap(),
            Start::Cell(Cell::new(2, 0)),
        )
        .unwrap();
        let claims = unit_claims(&p, &u);
        for c in p.cells().coverable.true_cells() {
            assert!(claims[c] == 1 || claims[c] == 2, "{c:?}: {}", claims[c]);
            if u.labels[c] != 0 {
                assert_eq!(claims[c], u.labels[c], "{c:?}");
            }
        }
        assert_eq!(claims[Cell::new(1, 3)], 1);
        assert_eq!(claims[Cell::new(1, 5)], 2);
        let order = room_order(&p, &u);
        assert_eq!(order, vec![1, 2]);
        let exits = unit_exits(&p, &u, &order);
        assert_eq!(exits, vec![Some(Cell::new(2, 4)), None]);
        // A room's problem covers only its claims.
        let claimed = claims.map(|&l| l == 2);
        let sub = p
            .restricted_claiming(&u.mask(2), Cell::new(2, 5), Some(&claimed))
            .unwrap();
        for c in sub.cells().coverable.true_cells() {
            assert!(claimed[sub.to_map_cell(c)], "{c:?}");
        }
        assert!(sub.cells().coverable.count_true() > 0);
        // The unit's own problem, read in its bounding box, is the same.
        let bounds = u.bounds();
        assert_eq!(bounds, vec![(1, 3, 0, 4), (1, 3, 5, 8)]);
        for (unit, start) in [(1, Cell::new(2, 0)), (2, Cell::new(2, 5))] {
            let mask = u.mask(unit);
            let claimed = claims.map(|&l| l == unit || l == ANY_UNIT);
            let whole = p.restricted_claiming(&mask, start, Some(&claimed)).unwrap();
            let own = u
                .restricted(&p, unit, bounds[unit as usize - 1], start, &claims)
                .unwrap();
            assert_eq!(own.offset(), whole.offset());
            assert_eq!(own.plannable(), whole.plannable());
            assert_eq!(own.cells().coverable, whole.cells().coverable);
            assert_eq!(own.cells().admissible, whole.cells().admissible);
        }
        // A start outside the unit is refused, as by restricted_claiming.
        assert!(
            u.restricted(&p, 1, bounds[0], Cell::new(2, 5), &claims)
                .is_err()
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]
        /// The units of a part of a map (a coverage target's), their claims
        /// and exits, found on their windows, are those found on the whole
        /// map: units numbered alike, claims by the nearest unit cell
        /// within reach, exits by a search over every plannable cell.
        #[test]
        fn a_part_is_planned_as_on_the_whole_map(seed in 0u64..1000, r0 in 0usize..70, c0 in 0usize..90, band in 4usize..20) {
            let map = oxcover_grid::random::blobs(150, 110, 12, 9, seed);
            let Ok(p) = CoverageProblem::new(&map, DiscRobot::new(0.0, 1.5).unwrap(), Start::LargestRegion) else {
                return Ok(());
            };
            let part = Grid::from_fn(150, 110, |c: Cell| {
                p.plannable()[c] && (r0..r0 + 40).contains(&c.row) && (c0..c0 + 60).contains(&c.col)
            });
            let rooms = Grid::from_fn(150, 110, |c: Cell| 1 + (c.col / band) as u32);
            let u = RoomUnits::new(&part, &rooms, 6);
            // Units: the whole map's components, merged and numbered alike.
            let Components { labels, sizes } = components4_by_class(&part, &rooms);
            let mut whole = RoomUnits { labels, sizes };
            whole.merge_small(6);
            proptest::prop_assert_eq!(&u, &whole);
            // Claims: a unit cell's own unit, else the nearest unit cell's.
            let claims = unit_claims(&p, &u);
            let reach = p.tool_cells() + oxcover_grid::TOLERANCE_CELLS;
            let unit_cells: Vec<Cell> = u.labels.cells().filter(|&c| u.labels[c] != 0).collect();
            let claim = |c: Cell| {
                let nearest = unit_cells
                    .iter()
                    .map(|&q| {
                        let (dr, dc) = (q.row as f64 - c.row as f64, q.col as f64 - c.col as f64);
                        (dr * dr + dc * dc, u.labels[q])
                    })
                    .filter(|&(d2, _)| d2 <= reach * reach)
                    .min_by(|a, b| a.partial_cmp(b).unwrap());
                if u.labels[c] != 0 { u.labels[c] } else { nearest.map_or(ANY_UNIT, |n| n.1) }
            };
            for c in p.cells().coverable.true_cells() {
                proptest::prop_assert_eq!(claims[c], claim(c), "{:?}", c);
            }
            // A target's (its coverable cells all within reach of its
            // units): every cell's claim, 0 off the coverable cells.
            let required = Grid::from_fn(150, 110, |c: Cell| {
                p.cells().coverable[c] && claim(c) != ANY_UNIT
            });
            let target = p.clone().with_required(&required).unwrap();
            let claims = unit_claims(&target, &u);
            for c in required.cells() {
                let want = if required[c] { claim(c) } else { 0 };
                proptest::prop_assert_eq!(claims[c], want, "{:?}", c);
            }
            // Each unit's cells, row by row, as a scan of every cell.
            let by_unit: Vec<Vec<Cell>> = (1..=u.count() as u32)
                .map(|l| unit_cells.iter().copied().filter(|&c| u.labels[c] == l).collect())
                .collect();
            proptest::prop_assert_eq!(&u.cells_by_unit(), &by_unit);
            // Each unit's bounds, as a scan of its cells.
            let bounds = u.bounds();
            let scanned: Vec<(usize, usize, usize, usize)> = by_unit
                .iter()
                .map(|cells| {
                    cells.iter().fold((usize::MAX, 0, usize::MAX, 0), |x, c| {
                        (x.0.min(c.row), x.1.max(c.row), x.2.min(c.col), x.3.max(c.col))
                    })
                })
                .collect();
            proptest::prop_assert_eq!(&bounds, &scanned);
            // A unit's problem from its first cell, moved to another of
            // its cells, is its problem from there; a cell the first does
            // not reach is refused.
            for (l, own) in (1..=u.count() as u32).zip(&by_unit) {
                let b = bounds[l as usize - 1];
                proptest::prop_assert_eq!(u.first_cell(l, b), own.first().copied());
                let (Some(&first), Some(&last)) = (own.first(), own.last()) else {
                    continue;
                };
                let from_first = u.restricted(&p, l, b, first, &claims).unwrap();
                for c in [own[own.len() / 2], last] {
                    let direct = u.restricted(&p, l, b, c, &claims).unwrap();
                    let local = from_first.from_map_cell(c).unwrap();
                    match from_first.clone().with_start_cell(local) {
                        Ok(moved) => {
                            proptest::prop_assert_eq!(moved.plannable(), direct.plannable());
                            proptest::prop_assert_eq!(&moved.cells().coverable, &direct.cells().coverable);
                            proptest::prop_assert_eq!(&moved.cells().admissible, &direct.cells().admissible);
                            proptest::prop_assert_eq!(moved.coarse(), direct.coarse());
                            proptest::prop_assert_eq!(moved.start_cell(), direct.start_cell());
                            proptest::prop_assert_eq!(moved.offset(), direct.offset());
                        }
                        Err(_) => proptest::prop_assert!(!from_first.plannable()[local]),
                    }
                }
            }
            // Exits: one search over every plannable cell per step.
            let order: Vec<u32> = (1..=u.count() as u32).collect();
            let mut wave = Wavefront::new(p.plannable());
            let mut want: Vec<Option<Cell>> = order
                .windows(2)
                .map(|s| {
                    let next: Vec<Cell> = unit_cells.iter().copied().filter(|&c| u.labels[c] == s[1]).collect();
                    cidt(&mut wave, &next, |c| u.labels[c] == s[0]).map(|f| f.first())
                })
                .collect();
            want.push(None);
            proptest::prop_assert_eq!(unit_exits(&p, &u, &order), want);
        }
    }
}
