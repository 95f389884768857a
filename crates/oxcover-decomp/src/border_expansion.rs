//! Border expansion roads (Pavlíček, Kulich, Přeučil et al. 2002).
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
//! The **adjacency graph** joins the roads of one component (each hole's road
//! to the outer road) and each road of level `j + 1` to the nearest
//! road of level `j` (by a labelled wavefront inside `S_j`). The outer road of
//! level 0 is the paper's road A₁, where the walk starts. The method depends
//! on distances only, so it does not change when the map is rotated.

use oxcover_grid::edt::{INFINITE, boundary_distance_sq4};
use oxcover_grid::{Cell, Dir4, Grid};

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
    /// Road adjacency graph: pairs `(a, b)`, `a < b`: each hole road to its
    /// component's outer road, each road above level 0 to the nearest road
    /// of the level below.
    pub edges: Vec<(usize, usize)>,
    /// Number of safety levels with at least one road.
    pub levels: usize,
}

/// The roads of `passable` at lane spacing `spacing` (cells; below one cell,
/// or not finite, it is taken as one cell).
///
/// One exact distance transform gives every cell its **rank**: one more than
/// the highest level whose region holds it (0 off the passable set). Because
/// the distance is 1-Lipschitz and `s ≥ 1`, 4-neighbours differ in rank by at
/// most one, so a level's region is the next level's plus the cells of its
/// own rank, and its roads run through cells of that rank only. The levels
/// are built from the top down: the cells of each rank are added to a
/// union-find (the component tree of the distance map), which labels the new
/// level's components and their children in the level above; the roads are
/// traced from that rank's cells. Every cell is touched a bounded number of
/// times in all: the work does not grow with the number of levels.
#[must_use]
pub fn border_expansion(passable: &Grid<bool>, spacing: f64) -> BorderExpansion {
    let spacing = if spacing.is_finite() && spacing > 1.0 {
        spacing
    } else {
        1.0
    };
    let blocked = passable.map(|&p| !p);
    let d4 = boundary_distance_sq4(&blocked, true);
    let rank = ranks(passable, &d4, spacing);
    let (w, h) = (passable.width(), passable.height());
    // Cells by rank, ascending: `order[start[r]..start[r + 1]]` has rank `r`.
    let top = rank.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let mut start = vec![0usize; top + 2];
    for &r in rank.as_slice() {
        start[r as usize + 1] += 1;
    }
    for j in 1..start.len() {
        start[j] += start[j - 1];
    }
    let mut order = vec![Cell::new(0, 0); w * h];
    let mut fill = start.clone();
    for c in rank.cells() {
        let r = rank[c] as usize;
        order[fill[r]] = c;
        fill[r] += 1;
    }
    let mut work = Scratch {
        sets: UnionFind::new(w * h),
        tag: vec![(u32::MAX, 0); w * h],
        done: Grid::new(w, h, 0),
        near: Grid::new(w, h, u32::MAX),
        seen: Grid::new(w, h, false),
    };
    // Per level, from the top: components (one cell each, and the local
    // parent), roads (local component), down edges (local road of this level,
    // local road of the level below).
    let mut levels: Vec<Level> = Vec::with_capacity(top);
    for level in (0..top).rev() {
        let rim = &order[start[level + 1]..start[level + 2]];
        let in_level = |c: Cell| rank[c] as usize > level;
        for &c in rim {
            let i = rank.index_of(c);
            for n in Dir4::ALL.map(|d| rank.step(c, d)).into_iter().flatten() {
                // Each pair of this rank once; higher ranks are all in.
                let rn = rank[n] as usize;
                let k = rank.index_of(n);
                if rn > level + 1 || (rn == level + 1 && k < i) {
                    work.sets.union(i, k);
                }
            }
        }
        // Components: every one holds a cell of this rank.
        let mut here = Level::default();
        for &c in rim {
            let root = work.sets.find(rank.index_of(c));
            if work.tag[root].0 != level as u32 {
                work.tag[root] = (level as u32, here.comps.len() as u32);
                here.comps.push((c, None));
            }
        }
        let local = |sets: &mut UnionFind, tag: &[(u32, u32)], c: Cell| {
            tag[sets.find(rank.index_of(c))].1 as usize
        };
        if let Some(above) = levels.last_mut() {
            for comp in &mut above.comps {
                comp.1 = Some(local(&mut work.sets, &work.tag, comp.0));
            }
        }
        for (cells, area) in trace_loops(rim, &in_level, &mut work.done) {
            let Some(&c0) = cells.first() else { continue };
            let comp = local(&mut work.sets, &work.tag, c0);
            here.roads.push((comp, area > 0, cells));
        }
        // Each road of the level above to the nearest road of this one.
        if let Some(above) = levels.last_mut() {
            let targets: Vec<Cell> = above.roads.iter().map(|r| r.2[0]).collect();
            let sources: Vec<&[Cell]> = here.roads.iter().map(|r| r.2.as_slice()).collect();
            above.down = nearest_road(&in_level, &sources, &targets, &mut work);
        }
        levels.push(here);
    }
    levels.reverse();
    assemble(levels)
}

