//! The exact minimum number of moves, MNP (Siamantas 2010's yardstick `PI_opt = MNP / ANP`).
//!
//! The shortest open walk from the start that visits every coverage cell,
//! 4-connected. A covering walk traverses a multiset `H` of grid edges that is
//! connected, spans every cell, and has an Eulerian trail from the start: all
//! degrees even, or exactly the start and one other cell odd. Conversely every
//! such `H` is walked in `|H|` moves. An optimal `H` never uses an edge more
//! than twice (removing two copies keeps parity and connectivity), so
//!
//! > MNP = min |H| over edge multiplicities in {0, 1, 2} with `H` connected,
//! > spanning, and odd vertices ⊆ {start, one more}.
//!
//! That is solved exactly by **frontier dynamic programming** (the "plug DP"
//! of grid path counting): cells are processed row by row along the longer side;
//! a state records, for the `w + 1` edges crossing the processed/unprocessed
//! boundary, their multiplicity and which processed component each comes from,
//! plus the number of odd vertices so far. Components may only close when
//! nothing else is left. One bounded run looks for a walk shorter than the
//! best heuristic one (Grid_Cover, or DTC towards its best goal); states whose
//! cost plus a lower bound on the edges still needed (connectivity, degree
//! parity, dead ends) reach that length are pruned. Finding none proves the
//! heuristic walk optimal.
//! Cost O(cells · states), states bounded by `3^(w+1)` times the non-crossing
//! partitions of the frontier: 75 ms per map on average for Siamantas 2010's 8×8
//! maps (0.8 s at worst), heavy beyond a width of about 12.
//! The walk is recovered from the DP's back-pointers by Hierholzer's algorithm.
//!
//! Limits: the coverage grid's shorter side must be at most
//! [`Optimal::MAX_WIDTH`] cells, and a state budget stops the DP (then
//! the best heuristic walk is returned with a proven lower bound, `proven =
//! false`). [`lower_bound`] gives that bound (count, chessboard parity, dead
//! ends) on any size without the DP.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::time::{Duration, Instant};

use oxcover_grid::{Cell, CoarseGrid, Dir4, Grid};

use crate::error::{Error, Result};
use crate::full_dtc::full_dtc;
use crate::grid_cover::grid_cover;
use crate::planner::{Planner, steps};
use crate::problem::{PlanOutput, PlannerInput};

/// A multiply-xorshift hasher for the packed `u128` states (SipHash's
/// DoS resistance buys nothing here and costs half the DP's time).
#[derive(Default)]
struct StateHasher(u64);

impl Hasher for StateHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn write_u128(&mut self, v: u128) {
        let x = (v as u64) ^ ((v >> 64) as u64).rotate_left(29);
        let x = (x ^ (x >> 31)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        self.0 = x ^ (x >> 29);
    }
}

type StateMap = HashMap<u128, u32, BuildHasherDefault<StateHasher>>;

/// The `optimal` planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Optimal {
    /// DP states the search may create before giving up (deterministic
    /// budget; memory is about 32 bytes per state). Default 10 million: the
    /// hardest of Siamantas 2010's 8×8 maps needs about 4 million.
    pub max_states: usize,
    /// Optional wall-clock budget; results then depend on the machine.
    pub time_budget: Option<Duration>,
}

impl Default for Optimal {
    fn default() -> Self {
        Self::new()
    }
}

impl Optimal {
    /// Largest frontier (shorter side of the coverage grid) accepted.
    pub const MAX_WIDTH: usize = 16;

    /// The planner with the default state budget and no time budget.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            max_states: 10_000_000,
            time_budget: None,
        }
    }

    /// Sets the state budget.
    #[must_use]
    pub const fn max_states(mut self, n: usize) -> Self {
        self.max_states = n;
        self
    }

    /// Sets a wall-clock budget.
    #[must_use]
    pub const fn time_budget(mut self, t: Duration) -> Self {
        self.time_budget = Some(t);
        self
    }
}

impl Planner for Optimal {
    fn name(&self) -> &'static str {
        "optimal"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "exact minimum-move covering walk (frontier DP; coverage grid's shorter side <= 16)"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Coverage(
            optimal(input.coarse, input.start, self)?.path,
        ))
    }
}

