//! Areas from GeoJSON: polygons (zones, keep-out areas) and lines (virtual
//! walls) in map-frame metres, read with the `geojson` crate and checked
//! with `geo` (ring sizes and closure on the file's own positions, since
//! `geo` closes rings itself; self-intersections by `geo`'s validation,
//! located by a search over the ring's segment pairs).

use std::path::Path;

use geo::algorithm::Validation;
use geo::algorithm::validation::InvalidPolygon;
use geo::line_intersection::{LineIntersection, line_intersection};
use geo::{Coord, Line, LineString, Polygon};
use geojson::{GeoJson, Geometry, GeometryValue, Position};

use crate::error::{Error, Result};

/// What a GeoJSON file holds, in the order of its features.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Areas {
    /// Polygons (holes as interior rings), MultiPolygons split into their
    /// polygons.
    pub polygons: Vec<Polygon<f64>>,
    /// LineStrings, MultiLineStrings split into their lines.
    pub lines: Vec<LineString<f64>>,
}

/// The geometries an option takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinds {
    /// Polygons and MultiPolygons only (`--zones`).
    Polygons,
    /// Polygons, MultiPolygons, LineStrings and MultiLineStrings
    /// (`--keep-out`: areas and virtual walls).
    PolygonsAndLines,
}

impl Kinds {
    fn expected(self) -> &'static str {
        match self {
            Kinds::Polygons => "Polygon or MultiPolygon",
            Kinds::PolygonsAndLines => "Polygon, MultiPolygon, LineString or MultiLineString",
        }
    }
}

/// Reads the GeoJSON file `path` given to `option` (capped as every text
/// input is).
///
/// # Errors
/// [`Error::Read`] when the file cannot be read; [`Error::Target`] naming
/// the option, the file, the feature and what is wrong otherwise.
pub fn read_areas(path: &Path, option: &'static str, kinds: Kinds) -> Result<Areas> {
    let text = oxcover_grid::io::limited::read_limited_string(
        path,
        oxcover_grid::io::limited::MAX_TEXT_BYTES,
    )
    .map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    parse_areas(&text, kinds).map_err(|message| Error::Target {
        what: format!("{option} {}", path.display()),
        message,
    })
}

/// Parses GeoJSON text: a FeatureCollection, a Feature or a bare geometry
/// (GeometryCollections are read through).
///
/// # Errors
/// What is wrong, naming the feature (its index in the collection) and,
/// for a ring, which one and where.
pub fn parse_areas(text: &str, kinds: Kinds) -> std::result::Result<Areas, String> {
    if !text.trim_start().starts_with('{') {
        return Err("not GeoJSON (expected a JSON object)".into());
    }
    let json: GeoJson = text
        .parse()
        .map_err(|e| format!("not valid GeoJSON: {e}"))?;
    let mut areas = Areas::default();
    match json {
        GeoJson::Geometry(g) => add_geometry(&mut areas, &g, "the geometry", kinds)?,
        GeoJson::Feature(f) => {
            let g = f.geometry.ok_or("the feature has no geometry")?;
            add_geometry(&mut areas, &g, "the feature", kinds)?;
        }
        GeoJson::FeatureCollection(fc) => {
            for (i, f) in fc.features.iter().enumerate() {
                let what = format!("feature {i}");
                let g = f
                    .geometry
                    .as_ref()
                    .ok_or_else(|| format!("{what} has no geometry"))?;
                add_geometry(&mut areas, g, &what, kinds)?;
            }
        }
    }
    let positions: usize = areas
        .polygons
        .iter()
        .map(|p| p.exterior().0.len() + p.interiors().iter().map(|r| r.0.len()).sum::<usize>())
        .chain(areas.lines.iter().map(|l| l.0.len()))
        .sum();
    if positions > MAX_FILE_POSITIONS {
        return Err(format!(
            "holds {positions} positions, at most {MAX_FILE_POSITIONS} are read (simplify it)"
        ));
    }
    if areas.polygons.is_empty() && areas.lines.is_empty() {
        return Err(format!("holds no geometry (expected {})", kinds.expected()));
    }
    Ok(areas)
}

