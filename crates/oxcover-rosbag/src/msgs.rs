//! The ROS 2 message types a bag of ours holds, as serde structs in the
//! field order of their `.msg` definitions (CDR encodes fields in that
//! order, nothing else), and each type's definition in the `ros2msg`
//! schema encoding MCAP and rosbag2 use: the type's own fields, then every
//! type it uses after a line of 80 `=` and `MSG: package/Type`.
//!
//! The definitions are those of ROS 2 Humble and later (Marker with its
//! texture and mesh fields).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `builtin_interfaces/msg/Time`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Time {
    /// Whole seconds.
    pub sec: i32,
    /// Nanoseconds, 0..1e9.
    pub nanosec: u32,
}

impl Time {
    /// The time `ns` nanoseconds after the epoch (saturating at i32 seconds).
    #[must_use]
    pub fn from_nanos(ns: u64) -> Self {
        Self {
            sec: i32::try_from(ns / 1_000_000_000).unwrap_or(i32::MAX),
            nanosec: (ns % 1_000_000_000) as u32,
        }
    }

    /// Nanoseconds since the epoch (negative seconds count as 0).
    #[must_use]
    pub fn nanos(self) -> u64 {
        u64::try_from(self.sec).unwrap_or(0) * 1_000_000_000 + u64::from(self.nanosec)
    }
}

/// `builtin_interfaces/msg/Duration`.
pub type Duration = Time;

/// `std_msgs/msg/Header`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Stamp.
    pub stamp: Time,
    /// Frame id.
    pub frame_id: String,
}

/// `geometry_msgs/msg/Point` (also `Vector3`'s layout).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/msg/Vector3`.
pub type Vector3 = Point;

/// `geometry_msgs/msg/Quaternion`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

impl Default for Quaternion {
    fn default() -> Self {
        Self::from_yaw(0.0)
    }
}

impl Quaternion {
    /// A rotation by `yaw` radians about z.
    #[must_use]
    pub fn from_yaw(yaw: f64) -> Self {
        let (s, c) = (yaw / 2.0).sin_cos();
        Self {
            x: 0.0,
            y: 0.0,
            z: s,
            w: c,
        }
    }

    /// The rotation's yaw (about z), in (-pi, pi].
    #[must_use]
    pub fn yaw(&self) -> f64 {
        let siny = 2.0 * (self.w * self.z + self.x * self.y);
        let cosy = 1.0 - 2.0 * (self.y * self.y + self.z * self.z);
        siny.atan2(cosy)
    }
}

/// `geometry_msgs/msg/Pose`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position.
    pub position: Point,
    /// Orientation.
    pub orientation: Quaternion,
}

/// `geometry_msgs/msg/PoseStamped`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    /// Header.
    pub header: Header,
    /// Pose.
    pub pose: Pose,
}

/// `nav_msgs/msg/MapMetaData`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MapMetaData {
    /// When the map was loaded.
    pub map_load_time: Time,
    /// Metres per cell.
    pub resolution: f32,
    /// Cells per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Pose of cell (0, 0)'s corner in the map frame.
    pub origin: Pose,
}

/// `nav_msgs/msg/OccupancyGrid`: row-major, row 0 at the origin, values
/// 0..100 (occupancy in percent) or -1 (unknown).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct OccupancyGrid {
    /// Header.
    pub header: Header,
    /// Size and placement.
    pub info: MapMetaData,
    /// Cells.
    #[serde(with = "int8_seq")]
    pub data: Vec<i8>,
}

/// An `int8[]` coded as CDR codes it, a length then the bytes, read and
/// written whole (serde's sequences go element by element: a 16384² map
/// would be 2^28 calls).
mod int8_seq {
    use serde::{Deserializer, Serializer};

