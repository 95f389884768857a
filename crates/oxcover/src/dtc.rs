//! Distance-transform coverage, DTC (Zelinsky, Jarvis, Byrne & Yuta 1993).
//!
//! A wavefront from the goal labels every coverage cell with its distance to the
//! goal. From the start the robot repeatedly steps to the unvisited neighbour
//! with the HIGHEST label ("pseudo gradient ascent"), so it sweeps the cells far
//! from the goal first and works its way towards it. When no unvisited neighbour
//! is left it travels by a shortest path to the nearest unvisited cell and climbs
//! again; the goal is entered last.
//!
//! Here the coverage cells are the cells of a [`CoarseGrid`] (one tool diameter
//! each; with the default radii the fine grid itself). Every coarse move is
//! expanded into the fine, collision-free path [`CoarseGrid::connect`] gives, and
//! every jump into a shortest fine path found by CIDT, so the result is a
//! 4-connected path of plannable fine cells.
//!
//! Choices the paper leaves open, pinned by tests:
//! - **Goal**: by default the coarse cell farthest from the start (most moves;
//!   ties row-major), so the sweep runs from the start's side to the far side.
//! - **Ties** between equally labelled neighbours: keep the current heading,
//!   then the fixed order N, E, S, W.
//! - **Jumps**: to the nearest unvisited cell by fine travel distance (the
//!   goal only when it is the last one); ties by highest label, then row-major.
//!   Jumps run on the fine grid, so coarse cells the coarse graph does not link
//!   are still reached.
//!
//! Complexity: O(cells) for the labels and the walk, plus one CIDT per jump
//! (each bounded by the cells within the jump distance).

use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{Cell, CoarseGrid, Dir4, Grid};

use crate::error::{Error, Result};

/// Parameters of [`dtc`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DtcParams {
    /// Goal as a coarse cell; `None` = the coarse cell farthest from the start.
    pub goal: Option<Cell>,
}

impl DtcParams {
    /// Default parameters (farthest goal).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the goal coarse cell.
    #[must_use]
    pub fn goal(mut self, goal: Cell) -> Self {
        self.goal = Some(goal);
        self
    }
}

/// Runs DTC over `coarse` from the fine cell `start`; returns the fine cell path
/// (4-connected, plannable cells only, starting at `start`).
///
/// `plannable` must be the fine mask `coarse` was built from, with `start` in it.
///
/// # Errors
/// [`Error::Internal`] if `start` is not plannable or the goal has no
/// representative (caller bugs).
pub fn dtc(
    plannable: &Grid<bool>,
    coarse: &CoarseGrid,
    start: Cell,
    params: DtcParams,
) -> Result<Vec<Cell>> {
    if !plannable.is_set(start) {
        return Err(Error::Internal(format!(
            "DTC start {start:?} is not plannable"
        )));
    }
    let passable = coarse.passable();
    let mut coarse_wave = Wavefront::with_moves(&passable, coarse.moves());
    let start_block = coarse.coarse_of(start);
    let goal = match params.goal {
        Some(g) => g,
        None => {
            coarse_wave.propagate(&[start_block]);
            farthest(&coarse_wave, &passable).unwrap_or(start_block)
        }
    };
    if !passable.is_set(goal) {
        return Err(Error::Internal(format!(
            "DTC goal {goal:?} has no representative"
        )));
    }
    coarse_wave.propagate(&[goal]);
    let labels = coarse_wave.distances();

    let mut fine_wave = Wavefront::new(plannable);
    let mut visited = Grid::new(coarse.width(), coarse.height(), false);
    let mut left = passable.count_true();
    let mut path = vec![start];
    let mut heading: Option<Dir4> = None;

    // Go to the representative of the start block first.
    let mut cur = start_block;
    let rep = coarse
        .representative(cur)
        .ok_or_else(|| Error::Internal("start block without representative".into()))?;
    if rep != start {
        let to_rep = travel(&mut fine_wave, start, |c| c == rep)?;
        path.extend_from_slice(&to_rep[1..]);
    }
    visited[cur] = true;
    left -= 1;

    let label = |c: Cell| labels[c].map_or(-1i64, i64::from);
    while left > 0 {
        let allow_goal = left == 1;
        let mut best: Option<(i64, u8, usize, Dir4, Cell)> = None;
        for d in Dir4::ALL {
            if !coarse.can_move(cur, d) {
                continue;
            }
            let Some(n) = visited.step(cur, d) else {
                continue;
            };
            if visited[n] || (n == goal && !allow_goal) {
                continue;
            }
            // Higher label, then same heading, then N, E, S, W.
            let key = (label(n), u8::from(heading == Some(d)), 3 - d.index(), d, n);
            if best.is_none_or(|b| (key.0, key.1, key.2) > (b.0, b.1, b.2)) {
                best = Some(key);
            }
        }
        let next = if let Some((_, _, _, d, n)) = best {
            let seg = coarse.connect(plannable, cur, n).ok_or_else(|| {
                Error::Internal(format!("coarse move {cur:?} -> {n:?} has no fine path"))
            })?;
            path.extend_from_slice(&seg[1..]);
            heading = Some(d);
            n
        } else {
            // Jump: nearest unvisited representative by fine distance.
            let here = *path.last().unwrap_or(&start);
            let is_target = |c: Cell| {
                let b = coarse.coarse_of(c);
                coarse.representative(b) == Some(c) && !visited[b] && (b != goal || allow_goal)
            };
            let near = cidt(&mut fine_wave, &[here], is_target)
                .ok_or_else(|| Error::Internal("unvisited coverage cell unreachable".into()))?;
            let target = near
                .targets
                .iter()
                .copied()
                .max_by_key(|&c| (label(coarse.coarse_of(c)), std::cmp::Reverse(c)))
                .unwrap_or(near.targets[0]);
            let seg = fine_wave
                .retrace(target)
                .ok_or_else(|| Error::Internal("jump retrace failed".into()))?;
            path.extend_from_slice(&seg[1..]);
            heading = seg
                .len()
                .checked_sub(2)
                .and_then(|i| seg[i].dir_to(seg[i + 1]));
            coarse.coarse_of(target)
        };
        cur = next;
        visited[cur] = true;
        left -= 1;
    }
    Ok(path)
}

