//! Priority coverage over a rectangular decomposition (Zhang & Yan 2008).
//!
//! **Global planning** walks the interleaving network of the
//! [`RectangularDecomposition`]: from the current node it looks at the eight
//! neighbouring nodes and computes `P[i] = C[i]·T[i]·L[i]` (eq. 1): `C` = 1 if
//! the neighbour's area is not covered yet, `T` = 1 if it is connectible, `L`
//! the user priority of Fig. 7 (south 1, west 0.9, east 0.8, south-west 0.7,
//! south-east 0.6, north 0.5, north-west 0.4, north-east 0.3; row 0 of the map
//! is north). It moves to the direction of `P_max` (eq. 2–3). A *dead node*
//! (every neighbour covered or not connectible) escapes to the nearest
//! uncovered node by the anti-gradient of a wavefront (a shortest fine path).
//!
//! **Local planning** covers each node's rectangle with a template, starting
//! and ending at the node (the paper: "each local path planning starts from the
//! node and ends at the node"): a spiral when nothing is nearby, otherwise
//! horizontal back-and-forth lanes when the rectangle is at least as wide as
//! tall, vertical ones when taller, one square apart through the grown
//! squares. With squares one tool wide, a rectangle that did not grow is one
//! square, where every template reduces to the node centre; and a rectangle
//! only grows next to an obstacle, so grown ones always take back-and-forth.
//! The spiral therefore never changes a path in this reading.
//!
//! Every move, global or local, is a fine, collision-free cell path. The paper
//! reports coverage above 90 % and repetition below 10 % rather than
//! completeness: cells in no rectangle stay uncovered (the boundary pass takes
//! them), so this planner does not promise complete coverage.

use oxcover_decomp::RectangularDecomposition;
use oxcover_distance::{Wavefront, cidt};
use oxcover_grid::{Cell, Dir8, Grid};

use crate::error::{Error, Result};
use crate::planner::Planner;
use crate::problem::{PlanOutput, PlannerInput};

/// Fig. 7: the user priority `L` of each direction (F = south = 1 highest).
pub const PRIORITY: [(Dir8, f64); 8] = [
    (Dir8::South, 1.0),
    (Dir8::West, 0.9),
    (Dir8::East, 0.8),
    (Dir8::SouthWest, 0.7),
    (Dir8::SouthEast, 0.6),
    (Dir8::North, 0.5),
    (Dir8::NorthWest, 0.4),
    (Dir8::NorthEast, 0.3),
];

/// The `rect-priority` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RectPriority;

impl RectPriority {
    /// The planner.
    #[must_use]
    pub const fn new() -> Self {
        Self
    }
}

impl Planner for RectPriority {
    fn name(&self) -> &'static str {
        "rect-priority"
    }
    fn complete(&self) -> bool {
        false
    }
    fn summary(&self) -> &'static str {
        "rectangular decomposition + 8-direction priority P = C*T*L (Zhang & Yan 2008), local templates"
    }
    fn plan(&self, input: &PlannerInput<'_>) -> Result<PlanOutput> {
        Ok(PlanOutput::Fine(rect_priority(input)?))
    }
}

/// Walks the interleaving network; returns the fine path from the start node's centre.
///
/// # Errors
/// [`Error::Internal`] if the start node is virtual or a planned move has no fine path.
pub fn rect_priority(input: &PlannerInput<'_>) -> Result<Vec<Cell>> {
    let coarse = input.coarse;
    let plannable = input.plannable;
    let dec = RectangularDecomposition::new(plannable, coarse);
    let start_rep = coarse
        .representative(input.start)
        .ok_or_else(|| Error::Internal(format!("start node {:?} is virtual", input.start)))?;
    let mut wave = Wavefront::new(plannable);
    let mut covered = Grid::new(coarse.width(), coarse.height(), false);
    let mut left = coarse.passable().count_true();
    let mut path = vec![start_rep];
    let mut cur = input.start;
    loop {
        if !covered[cur] {
            local_coverage(&dec, cur, &mut wave, &mut path)?;
            covered[cur] = true;
            left -= 1;
        }
        if left == 0 {
            break;
        }
        let best = PRIORITY
            .iter()
            .filter_map(|&(d, l)| {
                let m = covered.offset(cur, d.offset())?;
                let c = if covered[m] || coarse.representative(m).is_none() {
                    0.0
                } else {
                    1.0
                };
                let t = if dec.connectible(cur, d) { 1.0 } else { 0.0 };
                let p = c * t * l;
                (p > 0.0).then_some((p, m))
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, m)) = best {
            let seg = coarse.connect(plannable, cur, m).ok_or_else(|| {
                Error::Internal(format!(
                    "connectible nodes {cur:?} -> {m:?} have no fine path"
                ))
            })?;
            path.extend_from_slice(&seg[1..]);
            cur = m;
        } else {
            // Dead node: the nearest uncovered node centre by wavefront.
            let here = *path.last().unwrap_or(&start_rep);
            let near = cidt(&mut wave, &[here], |c| {
                let n = coarse.coarse_of(c);
                coarse.representative(n) == Some(c) && !covered[n]
            })
            .ok_or_else(|| Error::Internal("uncovered node unreachable".into()))?;
            let seg = wave
                .retrace(near.first())
                .ok_or_else(|| Error::Internal("dead-node retrace failed".into()))?;
            path.extend_from_slice(&seg[1..]);
            cur = coarse.coarse_of(near.first());
        }
    }
    Ok(path)
}

