//! navdeck's own message types in a recording (their definitions are in `schema.rs`),
//! and the exact conversions between them and what the pilot received.

use crate::ros::Header;
use navdeck_core::data::frame_check::{MAX_BEAMS, MAX_MARKERS};
use navdeck_core::data::{
    ArmState, CameraStatus, GripperState, LaserScan, MarkerSighting, SensorFrame,
};
use navdeck_core::geometry::Pose2;
use serde::{Deserialize, Serialize};

/// Sequences read from a recording, refused past a bound as their elements are read,
/// before a claimed length can make the decoder allocate for it.
mod bounded {
    use serde::de::{Deserialize, Deserializer, Error, SeqAccess, Visitor};
    use std::marker::PhantomData;

    struct Bounded<T, const MAX: usize>(PhantomData<T>);

    impl<'de, T: Deserialize<'de>, const MAX: usize> Visitor<'de> for Bounded<T, MAX> {
        type Value = Vec<T>;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a sequence of at most {MAX} elements")
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut out = Vec::new();
            while let Some(element) = seq.next_element()? {
                if out.len() == MAX {
                    return Err(A::Error::custom(format!(
                        "a sequence longer than {MAX} elements"
                    )));
                }
                out.push(element);
            }
            Ok(out)
        }
    }

    /// A `Vec` of at most `MAX` elements.
    pub fn vec<'de, D: Deserializer<'de>, T: Deserialize<'de>, const MAX: usize>(
        d: D,
    ) -> Result<Vec<T>, D::Error> {
        d.deserialize_seq(Bounded::<T, MAX>(PhantomData))
    }
}

/// Blocks a recorded truth holds at most: each carries two markers of the dictionary.
const MAX_BLOCKS: usize = MAX_MARKERS / 2;

/// navdeck_msgs/MarkerSighting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SightingMsg {
    pub id: u32,
    pub range: f64,
    pub bearing: f64,
}

impl From<&MarkerSighting> for SightingMsg {
    fn from(s: &MarkerSighting) -> Self {
        Self {
            id: s.id,
            range: s.range,
            bearing: s.bearing,
        }
    }
}

impl From<SightingMsg> for MarkerSighting {
    fn from(s: SightingMsg) -> Self {
        Self {
            id: s.id,
            range: s.range,
            bearing: s.bearing,
        }
    }
}

/// navdeck_msgs/MarkerSightings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SightingsMsg {
    pub header: Header,
    pub sightings: Vec<SightingMsg>,
}

/// navdeck_msgs/SensorFrame: one poll, exactly.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FrameMsg {
    pub time: f64,
    pub failed: bool,
    pub failure: String,
    pub stamp: f64,
    pub elapsed: f64,
    pub has_wheels: bool,
    pub wheel_left: f64,
    pub wheel_right: f64,
    pub has_sightings: bool,
    #[serde(deserialize_with = "bounded::vec::<_, _, MAX_MARKERS>")]
    pub sightings: Vec<SightingMsg>,
    pub has_scan: bool,
    pub scan_angle_min: f64,
    pub scan_angle_increment: f64,
    pub scan_range_min: f64,
    pub scan_range_max: f64,
    #[serde(deserialize_with = "bounded::vec::<_, _, MAX_BEAMS>")]
    pub scan_ranges: Vec<f32>,
    pub gripper: u8,
    pub has_initial_pose: bool,
    pub initial_pose: [f64; 3],
    pub has_arm: bool,
    pub arm_joints: [f64; 4],
    pub has_camera: bool,
    #[serde(deserialize_with = "bounded::vec::<_, _, MAX_MARKERS>")]
    pub camera_ids: Vec<u32>,
    pub camera_accepted: u32,
    pub camera_rejected: u32,
    pub camera_latency: f64,
    pub camera_error: String,
    pub has_goal: bool,
    pub goal: [f64; 3],
}

const GRIPPER_STATES: [GripperState; 5] = [
    GripperState::Open,
    GripperState::Opening,
    GripperState::Closing,
    GripperState::Closed,
    GripperState::Holding,
];

