//! visualization_msgs: RViz's markers, in Humble's layout and in Iron's and Jazzy's.

use super::{ColorRgba, CompressedImage, Duration, Header, Point, Pose, Vector3};
use serde::{Deserialize, Serialize};

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

/// Marker.type values used here (visualization_msgs/msg/Marker.msg's constants).
pub const MARKER_CUBE: i32 = 1;
pub const MARKER_LINE_STRIP: i32 = 4;
pub const MARKER_LINE_LIST: i32 = 5;
pub const MARKER_CUBE_LIST: i32 = 6;
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