    pub(super) fn serialize<S: Serializer>(v: &[i8], s: S) -> Result<S::Ok, S::Error> {
        let bytes: Vec<u8> = v.iter().map(|&x| x as u8).collect();
        s.serialize_bytes(&bytes)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<i8>, D::Error> {
        struct Visit;
        impl serde::de::Visitor<'_> for Visit {
            type Value = Vec<i8>;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("an int8 sequence")
            }
            fn visit_bytes<E: serde::de::Error>(self, v: &[u8]) -> Result<Vec<i8>, E> {
                Ok(v.iter().map(|&x| x as i8).collect())
            }
        }
        d.deserialize_bytes(Visit)
    }
}

/// `nav_msgs/msg/Path`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// Header.
    pub header: Header,
    /// Poses, each stamped.
    pub poses: Vec<PoseStamped>,
}

/// `float64[36]`: a row-major 6x6 covariance (serde derives stop at 32).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covariance(pub [f64; 36]);

impl Default for Covariance {
    fn default() -> Self {
        Self([0.0; 36])
    }
}

impl Serialize for Covariance {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple as _;
        let mut t = s.serialize_tuple(36)?;
        for v in &self.0 {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for Covariance {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = Covariance;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("36 float64")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Covariance, A::Error> {
                let mut out = [0.0; 36];
                for (i, v) in out.iter_mut().enumerate() {
                    *v = seq
                        .next_element()?
                        .ok_or_else(|| serde::de::Error::invalid_length(i, &self))?;
                }
                Ok(Covariance(out))
            }
        }
        d.deserialize_tuple(36, Visit)
    }
}

/// `geometry_msgs/msg/PoseWithCovariance`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    /// Pose.
    pub pose: Pose,
    /// Covariance.
    pub covariance: Covariance,
}

/// `geometry_msgs/msg/Twist`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// Linear velocity.
    pub linear: Vector3,
    /// Angular velocity.
    pub angular: Vector3,
}

/// `geometry_msgs/msg/TwistWithCovariance`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TwistWithCovariance {
    /// Twist.
    pub twist: Twist,
    /// Covariance.
    pub covariance: Covariance,
}

/// `nav_msgs/msg/Odometry`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Odometry {
    /// Header (frame of the pose).
    pub header: Header,
    /// Frame of the twist.
    pub child_frame_id: String,
    /// Pose.
    pub pose: PoseWithCovariance,
    /// Twist, in the child frame.
    pub twist: TwistWithCovariance,
}

/// `std_msgs/msg/ColorRGBA`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ColorRgba {
    /// Red, 0..1.
    pub r: f32,
    /// Green, 0..1.
    pub g: f32,
    /// Blue, 0..1.
    pub b: f32,
    /// Alpha, 0..1.
    pub a: f32,
}

/// `sensor_msgs/msg/CompressedImage` (a Marker's texture; empty here).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CompressedImage {
    /// Header.
    pub header: Header,
    /// Format.
    pub format: String,
    /// Bytes.
    pub data: Vec<u8>,
}

/// `visualization_msgs/msg/UVCoordinate`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct UvCoordinate {
    /// u.
    pub u: f32,
    /// v.
    pub v: f32,
}

/// `visualization_msgs/msg/MeshFile`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshFile {
    /// File name.
    pub filename: String,
    /// Bytes.
    pub data: Vec<u8>,
}

/// `visualization_msgs/msg/Marker`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Marker {
    /// Header.
    pub header: Header,
    /// Namespace.
    pub ns: String,
    /// Id within the namespace.
    pub id: i32,
    /// Kind: [`Marker::LINE_STRIP`], [`Marker::LINE_LIST`], [`Marker::TEXT_VIEW_FACING`]...
    #[serde(rename = "type")]
    pub kind: i32,
    /// 0 add/modify, 2 delete, 3 delete all.
    pub action: i32,
    /// Pose of the marker's frame.
    pub pose: Pose,
    /// Scale (line width in x; text height in z).
    pub scale: Vector3,
    /// Colour.
    pub color: ColorRgba,
    /// How long it lasts (0: forever).
    pub lifetime: Duration,
    /// Whether it follows its frame.
    pub frame_locked: bool,
    /// Points of a line strip or list.
    pub points: Vec<Point>,
    /// Per-point colours (none here).
    pub colors: Vec<ColorRgba>,
    /// Texture resource (none here).
    pub texture_resource: String,
    /// Texture (none here).
    pub texture: CompressedImage,
    /// Texture coordinates (none here).
    pub uv_coordinates: Vec<UvCoordinate>,
    /// Text of a text marker.
    pub text: String,
    /// Mesh resource (none here).
    pub mesh_resource: String,
    /// Mesh file (none here).
    pub mesh_file: MeshFile,
    /// Mesh materials flag.
    pub mesh_use_embedded_materials: bool,
}

