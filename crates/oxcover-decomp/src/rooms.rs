//! Room segmentation of indoor maps by morphology: erode the free space
//! until it falls apart into pieces of room size, keep those pieces as room
//! seeds, and grow the seeds back over the free space.
//!
//! 1. The clearance of every free cell (exact distance from its centre to the
//!    nearest non-free cell's boundary or the map edge) is computed once
//!    ([`oxcover_grid::edt::boundary_distance_sq4`]); eroding by `k` cells is
//!    keeping the cells of clearance at least `k`.
//! 2. For `k = 1, 2, …` until nothing is left, the free space eroded by `k`
//!    cells is cut into 4-connected pieces; each piece lies inside one piece
//!    of the level above, so the pieces form a tree. A piece is a room seed
//!    when its area lies within [`RoomParams::min_area_m2`] ..=
//!    [`RoomParams::max_area_m2`] and no further erosion splits it into two
//!    or more pieces of room size; the shallowest such pieces are kept. So
//!    two small rooms joined by a door are two seeds (they part once the
//!    erosion exceeds half the door's width), a niche or a doorway that
//!    never reaches room size is no seed, and a hall larger than a room is
//!    eroded until its pieces fit.
//! 3. The seeds grow back together, one cell ring at a time (a multi-source
//!    breadth-first search over the free cells, in label order), so every
//!    free cell reachable from a seed joins the nearest room by path. A free
//!    region no seed reaches (a closet behind a one-cell gap, a region
//!    smaller than a room) becomes a room of its own, so every free cell has
//!    exactly one room.
//! 4. Doors are where two rooms meet: the cells of each room pair that touch
//!    the other room, with the one nearest their middle as the door's centre.
//!
//! This is the morphological segmenter of Bormann et al. 2016 ("Room
//! segmentation: survey, implementation, and analysis"; the
//! `ipa_room_segmentation` package), written anew on this workspace's exact
//! clearance, with one departure: there a piece becomes a room the first time
//! its area is in range, so two small rooms joined by a door (together still
//! below the upper limit) come out as one room; here a piece must also not
//! split into two room-sized pieces further down the erosion tree. Free
//! regions no seed reaches are rooms of their own here (the survey leaves
//! them unlabelled), so every free cell belongs to exactly one room.

use rayon::prelude::*;
use std::collections::{BTreeMap, VecDeque};

use oxcover_grid::edt::boundary_distance_sq4;
use oxcover_grid::{Cell, Dir4, Grid, components4};

/// Limits of a room.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoomParams {
    /// Cell size (m).
    pub resolution: f64,
    /// Smallest eroded piece kept as a room seed (m²).
    pub min_area_m2: f64,
    /// Largest eroded piece kept as a room seed; larger pieces are eroded
    /// further (m²). Morphological method only.
    pub max_area_m2: f64,
    /// Widest opening taken for a door (m). Medial-axis method only
    /// ([`crate::voronoi_rooms`]).
    pub door_width_m: f64,
}

impl RoomParams {
    /// Indoor defaults for a map of `resolution`: seeds between 1 m² and
    /// 47 m² (the survey's values for the morphological method), doors up
    /// to 1.6 m wide (wide enough for double doors and open passages).
    #[must_use]
    pub fn indoor(resolution: f64) -> Self {
        Self {
            resolution,
            min_area_m2: 1.0,
            max_area_m2: 47.0,
            door_width_m: 1.6,
        }
    }
}

/// Where two rooms meet.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Door {
    /// The two rooms (1-based labels, the smaller first).
    pub rooms: (u32, u32),
    /// Cells of either room that touch the other (row-major).
    pub cells: Vec<Cell>,
    /// The door cell nearest the cells' mean position.
    pub centre: Cell,
}

/// A segmentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Rooms {
    /// 0 on cells that are not free, else the 1-based room label.
    pub labels: Grid<u32>,
    /// `areas[i]`: cells of room `i + 1`.
    pub areas: Vec<usize>,
    /// Rooms that came from an eroded seed (the rest are free regions no
    /// seed reached).
    pub seeded: usize,
    /// Every pair of rooms that touch, ordered by their labels.
    pub doors: Vec<Door>,
}

