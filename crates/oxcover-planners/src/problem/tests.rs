//! Tests of the coverage problem: its tightening, blocks, radii, start,
//! restriction to a region and lead-in.

use super::*;
use oxcover_grid::io::parse_ascii;

/// A walk over the plannable cells' centres from the start (metres),
/// each step to a 4-neighbour picked by `steps` (an index, wrapped).
fn walk(p: &CoverageProblem, steps: &[usize]) -> Vec<Point> {
    let mut here = p.start_cell();
    let mut out = vec![p.frame().cell_center(here)];
    for &k in steps {
        let next: Vec<Cell> = p
            .plannable()
            .neighbours4(here)
            .map(|(_, n)| n)
            .filter(|&n| p.plannable()[n])
            .collect();
        if next.is_empty() {
            break;
        }
        here = next[k % next.len()];
        out.push(p.frame().cell_center(here));
    }
    out
}

/// A 7 × 12 map of 1 m cells with the cells `blocked` (the first cell
/// stays free), for a robot of radius 0 and tool radius `tool`.
fn scattered(blocked: &[(usize, usize)], tool: f64) -> CoverageProblem {
    let mut rows = vec![vec!['.'; 12]; 7];
    for &(r, c) in blocked {
        if (r, c) != (0, 0) {
            rows[r][c] = '#';
        }
    }
    let text: Vec<String> = rows.iter().map(|r| r.iter().collect()).collect();
    let (map, _) = parse_ascii(&text.join("\n")).unwrap();
    CoverageProblem::new(&map, DiscRobot::new(0.0, tool).unwrap(), Start::First).unwrap()
}

/// Every coverable cell `path` covered (the metrics' own test) `tight`
/// still covers; `tight` never leaves the plannable cells and is never
/// slower.
fn still_covered_clear_and_no_slower(
    p: &CoverageProblem,
    path: &[Point],
    tight: &[Point],
) -> Result<(), proptest::test_runner::TestCaseError> {
    let (frame, tool) = (p.frame(), p.robot().tool_radius);
    let before = oxcover_grid::footprint::covered_cells(frame, path, tool);
    let after = oxcover_grid::footprint::covered_cells(frame, tight, tool);
    for c in before.true_cells() {
        proptest::prop_assert!(
            !p.cells().coverable[c] || after[c],
            "cell {:?} uncovered",
            c
        );
    }
    for w in metres_to_grid(frame, tight).windows(2) {
        proptest::prop_assert!(oxcover_grid::traverse::segment_clear(
            p.plannable(),
            w[0],
            w[1],
        ));
    }
    proptest::prop_assert!(p.time().polyline(tight) <= p.time().polyline(path) + 1e-9);
    Ok(())
}

proptest::proptest! {
    #[test]
    fn tightening_keeps_coverage_clearance_and_the_fixed_part(
        blocked in proptest::collection::vec((0usize..7, 0usize..12), 0..8),
        steps in proptest::collection::vec(0usize..4, 5..120),
        // Whole and half cells too: a walk through cell centres then
        // reaches cells exactly a tool radius away.
        tool in proptest::prop_oneof![
            proptest::sample::select(vec![1.0, 1.5, 2.0, 3.0]),
            0.6f64..2.5
        ],
        first in 0usize..20,
    ) {
        let p = scattered(&blocked, tool);
        let path = walk(&p, &steps);
        let first = first.min(path.len());
        let tight = p.tighten_from(&path, first);
        // With work beside it, the same path and that work's result.
        let (beside, n) = p.tighten_within_beside(&path, first, None, || path.len());
        proptest::prop_assert_eq!(&beside.0, &tight);
        proptest::prop_assert_eq!(n, path.len());
        // The fixed part stays, and the end too.
        proptest::prop_assert_eq!(&tight[..first], &path[..first]);
        proptest::prop_assert_eq!(tight.last(), path.last());
        still_covered_clear_and_no_slower(&p, &path, &tight)?;
    }
}

proptest::proptest! {
    /// Zoned, as the pipeline tightens a room-by-room plan: every
    /// waypoint kept lies in its own zone's cells (if it has one), the
    /// indices kept are the path's in order with both ends, coverage
    /// and clearance hold and the path is never slower. Waypoints are
    /// nudged off the cell centres by as little as new vertices are
    /// nudged off cell edges.
    #[test]
    fn zoned_tightening_keeps_each_waypoint_in_its_zone(
        blocked in proptest::collection::vec((0usize..7, 0usize..12), 0..8),
        steps in proptest::collection::vec(0usize..4, 5..120),
        tool in proptest::prop_oneof![
            proptest::sample::select(vec![1.0, 1.5, 2.0]),
            0.6f64..2.5
        ],
        zoned in proptest::collection::vec(proptest::bool::ANY, 120),
        nudge in proptest::collection::vec(-1i8..=1, 240),
    ) {
        let p = scattered(&blocked, tool);
        let frame = p.frame();
        let res = frame.resolution();
        let mut path = walk(&p, &steps);
        let last = path.len() - 1;
        for (i, q) in path.iter_mut().enumerate().skip(1).take(last.saturating_sub(1)) {
            q.x += f64::from(nudge[2 * i]) * 1e-4 * res;
            q.y += f64::from(nudge[2 * i + 1]) * 1e-4 * res;
        }
        // Zones: the left half of the map and the right.
        let (w, h) = (p.plannable().width(), p.plannable().height());
        let labels = Grid::from_fn(w, h, |c| if c.col < w / 2 { 1u32 } else { 2 });
        let of_vertex: Vec<u32> = path
            .iter()
            .enumerate()
            .map(|(i, q)| match frame.cell_at(q) {
                Some(c) if zoned[i] => labels[c],
                _ => 0,
            })
            .collect();
        let (tight, kept) = p.tighten_within(&path, 0, Some((&labels, &of_vertex)));
        proptest::prop_assert_eq!(tight.len(), kept.len());
        proptest::prop_assert_eq!(kept.first(), Some(&0));
        proptest::prop_assert_eq!(kept.last(), Some(&last));
        proptest::prop_assert!(kept.windows(2).all(|k| k[0] < k[1]));
        for (q, &i) in tight.iter().zip(&kept) {
            if of_vertex[i] != 0 {
                let c = frame.cell_at(q).unwrap();
                proptest::prop_assert_eq!(labels[c], of_vertex[i], "waypoint {} left its zone", i);
            }
        }
        still_covered_clear_and_no_slower(&p, &path, &tight)?;
    }
}