/// The result of [`optimal`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OptimalResult {
    /// The best walk found (coverage cells from the start).
    pub path: Vec<Cell>,
    /// Its moves.
    pub steps: usize,
    /// A proven lower bound on the minimum (equals `steps` when `proven`).
    pub lower_bound: usize,
    /// Whether `steps` is proven minimal.
    pub proven: bool,
    /// DP states created.
    pub states: u64,
}

/// The coverage cells reachable from `start` (4-connected through coverage moves).
fn reachable(coarse: &CoarseGrid, start: Cell) -> Grid<bool> {
    let passable = coarse.passable();
    let mut seen = Grid::new(coarse.width(), coarse.height(), false);
    let mut stack = vec![start];
    seen[start] = true;
    while let Some(c) = stack.pop() {
        for d in Dir4::ALL {
            if !coarse.can_move(c, d) {
                continue;
            }
            if let Some(n) = passable.step(c, d) {
                if !seen[n] {
                    seen[n] = true;
                    stack.push(n);
                }
            }
        }
    }
    seen
}

/// The lower bound used by [`optimal`] when it cannot finish, and by the
/// experiments on large grids: `max(count, parity, dead ends)` with
/// count = cells − 1, parity = moves alternate chessboard colours, dead ends =
/// every degree-1 cell but the start and the last needs an extra move back.
#[must_use]
pub fn lower_bound(coarse: &CoarseGrid, start: Cell) -> usize {
    let seen = reachable(coarse, start);
    let (mut n, mut odd, mut leaves) = (0usize, 0usize, 0usize);
    for c in seen.true_cells() {
        n += 1;
        odd += (c.row + c.col) % 2;
        let deg = Dir4::ALL
            .iter()
            .filter(|&&d| coarse.can_move(c, d) && seen.step(c, d).is_some_and(|m| seen[m]))
            .count();
        if deg == 1 && c != start {
            leaves += 1;
        }
    }
    if n <= 1 {
        return 0;
    }
    let start_odd = (start.row + start.col) % 2 == 1;
    let u = n - 1;
    let u_odd = odd - usize::from(start_odd);
    let (same, opp) = if start_odd {
        (u_odd, u - u_odd)
    } else {
        (u - u_odd, u_odd)
    };
    let parity = (2 * opp).saturating_sub(1).max(2 * same);
    u.max(parity).max(u + leaves.saturating_sub(1))
}

/// Cells in processing order: rows along the longer side, so the frontier is
/// the shorter side. `right` / `down` are the two forward edges of a cell.
struct Layout {
    w: usize,
    h: usize,
    transposed: bool,
}

impl Layout {
    fn cell(&self, i: usize) -> Cell {
        let (r, c) = (i / self.w, i % self.w);
        if self.transposed {
            Cell::new(c, r)
        } else {
            Cell::new(r, c)
        }
    }
    /// Original direction of the processing "right" and "down" edges.
    fn dirs(&self) -> (Dir4, Dir4) {
        if self.transposed {
            (Dir4::South, Dir4::East)
        } else {
            (Dir4::East, Dir4::South)
        }
    }
}

/// A frontier state: `w` down-edges then the right-edge, each with its
/// multiplicity (0..=2) and component label; odd-vertex bookkeeping.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct State {
    mult: [u8; 17],
    label: [u8; 17],
    odd: u8,
    s_odd: bool,
    finished: bool,
}

impl State {
    fn pack(&self, w: usize) -> u128 {
        let mut k = 0u128;
        for j in 0..=w {
            k = (k << 7) | (u128::from(self.mult[j]) << 5) | u128::from(self.label[j]);
        }
        (k << 4)
            | (u128::from(self.odd) << 2)
            | (u128::from(self.s_odd) << 1)
            | u128::from(self.finished)
    }

    fn unpack(mut k: u128, w: usize) -> Self {
        let finished = k & 1 == 1;
        let s_odd = (k >> 1) & 1 == 1;
        let odd = ((k >> 2) & 3) as u8;
        k >>= 4;
        let mut s = State {
            mult: [0; 17],
            label: [0; 17],
            odd,
            s_odd,
            finished,
        };
        for j in (0..=w).rev() {
            s.label[j] = (k & 31) as u8;
            s.mult[j] = ((k >> 5) & 3) as u8;
            k >>= 7;
        }
        s
    }

