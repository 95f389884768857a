//! Border expansion roads (Pavlicek, Kulich, Preucil et al., seed 004).
//!
//! Every obstacle and the outer border are grown into the free space in steps
//! of one lane width `s`; after each step the boundary of what is left is a set
//! of closed **roads**. On a grid this is exact with a Euclidean distance
//! transform: with `d` the distance from a passable cell's centre to the
//! nearest non-passable cell (or the map edge), **safety level** `j ≥ 0` is
//! the region `S_j = {passable, d ≥ ½ + j·s}` (`S_0` is the passable set
//! itself: level "0" of the paper, the safety zone, is what is not passable),
//! and its roads are the boundaries of its 4-connected components, traced as
//! closed 4-connected cell loops (crack following, inside kept on the right).
//! Overlapping growth needs no special handling: where two borders meet, the
//! level set simply merges into one road, as the paper's "composite road".
//!
//! The **adjacency graph** joins the roads of one component (an outer road and
//! the roads around its holes) and each road of level `j + 1` to the nearest
//! road of level `j` (by a labelled wavefront inside `S_j`). The outer road of
//! level 0 is the paper's road A₁, where the walk starts. The method depends
//! on distances only, so it does not change when the map is rotated.

use std::collections::VecDeque;

use oxcover_grid::edt::{INFINITE, boundary_distance_sq4};
use oxcover_grid::{Cell, Dir4, Grid, components4};

/// A closed road: a loop of 4-connected cells.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Road {
    /// Safety level (0 = the road along the passable region's boundary).
    pub level: usize,
    /// Component of that level's region the road bounds (index into
    /// [`BorderExpansion::components`]).
    pub component: usize,
    /// Whether it is the component's outer boundary (otherwise a hole's).
    pub outer: bool,
    /// The loop; the last cell is a 4-neighbour of the first (or the same
    /// cell for a one-cell road).
    pub cells: Vec<Cell>,
}

/// A connected region of one safety level.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// Safety level.
    pub level: usize,
    /// The component of the level below that contains it.
    pub parent: Option<usize>,
    /// Its roads (outer first).
    pub roads: Vec<usize>,
    /// Components of the next level inside it.
    pub children: Vec<usize>,
}

/// Roads, their components and the road adjacency graph.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BorderExpansion {
    /// Every road, by level.
    pub roads: Vec<Road>,
    /// Regions per level, by level.
    pub components: Vec<Component>,
    /// Road adjacency graph: pairs `(a, b)`, `a < b`.
    pub edges: Vec<(usize, usize)>,
    /// Number of safety levels with at least one road.
    pub levels: usize,
}

