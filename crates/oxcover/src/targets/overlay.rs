//! Targets drawn over a plan's picture: zones and the spot outlined,
//! keep-out areas outlined and hatched, virtual walls as thick strokes,
//! the done path in grey, each chosen room's label at its anchor.

use geo::{LineString, Polygon};
use oxcover_grid::{OccupancyGrid, Point};

use super::Targets;
use crate::error::Result;
use crate::render::{LegendMark, Overlay};
use crate::rooms::{SegmentOptions, room_anchors, segment};

const ZONE: [u8; 3] = [30, 150, 60];
const KEEP_OUT: [u8; 3] = [200, 40, 40];
const DONE: [u8; 3] = [130, 130, 130];

/// Hatch lines this far apart (metres) at least, and at most this many
/// across one area's bounding box.
const HATCH_MIN_M: f64 = 0.1;
const HATCH_LINES: f64 = 24.0;

fn point(c: geo::Coord<f64>) -> Point {
    Point::new(c.x, c.y)
}

fn outline(ring: &LineString<f64>, rgb: [u8; 3], overlay: &mut Overlay) {
    for l in ring.lines() {
        overlay.lines.push((point(l.start), point(l.end), rgb));
    }
}

/// The stretches of the line `y - x = k` inside `polygon` (even-odd over
/// all its rings), as segment pairs.
fn hatch_at(polygon: &Polygon<f64>, k: f64) -> Vec<(Point, Point)> {
    let mut xs: Vec<f64> = Vec::new();
    let rings = std::iter::once(polygon.exterior()).chain(polygon.interiors());
    for ring in rings {
        for l in ring.lines() {
            // Where the edge's points a + t (b - a) meet y - x = k.
            let (fa, fb) = (l.start.y - l.start.x - k, l.end.y - l.end.x - k);
            if (fa < 0.0) != (fb < 0.0) {
                let t = fa / (fa - fb);
                xs.push(l.start.x + t * (l.end.x - l.start.x));
            }
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.chunks_exact(2)
        .map(|p| (Point::new(p[0], p[0] + k), Point::new(p[1], p[1] + k)))
        .collect()
}

fn hatch(polygon: &Polygon<f64>, rgb: [u8; 3], overlay: &mut Overlay) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for c in polygon.exterior().coords() {
        lo = lo.min(c.y - c.x);
        hi = hi.max(c.y - c.x);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return;
    }
    let step = ((hi - lo) / HATCH_LINES).max(HATCH_MIN_M);
    let mut k = lo + step / 2.0;
    while k < hi {
        for (a, b) in hatch_at(polygon, k) {
            overlay.lines.push((a, b, rgb));
        }
        k += step;
    }
}

/// The drawing of `targets` on `map` (empty when there is none); with
/// `--rooms-only`, each chosen room's label where `oxcover segment`'s
/// picture writes it (so `map` is segmented then, as the target is).
///
/// # Errors
/// [`crate::Error::Target`] for a chosen room the map does not have (as
/// the target's cells refuse it); as [`segment`].
pub fn target_overlay(targets: &Targets, map: &OccupancyGrid) -> Result<Overlay> {
    let mut o = Overlay::default();
    if let Some(chosen) = &targets.rooms_only {
        let rooms = segment(map, &SegmentOptions::default())?;
        let n = rooms.labels.as_slice().iter().copied().max().unwrap_or(0);
        super::check_rooms(chosen, n)?;
        o.texts = room_anchors(map, &rooms)
            .into_iter()
            .filter(|(l, _)| chosen.contains(l))
            .map(|(l, p)| (p, l.to_string(), [0, 0, 0]))
            .collect();
    }
    if let Some(done) = &targets.done {
        o.strokes.push((done.clone(), DONE));
        o.legend.push(("done".into(), DONE, LegendMark::Stroke));
    }
    let mut zone = false;
    if let Some(z) = &targets.zones {
        for p in &z.polygons {
            outline(p.exterior(), ZONE, &mut o);
            for h in p.interiors() {
                outline(h, ZONE, &mut o);
            }
        }
        zone = true;
    }
    if let Some(s) = targets.spot {
        for w in s.outline().windows(2) {
            o.lines.push((w[0], w[1], ZONE));
        }
        zone = true;
    }
    if zone {
        o.legend.push(("zone".into(), ZONE, LegendMark::Line));
    }
    if let Some(k) = &targets.keep_out {
        for p in &k.polygons {
            outline(p.exterior(), KEEP_OUT, &mut o);
            hatch(p, KEEP_OUT, &mut o);
        }
        for l in &k.lines {
            o.strokes
                .push((l.coords().map(|&c| point(c)).collect(), KEEP_OUT));
        }
        o.legend
            .push(("keep-out".into(), KEEP_OUT, LegendMark::Line));
    }
    Ok(o)
}

#[cfg(test)]
mod tests {
    use geo::polygon;

    use super::*;

    #[test]
    fn hatching_stays_inside_the_area_and_skips_its_hole() {
        let outer =
            polygon![(x: 0.0, y: 0.0), (x: 4.0, y: 0.0), (x: 4.0, y: 4.0), (x: 0.0, y: 4.0)];
        let hole = polygon![(x: 1.0, y: 1.0), (x: 3.0, y: 1.0), (x: 3.0, y: 3.0), (x: 1.0, y: 3.0)];
        let p = Polygon::new(outer.exterior().clone(), vec![hole.exterior().clone()]);
        // The diagonal y = x crosses the outer square and the hole.
        let s = hatch_at(&p, 0.0);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0], (Point::new(0.0, 0.0), Point::new(1.0, 1.0)));
        assert_eq!(s[1], (Point::new(3.0, 3.0), Point::new(4.0, 4.0)));
    }

    /// The chosen rooms' labels, and theirs only, where `segment`'s
    /// picture writes them; none without `--rooms-only`.
    #[test]
    fn chosen_rooms_are_labelled() {
        // Three rooms side by side, joined by doors.
        let rows: Vec<String> = (0..20)
            .map(|r| {
                (0..62)
                    .map(|c| {
                        let wall = (c == 20 || c == 41) && !(8..12).contains(&r);
                        if wall { '#' } else { '.' }
                    })
                    .collect()
            })
            .collect();
        let (map, _) = oxcover_grid::io::parse_ascii(&rows.join("\n")).expect("valid map");
        let map = OccupancyGrid::new(map.cells().clone(), 0.1, Point::new(0.0, 0.0));
        let rooms = segment(&map, &SegmentOptions::default()).expect("rooms");
        assert!(rooms.count() >= 3, "{} rooms", rooms.count());
        let chosen = vec![3, 1];
        let targets = Targets {
            rooms_only: Some(chosen.clone()),
            ..Targets::default()
        };
        let o = target_overlay(&targets, &map).expect("overlay");
        let want: Vec<(Point, String, [u8; 3])> = room_anchors(&map, &rooms)
            .into_iter()
            .filter(|(l, _)| chosen.contains(l))
            .map(|(l, p)| (p, l.to_string(), [0, 0, 0]))
            .collect();
        assert_eq!(want.len(), 2);
        assert_eq!(o.texts, want);
        let none = target_overlay(&Targets::default(), &map).expect("overlay");
        assert_eq!(none, Overlay::default());
        // A room the map does not have is refused, as by the target's cells.
        let missing = Targets {
            rooms_only: Some(vec![1, 99]),
            ..Targets::default()
        };
        let e = target_overlay(&missing, &map).unwrap_err().to_string();
        assert!(e.contains("no room 99"), "{e}");
    }
}