fn add_geometry(
    areas: &mut Areas,
    g: &Geometry,
    what: &str,
    kinds: Kinds,
) -> std::result::Result<(), String> {
    let lines_ok = kinds == Kinds::PolygonsAndLines;
    match &g.value {
        GeometryValue::Polygon { coordinates } => {
            areas.polygons.push(polygon(coordinates, what)?);
        }
        GeometryValue::MultiPolygon { coordinates } => {
            for (k, p) in coordinates.iter().enumerate() {
                areas
                    .polygons
                    .push(polygon(p, &format!("{what}, polygon {k}"))?);
            }
        }
        GeometryValue::LineString { coordinates } if lines_ok => {
            areas.lines.push(line(coordinates, what)?);
        }
        GeometryValue::MultiLineString { coordinates } if lines_ok => {
            for (k, l) in coordinates.iter().enumerate() {
                areas.lines.push(line(l, &format!("{what}, line {k}"))?);
            }
        }
        GeometryValue::GeometryCollection { geometries } => {
            for (k, g) in geometries.iter().enumerate() {
                add_geometry(areas, g, &format!("{what}, geometry {k}"), kinds)?;
            }
        }
        other => {
            return Err(format!(
                "{what} is a {}, expected {}",
                other.type_name(),
                kinds.expected()
            ));
        }
    }
    Ok(())
}

/// A position's x and y (an altitude, if any, is ignored).
fn coord(p: &Position, what: &str) -> std::result::Result<Coord<f64>, String> {
    let s = p.as_slice();
    if s.len() < 2 {
        return Err(format!(
            "{what} has a position with {} number(s), expected x, y",
            s.len()
        ));
    }
    if !(s[0].is_finite() && s[1].is_finite()) {
        return Err(format!(
            "{what} has a non-finite position ({}, {})",
            s[0], s[1]
        ));
    }
    Ok(Coord { x: s[0], y: s[1] })
}

fn ring(positions: &[Position], what: &str) -> std::result::Result<LineString<f64>, String> {
    if positions.len() < 4 {
        return Err(format!(
            "{what} has {} position(s), a ring needs at least 4 (first and last the same)",
            positions.len()
        ));
    }
    let coords = positions
        .iter()
        .map(|p| coord(p, what))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    if coords.first() != coords.last() {
        return Err(format!(
            "{what} is not closed (its last position must repeat its first)"
        ));
    }
    Ok(LineString::new(coords))
}

/// Most positions of one polygon (its rings together): its validity check
/// grows with their square (about a second at this size).
pub const MAX_POLYGON_POSITIONS: usize = 10_000;

/// Most positions of one file.
pub const MAX_FILE_POSITIONS: usize = 100_000;

fn polygon(rings: &[Vec<Position>], what: &str) -> std::result::Result<Polygon<f64>, String> {
    let Some((outer, holes)) = rings.split_first() else {
        return Err(format!("{what} has no ring"));
    };
    let n: usize = rings.iter().map(Vec::len).sum();
    if n > MAX_POLYGON_POSITIONS {
        return Err(format!(
            "{what} has {n} positions, at most {MAX_POLYGON_POSITIONS} per polygon are read (simplify it)"
        ));
    }
    let exterior = ring(outer, &format!("{what}, exterior ring"))?;
    let interiors = holes
        .iter()
        .enumerate()
        .map(|(k, h)| ring(h, &format!("{what}, hole {k}")))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    let poly = Polygon::new(exterior, interiors);
    if let Err(e) = poly.check_validation() {
        let place = match &e {
            InvalidPolygon::SelfIntersection(_) => {
                let rings = std::iter::once(poly.exterior()).chain(poly.interiors());
                rings
                    .filter_map(self_crossing)
                    .next()
                    .map(|c| format!(" at ({:.3}, {:.3})", c.x, c.y))
                    .unwrap_or_default()
            }
            _ => String::new(),
        };
        return Err(format!("{what} is not a valid polygon: {e}{place}"));
    }
    Ok(poly)
}

/// Most segments of a ring whose self-intersection is located.
const LOCATE_MAX_SEGMENTS: usize = 4096;

/// Where a ring crosses or touches itself: the first point two of its
/// segments that are not neighbours share (or two neighbours overlapping
/// along a line).
fn self_crossing(ring: &LineString<f64>) -> Option<Coord<f64>> {
    let segs: Vec<Line<f64>> = ring.lines().collect();
    let n = segs.len();
    // Pairs of segments are searched: a larger ring is named without the
    // place (bounded work on bad input).
    if n > LOCATE_MAX_SEGMENTS {
        return None;
    }
    for i in 0..n {
        for j in i + 1..n {
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            match line_intersection(segs[i], segs[j]) {
                Some(LineIntersection::SinglePoint { intersection, .. }) if !neighbours => {
                    return Some(intersection);
                }
                Some(LineIntersection::Collinear { intersection }) => {
                    return Some(intersection.start);
                }
                _ => {}
            }
        }
    }
    None
}

fn line(positions: &[Position], what: &str) -> std::result::Result<LineString<f64>, String> {
    if positions.len() < 2 {
        return Err(format!(
            "{what} has {} position(s), a line needs at least 2",
            positions.len()
        ));
    }
    let coords = positions
        .iter()
        .map(|p| coord(p, what))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(LineString::new(coords))
}
