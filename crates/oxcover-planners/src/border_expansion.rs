//! Border-expansion coverage (Pavlicek et al., seed 004, §5).
//!
//! The roads of [`oxcover_decomp::border_expansion()`] (successive offsets of the
//! obstacles and the outer border, one coverage cell apart, from an exact
//! distance transform) are driven one after the other. The walk starts on the
//! outer road of level 0 (the paper's A₁) and is exhaustive over the road
//! graph: depth-first over the nesting of the level regions (each region's
//! roads, nearest first, then the regions of the next level inside it,
//! nearest first), so every road is passed once. A road is entered at its cell
//! nearest to the robot and driven once around; its staircase of cells is
//! straightened within half a cell. Transitions are shortest routes over the
//! fine grid, straightened without crossing walls (`PathBuilder`).
//!
//! Inner regions where offsets vanish (narrower than a lane) and strips a road
//! leaves between itself and the next are then covered by visiting the
//! remaining coverage cells (`PathBuilder::cover_leftovers`). The result is
//! a metre path; it does not depend on the map's rotation beyond pixel effects.

use oxcover_decomp::{BorderExpansion, border_expansion};
use oxcover_grid::Cell;
use oxcover_grid::traverse::{GridPoint, cell_center};

use crate::error::{Error, Result};
use crate::metre_path::PathBuilder;
use crate::planner::{PlanOutput, Planner, PlannerInput};

/// Largest deviation (cells) of a straightened road from its cells.
const ROAD_TOLERANCE: f64 = 0.5;

/// The `border-expansion` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BorderExpansionPlanner;

/// A border-expansion plan and its roads.
#[derive(Clone, Debug)]
pub struct BorderPlan {
    /// Roads, levels and the road graph.
    pub roads: BorderExpansion,
    /// The order in which roads were driven.
    pub order: Vec<usize>,
    /// The metre path.
    pub points: Vec<oxcover_grid::Point>,
}

impl BorderExpansionPlanner {
    /// The plan with its roads.
    ///
    /// # Errors
    /// Internal faults only.
    pub fn plan_detailed(&self, input: &PlannerInput<'_>) -> Result<BorderPlan> {
        let start = input
            .coarse
            .representative(input.start)
            .ok_or_else(|| Error::Internal("start coverage cell has no representative".into()))?;
        let spacing = input.coarse.block_size() as f64;
        let roads = border_expansion(input.plannable, spacing);
        let mut path = PathBuilder::new(input.plannable, start);
        let mut order = Vec::new();
        // Roots: level-0 regions (one when the plannable set is connected).
        let mut roots: Vec<usize> = (0..roads.components.len())
            .filter(|&c| roads.components[c].level == 0)
            .collect();
        while !roots.is_empty() {
            let here = path.last();
            let k = nearest_index(&roots, |c| region_distance(&roads, c, here));
            let root = roots.swap_remove(k);
            walk_region(&roads, root, &mut path, &mut order)?;
        }
        path.cover_leftovers(input.coarse)?;
        Ok(BorderPlan {
            roads,
            order,
            points: path.into_metres(&input.frame),
        })
    }
}

impl Planner for BorderExpansionPlanner {
    fn name(&self) -> &'static str {
        "border-expansion"
    }
    fn complete(&self) -> bool {
        true
    }
    fn summary(&self) -> &'static str {
        "border expansion (Pavlicek et al. 2002, seed 004): closed roads offset from every border, outer road first"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
}

/// Drives the roads of `region` (outer road first), then its inner regions.
fn walk_region(
    roads: &BorderExpansion,
    region: usize,
    path: &mut PathBuilder<'_>,
    order: &mut Vec<usize>,
) -> Result<()> {
    let comp = &roads.components[region];
    let mut todo = comp.roads.clone();
    let mut first = true;
    while !todo.is_empty() {
        let here = path.last();
        // The outer road opens a region (A₁ for the first); then nearest first.
        let k = if first {
            0
        } else {
            nearest_index(&todo, |r| road_distance(&roads.roads[r].cells, here).0)
        };
        first = false;
        let r = todo.remove(k);
        drive_road(&roads.roads[r].cells, path)?;
        order.push(r);
    }
    let mut children = comp.children.clone();
    while !children.is_empty() {
        let here = path.last();
        let k = nearest_index(&children, |c| region_distance(roads, c, here));
        let child = children.swap_remove(k);
        walk_region(roads, child, path, order)?;
    }
    Ok(())
}