/// The roads of `passable` at lane spacing `spacing` (cells).
#[must_use]
pub fn border_expansion(passable: &Grid<bool>, spacing: f64) -> BorderExpansion {
    let spacing = if spacing.is_finite() && spacing > 0.0 {
        spacing
    } else {
        1.0
    };
    let blocked = passable.map(|&p| !p);
    let d4 = boundary_distance_sq4(&blocked, true);
    let mut out = BorderExpansion {
        roads: Vec::new(),
        components: Vec::new(),
        edges: Vec::new(),
        levels: 0,
    };
    // Component index per cell at the previous level, and that level's roads.
    let mut prev_comp: Option<Grid<u32>> = None;
    let mut prev_base = 0usize;
    let mut prev_roads: Vec<usize> = Vec::new();
    for level in 0.. {
        let threshold = 1.0 + 2.0 * spacing * level as f64; // 2·(½ + j·s)
        let t2 = threshold * threshold;
        let region = Grid::from_fn(passable.width(), passable.height(), |c| {
            passable[c] && d4[c] != INFINITE && d4[c] as f64 >= t2 - 1e-9
        });
        if !region.as_slice().contains(&true) {
            break;
        }
        out.levels = level + 1;
        let comps = components4(&region);
        let base = out.components.len();
        for _ in 0..comps.count() {
            out.components.push(Component {
                level,
                parent: None,
                roads: Vec::new(),
                children: Vec::new(),
            });
        }
        let label = |c: Cell| (comps.labels[c] as usize).checked_sub(1);
        // Parents.
        if let Some(pc) = &prev_comp {
            for c in region.true_cells() {
                let Some(l) = label(c) else { continue };
                let id = base + l;
                if out.components[id].parent.is_none() {
                    let p = prev_base + pc[c] as usize - 1;
                    out.components[id].parent = Some(p);
                    out.components[p].children.push(id);
                }
            }
        }
        // Roads.
        let first_road = out.roads.len();
        for (cells, area) in trace_loops(&region) {
            let Some(l) = cells.first().and_then(|&c| label(c)) else {
                continue;
            };
            let id = out.roads.len();
            let outer = area > 0;
            let comp = &mut out.components[base + l];
            if outer {
                comp.roads.insert(0, id);
            } else {
                comp.roads.push(id);
            }
            out.roads.push(Road {
                level,
                component: base + l,
                outer,
                cells,
            });
        }
        // Edges: roads of one component, and each new road to the nearest
        // road of the level below.
        for comp in &out.components[base..] {
            for (i, &a) in comp.roads.iter().enumerate() {
                for &b in &comp.roads[i + 1..] {
                    out.edges.push((a.min(b), a.max(b)));
                }
            }
        }
        if let Some(pc) = &prev_comp {
            let near = nearest_road(&pc.map(|&l| l != 0), &out.roads, &prev_roads);
            for id in first_road..out.roads.len() {
                if let Some(&c) = out.roads[id].cells.first() {
                    if let Some(p) = near[c] {
                        out.edges.push((p.min(id), p.max(id)));
                    }
                }
            }
        }
        prev_comp = Some(comps.labels);
        prev_base = base;
        prev_roads = (first_road..out.roads.len()).collect();
    }
    out.edges.sort_unstable();
    out.edges.dedup();
    out
}

/// For every cell of `region`, the road (of `ids`) nearest by 4-connected
/// moves inside the region.
fn nearest_road(region: &Grid<bool>, roads: &[Road], ids: &[usize]) -> Grid<Option<usize>> {
    let mut near: Grid<Option<usize>> = Grid::new(region.width(), region.height(), None);
    let mut queue = VecDeque::new();
    for &id in ids {
        for &c in &roads[id].cells {
            if near[c].is_none() {
                near[c] = Some(id);
                queue.push_back(c);
            }
        }
    }
    while let Some(c) = queue.pop_front() {
        let id = near[c];
        for (_, n) in region.neighbours4(c) {
            if region[n] && near[n].is_none() {
                near[n] = id;
                queue.push_back(n);
            }
        }
    }
    near
}

/// The boundary loops of the 4-connected components of `region`, each as its
/// inside cells in walking order, with twice its signed area (positive for an
/// outer boundary, negative around a hole).
fn trace_loops(region: &Grid<bool>) -> Vec<(Vec<Cell>, i64)> {
    let inside = |c: Option<Cell>| c.is_some_and(|c| region[c]);
    let mut done: Grid<u8> = Grid::new(region.width(), region.height(), 0);
    let mut loops = Vec::new();
    for c0 in region.true_cells() {
        for d0 in Dir4::ALL {
            if inside(region.step(c0, d0)) || done[c0] & d0.bit() != 0 {
                continue;
            }
            // Follow cracks: the side of `c` facing `d` (outside), walking
            // in direction `d + 1` (clockwise) with the inside on the right.
            let (mut c, mut d) = (c0, d0);
            let mut cells = vec![c0];
            let mut area2 = 0i64;
            loop {
                done[c] |= d.bit();
                let m = Dir4::from_index(d.index() + 1);
                let (a, b) = crack_ends(c, d);
                area2 += a.0 * b.1 - b.0 * a.1;
                let ahead = region.step(c, m);
                let diag = ahead.and_then(|a| region.step(a, d));
                let (nc, nd) = if inside(ahead) && inside(diag) {
                    // Boundary turns outwards: around the corner via `ahead`.
                    let (Some(a), Some(g)) = (ahead, diag) else {
                        break;
                    };
                    push(&mut cells, a);
                    (g, m.opposite())
                } else if let (true, Some(a)) = (inside(ahead), ahead) {
                    (a, d)
                } else {
                    (c, m)
                };
                if (nc, nd) == (c0, d0) {
                    break;
                }
                push(&mut cells, nc);
                c = nc;
                d = nd;
            }
            if cells.len() > 1 && cells.first() == cells.last() {
                cells.pop();
            }
            loops.push((cells, area2));
        }
    }
    loops
}

