//! Lee wavefront (Lee 1961): breadth-first distance labels over 4-connected
//! cells, and a retrace that prefers to keep its direction (fewest bends).
//!
//! [`Wavefront`] is a reusable workspace: the passability is baked once into a
//! label array padded with a blocked border (no bounds tests in the inner loop),
//! the queue doubles as the list of cells a query touched, and the next query
//! resets only those cells, so repeated queries neither allocate nor clear the
//! whole map. Cost per query O(cells touched). Optional per-cell move masks
//! ([`Wavefront::with_moves`]) restrict which of the four moves leave a cell,
//! for graphs like [`oxcover_grid::CoarseGrid`] whose neighbours are not all
//! connected.

use oxcover_grid::{Cell, Dir4, Grid};

const BLOCKED: u32 = u32::MAX;
const UNSEEN: u32 = u32::MAX - 1;
/// How many cells a flood labels between asking whether it may stop.
const CHECK_EVERY: usize = 64;
/// Interior-cell share above which the branchy flood is used. Measured on real
/// maps (docs/benchmarks.md): open floors have 0.94 to 0.99 and run twice as
/// fast branchy; mazes (0.005) three times faster branch-free; a 20 % random
/// grid (0.41) about 15 % faster branch-free.
const BRANCHY_ABOVE: f64 = 0.7;

/// The cells of one wavefront layer, as handed to a layer callback.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Layer<'a> {
    cells: &'a [u32],
    stride: usize,
}

impl Layer<'_> {
    /// The layer's cells in BFS order.
    pub(crate) fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        let stride = self.stride;
        // Division by a multiplication: with c = ceil(2^64 / stride),
        // floor(i·c / 2^64) is i / stride for every 32-bit i (Lemire et al.
        // 2019); a hardware division per cell costs more than the search.
        let c = u128::from(u64::MAX / stride as u64 + 1);
        self.cells.iter().map(move |&i| {
            let row = ((u128::from(i) * c) >> 64) as usize;
            Cell::new(row - 1, i as usize - row * stride - 1)
        })
    }
}

/// The cells of `row` whose four neighbours are open, with `up` and `down`
/// the rows above and below (all of one length; the edge columns never
/// count): columns `1..w-1` as selects over equal slices, which vectorise.
fn interior_in(up: &[bool], row: &[bool], down: &[bool]) -> usize {
    let inner = row.len().saturating_sub(2);
    if inner == 0 {
        return 0;
    }
    let (u, d) = (&up[1..=inner], &down[1..=inner]);
    let (west, mid, east) = (&row[..inner], &row[1..=inner], &row[2..inner + 2]);
    (0..inner)
        .map(|i| u32::from(u[i] & d[i] & west[i] & mid[i] & east[i]))
        .sum::<u32>() as usize
}

/// A reusable Lee wavefront over a fixed grid.
#[derive(Clone, Debug)]
pub struct Wavefront {
    width: usize,
    height: usize,
    stride: usize,
    labels: Vec<u32>,
    moves: Option<Vec<u8>>,
    /// BFS queue, sized once to hold every passable cell plus one spare slot
    /// (the branch-free push writes one slot past the tail).
    queue: Vec<u32>,
    /// Cells queued by the last query: `queue[..tail]`.
    tail: usize,
    open: usize,
    offsets: [isize; 4],
    /// Use the branch-free flood (see [`Wavefront::flood`]).
    branch_free: bool,
}