    /// Renumbers labels 1.. in order of first appearance; returns how many.
    fn normalise(&mut self, w: usize) -> u8 {
        let mut map = [0u8; 40];
        let mut next = 0u8;
        for j in 0..=w {
            let l = self.label[j] as usize;
            if l == 0 {
                continue;
            }
            if map[l] == 0 {
                next += 1;
                map[l] = next;
            }
            self.label[j] = map[l];
        }
        next
    }
}

struct Entry {
    key: u128,
    cost: u32,
    prev: u32,
    x: u8,
    y: u8,
}

/// Searches for the minimum walk from `start` visiting every coverage cell reachable from it.
///
/// # Errors
/// [`Error::TooWide`] when both sides of the coverage grid exceed
/// [`Optimal::MAX_WIDTH`]; the heuristics' own errors.
pub fn optimal(coarse: &CoarseGrid, start: Cell, params: &Optimal) -> Result<OptimalResult> {
    let free = reachable(coarse, start);
    let n = free.count_true();
    let (gw, gh) = (coarse.width(), coarse.height());
    let transposed = gw > gh;
    let (w, h) = if transposed { (gh, gw) } else { (gw, gh) };
    if w > Optimal::MAX_WIDTH {
        return Err(Error::TooWide {
            planner: "optimal",
            width: gw,
            height: gh,
            limit: Optimal::MAX_WIDTH,
            hint: " (exact search; use grid-cover or dtc, or a larger tool radius)",
        });
    }
    // Upper bound and fallback from the heuristics: Grid_Cover and the best
    // DTC goal (full DTC is cheap at the sizes this DP handles).
    let mut best = grid_cover(coarse, start)?;
    if n <= 4096 {
        if let Ok(fd) = full_dtc(coarse, start) {
            if steps(&fd.shortest) < steps(&best) {
                best = fd.shortest;
            }
        }
    }
    let lb = lower_bound(coarse, start);
    if n <= 1 || steps(&best) <= lb {
        let s = steps(&best);
        return Ok(OptimalResult {
            path: best,
            steps: s,
            lower_bound: s,
            proven: true,
            states: 0,
        });
    }
    let layout = Layout { w, h, transposed };
    let problem = Problem::new(coarse, &free, start, layout);
    let deadline = params.time_budget.map(|t| Instant::now() + t);
    // One bounded run: the cheapest walk shorter than the heuristic one, or a
    // proof that there is none. (Deepening the bound from the lower bound
    // instead was measured slower: the gap to the optimum is often ten moves,
    // and each failed bound repeats most of the work.)
    let mut created = 0u64;
    if steps(&best) > lb {
        match problem.solve(
            steps(&best) as u32 - 1,
            params.max_states,
            deadline,
            &mut created,
        ) {
            Outcome::Found(path) => {
                let s = steps(&path);
                return Ok(OptimalResult {
                    path,
                    steps: s,
                    lower_bound: s,
                    proven: true,
                    states: created,
                });
            }
            Outcome::None => {}
            Outcome::Aborted => {
                return Ok(OptimalResult {
                    steps: steps(&best),
                    path: best,
                    lower_bound: lb,
                    proven: false,
                    states: created,
                });
            }
        }
    }
    // Nothing shorter than the heuristic walk exists.
    let s = steps(&best);
    Ok(OptimalResult {
        path: best,
        steps: s,
        lower_bound: s,
        proven: true,
        states: created,
    })
}

/// What one bounded DP run found.
enum Outcome {
    /// A walk within the bound (the shortest such).
    Found(Vec<Cell>),
    /// No walk within the bound.
    None,
    /// A budget ran out.
    Aborted,
}

/// The DP's view of the problem, in processing order.
struct Problem {
    layout: Layout,
    is_free: Vec<bool>,
    can_right: Vec<bool>,
    can_down: Vec<bool>,
    suffix: Vec<usize>,
    /// Dead ends (degree-1 cells other than the start) from index `i` on.
    leaf_suffix: Vec<usize>,
    s_index: usize,
}

