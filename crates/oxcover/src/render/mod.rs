//! Pictures of maps and plans, as SVG and PNG.
//!
//! Both formats show the same scene: the map (free white, occupied dark,
//! unknown grey), covered cells shaded blue, coverable cells the path missed in
//! orange, the path with arrowheads for its direction, a green start disc and a
//! red end square, and a legend panel with the metrics. The map is drawn so its
//! longer side is between [`MIN_SIDE_PX`] and [`MAX_SIDE_PX`] pixels: a
//! 2000×2000-cell map fits on a screen without zooming, an 8×8 one is not a
//! thumbnail. When several cells share a pixel the most telling one wins
//! (occupied, then missed, covered, free, unknown), so thin walls and small
//! gaps stay visible.

mod png;
mod svg;

pub use png::render_png;
pub use svg::render_svg;

use std::path::Path;

use oxcover_grid::{Grid, Occupancy, OccupancyGrid, Point};

use crate::error::{Error, Result};

/// Smallest longer side of the map drawing, in pixels.
pub const MIN_SIDE_PX: f64 = 900.0;
/// Largest longer side of the map drawing, in pixels.
pub const MAX_SIDE_PX: f64 = 1400.0;
/// Smallest width of the legend panel, in pixels (it grows with its text).
pub const LEGEND_PX: u32 = 360;
/// Width of one legend character in pixels (the PNG font is 8×8 doubled).
pub const CHAR_PX: u32 = 16;
/// Margin around the map, in pixels.
pub const MARGIN_PX: u32 = 12;

/// Everything a picture shows.
#[derive(Clone, Debug)]
pub struct Scene<'a> {
    /// The map.
    pub map: &'a OccupancyGrid,
    /// Metre waypoints (may be empty).
    pub path: &'a [Point],
    /// A second path drawn thin under the first (the plan, when `path` is
    /// what a robot executed).
    pub planned: Option<&'a [Point]>,
    /// Covered cells, if known.
    pub covered: Option<&'a Grid<bool>>,
    /// Coverable cells, if known (uncovered ones are drawn as missed).
    pub coverable: Option<&'a Grid<bool>>,
    /// Title line (map and planner).
    pub title: String,
    /// `(key, value)` rows under the title.
    pub rows: Vec<(String, String)>,
    /// Coloured pieces of path, lines and markers drawn over the path,
    /// with their own legend entries (e.g. the sensor-based planner's
    /// states, critical points and graph).
    pub overlay: Option<&'a Overlay>,
    /// Free cells coloured by region label (e.g. rooms; 0 = not coloured).
    pub regions: Option<&'a Grid<u32>>,
}

impl<'a> Scene<'a> {
    /// A picture of the map alone, with a title and rows.
    #[must_use]
    pub fn map_only(map: &'a OccupancyGrid, title: String, rows: Vec<(String, String)>) -> Self {
        Self {
            map,
            path: &[],
            planned: None,
            covered: None,
            coverable: None,
            title,
            rows,
            overlay: None,
            regions: None,
        }
    }
}

/// A marker's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkerShape {
    /// A filled disc.
    Disc,
    /// A circle outline.
    Ring,
    /// A filled square.
    Square,
}

/// What an overlay legend entry shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendMark {
    /// A stroke of path.
    Stroke,
    /// A thin line.
    Line,
    /// A marker.
    Marker(MarkerShape),
}

/// Drawings over the map and path.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    /// Polylines in a colour each, drawn like the path.
    pub strokes: Vec<(Vec<Point>, [u8; 3])>,
    /// Thin straight lines.
    pub lines: Vec<(Point, Point, [u8; 3])>,
    /// Markers: position, colour, shape, radius in pixels.
    pub markers: Vec<(Point, [u8; 3], MarkerShape, f64)>,
    /// Extra legend entries.
    pub legend: Vec<(String, [u8; 3], LegendMark)>,
    /// Text centred on a map point, in a colour each, on a white halo
    /// (room labels).
    pub texts: Vec<(Point, String, [u8; 3])>,
}

/// What a map pixel shows, by priority (highest first when cells share a pixel).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Shade {
    Unknown,
    Free,
    Covered,
    Missed,
    Occupied,
}

impl Shade {
    pub(crate) fn rgb(self) -> [u8; 3] {
        match self {
            Shade::Free => [255, 255, 255],
            Shade::Occupied => [38, 38, 38],
            Shade::Unknown => [160, 160, 160],
            Shade::Covered => [185, 215, 245],
            Shade::Missed => [247, 160, 80],
        }
    }