fn push(cells: &mut Vec<Cell>, c: Cell) {
    if cells.last() != Some(&c) {
        cells.push(c);
    }
}

/// Start and end vertex `(x, y)` of the crack on `c`'s side facing `d`.
fn crack_ends(c: Cell, d: Dir4) -> ((i64, i64), (i64, i64)) {
    let (x, y) = (c.col as i64, c.row as i64);
    match d {
        Dir4::North => ((x, y), (x + 1, y)),
        Dir4::East => ((x + 1, y), (x + 1, y + 1)),
        Dir4::South => ((x + 1, y + 1), (x, y + 1)),
        Dir4::West => ((x, y + 1), (x, y)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Grid<bool> {
        let (map, _) = oxcover_grid::io::parse_ascii(&rows.join("\n")).expect("valid map");
        map.free_mask()
    }

    fn is_loop(cells: &[Cell]) -> bool {
        cells.windows(2).all(|w| w[0].manhattan(w[1]) == 1)
            && (cells.len() == 1 || cells[0].manhattan(cells[cells.len() - 1]) == 1)
    }

    #[test]
    fn room_with_an_obstacle_has_outer_and_hole_roads() {
        let m = mask(&[
            "..........",
            "..........",
            "....##....",
            "....##....",
            "..........",
            "..........",
        ]);
        let b = border_expansion(&m, 1.0);
        let level0: Vec<&Road> = b.roads.iter().filter(|r| r.level == 0).collect();
        assert_eq!(level0.len(), 2);
        assert!(level0[0].outer && !level0[1].outer);
        // The outer road runs around the border: 2·10 + 2·6 − 4 cells.
        assert_eq!(level0[0].cells.len(), 28);
        // The hole road rings the obstacle: 12 cells.
        assert_eq!(level0[1].cells.len(), 12);
        assert!(b.roads.iter().all(|r| is_loop(&r.cells)));
        assert!(b.edges.contains(&(0, 1)));
        assert!(b.levels >= 2);
    }

    #[test]
    fn every_passable_cell_is_near_a_road() {
        let m = mask(&[
            "............",
            ".###........",
            ".#..........",
            ".#....##....",
            "......##....",
            "............",
            "..........#.",
        ]);
        let b = border_expansion(&m, 2.0);
        for c in m.true_cells() {
            let near = b.roads.iter().flat_map(|r| &r.cells).any(|r| {
                let (dr, dc) = (r.row.abs_diff(c.row), r.col.abs_diff(c.col));
                dr * dr + dc * dc <= 2
            });
            assert!(near, "{c:?}");
        }
        assert!(b.roads.iter().all(|r| is_loop(&r.cells)));
        // Every road of a higher level has a parent component and an edge down.
        for (i, r) in b.roads.iter().enumerate() {
            if r.level > 0 {
                assert!(b.components[r.component].parent.is_some());
                assert!(b.edges.iter().any(|&(a, z)| a == i || z == i));
            }
        }
    }

    #[test]
    fn a_diagonal_touch_is_two_regions() {
        let m = mask(&["..#", "..#", "##."]);
        let b = border_expansion(&m, 5.0);
        assert_eq!(b.roads.len(), 2);
        assert_eq!(b.roads[1].cells, vec![Cell::new(2, 2)]);
    }
}