/// One safety level while the levels are built, in local indices.
#[derive(Default)]
struct Level {
    /// A cell of each component, and the component of the level below
    /// holding it.
    comps: Vec<(Cell, Option<usize>)>,
    /// Roads: component, outer, cells.
    roads: Vec<(usize, bool, Vec<Cell>)>,
    /// For each road, the nearest road of the level below.
    down: Vec<Option<usize>>,
}

/// Numbers components and roads level by level, from level 0 up.
fn assemble(levels: Vec<Level>) -> BorderExpansion {
    let mut out = BorderExpansion {
        roads: Vec::new(),
        components: Vec::new(),
        edges: Vec::new(),
        levels: levels.len(),
    };
    let (mut comp_base, mut road_base) = (Vec::new(), Vec::new());
    for (j, level) in levels.iter().enumerate() {
        comp_base.push(out.components.len());
        road_base.push(
            road_base
                .last()
                .map_or(0, |b| b + levels[j - 1].roads.len()),
        );
        out.components.extend(level.comps.iter().map(|_| Component {
            level: j,
            parent: None,
            roads: Vec::new(),
            children: Vec::new(),
        }));
    }
    for (j, level) in levels.into_iter().enumerate() {
        for (k, (_, parent)) in level.comps.iter().enumerate() {
            let id = comp_base[j] + k;
            if let (Some(p), true) = (parent, j > 0) {
                let p = comp_base[j - 1] + p;
                out.components[id].parent = Some(p);
                out.components[p].children.push(id);
            }
        }
        for (k, (comp, outer, cells)) in level.roads.into_iter().enumerate() {
            let id = road_base[j] + k;
            let component = comp_base[j] + comp;
            let roads = &mut out.components[component].roads;
            if outer {
                roads.insert(0, id);
            } else {
                roads.push(id);
            }
            out.roads.push(Road {
                level: j,
                component,
                outer,
                cells,
            });
            if let (Some(Some(p)), true) = (level.down.get(k), j > 0) {
                out.edges.push((road_base[j - 1] + p, id));
            }
        }
    }
    // Roads of one component bound the same region: each hole road is joined
    // to the outer road (a star; a clique would be quadratic in the holes,
    // tens of millions of edges on a cluttered map).
    for comp in &out.components {
        if let Some((&outer, holes)) = comp.roads.split_first() {
            for &b in holes {
                out.edges.push((outer.min(b), outer.max(b)));
            }
        }
    }
    out.edges.sort_unstable();
    out.edges.dedup();
    out
}

/// Disjoint sets over cell indices (path halving, union by size).
struct UnionFind {
    parent: Vec<u32>,
    size: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] as usize != i {
            let g = self.parent[self.parent[i] as usize];
            self.parent[i] = g;
            i = g as usize;
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a == b {
            return;
        }
        let (big, small) = if self.size[a] >= self.size[b] {
            (a, b)
        } else {
            (b, a)
        };
        self.parent[small] = big as u32;
        self.size[big] += self.size[small];
    }
}

/// Reusable per-cell work space, so no level allocates or clears a whole grid.
struct Scratch {
    /// Components of the levels built so far.
    sets: UnionFind,
    /// Per union-find root: the level it was last labelled at, and its local
    /// component index there.
    tag: Vec<(u32, u32)>,
    /// Cracks already followed (cleared after each level).
    done: Grid<u8>,
    /// Road index on road cells (reset after each search).
    near: Grid<u32>,
    /// Cells reached by a search (reset after each).
    seen: Grid<bool>,
}

/// Rank of each cell: 0 off `passable`, else `1 + max j` with
/// `d ≥ ½ + j·s`, `d` the centre-to-obstacle distance (`d4 = 4·d²`).
fn ranks(passable: &Grid<bool>, d4: &Grid<u64>, spacing: f64) -> Grid<u16> {
    let reaches = |d4: u64, j: u64| {
        let t = 1.0 + 2.0 * spacing * j as f64; // 2·(½ + j·s)
        d4 as f64 >= t * t - 1e-9
    };
    Grid::from_fn(passable.width(), passable.height(), |c| {
        let d = d4[c];
        if !passable[c] || d == INFINITE || !reaches(d, 0) {
            return 0;
        }
        let mut j = (((d as f64).sqrt() - 1.0) / (2.0 * spacing)).max(0.0) as u64;
        while j > 0 && !reaches(d, j) {
            j -= 1;
        }
        while reaches(d, j + 1) {
            j += 1;
        }
        u16::try_from(j + 1).unwrap_or(u16::MAX)
    })
}

