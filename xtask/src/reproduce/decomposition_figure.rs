//! A picture in the spirit of Pavlíček 2002's Fig. 8, four panels in a 2×2 grid:
//! (a) the trapezoidal and (b) the boustrophedon decomposition of one map,
//! each cell in its own colour, drawn as the band its lanes sweep; (c) the
//! boustrophedon adjacency graph (a node at each cell's lane centroid); (d)
//! the border-expansion roads coloured by safety level (blue at the walls,
//! red at the centre) with their adjacency graph over them, as Fig. 10 (a)
//! and (c) draw it: a node on each road (its cell nearest the road's
//! centroid), an edge for each possible transition between two roads.

use std::path::Path;

use oxcover_decomp::{BorderExpansion, SliceDecomposition};
use oxcover_grid::Grid;
use tiny_skia::{IntSize, Pixmap};

/// Pastel cell colours; neighbouring cell indices get distant entries.
const PALETTE: [[u8; 3]; 10] = [
    [141, 211, 199],
    [255, 237, 111],
    [190, 186, 218],
    [251, 128, 114],
    [128, 177, 211],
    [253, 180, 98],
    [179, 222, 105],
    [252, 205, 229],
    [188, 128, 189],
    [204, 235, 197],
];
const WALL: [u8; 3] = [70, 70, 70];
const OUTSIDE: [u8; 3] = [215, 215, 215];
const FREE: [u8; 3] = [255, 255, 255];
/// Gap between panels, in map pixels.
const GAP: usize = 8;

/// One panel: RGB per map pixel.
type Panel = Grid<[u8; 3]>;

fn base(plannable: &Grid<bool>, free: &Grid<bool>) -> Panel {
    Grid::from_fn(plannable.width(), plannable.height(), |c| {
        if plannable[c] {
            FREE
        } else if free[c] {
            OUTSIDE
        } else {
            WALL
        }
    })
}

/// Each cell's lanes widened to the lane spacing, in the cell's colour.
fn cells_panel(d: &SliceDecomposition, plannable: &Grid<bool>, free: &Grid<bool>) -> Panel {
    let mut px = base(plannable, free);
    let (s, a) = (d.slices.spacing(), d.slices.angle());
    let normal = (a.sin(), a.cos());
    for (id, lanes) in d.cells.iter().enumerate() {
        let colour = PALETTE[(id * 3) % PALETTE.len()];
        for lane in lanes {
            let mut t = lane.interval.lo;
            while t <= lane.interval.hi {
                let p = d.slices.point(lane.line, t);
                let mut o = -s / 2.0;
                while o < s / 2.0 {
                    let q = oxcover_grid::Point::new(p.x + o * normal.0, p.y + o * normal.1);
                    if let Some(c) = oxcover_grid::traverse::cell_of(plannable, q)
                        && plannable[c]
                    {
                        px[c] = colour;
                    }
                    o += 0.5;
                }
                t += 0.5;
            }
        }
    }
    px
}

/// The adjacency graph over the cells: nodes at lane centroids, straight edges.
fn graph_panel(d: &SliceDecomposition, plannable: &Grid<bool>, free: &Grid<bool>) -> Panel {
    let mut px = cells_panel(d, plannable, free);
    let centres: Vec<(f64, f64)> = d
        .cells
        .iter()
        .map(|lanes| {
            let n = lanes.len().max(1) as f64;
            let (sx, sy) = lanes.iter().fold((0.0, 0.0), |(sx, sy), l| {
                let p = d
                    .slices
                    .point(l.line, (l.interval.lo + l.interval.hi) / 2.0);
                (sx + p.x, sy + p.y)
            });
            (sx / n, sy / n)
        })
        .collect();
    draw_graph(&mut px, &centres, &d.edges);
    for &c in &centres {
        dot(&mut px, c, 2, [200, 0, 0]);
    }
    px
}

/// A filled square of side `2r + 1` pixels centred on `p`.
fn dot(px: &mut Panel, p: (f64, f64), r: i64, colour: [u8; 3]) {
    for dy in -r..=r {
        for dx in -r..=r {
            let q = oxcover_grid::Point::new(p.0 + dx as f64, p.1 + dy as f64);
            if let Some(c) = oxcover_grid::traverse::cell_of(px, q) {
                px[c] = colour;
            }
        }
    }
}

/// The edges of a graph as dark straight lines between its node positions.
fn draw_graph(px: &mut Panel, nodes: &[(f64, f64)], edges: &[(usize, usize)]) {
    for &(a, b) in edges {
        let (p, q) = (nodes[a], nodes[b]);
        let n = (q.0 - p.0).abs().max((q.1 - p.1).abs()).ceil().max(1.0) as usize;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            dot(
                px,
                (p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)),
                0,
                [20, 20, 20],
            );
        }
    }
}

