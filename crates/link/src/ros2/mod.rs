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
pub mod cmd_vel;
pub mod config;
pub mod environment;
pub mod graph;
#[cfg(feature = "vision")]
pub mod image;
pub mod inbound;
pub mod initial_pose;
pub mod participant;
mod presence;
pub mod raw;
pub mod rosout;
mod rviz;

#[cfg(not(any(feature = "humble", feature = "jazzy")))]
compile_error!(
    "navdeck's ROS 2 link needs a distribution: the default feature `jazzy`, or `--no-default-features --features humble`"
);

use super::{
    Command, GripperCommand, LinkError, Notice, Picture, RobotLink, SensorFrame, WheelTravel,
};
use crate::rate::RateMeter;
use cmd_vel::CmdVelPolicy;
use config::{CmdVelType, Ros2Config};
use inbound::Refusal;
use navdeck_core::geometry::Pose2;
use navdeck_msgs::{picture, ros as msgs};
use participant::{Factory, Joined, fail, join, qos_profile, take_all, topic_name};
pub use participant::{dds_type, domain_from};
use presence::Presence;
use ros2_client::{Context, Node, NodeName, Publisher, Subscription};
use std::collections::BTreeMap;

/// navdeck's node on the graph, and its name on /rosout (under its namespace).
pub const NODE_NAME: &str = "navdeck";

/// How often discovery is asked which type cmd_vel's subscribers read, seconds: often
/// until one is found, then now and again.
const DISCOVERY_SEARCH: f64 = 0.05;
const DISCOVERY_EVERY: f64 = 1.0;

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

/// What discovery showed of the robot's side: other participants, and the endpoints on
/// the topics navdeck needs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct Discovered {
    participants: usize,
    cmd_vel_readers: usize,
    odom_writers: usize,
    scan_writers: usize,
}

/// What cmd_vel's subscribers were seen to read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Peer {
    Unknown,
    Twist,
    Stamped,
}

pub struct Ros2Link {
    label: String,
    config: Ros2Config,
    track: f64,
    max_wheel_speed: f64,
    context: Context,
    /// Owns the publishers and subscriptions: kept for as long as the link lives.
    _node: Node,
    odom: Subscription<msgs::Odometry>,
    joints: Subscription<msgs::JointState>,
    scan: Subscription<msgs::LaserScan>,
    twist: Option<Publisher<msgs::Twist>>,
    stamped: Option<Publisher<msgs::TwistStamped>>,
    gripper: Publisher<msgs::Float64>,
    /// The arm and its gripper action, when `[ros2] arm` is on.
    arm: Option<arm::Arm>,
    warned_no_arm: bool,
    /// navdeck on the graph: RViz's topics, goals, /rosout, the mission's state.
    presence: Presence,
    cmd_vel_dds: String,
    odom_dds: String,
    scan_dds: String,
    domain: u16,
    /// What discovery last showed of the other participants.
    discovered: Discovered,
    odom_rate: RateMeter,
    scan_rate: RateMeter,
    policy: CmdVelPolicy,
    peer: Peer,
    warned_no_peer: bool,
    next_discovery: f64,
    /// Session time the link was opened, and when odometry last arrived.
    opened_at: Option<f64>,
    odom_at: Option<f64>,
    /// The newest odometry pose and its stamp, for the fallback and the transform.
    odom_pose: Option<(Pose2, f64)>,
    joint_angles: Option<((f64, f64), f64)>,
    travel: WheelTravel,
    elapsed: f64,
    dropped: BTreeMap<&'static str, u64>,
    notices: Vec<Notice>,
}

