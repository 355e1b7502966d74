//! `--link ros2`: a TurtleBot3-class robot over ROS 2, spoken natively by the pure-Rust
//! `ros2-client` (no ROS installation needed on navdeck's machine).
//!
//! In: odometry (the watchdog's heartbeat), wheel joints (seed 001's wheel travel, with
//! odometry deltas as the fallback), laser scans, RViz's pose estimates (/initialpose).
//! With `[ros2] arm = true`, also an arm (arm.rs): trajectories out, its joints in, and
//! the gripper through its action instead of a topic.
//! Out: cmd_vel, the gripper, and for RViz the map, plan, landmarks, estimated pose,
//! MCL's particles and the map -> odom transform.

mod arm;
pub mod arm_joints;
pub mod beside;
pub mod camera_info;
pub mod cmd_vel;
mod cmd_vel_out;
pub mod config;
mod discovery;
pub mod environment;
pub mod graph;
#[cfg(feature = "vision")]
pub mod image;
pub mod inbound;
pub mod inbox;
pub mod initial_pose;
pub mod participant;
mod presence;
pub mod raw;
mod readings;
pub mod rosout;
mod rviz;
pub mod tag_topics;

#[cfg(not(any(feature = "humble", feature = "jazzy")))]
compile_error!(
    "navdeck's ROS 2 link needs a distribution: the default feature `jazzy`, or `--no-default-features --features humble`"
);

use super::{Command, GripperCommand, LinkError, Notice, Picture, RobotLink, SensorFrame};
use crate::rate::RateMeter;
use cmd_vel_out::CmdVelOut;
use config::Ros2Config;
use discovery::{Discovery, Peer};
use navdeck_msgs::{picture, ros as msgs};
use participant::{Factory, Joined, fail, join};
pub use participant::{dds_type, domain_from};
use presence::Presence;
use readings::{Inbound, WheelOdometry};
/// A DDS participant in a domain, which the nodes of a fleet's robots share.
pub use ros2_client::Context as Participant;
use ros2_client::{Context, Node, NodeName, Publisher};
use std::collections::BTreeMap;

/// navdeck's node on the graph, and its name on /rosout (under its namespace).
pub const NODE_NAME: &str = "navdeck";

/// Where and how to reach the robot.
#[derive(Clone, Debug)]
pub struct Ros2Options {
    pub config: Ros2Config,
    /// DDS domain (ROS_DOMAIN_ID).
    pub domain: u16,
    /// The robot's wheel track, metres, for the odometry fallback.
    pub track: f64,
    /// Wheel travel faster than this between two messages is refused, m/s
    /// (`RobotConfig::max_wheel_speed`).
    pub max_wheel_speed: f64,
}

pub struct Ros2Link {
    label: String,
    config: Ros2Config,
    domain: u16,
    context: Context,
    /// Owns the publishers and subscriptions: kept for as long as the link lives.
    _node: Node,
    /// Odometry, joint states and scans, and how often they arrive.
    inbound: Inbound,
    wheels: WheelOdometry,
    cmd_vel: CmdVelOut,
    gripper: Publisher<msgs::Float64>,
    /// The arm and its gripper action, when `[ros2] arm` is on.
    arm: Option<arm::Arm>,
    warned_no_arm: bool,
    /// navdeck on the graph: RViz's topics, goals, /rosout, the mission's state.
    presence: Presence,
    /// What discovery shows of the robot's side, and which type cmd_vel's readers read.
    discovery: Discovery,
    /// Session time the link was opened, and when odometry last arrived.
    opened_at: Option<f64>,
    odom_at: Option<f64>,
    dropped: BTreeMap<&'static str, u64>,
    notices: Vec<Notice>,
}

impl Ros2Link {
    /// Joins the DDS domain and sets up every topic. Nothing is published until the
    /// first command.
    pub fn connect(options: Ros2Options) -> Result<Self, LinkError> {
        let joined = join(&options.config, options.domain, NODE_NAME)?;
        Self::on(options, joined)
    }