impl Rooms {
    /// Number of rooms.
    #[must_use]
    pub fn count(&self) -> usize {
        self.areas.len()
    }

    /// The rooms next to `room`.
    #[must_use]
    pub fn neighbours(&self, room: u32) -> Vec<u32> {
        self.doors
            .iter()
            .filter_map(|d| match d.rooms {
                (a, b) if a == room => Some(b),
                (a, b) if b == room => Some(a),
                _ => None,
            })
            .collect()
    }
}

/// Segments the free cells of `free` into rooms (see the module docs).
#[must_use]
pub fn morphological(free: &Grid<bool>, params: &RoomParams) -> Rooms {
    let (w, h) = (free.width(), free.height());
    let cell_area = params.resolution * params.resolution;
    let (min_cells, max_cells) = if cell_area.is_finite() && cell_area > 0.0 {
        (
            (params.min_area_m2 / cell_area).max(1.0),
            params.max_area_m2 / cell_area,
        )
    } else {
        (1.0, f64::INFINITY)
    };
    // 4·clearance² in cells (0 on non-free cells).
    let blocked = free.map(|&f| !f);
    let d4 = boundary_distance_sq4(&blocked, true);
    let tree = ErosionTree::new(free, &d4);
    let chosen = tree.seeds(min_cells, max_cells);
    let mut seeds = Grid::new(w, h, 0u32);
    for (i, &p) in chosen.iter().enumerate() {
        let piece = &tree.pieces[p];
        flood(&mut seeds, piece.cell, i as u32 + 1, |c| {
            free[c] && d4[c] >= 4 * piece.level * piece.level
        });
    }
    let next = chosen.len() as u32 + 1;
    let seeded = chosen.len();

    // Grow the seeds back over the free cells, ring by ring.
    let mut labels = seeds;
    let mut queue: VecDeque<Cell> = labels.cells().filter(|&c| labels[c] != 0).collect();
    grow(free, &mut labels, &mut queue);
    // Free regions no seed reached: rooms of their own.
    let next = label_the_rest(free, &mut labels, next);
    let mut areas = vec![0usize; (next - 1) as usize];
    for c in labels.cells() {
        if labels[c] != 0 {
            areas[labels[c] as usize - 1] += 1;
        }
    }
    let doors = doors(&labels);
    Rooms {
        labels,
        areas,
        seeded,
        doors,
    }
}

/// One 4-connected piece of the free space eroded by `level` cells.
#[derive(Clone, Copy, Debug)]
struct Piece {
    level: u64,
    /// Its first cell (row-major).
    cell: Cell,
    area: usize,
}

/// The pieces of every erosion level and how they nest.
struct ErosionTree {
    pieces: Vec<Piece>,
    /// Pieces of level 1 (the roots), in row-major order of their first cell.
    roots: Vec<usize>,
    children: Vec<Vec<usize>>,
}

impl ErosionTree {
    /// Erodes by 1, 2, … cells until nothing is left.
    fn new(free: &Grid<bool>, d4: &Grid<u64>) -> Self {
        let (w, h) = (free.width(), free.height());
        let mut pieces: Vec<Piece> = Vec::new();
        let mut children: Vec<Vec<usize>> = Vec::new();
        let mut roots = Vec::new();
        // Piece index of every cell at the previous level.
        let mut above: Option<Grid<u32>> = None;
        let mut level: u64 = 1;
        loop {
            let need = 4 * level * level;
            let eroded = Grid::from_fn(w, h, |c| free[c] && d4[c] >= need);
            if eroded.count_true() == 0 {
                break;
            }
            let comps = components4(&eroded);
            let base = pieces.len();
            let mut first: Vec<Option<Cell>> = vec![None; comps.count()];
            for c in eroded.true_cells() {
                let l = comps.labels[c] as usize - 1;
                first[l].get_or_insert(c);
            }
            for (l, f) in first.into_iter().enumerate() {
                let cell = f.unwrap_or_default();
                let parent = above.as_ref().map(|g| g[cell] as usize);
                pieces.push(Piece {
                    level,
                    cell,
                    area: comps.sizes[l],
                });
                children.push(Vec::new());
                match parent {
                    Some(p) => children[p].push(base + l),
                    None => roots.push(base + l),
                }
            }
            above = Some(
                comps
                    .labels
                    .map(|&l| if l == 0 { 0 } else { base as u32 + l - 1 }),
            );
            level += 1;
        }
        Self {
            pieces,
            roots,
            children,
        }
    }

