//! Spanning-tree coverage, STC and Spiral-STC (Gabriely & Rimon 2001, 2002).
//!
//! Coverage cells (one tool diameter) are grouped into 2×2 **mega-cells**.
//! A spanning tree over the mega-cells is grown by depth-first search from the
//! start's mega-cell, trying neighbours counter-clockwise from the parent
//! direction (the spiral order of Spiral-STC). The robot then circumnavigates
//! the tree at coverage-cell resolution: every mega-cell's four subcells form
//! a small counter-clockwise cycle, and each tree edge splices two such cycles
//! (the two side moves facing each other are replaced by two crossing moves),
//! which yields one Hamiltonian cycle through the subcells of the tree with the
//! tree on the robot's left. The path follows that cycle from the start.
//!
//! Two variants, both registered:
//! - [`StcVariant::Plain`] (`stc`): a mega-cell is kept only when its four
//!   subcells are coverage cells linked to each other around the mega-cell; a
//!   tree edge needs both crossing moves. Partially occupied mega-cells are
//!   dropped, so coverage is lost next to obstacles (Lee 2011's 84 %); the
//!   planner says it is not complete. If the start's mega-cell is dropped the
//!   path first goes to the nearest kept subcell.
//! - [`StcVariant::Full`] (`spiral-stc`): a mega-cell is kept when any of its
//!   subcells is a coverage cell (linked to the start); a tree edge needs one
//!   crossing move between the two mega-cells. The cycle then runs through
//!   missing subcells; the robot skips them and detours by a shortest
//!   coverage-grid route to the next present subcell of the cycle ("detours
//!   inside mixed cells"). Complete on the coverage grid.
//!
//! **Path-length bound** (Gabriely & Rimon 2002, with D the coverage-cell
//! size): with only fully free mega-cells, n subcells are covered in exactly
//! n − 1 moves, each cell once (pinned by a test). With partially occupied
//! mega-cells, the full variant's length is at most (n + m)·D where m counts
//! the subcells next to missing ones, since each detour replaces one skipped
//! cycle subcell by a route around it; our detours take the shortest route on
//! the coverage grid, which can exceed that local bound only where a thin wall
//! splits a mega-cell (then the shortest way round is longer than two moves).

use oxcover_grid::{Cell, CoarseGrid, Dir4, Grid};

use crate::error::{Error, Result};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};
use crate::route::CoarseRouter;

/// Which STC.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StcVariant {
    /// Drops partially occupied mega-cells (not complete).
    Plain,
    /// Keeps them and detours around missing subcells (complete).
    Full,
}

/// The `stc` / `spiral-stc` planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stc {
    /// The variant.
    pub variant: StcVariant,
}

impl Stc {
    /// STC of the given variant.
    #[must_use]
    pub const fn new(variant: StcVariant) -> Self {
        Self { variant }
    }
}

impl Planner for Stc {
    fn name(&self) -> &'static str {
        match self.variant {
            StcVariant::Plain => "stc",
            StcVariant::Full => "spiral-stc",
        }
    }
    fn complete(&self) -> bool {
        self.variant == StcVariant::Full
    }
    fn summary(&self) -> &'static str {
        match self.variant {
            StcVariant::Plain => {
                "spanning-tree coverage (Gabriely & Rimon 2001) on 2x2 mega-cells; drops partly blocked ones"
            }
            StcVariant::Full => {
                "Spiral-STC (Gabriely & Rimon 2002) keeping partly blocked mega-cells, with detours"
            }
        }
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Coverage(stc(
            input.coarse,
            input.start,
            self.variant,
        )?))
    }
}

