//! Areas onto the map's cells, in the contract's terms: the cells whose
//! square meets a polygon (boundary included), the cells whose square a
//! line touches, the cells whose centre lies inside a polygon (holes
//! excluded, boundary included) or within a disc.
//!
//! Geometry is carried into grid coordinates first (`u` along columns, `v`
//! along rows from the image's top, cell `(r, c)` the square
//! `[c, c+1] x [r, r+1]`), so a rotated map frame costs nothing more.

use geo::{Coord, LineString, MapCoords, Polygon};
use oxcover_grid::{Cell, Grid, MapFrame, Point};

/// `p` (metres, map frame) in grid coordinates.
fn grid_coord(frame: &MapFrame, p: Coord<f64>) -> Coord<f64> {
    let (row, col) = frame.fractional_cell(&Point::new(p.x, p.y));
    Coord {
        x: col + 0.5,
        y: row + 0.5,
    }
}

/// How an area lies on the map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Placement {
    /// Cells marked.
    pub cells: usize,
    /// Whether part of the area lies outside the map (clipped).
    pub clipped: bool,
}

impl std::ops::AddAssign for Placement {
    fn add_assign(&mut self, other: Self) {
        self.cells += other.cells;
        self.clipped |= other.clipped;
    }
}

/// The cells whose squares the grid-space bounding box `(lo, hi)` meets,
/// clipped to the map, and whether it had to be clipped.
fn cell_range(
    (w, h): (usize, usize),
    lo: Coord<f64>,
    hi: Coord<f64>,
) -> (Option<(Cell, Cell)>, bool) {
    let clipped = lo.x < 0.0 || lo.y < 0.0 || hi.x > w as f64 || hi.y > h as f64;
    // Squares [c, c+1] meeting [lo, hi]: c from ceil(lo) - 1 to floor(hi).
    let first = |a: f64| (a.ceil() - 1.0).max(0.0);
    let (c0, r0) = (first(lo.x), first(lo.y));
    let (c1, r1) = (
        hi.x.floor().min(w as f64 - 1.0),
        hi.y.floor().min(h as f64 - 1.0),
    );
    if w == 0 || h == 0 || c0 > c1 || r0 > r1 {
        return (None, clipped);
    }
    (
        Some((
            Cell::new(r0 as usize, c0 as usize),
            Cell::new(r1 as usize, c1 as usize),
        )),
        clipped,
    )
}

fn bbox(coords: impl Iterator<Item = Coord<f64>>) -> (Coord<f64>, Coord<f64>) {
    let mut lo = Coord {
        x: f64::INFINITY,
        y: f64::INFINITY,
    };
    let mut hi = Coord {
        x: f64::NEG_INFINITY,
        y: f64::NEG_INFINITY,
    };
    for c in coords {
        lo.x = lo.x.min(c.x);
        lo.y = lo.y.min(c.y);
        hi.x = hi.x.max(c.x);
        hi.y = hi.y.max(c.y);
    }
    (lo, hi)
}

fn for_range(range: (Cell, Cell), mut f: impl FnMut(Cell)) {
    let (a, b) = range;
    for r in a.row..=b.row {
        for c in a.col..=b.col {
            f(Cell::new(r, c));
        }
    }
}

/// Marks in `mark` every cell whose square meets `polygon` (metres, map
/// frame; boundary included): a closed square meets a closed polygon
/// exactly when its centre lies inside or the polygon's boundary touches
/// it, so the cells are those of [`polygon_centres`] and those every ring
/// touches ([`line_squares`]).
pub fn polygon_squares(
    frame: &MapFrame,
    polygon: &Polygon<f64>,
    mark: &mut Grid<bool>,
) -> Placement {
    let mut placed = polygon_centres(frame, polygon, mark);
    for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
        placed += line_squares(frame, ring, mark);
    }
    placed
}