    /// The seeds: the shallowest pieces within the area limits that do not
    /// fall apart, further eroded, into two or more room-sized pieces.
    fn seeds(&self, min_cells: f64, max_cells: f64) -> Vec<usize> {
        let n = self.pieces.len();
        let in_range = |p: &Piece| (p.area as f64) >= min_cells && (p.area as f64) <= max_cells;
        // Rooms each piece holds, children first (a child is always later).
        let mut rooms = vec![0usize; n];
        for i in (0..n).rev() {
            let below: usize = self.children[i].iter().map(|&c| rooms[c]).sum();
            rooms[i] = if below >= 2 {
                below
            } else if in_range(&self.pieces[i]) {
                1
            } else {
                below
            };
        }
        let mut out = Vec::new();
        let mut stack: Vec<usize> = self.roots.iter().rev().copied().collect();
        while let Some(i) = stack.pop() {
            let below: usize = self.children[i].iter().map(|&c| rooms[c]).sum();
            if rooms[i] == 1 && below < 2 && in_range(&self.pieces[i]) {
                out.push(i);
            } else {
                stack.extend(self.children[i].iter().rev().copied());
            }
        }
        out
    }
}

/// Labels with `label` the 4-connected cells from `start` where `inside` holds.
fn flood(labels: &mut Grid<u32>, start: Cell, label: u32, inside: impl Fn(Cell) -> bool) {
    let mut queue = VecDeque::from([start]);
    labels[start] = label;
    while let Some(c) = queue.pop_front() {
        for d in Dir4::ALL {
            if let Some(n) = labels.step(c, d) {
                if labels[n] == 0 && inside(n) {
                    labels[n] = label;
                    queue.push_back(n);
                }
            }
        }
    }
}

/// Gives every free region still unlabelled a label of its own, from
/// `next` on (each grown breadth first); returns the next unused label.
pub(crate) fn label_the_rest(free: &Grid<bool>, labels: &mut Grid<u32>, mut next: u32) -> u32 {
    let mut queue = VecDeque::new();
    let w = free.width();
    // By index to the unlabelled free cells (this reads every cell).
    for i in 0..free.len() {
        if free.as_slice()[i] && labels.as_slice()[i] == 0 {
            let c = Cell::new(i / w, i % w);
            labels[c] = next;
            next += 1;
            queue.push_back(c);
            grow(free, labels, &mut queue);
        }
    }
    next
}

/// How many cells hold each label (by label, 0 included, up to the
/// largest), counted a run of equal labels at a time: a count bumped cell
/// by cell waits on its own last store.
pub(crate) fn label_counts(labels: &[u32]) -> Vec<usize> {
    // (Stretches of 64 Ki cells in parallel, their counts added.)
    let count = |labels: &[u32]| {
        let mut size: Vec<usize> = Vec::new();
        for (l, run) in label_runs(labels) {
            if l as usize >= size.len() {
                size.resize(l as usize + 1, 0);
            }
            size[l as usize] += run;
        }
        size
    };
    labels
        .par_chunks(1 << 16)
        .map(count)
        .reduce(Vec::new, |a, b| {
            let (mut long, short) = if a.len() >= b.len() { (a, b) } else { (b, a) };
            for (x, y) in long.iter_mut().zip(short) {
                *x += y;
            }
            long
        })
}

/// The runs of equal labels in `labels`, in order: each label and how
/// many cells in a row hold it.
pub(crate) fn label_runs(labels: &[u32]) -> impl Iterator<Item = (u32, usize)> + '_ {
    let mut i = 0;
    std::iter::from_fn(move || {
        let &l = labels.get(i)?;
        let run = labels[i..].iter().take_while(|&&m| m == l).count();
        i += run;
        Some((l, run))
    })
}

