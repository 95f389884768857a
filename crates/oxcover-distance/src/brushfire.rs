//! Brushfire: grid distance from every cell to the nearest obstacle.
//!
//! A multi-source BFS seeded at every blocked cell (and, optionally, the map
//! edge), 4-connected (Manhattan distance) or 8-connected (chessboard distance).
//! Blocked cells get 0; a free cell next to an obstacle gets 1. O(cells). For an
//! exact Euclidean clearance use [`oxcover_grid::clearance`].

use std::collections::VecDeque;

use oxcover_grid::{Cell, Grid};

/// Neighbourhood of the brushfire wave.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Connectivity {
    /// 4-connected: Manhattan distance.
    Four,
    /// 8-connected: chessboard distance.
    #[default]
    Eight,
}

/// Distance (in moves) from each cell to the nearest non-passable cell; when
/// `edge_is_obstacle`, the area outside the map counts as obstacle too. Cells
/// that no obstacle reaches get `u32::MAX`.
#[must_use]
pub fn brushfire(
    passable: &Grid<bool>,
    connectivity: Connectivity,
    edge_is_obstacle: bool,
) -> Grid<u32> {
    let (w, h) = (passable.width(), passable.height());
    let mut dist = Grid::new(w, h, u32::MAX);
    let mut queue = VecDeque::new();
    for c in passable.cells() {
        if !passable[c] {
            dist[c] = 0;
            queue.push_back(c);
        }
    }
    if edge_is_obstacle {
        for c in passable.cells() {
            let on_edge = c.row == 0 || c.col == 0 || c.row + 1 == h || c.col + 1 == w;
            // Edge cells touch the outside in both neighbourhoods.
            if passable[c] && on_edge && dist[c] == u32::MAX {
                dist[c] = 1;
                queue.push_back(c);
            }
        }
    }
    let offsets: &[(isize, isize)] = match connectivity {
        Connectivity::Four => &[(-1, 0), (0, 1), (1, 0), (0, -1)],
        Connectivity::Eight => &[
            (-1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
            (1, 0),
            (1, -1),
            (0, -1),
            (-1, -1),
        ],
    };
    while let Some(c) = queue.pop_front() {
        let d = dist[c];
        for &o in offsets {
            if let Some(n) = passable.offset(c, o) {
                if dist[n] == u32::MAX {
                    dist[n] = d + 1;
                    queue.push_back(n);
                }
            }
        }
    }
    dist
}

/// Distance from `cell` to the nearest obstacle in a brushfire grid (`None` if none).
#[must_use]
pub fn clearance_at(field: &Grid<u32>, cell: Cell) -> Option<u32> {
    field.get(cell).copied().filter(|&d| d != u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn distances_grow_away_from_obstacles() {
        let (m, _) = parse_ascii(
            "
            #....
            .....
            .....",
        )
        .unwrap();
        let f = m.free_mask();
        let d8 = brushfire(&f, Connectivity::Eight, false);
        assert_eq!(d8.row(0), &[0, 1, 2, 3, 4]);
        assert_eq!(d8.row(2), &[2, 2, 2, 3, 4]);
        let d4 = brushfire(&f, Connectivity::Four, false);
        assert_eq!(d4.row(2), &[2, 3, 4, 5, 6]);
        let e = brushfire(&f, Connectivity::Four, true);
        assert_eq!(e.row(1), &[1, 2, 2, 2, 1]);
        assert_eq!(clearance_at(&e, Cell::new(1, 2)), Some(2));
        assert_eq!(
            clearance_at(
                &brushfire(&Grid::new(2, 2, true), Connectivity::Four, false),
                Cell::new(0, 0)
            ),
            None
        );
    }
}