impl Wavefront {
    /// A workspace over the `true` cells of `passable`.
    #[must_use]
    pub fn new(passable: &Grid<bool>) -> Self {
        let (w, h) = (passable.width(), passable.height());
        let stride = w + 2;
        // One spare slot past the padded grid: the branch-free BFS stores its
        // "no new cell" writes there. Written in one pass, row by row: the
        // padding row above and each row's padding either side.
        let len = stride * (h + 2) + 1;
        let mut labels = Vec::with_capacity(len);
        labels.resize(stride + 1, BLOCKED);
        let mut open = 0;
        // Share of open cells whose four neighbours are all open: near 1 on
        // open floors, near 0 in mazes (see `flood`).
        let mut interior = 0usize;
        let none = vec![false; w];
        for r in 0..h {
            let row = passable.row(r);
            labels.extend(row.iter().map(|&p| if p { UNSEEN } else { BLOCKED }));
            labels.extend([BLOCKED; 2]);
            open += row.iter().map(|&p| usize::from(p)).sum::<usize>();
            let up = if r > 0 { passable.row(r - 1) } else { &none };
            let down = if r + 1 < h {
                passable.row(r + 1)
            } else {
                &none
            };
            interior += interior_in(up, row, down);
        }
        labels.resize(len, BLOCKED);
        let branch_free = (interior as f64) < BRANCHY_ABOVE * open as f64;
        Self {
            width: w,
            height: h,
            stride,
            labels,
            moves: None,
            queue: vec![0; open + 1],
            tail: 0,
            open,
            offsets: [-(stride as isize), 1, stride as isize, -1],
            branch_free,
        }
    }

    /// A workspace where a move from a cell in direction `d` is allowed only when
    /// bit [`Dir4::bit`] of `moves[cell]` is set (and the target is passable).
    #[must_use]
    pub fn with_moves(passable: &Grid<bool>, moves: &Grid<u8>) -> Self {
        let mut wf = Self::new(passable);
        let mut padded = vec![0u8; wf.labels.len()];
        for r in 0..wf.height.min(moves.height()) {
            let base = (r + 1) * wf.stride + 1;
            let row = moves.row(r);
            let n = row.len().min(wf.width);
            padded[base..base + n].copy_from_slice(&row[..n]);
        }
        wf.moves = Some(padded);
        wf
    }