/// Breadth-first growth of labelled cells over unlabelled free cells.
pub(crate) fn grow(free: &Grid<bool>, labels: &mut Grid<u32>, queue: &mut VecDeque<Cell>) {
    while let Some(c) = queue.pop_front() {
        let l = labels[c];
        for d in Dir4::ALL {
            if let Some(n) = free.step(c, d) {
                if free[n] && labels[n] == 0 {
                    labels[n] = l;
                    queue.push_back(n);
                }
            }
        }
    }
}

/// Merges the regions of `labels` (1-based, 0 = none) smaller than
/// `min_cells` into the neighbour they share the longest 4-connected border
/// with (smallest first; ties: the larger neighbour, then the lower label).
/// A merged region takes its neighbour's label; labels are not renumbered.
pub fn merge_small_regions(labels: &mut Grid<u32>, min_cells: f64) {
    let n = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    if n < 2 {
        return;
    }
    let mut sizes = label_counts(labels.as_slice());
    sizes.remove(0);
    let small: Vec<bool> = sizes.iter().map(|&k| (k as f64) < min_cells).collect();
    if !small.contains(&true) {
        return;
    }
    // Only a small region's contacts are ever read (its own, and those of
    // the small regions merged into it).
    let mut contacts: Vec<BTreeMap<u32, usize>> = vec![BTreeMap::new(); n];
    // Each 4-neighbour pair once (a cell and the cells right of and below
    // it), counted for both sides: by row slices, as this reads every cell.
    let mut touch = |l: u32, m: u32| {
        if l != 0 && m != 0 && l != m && (small[l as usize - 1] || small[m as usize - 1]) {
            *contacts[l as usize - 1].entry(m).or_default() += 1;
            *contacts[m as usize - 1].entry(l).or_default() += 1;
        }
    };
    // (A run of one label at a time: its right end, and the cells below
    // it where they are not all of its label.)
    for row in 0..labels.height() {
        let here = labels.row(row);
        let below = (row + 1 < labels.height()).then(|| labels.row(row + 1));
        let mut a = 0;
        for (l, run) in label_runs(here) {
            let b = a + run;
            // (Unlabelled cells touch nothing.)
            if l != 0 {
                if let Some(&right) = here.get(b) {
                    touch(l, right);
                }
                if let Some(under) = below.map(|v| &v[a..b]) {
                    if under.iter().any(|&m| m != l) {
                        for &m in under {
                            touch(l, m);
                        }
                    }
                }
            }
            a = b;
        }
    }
    let mut parent: Vec<u32> = (1..=n as u32).collect();
    let find = |p: &[u32], mut u: u32| {
        while p[u as usize - 1] != u {
            u = p[u as usize - 1];
        }
        u
    };
    let mut order: Vec<usize> = (0..n).filter(|&i| (sizes[i] as f64) < min_cells).collect();
    order.sort_by_key(|&i| (sizes[i], i));
    for i in order {
        let me = i as u32 + 1;
        if find(&parent, me) != me || (sizes[i] as f64) >= min_cells {
            continue;
        }
        let mut by_root: BTreeMap<u32, usize> = BTreeMap::new();
        for (&v, &k) in &contacts[i] {
            let r = find(&parent, v);
            if r != me {
                *by_root.entry(r).or_default() += k;
            }
        }
        let best = by_root
            .iter()
            .max_by_key(|&(&u, &k)| (k, sizes[u as usize - 1], std::cmp::Reverse(u)));
        if let Some((&to, _)) = best {
            parent[i] = to;
            sizes[to as usize - 1] += std::mem::take(&mut sizes[i]);
            let mine = std::mem::take(&mut contacts[i]);
            for (v, k) in mine {
                *contacts[to as usize - 1].entry(v).or_default() += k;
            }
        }
    }
    let root: Vec<u32> = (0..=n as u32)
        .map(|l| if l == 0 { 0 } else { find(&parent, l) })
        .collect();
    // (Nothing to write where no region merged.)
    if root.iter().enumerate().any(|(l, &r)| r != l as u32) {
        for l in labels.as_mut_slice() {
            *l = root[*l as usize];
        }
    }
}

