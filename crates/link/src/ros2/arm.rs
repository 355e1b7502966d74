//! `[ros2] arm = true`: a four-joint arm and its gripper as TurtleBot3's manipulation
//! bringup runs them (OpenManipulator-X). Targets go out as trajectory_msgs/JointTrajectory
//! to the arm's JointTrajectoryController, gripper orders as goals of the
//! control_msgs/action/GripperCommand action of its GripperActionController, and the
//! arm's positions come back from joint_states.
//!
//! Both the trajectory topic and the goal service are volatile: what is written before
//! the robot's reader is known is lost. So a target or an order waits until discovery
//! has shown that reader, and goes out then.

use super::arm_joints::Refused;
use super::config::{Qos, Reliability, Rmw, Ros2Config};
use super::participant::{Factory, fail, qos_profile, topic_name};
use crate::{LinkError, Notice};
use navdeck_core::data::{ArmState, ArmTarget, GripperCommand};
use navdeck_msgs::ros as msgs;
use ros2_client::action::ActionClientQosPolicies;
use ros2_client::{
    ActionClient, ActionTypeName, Context, NodeName, Publisher, RmwRequestId, ServiceMapping,
};

/// Discovery fills its table a moment before the writer has matched the reader it found:
/// a reader counts as there once it has been seen for this long, seconds.
const SETTLE: f64 = 0.05;
/// How often discovery is asked while something waits, and otherwise (so that a target
/// sent at once finds the readers as they are, give or take this), seconds.
const LOOK_EVERY: f64 = 0.05;
const LOOK_IDLE: f64 = 1.0;
/// A target or order still waiting after this long is worth a warning, seconds.
const WAIT_WARNING: f64 = 2.0;

type GripperClient = ActionClient<
    msgs::GripperCommandGoal,
    msgs::GripperCommandResult,
    msgs::GripperCommandFeedback,
>;

/// A remote reader navdeck writes to: its DDS topic, and since when discovery shows it.
struct Reader {
    dds_topic: String,
    since: Option<f64>,
}

impl Reader {
    fn ready(&self, now: f64) -> bool {
        self.since.is_some_and(|t| now - t >= SETTLE)
    }
}

/// Something waiting for its reader: the item, when it began to wait, whether the wait
/// has been warned about.
struct Waiting<T> {
    item: T,
    since: Option<f64>,
    warned: bool,
}

impl<T> Waiting<T> {
    fn new(item: T) -> Self {
        Self {
            item,
            since: None,
            warned: false,
        }
    }
}

pub(super) struct Arm {
    names: Vec<String>,
    trajectory_topic: String,
    gripper_action: String,
    open_width: f64,
    closed_width: f64,
    max_effort: f64,
    trajectory: Publisher<msgs::JointTrajectory>,
    gripper: GripperClient,
    controller: Reader,
    server: Reader,
    /// Session time of the newest poll, and when discovery is next asked.
    now: f64,
    next_look: f64,
    target: Option<Waiting<ArmTarget>>,
    /// The last target that went out: the same one again is not sent again.
    sent: Option<ArmTarget>,
    order: Option<Waiting<GripperCommand>>,
    /// The newest goal sent, until the server answers whether it took it.
    goal: Option<(RmwRequestId, GripperCommand)>,
    /// The newest good arm reading, until a frame carries it.
    state: Option<ArmState>,
    /// Why the last target was refused: the same reason is not logged again.
    refused: Option<String>,
}

impl Arm {
    /// The arm's trajectory publisher and the gripper's action client, on `f`'s node.
    pub(super) fn open(f: &mut Factory, node_name: &NodeName) -> Result<Self, LinkError> {
        let c: &Ros2Config = f.config;
        let (names, topic, action) = (
            c.arm_joint_names.clone(),
            c.arm_trajectory_topic.clone(),
            c.gripper_action.clone(),
        );
        let reliable = qos_profile(Qos::default(), false);
        let trajectory = f.publisher(
            "arm_trajectory_topic",
            &topic,
            "trajectory_msgs",
            "JointTrajectory",
            reliable.clone(),
        )?;
        let trajectory_name = topic_name(f.namespace, "arm_trajectory_topic", &topic)?;
        let action_name = topic_name(f.namespace, "gripper_action", &action)?;
        // rmw's action QoS: services reliable, volatile, keep-last 10; status latched.
        let status = qos_profile(
            Qos {
                reliability: Reliability::Reliable,
                depth: 1,
            },
            true,
        );
        let policies = ActionClientQosPolicies {
            goal_service: reliable.clone(),
            result_service: reliable.clone(),
            cancel_service: reliable.clone(),
            feedback_subscription: reliable,
            status_subscription: status,
        };
        let mapping = match c.gripper_action_rmw {
            Rmw::FastDds => ServiceMapping::Enhanced,
            Rmw::CycloneDds => ServiceMapping::Cyclone,
        };
        let gripper = f
            .node
            .create_action_client(
                mapping,
                &action_name,
                &ActionTypeName::new("control_msgs", "GripperCommand"),
                policies,
            )
            .map_err(|e| fail(format!("make an action client for {action}"), e))?;
        let reader = |dds_topic: String| Reader {
            dds_topic,
            since: None,
        };
        // ROS 2's names for an action's goal service: <action>/_action/send_goal.
        let goal_dds = format!(
            "{}/_action/send_goalRequest",
            action_name.to_dds_name("rq", node_name, "")
        );
        Ok(Self {
            controller: reader(trajectory_name.to_dds_name("rt", node_name, "")),
            server: reader(goal_dds),
            names,
            trajectory_topic: topic,
            gripper_action: action,
            open_width: c.gripper_open_width,
            closed_width: c.gripper_closed_width,
            max_effort: c.gripper_max_effort,
            trajectory,
            gripper,
            now: 0.0,
            next_look: 0.0,
            target: None,
            sent: None,
            order: None,
            goal: None,
            state: None,
            refused: None,
        })
    }

