//! Rooms of a map for people and files: the segmentation of
//! [`oxcover_decomp::rooms`] in metres (room areas and centroids, door
//! centres and widths), as JSON, and drawn with one colour per room.

use oxcover_decomp::{RoomParams, Rooms, doorways, morphological, voronoi};
use oxcover_grid::{Cell, OccupancyGrid, Point};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::render::{LegendMark, MarkerShape, Overlay, Scene};

/// One room, in metres.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoomInfo {
    /// Label (1-based, as in the label grid).
    pub label: u32,
    /// Area (m²).
    pub area_m2: f64,
    /// Mean position of its cells (m, map frame).
    pub centroid: [f64; 2],
    /// Where its label is drawn: the centre of its cell nearest the
    /// centroid, inside the room where the centroid of an L-shaped one is
    /// not (m, map frame).
    pub label_at: [f64; 2],
    /// Whether it grew from an eroded seed (else a free region no seed reached).
    pub seeded: bool,
}

/// One door, in metres.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DoorInfo {
    /// The two rooms.
    pub rooms: [u32; 2],
    /// Its centre cell's centre (m, map frame).
    pub centre: [f64; 2],
    /// Cells on either side of the boundary between the rooms.
    pub cells: usize,
}

/// The `oxcover segment --out F.json` object.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoomsReport {
    /// Method (`doorways`, `voronoi` or `morphological`).
    pub method: String,
    /// Smallest room asked for (m²).
    pub min_area_m2: f64,
    /// Largest room seed asked for (m², morphological).
    pub max_area_m2: f64,
    /// Widest door asked for (m, doorways and voronoi).
    pub door_width_m: f64,
    /// Rooms grown from seeds (morphological), or rooms of at least the
    /// smallest area (doorways, voronoi); they come first.
    pub seeded: usize,
    /// Every room, seeded ones first.
    pub rooms: Vec<RoomInfo>,
    /// Every pair of touching rooms.
    pub doors: Vec<DoorInfo>,
}

/// A segmentation method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Split where a wall has a gap: doors between wall ends, walls
    /// continued across a room's open side
    /// ([`oxcover_decomp::doorways`](mod@oxcover_decomp::doorways)); the
    /// rooms people name (IoU 0.98 on the ipa benchmark's plans).
    #[default]
    Doorways,
    /// Erode until the free space splits into room-sized pieces, grow them
    /// back ([`oxcover_decomp::rooms`]).
    Morphological,
    /// Split at the narrow points of the distance transform's medial axis
    /// ([`oxcover_decomp::voronoi_rooms`]).
    Voronoi,
}

impl Method {
    /// Its command-line name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Method::Doorways => "doorways",
            Method::Morphological => "morphological",
            Method::Voronoi => "voronoi",
        }
    }
}

/// How to segment: the method and its limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentOptions {
    /// The method.
    pub method: Method,
    /// Smallest room (m²): the smallest eroded seed (morphological) or the
    /// smallest region kept apart (doorways, voronoi).
    pub min_area_m2: f64,
    /// Largest eroded seed (m², morphological only).
    pub max_area_m2: f64,
    /// Widest opening taken for a door (m, doorways and voronoi).
    pub door_width_m: f64,
}

impl Default for SegmentOptions {
    fn default() -> Self {
        let d = RoomParams::indoor(1.0);
        Self {
            method: Method::Doorways,
            min_area_m2: d.min_area_m2,
            max_area_m2: d.max_area_m2,
            door_width_m: d.door_width_m,
        }
    }
}

/// Segments the free cells of `map` into rooms.
///
/// # Errors
/// [`Error::BadParameter`] naming `--min-area`, `--max-area` or
/// `--door-width` when they are not finite and positive, or the minimum
/// exceeds the maximum.
pub fn segment(map: &OccupancyGrid, options: &SegmentOptions) -> Result<Rooms> {
    let min = oxcover_grid::error::positive("--min-area", options.min_area_m2)?;
    let max = oxcover_grid::error::positive("--max-area", options.max_area_m2)?;
    let door = oxcover_grid::error::positive("--door-width", options.door_width_m)?;
    if min > max {
        return Err(Error::BadParameter {
            name: "--min-area",
            value: min.to_string(),
            expected: format!("at most --max-area ({max})"),
        });
    }
    let params = RoomParams {
        resolution: map.resolution(),
        min_area_m2: min,
        max_area_m2: max,
        door_width_m: door,
    };
    let free = map.free_mask();
    Ok(match options.method {
        Method::Doorways => doorways(&free, &params),
        Method::Morphological => morphological(&free, &params),
        Method::Voronoi => voronoi(&free, &params),
    })
}

