//! Backtracking spiral algorithm, BSA (Gonzalez, Alvarez, Diaz, Parra & Bustacara 2005).
//!
//! The robot spirals over the coverage grid keeping covered cells or walls on
//! its left: at every cell it tries, in order, the unvisited neighbour to the
//! left of its heading, straight ahead, then to the right. Every unvisited
//! neighbour it passes is recorded as a **backtracking point**. When no move is
//! left (the spiral's end), it goes by a shortest coverage-grid route to the
//! nearest backtracking point that is still unvisited (ties: row-major first),
//! and spirals again from there with the heading of the route's last move.
//! It stops when no backtracking point is left, which on a connected coverage
//! grid means every cell was visited (the nearest unvisited cell always
//! borders a visited one, so it was recorded).
//!
//! Choices the paper leaves open: the initial heading is the first of N, E, S,
//! W with an unvisited linked neighbour; after a jump the route's last move
//! sets the heading. O(cells) for the spirals plus one CIDT per backtrack.

use oxcover_grid::{Cell, Dir4, Grid};

use crate::error::{Error, Result};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};
use crate::route::CoarseRouter;

/// The `bsa` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bsa;

impl Planner for Bsa {
    fn name(&self) -> &'static str {
        "bsa"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "backtracking spiral algorithm (Gonzalez et al. 2005): spirals joined by shortest returns to backtracking points"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Coverage(bsa(input)?))
    }
}

fn bsa(input: &PlannerInput<'_>) -> Result<Vec<Cell>> {
    let coarse = input.coarse;
    let start = input.start;
    let mut router = CoarseRouter::new(coarse);
    let present = router.reachable(start);
    if !present.is_set(start) {
        return Err(Error::Internal(format!(
            "BSA start {start:?} is not a coverage cell"
        )));
    }
    let mut visited = Grid::new(coarse.width(), coarse.height(), false);
    let mut backtrack = Grid::new(coarse.width(), coarse.height(), false);
    let mut left = present.count_true();
    let open = |visited: &Grid<bool>, c: Cell, d: Dir4| {
        coarse
            .can_move(c, d)
            .then(|| visited.step(c, d))
            .flatten()
            .filter(|&n| present[n] && !visited[n])
    };
    let mut path = vec![start];
    let mut cur = start;
    visited[cur] = true;
    left -= 1;
    let mut heading = Dir4::ALL
        .into_iter()
        .find(|&d| open(&visited, cur, d).is_some())
        .unwrap_or(Dir4::North);
    while left > 0 {
        for d in Dir4::ALL {
            if let Some(n) = open(&visited, cur, d) {
                backtrack[n] = true;
            }
        }
        let order = [
            Dir4::from_index(heading.index() + 3),
            heading,
            Dir4::from_index(heading.index() + 1),
        ];
        if let Some((d, n)) = order
            .into_iter()
            .find_map(|d| open(&visited, cur, d).map(|n| (d, n)))
        {
            heading = d;
            cur = n;
            path.push(n);
        } else {
            let route = router
                .nearest(cur, |c| backtrack[c] && !visited[c])
                .ok_or_else(|| {
                    Error::Internal("BSA: unvisited cells but no backtracking point".into())
                })?;
            let n = route.len();
            if n >= 2 {
                heading = route[n - 2].dir_to(route[n - 1]).unwrap_or(heading);
            }
            path.extend_from_slice(&route[1..]);
            cur = route[n - 1];
        }
        visited[cur] = true;
        left -= 1;
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{cells, plan_ascii};

    #[test]
    fn spirals_inwards_in_an_open_room() {
        // Heading east first (north is a wall); keeps the wall on its left.
        let p = plan_ascii(&Bsa, "S..\n...\n...");
        assert_eq!(
            p,
            cells(&[
                (0, 0),
                (0, 1),
                (0, 2),
                (1, 2),
                (2, 2),
                (2, 1),
                (2, 0),
                (1, 0),
                (1, 1)
            ])
        );
    }

    #[test]
    fn backtracks_to_the_nearest_point() {
        // The spiral along the corridor ends at the right; the cell below the
        // start is the only backtracking point left.
        let p = plan_ascii(&Bsa, "S...\n.###");
        assert_eq!(
            p,
            cells(&[
                (0, 0),
                (0, 1),
                (0, 2),
                (0, 3),
                (0, 2),
                (0, 1),
                (0, 0),
                (1, 0)
            ])
        );
    }

    #[test]
    fn covers_u_room_stacked_obstacles_and_corridor() {
        for map in [
            "S.......\n........\n..####..\n..####..\n........\n........",
            "S......\n.......\n..##...\n.......\n..##...\n.......\n.......",
            "#######\nS......\n#######",
        ] {
            let p = plan_ascii(&Bsa, map);
            let mut v = p.clone();
            v.sort_unstable();
            v.dedup();
            let free = map.bytes().filter(|&b| b == b'.' || b == b'S').count();
            assert_eq!(v.len(), free, "{map}");
        }
    }
}