impl FrameMsg {
    /// The poll at session time `time`: what it brought, or why it failed.
    pub fn from_poll(time: f64, polled: Result<&SensorFrame, &str>) -> Self {
        let frame = match polled {
            Ok(frame) => frame,
            Err(why) => {
                return Self {
                    time,
                    failed: true,
                    failure: why.to_string(),
                    ..Self::default()
                };
            }
        };
        let wheels = frame.wheels.unwrap_or_default();
        let scan = frame.scan.as_ref();
        let pose = frame.initial_pose.unwrap_or_default();
        let goal = frame.goal.unwrap_or_default();
        let camera = frame.camera.as_ref();
        Self {
            time,
            failed: false,
            failure: String::new(),
            stamp: frame.stamp,
            elapsed: frame.elapsed,
            has_wheels: frame.wheels.is_some(),
            wheel_left: wheels.left,
            wheel_right: wheels.right,
            has_sightings: frame.sightings.is_some(),
            sightings: (frame.sightings.iter().flatten().map(SightingMsg::from)).collect(),
            has_scan: scan.is_some(),
            scan_angle_min: scan.map_or(0.0, |s| s.angle_min),
            scan_angle_increment: scan.map_or(0.0, |s| s.angle_increment),
            scan_range_min: scan.map_or(0.0, |s| s.range_min),
            scan_range_max: scan.map_or(0.0, |s| s.range_max),
            scan_ranges: scan.map(|s| s.ranges.clone()).unwrap_or_default(),
            gripper: frame.gripper.map_or(0, |g| {
                GRIPPER_STATES.iter().position(|s| *s == g).unwrap_or(0) as u8 + 1
            }),
            has_initial_pose: frame.initial_pose.is_some(),
            initial_pose: [pose.x, pose.y, pose.theta],
            has_arm: frame.arm.is_some(),
            arm_joints: frame.arm.map_or([0.0; 4], |a| a.joints),
            has_camera: camera.is_some(),
            camera_ids: camera.map(|c| c.ids.clone()).unwrap_or_default(),
            camera_accepted: camera.map_or(0, |c| c.accepted as u32),
            camera_rejected: camera.map_or(0, |c| c.rejected as u32),
            camera_latency: camera.and_then(|c| c.latency).unwrap_or(-1.0),
            camera_error: camera.and_then(|c| c.error.clone()).unwrap_or_default(),
            has_goal: frame.goal.is_some(),
            goal: [goal.x, goal.y, goal.theta],
        }
    }

    /// The poll as the pilot received it: the frame, or the failure's text.
    pub fn to_poll(&self) -> Result<SensorFrame, String> {
        if self.failed {
            return Err(self.failure.clone());
        }
        let [x, y, theta] = self.initial_pose;
        let [gx, gy, gtheta] = self.goal;
        Ok(SensorFrame {
            stamp: self.stamp,
            elapsed: self.elapsed,
            wheels: self.has_wheels.then_some(navdeck_core::data::WheelTravel {
                left: self.wheel_left,
                right: self.wheel_right,
            }),
            sightings: self
                .has_sightings
                .then(|| self.sightings.iter().copied().map(Into::into).collect()),
            scan: self.has_scan.then(|| LaserScan {
                angle_min: self.scan_angle_min,
                angle_increment: self.scan_angle_increment,
                range_min: self.scan_range_min,
                range_max: self.scan_range_max,
                ranges: self.scan_ranges.clone(),
            }),
            gripper: usize::from(self.gripper)
                .checked_sub(1)
                .and_then(|i| GRIPPER_STATES.get(i).copied()),
            camera: self.has_camera.then(|| CameraStatus {
                ids: self.camera_ids.clone(),
                accepted: self.camera_accepted as usize,
                rejected: self.camera_rejected as usize,
                latency: (self.camera_latency >= 0.0).then_some(self.camera_latency),
                thumbnail: None,
                error: (!self.camera_error.is_empty()).then(|| self.camera_error.clone()),
            }),
            initial_pose: self.has_initial_pose.then_some(Pose2::new(x, y, theta)),
            goal: self.has_goal.then_some(Pose2::new(gx, gy, gtheta)),
            arm: self.has_arm.then_some(ArmState {
                joints: self.arm_joints,
            }),
            lane: None,
            tags: None,
        })
    }
}

/// navdeck_msgs/Input kinds.
pub const INPUT_UPDATE: u8 = 0;
pub const INPUT_KEY: u8 = 1;
pub const INPUT_RESIZE: u8 = 2;

/// navdeck_msgs/Input: one call into the console.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct InputMsg {
    pub kind: u8,
    pub time: f64,
    pub key: String,
    pub key_event: u8,
    pub width: u16,
    pub height: u16,
}