    pub(crate) fn hex(self) -> String {
        let [r, g, b] = self.rgb();
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

/// Colour of the path line.
pub(crate) const PATH_RGB: [u8; 3] = [31, 78, 156];
/// Colour of the planned path under an executed one.
pub(crate) const PLANNED_RGB: [u8; 3] = [235, 120, 20];
/// Colour of the start marker.
pub(crate) const START_RGB: [u8; 3] = [30, 160, 60];
/// Colour of the end marker.
pub(crate) const END_RGB: [u8; 3] = [210, 40, 40];

/// Legend entries of `scene`: label and what to draw for it (coverage
/// shades only with a coverage mask, path marks only with a path).
pub(crate) fn legend_key(scene: &Scene<'_>) -> Vec<(&'static str, Swatch)> {
    let mut key = vec![
        ("free", Swatch::Cell(Shade::Free)),
        ("occupied", Swatch::Cell(Shade::Occupied)),
        ("unknown", Swatch::Cell(Shade::Unknown)),
    ];
    if scene.covered.is_some() {
        key.push(("covered", Swatch::Cell(Shade::Covered)));
        key.push(("missed (coverable)", Swatch::Cell(Shade::Missed)));
    }
    if !scene.path.is_empty() {
        key.push(("path", Swatch::Line));
        key.push(("start", Swatch::Start));
        key.push(("end", Swatch::End));
    }
    key
}

/// How a legend entry is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Swatch {
    Cell(Shade),
    Line,
    Start,
    End,
}

/// Pixel geometry of a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Layout {
    /// Pixels per cell.
    pub scale: f64,
    /// Map drawing size in pixels.
    pub map_w: u32,
    pub map_h: u32,
    /// Legend panel width.
    pub legend_w: u32,
    /// Whole picture size.
    pub width: u32,
    pub height: u32,
}

impl Layout {
    pub(crate) fn of(scene: &Scene<'_>) -> Self {
        let map = scene.map;
        let legend_rows = scene.rows.len();
        let chars = scene
            .rows
            .iter()
            .map(|(k, v)| k.chars().count() + v.chars().count() + 2)
            .chain([scene.title.chars().count(), 20])
            .max()
            .unwrap_or(20) as u32;
        let legend_w = LEGEND_PX.max(chars * CHAR_PX + 28);
        let side = map.width().max(map.height()) as f64;
        let scale = if side < MIN_SIDE_PX {
            // Whole pixels per cell when there is room (crisp cells), else exact.
            let s = MIN_SIDE_PX / side;
            if s >= 2.0 { s.floor() } else { s }
        } else if side > MAX_SIDE_PX {
            MAX_SIDE_PX / side
        } else {
            1.0
        };
        let map_w = ((map.width() as f64 * scale).round() as u32).max(1);
        let map_h = ((map.height() as f64 * scale).round() as u32).max(1);
        let extra = scene.overlay.map_or(0, |o| o.legend.len()) as u32;
        let legend_h = 60 + 26 * (legend_rows as u32 + 9 + extra);
        Self {
            scale,
            map_w,
            map_h,
            legend_w,
            width: map_w + 2 * MARGIN_PX + legend_w,
            height: (map_h + 2 * MARGIN_PX).max(legend_h),
        }
    }

    /// Picture coordinates of a metre point.
    pub(crate) fn pixel_of(self, map: &OccupancyGrid, p: &Point) -> (f64, f64) {
        // The picture shows the image as stored (row 0 on top), whatever
        // its yaw: place the point by its fractional cell.
        let (row, col) = map.frame().fractional_cell(p);
        (
            f64::from(MARGIN_PX) + (col + 0.5) * self.scale,
            f64::from(MARGIN_PX) + (row + 0.5) * self.scale,
        )
    }
}

/// A light colour for region `label` (neighbouring labels differ in hue).
#[must_use]
pub fn region_rgb(label: u32) -> [u8; 3] {
    // Hues a golden angle apart, pale enough to keep the path readable.
    let hue = (f64::from(label) * 137.507_764) % 360.0;
    let (s, v) = (0.35, 0.95);
    let c = v * s;
    let x = c * (1.0 - ((hue / 60.0) % 2.0 - 1.0).abs());
    let (r, g, b) = match (hue / 60.0) as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    let byte = |t: f64| ((t + m) * 255.0).round() as u8;
    [byte(r), byte(g), byte(b)]
}

