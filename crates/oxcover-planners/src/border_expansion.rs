//! Border-expansion coverage (Pavlíček et al. 2002, §5).
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
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};

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
        let mut walk = Walk {
            roads: &roads,
            index: RoadIndex::new(&roads, input.plannable.width(), input.plannable.height()),
            driven: vec![false; roads.roads.len()],
            wanted_by: vec![None; roads.components.len()],
            path: PathBuilder::new(input.plannable, start),
            order: Vec::new(),
        };
        // Roots: level-0 regions (one when the plannable set is connected),
        // nearest first. `usize::MAX` stands for "no parent".
        let mut roots = 0;
        for (c, comp) in roads.components.iter().enumerate() {
            if comp.level == 0 {
                walk.wanted_by[c] = Some(usize::MAX);
                roots += 1;
            }
        }
        for _ in 0..roots {
            let Some(root) = walk.nearest_wanted(usize::MAX) else {
                break;
            };
            walk.wanted_by[root] = None;
            walk.region(root)?;
        }
        let Walk {
            mut path, order, ..
        } = walk;
        path.cover_leftovers(input.coarse, input.visit_radius())?;
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
        "border expansion (Pavlicek et al. 2002): closed roads offset from every border, outer road first"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Metres(self.plan_detailed(input)?.points))
    }
}

/// The walk over the road graph.
struct Walk<'r, 'p> {
    roads: &'r BorderExpansion,
    index: RoadIndex,
    /// Roads already driven.
    driven: Vec<bool>,
    /// Per component: the region whose walk is about to enter it.
    wanted_by: Vec<Option<usize>>,
    path: PathBuilder<'p>,
    order: Vec<usize>,
}

impl Walk<'_, '_> {
    /// Drives the roads of `region` (outer road first, then nearest first),
    /// then its inner regions, nearest first.
    fn region(&mut self, region: usize) -> Result<()> {
        let comp = &self.roads.components[region];
        if let Some(&outer) = comp.roads.first() {
            self.drive(outer)?;
        }
        let roads = self.roads;
        // Exactly as many queries as there are roads and children left, so
        // no search ever runs over the whole map to find nothing.
        for _ in 1..comp.roads.len() {
            let here = self.path.last();
            let driven = &self.driven;
            let Some((r, _)) = self
                .index
                .nearest(here, |r| !driven[r] && roads.roads[r].component == region)
            else {
                break;
            };
            self.drive(r)?;
        }
        for &child in &comp.children {
            self.wanted_by[child] = Some(region);
        }
        for _ in 0..comp.children.len() {
            let Some(child) = self.nearest_wanted(region) else {
                break;
            };
            self.wanted_by[child] = None;
            self.region(child)?;
        }
        Ok(())
    }

    /// The component wanted by `parent` with a road nearest the robot.
    fn nearest_wanted(&mut self, parent: usize) -> Option<usize> {
        let (roads, wanted) = (self.roads, &self.wanted_by);
        self.index
            .nearest(self.path.last(), |r| {
                wanted[roads.roads[r].component] == Some(parent)
            })
            .map(|(r, _)| roads.roads[r].component)
    }

    fn drive(&mut self, r: usize) -> Result<()> {
        self.driven[r] = true;
        self.order.push(r);
        drive_road(&self.roads.roads[r].cells, &mut self.path)
    }
}

/// Road cells bucketed by square blocks of the grid, for nearest-road
/// queries that look only near the robot (a scan over every road at every
/// step is quadratic on cluttered maps with thousands of roads).
struct RoadIndex {
    block: usize,
    bw: usize,
    bh: usize,
    /// Per block: (road, cell centre).
    buckets: Vec<Vec<(usize, GridPoint)>>,
}

impl RoadIndex {
    const BLOCK: usize = 16;

    fn new(roads: &BorderExpansion, width: usize, height: usize) -> Self {
        let block = Self::BLOCK;
        let (bw, bh) = (width.div_ceil(block).max(1), height.div_ceil(block).max(1));
        let mut buckets = vec![Vec::new(); bw * bh];
        for (r, road) in roads.roads.iter().enumerate() {
            for &c in &road.cells {
                buckets[(c.row / block) * bw + c.col / block].push((r, cell_center(c)));
            }
        }
        Self {
            block,
            bw,
            bh,
            buckets,
        }
    }

    /// The road accepted by `keep` with a cell nearest to `p` (Euclidean;
    /// ties to the lower road index), and that distance.
    fn nearest(&self, p: GridPoint, keep: impl Fn(usize) -> bool) -> Option<(usize, f64)> {
        let k = self.block as f64;
        let bx = ((p.x / k).floor().max(0.0) as usize).min(self.bw - 1);
        let by = ((p.y / k).floor().max(0.0) as usize).min(self.bh - 1);
        let mut best: Option<(f64, usize)> = None;
        for ring in 0..self.bw.max(self.bh) {
            // Every cell of a farther ring is at least `ring · block` away.
            if best.is_some_and(|(d, _)| d <= ring.saturating_sub(1) as f64 * k) {
                break;
            }
            let (x0, x1) = (bx.saturating_sub(ring), (bx + ring).min(self.bw - 1));
            let (y0, y1) = (by.saturating_sub(ring), (by + ring).min(self.bh - 1));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if x.abs_diff(bx).max(y.abs_diff(by)) != ring {
                        continue;
                    }
                    for &(r, q) in &self.buckets[y * self.bw + x] {
                        let d = (q.x - p.x).hypot(q.y - p.y);
                        if best.is_none_or(|b| (d, r) < b) && keep(r) {
                            best = Some((d, r));
                        }
                    }
                }
            }
        }
        best.map(|(d, r)| (r, d))
    }
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

fn road_distance(cells: &[Cell], p: GridPoint) -> (f64, usize) {
    let mut best = (f64::INFINITY, 0);
    for (i, &c) in cells.iter().enumerate() {
        let q = cell_center(c);
        let d = (q.x - p.x).hypot(q.y - p.y);
        if d < best.0 {
            best = (d, i);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    use oxcover_grid::traverse::segment_clear;

    fn plan(text: &str, block: usize) -> (BorderPlan, oxcover_grid::Grid<bool>) {
        let p = crate::testing::problem(text, block);
        (
            BorderExpansionPlanner.plan_detailed(&p.input(0)).unwrap(),
            p.plannable().clone(),
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
        let pts: Vec<GridPoint> = p
            .points
            .iter()
            .map(|q| GridPoint::new(q.x, h - q.y))
            .collect();
        for w in pts.windows(2) {
            assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
        }
        // The outer road of a 10x6 room: around the border, back to the start.
        assert_eq!(
            &pts[..5],
            &[
                GridPoint::new(0.5, 0.5),
                GridPoint::new(9.5, 0.5),
                GridPoint::new(9.5, 5.5),
                GridPoint::new(0.5, 5.5),
                GridPoint::new(0.5, 0.5)
            ]
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
            let pts: Vec<GridPoint> = p
                .points
                .iter()
                .map(|q| GridPoint::new(q.x, h - q.y))
                .collect();
            for w in pts.windows(2) {
                assert!(segment_clear(&m, w[0], w[1]), "{w:?}");
            }
        }
    }
}