impl InputMsg {
    /// Time passing: `App::update(time)`.
    pub fn update(time: f64) -> Self {
        Self {
            kind: INPUT_UPDATE,
            time,
            ..Self::default()
        }
    }

    /// A key named as keymaps name it, and its event (0 press, 1 repeat, 2 release).
    pub fn key(time: f64, key: String, key_event: u8) -> Self {
        Self {
            kind: INPUT_KEY,
            time,
            key,
            key_event,
            ..Self::default()
        }
    }

    /// The terminal's size.
    pub fn resize(time: f64, width: u16, height: u16) -> Self {
        Self {
            kind: INPUT_RESIZE,
            time,
            width,
            height,
            ..Self::default()
        }
    }
}

/// navdeck_msgs/Block.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BlockMsg {
    pub marker_a: u32,
    pub marker_b: u32,
    pub x: f64,
    pub y: f64,
    pub theta: f64,
    pub held: bool,
}

/// navdeck_msgs/Truth.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TruthMsg {
    pub time: f64,
    pub x: f64,
    pub y: f64,
    pub theta: f64,
    pub linear: f64,
    pub angular: f64,
    pub command_linear: f64,
    pub command_angular: f64,
    pub distance_driven: f64,
    pub collisions: u32,
    #[serde(deserialize_with = "bounded::vec::<_, _, MAX_BLOCKS>")]
    pub blocks: Vec<BlockMsg>,
}

impl BlockMsg {
    pub fn of(b: &navdeck_core::sim::BlockState) -> Self {
        Self {
            marker_a: b.markers[0],
            marker_b: b.markers[1],
            x: b.pose.x,
            y: b.pose.y,
            theta: b.pose.theta,
            held: b.held,
        }
    }

    /// Whether `b` is where this says.
    pub fn is(&self, b: &navdeck_core::sim::BlockState) -> bool {
        *self == Self::of(b)
    }
}

impl TruthMsg {
    /// The truth without its blocks.
    pub fn pose_of(time: f64, truth: &dyn navdeck_core::sim::GroundTruth) -> Self {
        let (pose, v, c) = (truth.pose(), truth.velocity(), truth.command());
        Self {
            time,
            x: pose.x,
            y: pose.y,
            theta: pose.theta,
            linear: v.linear,
            angular: v.angular,
            command_linear: c.linear,
            command_angular: c.angular,
            distance_driven: truth.distance_driven(),
            collisions: truth.collisions(),
            blocks: Vec::new(),
        }
    }

    /// The truth with every block.
    pub fn of(time: f64, truth: &dyn navdeck_core::sim::GroundTruth) -> Self {
        Self {
            blocks: truth.blocks().iter().map(BlockMsg::of).collect(),
            ..Self::pose_of(time, truth)
        }
    }

    pub fn pose(&self) -> Pose2 {
        Pose2::new(self.x, self.y, self.theta)
    }
}

/// rcl_interfaces/Log and std_msgs/String, as the ROS 2 link carries them.
pub use crate::ros::{Log as LogMsg, StringMsg};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_comes_back_exactly() {
        let frame = SensorFrame {
            stamp: 1.25,
            elapsed: 0.1,
            wheels: Some(navdeck_core::data::WheelTravel {
                left: 0.1f64.sqrt(),
                right: -1e-17,
            }),
            sightings: Some(vec![MarkerSighting {
                id: 7,
                range: 0.3,
                bearing: -0.2,
            }]),
            scan: Some(LaserScan {
                angle_min: -std::f64::consts::PI,
                angle_increment: std::f64::consts::TAU / 360.0,
                range_min: 0.12,
                range_max: 3.5,
                ranges: vec![1.0, f32::INFINITY, 0.5],
            }),
            gripper: Some(GripperState::Holding),
            camera: None,
            initial_pose: Some(Pose2::new(1.0, 2.0, 0.5)),
            goal: Some(Pose2::new(-1.0, 0.25, 3.0)),
            arm: Some(ArmState {
                joints: [0.1, 0.2, 0.3, 0.4],
            }),
            lane: None,
            tags: None,
        };
        let msg = FrameMsg::from_poll(3.0, Ok(&frame));
        assert_eq!(msg.to_poll(), Ok(frame));
        let failed = FrameMsg::from_poll(4.0, Err("link lost: quiet"));
        assert_eq!(failed.to_poll(), Err("link lost: quiet".to_string()));
    }
}
