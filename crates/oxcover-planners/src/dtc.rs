//! Distance-transform coverage, DTC (Zelinsky, Jarvis, Byrne & Yuta 1993).
//!
//! A wavefront from the goal labels every coverage cell with its distance to the
//! goal. From the start the robot repeatedly steps to the unvisited neighbour
//! with the HIGHEST label ("pseudo gradient ascent"), so it sweeps the cells far
//! from the goal first and works its way towards it. When no unvisited neighbour
//! is left it travels by a shortest path to the nearest unvisited cell and climbs
//! again; the goal is entered last.
//!
//! Choices the paper leaves open, pinned by tests:
//! - **Goal**: by default the coverage cell farthest from the start (most
//!   moves; ties row-major), so the sweep runs from the start's side to the far side.
//!   Room by room the pipeline passes the room's cell nearest the next room
//!   ([`crate::PlannerInput::exit`]); its coverage cell is then the goal, so
//!   the room's path ends where the robot leaves it (rooms on, measured over
//!   the shared maps when introduced: mean estimated time 16705 → 16639 s on the ipa floor
//!   plans and 10311 → 10281 s on the ROS maps, `docs/efficiency.md`).
//! - **Ties** between equally labelled neighbours: keep the current heading,
//!   then the fixed order N, E, S, W.
//! - **Jumps**: to the nearest unvisited cell by coverage-grid moves (the goal
//!   only when it is the last one); ties by highest label, then row-major; the
//!   route keeps its heading where a shortest route allows.
//!
//! Everything runs on the coverage grid (its connected moves), so the path is a
//! coverage path; [`crate::CoverageProblem::expand`] makes it fine. O(cells) for the labels and
//! the walk, plus one CIDT per jump. [`DtcWorkspace`] reuses its buffers across
//! runs (full DTC runs DTC once per goal).

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{Cell, CoarseGrid, Dir4, Grid};

use crate::error::{Error, Result};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};

/// The `dtc` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dtc {
    /// Goal coverage cell; `None` = the cell farthest from the start.
    pub goal: Option<Cell>,
}

impl Dtc {
    /// DTC with the default goal.
    #[must_use]
    pub const fn new() -> Self {
        Self { goal: None }
    }

    /// DTC towards the given goal coverage cell.
    #[must_use]
    pub const fn with_goal(goal: Cell) -> Self {
        Self { goal: Some(goal) }
    }
}

impl Planner for Dtc {
    fn name(&self) -> &'static str {
        "dtc"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "distance-transform coverage (Zelinsky et al. 1993): climb the wavefront from the farthest goal"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        let mut ws = DtcWorkspace::new(input.coarse);
        // Room by room, the cell nearest the next room is a natural goal
        // (DTC enters its goal last).
        let exit = input
            .exit
            .map(|c| input.coarse.coarse_of(c))
            .filter(|&c| input.coarse.passable().is_set(c));
        Ok(PlanOutput::Coverage(ws.run(
            input.coarse,
            input.start,
            self.goal.or(exit),
        )?))
    }
}

/// Reusable buffers for DTC runs on one coverage grid.
#[derive(Clone, Debug)]
pub struct DtcWorkspace {
    passable: Grid<bool>,
    wave: Wavefront,
    labels: Grid<i64>,
    visited: Grid<bool>,
}

impl DtcWorkspace {
    /// Buffers for `coarse`.
    #[must_use]
    pub fn new(coarse: &CoarseGrid) -> Self {
        let passable = coarse.passable();
        let wave = Wavefront::with_moves(&passable, coarse.moves());
        let (w, h) = (coarse.width(), coarse.height());
        Self {
            passable,
            wave,
            labels: Grid::new(w, h, -1),
            visited: Grid::new(w, h, false),
        }
    }

    /// The coverage cells reachable from `start` and the farthest of them.
    fn reach(&mut self, start: Cell) -> (usize, Cell) {
        let n = self.wave.propagate(&[start]);
        let mut best = (0, start);
        for c in self.wave.touched_cells() {
            let d = self.wave.distance(c).unwrap_or(0);
            if d > best.0 || (d == best.0 && c < best.1) {
                best = (d, c);
            }
        }
        (n, best.1)
    }