impl Marker {
    /// A connected polyline.
    pub const LINE_STRIP: i32 = 4;
    /// Separate segments, two points each.
    pub const LINE_LIST: i32 = 5;
    /// Text facing the viewer.
    pub const TEXT_VIEW_FACING: i32 = 9;
}

/// `visualization_msgs/msg/MarkerArray`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MarkerArray {
    /// Markers.
    pub markers: Vec<Marker>,
}

/// One type's own fields (package-relative names resolve in its package)
/// and the full names of the types it uses.
const DEFINITIONS: &[(&str, &str, &[&str])] = &[
    (
        "builtin_interfaces/Time",
        "int32 sec\nuint32 nanosec\n",
        &[],
    ),
    (
        "builtin_interfaces/Duration",
        "int32 sec\nuint32 nanosec\n",
        &[],
    ),
    (
        "std_msgs/Header",
        "builtin_interfaces/Time stamp\nstring frame_id\n",
        &["builtin_interfaces/Time"],
    ),
    (
        "std_msgs/ColorRGBA",
        "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n",
        &[],
    ),
    (
        "geometry_msgs/Point",
        "float64 x\nfloat64 y\nfloat64 z\n",
        &[],
    ),
    (
        "geometry_msgs/Vector3",
        "float64 x\nfloat64 y\nfloat64 z\n",
        &[],
    ),
    (
        "geometry_msgs/Quaternion",
        "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
        &[],
    ),
    (
        "geometry_msgs/Pose",
        "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
        &["geometry_msgs/Point", "geometry_msgs/Quaternion"],
    ),
    (
        "geometry_msgs/PoseStamped",
        "std_msgs/Header header\ngeometry_msgs/Pose pose\n",
        &["std_msgs/Header", "geometry_msgs/Pose"],
    ),
    (
        "geometry_msgs/PoseWithCovariance",
        "geometry_msgs/Pose pose\nfloat64[36] covariance\n",
        &["geometry_msgs/Pose"],
    ),
    (
        "geometry_msgs/Twist",
        "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
        &["geometry_msgs/Vector3"],
    ),
    (
        "geometry_msgs/TwistWithCovariance",
        "geometry_msgs/Twist twist\nfloat64[36] covariance\n",
        &["geometry_msgs/Twist"],
    ),
    (
        "nav_msgs/MapMetaData",
        "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\ngeometry_msgs/Pose origin\n",
        &["builtin_interfaces/Time", "geometry_msgs/Pose"],
    ),
    (
        "nav_msgs/OccupancyGrid",
        "std_msgs/Header header\nnav_msgs/MapMetaData info\nint8[] data\n",
        &["std_msgs/Header", "nav_msgs/MapMetaData"],
    ),
    (
        "nav_msgs/Path",
        "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
        &["std_msgs/Header", "geometry_msgs/PoseStamped"],
    ),
    (
        "nav_msgs/Odometry",
        "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
        &[
            "std_msgs/Header",
            "geometry_msgs/PoseWithCovariance",
            "geometry_msgs/TwistWithCovariance",
        ],
    ),
    (
        "sensor_msgs/CompressedImage",
        "std_msgs/Header header\nstring format\nuint8[] data\n",
        &["std_msgs/Header"],
    ),
    (
        "visualization_msgs/UVCoordinate",
        "float32 u\nfloat32 v\n",
        &[],
    ),
    (
        "visualization_msgs/MeshFile",
        "string filename\nuint8[] data\n",
        &[],
    ),
    (
        "visualization_msgs/Marker",
        "int32 LINE_STRIP=4\nint32 LINE_LIST=5\nint32 TEXT_VIEW_FACING=9\nint32 ADD=0\n\
std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\ngeometry_msgs/Pose pose\n\
geometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\nbuiltin_interfaces/Duration lifetime\n\
bool frame_locked\ngeometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring texture_resource\n\
sensor_msgs/CompressedImage texture\nvisualization_msgs/UVCoordinate[] uv_coordinates\nstring text\n\
string mesh_resource\nvisualization_msgs/MeshFile mesh_file\nbool mesh_use_embedded_materials\n",
        &[
            "std_msgs/Header",
            "geometry_msgs/Pose",
            "geometry_msgs/Vector3",
            "std_msgs/ColorRGBA",
            "builtin_interfaces/Duration",
            "geometry_msgs/Point",
            "sensor_msgs/CompressedImage",
            "visualization_msgs/UVCoordinate",
            "visualization_msgs/MeshFile",
        ],
    ),
    (
        "visualization_msgs/MarkerArray",
        "visualization_msgs/Marker[] markers\n",
        &["visualization_msgs/Marker"],
    ),
];