impl Problem {
    fn new(coarse: &CoarseGrid, free: &Grid<bool>, start: Cell, layout: Layout) -> Self {
        let (w, h) = (layout.w, layout.h);
        let (right_dir, down_dir) = layout.dirs();
        let total = w * h;
        let is_free: Vec<bool> = (0..total).map(|i| free[layout.cell(i)]).collect();
        let edge = |i: usize, d: Dir4| -> bool {
            let c = layout.cell(i);
            coarse.can_move(c, d) && free.step(c, d).is_some_and(|m| free[m])
        };
        let can_right = (0..total)
            .map(|i| is_free[i] && i % w + 1 < w && edge(i, right_dir))
            .collect();
        let can_down = (0..total)
            .map(|i| is_free[i] && i / w + 1 < h && edge(i, down_dir))
            .collect();
        let mut suffix = vec![0usize; total + 1];
        for i in (0..total).rev() {
            suffix[i] = suffix[i + 1] + usize::from(is_free[i]);
        }
        let s_index = (0..total).find(|&i| layout.cell(i) == start).unwrap_or(0);
        let mut leaf_suffix = vec![0usize; total + 1];
        for i in (0..total).rev() {
            let c = layout.cell(i);
            let deg = Dir4::ALL
                .iter()
                .filter(|&&d| coarse.can_move(c, d) && free.step(c, d).is_some_and(|m| free[m]))
                .count();
            let leaf = is_free[i] && deg == 1 && i != s_index;
            leaf_suffix[i] = leaf_suffix[i + 1] + usize::from(leaf);
        }
        Self {
            layout,
            is_free,
            can_right,
            can_down,
            suffix,
            leaf_suffix,
            s_index,
        }
    }