impl Ros2Link {
    /// Joins the DDS domain and sets up every topic. Nothing is published until the
    /// first command.
    pub fn connect(options: Ros2Options) -> Result<Self, LinkError> {
        let config = options.config;
        let Joined {
            context,
            namespace,
            mut node,
            notes,
        } = join(&config, options.domain, NODE_NAME)?;
        let c = &config;
        let mut f = Factory {
            node: &mut node,
            config: c,
            namespace: &namespace,
        };
        let qos = f.qos();
        let odom = f.subscription(
            "odom_topic",
            &c.odom_topic,
            "nav_msgs",
            "Odometry",
            qos.clone(),
        )?;
        let joints = f.subscription(
            "joint_states_topic",
            &c.joint_states_topic,
            "sensor_msgs",
            "JointState",
            qos.clone(),
        )?;
        let scan = f.subscription(
            "scan_topic",
            &c.scan_topic,
            "sensor_msgs",
            "LaserScan",
            qos_profile(c.scan_qos, false),
        )?;
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
        let dds_name = |field: &str, topic: &str| {
            topic_name(&namespace, field, topic).map(|t| t.to_dds_name("rt", &node_name, ""))
        };
        let cmd_vel_dds = dds_name("cmd_vel_topic", &c.cmd_vel_topic)?;
        let odom_dds = dds_name("odom_topic", &c.odom_topic)?;
        let scan_dds = dds_name("scan_topic", &c.scan_topic)?;
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
            track: options.track,
            max_wheel_speed: options.max_wheel_speed,
            context,
            _node: node,
            odom,
            joints,
            scan,
            twist,
            stamped,
            gripper,
            arm,
            warned_no_arm: false,
            presence,
            cmd_vel_dds,
            odom_dds,
            scan_dds,
            domain: options.domain,
            discovered: Discovered::default(),
            odom_rate: RateMeter::default(),
            scan_rate: RateMeter::default(),
            policy: CmdVelPolicy::default(),
            peer: Peer::Unknown,
            warned_no_peer: false,
            next_discovery: 0.0,
            opened_at: None,
            odom_at: None,
            odom_pose: None,
            joint_angles: None,
            travel: WheelTravel::default(),
            elapsed: 0.0,
            dropped: BTreeMap::new(),
            notices: notes,
            config,
        })
    }

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

    fn take_odometry(&mut self, now: f64) {
        for msg in take_all(&self.odom, "odometry", &mut self.notices) {
            let pose = match inbound::odom_pose(&msg) {
                Ok(p) => p,
                Err(why) => {
                    self.refuse("odometry", why);
                    continue;
                }
            };
            let stamp = inbound::stamp_seconds(&msg.header).unwrap_or(now);
            if self.joint_angles.is_none()
                && let Some((before, at)) = self.odom_pose
            {
                let dt = (stamp - at).max(0.0);
                match inbound::odom_travel(before, pose, self.track, dt, self.max_wheel_speed) {
                    Ok(t) => self.add_travel(t, dt),
                    Err(why) => self.refuse("odometry", why),
                }
            }
            self.odom_pose = Some((pose, stamp));
            self.odom_at = Some(now);
            self.odom_rate.note(now);
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

    fn take_joints(&mut self, now: f64) {
        for msg in take_all(&self.joints, "joint states", &mut self.notices) {
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
            if let Some((before, at)) = self.joint_angles {
                let dt = (stamp - at).max(0.0);
                match inbound::joint_travel(
                    before,
                    angles,
                    self.config.wheel_radius,
                    dt,
                    self.max_wheel_speed,
                ) {
                    Ok(t) => self.add_travel(t, dt),
                    Err(why) => self.refuse("joint_states", why),
                }
            } else {
                self.notices.push(Notice::info(
                    "ROS 2: wheel joints found: wheel travel from joint states",
                ));
            }
            self.joint_angles = Some((angles, stamp));
        }
    }

    fn add_travel(&mut self, t: WheelTravel, dt: f64) {
        self.travel.left += t.left;
        self.travel.right += t.right;
        self.elapsed += dt;
    }

    fn take_scan(&mut self, now: f64) -> Option<crate::LaserScan> {
        let mut newest = None;
        for msg in take_all(&self.scan, "scan", &mut self.notices) {
            self.scan_rate.note(now);
            match inbound::scan(&msg) {
                Ok(s) => newest = Some(s),
                Err(why) => self.refuse("scan", why),
            }
        }
        newest
    }

    /// Asks discovery which type the robot's cmd_vel subscriber reads, and says so.
    fn check_peer(&mut self, now: f64) {
        if now < self.next_discovery {
            return;
        }
        self.next_discovery = now
            + if self.peer == Peer::Unknown {
                DISCOVERY_SEARCH
            } else {
                DISCOVERY_EVERY
            };
        let own = self
            .twist
            .as_ref()
            .map(|p| p.guid().prefix)
            .or_else(|| self.stamped.as_ref().map(|p| p.guid().prefix));
        let participant = self.context.domain_participant();
        let readers = participant.discovered_readers();
        let writers = participant.discovered_writers();
        let mut peers: Vec<_> = readers
            .iter()
            .map(|r| r.reader_proxy.remote_reader_guid.prefix)
            .chain(
                writers
                    .iter()
                    .map(|w| w.writer_proxy.remote_writer_guid.prefix),
            )
            .filter(|p| Some(*p) != own)
            .collect();
        peers.sort();
        peers.dedup();
        let writing = |topic: &str| {
            writers
                .iter()
                .filter(|w| w.publication_topic_data.topic_name == topic)
                .count()
        };
        self.discovered = Discovered {
            participants: peers.len(),
            cmd_vel_readers: readers
                .iter()
                .filter(|r| {
                    r.subscription_topic_data.topic_name == self.cmd_vel_dds
                        && Some(r.reader_proxy.remote_reader_guid.prefix) != own
                })
                .count(),
            odom_writers: writing(&self.odom_dds),
            scan_writers: writing(&self.scan_dds),
        };
        let twist_type = dds_type("geometry_msgs", "Twist");
        let stamped_type = dds_type("geometry_msgs", "TwistStamped");
        let mut seen = Peer::Unknown;
        for r in readers.iter().filter(|r| {
            r.subscription_topic_data.topic_name == self.cmd_vel_dds
                && Some(r.reader_proxy.remote_reader_guid.prefix) != own
        }) {
            let kind = r.subscription_topic_data.type_name();
            if *kind == stamped_type {
                seen = Peer::Stamped;
            } else if *kind == twist_type && seen == Peer::Unknown {
                seen = Peer::Twist;
            }
        }
        if seen == self.peer || seen == Peer::Unknown {
            return;
        }
        self.peer = seen;
        let (found, wrong) = match seen {
            Peer::Stamped => (
                "TwistStamped",
                self.config.cmd_vel_type == CmdVelType::Twist,
            ),
            _ => (
                "Twist",
                self.config.cmd_vel_type == CmdVelType::TwistStamped,
            ),
        };
        self.notices.push(if wrong {
            Notice::warn(format!(
                "ROS 2: the robot's {} subscriber reads {found}, but [ros2] cmd_vel_type = {:?}: it will not move (set cmd_vel_type = \"auto\")",
                self.config.cmd_vel_topic, self.config.cmd_vel_type
            ))
        } else {
            Notice::info(format!(
                "ROS 2: the robot reads {found} on {}",
                self.config.cmd_vel_topic
            ))
        });
    }

    fn publish_twist(&mut self, twist: navdeck_core::geometry::Twist) {
        let body = msgs::Twist::planar(twist.linear, twist.angular);
        // In auto mode nothing goes out before the subscriber's type is known: some DDS
        // implementations match readers by topic name alone and would misread the other type.
        let (plain, stamped) = match (self.config.cmd_vel_type, self.peer) {
            (CmdVelType::Auto, Peer::Twist) => (true, false),
            (CmdVelType::Auto, Peer::Stamped) => (false, true),
            (CmdVelType::Auto, Peer::Unknown) => {
                if !self.warned_no_peer && twist != navdeck_core::geometry::Twist::ZERO {
                    self.warned_no_peer = true;
                    self.notices.push(Notice::warn(format!(
                        "ROS 2: nothing subscribes to {} yet: not moving (set [ros2] cmd_vel_type to publish blind)",
                        self.config.cmd_vel_topic
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
        if self.policy.should_send(command.twist) {
            self.publish_twist(command.twist);
        }
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
        self.check_peer(now);
        let topic = &self.config.odom_topic;
        match self.odom_at {
            None => {
                // Whether anything publishes it tells a wrong domain or topic from QoS.
                let hint = match self.discovered.odom_writers {
                    0 => format!(
                        "nothing publishes it in domain {} ({} other participants)",
                        self.domain, self.discovered.participants
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
        let wheels = (self.elapsed > 0.0 || self.travel != WheelTravel::default())
            .then(|| std::mem::take(&mut self.travel));
        let elapsed = std::mem::take(&mut self.elapsed);
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
        })
    }

    fn details(&self, now: f64) -> Vec<(&'static str, String)> {
        let d = &self.discovered;
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
        let readers = match (d.cmd_vel_readers, self.peer) {
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
                format!("{} {}", c.odom_topic, rate(&self.odom_rate, d.odom_writers)),
            ),
            (
                "Scan",
                format!("{} {}", c.scan_topic, rate(&self.scan_rate, d.scan_writers)),
            ),
            ("cmd_vel", readers),
        ]
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        std::mem::take(&mut self.notices)
    }

    fn stop(&mut self) {
        for _ in 0..cmd_vel::ZERO_REPEATS {
            self.publish_twist(navdeck_core::geometry::Twist::ZERO);
        }
    }

    fn picture_period(&self) -> Option<f64> {
        Some(1.0 / self.config.picture_rate_hz)
    }

    fn show(&mut self, picture: &Picture) {
        let odom = self.odom_pose.map(|(pose, _)| pose);
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