/// The labelled cell with the largest label (ties row-major first).
fn farthest(wave: &Wavefront, passable: &Grid<bool>) -> Option<Cell> {
    let mut best: Option<(u32, Cell)> = None;
    for c in passable.true_cells() {
        if let Some(d) = wave.distance(c) {
            if best.is_none_or(|(bd, _)| d > bd) {
                best = Some((d, c));
            }
        }
    }
    best.map(|(_, c)| c)
}

/// Shortest fine path from `from` to the nearest cell satisfying `is_target`.
pub(crate) fn travel(
    wave: &mut Wavefront,
    from: Cell,
    is_target: impl FnMut(Cell) -> bool,
) -> Result<Vec<Cell>> {
    let near = cidt(wave, &[from], is_target)
        .ok_or_else(|| Error::Internal(format!("no path from {from:?}")))?;
    wave.retrace(near.first())
        .ok_or_else(|| Error::Internal("retrace failed".into()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::{parse_ascii, to_ascii};
    use oxcover_grid::random::random_density;
    use oxcover_grid::{Coverability, DiscRobot};
    use proptest::prelude::*;

    fn plan_ascii(text: &str, goal: Option<Cell>) -> (Vec<Cell>, oxcover_grid::OccupancyGrid) {
        let (map, start) = parse_ascii(text).unwrap();
        let p = Coverability::with_start_cell(&map, DiscRobot::cell_sized(1.0), start.unwrap())
            .unwrap();
        let coarse = CoarseGrid::new(&p.reachable, 1);
        let params = goal.map_or(DtcParams::new(), |g| DtcParams::new().goal(g));
        (dtc(&p.reachable, &coarse, p.start, params).unwrap(), map)
    }

    fn cells(list: &[(usize, usize)]) -> Vec<Cell> {
        list.iter().copied().map(Cell::from).collect()
    }

    #[test]
    fn exact_path_on_an_open_room() {
        // Goal = farthest from S = (2,3); label = distance to it. At S both
        // neighbours have label 4: the fixed order takes E; then the heading is
        // kept while labels tie, which yields a boustrophedon ending at the goal.
        let (path, _) = plan_ascii(
            "
            S...
            ....
            ....",
            None,
        );
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
        let (path, _) = plan_ascii(
            "
            S.#.
            ..#.
            ....",
            Some(Cell::new(0, 3)),
        );
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
    fn exact_path_with_a_jump_and_the_goal_last() {
        // Farthest cells from S tie at distance 2; row-major takes (0,0) as goal.
        // S climbs east to the dead end, jumps back over visited cells to the
        // nearest unvisited one, and only then enters the goal.
        let (path, map) = plan_ascii("..S..", None);
        let want = cells(&[(0, 2), (0, 3), (0, 4), (0, 3), (0, 2), (0, 1), (0, 0)]);
        let marks: Vec<(Cell, char)> = path.iter().map(|&c| (c, '*')).collect();
        assert_eq!(path, want, "{}", to_ascii(map.cells(), &marks));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn admissible_and_complete_on_random_maps(w in 2usize..30, h in 2usize..30, density in 0.0f64..0.4, seed in any::<u64>(), k in 1usize..5) {
            let map = random_density(w, h, density, seed);
            let Ok(p) = Coverability::new(&map, DiscRobot::cell_sized(1.0), None) else { return Ok(()); };
            let coarse = CoarseGrid::new(&p.reachable, k);
            let path = dtc(&p.reachable, &coarse, p.start, DtcParams::new()).unwrap();
            prop_assert_eq!(path[0], p.start);
            prop_assert!(path.windows(2).all(|s| s[0].manhattan(s[1]) == 1));
            prop_assert!(path.iter().all(|&c| p.reachable[c]));
            // Every coverage cell's representative is visited.
            for b in coarse.passable().true_cells() {
                let rep = coarse.representative(b).unwrap();
                prop_assert!(path.contains(&rep));
            }
            if k == 1 {
                let mut seen = Grid::new(w, h, false);
                for &c in &path { seen[c] = true; }
                prop_assert_eq!(seen, p.reachable.clone());
            }
        }
    }
}