    /// Takes a command's arm target and gripper order; each goes out now if its reader
    /// is known, else at a later poll.
    pub(super) fn send(
        &mut self,
        target: Option<ArmTarget>,
        order: Option<GripperCommand>,
        notices: &mut Vec<Notice>,
    ) {
        if let Some(t) = target {
            let known = self.target.as_ref().map(|w| w.item).or(self.sent);
            match super::arm_joints::trajectory(&t, &self.names) {
                Ok(_) if known != Some(t) => {
                    self.refused = None;
                    self.target = Some(Waiting::new(t));
                }
                Ok(_) => {}
                Err(why) => {
                    if self.refused.as_ref() != Some(&why) {
                        notices.push(Notice::warn(format!(
                            "ROS 2: arm target not sent on {}: {why}",
                            self.trajectory_topic
                        )));
                    }
                    self.refused = Some(why);
                }
            }
        }
        if let Some(g) = order {
            self.order = Some(Waiting::new(g));
        }
        self.flush(notices);
    }

    /// Reads the arm from one joint_states message; `Err` names the field and value.
    pub(super) fn read(&mut self, msg: &msgs::JointState) -> Result<(), Refused> {
        if let Some(state) = super::arm_joints::arm_state(msg, &self.names)? {
            self.state = Some(state);
        }
        Ok(())
    }

    /// The newest good arm reading, once.
    pub(super) fn take_state(&mut self) -> Option<ArmState> {
        self.state.take()
    }

    /// Sends what waited for its reader and hears whether the gripper took its goal.
    pub(super) fn poll(&mut self, now: f64, context: &Context, notices: &mut Vec<Notice>) {
        self.now = now;
        if now >= self.next_look {
            let waiting = self.target.is_some() || self.order.is_some();
            self.next_look = now + if waiting { LOOK_EVERY } else { LOOK_IDLE };
            let readers = context.domain_participant().discovered_readers();
            for reader in [&mut self.controller, &mut self.server] {
                let seen = readers
                    .iter()
                    .any(|r| r.subscription_topic_data.topic_name == reader.dds_topic);
                reader.since = match (seen, reader.since) {
                    (true, Some(t)) => Some(t),
                    (true, None) => Some(now),
                    (false, _) => None,
                };
            }
        }
        self.flush(notices);
        self.warn_waiting(notices);
        self.hear_goal_response(notices);
    }

    fn flush(&mut self, notices: &mut Vec<Notice>) {
        if self.controller.ready(self.now)
            && let Some(w) = self.target.take()
        {
            // Checked when it came in.
            if let Ok(msg) = super::arm_joints::trajectory(&w.item, &self.names) {
                match self.trajectory.publish(msg) {
                    Ok(()) => self.sent = Some(w.item),
                    Err(e) => notices.push(Notice::warn(format!(
                        "ROS 2: cannot publish the arm target on {}: {e:?}",
                        self.trajectory_topic
                    ))),
                }
            }
        }
        if self.server.ready(self.now)
            && let Some(w) = self.order.take()
        {
            let position = match w.item {
                GripperCommand::Open => self.open_width,
                GripperCommand::Close => self.closed_width,
            };
            let goal = msgs::GripperCommandGoal {
                command: msgs::GripperCommand {
                    position,
                    max_effort: self.max_effort,
                },
            };
            match self.gripper.send_goal(goal) {
                Ok((request, _goal_id)) => self.goal = Some((request, w.item)),
                Err(e) => notices.push(Notice::warn(format!(
                    "ROS 2: cannot send the gripper goal to {}: {e:?}",
                    self.gripper_action
                ))),
            }
        }
    }

    /// One warning per target or order that has waited WAIT_WARNING for its reader.
    fn warn_waiting(&mut self, notices: &mut Vec<Notice>) {
        let now = self.now;
        let mut check = |since: &mut Option<f64>, warned: &mut bool, what: String| {
            let t = *since.get_or_insert(now);
            if !*warned && now - t >= WAIT_WARNING {
                *warned = true;
                notices.push(Notice::warn(what));
            }
        };
        if let Some(w) = &mut self.target {
            check(
                &mut w.since,
                &mut w.warned,
                format!(
                    "ROS 2: nothing reads {} yet: the arm target waits for the arm controller",
                    self.trajectory_topic
                ),
            );
        }
        if let Some(w) = &mut self.order {
            check(
                &mut w.since,
                &mut w.warned,
                format!(
                    "ROS 2: no {} action server yet: the gripper order waits",
                    self.gripper_action
                ),
            );
        }
    }

    fn hear_goal_response(&mut self, notices: &mut Vec<Notice>) {
        let Some((request, order)) = self.goal else {
            return;
        };
        // A reply that cannot be read (another RMW's framing) is as good as none.
        if let Ok(Some(response)) = self.gripper.receive_goal_response(request) {
            self.goal = None;
            if !response.accepted {
                notices.push(Notice::warn(format!(
                    "ROS 2: {} refused the gripper goal ({})",
                    self.gripper_action,
                    match order {
                        GripperCommand::Open => "open",
                        GripperCommand::Close => "close",
                    }
                )));
            }
        }
    }
}