#[test]
fn a_wiggle_along_a_row_is_taken_out() {
    // A route up and down a row of cell centres, one cell at a time:
    // tightening leaves a straight run (the ends), with the same cells
    // covered.
    let (map, _) = parse_ascii("........\n........").unwrap();
    let p = CoverageProblem::new(&map, DiscRobot::new(0.0, 1.0).unwrap(), Start::First).unwrap();
    let f = p.frame();
    let mut path: Vec<Point> = (0..8).map(|c| f.cell_center(Cell::new(0, c))).collect();
    path.push(f.cell_center(Cell::new(1, 7)));
    let tight = p.tighten_from(&path, 1);
    assert!(tight.len() < path.len());
    assert!(p.time().polyline(&tight) < p.time().polyline(&path));
    let before = oxcover_grid::footprint::covered_cells(f, &path, 1.0);
    let after = oxcover_grid::footprint::covered_cells(f, &tight, 1.0);
    assert_eq!(before, after);
}

#[test]
fn block_is_one_tool_diameter() {
    assert_eq!(coarse_block(&DiscRobot::cell_sized(0.05), 0.05), 1);
    assert_eq!(coarse_block(&DiscRobot::new(0.15, 0.15).unwrap(), 0.05), 6);
    assert_eq!(coarse_block(&DiscRobot::new(0.0, 0.01).unwrap(), 0.05), 1);
}

#[test]
fn one_tool_radius_everywhere() {
    let (map, _) = parse_ascii("........\n........\n........\n........").unwrap();
    let p = CoverageProblem::new(&map, DiscRobot::new(0.0, 1.6).unwrap(), Start::First).unwrap();
    let input = p.input(7);
    assert_eq!(p.block(), 3);
    assert_eq!((input.tool_cells, p.tool_cells()), (1.6, 1.6));
    assert_eq!(input.visit_radius(), 1.5);
    assert_eq!(input.seed, 7);
}

#[test]
fn largest_region_beats_the_first_cell() {
    let (map, _) = parse_ascii(".#....\n##....\n......").unwrap();
    let robot = DiscRobot::cell_sized(1.0);
    let first = CoverageProblem::new(&map, robot, Start::First).unwrap();
    assert_eq!(first.start_cell(), Cell::new(0, 0));
    let big = CoverageProblem::new(&map, robot, Start::LargestRegion).unwrap();
    assert_eq!(big.start_cell(), Cell::new(0, 2));
    assert_eq!(big.plannable().count_true(), 14);
}

#[test]
fn restriction_keeps_the_region_and_refuses_starts_outside_it() {
    let (map, _) = parse_ascii("....#....\n.........\n....#....").unwrap();
    let p = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).unwrap();
    let left = Grid::from_fn(9, 3, |c: Cell| c.col < 4);
    let r = p.restricted(&left, Cell::new(1, 1)).unwrap();
    assert_eq!(r.plannable().count_true(), 12);
    assert_eq!(r.cells().coverable.count_true(), 12);
    // Cropped to the region and its margin; the same metres in both frames.
    assert_eq!((r.frame().width(), r.offset()), (7, Cell::new(0, 0)));
    let right = Grid::from_fn(9, 3, |c: Cell| c.col > 4);
    let q = p.restricted(&right, Cell::new(0, 8)).unwrap();
    assert_eq!(q.offset(), Cell::new(0, 2));
    let local = q.start_cell();
    assert_eq!(q.to_map_cell(local), Cell::new(0, 8));
    assert_eq!(
        q.frame().cell_center(local),
        p.frame().cell_center(Cell::new(0, 8))
    );
    assert!(p.restricted(&left, Cell::new(1, 6)).is_err());
    let small = Grid::new(2, 2, true);
    assert!(p.restricted(&small, Cell::new(0, 0)).is_err());
}

#[test]
fn lead_in_is_a_shortest_path() {
    let (map, _) = parse_ascii("...\n.#.\n...").unwrap();
    let p = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).unwrap();
    assert_eq!(p.lead_in(None).unwrap(), vec![Cell::new(0, 0)]);
    assert_eq!(p.lead_in(Some(Cell::new(2, 2))).unwrap().len(), 5);
}
