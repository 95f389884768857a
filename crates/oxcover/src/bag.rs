//! Plans as ROS 2 bags (`--bag OUT.mcap`): the map, the path stamped by the
//! time model of `est_time_s`, the rooms of `oxcover segment` and the
//! coverage targets as markers, and an executed trajectory as odometry,
//! written by [`oxcover_rosbag::write_mcap`].

use std::path::Path;

use oxcover_grid::{OccupancyGrid, Point};
use oxcover_planners::TimeModel;
use oxcover_rosbag::msgs::MarkerArray;
use oxcover_rosbag::{OdomSample, PlanBag, StampedPose, markers};

use crate::error::{Error, Result};
use crate::metrics::arrival_times;
use crate::render::{LegendMark, Overlay};
use crate::rooms::{SegmentOptions, room_anchors, segment};
use crate::targets::Targets;
use oxcover_decomp::Rooms;

/// The poses of `points`, each oriented along the path (towards the next
/// waypoint that is elsewhere; the last along the way it came) and stamped
/// with [`arrival_times`].
#[must_use]
pub fn path_poses(points: &[Point], resolution: f64, time: &TimeModel) -> Vec<StampedPose> {
    let times = arrival_times(points, resolution, time);
    let mut yaw = 0.0;
    let mut out = Vec::with_capacity(points.len());
    // Headings looked up from the end, so each pose knows its next move.
    let mut next_yaw = vec![None; points.len()];
    let mut ahead: Option<f64> = None;
    for i in (0..points.len()).rev() {
        next_yaw[i] = ahead;
        if i > 0 {
            let d = points[i] - points[i - 1];
            if d.norm() > 0.0 {
                ahead = Some(d.y.atan2(d.x));
            }
        }
    }
    for (i, p) in points.iter().enumerate() {
        if let Some(y) = next_yaw[i] {
            yaw = y;
        }
        out.push(StampedPose {
            x: p.x,
            y: p.y,
            yaw,
            t: times[i],
        });
    }
    out
}

/// The rooms `oxcover segment` gives `map` by default, as outlines and
/// labels (each label at the room's cell nearest its centroid).
///
/// # Errors
/// As [`segment`] (not expected with the defaults).
pub fn room_markers(map: &OccupancyGrid) -> Result<MarkerArray> {
    let options = SegmentOptions::default();
    let rooms = segment(map, &options)?;
    Ok(label_markers(map, &rooms))
}

/// Room outlines and labels of `rooms`, each label at its room's anchor
/// ([`room_anchors`]: the cell nearest the centroid `oxcover segment`
/// reports).
#[must_use]
pub fn label_markers(map: &OccupancyGrid, rooms: &Rooms) -> MarkerArray {
    markers::rooms(&rooms.labels, map.frame(), &room_anchors(map, rooms))
}

/// Zones (green outlines, namespace `zones`), keep-out areas (red,
/// `keep_out`) and virtual walls (red and thicker, `virtual_walls`);
/// `None` where `targets` has none of them.
#[must_use]
pub fn target_markers(targets: &Targets, resolution: f64) -> Option<MarkerArray> {
    const ZONE: [u8; 3] = [44, 160, 44];
    const KEEP_OUT: [u8; 3] = [214, 39, 40];
    let ring = |r: &geo::LineString<f64>| -> Vec<Point> {
        r.coords().map(|c| Point::new(c.x, c.y)).collect()
    };
    // Every ring of the areas' polygons, holes included.
    let rings = |areas: Option<&crate::targets::Areas>| -> Vec<Vec<Point>> {
        areas.map_or_else(Vec::new, |a| {
            a.polygons
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .map(ring)
                .collect()
        })
    };
    let zones = rings(targets.zones.as_ref())
        .into_iter()
        .chain(targets.spot.map(|s| s.outline()));
    let walls = targets
        .keep_out
        .iter()
        .flat_map(|k| k.lines.iter().map(ring));
    let lines = zones
        .map(|z| ("zones", z, 1.0, ZONE))
        .chain(
            rings(targets.keep_out.as_ref())
                .into_iter()
                .map(|k| ("keep_out", k, 1.0, KEEP_OUT)),
        )
        .chain(walls.map(|w| ("virtual_walls", w, 2.0, KEEP_OUT)));
    let out: Vec<_> = lines
        .enumerate()
        .map(|(id, (ns, points, width, rgb))| {
            markers::polyline(ns, id as i32, &points, width * resolution, rgb)
        })
        .collect();
    (!out.is_empty()).then_some(MarkerArray { markers: out })
}

