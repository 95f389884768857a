//! Rooms of a map for people and files: the segmentation of
//! [`oxcover_decomp::rooms`] in metres (room areas and centroids, door
//! centres and widths), as JSON, and drawn with one colour per room.

use oxcover_decomp::{RoomParams, Rooms, doorways, morphological, voronoi};
use oxcover_grid::OccupancyGrid;
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

/// The report of `rooms` on `map`.
#[must_use]
pub fn report(map: &OccupancyGrid, rooms: &Rooms, options: &SegmentOptions) -> RoomsReport {
    let f = map.frame();
    let cell = f.resolution() * f.resolution();
    let mut sums = vec![(0.0, 0.0); rooms.count()];
    for c in rooms.labels.cells() {
        let l = rooms.labels[c] as usize;
        if l > 0 {
            let p = f.cell_center(c);
            sums[l - 1].0 += p.x;
            sums[l - 1].1 += p.y;
        }
    }
    let rooms_out = rooms
        .areas
        .iter()
        .zip(&sums)
        .enumerate()
        .map(|(i, (&n, &(sx, sy)))| RoomInfo {
            label: i as u32 + 1,
            area_m2: n as f64 * cell,
            centroid: [sx / n as f64, sy / n as f64],
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

/// Door centres as markers over a picture of the rooms.
#[must_use]
pub fn door_overlay(map: &OccupancyGrid, rooms: &Rooms) -> Overlay {
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
    }
}

/// A picture of `rooms` on `map`: one colour per room, doors marked.
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
