//! The ROS 2 message types navdeck speaks, laid out field for field as their `.msg`
//! definitions so that CDR (the DDS wire encoding) reads and writes them as ROS 2 does.

use serde::de::{Error as _, SeqAccess, Visitor};
use serde::ser::SerializeTuple;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// builtin_interfaces/Time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    /// Seconds as a float.
    pub fn seconds(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }

    /// From seconds since the epoch (saturating outside i32 seconds).
    pub fn from_seconds(t: f64) -> Self {
        let sec = t.floor();
        Self {
            sec: sec.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32,
            nanosec: (((t - sec) * 1e9) as u32).min(999_999_999),
        }
    }
}

/// builtin_interfaces/Duration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Duration {
    pub sec: i32,
    pub nanosec: u32,
}

impl Duration {
    /// From seconds, rounded to the nanosecond (non-finite or negative: zero; saturating
    /// at i32 seconds).
    pub fn from_seconds(t: f64) -> Self {
        if !(t.is_finite() && t > 0.0) {
            return Self::default();
        }
        let whole = t.floor().min(f64::from(i32::MAX));
        let nanos = ((t - whole) * 1e9).round().min(999_999_999.0);
        Self {
            sec: whole as i32,
            nanosec: nanos as u32,
        }
    }

    pub fn seconds(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }
}

/// std_msgs/Header.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}

impl Header {
    pub fn new(stamp: Time, frame_id: &str) -> Self {
        Self {
            stamp,
            frame_id: frame_id.to_string(),
        }
    }
}

/// geometry_msgs/Vector3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Vector3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// geometry_msgs/Point.
pub type Point = Vector3;

/// geometry_msgs/Quaternion.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

impl Default for Quaternion {
    fn default() -> Self {
        Self::from_yaw(0.0)
    }
}

impl Quaternion {
    /// A rotation of `yaw` radians about z.
    pub fn from_yaw(yaw: f64) -> Self {
        let (s, c) = (0.5 * yaw).sin_cos();
        Self {
            x: 0.0,
            y: 0.0,
            z: s,
            w: c,
        }
    }

    /// The rotation's yaw (heading about z), radians: atan2(2(wz + xy), 1 - 2(y² + z²)).
    pub fn yaw(self) -> f64 {
        let Self { x, y, z, w } = self;
        (2.0 * (w * z + x * y)).atan2(1.0 - 2.0 * (y * y + z * z))
    }

    pub fn is_finite(self) -> bool {
        [self.x, self.y, self.z, self.w]
            .iter()
            .all(|v| v.is_finite())
    }
}

/// geometry_msgs/Pose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub position: Point,
    pub orientation: Quaternion,
}

/// A row-major 6x6 covariance (x, y, z, roll, pitch, yaw), as ROS 2 sends it: a fixed
/// array, so no length on the wire.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covariance6(pub [f64; 36]);

impl Default for Covariance6 {
    fn default() -> Self {
        Self([0.0; 36])
    }
}

impl Serialize for Covariance6 {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut tuple = serializer.serialize_tuple(36)?;
        for v in &self.0 {
            tuple.serialize_element(v)?;
        }
        tuple.end()
    }
}

impl<'de> Deserialize<'de> for Covariance6 {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Elements;
        impl<'de> Visitor<'de> for Elements {
            type Value = Covariance6;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("36 doubles")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Covariance6, A::Error> {
                let mut out = [0.0; 36];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| A::Error::invalid_length(i, &self))?;
                }
                Ok(Covariance6(out))
            }
        }
        deserializer.deserialize_tuple(36, Elements)
    }
}

/// geometry_msgs/PoseWithCovariance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    pub pose: Pose,
    pub covariance: Covariance6,
}

/// geometry_msgs/Twist.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    pub linear: Vector3,
    pub angular: Vector3,
}

impl Twist {
    /// A planar twist: forward speed and yaw rate.
    pub fn planar(linear: f64, angular: f64) -> Self {
        Self {
            linear: Vector3 {
                x: linear,
                ..Vector3::default()
            },
            angular: Vector3 {
                z: angular,
                ..Vector3::default()
            },
        }
    }
}

/// geometry_msgs/TwistStamped (what Jazzy's TurtleBot3 listens for on cmd_vel).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TwistStamped {
    pub header: Header,
    pub twist: Twist,
}

/// geometry_msgs/TwistWithCovariance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TwistWithCovariance {
    pub twist: Twist,
    pub covariance: Covariance6,
}

/// nav_msgs/Odometry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Odometry {
    pub header: Header,
    pub child_frame_id: String,
    pub pose: PoseWithCovariance,
    pub twist: TwistWithCovariance,
}

/// sensor_msgs/JointState.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    pub header: Header,
    pub name: Vec<String>,
    pub position: Vec<f64>,
    pub velocity: Vec<f64>,
    pub effort: Vec<f64>,
}

pub use crate::arm_msgs::{
    GripperCommand, GripperCommandFeedback, GripperCommandGoal, GripperCommandResult,
    JointTrajectory, JointTrajectoryPoint,
};

/// sensor_msgs/LaserScan.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    pub header: Header,
    pub angle_min: f32,
    pub angle_max: f32,
    pub angle_increment: f32,
    pub time_increment: f32,
    pub scan_time: f32,
    pub range_min: f32,
    pub range_max: f32,
    pub ranges: Vec<f32>,
    pub intensities: Vec<f32>,
}

/// sensor_msgs/Image.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Image {
    pub header: Header,
    pub height: u32,
    pub width: u32,
    pub encoding: String,
    pub is_bigendian: u8,
    pub step: u32,
    pub data: Vec<u8>,
}

/// std_msgs/Float64.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Float64 {
    pub data: f64,
}