/// Marks in `mark` every cell whose centre lies inside `polygon` (metres,
/// map frame; on its boundary counts as inside, in a hole as outside).
///
/// A scanline per row of cell centres: each ring edge adds its crossing of
/// the rows it spans (half-open in the row coordinate, so a vertex is
/// counted once), the crossings sorted, and the centres between each pair
/// marked (even-odd over all rings, holes included). Centres exactly on a
/// horizontal edge or a vertex, which the half-open rule may miss, are
/// marked too. The work is the edges' row crossings and the cells marked,
/// whatever the polygon's size.
pub fn polygon_centres(
    frame: &MapFrame,
    polygon: &Polygon<f64>,
    mark: &mut Grid<bool>,
) -> Placement {
    let g = polygon.map_coords(|p| grid_coord(frame, p));
    let (lo, hi) = bbox(g.exterior().coords().copied());
    let (w, h) = (mark.width(), mark.height());
    let (range, clipped) = cell_range((w, h), lo, hi);
    let mut placed = Placement { cells: 0, clipped };
    let Some((first, last)) = range else {
        return placed;
    };
    let rings: Vec<&LineString<f64>> = std::iter::once(g.exterior()).chain(g.interiors()).collect();
    // Row r's centres lie at v = r + 0.5.
    let rows = last.row - first.row + 1;
    let mut crossings: Vec<Vec<f64>> = vec![Vec::new(); rows];
    let mut set = |r: usize, c: usize, placed: &mut Placement| {
        let cell = Cell::new(r, c);
        placed.cells += usize::from(!mark[cell]);
        mark[cell] = true;
    };
    let row_of = |v: f64| -> Option<usize> {
        let r = v - 0.5;
        (r.fract() == 0.0 && r >= first.row as f64 && r <= last.row as f64).then_some(r as usize)
    };
    let col_of = |u: f64| -> Option<usize> {
        let c = u - 0.5;
        (c.fract() == 0.0 && c >= first.col as f64 && c <= last.col as f64).then_some(c as usize)
    };
    for ring in &rings {
        for l in ring.lines() {
            let (a, b) = (l.start, l.end);
            // A vertex exactly on a centre.
            if let (Some(r), Some(c)) = (row_of(a.y), col_of(a.x)) {
                set(r, c, &mut placed);
            }
            if a.y == b.y {
                // A horizontal edge exactly on a row of centres.
                if let Some(r) = row_of(a.y) {
                    let (x0, x1) = (a.x.min(b.x), a.x.max(b.x));
                    let c0 = (x0 - 0.5).ceil().max(first.col as f64);
                    let c1 = (x1 - 0.5).floor().min(last.col as f64);
                    let mut c = c0;
                    while c <= c1 {
                        set(r, c as usize, &mut placed);
                        c += 1.0;
                    }
                }
                continue;
            }
            let (ylo, yhi) = (a.y.min(b.y), a.y.max(b.y));
            // Rows whose centre v satisfies ylo <= v < yhi.
            let r0 = ((ylo - 0.5).ceil()).max(first.row as f64);
            let r1 = ((yhi - 0.5).ceil() - 1.0).min(last.row as f64);
            let mut r = r0;
            while r <= r1 {
                let v = r + 0.5;
                let x = a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y);
                crossings[r as usize - first.row].push(x);
                r += 1.0;
            }
        }
    }
    for (k, xs) in crossings.iter_mut().enumerate() {
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            let c0 = (pair[0] - 0.5).ceil().max(first.col as f64);
            let c1 = (pair[1] - 0.5).floor().min(last.col as f64);
            let mut c = c0;
            while c <= c1 {
                set(first.row + k, c as usize, &mut placed);
                c += 1.0;
            }
        }
    }
    placed
}

/// Marks in `mark` every cell whose square `line` (metres, map frame)
/// touches, corners included: row by row, the stretch of each segment
/// within the row's band gives the columns it meets.
pub fn line_squares(frame: &MapFrame, line: &LineString<f64>, mark: &mut Grid<bool>) -> Placement {
    let g: Vec<Coord<f64>> = line.coords().map(|&p| grid_coord(frame, p)).collect();
    let (w, h) = (mark.width(), mark.height());
    let mut placed = Placement::default();
    let points: Vec<Coord<f64>> = if g.len() == 1 { vec![g[0], g[0]] } else { g };
    for s in points.windows(2) {
        let (a, b) = (s[0], s[1]);
        let (lo, hi) = bbox([a, b].into_iter());
        let (range, clipped) = cell_range((w, h), lo, hi);
        placed.clipped |= clipped;
        let Some((first, last)) = range else {
            continue;
        };
        for r in first.row..=last.row {
            // The segment's part within the band v in [r, r+1].
            let (v0, v1) = (r as f64, r as f64 + 1.0);
            let (ua, ub) = if a.y == b.y {
                (a.x.min(b.x), a.x.max(b.x))
            } else {
                let t = |v: f64| ((v - a.y) / (b.y - a.y)).clamp(0.0, 1.0);
                let (ta, tb) = (t(v0), t(v1));
                let (ta, tb) = (ta.min(tb), ta.max(tb));
                let (pa, pb) = (a.y + ta * (b.y - a.y), a.y + tb * (b.y - a.y));
                // The segment does not reach this band (both ends clamped
                // to the same side of it).
                if pa.max(pb) < v0 || pa.min(pb) > v1 {
                    continue;
                }
                let (xa, xb) = (a.x + ta * (b.x - a.x), a.x + tb * (b.x - a.x));
                (xa.min(xb), xa.max(xb))
            };
            let c0 = (ua.ceil() - 1.0).max(first.col as f64) as usize;
            let c1 = ub.floor().min(last.col as f64);
            if c1 < c0 as f64 {
                continue;
            }
            for c in c0..=c1 as usize {
                let cell = Cell::new(r, c);
                placed.cells += usize::from(!mark[cell]);
                mark[cell] = true;
            }
        }
    }
    placed
}

/// Marks in `mark` every cell whose centre lies within `radius` metres of
/// `centre` (map frame).
pub fn disc_centres(
    frame: &MapFrame,
    centre: Point,
    radius: f64,
    mark: &mut Grid<bool>,
) -> Placement {
    let c = grid_coord(
        frame,
        Coord {
            x: centre.x,
            y: centre.y,
        },
    );
    let k = radius / frame.resolution();
    let (lo, hi) = (
        Coord {
            x: c.x - k,
            y: c.y - k,
        },
        Coord {
            x: c.x + k,
            y: c.y + k,
        },
    );
    let (range, clipped) = cell_range((mark.width(), mark.height()), lo, hi);
    let mut cells = 0;
    if let Some(range) = range {
        for_range(range, |cell| {
            if (frame.cell_center(cell) - centre).norm() <= radius {
                cells += usize::from(!mark[cell]);
                mark[cell] = true;
            }
        });
    }
    Placement { cells, clipped }
}
