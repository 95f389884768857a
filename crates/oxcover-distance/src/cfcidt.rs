//! Coarse-to-fine CIDT, CFCIDT (Lee et al. 2011), made exact.
//!
//! The paper keeps a *block map* (each block = `k × k` cells) next to the fine
//! map, updated incrementally as cells are explored; it runs CIDT on the blocks
//! to find the nearest unexplored block, then a fine CIDT only inside the
//! corridor of blocks on that coarse path, and descends to the target. That
//! corridor search is fast but not exact: the true nearest target may lie
//! outside the corridor. Here it gives an *upper bound* `U` and a path, and an
//! A* search then proves or improves it:
//!
//! 1. **Coarse CIDT** over open blocks from the robot's block to the nearest
//!    block holding a target.
//! 2. **Corridor CIDT** on the fine map restricted to the blocks of that coarse
//!    path plus a one-block margin: target distance `U`.
//! 3. **Block lower bound**: a backward Dijkstra over states (block, entry
//!    direction) from every target block, bounded by `U`. Crossing a block
//!    straight costs at least its side, turning or reversing at least one move,
//!    so these costs bound the fine distance from below. The per-cell heuristic
//!    `h(x) = min_d dist(x, side d) + 1 + H(next block, d)` is admissible and
//!    consistent (a one-move change alters it by at most one).
//! 4. **A\*** on the fine map pruned at `f >= U`: it either finds a strictly
//!    nearer target or confirms the corridor's.
//!
//! The returned distance always equals a full BFS's (property-tested). Cells
//! touched = corridor + A\* cells; block states touched are counted apart. With
//! near targets both stay a small fraction of the map (see `docs/benchmarks.md`).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use oxcover_grid::{Cell, Dir4, Grid};

const INF: u32 = u32::MAX;

/// The fine map, its targets, and per-block summaries, updated incrementally.
#[derive(Clone, Debug)]
pub struct BlockMap {
    k: usize,
    width: usize,
    height: usize,
    bw: usize,
    bh: usize,
    passable: Vec<bool>,
    target: Vec<bool>,
    block_open: Vec<u32>,
    block_targets: Vec<u32>,
}

impl BlockMap {
    /// A block map over `passable` with `block × block` blocks (0 is taken as 1); no targets yet.
    #[must_use]
    pub fn new(passable: &Grid<bool>, block: usize) -> Self {
        let k = block.max(1);
        let (w, h) = (passable.width(), passable.height());
        let (bw, bh) = (w.div_ceil(k), h.div_ceil(k));
        let mut block_open = vec![0u32; bw * bh];
        for c in passable.true_cells() {
            block_open[(c.row / k) * bw + c.col / k] += 1;
        }
        Self {
            k,
            width: w,
            height: h,
            bw,
            bh,
            passable: passable.as_slice().to_vec(),
            target: vec![false; w * h],
            block_open,
            block_targets: vec![0; bw * bh],
        }
    }

    fn block_index(&self, c: Cell) -> usize {
        (c.row / self.k) * self.bw + c.col / self.k
    }

    fn idx(&self, c: Cell) -> usize {
        c.row * self.width + c.col
    }

    /// Marks or unmarks a cell as a target (e.g. "unexplored").
    pub fn set_target(&mut self, cell: Cell, target: bool) {
        if cell.row >= self.height || cell.col >= self.width {
            return;
        }
        let i = self.idx(cell);
        if self.target[i] == target {
            return;
        }
        self.target[i] = target;
        if self.passable[i] {
            let b = self.block_index(cell);
            if target {
                self.block_targets[b] += 1;
            } else {
                self.block_targets[b] -= 1;
            }
        }
    }

    /// Changes the passability of a cell.
    pub fn set_passable(&mut self, cell: Cell, passable: bool) {
        if cell.row >= self.height || cell.col >= self.width {
            return;
        }
        let i = self.idx(cell);
        if self.passable[i] == passable {
            return;
        }
        self.passable[i] = passable;
        let b = self.block_index(cell);
        if passable {
            self.block_open[b] += 1;
        } else {
            self.block_open[b] -= 1;
        }
        if self.target[i] {
            if passable {
                self.block_targets[b] += 1;
            } else {
                self.block_targets[b] -= 1;
            }
        }
    }