    /// Runs DTC from `start` towards `goal` (default: farthest) on `coarse`,
    /// which must be the grid this workspace was built for.
    ///
    /// # Errors
    /// [`Error::Internal`] if `start` has no representative or `goal` is not
    /// reachable from it.
    pub fn run(
        &mut self,
        coarse: &CoarseGrid,
        start: Cell,
        goal: Option<Cell>,
    ) -> Result<Vec<Cell>> {
        if !self.passable.is_set(start) {
            return Err(Error::Internal(format!(
                "DTC start {start:?} is not a coverage cell"
            )));
        }
        let (mut left, farthest) = self.reach(start);
        let goal = goal.unwrap_or(farthest);
        if self.wave.distance(goal).is_none() {
            return Err(Error::Internal(format!(
                "DTC goal {goal:?} is not reachable from {start:?}"
            )));
        }
        self.wave.propagate(&[goal]);
        self.labels.fill(-1);
        for c in self.wave.touched_cells() {
            self.labels[c] = i64::from(self.wave.distance(c).unwrap_or(0));
        }
        self.visited.fill(false);
        let mut path = vec![start];
        let mut heading: Option<Dir4> = None;
        let mut cur = start;
        self.visited[cur] = true;
        left -= 1;
        while left > 0 {
            let allow_goal = left == 1;
            let mut best: Option<(i64, bool, usize, Dir4, Cell)> = None;
            for d in Dir4::ALL {
                if !coarse.can_move(cur, d) {
                    continue;
                }
                let Some(n) = self.visited.step(cur, d) else {
                    continue;
                };
                if self.visited[n] || (n == goal && !allow_goal) {
                    continue;
                }
                // Higher label, then same heading, then N, E, S, W.
                let key = (self.labels[n], heading == Some(d), 3 - d.index(), d, n);
                if best.is_none_or(|b| (key.0, key.1, key.2) > (b.0, b.1, b.2)) {
                    best = Some(key);
                }
            }
            if let Some((_, _, _, d, n)) = best {
                path.push(n);
                heading = Some(d);
                cur = n;
            } else {
                let (visited, labels) = (&self.visited, &self.labels);
                let near = cidt(&mut self.wave, &[cur], |c| {
                    !visited[c] && (c != goal || allow_goal)
                })
                .ok_or_else(|| Error::Internal("unvisited coverage cell unreachable".into()))?;
                let target = near
                    .targets
                    .iter()
                    .copied()
                    .max_by_key(|&c| (labels[c], std::cmp::Reverse(c)))
                    .unwrap_or(near.targets[0]);
                let seg = self
                    .wave
                    .retrace(target)
                    .ok_or_else(|| Error::Internal("jump retrace failed".into()))?;
                heading = seg
                    .len()
                    .checked_sub(2)
                    .and_then(|i| seg[i].dir_to(seg[i + 1]));
                path.extend_from_slice(&seg[1..]);
                cur = target;
            }
            self.visited[cur] = true;
            left -= 1;
        }
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{cells, plan_ascii, plan_cells};

    #[test]
    fn exact_path_on_an_open_room() {
        // Goal = farthest from S = (2,3); label = distance to it. At S both
        // neighbours have label 4: the fixed order takes E; then the heading is
        // kept while labels tie, which yields a boustrophedon ending at the goal.
        let path = plan_ascii(&Dtc::new(), "S...\n....\n....");
        let want = cells(&[
            (0, 0),
            (0, 1),
            (0, 2),
            (0, 3),
            (1, 3),
            (1, 2),
            (1, 1),
            (1, 0),
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
        ]);
        assert_eq!(path, want);
    }

    #[test]
    fn exact_path_around_a_wall() {
        // Goal (0,3) given. Labels: S=7, (0,1)=(1,0)=6, (1,1)=(2,0)=5, ...
        let path = plan_ascii(&Dtc::with_goal(Cell::new(0, 3)), "S.#.\n..#.\n....");
        let want = cells(&[
            (0, 0),
            (0, 1),
            (1, 1),
            (1, 0),
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
            (1, 3),
            (0, 3),
        ]);
        assert_eq!(path, want);
    }

    #[test]
    fn room_by_room_the_exit_is_the_goal() {
        // Without an exit the goal is the farthest cell, (0,0) on ties; with
        // one (the pipeline's cell nearest the next room) the path ends there.
        let p = crate::testing::problem("..S..", 1);
        let mut input = p.input(0);
        let free = Dtc::new().plan(&input).unwrap();
        assert_eq!(free.coverage().unwrap().last(), Some(&Cell::new(0, 0)));
        input.exit = Some(Cell::new(0, 4));
        let out = Dtc::new().plan(&input).unwrap();
        assert_eq!(
            out.coverage().unwrap(),
            cells(&[(0, 2), (0, 1), (0, 0), (0, 1), (0, 2), (0, 3), (0, 4)])
        );
        // A goal given explicitly wins over the exit.
        let fixed = Dtc::with_goal(Cell::new(0, 0)).plan(&input).unwrap();
        assert_eq!(fixed.coverage().unwrap().last(), Some(&Cell::new(0, 0)));
    }

    #[test]
    fn exact_path_with_a_jump_and_the_goal_last() {
        // Farthest cells from S tie at distance 2; row-major takes (0,0) as goal.
        // S climbs east to the dead end, jumps back over visited cells to the
        // nearest unvisited one, and only then enters the goal.
        let path = plan_ascii(&Dtc::new(), "..S..");
        assert_eq!(
            path,
            cells(&[(0, 2), (0, 3), (0, 4), (0, 3), (0, 2), (0, 1), (0, 0)])
        );
    }

    #[test]
    fn wide_coverage_cells_give_connected_fine_paths() {
        let (path, fine) = plan_cells(
            &Dtc::new(),
            "S........\n.........\n..###....\n.........\n.........\n.........",
            3,
        );
        let distinct: std::collections::BTreeSet<Cell> = path.iter().copied().collect();
        assert_eq!(distinct.len(), 6);
        assert!(fine.windows(2).all(|w| w[0].manhattan(w[1]) == 1));
    }
}
