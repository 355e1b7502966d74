//! cmd_vel out: Twist, TwistStamped or both, as `[ros2] cmd_vel_type` says, at the pace
//! `cmd_vel.rs` sets; in auto mode, the type discovery found the robot reading.

use super::cmd_vel::CmdVelPolicy;
use super::config::{CmdVelType, Ros2Config};
use super::discovery::Peer;
use super::participant::Factory;
use super::{msgs, now_stamp};
use crate::{LinkError, Notice};
use navdeck_core::geometry::Twist;
use ros2_client::dds::rustdds::GUID;
use ros2_client::{Publisher, QosProfile};

/// cmd_vel's publishers, when to put a velocity on them, and whether the user was told
/// that nothing reads them yet.
pub(super) struct CmdVelOut {
    twist: Option<Publisher<msgs::Twist>>,
    stamped: Option<Publisher<msgs::TwistStamped>>,
    policy: CmdVelPolicy,
    warned_no_peer: bool,
}

impl CmdVelOut {
    /// The publishers `[ros2] cmd_vel_type` asks for: Twist, then TwistStamped.
    pub(super) fn open(f: &mut Factory<'_>, qos: &QosProfile) -> Result<Self, LinkError> {
        let c = f.config;
        let twist = match c.cmd_vel_type {
            CmdVelType::TwistStamped => None,
            _ => Some(f.publisher(
                "cmd_vel_topic",
                &c.cmd_vel_topic,
                "geometry_msgs",
                "Twist",
                qos.clone(),
            )?),
        };
        let stamped = match c.cmd_vel_type {
            CmdVelType::Twist => None,
            _ => Some(f.publisher(
                "cmd_vel_topic",
                &c.cmd_vel_topic,
                "geometry_msgs",
                "TwistStamped",
                qos.clone(),
            )?),
        };
        Ok(Self {
            twist,
            stamped,
            policy: CmdVelPolicy::default(),
            warned_no_peer: false,
        })
    }

    /// One of navdeck's own cmd_vel publishers, which discovery leaves out.
    pub(super) fn guid(&self) -> Option<GUID> {
        self.twist
            .as_ref()
            .map(|p| p.guid())
            .or_else(|| self.stamped.as_ref().map(|p| p.guid()))
    }

    /// A control step's command: on the wire when the policy says it should go.
    pub(super) fn send(
        &mut self,
        twist: Twist,
        config: &Ros2Config,
        peer: Peer,
        notices: &mut Vec<Notice>,
    ) {
        if self.policy.should_send(twist) {
            self.publish(twist, config, peer, notices);
        }
    }

    /// `twist` on the publishers the robot reads.
    pub(super) fn publish(
        &mut self,
        twist: Twist,
        config: &Ros2Config,
        peer: Peer,
        notices: &mut Vec<Notice>,
    ) {
        let body = msgs::Twist::planar(twist.linear, twist.angular);
        // In auto mode nothing goes out before the subscriber's type is known: some DDS
        // implementations match readers by topic name alone and would misread the other type.
        let (plain, stamped) = match (config.cmd_vel_type, peer) {
            (CmdVelType::Auto, Peer::Twist) => (true, false),
            (CmdVelType::Auto, Peer::Stamped) => (false, true),
            (CmdVelType::Auto, Peer::Unknown) => {
                if !self.warned_no_peer && twist != Twist::ZERO {
                    self.warned_no_peer = true;
                    notices.push(Notice::warn(format!(
                        "ROS 2: nothing subscribes to {} yet: not moving (set [ros2] cmd_vel_type to publish blind)",
                        config.cmd_vel_topic
                    )));
                }
                (false, false)
            }
            _ => (self.twist.is_some(), self.stamped.is_some()),
        };
        // Best effort: moving, the next control step sends again; a stop goes out three times.
        if plain && let Some(p) = &self.twist {
            let _ = p.publish(body);
        }
        if stamped && let Some(p) = &self.stamped {
            let msg = msgs::TwistStamped {
                header: msgs::Header::new(now_stamp(), "base_link"),
                twist: body,
            };
            let _ = p.publish(msg);
        }
    }
}