/// The map drawing as RGB pixels, `map_w × map_h`.
pub(crate) fn map_raster(scene: &Scene<'_>, layout: &Layout) -> Vec<[u8; 3]> {
    let map = scene.map;
    let shade = Grid::from_fn(map.width(), map.height(), |c| match map.cells()[c] {
        Occupancy::Occupied => Shade::Occupied,
        Occupancy::Unknown => Shade::Unknown,
        Occupancy::Free => {
            let covered = scene.covered.is_some_and(|g| g[c]);
            let coverable = scene.coverable.is_some_and(|g| g[c]);
            if covered {
                Shade::Covered
            } else if coverable && scene.covered.is_some() {
                Shade::Missed
            } else {
                Shade::Free
            }
        }
    });
    let (w, h) = (layout.map_w as usize, layout.map_h as usize);
    let mut out = vec![[255u8; 3]; w * h];
    let s = layout.scale;
    for py in 0..h {
        let r0 = ((py as f64 / s).floor() as usize).min(map.height() - 1);
        let r1 = (((py + 1) as f64 / s).ceil() as usize).clamp(r0 + 1, map.height());
        for px in 0..w {
            let c0 = ((px as f64 / s).floor() as usize).min(map.width() - 1);
            let c1 = (((px + 1) as f64 / s).ceil() as usize).clamp(c0 + 1, map.width());
            let mut best = Shade::Unknown;
            for r in r0..r1 {
                for &sh in &shade.row(r)[c0..c1] {
                    best = best.max(sh);
                }
            }
            let region = scene.regions.map_or(0, |g| {
                g[oxcover_grid::Cell::new((r0 + r1) / 2, (c0 + c1) / 2)]
            });
            out[py * w + px] = if best == Shade::Free && region > 0 {
                region_rgb(region)
            } else {
                best.rgb()
            };
        }
    }
    out
}

/// Places along the path, every `spacing` pixels, with the direction there:
/// `(x, y, dx, dy)` with a unit direction.
pub(crate) fn arrow_marks(px: &[(f64, f64)], spacing: f64) -> Vec<(f64, f64, f64, f64)> {
    let mut marks = Vec::new();
    let mut next = spacing / 2.0;
    let mut walked = 0.0;
    for w in px.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        if len <= 0.0 {
            continue;
        }
        while next <= walked + len {
            let t = (next - walked) / len;
            marks.push((a.0 + dx * t, a.1 + dy * t, dx / len, dy / len));
            next += spacing;
            if marks.len() > 5000 {
                return marks;
            }
        }
        walked += len;
    }
    marks
}

/// Writes the scene to `out`, as SVG or PNG by its extension.
///
/// # Errors
/// [`Error::BadParameter`] for another extension, [`Error::Write`] when the file
/// cannot be written.
pub fn render_to_file(scene: &Scene<'_>, out: &Path) -> Result<()> {
    crate::output::write_file(out, render_bytes(scene, out)?)
}

/// The picture of `scene` in the format `out`'s extension names.
///
/// # Errors
/// [`Error::BadParameter`] naming `--out` for an extension other than
/// `.svg` or `.png`; a rendering fault.
pub fn render_bytes(scene: &Scene<'_>, out: &Path) -> Result<Vec<u8>> {
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match ext.as_str() {
        "svg" => Ok(render_svg(scene)?.into_bytes()),
        "png" => render_png(scene),
        _ => Err(Error::BadParameter {
            name: "--out",
            value: out.display().to_string(),
            expected: "a file name ending in .svg or .png".into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    #[test]
    fn layout_fits_small_and_large_maps() {
        let scene = |map| Scene {
            map,
            path: &[],
            planned: None,
            covered: None,
            coverable: None,
            title: "a title".into(),
            overlay: None,
            regions: None,
            rows: vec![],
        };
        let (small, _) = parse_ascii("....\n....").unwrap();
        let l = Layout::of(&scene(&small));
        assert_eq!(l.scale, 225.0);
        assert_eq!((l.map_w, l.map_h), (900, 450));
        let mid = OccupancyGrid::unit(Grid::new(600, 300, Occupancy::Free));
        assert_eq!(Layout::of(&scene(&mid)).map_w, 900);
        let big = OccupancyGrid::unit(Grid::new(2000, 1000, Occupancy::Free));
        let l = Layout::of(&scene(&big));
        assert_eq!((l.map_w, l.map_h), (1400, 700));
        assert_eq!(l.legend_w, LEGEND_PX);
    }

    #[test]
    fn downscaling_keeps_thin_walls() {
        let mut g = Grid::new(3000, 10, Occupancy::Free);
        g[oxcover_grid::Cell::new(5, 1500)] = Occupancy::Occupied;
        let map = OccupancyGrid::unit(g);
        let scene = Scene {
            map: &map,
            path: &[],
            planned: None,
            covered: None,
            coverable: None,
            title: String::new(),
            overlay: None,
            regions: None,
            rows: vec![],
        };
        let l = Layout::of(&scene);
        let r = map_raster(&scene, &l);
        assert!(r.contains(&Shade::Occupied.rgb()));
    }

    #[test]
    fn arrows_are_spaced_along_the_path() {
        let m = arrow_marks(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0)], 50.0);
        assert_eq!(m.len(), 4);
        assert_eq!(m[0], (25.0, 0.0, 1.0, 0.0));
        assert_eq!(m[2], (100.0, 25.0, 0.0, 1.0));
    }
}
