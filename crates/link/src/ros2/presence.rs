//! navdeck as a node on the ROS 2 graph, whatever drives the robot: what RViz draws
//! (rviz.rs), RViz's pose estimates and goals in, the console's log on /rosout and the
//! robot's /rosout into the log pane, and the mission's state for other nodes.

use super::config::{Qos, Ros2Config};
use super::inbox::{Inbox, Urgency};
use super::initial_pose::{self, BadPose};
use super::participant::{Factory, qos_profile};
use super::rviz::RvizPublishers;
use super::{msgs, now_stamp, rosout};
use crate::{ConsoleLine, LinkError, Notice, Picture};
use navdeck_core::geometry::Pose2;
use ros2_client::{Publisher, QosProfile};
use std::collections::BTreeMap;

/// Refused poses logged one by one in a poll; the rest are counted.
const POSE_NOTES: usize = 3;
/// /rosout as rcl keeps it: reliable, transient local, the last 1000 lines, each for 10 s.
const ROSOUT_DEPTH: u32 = 1000;
const ROSOUT_LIFESPAN: std::time::Duration = std::time::Duration::from_secs(10);
/// Robot lines taken into the log in one poll at most: a flood cannot bury the console's own.
const ROSOUT_PER_POLL: usize = 50;

pub(super) struct Presence {
    rviz: RvizPublishers,
    initial_pose_sub: Inbox<msgs::PoseWithCovarianceStamped>,
    goal_sub: Inbox<msgs::PoseStamped>,
    rosout_out: Option<Publisher<msgs::Log>>,
    rosout_in: Inbox<msgs::Log>,
    state: Publisher<msgs::StringMsg>,
    /// navdeck's logger name ("tb3.navdeck" in namespace /tb3).
    logger: String,
    /// The newest good pose estimate and goal, until a frame carries them.
    initial_pose: Option<Pose2>,
    goal: Option<Pose2>,
    /// Robot lines left out over a poll's share since the last note.
    skipped_lines: u64,
}

impl Presence {
    /// Sets up every topic on the node `f` makes them on.
    pub(super) fn open(f: &mut Factory<'_>, logger: String) -> Result<Self, LinkError> {
        let c = f.config;
        let qos = f.qos();
        let latched = qos_profile(c.qos, true);
        let rviz = RvizPublishers::open(f, qos.clone(), latched.clone())?;
        // Reliable, volatile, keep-last 10: what RViz's pose and goal tools write.
        let tools = qos_profile(Qos::default(), false);
        let initial_pose_sub = f.inbox(
            "initial_pose_topic",
            &c.initial_pose_topic,
            ("geometry_msgs", "PoseWithCovarianceStamped"),
            tools.clone(),
            Urgency::Wake,
        )?;
        let goal_sub = f.inbox(
            "goal_topic",
            &c.goal_topic,
            ("geometry_msgs", "PoseStamped"),
            tools,
            Urgency::Wake,
        )?;
        let rosout_qos = rosout_qos();
        let rosout_out = match c.rosout {
            true => Some(f.publisher(
                "rosout",
                "/rosout",
                "rcl_interfaces",
                "Log",
                rosout_qos.clone(),
            )?),
            false => None,
        };
        let rosout_in = f.inbox(
            "rosout",
            "/rosout",
            ("rcl_interfaces", "Log"),
            rosout_qos,
            Urgency::Tick,
        )?;
        let state = f.publisher(
            "state_topic",
            &c.state_topic,
            "std_msgs",
            "String",
            qos_profile(Qos { depth: 1, ..c.qos }, true),
        )?;
        Ok(Self {
            rviz,
            initial_pose_sub,
            goal_sub,
            rosout_out,
            rosout_in,
            state,
            logger,
            initial_pose: None,
            goal: None,
            skipped_lines: 0,
        })
    }