/// Road cells coloured by level, and the road adjacency graph.
fn roads_panel(b: &BorderExpansion, plannable: &Grid<bool>, free: &Grid<bool>) -> Panel {
    let mut px = base(plannable, free);
    let top = b.levels.max(2) - 1;
    for road in &b.roads {
        let f = road.level as f64 / top as f64;
        let colour = [
            (40.0 + 215.0 * f) as u8,
            (90.0 * (1.0 - (2.0 * f - 1.0).abs())) as u8,
            (220.0 * (1.0 - f)) as u8,
        ];
        for &c in &road.cells {
            px[c] = colour;
        }
    }
    // Fig. 10c: a node on each road, an edge per possible transition.
    let nodes: Vec<(f64, f64)> = b
        .roads
        .iter()
        .map(|road| {
            let n = road.cells.len().max(1) as f64;
            let (sr, sc) = road
                .cells
                .iter()
                .fold((0.0, 0.0), |(r, c), x| (r + x.row as f64, c + x.col as f64));
            let (mr, mc) = (sr / n, sc / n);
            let d =
                |x: &oxcover_grid::Cell| (x.row as f64 - mr).powi(2) + (x.col as f64 - mc).powi(2);
            road.cells
                .iter()
                .min_by(|a, b| d(a).total_cmp(&d(b)))
                .map_or((mc + 0.5, mr + 0.5), |x| {
                    (x.col as f64 + 0.5, x.row as f64 + 0.5)
                })
        })
        .collect();
    draw_graph(&mut px, &nodes, &b.edges);
    for &p in &nodes {
        dot(&mut px, p, 2, [0, 0, 0]);
        dot(&mut px, p, 1, [255, 255, 255]);
    }
    px
}

/// Writes the four panels in a 2×2 grid, each map pixel `scale`×`scale`.
///
/// # Errors
/// When the picture cannot be allocated or written.
pub(crate) fn write(
    out: &Path,
    plannable: &Grid<bool>,
    free: &Grid<bool>,
    trapezoidal: &SliceDecomposition,
    boustrophedon: &SliceDecomposition,
    roads: &BorderExpansion,
    scale: usize,
) -> anyhow::Result<()> {
    let panels = [
        cells_panel(trapezoidal, plannable, free),
        cells_panel(boustrophedon, plannable, free),
        graph_panel(boustrophedon, plannable, free),
        roads_panel(roads, plannable, free),
    ];
    let (w, h) = (plannable.width(), plannable.height());
    let total_w = (2 * w + GAP) * scale;
    let total_h = (2 * h + GAP) * scale;
    let mut rgba = vec![255u8; total_w * total_h * 4];
    for (k, panel) in panels.iter().enumerate() {
        let (x0, y0) = ((k % 2) * (w + GAP), (k / 2) * (h + GAP));
        for c in panel.cells() {
            let rgb = panel[c];
            for dy in 0..scale {
                for dx in 0..scale {
                    let (x, y) = ((x0 + c.col) * scale + dx, (y0 + c.row) * scale + dy);
                    let i = (y * total_w + x) * 4;
                    rgba[i..i + 3].copy_from_slice(&rgb);
                }
            }
        }
    }
    let size = IntSize::from_wh(total_w as u32, total_h as u32)
        .ok_or_else(|| anyhow::anyhow!("figure of {total_w}x{total_h} px"))?;
    let pm = Pixmap::from_vec(rgba, size)
        .ok_or_else(|| anyhow::anyhow!("cannot build a {total_w}x{total_h} picture"))?;
    pm.save_png(out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn four_panels_of_the_map_size() {
        let (map, _) = parse_ascii(
            "
            ..........
            ..##......
            ..##...#..
            .......#..
            ..........
            ",
        )
        .expect("valid map");
        let free = map.free_mask();
        let trap = oxcover_decomp::trapezoidal(&free, 0.0, 1.0);
        let bous = oxcover_decomp::boustrophedon(&free, 0.0, 1.0);
        let roads = oxcover_decomp::border_expansion(&free, 1.0);
        let out = std::env::temp_dir().join(format!("fig8-{}.png", std::process::id()));
        write(&out, &free, &free, &trap, &bous, &roads, 2).expect("written");
        let png = Pixmap::load_png(&out).expect("a PNG");
        assert_eq!(
            (png.width(), png.height()),
            (2 * (2 * 10 + GAP as u32), 2 * (2 * 5 + GAP as u32))
        );
        // The obstacle pixel (row 1, col 2) stays wall-coloured in panel (a).
        let px = png.pixel(2 * 2, 2).expect("inside");
        assert_eq!(
            (px.red(), px.green(), px.blue()),
            (WALL[0], WALL[1], WALL[2])
        );
        // A free pixel of panel (a) is painted with a cell colour.
        let px = png.pixel(0, 0).expect("inside");
        assert!(PALETTE.contains(&[px.red(), px.green(), px.blue()]));
        let _ = std::fs::remove_file(out);
    }
}