/// What a bag of a plan holds besides the map and the path.
#[derive(Clone, Debug, Default)]
pub struct BagExtras {
    /// Rooms to draw.
    pub rooms: Option<MarkerArray>,
    /// Targets to draw.
    pub targets: Option<MarkerArray>,
    /// An executed trajectory.
    pub odom: Vec<OdomSample>,
}

/// The MCAP bytes of a bag holding `map`, the path `points` stamped by
/// `time`, and `extras`, to be written as `out`.
///
/// # Errors
/// [`Error::Internal`] where the encoder refuses a message (not expected).
pub fn bag_bytes(
    map: &OccupancyGrid,
    points: &[Point],
    time: &TimeModel,
    extras: BagExtras,
    out: &Path,
) -> Result<Vec<u8>> {
    let name = out
        .file_name()
        .map_or_else(|| "plan.mcap".into(), |n| n.to_string_lossy().into_owned());
    let bag = PlanBag {
        map,
        path: path_poses(points, map.resolution(), time),
        rooms: extras.rooms,
        targets: extras.targets,
        odom: extras.odom,
    };
    oxcover_rosbag::write_mcap(&bag, &name).map_err(Error::Internal)
}

/// What a bag of a plan holds, decoded for a picture: the path of
/// `/coverage_path`, the executed trajectory of `/odom`, and the lines of
/// the markers of `/rooms` and `/coverage_targets` in their colours, and
/// their text (the rooms' labels).
#[derive(Clone, Debug, Default)]
pub struct DecodedBag {
    /// `/coverage_path`'s positions.
    pub path: Option<Vec<Point>>,
    /// `/odom`'s positions, in order.
    pub odom: Option<Vec<Point>>,
    /// Markers' lines (line strips as strokes, line lists as lines) and
    /// text.
    pub overlay: Overlay,
}

