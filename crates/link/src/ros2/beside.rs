//! `--ros2` beside a robot that is not on ROS 2 (the twin, a serial robot): navdeck joins
//! the graph as a node of its own, so RViz draws what it believes, RViz's tools place
//! the estimate and give goals, /rosout carries its log both ways, and other nodes can
//! follow its state. The robot itself is still driven by the link it wraps.

use super::config::Ros2Config;
use super::participant::{Factory, Joined, join};
use super::presence::Presence;
use super::rosout;
use crate::{Command, ConsoleLine, LinkError, Notice, Picture, RobotLink, SensorFrame};
use navdeck_core::geometry::Pose2;
use ros2_client::{Context, Node};
use std::collections::BTreeMap;

pub struct Ros2Beside {
    inner: Box<dyn RobotLink>,
    config: Ros2Config,
    domain: u16,
    presence: Presence,
    /// Owns the publishers and subscriptions: kept for as long as the link lives.
    _node: Node,
    _context: Context,
    dropped: BTreeMap<&'static str, u64>,
    notices: Vec<Notice>,
}

impl Ros2Beside {
    /// Joins `domain` as node `navdeck` in the configured namespace, beside `inner`.
    pub fn join(
        inner: Box<dyn RobotLink>,
        config: Ros2Config,
        domain: u16,
    ) -> Result<Self, LinkError> {
        let Joined {
            context,
            namespace,
            mut node,
            mut notes,
        } = join(&config, domain, super::NODE_NAME)?;
        let logger = rosout::logger_name(&namespace, super::NODE_NAME);
        let presence = Presence::open(
            &mut Factory {
                node: &mut node,
                config: &config,
                namespace: &namespace,
            },
            logger,
        )?;
        notes.push(Notice::info(format!(
            "ROS 2: on domain {domain} beside {}: goals on {}, pose estimates on {}",
            inner.label(),
            config.goal_topic,
            config.initial_pose_topic
        )));
        Ok(Self {
            inner,
            config,
            domain,
            presence,
            _node: node,
            _context: context,
            dropped: BTreeMap::new(),
            notices: notes,
        })
    }
}

impl RobotLink for Ros2Beside {
    fn label(&self) -> String {
        format!("{} + ros2 d{}", self.inner.label(), self.domain)
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.inner.send(command)
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        self.presence
            .poll(&self.config, &mut self.notices, &mut self.dropped);
        let mut frame = self.inner.poll(now)?;
        // A pose or goal from RViz waits for a frame that carries it.
        if frame.initial_pose.is_none() {
            frame.initial_pose = self.presence.take_initial_pose();
        }
        if frame.goal.is_none() {
            frame.goal = self.presence.take_goal();
        }
        Ok(frame)
    }

    fn stop(&mut self) {
        self.inner.stop();
    }

    fn picture_period(&self) -> Option<f64> {
        Some(1.0 / self.config.picture_rate_hz)
    }

    fn show(&mut self, picture: &Picture) {
        self.inner.show(picture);
        self.presence.show(picture, None::<Pose2>, &self.config);
    }

    fn teleport(&mut self, pose: Pose2) -> bool {
        self.inner.teleport(pose)
    }

    fn ground_truth(&self) -> Option<&dyn navdeck_core::sim::GroundTruth> {
        self.inner.ground_truth()
    }

    fn faults(&self) -> Option<&navdeck_core::sim::Faults> {
        self.inner.faults()
    }

    fn faults_mut(&mut self) -> Option<&mut navdeck_core::sim::Faults> {
        self.inner.faults_mut()
    }

    fn details(&self, now: f64) -> Vec<(&'static str, String)> {
        let mut rows = self.inner.details(now);
        rows.push(("ROS 2", format!("domain {}", self.domain)));
        rows
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        let mut notes = self.inner.take_notes();
        notes.append(&mut self.notices);
        notes
    }

    fn takes_log(&self) -> bool {
        true
    }

    fn log(&mut self, lines: &[ConsoleLine]) {
        self.inner.log(lines);
        self.presence.log(lines);
    }
}

impl Drop for Ros2Beside {
    fn drop(&mut self) {
        // The last log lines and state go out on the participant's own thread.
        std::thread::sleep(super::STOP_DELIVERY);
    }
}