/// Each room's centroid (metres, map frame): the mean of its cells'
/// centres, `centroids[label - 1]`.
fn centroids(map: &OccupancyGrid, rooms: &Rooms) -> Vec<Point> {
    let f = map.frame();
    let mut sums = vec![(0.0, 0.0); rooms.count()];
    for c in rooms.labels.cells() {
        let l = rooms.labels[c] as usize;
        if l > 0 {
            let p = f.cell_center(c);
            sums[l - 1].0 += p.x;
            sums[l - 1].1 += p.y;
        }
    }
    sums.iter()
        .zip(&rooms.areas)
        .map(|(&(sx, sy), &n)| Point::new(sx / n as f64, sy / n as f64))
        .collect()
}

/// Where each room's label is shown: the centre of its cell nearest its
/// centroid (the centroid [`report`] gives, which may lie outside an
/// L-shaped room), as `(label, point)` in label order.
#[must_use]
pub fn room_anchors(map: &OccupancyGrid, rooms: &Rooms) -> Vec<(u32, Point)> {
    anchors(map, rooms, &centroids(map, rooms))
}

/// [`room_anchors`] given the rooms' `centroids` ([`centroids`]).
fn anchors(map: &OccupancyGrid, rooms: &Rooms, centroids: &[Point]) -> Vec<(u32, Point)> {
    let frame = map.frame();
    let labels = &rooms.labels;
    let mut best: Vec<Option<(f64, Cell)>> = vec![None; centroids.len() + 1];
    for c in labels.cells() {
        let l = labels[c] as usize;
        if let Some(centroid) = l.checked_sub(1).and_then(|i| centroids.get(i)) {
            let d = (frame.cell_center(c) - centroid).norm();
            if best[l].is_none_or(|(b, _)| d < b) {
                best[l] = Some((d, c));
            }
        }
    }
    best.iter()
        .enumerate()
        .filter_map(|(l, b)| b.map(|(_, c)| (l as u32, frame.cell_center(c))))
        .collect()
}

/// The report of `rooms` on `map`.
#[must_use]
pub fn report(map: &OccupancyGrid, rooms: &Rooms, options: &SegmentOptions) -> RoomsReport {
    let f = map.frame();
    let cell = f.resolution() * f.resolution();
    let centres = centroids(map, rooms);
    let mut label_at = centres.clone();
    for (l, p) in anchors(map, rooms, &centres) {
        label_at[l as usize - 1] = p;
    }
    let rooms_out = rooms
        .areas
        .iter()
        .zip(centres.iter().zip(&label_at))
        .enumerate()
        .map(|(i, (&n, (centre, at)))| RoomInfo {
            label: i as u32 + 1,
            area_m2: n as f64 * cell,
            centroid: [centre.x, centre.y],
            label_at: [at.x, at.y],
            seeded: i < rooms.seeded,
        })
        .collect();
    let doors = rooms
        .doors
        .iter()
        .map(|d| {
            let p = f.cell_center(d.centre);
            DoorInfo {
                rooms: [d.rooms.0, d.rooms.1],
                centre: [p.x, p.y],
                cells: d.cells.len(),
            }
        })
        .collect();
    RoomsReport {
        method: options.method.name().into(),
        min_area_m2: options.min_area_m2,
        max_area_m2: options.max_area_m2,
        door_width_m: options.door_width_m,
        seeded: rooms.seeded,
        rooms: rooms_out,
        doors,
    }
}

/// What a picture of the rooms shows over them: door centres as markers,
/// and each room's label at its anchor ([`room_anchors`]), the label that
/// `--rooms-only` takes.
#[must_use]
pub fn rooms_overlay(map: &OccupancyGrid, rooms: &Rooms) -> Overlay {
    let f = map.frame();
    let red = [200, 30, 30];
    Overlay {
        strokes: Vec::new(),
        lines: Vec::new(),
        markers: rooms
            .doors
            .iter()
            .map(|d| (f.cell_center(d.centre), red, MarkerShape::Disc, 4.0))
            .collect(),
        legend: vec![("door".into(), red, LegendMark::Marker(MarkerShape::Disc))],
        texts: room_anchors(map, rooms)
            .into_iter()
            .map(|(l, p)| (p, l.to_string(), [0, 0, 0]))
            .collect(),
    }
}