/// Enters the loop at its cell nearest the robot and drives once around.
fn drive_road(cells: &[Cell], path: &mut PathBuilder<'_>) -> Result<()> {
    let (_, i) = road_distance(cells, path.last());
    path.go_to(cell_center(cells[i]))?;
    let mut around: Vec<Cell> = cells[i..].iter().chain(&cells[..i]).copied().collect();
    // Close the loop so the stretch between its last and first cell is driven.
    if around.len() > 2 {
        around.push(cells[i]);
    }
    path.follow(&around, ROAD_TOLERANCE);
    Ok(())
}

fn nearest_index(items: &[usize], mut key: impl FnMut(usize) -> f64) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (k, &it) in items.iter().enumerate() {
        let d = key(it);
        if d < best.0 {
            best = (d, k);
        }
    }
    best.1
}

fn road_distance(cells: &[Cell], p: GridPoint) -> (f64, usize) {
    let mut best = (f64::INFINITY, 0);
    for (i, &c) in cells.iter().enumerate() {
        let q = cell_center(c);
        let d = (q.0 - p.0).hypot(q.1 - p.1);
        if d < best.0 {
            best = (d, i);
        }
    }
    best
}

fn region_distance(roads: &BorderExpansion, region: usize, p: GridPoint) -> f64 {
    roads.components[region]
        .roads
        .iter()
        .map(|&r| road_distance(&roads.roads[r].cells, p).0)
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;
    use oxcover_grid::traverse::segment_clear;
    use oxcover_grid::{CoarseGrid, Coverability, DiscRobot};

    fn plan(text: &str, block: usize) -> (BorderPlan, oxcover_grid::Grid<bool>) {
        let (map, start) = parse_ascii(text).unwrap();
        let p = Coverability::with_start_cell(&map, DiscRobot::cell_sized(1.0), start.unwrap())
            .unwrap();
        let coarse = CoarseGrid::new(&p.reachable, block);
        let input = PlannerInput::new(&p.reachable, &coarse, p.start);
        (
            BorderExpansionPlanner.plan_detailed(&input).unwrap(),
            p.reachable,
        )
    }

    #[test]
    fn starts_on_the_outer_road_and_drives_every_road() {
        let map = "S.........\n..........\n...##.....\n...##.....\n..........\n..........";
        let (p, m) = plan(map, 1);
        assert!(p.roads.roads[p.order[0]].outer && p.roads.roads[p.order[0]].level == 0);
        let mut seen = p.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..p.roads.roads.len()).collect::<Vec<_>>());
        let h = m.height() as f64;
        let pts: Vec<GridPoint> = p.points.iter().map(|q| (q.x, h - q.y)).collect();
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        // The outer road of a 10x6 room: around the border, back to the start.
        assert_eq!(
            &pts[..5],
            &[(0.5, 0.5), (9.5, 0.5), (9.5, 5.5), (0.5, 5.5), (0.5, 0.5)]
        );
    }

    #[test]
    fn stacked_obstacles_and_a_corridor() {
        for map in [
            "S......\n.......\n..##...\n.......\n..##...\n.......\n.......",
            "#########\n#S......#\n#########",
        ] {
            let (p, m) = plan(map, 1);
            assert!(!p.order.is_empty());
            let h = m.height() as f64;
            let pts: Vec<GridPoint> = p.points.iter().map(|q| (q.x, h - q.y)).collect();
            for w in pts.windows(2) {
                assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
            }
        }
    }
}