    /// The shortest walk of at most `ub` moves, if any.
    fn solve(
        &self,
        ub: u32,
        max_states: usize,
        deadline: Option<Instant>,
        created: &mut u64,
    ) -> Outcome {
        let (w, total, s_index) = (self.layout.w, self.is_free.len(), self.s_index);
        let (is_free, can_right, can_down, suffix) =
            (&self.is_free, &self.can_right, &self.can_down, &self.suffix);
        let initial = State {
            mult: [0; 17],
            label: [0; 17],
            odd: 0,
            s_odd: false,
            finished: false,
        };
        let mut layers: Vec<Vec<Entry>> = vec![vec![Entry {
            key: initial.pack(w),
            cost: 0,
            prev: u32::MAX,
            x: 0,
            y: 0,
        }]];
        for i in 0..total {
            let c = i % w;
            let prev_layer = &layers[i];
            let mut index =
                StateMap::with_capacity_and_hasher(prev_layer.len() * 2, Default::default());
            let mut next: Vec<Entry> = Vec::with_capacity(prev_layer.len() * 2);
            let remaining = suffix[i + 1];
            let leaves = self.leaf_suffix[i + 1];
            for (pi, e) in prev_layer.iter().enumerate() {
                let f = State::unpack(e.key, w);
                let (a, la) = (f.mult[w], f.label[w]);
                let (b, lb_) = (f.mult[c], f.label[c]);
                let mut emit = |mut s: State, x: u8, y: u8| {
                    let k = s.normalise(w);
                    let cost = e.cost + u32::from(x) + u32::from(y);
                    // Edges still needed: the remaining cells and the k frontier
                    // components must end connected; frontier edges already count.
                    let frontier = (0..=w).filter(|&j| s.mult[j] > 0).count();
                    let frontier_mult: usize = (0..=w).map(|j| usize::from(s.mult[j])).sum();
                    // Odd vertices still allowed.
                    let slots = if i >= s_index {
                        if s.s_odd { 2 - usize::from(s.odd) } else { 0 }
                    } else {
                        2 - usize::from(s.odd).min(1)
                    };
                    // Connectivity: the remaining cells and the k frontier
                    // components end connected; frontier edges are paid already.
                    let connect = (remaining + k as usize)
                        .saturating_sub(1)
                        .saturating_sub(frontier);
                    // Parity: remaining cells end with even degree >= 2, but for
                    // the odd slots (>= 1); their degrees sum to twice the later
                    // edges plus the frontier multiplicities.
                    let parity = (2 * remaining)
                        .saturating_sub(slots + frontier_mult)
                        .div_ceil(2);
                    // Dead ends: odd (a slot) or their only edge doubled, one more
                    // edge unless that edge is a frontier edge, already paid.
                    let need = connect.max(parity) + leaves.saturating_sub(slots + frontier);
                    if cost as usize + need > ub as usize {
                        return;
                    }
                    let key = s.pack(w);
                    *created += 1;
                    match index.get(&key) {
                        Some(&j) => {
                            let slot = &mut next[j as usize];
                            if cost < slot.cost {
                                *slot = Entry {
                                    key,
                                    cost,
                                    prev: pi as u32,
                                    x,
                                    y,
                                };
                            }
                        }
                        None => {
                            index.insert(key, next.len() as u32);
                            next.push(Entry {
                                key,
                                cost,
                                prev: pi as u32,
                                x,
                                y,
                            });
                        }
                    }
                };
                if !is_free[i] {
                    if a > 0 || b > 0 {
                        continue;
                    }
                    let mut s = f;
                    s.mult[c] = 0;
                    s.label[c] = 0;
                    s.mult[w] = 0;
                    s.label[w] = 0;
                    emit(s, 0, 0);
                    continue;
                }
                if f.finished {
                    continue;
                }
                let xs: &[u8] = if can_right[i] { &[0, 1, 2] } else { &[0] };
                let ys: &[u8] = if can_down[i] { &[0, 1, 2] } else { &[0] };
                for &x in xs {
                    for &y in ys {
                        let deg = a + b + x + y;
                        if deg == 0 {
                            continue;
                        }
                        let mut s = f;
                        if deg % 2 == 1 {
                            s.odd += 1;
                            if i == s_index {
                                s.s_odd = true;
                            }
                        }
                        // Odd vertices must end as {} or {start, one more}.
                        let s_done = i >= s_index;
                        if s.odd > 2 || (!s_done && s.odd > 1) || (s_done && !s.s_odd && s.odd > 0)
                        {
                            continue;
                        }
                        // The cell's component: merge left and above.
                        let l = if a > 0 && b > 0 {
                            if la != lb_ {
                                for j in 0..=w {
                                    if s.label[j] == lb_ {
                                        s.label[j] = la;
                                    }
                                }
                            }
                            la
                        } else if a > 0 {
                            la
                        } else if b > 0 {
                            lb_
                        } else {
                            39
                        };
                        s.mult[c] = y;
                        s.label[c] = if y > 0 { l } else { 0 };
                        s.mult[w] = x;
                        s.label[w] = if x > 0 { l } else { 0 };
                        let alive = (0..=w).any(|j| s.mult[j] > 0 && s.label[j] == l);
                        if !alive {
                            // The component closes: only allowed as the very last piece.
                            let others = (0..=w).any(|j| s.mult[j] > 0);
                            if others || remaining > 0 {
                                continue;
                            }
                            s.finished = true;
                        }
                        emit(s, x, y);
                    }
                }
            }
            if *created > max_states as u64 || deadline.is_some_and(|d| Instant::now() >= d) {
                return Outcome::Aborted;
            }
            layers.push(next);
        }
        let finish = layers[total]
            .iter()
            .enumerate()
            .filter(|(_, e)| {
                let s = State::unpack(e.key, w);
                s.finished && (s.odd == 0 || (s.odd == 2 && s.s_odd))
            })
            .min_by_key(|(j, e)| (e.cost, *j))
            .map(|(j, _)| j);
        let Some(end) = finish else {
            return Outcome::None;
        };
        // Back-pointers to edge multiplicities.
        let mut mult_right = vec![0u8; total];
        let mut mult_down = vec![0u8; total];
        let mut j = end;
        for i in (0..total).rev() {
            let e = &layers[i + 1][j];
            mult_right[i] = e.x;
            mult_down[i] = e.y;
            j = e.prev as usize;
        }
        let cost = layers[total][end].cost as usize;
        let path = euler_walk(&self.layout, &mult_right, &mult_down, s_index);
        debug_assert_eq!(
            path.len(),
            cost + 1,
            "Euler walk length differs from the DP cost"
        );
        Outcome::Found(path)
    }
}