    /// As `connect`, on `context`: a participant in `options.domain` that other robots
    /// of a fleet share (`participant::participant` makes one).
    pub fn connect_on(options: Ros2Options, context: Context) -> Result<Self, LinkError> {
        let joined = participant::join_on(context, Vec::new(), &options.config, NODE_NAME)?;
        Self::on(options, joined)
    }

    fn on(options: Ros2Options, joined: Joined) -> Result<Self, LinkError> {
        let config = options.config;
        let Joined {
            context,
            namespace,
            mut node,
            notes,
        } = joined;
        let c = &config;
        let mut f = Factory {
            node: &mut node,
            config: c,
            namespace: &namespace,
        };
        let qos = f.qos();
        let inbound = Inbound::open(&mut f, &qos)?;
        let cmd_vel = CmdVelOut::open(&mut f, &qos)?;
        let gripper = f.publisher(
            "gripper_topic",
            &c.gripper_topic,
            "std_msgs",
            "Float64",
            qos.clone(),
        )?;
        let presence = Presence::open(&mut f, rosout::logger_name(&namespace, NODE_NAME))?;
        let node_name = NodeName::new(&namespace, NODE_NAME).expect("checked above");
        let arm = match c.arm {
            true => Some(arm::Arm::open(&mut f, &node_name)?),
            false => None,
        };
        let discovery = Discovery::new(&namespace, &node_name, c)?;
        let label = format!(
            "ros2 d{}{}",
            options.domain,
            if c.namespace.is_empty() {
                String::new()
            } else {
                format!(" {}", c.namespace)
            }
        );
        Ok(Self {
            label,
            domain: options.domain,
            context,
            _node: node,
            inbound,
            wheels: WheelOdometry::new(options.track, options.max_wheel_speed),
            cmd_vel,
            gripper,
            arm,
            warned_no_arm: false,
            presence,
            discovery,
            opened_at: None,
            odom_at: None,
            dropped: BTreeMap::new(),
            notices: notes,
            config,
        })
    }
}

/// The wall clock as a ROS time stamp (the edge of the system may read it).
pub(super) fn now_stamp() -> msgs::Time {
    let t = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs_f64())
        .unwrap_or(0.0);
    msgs::Time::from_seconds(t)
}

impl RobotLink for Ros2Link {
    fn label(&self) -> String {
        let dropped: u64 = self.dropped.values().sum();
        if dropped == 0 {
            self.label.clone()
        } else {
            format!("{} ({dropped} dropped)", self.label)
        }
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.cmd_vel.send(
            command.twist,
            &self.config,
            self.discovery.peer,
            &mut self.notices,
        );
        if let Some(arm) = &mut self.arm {
            arm.send(command.arm, command.gripper, &mut self.notices);
            return Ok(());
        }
        if command.arm.is_some() && !std::mem::replace(&mut self.warned_no_arm, true) {
            self.notices.push(Notice::warn(
                "ROS 2: arm target ignored: no arm configured ([ros2] arm = false)",
            ));
        }
        if let Some(g) = command.gripper {
            let data = match g {
                GripperCommand::Open => self.config.gripper_open,
                GripperCommand::Close => self.config.gripper_closed,
            };
            self.gripper
                .publish(msgs::Float64 { data })
                .map_err(|e| fail("command the gripper", e))?;
        }
        Ok(())
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        let opened = *self.opened_at.get_or_insert(now);
        self.take_joints(now);
        self.take_odometry(now);
        let scan = self.take_scan(now);
        self.presence
            .poll(&self.config, &mut self.notices, &mut self.dropped);
        if let Some(arm) = &mut self.arm {
            arm.poll(now, &self.context, &mut self.notices);
        }
        let own = self.cmd_vel.guid();
        self.discovery
            .check(now, &self.context, own, &self.config, &mut self.notices);
        let topic = &self.config.odom_topic;
        match self.odom_at {
            None => {
                // Whether anything publishes it tells a wrong domain or topic from QoS.
                let hint = match self.discovery.discovered.odom_writers {
                    0 => format!(
                        "nothing publishes it in domain {} ({} other participants)",
                        self.domain, self.discovery.discovered.participants
                    ),
                    n => format!("{n} publisher found, nothing received: check [ros2.qos]"),
                };
                return Err(LinkError::Lost(format!(
                    "waiting for odometry on {topic} ({:.1} s): {hint}",
                    now - opened
                )));
            }
            Some(at) if now - at > self.config.odom_timeout => {
                return Err(LinkError::Lost(format!(
                    "no odometry on {topic} for {:.1} s",
                    now - at
                )));
            }
            Some(_) => {}
        }
        let (wheels, elapsed) = self.wheels.take();
        Ok(SensorFrame {
            stamp: now,
            elapsed,
            wheels,
            sightings: None,
            scan,
            gripper: None,
            camera: None,
            initial_pose: self.presence.take_initial_pose(),
            goal: self.presence.take_goal(),
            arm: self.arm.as_mut().and_then(arm::Arm::take_state),
            lane: None,
            tags: None,
        })
    }