/// Decodes the plan topics of the bag at `path` (those it has).
///
/// # Errors
/// A bag that cannot be read; a message that does not decode as its type.
pub fn decode_bag(path: &Path) -> Result<DecodedBag> {
    use oxcover_rosbag::msgs::{self, Marker};
    use oxcover_rosbag::{Bag, MessageChoice, cdr};
    let mut bag = Bag::open(path)?;
    let topics = bag.topics()?;
    let mut out = DecodedBag::default();
    let bad = |topic: &str, e: String| {
        Error::Map(oxcover_grid::Error::Format {
            path: path.to_path_buf(),
            message: format!("{topic}: {e}"),
        })
    };
    let point = |p: &msgs::Point| Point::new(p.x, p.y);
    for t in &topics {
        match (t.name.as_str(), t.type_name.as_str()) {
            ("/coverage_path", oxcover_rosbag::msgs::types::PATH) => {
                let data = bag.message(&t.name, MessageChoice::Last)?;
                let m: msgs::Path = cdr::decode(&data).map_err(|e| bad(&t.name, e))?;
                out.path = Some(m.poses.iter().map(|p| point(&p.pose.position)).collect());
            }
            ("/odom", oxcover_rosbag::msgs::types::ODOMETRY) => {
                let mut odom = Vec::new();
                for data in bag.messages(&t.name)? {
                    let m: msgs::Odometry = cdr::decode(&data).map_err(|e| bad(&t.name, e))?;
                    odom.push(point(&m.pose.pose.position));
                }
                out.odom = Some(odom);
            }
            ("/rooms" | "/coverage_targets", oxcover_rosbag::msgs::types::MARKER_ARRAY) => {
                let data = bag.message(&t.name, MessageChoice::Last)?;
                let m: msgs::MarkerArray = cdr::decode(&data).map_err(|e| bad(&t.name, e))?;
                for marker in &m.markers {
                    let c = marker.color;
                    let rgb = [c.r, c.g, c.b].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
                    let pts: Vec<Point> = marker.points.iter().map(point).collect();
                    match marker.kind {
                        Marker::TEXT_VIEW_FACING if !marker.text.is_empty() => {
                            let at = point(&marker.pose.position);
                            out.overlay.texts.push((at, marker.text.clone(), rgb));
                        }
                        Marker::LINE_STRIP => out.overlay.strokes.push((pts, rgb)),
                        Marker::LINE_LIST => {
                            out.overlay
                                .lines
                                .extend(pts.chunks_exact(2).map(|w| (w[0], w[1], rgb)));
                        }
                        _ => {}
                    }
                }
                let legend = if t.name == "/rooms" {
                    "rooms"
                } else {
                    "targets"
                };
                if let Some(first) = m.markers.iter().find(|m| !m.points.is_empty()) {
                    let c = first.color;
                    let rgb = [c.r, c.g, c.b].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
                    out.overlay.legend.push((
                        format!("{} ({legend})", t.name),
                        rgb,
                        LegendMark::Line,
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::PathShape;

    /// The rooms' labels written as text markers come back from the bag
    /// as text at the same places (what `oxcover render BAG` draws).
    #[test]
    fn room_labels_come_back_from_the_bag() {
        let mut rows = vec![".".repeat(50); 30];
        for (r, row) in rows.iter_mut().enumerate() {
            if !(12..18).contains(&r) {
                row.replace_range(20..21, "#");
            }
        }
        let (map, _) = oxcover_grid::io::parse_ascii(&rows.join("\n")).expect("valid map");
        let map = OccupancyGrid::new(map.cells().clone(), 0.1, Point::new(-1.0, 2.0));
        let rooms = segment(&map, &SegmentOptions::default()).expect("rooms");
        assert!(rooms.count() >= 2);
        let extras = BagExtras {
            rooms: Some(label_markers(&map, &rooms)),
            ..BagExtras::default()
        };
        let out = std::env::temp_dir().join(format!("oxcover-labels-{}.mcap", std::process::id()));
        let bytes = bag_bytes(&map, &[], &TimeModel::default(), extras, &out).expect("bag");
        std::fs::write(&out, bytes).expect("write");
        let decoded = decode_bag(&out);
        std::fs::remove_file(&out).expect("remove");
        let texts = decoded.expect("decodes").overlay.texts;
        let want: Vec<(Point, String, [u8; 3])> = room_anchors(&map, &rooms)
            .into_iter()
            .map(|(l, p)| (p, l.to_string(), [0, 0, 0]))
            .collect();
        assert_eq!(texts, want);
    }

    #[test]
    fn stamps_end_at_the_estimated_time_and_never_decrease() {
        // Short jogs (merged by the metrics), a U-turn and a repeated point.
        let pts: Vec<Point> = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 0.01),
            (2.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (0.0, 1.0),
            (0.5, 1.0),
        ]
        .iter()
        .map(|&(x, y)| Point::new(x, y))
        .collect();
        let time = TimeModel::default();
        let poses = path_poses(&pts, 0.1, &time);
        let shape = PathShape::of(&pts, 0.1);
        let est = time.time(shape.length_m, shape.rotation_rad);
        assert!((poses.last().expect("poses").t - est).abs() < 1e-9 * est);
        assert!(poses.windows(2).all(|w| w[1].t >= w[0].t));
        assert_eq!(poses[0].t, 0.0);
        // Oriented along the next move; the repeated point keeps the heading
        // of its next move (north), the last pose the way it came (east).
        assert!((poses[0].yaw).abs() < 1e-12);
        assert!((poses[4].yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!((poses[7].yaw).abs() < 1e-12);
    }
}
