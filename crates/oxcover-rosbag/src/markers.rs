//! `visualization_msgs/msg/Marker`s for what a plan shows besides its path:
//! room outlines (the cell edges between a room and anything else) with
//! their labels, and polylines for zones, keep-out areas and virtual walls.
//! All in frame `map`, lasting forever.

use oxcover_grid::{Cell, Grid, MapFrame, Point as MapPoint};

use crate::msgs::{ColorRgba, Header, Marker, MarkerArray, Point, Vector3};

fn rgba(rgb: [u8; 3]) -> ColorRgba {
    let c = |v: u8| f32::from(v) / 255.0;
    ColorRgba {
        r: c(rgb[0]),
        g: c(rgb[1]),
        b: c(rgb[2]),
        a: 1.0,
    }
}

fn base(ns: &str, id: i32, kind: i32, width: f64, rgb: [u8; 3]) -> Marker {
    Marker {
        header: Header {
            frame_id: "map".into(),
            ..Header::default()
        },
        ns: ns.into(),
        id,
        kind,
        scale: Vector3 {
            x: width,
            y: width,
            z: width,
        },
        color: rgba(rgb),
        ..Marker::default()
    }
}

/// A `LINE_STRIP` through `points` (metres, map frame), `width` metres wide.
#[must_use]
pub fn polyline(ns: &str, id: i32, points: &[MapPoint], width: f64, rgb: [u8; 3]) -> Marker {
    let mut m = base(ns, id, Marker::LINE_STRIP, width, rgb);
    m.points = points
        .iter()
        .map(|p| Point {
            x: p.x,
            y: p.y,
            z: 0.0,
        })
        .collect();
    m
}

/// A `TEXT_VIEW_FACING` marker showing `text` at `at`, `height` metres tall.
#[must_use]
pub fn text(ns: &str, id: i32, at: MapPoint, text: &str, height: f64, rgb: [u8; 3]) -> Marker {
    let mut m = base(ns, id, Marker::TEXT_VIEW_FACING, height, rgb);
    m.pose.position = Point {
        x: at.x,
        y: at.y,
        z: 0.0,
    };
    m.text = text.into();
    m
}

/// Markers of rooms: for each label (1..=n, 0 is no room) a `LINE_LIST` of
/// the cell edges where its cells meet another label (namespace
/// `rooms`, id = label) and a text marker with the label at `anchors[label]`
/// (namespace `room_labels`).
#[must_use]
pub fn rooms(labels: &Grid<u32>, frame: &MapFrame, anchors: &[(u32, MapPoint)]) -> MarkerArray {
    let n = labels.as_slice().iter().copied().max().unwrap_or(0) as usize;
    let mut edges: Vec<Vec<Point>> = vec![Vec::new(); n + 1];
    let (w, h) = (labels.width(), labels.height());
    let corner = |row: usize, col: usize| {
        // Corner (row, col) of the cell lattice: row counts down from the top.
        let p = frame.position(row as f64 - 0.5, col as f64 - 0.5);
        Point {
            x: p.x,
            y: p.y,
            z: 0.0,
        }
    };
    for row in 0..h {
        for col in 0..w {
            let l = labels[Cell::new(row, col)];
            if l == 0 {
                continue;
            }
            let other = |r: isize, c: isize| {
                if r < 0 || c < 0 || r as usize >= h || c as usize >= w {
                    true
                } else {
                    labels[Cell::new(r as usize, c as usize)] != l
                }
            };
            let (r, c) = (row as isize, col as isize);
            let e = &mut edges[l as usize];
            if other(r - 1, c) {
                e.extend([corner(row, col), corner(row, col + 1)]);
            }
            if other(r + 1, c) {
                e.extend([corner(row + 1, col), corner(row + 1, col + 1)]);
            }
            if other(r, c - 1) {
                e.extend([corner(row, col), corner(row + 1, col)]);
            }
            if other(r, c + 1) {
                e.extend([corner(row, col + 1), corner(row + 1, col + 1)]);
            }
        }
    }
    let width = frame.resolution();
    let mut markers = Vec::new();
    for (label, points) in edges.into_iter().enumerate().skip(1) {
        if points.is_empty() {
            continue;
        }
        let mut m = base(
            "rooms",
            label as i32,
            Marker::LINE_LIST,
            width,
            [31, 119, 180],
        );
        m.points = points;
        markers.push(m);
    }
    for &(label, at) in anchors {
        markers.push(text(
            "room_labels",
            label as i32,
            at,
            &label.to_string(),
            10.0 * width,
            [0, 0, 0],
        ));
    }
    MarkerArray { markers }
}