/// The doors between every pair of touching rooms.
pub(crate) fn doors(labels: &Grid<u32>) -> Vec<Door> {
    let mut touching: BTreeMap<(u32, u32), Vec<Cell>> = BTreeMap::new();
    // Each pair of 4-neighbours once: a cell and the cells right of and
    // below it; both cells of a pair with two labels touch.
    let (w, s) = (labels.width(), labels.as_slice());
    let mut meet = |a: u32, b: u32, at: Cell, n: Cell| {
        if b != 0 && b != a {
            let cells = touching.entry((a.min(b), a.max(b))).or_default();
            cells.push(at);
            cells.push(n);
        }
    };
    // Row by row (this reads every cell): a cell's right neighbour, then
    // the one below it.
    for (r, row) in s.chunks(w.max(1)).enumerate() {
        let below = s.get((r + 1) * w..(r + 2) * w);
        for (col, &a) in row.iter().enumerate() {
            if a == 0 {
                continue;
            }
            if let Some(&b) = row.get(col + 1) {
                meet(a, b, Cell::new(r, col), Cell::new(r, col + 1));
            }
            if let Some(&b) = below.map(|v| &v[col]) {
                meet(a, b, Cell::new(r, col), Cell::new(r + 1, col));
            }
        }
    }
    door_list(touching)
}