    /// Takes what arrived: pose estimates and goals wait for the next frame; refusals and
    /// the robot's /rosout lines go to `notices`.
    pub(super) fn poll(
        &mut self,
        config: &Ros2Config,
        notices: &mut Vec<Notice>,
        dropped: &mut BTreeMap<&'static str, u64>,
    ) {
        let frame = &config.map_frame;
        let topic = &config.initial_pose_topic;
        let estimates = self.initial_pose_sub.take_all(topic, notices);
        let (pose, refused) = initial_pose::newest(&estimates, frame, initial_pose::initial_pose);
        self.initial_pose = pose.or(self.initial_pose);
        refusals(topic, "pose estimate", &refused, notices, dropped);
        let topic = &config.goal_topic;
        let goals = self.goal_sub.take_all(topic, notices);
        let (goal, refused) = initial_pose::newest(&goals, frame, initial_pose::goal_pose);
        self.goal = goal.or(self.goal);
        refusals(topic, "goal", &refused, notices, dropped);
        self.take_rosout(config, notices);
    }

    fn take_rosout(&mut self, config: &Ros2Config, notices: &mut Vec<Notice>) {
        let lowest = config.rosout_level.lowest();
        let mut taken = 0;
        for msg in self.rosout_in.take_all("/rosout", notices) {
            match rosout::wanted(&msg, &self.logger, lowest) {
                Some(note) if taken < ROSOUT_PER_POLL => {
                    taken += 1;
                    notices.push(note);
                }
                Some(_) => self.skipped_lines += 1,
                None => {}
            }
        }
        if taken == ROSOUT_PER_POLL && self.skipped_lines > 0 {
            notices.push(Notice::warn(format!(
                "ROS 2: /rosout: {} more lines from the robot left out of the log",
                std::mem::take(&mut self.skipped_lines)
            )));
        }
    }

    pub(super) fn take_initial_pose(&mut self) -> Option<Pose2> {
        self.initial_pose.take()
    }

    pub(super) fn take_goal(&mut self) -> Option<Pose2> {
        self.goal.take()
    }

    /// What RViz draws, and the mission's state when it changed.
    pub(super) fn show(&self, picture: &Picture, odom: Option<Pose2>, config: &Ros2Config) {
        self.rviz.show(picture, odom, config);
        if let Some(state) = &picture.state {
            let _ = self.state.publish(msgs::StringMsg {
                data: state.clone(),
            });
        }
    }

    /// The console's own lines out on /rosout (the robot's came from there already).
    pub(super) fn log(&self, lines: &[ConsoleLine]) {
        let Some(out) = &self.rosout_out else {
            return;
        };
        for line in lines.iter().filter(|l| l.source.is_none()) {
            let msg = rosout::log_message(now_stamp(), line.level, &self.logger, &line.text);
            let _ = out.publish(msg);
        }
    }
}

/// /rosout's QoS as rcl sets it.
fn rosout_qos() -> QosProfile {
    qos_profile(
        Qos {
            depth: ROSOUT_DEPTH,
            ..Qos::default()
        },
        true,
    )
    .lifespan(Some(ROSOUT_LIFESPAN))
}

/// Each refused pose is logged with what was wrong (a few a poll, then a count).
fn refusals(
    topic: &str,
    what: &str,
    refused: &[BadPose],
    notices: &mut Vec<Notice>,
    dropped: &mut BTreeMap<&'static str, u64>,
) {
    if refused.is_empty() {
        return;
    }
    *dropped.entry("bad pose").or_insert(0) += refused.len() as u64;
    for why in refused.iter().take(POSE_NOTES) {
        notices.push(Notice::warn(format!(
            "ROS 2: ignored a {what} on {topic}: {why}"
        )));
    }
    if refused.len() > POSE_NOTES {
        notices.push(Notice::warn(format!(
            "ROS 2: ignored {} more on {topic}",
            refused.len() - POSE_NOTES
        )));
    }
}