/// std_msgs/String.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StringMsg {
    pub data: String,
}

/// rcl_interfaces/Log: a line on /rosout (severities in `rosout.rs`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Log {
    pub stamp: Time,
    pub level: u8,
    pub name: String,
    pub msg: String,
    pub file: String,
    pub function: String,
    pub line: u32,
}

/// nav_msgs/MapMetaData.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MapMetaData {
    pub map_load_time: Time,
    pub resolution: f32,
    pub width: u32,
    pub height: u32,
    pub origin: Pose,
}

/// nav_msgs/OccupancyGrid: row-major from the lower-left cell, -1 unknown, 0..100.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct OccupancyGrid {
    pub header: Header,
    pub info: MapMetaData,
    pub data: Cells,
}

/// A grid's int8[] cells. CDR lays a sequence of int8 out as its length and then the
/// bytes, exactly as it does octets: written as one block, not cell by cell (a 450 x 450
/// map is 200 k cells).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cells(pub Vec<i8>);

impl Serialize for Cells {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let bytes: Vec<u8> = self.0.iter().map(|&c| c as u8).collect();
        serializer.serialize_bytes(&bytes)
    }
}

impl<'de> Deserialize<'de> for Cells {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Bytes;
        impl<'de> Visitor<'de> for Bytes {
            type Value = Cells;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a sequence of int8")
            }
            fn visit_bytes<E: serde::de::Error>(self, v: &[u8]) -> Result<Cells, E> {
                Ok(Cells(v.iter().map(|&b| b as i8).collect()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Cells, A::Error> {
                let mut out = Vec::new();
                while let Some(c) = seq.next_element::<i8>()? {
                    out.push(c);
                }
                Ok(Cells(out))
            }
        }
        deserializer.deserialize_bytes(Bytes)
    }
}

/// geometry_msgs/PoseStamped.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    pub header: Header,
    pub pose: Pose,
}

/// nav_msgs/Path.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Path {
    pub header: Header,
    pub poses: Vec<PoseStamped>,
}

/// geometry_msgs/PoseArray (what AMCL publishes its particles as).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseArray {
    pub header: Header,
    pub poses: Vec<Pose>,
}

/// geometry_msgs/PoseWithCovarianceStamped.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovarianceStamped {
    pub header: Header,
    pub pose: PoseWithCovariance,
}

/// geometry_msgs/Transform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Transform {
    pub translation: Vector3,
    pub rotation: Quaternion,
}

/// geometry_msgs/TransformStamped.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TransformStamped {
    pub header: Header,
    pub child_frame_id: String,
    pub transform: Transform,
}

/// tf2_msgs/TFMessage.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TfMessage {
    pub transforms: Vec<TransformStamped>,
}

/// std_msgs/ColorRGBA.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ColorRgba {
    pub r: f32,
    pub g: f32,
    pub b: f32,
    pub a: f32,
}

/// visualization_msgs/Marker as Humble defines it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MarkerHumble {
    pub header: Header,
    pub ns: String,
    pub id: i32,
    pub kind: i32,
    pub action: i32,
    pub pose: Pose,
    pub scale: Vector3,
    pub color: ColorRgba,
    pub lifetime: Duration,
    pub frame_locked: bool,
    pub points: Vec<Point>,
    pub colors: Vec<ColorRgba>,
    pub text: String,
    pub mesh_resource: String,
    pub mesh_use_embedded_materials: bool,
}

/// sensor_msgs/CompressedImage (carried, empty, by Iron's and Jazzy's Marker).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CompressedImage {
    pub header: Header,
    pub format: String,
    pub data: Vec<u8>,
}

/// visualization_msgs/UVCoordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct UvCoordinate {
    pub u: f32,
    pub v: f32,
}

/// visualization_msgs/MeshFile.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshFile {
    pub filename: String,
    pub data: Vec<u8>,
}

/// visualization_msgs/Marker as Iron and Jazzy define it (texture and mesh fields added).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MarkerJazzy {
    pub header: Header,
    pub ns: String,
    pub id: i32,
    pub kind: i32,
    pub action: i32,
    pub pose: Pose,
    pub scale: Vector3,
    pub color: ColorRgba,
    pub lifetime: Duration,
    pub frame_locked: bool,
    pub points: Vec<Point>,
    pub colors: Vec<ColorRgba>,
    pub texture_resource: String,
    pub texture: CompressedImage,
    pub uv_coordinates: Vec<UvCoordinate>,
    pub text: String,
    pub mesh_resource: String,
    pub mesh_file: MeshFile,
    pub mesh_use_embedded_materials: bool,
}

/// visualization_msgs/MarkerArray, generic over the distribution's Marker layout.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MarkerArray<M> {
    pub markers: Vec<M>,
}

/// Marker.type values used here (visualization_msgs/Marker constants).
pub const MARKER_LINE_STRIP: i32 = 4;
pub const MARKER_TEXT_VIEW_FACING: i32 = 9;
/// Marker.action values.
pub const MARKER_ADD: i32 = 0;
pub const MARKER_DELETEALL: i32 = 3;

impl From<MarkerHumble> for MarkerJazzy {
    fn from(m: MarkerHumble) -> Self {
        Self {
            header: m.header,
            ns: m.ns,
            id: m.id,
            kind: m.kind,
            action: m.action,
            pose: m.pose,
            scale: m.scale,
            color: m.color,
            lifetime: m.lifetime,
            frame_locked: m.frame_locked,
            points: m.points,
            colors: m.colors,
            text: m.text,
            mesh_resource: m.mesh_resource,
            mesh_use_embedded_materials: m.mesh_use_embedded_materials,
            ..Self::default()
        }
    }
}