/// Maps a cell to (lane coordinate, position along the lane).
type Along = fn(Cell) -> (usize, usize);

/// Appends the local template of `node`, from and back to its centre.
fn local_coverage(
    dec: &RectangularDecomposition,
    node: Cell,
    wave: &mut Wavefront,
    path: &mut Vec<Cell>,
) -> Result<()> {
    let coarse = dec.nodes();
    let (Some(rect), Some(rep)) = (dec.rectangle(node), coarse.representative(node)) else {
        return Ok(());
    };
    if rect.grown == 0 {
        // A one-square rectangle: every template (spiral or one lane) reduces
        // to the node centre, where the tool covers the square.
        return Ok(());
    }
    let cells = dec.cells_of(node);
    let horizontal = rect.width_nodes() >= rect.height_nodes();
    let k = coarse.block_size();
    // One lane per square row (horizontal) or column (vertical) of the
    // rectangle, on the fine line nearest the node's lane shifted by whole squares.
    let (spans, along): (Vec<usize>, Along) = if horizontal {
        (rect.node_rows.clone().collect(), |c| (c.row, c.col))
    } else {
        (rect.node_cols.clone().collect(), |c| (c.col, c.row))
    };
    let own_line = along(rep).0;
    let own_square = if horizontal { node.row } else { node.col };
    let mut targets: Vec<Cell> = Vec::new();
    let mut forward = true;
    for s in spans {
        let nominal = (own_line + s * k).saturating_sub(own_square * k);
        let lines: std::collections::BTreeSet<usize> = cells
            .iter()
            .map(|&c| along(c).0)
            .filter(|&l| l / k == s)
            .collect();
        let Some(&line) = lines.iter().min_by_key(|&&l| (l.abs_diff(nominal), l)) else {
            continue;
        };
        let on_line: Vec<usize> = cells
            .iter()
            .filter(|&&c| along(c).0 == line)
            .map(|&c| along(c).1)
            .collect();
        let (Some(&lo), Some(&hi)) = (on_line.iter().min(), on_line.iter().max()) else {
            continue;
        };
        let cell = |pos: usize| {
            if horizontal {
                Cell::new(line, pos)
            } else {
                Cell::new(pos, line)
            }
        };
        let (a, b) = if forward { (lo, hi) } else { (hi, lo) };
        targets.push(cell(a));
        targets.push(cell(b));
        forward = !forward;
    }
    targets.push(rep);
    let mut here = *path.last().unwrap_or(&rep);
    for t in targets {
        if t == here {
            continue;
        }
        let near = cidt(wave, &[here], |c| c == t)
            .ok_or_else(|| Error::Internal(format!("lane end {t:?} unreachable")))?;
        let seg = wave
            .retrace(near.first())
            .ok_or_else(|| Error::Internal("lane retrace failed".into()))?;
        path.extend_from_slice(&seg[1..]);
        here = t;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{cells, plan_cells};

    #[test]
    fn exact_path_on_a_small_room() {
        // Unit squares. From S: south (1.0) first, then east (0.8) twice, then
        // north (0.5), then west (0.9) back to the last square.
        let (_, fine) = plan_cells(&RectPriority::new(), "S..\n...", 1);
        assert_eq!(
            fine,
            cells(&[(0, 0), (1, 0), (1, 1), (1, 2), (0, 2), (0, 1)])
        );
    }

    #[test]
    fn exact_path_with_a_dead_node() {
        // From S: south is a wall, east (0.8) beats south-east (0.6). At (0,1)
        // south (1.0); at (1,1) south again; at (2,1) west (0.9) beats east
        // (0.8). (2,0) is a dead node (its neighbours are covered or walls):
        // the wavefront leads to the nearest uncovered node, (2,2), then north
        // (0.5) twice.
        let (_, fine) = plan_cells(&RectPriority::new(), "S..\n#..\n...", 1);
        assert_eq!(
            fine,
            cells(&[
                (0, 0),
                (0, 1),
                (1, 1),
                (2, 1),
                (2, 0),
                (2, 1),
                (2, 2),
                (1, 2),
                (0, 2)
            ])
        );
    }
}
