//! What the user can ask of the pilot, and how each request changes it.

use super::Pilot;
use super::mode::Mode;
use super::navigation::Target;
use super::safety::LinkStatus;
use super::teleop::{DriveKey, SpeedChange};
use navdeck_core::control::config::ControllerKind;
use navdeck_core::data::{GripperCommand, Level};
use navdeck_core::geometry::{Pose2, Twist};
use navdeck_core::map::io::MapFile;

/// A request to the pilot, from a key or a typed command.
#[derive(Clone, Debug, PartialEq)]
pub enum Intent {
    Mode(Mode),
    /// A drive key pressed, or auto-repeated.
    KeyDown {
        key: DriveKey,
        repeat: bool,
    },
    /// A drive key released (only terminals speaking the kitty protocol say so).
    KeyUp(DriveKey),
    /// The terminal reported a key release: releases can be trusted from now on.
    ReleasesReported,
    Gripper(GripperCommand),
    Stop,
    EmergencyStop,
    Speed(SpeedChange),
    /// Plan a path to a point or a landmark.
    Goto(Target),
    Controller(ControllerKind),
    /// The next path controller in turn.
    NextController,
    ClearRoute,
    /// Control back after the link returned.
    Resume,
    /// Drop the mission kept since the last takeover and start a fresh one.
    RestartMission,
    /// Stop for good: the console is ending.
    Halt,
    /// Take a saved map's grid and landmarks; `source` names it in the log.
    AdoptMap {
        map: Box<MapFile>,
        source: String,
    },
    /// Put the planning map and the filter's landmarks back as they were before the last
    /// `AdoptMap`.
    UndoMapLoad,
    /// Place the estimate here (RViz's "2D Pose Estimate", `:pose`, ROS 2 /initialpose).
    SetPose(Pose2),
    /// Start global localisation afresh (`:relocalize`).
    Relocalize,
    /// An arm key pressed or auto-repeated in gripper mode: the axis and its direction.
    ArmKey(super::arm::ArmAxis, f64),
    /// The arm to a named pose.
    ArmPose(super::arm::ArmPose),
    /// The waypoint route: add, start, pause, skip, loop, clear, load.
    Route(super::waypoints::RouteAsk),
    /// Keepout and speed zones: add, delete, clear, or take a map's.
    Zones(super::zones::ZoneAsk),
    /// Route mode (seed 003): drive a tag map's task, or to one tag, from the tag under
    /// the robot.
    TagRoute(super::tag_route::TagGoal),
    /// Switch a behaviour on, or off for a while (None: until switched on).
    Behaviour {
        behaviour: super::behaviours::Behaviour,
        on: bool,
        seconds: Option<f64>,
    },
}