/// Hierholzer's algorithm on the multigraph of the chosen edges, from the start.
fn euler_walk(layout: &Layout, right: &[u8], down: &[u8], s: usize) -> Vec<Cell> {
    let w = layout.w;
    let total = right.len();
    // Remaining multiplicity of each undirected edge, keyed by (cell, 0=right/1=down).
    let mut rem: HashMap<(usize, u8), u8> = HashMap::new();
    for i in 0..total {
        if right[i] > 0 {
            rem.insert((i, 0), right[i]);
        }
        if down[i] > 0 {
            rem.insert((i, 1), down[i]);
        }
    }
    let neighbours = |i: usize| -> [(usize, (usize, u8)); 4] {
        // (neighbour, edge key); invalid entries point at themselves.
        [
            if i >= w {
                (i - w, (i - w, 1))
            } else {
                (i, (usize::MAX, 9))
            },
            if i % w > 0 {
                (i - 1, (i - 1, 0))
            } else {
                (i, (usize::MAX, 9))
            },
            (i + 1, (i, 0)),
            (i + w, (i, 1)),
        ]
    };
    let degree = |i: usize, rem: &HashMap<(usize, u8), u8>| -> u32 {
        neighbours(i)
            .iter()
            .map(|(_, k)| u32::from(rem.get(k).copied().unwrap_or(0)))
            .sum()
    };
    // Start at s; if s has odd degree the trail ends at the other odd vertex.
    let _ = degree(s, &rem);
    let mut stack = vec![s];
    let mut out = Vec::new();
    while let Some(&v) = stack.last() {
        let mut moved = false;
        for (u, key) in neighbours(v) {
            if let Some(m) = rem.get_mut(&key) {
                if *m > 0 {
                    *m -= 1;
                    stack.push(u);
                    moved = true;
                    break;
                }
            }
        }
        if !moved {
            out.push(v);
            stack.pop();
        }
    }
    out.reverse();
    out.into_iter().map(|i| layout.cell(i)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    fn solve(text: &str) -> OptimalResult {
        let p = crate::testing::problem(text, 1);
        optimal(p.coarse(), p.input(0).start, &Optimal::new()).unwrap()
    }

    fn is_walk(r: &OptimalResult) -> bool {
        r.path.len() == r.steps + 1 && r.path.windows(2).all(|w| w[0].manhattan(w[1]) == 1)
    }

    #[test]
    fn hamiltonian_walks_and_forced_revisits() {
        // A 3x3 room from a corner: a Hamiltonian path, 8 moves.
        let r = solve("S..\n...\n...");
        assert_eq!((r.steps, r.proven), (8, true));
        assert!(is_walk(&r));
        // From the centre of a 3x3 room: edges and corners alternate, 8 moves.
        let r = solve("...\n.S.\n...");
        assert_eq!((r.steps, r.proven), (8, true));
        // From an edge cell the colours do not balance: the 5 cells of the
        // other colour (corners and centre) need 2*5 - 1 = 9 moves by parity.
        let r = solve(".S.\n...\n...");
        assert_eq!((r.steps, r.proven), (9, true));
        assert!(is_walk(&r));
        // A plus shape from its centre: four dead ends, three must be left
        // again: 4 + 3 = 7 moves.
        let r = solve("#.#\n.S.\n#.#");
        assert_eq!((r.steps, r.proven), (7, true));
        assert!(is_walk(&r));
        // A comb: the teeth are dead ends off a corridor.
        let r = solve("S....\n.#.#.\n.#.#.");
        assert!(r.proven && is_walk(&r));
        assert_eq!(
            r.path
                .iter()
                .collect::<std::collections::BTreeSet<_>>()
                .len(),
            11
        );
    }

    #[test]
    fn wide_maps_are_transposed_and_budgets_stop_the_dp() {
        let (map, _) = parse_ascii(&vec![".".repeat(20); 5].join("\n")).unwrap();
        let coarse = CoarseGrid::new(&map.free_mask(), 1);
        let start = Cell::new(2, 7);
        let r = optimal(&coarse, start, &Optimal::new()).unwrap();
        assert!(r.proven && is_walk(&r));
        assert!(r.steps >= lower_bound(&coarse, start));
        let r = optimal(&coarse, start, &Optimal::new().max_states(3)).unwrap();
        assert!(r.lower_bound <= r.steps);
        assert_eq!(r.path[0], start);
        assert!(is_walk(&r));
        let (big, _) = parse_ascii(&vec![".".repeat(17); 17].join("\n")).unwrap();
        let coarse = CoarseGrid::new(&big.free_mask(), 1);
        assert!(optimal(&coarse, Cell::new(0, 0), &Optimal::new()).is_err());
    }
}