/// The ROS 2 type name (`pkg/msg/Type`) of a definition's `pkg/Type`.
#[must_use]
pub fn full_name(short: &str) -> String {
    match short.split_once('/') {
        Some((pkg, ty)) => format!("{pkg}/msg/{ty}"),
        None => short.to_string(),
    }
}

/// The `ros2msg` schema text of `type_name` (`pkg/msg/Type` or
/// `pkg/Type`): its fields, then each type it uses, once, depth first.
/// `None` for a type this crate does not define.
#[must_use]
pub fn schema_text(type_name: &str) -> Option<String> {
    let short = type_name.replace("/msg/", "/");
    let find = |name: &str| DEFINITIONS.iter().find(|d| d.0 == name);
    let root = find(&short)?;
    let mut text = root.1.to_string();
    let mut seen = vec![root.0];
    let mut stack: Vec<&str> = root.2.iter().rev().copied().collect();
    while let Some(name) = stack.pop() {
        if seen.contains(&name) {
            continue;
        }
        seen.push(name);
        let def = find(name)?;
        text.push_str(&"=".repeat(80));
        text.push_str("\nMSG: ");
        text.push_str(name);
        text.push('\n');
        text.push_str(def.1);
        stack.extend(def.2.iter().rev().copied());
    }
    Some(text)
}

/// ROS 2 type names of the messages this crate writes and reads.
pub mod types {
    /// `nav_msgs/msg/OccupancyGrid`.
    pub const OCCUPANCY_GRID: &str = "nav_msgs/msg/OccupancyGrid";
    /// `nav_msgs/msg/Path`.
    pub const PATH: &str = "nav_msgs/msg/Path";
    /// `nav_msgs/msg/Odometry`.
    pub const ODOMETRY: &str = "nav_msgs/msg/Odometry";
    /// `visualization_msgs/msg/MarkerArray`.
    pub const MARKER_ARRAY: &str = "visualization_msgs/msg/MarkerArray";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_used_type_is_defined_and_schemas_list_each_once() {
        for (name, _, deps) in DEFINITIONS {
            for d in *deps {
                assert!(DEFINITIONS.iter().any(|x| x.0 == *d), "{name} uses {d}");
            }
            let text = schema_text(name).expect("defined");
            for d in *deps {
                assert_eq!(
                    text.matches(&format!("MSG: {d}\n")).count(),
                    1,
                    "{name}: {d}"
                );
            }
        }
        let path = schema_text(types::PATH).expect("path");
        assert!(path.starts_with("std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n"));
        assert!(schema_text("nav_msgs/msg/Nothing").is_none());
    }

    #[test]
    fn quaternion_yaw_round_trips() {
        for yaw in [-3.0, -1.0, 0.0, 0.5, 3.1] {
            assert!((Quaternion::from_yaw(yaw).yaw() - yaw).abs() < 1e-12);
        }
        assert_eq!(Time::from_nanos(1_500_000_000).nanos(), 1_500_000_000);
    }
}
