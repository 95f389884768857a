//! Plans written as one MCAP file that `ros2 bag play` and Foxglove open as
//! it is: profile `ros2`, CDR messages, `ros2msg` schemas, each topic's
//! offered QoS in its channel's metadata, and rosbag2's own metadata (the
//! `metadata.yaml` of a bag folder) in a `rosbag2` metadata record.
//! Chunks are zstd-compressed on one thread, so the same plan gives the
//! same bytes on any machine.

use std::collections::BTreeMap;
use std::io::Cursor;

use mcap::records::{MessageHeader, Metadata};

use crate::cdr;
use crate::grid;
use crate::msgs::{
    self, Header, MarkerArray, Odometry, Pose, PoseStamped, PoseWithCovariance, Quaternion, Time,
    Twist, TwistWithCovariance, types,
};

/// A pose of the path and when the robot reaches it, in seconds from the
/// first pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StampedPose {
    /// x in metres, map frame.
    pub x: f64,
    /// y in metres, map frame.
    pub y: f64,
    /// Heading in radians.
    pub yaw: f64,
    /// Seconds from the first pose.
    pub t: f64,
}

/// A sample of an executed trajectory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OdomSample {
    /// Seconds from the start.
    pub t: f64,
    /// x in metres, map frame.
    pub x: f64,
    /// y in metres, map frame.
    pub y: f64,
    /// Heading in radians.
    pub yaw: f64,
    /// Forward speed, m/s.
    pub v: f64,
    /// Turn rate, rad/s.
    pub w: f64,
}

/// What a bag of ours holds; topics left empty are not written.
#[derive(Clone, Debug)]
pub struct PlanBag<'a> {
    /// `/map`: the map as read.
    pub map: &'a oxcover_grid::OccupancyGrid,
    /// `/coverage_path`, stamped by the time model.
    pub path: Vec<StampedPose>,
    /// `/rooms`: room outlines and labels.
    pub rooms: Option<MarkerArray>,
    /// `/coverage_targets`: zones, keep-out areas, virtual walls.
    pub targets: Option<MarkerArray>,
    /// `/odom`: an executed trajectory.
    pub odom: Vec<OdomSample>,
}

/// The topics of a bag of ours.
pub mod topics {
    /// The map.
    pub const MAP: &str = "/map";
    /// The coverage path.
    pub const PATH: &str = "/coverage_path";
    /// Rooms.
    pub const ROOMS: &str = "/rooms";
    /// Coverage targets.
    pub const TARGETS: &str = "/coverage_targets";
    /// Executed trajectory.
    pub const ODOM: &str = "/odom";
}

/// rosbag2's QoS profile text (reliable; transient local for the map, so
/// a late subscriber such as RViz still receives it; volatile otherwise).
fn qos(transient_local: bool) -> String {
    let durability = if transient_local { 1 } else { 2 };
    format!(
        "- history: 3\n  depth: 0\n  reliability: 1\n  durability: {durability}\n  deadline:\n    sec: 9223372036\n    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n  avoid_ros_namespace_conventions: false"
    )
}

/// Nanoseconds of `t` seconds (negative and non-finite times count as 0).
fn nanos(t: f64) -> u64 {
    if t.is_finite() && t > 0.0 {
        (t * 1e9).round() as u64
    } else {
        0
    }
}

fn header(t: u64) -> Header {
    Header {
        stamp: Time::from_nanos(t),
        frame_id: "map".into(),
    }
}

fn pose(x: f64, y: f64, yaw: f64) -> Pose {
    Pose {
        position: msgs::Point { x, y, z: 0.0 },
        orientation: Quaternion::from_yaw(yaw),
    }
}

/// One topic's messages: (log time ns, CDR data).
struct Topic {
    name: &'static str,
    type_name: &'static str,
    transient_local: bool,
    messages: Vec<(u64, Vec<u8>)>,
}