/// A picture of `rooms` on `map`: one colour per room, doors and labels
/// as `overlay` ([`rooms_overlay`]) shows them.
#[must_use]
pub fn scene<'a>(
    map: &'a OccupancyGrid,
    rooms: &'a Rooms,
    overlay: &'a Overlay,
    title: String,
) -> Scene<'a> {
    let mut s = Scene::map_only(
        map,
        title,
        vec![
            ("rooms".into(), rooms.seeded.to_string()),
            (
                "other regions".into(),
                (rooms.count() - rooms.seeded).to_string(),
            ),
            ("doors".into(), rooms.doors.len().to_string()),
        ],
    );
    s.regions = Some(&rooms.labels);
    s.overlay = Some(overlay);
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::render_bytes;

    /// Two rooms joined by a door, the second an L whose centroid lies in
    /// the corner it lacks, at 0.1 m a cell.
    fn two_rooms() -> OccupancyGrid {
        let mut rows: Vec<String> = Vec::new();
        for r in 0..40 {
            rows.push(
                (0..60)
                    .map(|c| {
                        let border = r == 0 || r == 39 || c == 0 || c == 59;
                        // The wall between the rooms, with a door 1 m wide.
                        let wall = c == 25 && !(18..28).contains(&r);
                        // The L's missing corner.
                        let corner = c > 25 && r < 22 && c > 40;
                        if border || wall || corner { '#' } else { '.' }
                    })
                    .collect(),
            );
        }
        let (map, _) = oxcover_grid::io::parse_ascii(&rows.join("\n")).expect("valid map");
        OccupancyGrid::new(map.cells().clone(), 0.1, Point::new(0.0, 0.0))
    }

    #[test]
    fn each_label_is_shown_in_its_own_room_nearest_its_centroid() {
        let map = two_rooms();
        let rooms = segment(&map, &SegmentOptions::default()).expect("rooms");
        assert!(rooms.count() >= 2, "{} rooms", rooms.count());
        let rep = report(&map, &rooms, &SegmentOptions::default());
        let anchors = room_anchors(&map, &rooms);
        assert_eq!(
            anchors.iter().map(|a| a.0).collect::<Vec<_>>(),
            (1..=rooms.count() as u32).collect::<Vec<_>>()
        );
        let f = map.frame();
        for (&(label, at), info) in anchors.iter().zip(&rep.rooms) {
            assert_eq!(info.label_at, [at.x, at.y]);
            let cell = f.cell_at(&at).expect("on the map");
            assert_eq!(rooms.labels[cell], label);
            let centroid = Point::new(info.centroid[0], info.centroid[1]);
            let d = (at - centroid).norm();
            for c in rooms.labels.cells().filter(|&c| rooms.labels[c] == label) {
                assert!((f.cell_center(c) - centroid).norm() >= d - 1e-12);
            }
        }
        // The overlay writes each label at its anchor, as text.
        let o = rooms_overlay(&map, &rooms);
        let texts: Vec<(Point, String)> = o.texts.iter().map(|t| (t.0, t.1.clone())).collect();
        let want: Vec<(Point, String)> = anchors.iter().map(|&(l, p)| (p, l.to_string())).collect();
        assert_eq!(texts, want);
    }

    #[test]
    fn pictures_of_the_rooms_carry_their_labels() {
        let map = two_rooms();
        let rooms = segment(&map, &SegmentOptions::default()).expect("rooms");
        let overlay = rooms_overlay(&map, &rooms);
        let picture = scene(&map, &rooms, &overlay, "rooms".into());
        let svg =
            String::from_utf8(render_bytes(&picture, std::path::Path::new("r.svg")).expect("svg"))
                .expect("utf-8");
        for l in 1..=rooms.count() {
            assert!(
                svg.contains(&format!("paint-order=\"stroke\">{l}</text>")),
                "label {l}"
            );
        }
        // In the PNG, black glyph pixels where the first label stands (the
        // room around it is coloured, the walls are far off), none there
        // without the labels.
        let at = |o: &Overlay| {
            let s = scene(&map, &rooms, o, "rooms".into());
            let png = render_bytes(&s, std::path::Path::new("r.png")).expect("png");
            let img = tiny_skia::Pixmap::decode_png(&png).expect("decodes");
            let layout = crate::render::Layout::of(&s);
            let (x, y) = layout.pixel_of(&map, &overlay.texts[0].0);
            let (x, y) = (x.round() as i64, y.round() as i64);
            let mut black = 0;
            for py in y - 8..y + 8 {
                for px in x - 8..x + 8 {
                    let p = img.pixel(px as u32, py as u32).expect("inside");
                    black += usize::from(p.red() == 0 && p.green() == 0 && p.blue() == 0);
                }
            }
            black
        };
        assert!(at(&overlay) > 20);
        let bare = Overlay {
            texts: Vec::new(),
            ..overlay.clone()
        };
        assert_eq!(at(&bare), 0);
    }
}