    /// Row-major indices of the passable 4-neighbours of cell index `i`.
    fn open_neighbours(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        let (r, c) = (i / self.width, i % self.width);
        Dir4::ALL.into_iter().filter_map(move |d| {
            let (dr, dc) = d.offset();
            let (r, c) = (r.checked_add_signed(dr)?, c.checked_add_signed(dc)?);
            let j = r * self.width + c;
            (r < self.height && c < self.width && self.passable[j]).then_some(j)
        })
    }

    /// Whether `cell` is a passable target.
    #[must_use]
    pub fn is_target(&self, cell: Cell) -> bool {
        cell.row < self.height && cell.col < self.width && {
            let i = self.idx(cell);
            self.target[i] && self.passable[i]
        }
    }

    /// Whether `cell` is passable.
    #[must_use]
    pub fn is_passable(&self, cell: Cell) -> bool {
        cell.row < self.height && cell.col < self.width && self.passable[self.idx(cell)]
    }

    /// Number of passable targets.
    #[must_use]
    pub fn target_count(&self) -> usize {
        self.block_targets.iter().map(|&n| n as usize).sum()
    }

    /// Fine cells per block side.
    #[must_use]
    pub fn block_size(&self) -> usize {
        self.k
    }

    /// `(rows, cols)` extent of block `b` along the axis of `d`.
    fn extent(&self, b: usize, d: usize) -> u32 {
        let (br, bc) = (b / self.bw, b % self.bw);
        if d % 2 == 0 {
            (((br + 1) * self.k).min(self.height) - br * self.k) as u32
        } else {
            (((bc + 1) * self.k).min(self.width) - bc * self.k) as u32
        }
    }

    /// A lower bound on the distance from `source` to any target: along an
    /// axis where a target's block is `m > 0` blocks away, the target is at
    /// least `(m - 1) * k + 1` cells away; a target in the source's own
    /// block (not the source) at least 1 move.
    fn block_lower_bound(&self, source: Cell) -> u32 {
        let (sr, sc) = (source.row / self.k, source.col / self.k);
        let axis = |m: usize| if m == 0 { 0 } else { (m - 1) * self.k + 1 };
        let best = self
            .block_targets
            .iter()
            .enumerate()
            .filter(|&(_, &n)| n > 0)
            .map(|(b, _)| axis((b / self.bw).abs_diff(sr)) + axis((b % self.bw).abs_diff(sc)))
            .min();
        best.map_or(u32::MAX, |d| d.max(1) as u32)
    }

    fn block_step(&self, b: usize, d: usize) -> Option<usize> {
        let (br, bc) = (b / self.bw, b % self.bw);
        let (dr, dc) = Dir4::from_index(d).offset();
        let r = br.checked_add_signed(dr)?;
        let c = bc.checked_add_signed(dc)?;
        (r < self.bh && c < self.bw).then_some(r * self.bw + c)
    }
}

/// The result of a coarse-to-fine search.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoarseToFineFound {
    /// The target reached.
    pub target: Cell,
    /// Its distance in moves (equal to a full BFS's nearest-target distance).
    pub distance: u32,
    /// A shortest path from the source to `target`, both included.
    pub path: Vec<Cell>,
    /// Fine cells labelled (corridor search + A\*).
    pub fine_touched: usize,
    /// Blocks and block states labelled (coarse search + lower bound).
    pub coarse_touched: usize,
    /// A distance no target can be nearer than: `distance` itself for the
    /// exact search; for [`CoarseToFine::corridor_nearest`] the block
    /// Manhattan bound, so `distance / lower_bound` bounds its detour.
    pub lower_bound: u32,
}

impl CoarseToFineFound {
    /// The answer when the source is itself a target.
    fn at_source(source: Cell) -> Self {
        Self {
            target: source,
            distance: 0,
            path: vec![source],
            fine_touched: 1,
            coarse_touched: 0,
            lower_bound: 0,
        }
    }
}