    /// Grid width.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    fn pad(&self, c: Cell) -> usize {
        (c.row + 1) * self.stride + c.col + 1
    }

    fn unpad(&self, i: usize) -> Cell {
        Cell::new(i / self.stride - 1, i % self.stride - 1)
    }

    fn inside(&self, c: Cell) -> bool {
        c.row < self.height && c.col < self.width
    }

    /// Whether `cell` is passable.
    #[must_use]
    pub fn is_passable(&self, cell: Cell) -> bool {
        self.inside(cell) && self.labels[self.pad(cell)] != BLOCKED
    }

    /// Changes the passability of a cell. Invalidates the labels of the last query.
    pub fn set_passable(&mut self, cell: Cell, passable: bool) {
        if !self.inside(cell) {
            return;
        }
        self.reset();
        let i = self.pad(cell);
        let was = self.labels[i] != BLOCKED;
        self.labels[i] = if passable { UNSEEN } else { BLOCKED };
        match (was, passable) {
            (false, true) => {
                self.open += 1;
                if self.queue.len() < self.open + 1 {
                    self.queue.resize(self.open + 1, 0);
                }
            }
            (true, false) => self.open -= 1,
            _ => {}
        }
    }

    /// Clears the labels of the last query: O(cells it touched), or one
    /// sequential sweep when it touched much of the map (faster than scattered writes).
    pub fn reset(&mut self) {
        if self.tail > self.labels.len() / 16 {
            // A select, not a branch: the sweep vectorises.
            for l in &mut self.labels {
                *l = if *l == BLOCKED { BLOCKED } else { UNSEEN };
            }
        } else {
            for &i in &self.queue[..self.tail] {
                let l = &mut self.labels[i as usize];
                if *l != BLOCKED {
                    *l = UNSEEN;
                }
            }
        }
        self.tail = 0;
    }

    /// Labels every passable cell reachable from `sources` with its distance.
    /// Returns the number of cells labelled.
    pub fn propagate(&mut self, sources: &[Cell]) -> usize {
        self.propagate_within(sources, u32::MAX)
    }

    /// Like [`Wavefront::propagate`] but stops after distance `max_distance`.
    pub fn propagate_within(&mut self, sources: &[Cell], max_distance: u32) -> usize {
        self.seed(sources);
        self.flood_until(max_distance, |_| false);
        self.tail
    }

    /// Floods from the seeded queue up to `max_distance`, asking `done`
    /// (with the labels so far) every [`CHECK_EVERY`] cells whether to stop.
    fn flood_until(&mut self, max_distance: u32, done: impl FnMut(&[u32]) -> bool) {
        if self.moves.is_some() {
            self.flood_masked(max_distance, done);
        } else if self.branch_free {
            self.flood(max_distance, done);
        } else {
            self.flood_branchy(max_distance, done);
        }
    }

    /// Resets, then labels the passable in-grid `sources` 0 and queues them.
    fn seed(&mut self, sources: &[Cell]) {
        self.reset();
        for &s in sources {
            if !self.inside(s) {
                continue;
            }
            let i = self.pad(s);
            if self.labels[i] == UNSEEN {
                self.labels[i] = 0;
                self.queue[self.tail] = i as u32;
                self.tail += 1;
            }
        }
    }

    /// Plain BFS without layer bookkeeping, the fast path of full transforms:
    /// each popped cell's label + 1 labels the neighbours it discovers.
    ///
    /// Two loops with the same result. Where which neighbours are open is
    /// unpredictable (mazes, scattered obstacles), branch mispredictions
    /// dominate, so the neighbour test is branch-free: a select picks the store
    /// address, the queue slot is always written and the tail advances only for
    /// new cells. On open floors the branches predict well and the plain loop,
    /// without that serial dependency, is faster. The choice is made once per
    /// map from its share of interior cells.
    fn flood(&mut self, max_distance: u32, mut done: impl FnMut(&[u32]) -> bool) {
        let [n, e, s, w] = self.offsets;
        let labels: &mut [u32] = &mut self.labels;
        let spare = labels.len() - 1;
        let queue: &mut [u32] = &mut self.queue;
        let mut tail = self.tail;
        let mut head = 0;
        while head < tail {
            if head % CHECK_EVERY == 0 && done(labels) {
                break;
            }
            let i = queue[head] as usize;
            head += 1;
            let d = labels[i] + 1;
            if d > max_distance {
                break;
            }
            for off in [n, e, s, w] {
                let j = i.wrapping_add_signed(off);
                let new = labels[j] == UNSEEN;
                // Old cells write to the spare slot, so no cache line is dirtied.
                labels[if new { j } else { spare }] = d;
                queue[tail] = j as u32;
                tail += usize::from(new);
            }
        }
        self.tail = tail;
    }

    fn flood_branchy(&mut self, max_distance: u32, mut done: impl FnMut(&[u32]) -> bool) {
        let [n, e, s, w] = self.offsets;
        let labels: &mut [u32] = &mut self.labels;
        let queue: &mut [u32] = &mut self.queue;
        let mut tail = self.tail;
        let mut head = 0;
        while head < tail {
            if head % CHECK_EVERY == 0 && done(labels) {
                break;
            }
            let i = queue[head] as usize;
            head += 1;
            let d = labels[i] + 1;
            if d > max_distance {
                break;
            }
            for off in [n, e, s, w] {
                let j = i.wrapping_add_signed(off);
                if labels[j] == UNSEEN {
                    labels[j] = d;
                    queue[tail] = j as u32;
                    tail += 1;
                }
            }
        }
        self.tail = tail;
    }

    fn flood_masked(&mut self, max_distance: u32, mut done: impl FnMut(&[u32]) -> bool) {
        let offsets = self.offsets;
        let Some(moves) = self.moves.as_deref() else {
            return;
        };
        let labels: &mut [u32] = &mut self.labels;
        let spare = labels.len() - 1;
        let queue: &mut [u32] = &mut self.queue;
        let mut tail = self.tail;
        let mut head = 0;
        while head < tail {
            if head % CHECK_EVERY == 0 && done(labels) {
                break;
            }
            let i = queue[head] as usize;
            head += 1;
            let d = labels[i] + 1;
            if d > max_distance {
                break;
            }
            let m = moves[i];
            for (k, off) in offsets.into_iter().enumerate() {
                let j = i.wrapping_add_signed(off);
                let new = m & (1 << k) != 0 && labels[j] == UNSEEN;
                labels[if new { j } else { spare }] = d;
                queue[tail] = j as u32;
                tail += usize::from(new);
            }
        }
        self.tail = tail;
    }

    /// Like [`Wavefront::propagate`] but stops soon after every passable
    /// in-grid cell of `targets` is labelled (within 64 more
    /// cells; their distances, and those of every cell labelled so far,
    /// are final; targets no source reaches stay unlabelled). Returns the
    /// number of cells labelled.
    pub fn propagate_until_reached(&mut self, sources: &[Cell], targets: &[Cell]) -> usize {
        // The passable targets, each once. Labels are never taken back, so
        // a cursor over them moves past each once.
        let mut wanted: Vec<u32> = targets
            .iter()
            .filter(|&&t| self.inside(t))
            .map(|&t| self.pad(t) as u32)
            .filter(|&i| self.labels[i as usize] != BLOCKED)
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        self.seed(if wanted.is_empty() { &[] } else { sources });
        let mut next = 0;
        self.flood_until(u32::MAX, |labels| {
            while next < wanted.len() && labels[wanted[next] as usize] < UNSEEN {
                next += 1;
            }
            next == wanted.len()
        });
        self.tail
    }

    /// Core BFS by layers. After each completed layer of distance `d`,
    /// `on_layer(layer, d)` sees that layer's cells and may stop the wave by
    /// returning `true`. Distance-0 sources are the first layer; sources that are
    /// blocked or outside the grid are ignored.
    pub(crate) fn run(
        &mut self,
        sources: &[Cell],
        max_distance: u32,
        mut on_layer: impl FnMut(Layer<'_>, u32) -> bool,
    ) {
        self.seed(sources);
        let stride = self.stride;
        if on_layer(
            Layer {
                cells: &self.queue[..self.tail],
                stride,
            },
            0,
        ) {
            return;
        }
        let mut head = 0;
        let mut d = 0u32;
        while head < self.tail && d < max_distance {
            let end = self.tail;
            let limit = d;
            // Expand exactly one layer: cells labelled `d` become parents of `d + 1`.
            self.expand_layer(head, end, limit);
            d += 1;
            head = end;
            if head == self.tail {
                break;
            }
            if on_layer(
                Layer {
                    cells: &self.queue[head..self.tail],
                    stride,
                },
                d,
            ) {
                return;
            }
        }
    }

    /// Labels the unseen neighbours of `queue[from..to]` (all labelled `d`) with `d + 1`.
    fn expand_layer(&mut self, from: usize, to: usize, d: u32) {
        let offsets = self.offsets;
        let moves = self.moves.as_deref();
        let labels: &mut [u32] = &mut self.labels;
        let queue: &mut [u32] = &mut self.queue;
        let mut tail = self.tail;
        let Some(moves) = moves else {
            for qi in from..to {
                let i = queue[qi] as usize;
                for off in offsets {
                    let j = i.wrapping_add_signed(off);
                    if labels[j] == UNSEEN {
                        labels[j] = d + 1;
                        queue[tail] = j as u32;
                        tail += 1;
                    }
                }
            }
            self.tail = tail;
            return;
        };
        for qi in from..to {
            let i = queue[qi] as usize;
            let m = moves[i];
            for (k, off) in offsets.into_iter().enumerate() {
                let j = i.wrapping_add_signed(off);
                if m & (1 << k) != 0 && labels[j] == UNSEEN {
                    labels[j] = d + 1;
                    queue[tail] = j as u32;
                    tail += 1;
                }
            }
        }
        self.tail = tail;
    }

    /// Number of cells the last query labelled.
    #[must_use]
    pub fn touched(&self) -> usize {
        self.tail
    }

    /// Cells labelled by the last query, in BFS order.
    pub fn touched_cells(&self) -> impl Iterator<Item = Cell> + '_ {
        self.queue[..self.tail]
            .iter()
            .map(|&i| self.unpad(i as usize))
    }

    /// Distance of `cell` from the sources of the last query, if it was reached.
    #[must_use]
    pub fn distance(&self, cell: Cell) -> Option<u32> {
        if !self.inside(cell) {
            return None;
        }
        let l = self.labels[self.pad(cell)];
        (l < UNSEEN).then_some(l)
    }

    /// The labels of the last query as a grid (`None` = not reached or blocked).
    #[must_use]
    pub fn distances(&self) -> Grid<Option<u32>> {
        Grid::from_fn(self.width, self.height, |c| self.distance(c))
    }

    fn can_step(&self, from: usize, dir: Dir4) -> bool {
        self.moves.as_ref().is_none_or(|m| m[from] & dir.bit() != 0)
    }

    /// The shortest path from the nearest source to `target` (both included),
    /// following labels down and keeping the current direction whenever a
    /// shortest path allows it (then N, E, S, W). `None` if not reached.
    #[must_use]
    pub fn retrace(&self, target: Cell) -> Option<Vec<Cell>> {
        let mut l = self.distance(target)?;
        let mut i = self.pad(target);
        let mut path = vec![target];
        // Direction of travel of the forward path, seen from its end.
        let mut dir: Option<Dir4> = None;
        while l > 0 {
            let order = dir.into_iter().chain(Dir4::ALL);
            let mut next = None;
            for d in order {
                // Forward move was `d`, so the previous cell lies opposite.
                let back = d.opposite();
                let n = i.wrapping_add_signed(self.offsets[back.index()]);
                if self.labels[n] == l - 1 && self.can_step(n, d) {
                    next = Some((n, d));
                    break;
                }
            }
            let (n, d) = next?;
            i = n;
            dir = Some(d);
            l -= 1;
            path.push(self.unpad(i));
        }
        path.reverse();
        Some(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bfs_distances;
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::random::random_density;
    use proptest::prelude::*;

    #[test]
    fn retrace_keeps_direction() {
        let (m, _) = parse_ascii(
            "
            .....
            .....
            .....",
        )
        .unwrap();
        let mut wf = Wavefront::new(&m.free_mask());
        wf.propagate(&[Cell::new(0, 0)]);
        let p = wf.retrace(Cell::new(2, 4)).unwrap();
        // One bend: the last move is kept as long as possible going back.
        let bends = p
            .windows(3)
            .filter(|w| w[0].dir_to(w[1]) != w[1].dir_to(w[2]))
            .count();
        assert_eq!(bends, 1);
        assert_eq!(p.len(), 7);
        assert_eq!(p[0], Cell::new(0, 0));
    }

    #[test]
    fn masks_restrict_moves_and_queries_reuse_the_workspace() {
        let free = Grid::new(3, 1, true);
        let mut moves = Grid::new(3, 1, Dir4::East.bit() | Dir4::West.bit());
        moves[Cell::new(0, 1)] = Dir4::West.bit(); // one-way: 1 -> 2 closed
        let mut wf = Wavefront::with_moves(&free, &moves);
        wf.propagate(&[Cell::new(0, 0)]);
        assert_eq!(wf.distance(Cell::new(0, 1)), Some(1));
        assert_eq!(wf.distance(Cell::new(0, 2)), None);
        wf.propagate(&[Cell::new(0, 2)]);
        assert_eq!(wf.distance(Cell::new(0, 0)), Some(2));
        assert_eq!(wf.retrace(Cell::new(0, 0)).unwrap().len(), 3);
        wf.set_passable(Cell::new(0, 1), false);
        wf.propagate(&[Cell::new(0, 2)]);
        assert_eq!(wf.distance(Cell::new(0, 0)), None);
        assert_eq!(wf.touched(), 1);
    }

    /// The flood chosen is the one the share of interior cells (open
    /// cells with four open neighbours) asks for, counted cell by cell.
    #[test]
    fn the_flood_follows_the_interior_share() {
        for (i, density) in [0.0, 0.02, 0.1, 0.3, 0.6].into_iter().enumerate() {
            for (w, h) in [(1, 1), (2, 7), (3, 3), (41, 29)] {
                let free = random_density(w, h, density, i as u64).free_mask();
                let open = free.count_true();
                let interior = free
                    .cells()
                    .filter(|&c| {
                        free[c]
                            && free.neighbours4(c).count() == 4
                            && free.neighbours4(c).all(|(_, n)| free[n])
                    })
                    .count();
                let none = vec![false; w];
                let rows: usize = (0..h)
                    .map(|r| {
                        let up = if r > 0 { free.row(r - 1) } else { &none };
                        let down = if r + 1 < h { free.row(r + 1) } else { &none };
                        interior_in(up, free.row(r), down)
                    })
                    .sum();
                assert_eq!(rows, interior, "{w}x{h} at {density}");
                let wf = Wavefront::new(&free);
                assert_eq!(wf.open, open);
                assert_eq!(
                    wf.branch_free,
                    (interior as f64) < BRANCHY_ABOVE * open as f64,
                    "{w}x{h} at {density}"
                );
            }
        }
    }

    proptest! {
        #[test]
        fn equals_reference_bfs(w in 1usize..40, h in 1usize..40, density in 0.0f64..0.5, seed in any::<u64>(), sr in 0usize..40, sc in 0usize..40) {
            let map = random_density(w, h, density, seed);
            let free = map.free_mask();
            let src = Cell::new(sr % h, sc % w);
            let mut wf = Wavefront::new(&free);
            // A previous query must not leak into the next.
            wf.propagate(&[Cell::new(0, 0)]);
            wf.propagate(&[src]);
            let want = bfs_distances(&free, src);
            for c in free.cells() {
                prop_assert_eq!(wf.distance(c), want[c]);
                if let Some(d) = want[c] {
                    let p = wf.retrace(c).unwrap();
                    prop_assert_eq!(p.len(), d as usize + 1);
                    prop_assert_eq!(p[0], src);
                    prop_assert!(p.windows(2).all(|s| s[0].manhattan(s[1]) == 1 && free[s[1]]));
                }
            }
        }

        /// A search that stops once its targets are reached gives them (and
        /// every cell it labelled) the full search's distances, and labels
        /// no more cells than it.
        #[test]
        fn stopping_at_the_targets_keeps_their_distances(w in 1usize..40, h in 1usize..40, density in 0.0f64..0.5, seed in any::<u64>(), at in any::<u64>(), k in 0usize..6) {
            let free = random_density(w, h, density, seed).free_mask();
            let cell = |x: u64| Cell::new((x % h as u64) as usize, ((x / 97) % w as u64) as usize);
            let src = cell(at);
            let targets: Vec<Cell> = (1..=k as u64).map(|t| cell(at.wrapping_mul(31).wrapping_add(t * 7919))).collect();
            let mut full = Wavefront::new(&free);
            let all = full.propagate(&[src]);
            let mut part = Wavefront::new(&free);
            let some = part.propagate_until_reached(&[src], &targets);
            prop_assert!(some <= all);
            for &t in &targets {
                prop_assert_eq!(part.distance(t), full.distance(t));
            }
            for c in part.touched_cells() {
                prop_assert_eq!(part.distance(c), full.distance(c));
            }
        }
    }
}