/// The doors of the touching cells of each pair of rooms.
pub(crate) fn door_list(touching: BTreeMap<(u32, u32), Vec<Cell>>) -> Vec<Door> {
    touching
        .into_iter()
        .map(|(rooms, mut cells)| {
            cells.sort_unstable();
            cells.dedup();
            let n = cells.len() as f64;
            let (mr, mc) = cells.iter().fold((0.0, 0.0), |(r, q), c| {
                (r + c.row as f64 / n, q + c.col as f64 / n)
            });
            let centre = cells
                .iter()
                .copied()
                .min_by(|a, b| {
                    let da = (a.row as f64 - mr).powi(2) + (a.col as f64 - mc).powi(2);
                    let db = (b.row as f64 - mr).powi(2) + (b.col as f64 - mc).powi(2);
                    da.total_cmp(&db).then(a.cmp(b))
                })
                .unwrap_or_default();
            Door {
                rooms,
                cells,
                centre,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::ascii_mask;

    #[test]
    fn label_counts_add_up_across_stretches() {
        // Runs that cross the parallel stretches' boundaries (64 Ki cells).
        let labels: Vec<u32> = (0..200_000u32).map(|i| (i / 7_001) % 5).collect();
        let mut brute = vec![0usize; 5];
        for &l in &labels {
            brute[l as usize] += 1;
        }
        assert_eq!(label_counts(&labels), brute);
        assert_eq!(label_counts(&[]), Vec::<usize>::new());
        assert_eq!(label_counts(&[0, 0, 3]), vec![2, 0, 0, 1]);
    }

    /// `n` square rooms of `side` cells in a row, walls `wall` cells thick,
    /// joined by doors `door` cells wide in the middle of each wall.
    fn row_of_rooms(n: usize, side: usize, wall: usize, door: usize) -> Grid<bool> {
        let w = n * side + (n + 1) * wall;
        let h = side + 2 * wall;
        Grid::from_fn(w, h, |c| {
            let inside_y = c.row >= wall && c.row < wall + side;
            let x = c.col;
            let period = side + wall;
            let in_room = x >= wall && (x - wall) % period < side && x < w - wall;
            let mid = wall + side / 2;
            let in_door = x >= wall
                && (x - wall) % period >= side
                && x < w - wall
                && c.row >= mid - door / 2
                && c.row < mid - door / 2 + door;
            (inside_y && in_room) || in_door
        })
    }

    fn check_partition(free: &Grid<bool>, r: &Rooms) {
        for c in free.cells() {
            assert_eq!(free[c], r.labels[c] != 0, "{c:?}");
        }
        assert_eq!(r.areas.iter().sum::<usize>(), free.count_true());
        assert!(r.areas.iter().all(|&a| a > 0));
    }

    #[test]
    fn two_rooms_and_their_door() {
        // 4 × 4 m rooms at 0.1 m, a 0.8 m door through a 0.2 m wall.
        let free = row_of_rooms(2, 40, 2, 8);
        let r = morphological(&free, &RoomParams::indoor(0.1));
        check_partition(&free, &r);
        assert_eq!((r.count(), r.seeded), (2, 2));
        assert_eq!(r.doors.len(), 1);
        let d = &r.doors[0];
        assert_eq!(d.rooms, (1, 2));
        // The door is in the wall's gap (columns 42 and 43), around row 22.
        assert!((40..=45).contains(&d.centre.col), "{d:?}");
        assert!((18..=26).contains(&d.centre.row), "{d:?}");
        // The rooms split at the door: each keeps its own 40 × 40 cells
        // and a share of the doorway.
        for &a in &r.areas {
            assert!((1600..=1616).contains(&a), "{:?}", r.areas);
        }
    }

    #[test]
    fn three_rooms_in_a_row_form_a_chain() {
        let free = row_of_rooms(3, 40, 2, 8);
        let r = morphological(&free, &RoomParams::indoor(0.1));
        check_partition(&free, &r);
        assert_eq!(r.count(), 3);
        let pairs: Vec<(u32, u32)> = r.doors.iter().map(|d| d.rooms).collect();
        assert_eq!(pairs, [(1, 2), (2, 3)]);
        assert_eq!(r.neighbours(2), [1, 3]);
        assert_eq!(r.neighbours(1), [2]);
    }

    #[test]
    fn one_room_has_no_door_and_a_too_small_map_is_one_region() {
        let free = Grid::new(50, 30, true);
        let r = morphological(&free, &RoomParams::indoor(0.1));
        check_partition(&free, &r);
        assert_eq!((r.count(), r.seeded, r.doors.len()), (1, 1, 0));
        // 2 × 2 cells at 0.1 m: smaller than any room, still one region.
        let tiny = ascii_mask(&["..", ".."]).unwrap();
        let r = morphological(&tiny, &RoomParams::indoor(0.1));
        check_partition(&tiny, &r);
        assert_eq!((r.count(), r.seeded), (1, 0));
        // No free cell: no room.
        let none = Grid::new(4, 4, false);
        let r = morphological(&none, &RoomParams::indoor(0.1));
        assert_eq!((r.count(), r.doors.len()), (0, 0));
    }

    #[test]
    fn a_closet_behind_a_slit_is_its_own_room() {
        // A 4 × 4 m room and a 0.5 × 0.5 m closet joined by a 1-cell slit.
        let mut free = Grid::new(60, 44, false);
        for c in free.cells().collect::<Vec<_>>() {
            let room = c.row >= 2 && c.row < 42 && c.col >= 2 && c.col < 42;
            let closet = c.row >= 20 && c.row < 25 && c.col >= 44 && c.col < 49;
            let slit = c.row == 22 && (42..44).contains(&c.col);
            free[c] = room || closet || slit;
        }
        let r = morphological(&free, &RoomParams::indoor(0.1));
        check_partition(&free, &r);
        // The closet never holds a 1 m² seed, so the room's growth takes it.
        assert_eq!(r.count(), 1);
        // Without the slit it is a free region of its own.
        free[Cell::new(22, 42)] = false;
        free[Cell::new(22, 43)] = false;
        let r = morphological(&free, &RoomParams::indoor(0.1));
        check_partition(&free, &r);
        assert_eq!((r.count(), r.seeded, r.doors.len()), (2, 1, 0));
    }

    #[test]
    fn labels_do_not_depend_on_anything_but_the_map() {
        let free = row_of_rooms(3, 30, 2, 6);
        let p = RoomParams::indoor(0.1);
        assert_eq!(morphological(&free, &p), morphological(&free, &p));
    }
}