impl Pilot {
    /// Applies `intent`; true when a command is due at once (the robot's motion changed).
    pub(super) fn apply(&mut self, intent: Intent) -> bool {
        match intent {
            Intent::Mode(mode) => self.set_mode(mode),
            Intent::KeyDown { key, repeat } => {
                self.drive_key(key, repeat);
                true
            }
            Intent::KeyUp(key) => {
                self.teleop.set_release_events(true);
                self.teleop.release(key);
                true
            }
            Intent::ReleasesReported => {
                self.teleop.set_release_events(true);
                false
            }
            Intent::Gripper(cmd) => self.gripper_command(cmd),
            Intent::Stop => {
                self.stop_key();
                true
            }
            Intent::EmergencyStop => {
                self.emergency_stop();
                true
            }
            Intent::Speed(change) if self.mode == Mode::Gripper => {
                use super::teleop::SpeedChange;
                let faster = matches!(
                    change,
                    SpeedChange::SpeedUp | SpeedChange::LinearUp | SpeedChange::AngularUp
                );
                self.arm_speed(faster);
                false
            }
            Intent::Speed(change) => {
                if self.teleop.adjust(change) {
                    let (v, w) = (self.teleop.linear_speed, self.teleop.angular_speed);
                    // teleop_twist_keyboard's line after a speed key ("currently: speed
                    // 0.5 turn 1.0"), with units.
                    let text = format!("currently: speed {v:.2} m/s turn {w:.2} rad/s");
                    self.log(Level::Info, text);
                } else {
                    // Routine, not a warning: repeated presses collapse in the log.
                    self.log(Level::Info, "speeds already at their limit");
                }
                false
            }
            Intent::Goto(target) => {
                self.new_goal(target);
                false
            }
            Intent::Controller(kind) => {
                self.set_controller(kind);
                false
            }
            Intent::Behaviour {
                behaviour,
                on,
                seconds,
            } => {
                self.switch_behaviour(behaviour, on, seconds);
                true
            }
            Intent::NextController => {
                let all = ControllerKind::ALL;
                let k = all
                    .iter()
                    .position(|&k| k == self.follower.controller())
                    .unwrap_or(0);
                self.set_controller(all[(k + 1) % all.len()]);
                false
            }
            Intent::ClearRoute => {
                self.drop_route();
                self.log(Level::Info, "path cleared");
                true
            }
            Intent::Resume => {
                self.resume();
                false
            }
            Intent::RestartMission => {
                self.exploring.mission = None;
                if self.mode == Mode::Exploration {
                    self.start_mission();
                    true
                } else {
                    self.set_mode(Mode::Exploration)
                }
            }
            Intent::Halt => {
                self.teleop.clear();
                self.measuring.commanded = Twist::ZERO;
                self.behaviours.gate.halted = true;
                false
            }
            Intent::AdoptMap { map, source } => {
                self.adopt_map(&map, &source);
                self.set_mode(Mode::Manual)
            }
            Intent::UndoMapLoad => {
                self.undo_map_load();
                false
            }
            Intent::SetPose(pose) => {
                self.set_pose(pose);
                false
            }
            Intent::Relocalize => {
                self.relocalize();
                false
            }
            Intent::ArmKey(axis, sign) => {
                self.arm_key(axis, sign);
                true
            }
            Intent::ArmPose(pose) => {
                self.arm_pose(pose);
                true
            }
            Intent::Route(ask) => self.ask_route(ask),
            Intent::TagRoute(goal) => self.go_tag_route(goal),
            Intent::Zones(ask) => {
                self.ask_zones(ask);
                false
            }
        }
    }

    /// Switches mode; true when it changed.
    pub(super) fn set_mode(&mut self, mode: Mode) -> bool {
        if !mode.is_built() {
            self.log(
                Level::Warn,
                format!("{} mode is not built yet", mode.label().to_lowercase()),
            );
            return false;
        }
        if mode == self.mode {
            return false;
        }
        if let (
            Mode::PathFollowing | Mode::Exploration | Mode::Lane | Mode::Route,
            LinkStatus::Lost(reason),
        ) = (mode, &self.behaviours.gate.link)
        {
            // Autonomy needs the robot's odometry to start from.
            let text = format!(
                "{} mode needs the robot to answer first ({reason})",
                mode.label().to_lowercase()
            );
            self.log(Level::Error, text);
            return false;
        }
        if mode == Mode::Gripper && self.hand.arm.is_none() {
            self.log(
                Level::Error,
                "gripper mode needs an arm: add an [arm] section to the config (see README)",
            );
            return false;
        }
        if let (Mode::Lane, Some(why)) = (mode, self.lane_refusal()) {
            let text = format!("lane mode cannot start: {why}");
            self.log(Level::Error, text);
            return false;
        }
        if let (Mode::Route, Some(why)) = (mode, self.route_refusal()) {
            self.log(Level::Error, why);
            return false;
        }
        if mode == Mode::PathFollowing && !self.start_following() {
            return false;
        }
        self.teleop.clear();
        self.set_speed_limits(mode);
        if matches!(self.mode, Mode::PathFollowing | Mode::Exploration) {
            // Leaving an autonomous mode stops it at once.
            self.leave_autonomy();
        }
        if self.mode == Mode::Exploration {
            // The mission's path is its own: it plans afresh when it resumes.
            self.drop_route();
        }
        self.mode = mode;
        self.log(Level::Info, format!("mode {}", mode.label()));
        if mode == Mode::Exploration {
            self.enter_mission();
        }
        if mode == Mode::Lane {
            self.enter_lane(self.now);
        }
        if mode == Mode::Route {
            self.enter_route();
        }
        true
    }

