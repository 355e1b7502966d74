//! The pilot's proposals: the safety gate's e-stop, and the task behaviour the mode runs
//! (teleop, race, path following, the mission's exploration or pick-and-place, gripper
//! jogging, lane following, the tag route). The arbiter picks among them each control step.

use super::{Behaviour, Proposal, Response};
use crate::Pilot;
use crate::mode::Mode;
use navdeck_core::data::Level;
use navdeck_core::geometry::Twist;

impl Pilot {
    /// The twist the arbiter sends at `t`; zero whenever control is in doubt.
    pub(crate) fn decide(&mut self, t: f64) -> Twist {
        // The deadman always drops expired keys, even while the command is forced to zero,
        // so its deadline moves on and the console's tick loop always progresses.
        let keys = self.teleop.twist(t, self.brake_margin());
        let mut proposals = Vec::with_capacity(2);
        if !self.behaviours.gate.in_doubt() {
            self.check_sensor_health(t);
        }
        let held = match (self.behaviours.gate.why_in_doubt(), self.health_response()) {
            // A stopped robot's tasks are suppressed, not merely outvoted: the mission
            // and the follower do not step while it stands.
            (Some(why), _) => Some(Proposal::new(Behaviour::EmergencyStop, Twist::ZERO, why)),
            (None, Response::Hold(why)) => {
                Some(Proposal::new(Behaviour::SensorHealth, Twist::ZERO, why))
            }
            (None, response) => {
                if let Some(task) = self.task_proposal(t, keys, &mut proposals) {
                    let mut twist = task.twist;
                    if let Response::Slow(linear, angular) = response
                        && let Some(slow) = Self::slow_proposal(twist, linear, angular)
                    {
                        twist = slow.twist;
                        proposals.push(slow);
                    }
                    // Picking up and putting down a block touches it by design: the
                    // monitor leaves the gripper's lane to it.
                    let handling = task.behaviour == Behaviour::PickAndPlace;
                    let monitor = self.collision_proposal(t, twist, handling);
                    if task.behaviour == Behaviour::TagRoute {
                        // A leg the monitor holds the robot on is blocked (tag_route_drive.rs).
                        let held = monitor
                            .as_ref()
                            .is_some_and(|m| m.twist.linear.abs() < 1e-9);
                        self.note_route_hold(t, twist, held);
                    }
                    proposals.extend(monitor);
                    proposals.extend(self.yield_proposal(&task));
                    proposals.push(task);
                }
                None
            }
        };
        self.note_task_held(t, held.is_some());
        proposals.extend(held);
        let (twist, transition) = self.behaviours.arbiter.arbitrate(t, &proposals);
        // A change between task behaviours follows the mode or the mission, which log
        // themselves: the log gets the changes a safety behaviour makes; `:behaviours`
        // lists them all.
        if let Some(tr) = transition {
            // Before the robot first answers, waiting is expected, not a warning.
            let awaited = !self.behaviours.gate.link_was_up;
            match (tr.from, tr.to) {
                (_, Some(Behaviour::EmergencyStop)) if awaited => {
                    self.log_at(t, Level::Info, tr.text())
                }
                (_, Some(b)) if b.is_safety() => self.log_at(t, Level::Warn, tr.text()),
                (Some(b), _) if b.is_safety() => self.log_at(t, Level::Info, tr.text()),
                _ => {}
            }
        }
        twist
    }

    /// `:behaviour NAME on|off [SECONDS]`: switches a behaviour on, or off for a while.
    pub(crate) fn switch_behaviour(&mut self, b: Behaviour, on: bool, seconds: Option<f64>) {
        let arbiter = &mut self.behaviours.arbiter;
        if on {
            arbiter.switch_on(b);
            return self.log(Level::Info, format!("behaviour {b}: on"));
        }
        match arbiter.switch_off(b, self.now, seconds) {
            Ok(()) => {
                let how_long = seconds.map_or("until switched on".into(), |s| format!("for {s} s"));
                let level = if b.is_safety() {
                    Level::Warn
                } else {
                    Level::Info
                };
                self.log(level, format!("behaviour {b}: off {how_long}"));
            }
            Err(why) => self.log(Level::Warn, format!("behaviour {b}: {why}")),
        }
    }

    /// What the mode's task behaviour asks for at `t` (`keys`: the held drive keys'
    /// twist); none in the modes that do not drive. Lane mode's traffic compliance adds
    /// its hold to `others`.
    fn task_proposal(
        &mut self,
        t: f64,
        keys: Twist,
        others: &mut Vec<Proposal>,
    ) -> Option<Proposal> {
        let proposal = match self.mode {
            Mode::Manual => Proposal::new(Behaviour::Teleop, keys, "driving by keys"),
            Mode::Race => Proposal::new(Behaviour::Race, keys, "racing by keys"),
            Mode::PathFollowing => {
                let twist = self.follow(t);
                Proposal::new(Behaviour::PathFollowing, twist, "following the path")
            }
            Mode::Exploration => {
                let twist = self.explore(t);
                let mission = self.exploring.mission.as_ref();
                let state = mission.map_or(String::new(), |m| m.state_label());
                let behaviour = match mission.is_some_and(|m| m.is_handling_a_block()) {
                    true => Behaviour::PickAndPlace,
                    false => Behaviour::Exploration,
                };
                Proposal::new(behaviour, twist, state)
            }
            // Jogging the arm's tool holds the base still.
            Mode::Gripper => Proposal::new(Behaviour::GripperJog, Twist::ZERO, "jogging the arm"),
            Mode::Lane => {
                let (follow, hold) = self.lane_proposals(t);
                others.extend(hold);
                follow
            }
            Mode::Route => self.tag_route_proposal(t),
            Mode::Thinking | Mode::Load => return None,
        };
        Some(proposal)
    }
}