/// For each of `targets`, the index of the road (of `roads`) nearest to it by
/// 4-connected moves inside the region (`None` if none reaches it).
///
/// Each target runs its own breadth-first search until it meets a road cell:
/// a target lies about one lane from the roads below it, so each search stays
/// local (a wavefront from all roads at once would sweep the whole band
/// between two levels). Ties go to the first road met in `Dir4` order.
fn nearest_road(
    region: &impl Fn(Cell) -> bool,
    roads: &[&[Cell]],
    targets: &[Cell],
    work: &mut Scratch,
) -> Vec<Option<usize>> {
    let (near, seen) = (&mut work.near, &mut work.seen);
    for (id, cells) in roads.iter().enumerate() {
        for &c in *cells {
            if near[c] == u32::MAX {
                near[c] = id as u32;
            }
        }
    }
    let mut queue = Vec::new();
    let found = targets
        .iter()
        .map(|&t| {
            queue.clear();
            queue.push(t);
            seen[t] = true;
            let mut head = 0;
            let mut hit = None;
            while let Some(&c) = queue.get(head) {
                head += 1;
                if near[c] != u32::MAX {
                    hit = Some(near[c] as usize);
                    break;
                }
                for n in Dir4::ALL.map(|d| seen.step(c, d)).into_iter().flatten() {
                    if !seen[n] && region(n) {
                        seen[n] = true;
                        queue.push(n);
                    }
                }
            }
            for &c in &queue {
                seen[c] = false;
            }
            hit
        })
        .collect();
    for cells in roads {
        for &c in *cells {
            near[c] = u32::MAX;
        }
    }
    found
}

/// The boundary loops of the 4-connected components of the region (cells
/// that are `inside`; `cells` holds at least every one of them on a boundary),
/// each as its inside cells in walking order, with twice its
/// signed area (positive for an outer boundary, negative around a hole).
/// `done` must be all zero; it is left so.
fn trace_loops(
    cells: &[Cell],
    inside: &impl Fn(Cell) -> bool,
    done: &mut Grid<u8>,
) -> Vec<(Vec<Cell>, i64)> {
    let inside = |c: Option<Cell>| c.is_some_and(inside);
    let mut loops = Vec::new();
    for &c0 in cells {
        for d0 in Dir4::ALL {
            if inside(done.step(c0, d0)) || done[c0] & d0.bit() != 0 {
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
                let ahead = done.step(c, m);
                let diag = ahead.and_then(|a| done.step(a, d));
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
    for &c in cells {
        done[c] = 0;
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
        oxcover_grid::io::ascii_mask(rows).expect("valid map")
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

    proptest::proptest! {
        /// Against the plain construction: each level's region by threshold
        /// on the whole grid, its components by flood fill, its loops traced
        /// from every cell.
        #[test]
        fn same_levels_roads_and_nesting_as_the_plain_construction(
            w in 1usize..40, h in 1usize..40, density in 0.0f64..0.4,
            seed in proptest::prelude::any::<u64>(), spacing in 1.0f64..5.0,
        ) {
            let m = oxcover_grid::random::random_density(w, h, density, seed).free_mask();
            let b = border_expansion(&m, spacing);
            let d4 = boundary_distance_sq4(&m.map(|&p| !p), true);
            let mut prev: Option<oxcover_grid::Components> = None;
            for level in 0.. {
                let t = 1.0 + 2.0 * spacing * level as f64;
                let region = Grid::from_fn(w, h, |c| m[c] && d4[c] as f64 >= t * t - 1e-9);
                let comps = oxcover_grid::components4(&region);
                let ours: Vec<&Component> = b.components.iter().filter(|c| c.level == level).collect();
                proptest::prop_assert_eq!(ours.len(), comps.count());
                if comps.count() == 0 {
                    proptest::prop_assert_eq!(b.levels, level);
                    break;
                }
                let cells: Vec<Cell> = region.true_cells().collect();
                let mut done = Grid::new(w, h, 0);
                let mut want: Vec<(bool, Vec<Cell>)> = trace_loops(&cells, &|c| region[c], &mut done)
                    .into_iter()
                    .map(|(mut l, a)| { l.sort_unstable(); (a > 0, l) })
                    .collect();
                let mut got: Vec<(bool, Vec<Cell>)> = b.roads.iter().filter(|r| r.level == level)
                    .map(|r| { let mut l = r.cells.clone(); l.sort_unstable(); (r.outer, l) })
                    .collect();
                want.sort();
                got.sort();
                proptest::prop_assert_eq!(got, want);
                // A road's component and its parent hold the road's cells.
                for r in b.roads.iter().filter(|r| r.level == level) {
                    let label = comps.labels[r.cells[0]];
                    proptest::prop_assert!(r.cells.iter().all(|&c| comps.labels[c] == label));
                    let comp = &b.components[r.component];
                    for &o in &comp.roads {
                        proptest::prop_assert_eq!(comps.labels[b.roads[o].cells[0]], label);
                    }
                    if let (Some(p), Some(pc)) = (comp.parent, &prev) {
                        let pl = pc.labels[r.cells[0]];
                        let parent_road = b.components[p].roads[0];
                        proptest::prop_assert_eq!(pc.labels[b.roads[parent_road].cells[0]], pl);
                        proptest::prop_assert!(b.components[p].children.contains(&r.component));
                    } else {
                        proptest::prop_assert!(level == 0 && comp.parent.is_none());
                    }
                }
                prev = Some(comps);
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