    /// Race mode drives up to the robot's limits; manual stays within teleop's.
    fn set_speed_limits(&mut self, mode: Mode) {
        let (s, r) = (&self.settings, &self.settings.robot);
        if mode == Mode::Race {
            self.teleop.keep_speeds();
            let speeds = (s.race.linear_speed, s.race.angular_speed);
            self.teleop.set_limits(r.max_linear, r.max_angular, speeds);
        } else if self.mode == Mode::Race {
            let (lin, ang) = (
                s.teleop.max_linear.min(r.max_linear),
                s.teleop.max_angular.min(r.max_angular),
            );
            let kept = self.teleop.kept_speeds();
            self.teleop.set_limits(lin, ang, kept);
        }
    }

    fn drive_key(&mut self, key: DriveKey, repeat: bool) {
        if !self.mode.drives_by_keys() {
            // A drive key in an autonomous mode takes control back at once.
            let name = key.name();
            self.log(
                Level::Warn,
                format!(
                    "{name} key: manual control taken back from {} mode",
                    self.mode.label().to_lowercase()
                ),
            );
            // A move the mission started stops with the base.
            self.halt_arm();
            self.set_mode(Mode::Manual);
        }
        if let LinkStatus::Lost(_) = &self.behaviours.gate.link {
            // Nothing can move: say so rather than ignore the key, in one short line (the
            // status panel's Link row says why the link is lost).
            if !repeat {
                let what = key.name().replace('_', " ");
                let text = format!("{what}: nothing moves while the link is lost");
                self.log(Level::Warn, text);
            }
            return;
        }
        if self.behaviours.gate.estop {
            // Leaving an emergency stop is its own deliberate key, never a side effect.
            if !repeat {
                self.log(
                    Level::Warn,
                    "emergency stop is on: press it again (space) to release, then drive",
                );
            }
            return;
        }
        self.teleop.press(key, self.now, repeat);
    }

    /// The stop key, the same in every mode: keys are let go, and an autonomous mode
    /// hands the robot back to manual mode, paused where it stands.
    fn stop_key(&mut self) {
        self.teleop.clear();
        self.halt_arm();
        let again = match self.mode {
            Mode::Exploration => "e resumes the mission",
            Mode::PathFollowing => "p follows the path again",
            Mode::Lane => "k follows the lane again",
            Mode::Route => "i drives the route on",
            _ => {
                self.log(Level::Info, "stop");
                return;
            }
        };
        let from = self.mode.label().to_lowercase();
        self.set_mode(Mode::Manual);
        self.log(
            Level::Info,
            format!("stop: {from} paused, manual control ({again})"),
        );
    }

    /// Queues a gripper command; false when the mission holds the gripper.
    fn gripper_command(&mut self, cmd: GripperCommand) -> bool {
        if self.mode == Mode::PathFollowing && self.is_busy() {
            self.log(
                Level::Warn,
                "gripper key ignored while following a path (x stops, m takes control)",
            );
            return false;
        }
        if self.mode == Mode::Exploration && self.mission().is_some_and(|m| m.holds_gripper()) {
            self.log(
                Level::Warn,
                "gripper key ignored: the mission is using the gripper (x stops, m takes control)",
            );
            return false;
        }
        self.hand.pending = Some(cmd);
        // The ask; the link's "gripper closing", "gripper closed" follow as they happen.
        let verb = match cmd {
            GripperCommand::Open => "open",
            GripperCommand::Close => "close",
        };
        self.log(Level::Info, format!("gripper asked to {verb}"));
        true
    }

    /// The emergency stop key: on, or off again when it is on (the robot stays still).
    fn emergency_stop(&mut self) {
        self.halt_arm();
        if self.behaviours.gate.estop {
            self.behaviours.gate.estop = false;
            self.log(
                Level::Success,
                "emergency stop released: the robot stays still until driven",
            );
            return;
        }
        self.teleop.clear();
        self.behaviours.gate.estop = true;
        if self.mode != Mode::Manual {
            self.set_speed_limits(Mode::Manual);
            self.mode = Mode::Manual;
            self.leave_autonomy();
        }
        self.log(
            Level::Error,
            "EMERGENCY STOP: robot halted; press it again (space) to release",
        );
    }

    /// Stops following and the mission's driving at once: the trajectory and the last
    /// commands of both are dropped.
    pub(super) fn leave_autonomy(&mut self) {
        self.follower.clear_trajectory();
        self.nav.following = None;
        self.nav.last_step = None;
        self.exploring.last_step = None;
    }
}