/// Reusable scratch for [`CoarseToFine::nearest`].
#[derive(Clone, Debug, Default)]
pub struct CoarseToFine {
    g: Vec<u32>,
    parent: Vec<u32>,
    stamp: Vec<u32>,
    epoch: u32,
    hstate: Vec<u32>,
    bparent: Vec<u32>,
    corridor: Vec<bool>,
}

impl CoarseToFine {
    /// Empty scratch; it grows to the map on first use.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    fn next_epoch(&mut self, n: usize) {
        if self.stamp.len() != n {
            self.stamp = vec![0; n];
            self.g = vec![INF; n];
            self.parent = vec![0; n];
            self.epoch = 0;
        }
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.fill(0);
            self.epoch = 1;
        }
    }

    fn g_of(&self, i: usize) -> u32 {
        if self.stamp[i] == self.epoch {
            self.g[i]
        } else {
            INF
        }
    }

    fn path_to(&self, map: &BlockMap, mut i: usize, source: usize) -> Vec<Cell> {
        let mut path = vec![Cell::new(i / map.width, i % map.width)];
        while i != source {
            i = self.parent[i] as usize;
            path.push(Cell::new(i / map.width, i % map.width));
        }
        path.reverse();
        path
    }

    /// Breadth-first search over open blocks from block `sb` to the nearest
    /// block holding a target (`bparent` keeps the tree); the goal block and
    /// the blocks labelled.
    fn coarse_search(&mut self, map: &BlockMap, sb: usize) -> (Option<usize>, usize) {
        let nb = map.bw * map.bh;
        self.bparent.clear();
        self.bparent.resize(nb, INF);
        let mut q = VecDeque::from([sb]);
        self.bparent[sb] = sb as u32;
        let mut touched = 0;
        while let Some(b) = q.pop_front() {
            touched += 1;
            if map.block_targets[b] > 0 {
                return (Some(b), touched);
            }
            for d in 0..4 {
                if let Some(nbk) = map.block_step(b, d)
                    && map.block_open[nbk] > 0
                    && self.bparent[nbk] == INF
                {
                    self.bparent[nbk] = b as u32;
                    q.push_back(nbk);
                }
            }
        }
        (None, touched)
    }

    /// Marks the corridor: the blocks of the coarse path from `sb` to
    /// `goal`, each with the blocks within `margin` of it.
    fn mark_corridor(&mut self, map: &BlockMap, goal: usize, sb: usize, margin: usize) {
        let nb = map.bw * map.bh;
        self.corridor.clear();
        self.corridor.resize(nb, false);
        let mut b = goal;
        loop {
            let (br, bc) = (b / map.bw, b % map.bw);
            for r in br.saturating_sub(margin)..(br + margin + 1).min(map.bh) {
                for c in bc.saturating_sub(margin)..(bc + margin + 1).min(map.bw) {
                    self.corridor[r * map.bw + c] = true;
                }
            }
            if b == sb {
                break;
            }
            b = self.bparent[b] as usize;
        }
    }

    /// Breadth-first search on the fine map inside the corridor from `src`,
    /// finishing the first layer that holds a target: `(distance, the
    /// row-major first target of that layer)` and the cells labelled.
    fn corridor_bfs(&mut self, map: &BlockMap, src: usize) -> (Option<(u32, usize)>, usize) {
        self.next_epoch(map.width * map.height);
        let mut layer = vec![src];
        self.g[src] = 0;
        self.stamp[src] = self.epoch;
        let mut touched = 1;
        let mut d = 0;
        while !layer.is_empty() {
            d += 1;
            let mut next = Vec::new();
            for &i in &layer {
                for j in map.open_neighbours(i) {
                    let nc = Cell::new(j / map.width, j % map.width);
                    if self.stamp[j] == self.epoch || !self.corridor[map.block_index(nc)] {
                        continue;
                    }
                    self.stamp[j] = self.epoch;
                    self.g[j] = d;
                    self.parent[j] = i as u32;
                    touched += 1;
                    next.push(j);
                }
            }
            if let Some(t) = next.iter().copied().filter(|&j| map.target[j]).min() {
                return (Some((d, t)), touched);
            }
            layer = next;
        }
        (None, touched)
    }

    /// The coarse-to-fine search as Lee et al. 2011 describe it, without a
    /// proof of optimality: the nearest target block on the block map, then
    /// a fine search only inside the corridor of blocks along that coarse
    /// path (one block of margin). Where the corridor holds no reachable
    /// target (the coarse path crosses blocks that are open but not
    /// connected inside), the margin doubles until it does, up to the whole
    /// map.
    ///
    /// The distance is that of a real path but not always the shortest: the
    /// nearest target may lie outside the corridor, or be nearer by a route
    /// leaving it. [`Self::nearest`] is the exact search;
    /// `docs/benchmarks.md` measures this one's detour against CIDT's
    /// distance, and its property test bounds it on random maps.
    pub fn corridor_nearest(&mut self, map: &BlockMap, source: Cell) -> Option<CoarseToFineFound> {
        if !map.is_passable(source) {
            return None;
        }
        if map.is_target(source) {
            return Some(CoarseToFineFound::at_source(source));
        }
        let src = map.idx(source);
        let sb = map.block_index(source);
        let (goal, coarse_touched) = self.coarse_search(map, sb);
        let goal = goal?;
        let mut fine_touched = 0;
        let mut margin = 1;
        loop {
            self.mark_corridor(map, goal, sb, margin);
            let (hit, touched) = self.corridor_bfs(map, src);
            fine_touched += touched;
            if let Some((d, t)) = hit {
                return Some(CoarseToFineFound {
                    target: Cell::new(t / map.width, t % map.width),
                    distance: d,
                    path: self.path_to(map, t, src),
                    fine_touched,
                    coarse_touched,
                    lower_bound: map.block_lower_bound(source).min(d),
                });
            }
            if margin >= map.bw.max(map.bh) {
                return None;
            }
            margin *= 2;
        }
    }

    /// Nearest passable target from `source`, with a shortest path to it.
    pub fn nearest(&mut self, map: &BlockMap, source: Cell) -> Option<CoarseToFineFound> {
        if !map.is_passable(source) {
            return None;
        }
        let n = map.width * map.height;
        let src = map.idx(source);
        if map.is_target(source) {
            return Some(CoarseToFineFound::at_source(source));
        }
        let nb = map.bw * map.bh;
        let sb = map.block_index(source);
        // 1. Coarse CIDT over open blocks.
        let (goal_block, mut coarse_touched) = self.coarse_search(map, sb);
        let goal_block = goal_block?;
        // 2. Corridor CIDT: blocks of the coarse path plus a one-block margin.
        self.mark_corridor(map, goal_block, sb, 1);
        let (hit, mut fine_touched) = self.corridor_bfs(map, src);
        let upper = hit.map(|(d, t)| (d, self.path_to(map, t, src)));
        let bound = upper.as_ref().map_or(INF, |(d, _)| *d);

        // 3. Backward Dijkstra over (block, entry direction) states.
        self.hstate.clear();
        self.hstate.resize(nb * 4, INF);
        let mut heap = BinaryHeap::new();
        for b in 0..nb {
            if map.block_targets[b] > 0 {
                for d in 0..4 {
                    self.hstate[b * 4 + d] = 0;
                    heap.push(Reverse((0u32, b * 4 + d)));
                }
            }
        }
        let mut settled = vec![false; nb * 4];
        while let Some(Reverse((v, s))) = heap.pop() {
            if v >= bound {
                break;
            }
            if settled[s] || v > self.hstate[s] {
                continue;
            }
            settled[s] = true;
            coarse_touched += 1;
            let (bp, dp) = (s / 4, s % 4);
            // Predecessor block: the one that reaches `bp` by moving `dp`.
            let Some(b) = map.block_step(bp, (dp + 2) % 4) else {
                continue;
            };
            if map.block_open[b] == 0 || map.block_targets[b] > 0 {
                continue;
            }
            for d in 0..4 {
                let inner = if d == dp { map.extent(b, dp) - 1 } else { 0 };
                let cand = v.saturating_add(inner + 1);
                let t = b * 4 + d;
                if cand < self.hstate[t] {
                    self.hstate[t] = cand;
                    heap.push(Reverse((cand, t)));
                }
            }
        }
        // Unsettled states have H >= bound (or are unreachable when unbounded).
        for (h, s) in self.hstate.iter_mut().zip(&settled) {
            if !s {
                *h = bound;
            }
        }

        // 4. A* pruned at f >= bound.
        self.next_epoch(n);
        let h_of = |this: &Self, c: Cell| -> u32 {
            let b = map.block_index(c);
            if map.block_targets[b] > 0 {
                return 0;
            }
            let (br, bc) = (b / map.bw, b % map.bw);
            let r0 = br * map.k;
            let r1 = ((br + 1) * map.k).min(map.height) - 1;
            let c0 = bc * map.k;
            let c1 = ((bc + 1) * map.k).min(map.width) - 1;
            let side = [c.row - r0, c1 - c.col, r1 - c.row, c.col - c0];
            let mut best = INF;
            for (d, &to_side) in side.iter().enumerate() {
                let Some(nbk) = map.block_step(b, d) else {
                    continue;
                };
                if map.block_open[nbk] == 0 {
                    continue;
                }
                let hv = this.hstate[nbk * 4 + d];
                if hv == INF {
                    continue;
                }
                best = best.min((to_side as u32 + 1).saturating_add(hv));
            }
            best
        };
        let mut found: Option<(u32, usize)> = None;
        let h0 = h_of(self, source);
        if h0 < bound {
            let mut open = BinaryHeap::new();
            self.stamp[src] = self.epoch;
            self.g[src] = 0;
            fine_touched += 1;
            open.push(Reverse((h0, h0, src)));
            while let Some(Reverse((f, h, i))) = open.pop() {
                let g = f - h;
                if g > self.g_of(i) {
                    continue;
                }
                if map.target[i] && map.passable[i] {
                    found = Some((g, i));
                    break;
                }
                for j in map.open_neighbours(i) {
                    let ng = g + 1;
                    if ng >= self.g_of(j) {
                        continue;
                    }
                    let hj = h_of(self, Cell::new(j / map.width, j % map.width));
                    let f = ng.saturating_add(hj);
                    if f >= bound {
                        continue;
                    }
                    if self.stamp[j] != self.epoch {
                        fine_touched += 1;
                    }
                    self.stamp[j] = self.epoch;
                    self.g[j] = ng;
                    self.parent[j] = i as u32;
                    open.push(Reverse((f, hj, j)));
                }
            }
        }
        match (found, upper) {
            (Some((d, t)), _) => Some(CoarseToFineFound {
                target: Cell::new(t / map.width, t % map.width),
                distance: d,
                path: self.path_to(map, t, src),
                fine_touched,
                coarse_touched,
                lower_bound: d,
            }),
            (None, Some((d, path))) => Some(CoarseToFineFound {
                target: *path.last().unwrap_or(&source),
                distance: d,
                path,
                fine_touched,
                coarse_touched,
                lower_bound: d,
            }),
            (None, None) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bfs_distances;
    use oxcover_grid::random::random_density;
    use proptest::prelude::*;

    /// A seeded random map with random targets, its block map, the source
    /// (first free cell) and the exact nearest-target distance.
    struct Case {
        free: Grid<bool>,
        targets: Grid<bool>,
        src: Cell,
        want: Option<u32>,
        map: BlockMap,
    }

    fn case(
        w: usize,
        h: usize,
        density: f64,
        seed: u64,
        target_density: f64,
        k: usize,
    ) -> Option<Case> {
        let free = random_density(w, h, density, seed).free_mask();
        let targets = random_density(w, h, 1.0 - target_density, seed ^ 0xface)
            .free_mask()
            .map(|f| !f);
        let src = free.true_cells().next()?;
        let full = bfs_distances(&free, src);
        let want = free
            .cells()
            .filter(|&c| targets[c])
            .filter_map(|c| full[c])
            .min();
        let mut map = BlockMap::new(&free, k);
        for c in targets.true_cells() {
            map.set_target(c, true);
        }
        Some(Case {
            free,
            targets,
            src,
            want,
            map,
        })
    }

    proptest! {
        #[test]
        fn same_distance_as_full_bfs(w in 2usize..60, h in 2usize..60, density in 0.0f64..0.45, seed in any::<u64>(), target_density in 0.0f64..0.05, k in 1usize..9) {
            let Some(Case { free, targets, src, want, mut map }) = case(w, h, density, seed, target_density, k) else { return Ok(()); };
            let mut search = CoarseToFine::new();
            let got = search.nearest(&map, src);
            prop_assert_eq!(got.as_ref().map(|f| f.distance), want);
            if let Some(f) = got {
                prop_assert!(targets[f.target] && free[f.target]);
                prop_assert_eq!(f.path.len() as u32, f.distance + 1);
                prop_assert_eq!(f.path[0], src);
                prop_assert_eq!(*f.path.last().unwrap(), f.target);
                prop_assert!(f.path.windows(2).all(|s| s[0].manhattan(s[1]) == 1 && free[s[1]]));
            }
            // Reuse: clearing the targets leaves nothing to find.
            for c in targets.true_cells() {
                map.set_target(c, false);
            }
            prop_assert_eq!(map.target_count(), 0);
            prop_assert!(search.nearest(&map, src).is_none());
        }
    }

    proptest! {
        /// The corridor search of the paper finds a real path to a target
        /// whenever one exists, never shorter than the exact distance, and
        /// its lower bound holds.
        #[test]
        fn corridor_search_is_a_valid_upper_bound(w in 2usize..60, h in 2usize..60, density in 0.0f64..0.45, seed in any::<u64>(), target_density in 0.0f64..0.05, k in 1usize..9) {
            let Some(Case { free, targets, src, want, map }) = case(w, h, density, seed, target_density, k) else { return Ok(()); };
            let got = CoarseToFine::new().corridor_nearest(&map, src);
            prop_assert_eq!(got.is_some(), want.is_some());
            if let (Some(f), Some(want)) = (got, want) {
                prop_assert!(f.distance >= want);
                prop_assert!(f.lower_bound <= want, "bound {} above the true {}", f.lower_bound, want);
                prop_assert!(targets[f.target] && free[f.target]);
                prop_assert_eq!(f.path.len() as u32, f.distance + 1);
                prop_assert_eq!(f.path[0], src);
                prop_assert!(f.path.windows(2).all(|s| s[0].manhattan(s[1]) == 1 && free[s[1]]));
            }
        }
    }

    /// Two rooms joined by a door far from the straight line: the block
    /// path runs along open blocks that do not connect inside, so the
    /// corridor widens until it holds the door.
    #[test]
    fn the_corridor_widens_round_a_wall() {
        let mut free = Grid::new(64, 64, true);
        for r in 0..60 {
            free[Cell::new(r, 32)] = false;
        }
        let mut map = BlockMap::new(&free, 8);
        map.set_target(Cell::new(2, 40), true);
        let f = CoarseToFine::new()
            .corridor_nearest(&map, Cell::new(2, 24))
            .unwrap();
        let exact = CoarseToFine::new().nearest(&map, Cell::new(2, 24)).unwrap();
        assert_eq!(exact.distance, 16 + 2 * 58);
        assert_eq!(f.distance, exact.distance);
        assert!(f.lower_bound <= exact.distance);
    }

    #[test]
    fn near_target_on_an_open_map_touches_little() {
        let free = Grid::new(512, 512, true);
        let mut map = BlockMap::new(&free, 16);
        map.set_target(Cell::new(300, 340), true);
        let f = CoarseToFine::new()
            .nearest(&map, Cell::new(300, 300))
            .unwrap();
        assert_eq!(f.distance, 40);
        assert!(f.fine_touched < 512 * 512 / 20, "{}", f.fine_touched);
    }
}
