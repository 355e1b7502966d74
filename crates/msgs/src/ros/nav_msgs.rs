//! nav_msgs: odometry, the occupancy grid and paths.

use super::{Header, Pose, PoseStamped, PoseWithCovariance, Time, TwistWithCovariance};
use serde::de::{SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// nav_msgs/Odometry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Odometry {
    pub header: Header,
    pub child_frame_id: String,
    pub pose: PoseWithCovariance,
    pub twist: TwistWithCovariance,
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

/// nav_msgs/Path.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Path {
    pub header: Header,
    pub poses: Vec<PoseStamped>,
}