/// Subcell quadrants in counter-clockwise order (north up): TL, BL, BR, TR.
const TL: usize = 0;
const BL: usize = 1;
const BR: usize = 2;
const TR: usize = 3;
const QUADRANT: [(usize, usize); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// The STC coverage path from `start` on `coarse`.
///
/// # Errors
/// [`Error::Internal`] if `start` is not a coverage cell or a route the cycle
/// needs does not exist (both would be bugs).
pub fn stc(coarse: &CoarseGrid, start: Cell, variant: StcVariant) -> Result<Vec<Cell>> {
    let mut router = CoarseRouter::new(coarse);
    let present = router.reachable(start);
    if !present.is_set(start) {
        return Err(Error::Internal(format!(
            "STC start {start:?} is not a coverage cell"
        )));
    }
    let (mw, mh) = (coarse.width().div_ceil(2), coarse.height().div_ceil(2));
    let sub = |m: Cell, q: usize| {
        let (dr, dc) = QUADRANT[q];
        Cell::new(2 * m.row + dr, 2 * m.col + dc)
    };
    let has = |c: Cell| present.is_set(c);
    let linked =
        |a: Cell, b: Cell| has(a) && has(b) && a.dir_to(b).is_some_and(|d| coarse.can_move(a, d));
    let kept = Grid::from_fn(mw, mh, |m| match variant {
        StcVariant::Full => (0..4).any(|q| has(sub(m, q))),
        StcVariant::Plain => (0..4).all(|q| linked(sub(m, q), sub(m, (q + 1) % 4))),
    });
    // Crossing moves of a tree edge from mega-cell `m` towards `d`: pairs
    // (subcell of m, subcell of the neighbour) facing each other.
    let crossings = |d: Dir4| match d {
        Dir4::East => [(BR, BL), (TR, TL)],
        Dir4::West => [(BL, BR), (TL, TR)],
        Dir4::South => [(BL, TL), (BR, TR)],
        Dir4::North => [(TL, BL), (TR, BR)],
    };
    let edge_ok = |m: Cell, n: Cell, d: Dir4| {
        let ok = crossings(d).map(|(a, b)| linked(sub(m, a), sub(n, b)));
        match variant {
            StcVariant::Plain => ok[0] && ok[1],
            StcVariant::Full => ok[0] || ok[1],
        }
    };

    let mut path = vec![start];
    let mut root = Cell::new(start.row / 2, start.col / 2);
    if !kept[root] {
        // Plain STC dropped the start's mega-cell: go to the nearest kept one.
        let Some(route) = router.nearest(start, |c| kept[Cell::new(c.row / 2, c.col / 2)]) else {
            return Ok(path);
        };
        let last = *route.last().unwrap_or(&start);
        path.extend_from_slice(&route[1..]);
        root = Cell::new(last.row / 2, last.col / 2);
    }

    // Spanning tree by DFS, neighbours counter-clockwise from the parent.
    // `tree[m]` holds the directions of m's tree edges as a bit mask.
    let mut tree = Grid::new(mw, mh, 0u8);
    let mut in_tree = Grid::new(mw, mh, false);
    in_tree[root] = true;
    // (mega-cell, direction towards its parent, next rotation to try)
    let mut stack = vec![(root, Dir4::South, 1usize)];
    while let Some(top) = stack.last_mut() {
        let (m, parent, k) = *top;
        if k > 4 {
            stack.pop();
            continue;
        }
        top.2 += 1;
        // Counter-clockwise from the parent: parent+3, parent+2, parent+1 (mod 4);
        // the root also tries its "parent" side last.
        let d = Dir4::from_index(parent.index() + 4 - k % 4);
        if k == 4 && m != root {
            continue;
        }
        let Some(n) = kept.step(m, d) else { continue };
        if !kept[n] || in_tree[n] || !edge_ok(m, n, d) {
            continue;
        }
        in_tree[n] = true;
        tree[m] |= d.bit();
        tree[n] |= d.opposite().bit();
        stack.push((n, d.opposite(), 1));
    }

    // The circumnavigation cycle: next[subcell] per mega-cell quadrant.
    let next_of = |m: Cell, q: usize| -> Cell {
        let t = tree[m];
        let has_edge = |d: Dir4| t & d.bit() != 0;
        let step = |d: Dir4, q2: usize| {
            let n = Cell::new(
                m.row.wrapping_add_signed(d.offset().0),
                m.col.wrapping_add_signed(d.offset().1),
            );
            sub(n, q2)
        };
        match q {
            TL if has_edge(Dir4::West) => step(Dir4::West, TR),
            BL if has_edge(Dir4::South) => step(Dir4::South, TL),
            BR if has_edge(Dir4::East) => step(Dir4::East, BL),
            TR if has_edge(Dir4::North) => step(Dir4::North, BR),
            _ => sub(m, (q + 1) % 4),
        }
    };
    let entry = *path.last().unwrap_or(&start);
    let quadrant_of = |c: Cell| {
        let q = (c.row % 2, c.col % 2);
        QUADRANT.iter().position(|&x| x == q).unwrap_or(TL)
    };
    let total = 4 * in_tree.count_true();
    let mut cur = entry;
    let mut at = entry;
    for _ in 1..total {
        let m = Cell::new(at.row / 2, at.col / 2);
        at = next_of(m, quadrant_of(at));
        if !has(at) {
            continue;
        }
        if linked(cur, at) {
            path.push(at);
        } else {
            let route = router.route(cur, at).ok_or_else(|| {
                Error::Internal(format!("STC detour {cur:?} -> {at:?} has no route"))
            })?;
            path.extend_from_slice(&route[1..]);
        }
        cur = at;
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::plan_ascii;

    const FULL: Stc = Stc::new(StcVariant::Full);
    const PLAIN: Stc = Stc::new(StcVariant::Plain);

    fn distinct(path: &[Cell]) -> usize {
        let mut v = path.to_vec();
        v.sort_unstable();
        v.dedup();
        v.len()
    }

    #[test]
    fn free_rectangle_is_a_hamiltonian_cycle() {
        let p = plan_ascii(&FULL, "S.....\n......\n......\n......");
        assert_eq!(p.len(), 24);
        assert_eq!(distinct(&p), 24);
        assert!(p.windows(2).all(|w| w[0].manhattan(w[1]) == 1));
        // The cycle closes: the last cell neighbours the start.
        assert_eq!(p[23].manhattan(p[0]), 1);
        assert_eq!(plan_ascii(&PLAIN, "S.....\n......\n......\n......"), p);
    }

    #[test]
    fn exact_path_on_a_two_by_four_room() {
        // Two mega-cells side by side; from TL the cycle runs counter-clockwise.
        let p = plan_ascii(&FULL, "S...\n....");
        let want: Vec<Cell> = [
            (0, 0),
            (1, 0),
            (1, 1),
            (1, 2),
            (1, 3),
            (0, 3),
            (0, 2),
            (0, 1),
        ]
        .into_iter()
        .map(Cell::from)
        .collect();
        assert_eq!(p, want);
    }

    #[test]
    fn half_blocked_mega_cell() {
        // The right mega-cell has its top half blocked.
        let map = "S.##\n....";
        let full = plan_ascii(&FULL, map);
        assert_eq!(distinct(&full), 6);
        assert_eq!(
            full,
            [
                (0, 0),
                (1, 0),
                (1, 1),
                (1, 2),
                (1, 3),
                (1, 2),
                (1, 1),
                (0, 1)
            ]
            .into_iter()
            .map(Cell::from)
            .collect::<Vec<_>>()
        );
        // Plain STC drops the half-blocked mega-cell.
        let plain = plan_ascii(&PLAIN, map);
        assert_eq!(distinct(&plain), 4);
    }

    #[test]
    fn u_shaped_room_and_stacked_obstacles_are_covered() {
        for map in [
            "S.......\n........\n..####..\n..####..\n........\n........",
            "S......\n.......\n..##...\n.......\n..##...\n.......\n.......",
        ] {
            let p = plan_ascii(&FULL, map);
            let free = map.bytes().filter(|&b| b == b'.' || b == b'S').count();
            assert_eq!(distinct(&p), free, "{map}");
        }
    }

    #[test]
    fn corridor_one_cell_wide() {
        let p = plan_ascii(&FULL, "S.....");
        assert_eq!(distinct(&p), 6);
        // Plain STC has no full mega-cell in a one-cell corridor.
        assert_eq!(plan_ascii(&PLAIN, "S....."), vec![Cell::new(0, 0)]);
    }
}