/// The MCAP bytes of `bag`, named `file_name` in its rosbag2 metadata.
///
/// # Errors
/// A message or record the encoders refuse (not expected for our types).
pub fn write_mcap(bag: &PlanBag<'_>, file_name: &str) -> Result<Vec<u8>, String> {
    let enc = |e: String| e;
    let mut topics = vec![Topic {
        name: topics::MAP,
        type_name: types::OCCUPANCY_GRID,
        transient_local: true,
        messages: vec![(
            0,
            cdr::encode(&grid::to_msg(bag.map, Time::default())).map_err(enc)?,
        )],
    }];
    if !bag.path.is_empty() {
        let path = msgs::Path {
            header: header(0),
            poses: bag
                .path
                .iter()
                .map(|p| PoseStamped {
                    header: header(nanos(p.t)),
                    pose: pose(p.x, p.y, p.yaw),
                })
                .collect(),
        };
        topics.push(Topic {
            name: topics::PATH,
            type_name: types::PATH,
            transient_local: true,
            messages: vec![(0, cdr::encode(&path)?)],
        });
    }
    for (name, markers) in [(topics::ROOMS, &bag.rooms), (topics::TARGETS, &bag.targets)] {
        if let Some(m) = markers {
            topics.push(Topic {
                name,
                type_name: types::MARKER_ARRAY,
                transient_local: true,
                messages: vec![(0, cdr::encode(m)?)],
            });
        }
    }
    if !bag.odom.is_empty() {
        let messages = bag
            .odom
            .iter()
            .map(|s| {
                let t = nanos(s.t);
                let odom = Odometry {
                    header: Header {
                        stamp: Time::from_nanos(t),
                        frame_id: "map".into(),
                    },
                    child_frame_id: "base_link".into(),
                    pose: PoseWithCovariance {
                        pose: pose(s.x, s.y, s.yaw),
                        ..PoseWithCovariance::default()
                    },
                    twist: TwistWithCovariance {
                        twist: Twist {
                            linear: msgs::Point {
                                x: s.v,
                                y: 0.0,
                                z: 0.0,
                            },
                            angular: msgs::Point {
                                x: 0.0,
                                y: 0.0,
                                z: s.w,
                            },
                        },
                        ..TwistWithCovariance::default()
                    },
                };
                cdr::encode(&odom).map(|d| (t, d))
            })
            .collect::<Result<Vec<_>, _>>()?;
        topics.push(Topic {
            name: topics::ODOM,
            type_name: types::ODOMETRY,
            transient_local: false,
            messages,
        });
    }
    write_topics(&topics, file_name).map_err(|e| format!("MCAP writing failed: {e}"))
}

fn write_topics(topics: &[Topic], file_name: &str) -> mcap::McapResult<Vec<u8>> {
    let options = mcap::WriteOptions::new()
        .profile("ros2")
        .library(concat!("oxcover ", env!("CARGO_PKG_VERSION")))
        .compression(Some(mcap::Compression::Zstd))
        .compression_threads(0);
    let mut out = options.create(Cursor::new(Vec::new()))?;
    let mut channels = Vec::new();
    for t in topics {
        let schema = msgs::schema_text(t.type_name).unwrap_or_default();
        let schema_id = out.add_schema(t.type_name, "ros2msg", schema.as_bytes())?;
        let mut meta = BTreeMap::new();
        meta.insert("offered_qos_profiles".to_string(), qos(t.transient_local));
        channels.push(out.add_channel(schema_id, t.name, "cdr", &meta)?);
    }
    // Messages in log-time order across topics (ties by topic order).
    let mut all: Vec<(u64, usize, usize)> = Vec::new();
    for (ti, t) in topics.iter().enumerate() {
        all.extend(t.messages.iter().enumerate().map(|(mi, m)| (m.0, ti, mi)));
    }
    all.sort_unstable();
    let mut sequence = vec![0u32; topics.len()];
    for &(log_time, ti, mi) in &all {
        sequence[ti] += 1;
        out.write_to_known_channel(
            &MessageHeader {
                channel_id: channels[ti],
                sequence: sequence[ti],
                log_time,
                publish_time: log_time,
            },
            &topics[ti].messages[mi].1,
        )?;
    }
    let mut meta = BTreeMap::new();
    meta.insert(
        "serialized_metadata".to_string(),
        metadata_yaml(topics, file_name, &all),
    );
    out.write_metadata(&Metadata {
        name: "rosbag2".into(),
        metadata: meta,
    })?;
    out.finish()?;
    Ok(out.into_inner().into_inner())
}

/// rosbag2's `metadata.yaml` for these topics (version 5, which every
/// rosbag2 from Humble on reads).
fn metadata_yaml(topics: &[Topic], file_name: &str, all: &[(u64, usize, usize)]) -> String {
    let start = all.first().map_or(0, |m| m.0);
    let end = all.last().map_or(0, |m| m.0);
    let (count, duration) = (all.len(), end - start);
    let name = format!("{file_name:?}");
    let mut y = format!(
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  duration:\n    nanoseconds: {duration}\n  starting_time:\n    nanoseconds_since_epoch: {start}\n  message_count: {count}\n  topics_with_message_count:\n"
    );
    for t in topics {
        let qos = qos(t.transient_local).replace('\n', "\\n");
        y.push_str(&format!(
            "    - topic_metadata:\n        name: {}\n        type: {}\n        serialization_format: cdr\n        offered_qos_profiles: \"{qos}\"\n      message_count: {}\n",
            t.name,
            t.type_name,
            t.messages.len()
        ));
    }
    y.push_str(&format!(
        "  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n    - {name}\n  files:\n    - path: {name}\n      starting_time:\n        nanoseconds_since_epoch: {start}\n      duration:\n        nanoseconds: {duration}\n      message_count: {count}\n"
    ));
    y
}