    fn details(&self, now: f64) -> Vec<(&'static str, String)> {
        let d = &self.discovery.discovered;
        let rate = |meter: &RateMeter, writers: usize| match meter.rate(now) {
            Some(hz) => format!("{hz:.1} Hz"),
            None if writers == 0 => "no publisher".to_string(),
            None => format!("silent, {writers} pub"),
        };
        let c = &self.config;
        let plural = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
        let namespace = if c.namespace.is_empty() {
            String::new()
        } else {
            format!(" {}", c.namespace)
        };
        let readers = match (d.cmd_vel_readers, self.discovery.peer) {
            (0, _) => "no subscriber".to_string(),
            (n, Peer::Stamped) => format!("{} (TwistStamped)", plural(n, "reader")),
            (n, Peer::Twist) => format!("{} (Twist)", plural(n, "reader")),
            (n, Peer::Unknown) => plural(n, "reader"),
        };
        vec![
            (
                "DDS",
                format!(
                    "domain {}{namespace} · {}",
                    self.domain,
                    plural(d.participants, "peer")
                ),
            ),
            (
                "Odom",
                format!(
                    "{} {}",
                    c.odom_topic,
                    rate(&self.inbound.odom_rate, d.odom_writers)
                ),
            ),
            (
                "Scan",
                format!(
                    "{} {}",
                    c.scan_topic,
                    rate(&self.inbound.scan_rate, d.scan_writers)
                ),
            ),
            ("cmd_vel", readers),
        ]
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        std::mem::take(&mut self.notices)
    }

    fn stop(&mut self) {
        for _ in 0..cmd_vel::ZERO_REPEATS {
            self.cmd_vel.publish(
                navdeck_core::geometry::Twist::ZERO,
                &self.config,
                self.discovery.peer,
                &mut self.notices,
            );
        }
    }

    fn picture_period(&self) -> Option<f64> {
        Some(1.0 / self.config.picture_rate_hz)
    }

    fn show(&mut self, picture: &Picture) {
        let odom = self.wheels.odom_pose.map(|(pose, _)| pose);
        self.presence.show(picture, odom, &self.config);
    }

    fn takes_log(&self) -> bool {
        true
    }

    fn log(&mut self, lines: &[super::ConsoleLine]) {
        self.presence.log(lines);
    }
}

/// How long a closing link keeps its DDS participant after the last zero cmd_vel, so the
/// participant's own thread sends it before the writer goes (ros2-client offers no wait
/// for acknowledgements). Well inside the console's exit deadline.
pub(super) const STOP_DELIVERY: std::time::Duration = std::time::Duration::from_millis(100);

impl Drop for Ros2Link {
    fn drop(&mut self) {
        self.stop();
        std::thread::sleep(STOP_DELIVERY);
    }
}
