//! What the robot's topics bring in: odometry (the watchdog's heartbeat, and wheel travel
//! from its deltas when there are no wheel joints), wheel joints (seed 001's wheel travel)
//! and laser scans. A message that fails its checks is dropped and counted.

use super::inbound::{self, Refusal};
use super::inbox::{Inbox, Urgency};
use super::participant::{Factory, qos_profile};
use super::{Ros2Link, arm_joints, msgs};
use crate::rate::RateMeter;
use crate::{LinkError, Notice, WheelTravel};
use navdeck_core::geometry::Pose2;
use ros2_client::QosProfile;

/// The robot's topics navdeck reads, and how often odometry and scans arrive.
pub(super) struct Inbound {
    odom: Inbox<msgs::Odometry>,
    joints: Inbox<msgs::JointState>,
    scan: Inbox<msgs::LaserScan>,
    pub(super) odom_rate: RateMeter,
    pub(super) scan_rate: RateMeter,
}

impl Inbound {
    /// Subscribes to odometry, joint states and scans, in that order.
    pub(super) fn open(f: &mut Factory<'_>, qos: &QosProfile) -> Result<Self, LinkError> {
        let c = f.config;
        let odom = f.inbox(
            "odom_topic",
            &c.odom_topic,
            ("nav_msgs", "Odometry"),
            qos.clone(),
            Urgency::Tick,
        )?;
        let joints = f.inbox(
            "joint_states_topic",
            &c.joint_states_topic,
            ("sensor_msgs", "JointState"),
            qos.clone(),
            Urgency::Tick,
        )?;
        let scan = f.inbox(
            "scan_topic",
            &c.scan_topic,
            ("sensor_msgs", "LaserScan"),
            qos_profile(c.scan_qos, false),
            Urgency::Tick,
        )?;
        Ok(Self {
            odom,
            joints,
            scan,
            odom_rate: RateMeter::default(),
            scan_rate: RateMeter::default(),
        })
    }
}

/// Wheel travel gathered from joint states (or odometry deltas) since the last frame,
/// and the readings the next delta is taken from.
pub(super) struct WheelOdometry {
    /// The robot's wheel track, metres, for the odometry fallback.
    track: f64,
    /// Wheel travel faster than this between two messages is refused, m/s
    /// (`RobotConfig::max_wheel_speed`).
    max_wheel_speed: f64,
    /// The newest odometry pose and its stamp, for the fallback and the transform.
    pub(super) odom_pose: Option<(Pose2, f64)>,
    joint_angles: Option<((f64, f64), f64)>,
    travel: WheelTravel,
    elapsed: f64,
}

impl WheelOdometry {
    pub(super) fn new(track: f64, max_wheel_speed: f64) -> Self {
        Self {
            track,
            max_wheel_speed,
            odom_pose: None,
            joint_angles: None,
            travel: WheelTravel::default(),
            elapsed: 0.0,
        }
    }

    fn add_travel(&mut self, t: WheelTravel, dt: f64) {
        self.travel.left += t.left;
        self.travel.right += t.right;
        self.elapsed += dt;
    }

    /// The travel and time gathered since the last take (no travel when nothing moved
    /// and no time passed), starting afresh.
    pub(super) fn take(&mut self) -> (Option<WheelTravel>, f64) {
        let wheels = (self.elapsed > 0.0 || self.travel != WheelTravel::default())
            .then(|| std::mem::take(&mut self.travel));
        let elapsed = std::mem::take(&mut self.elapsed);
        (wheels, elapsed)
    }
}

impl Ros2Link {
    fn refuse(&mut self, topic: &str, why: Refusal) {
        let count = self.dropped.entry(why.label()).or_insert(0);
        *count += 1;
        // The first of each kind is worth a line; after that, every hundredth.
        if *count == 1 || (*count).is_multiple_of(100) {
            self.notices.push(Notice::warn(format!(
                "ROS 2: dropped a {topic} message ({}; {count} so far)",
                why.label()
            )));
        }
    }

    pub(super) fn take_odometry(&mut self, now: f64) {
        for msg in self.inbound.odom.take_all("odometry", &mut self.notices) {
            let pose = match inbound::odom_pose(&msg) {
                Ok(p) => p,
                Err(why) => {
                    self.refuse("odometry", why);
                    continue;
                }
            };
            let stamp = inbound::stamp_seconds(&msg.header).unwrap_or(now);
            if self.wheels.joint_angles.is_none()
                && let Some((before, at)) = self.wheels.odom_pose
            {
                let dt = (stamp - at).max(0.0);
                match inbound::odom_travel(
                    before,
                    pose,
                    self.wheels.track,
                    dt,
                    self.wheels.max_wheel_speed,
                ) {
                    Ok(t) => self.wheels.add_travel(t, dt),
                    Err(why) => self.refuse("odometry", why),
                }
            }
            self.wheels.odom_pose = Some((pose, stamp));
            self.odom_at = Some(now);
            self.inbound.odom_rate.note(now);
        }
    }

    /// An arm reading dropped: the first of each kind and every hundredth say why.
    fn refuse_arm(&mut self, why: arm_joints::Refused) {
        let count = self.dropped.entry(why.kind).or_insert(0);
        *count += 1;
        if *count == 1 || (*count).is_multiple_of(100) {
            self.notices.push(Notice::warn(format!(
                "ROS 2: dropped a {} message for the arm: {} ({}; {count} so far)",
                self.config.joint_states_topic, why.detail, why.kind
            )));
        }
    }

    pub(super) fn take_joints(&mut self, now: f64) {
        for msg in self
            .inbound
            .joints
            .take_all("joint states", &mut self.notices)
        {
            if let Some(arm) = &mut self.arm
                && let Err(why) = arm.read(&msg)
            {
                self.refuse_arm(why);
            }
            let angles = match inbound::wheel_angles(
                &msg,
                &self.config.left_wheel_joint,
                &self.config.right_wheel_joint,
            ) {
                Ok(a) => a,
                // Other joints (an arm) share the topic: not an error.
                Err(Refusal::BadJoints) => continue,
                Err(why) => {
                    self.refuse("joint_states", why);
                    continue;
                }
            };
            let stamp = inbound::stamp_seconds(&msg.header).unwrap_or(now);
            if let Some((before, at)) = self.wheels.joint_angles {
                let dt = (stamp - at).max(0.0);
                match inbound::joint_travel(
                    before,
                    angles,
                    self.config.wheel_radius,
                    dt,
                    self.wheels.max_wheel_speed,
                ) {
                    Ok(t) => self.wheels.add_travel(t, dt),
                    Err(why) => self.refuse("joint_states", why),
                }
            } else {
                self.notices.push(Notice::info(
                    "ROS 2: wheel joints found: wheel travel from joint states",
                ));
            }
            self.wheels.joint_angles = Some((angles, stamp));
        }
    }

    pub(super) fn take_scan(&mut self, now: f64) -> Option<crate::LaserScan> {
        let mut newest = None;
        for msg in self.inbound.scan.take_all("scan", &mut self.notices) {
            self.inbound.scan_rate.note(now);
            match inbound::scan(&msg) {
                Ok(s) => newest = Some(s),
                Err(why) => self.refuse("scan", why),
            }
        }
        newest
    }
}
