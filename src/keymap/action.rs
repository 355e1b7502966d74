//! The one enum through which keys change the console's state, declared once: each
//! action's variant, keymap name, help line and route sit on one row of `actions!`.

use crate::app::fleet_view::FleetAsk;
use crate::data::GripperCommand;
use crate::pilot::Intent;
use crate::pilot::arm::{ArmAxis, ArmPose};
use crate::pilot::mode::Mode;
use crate::pilot::teleop::{DriveKey, SpeedChange};

/// Where an action goes: to the pilot (as a held drive key, a speed change or a
/// request), or to one of the console's own handlers.
#[derive(Clone, Debug, PartialEq)]
pub enum Route {
    /// A drive key: held, it moves the robot.
    Drive(DriveKey),
    /// A speed key.
    Speed(SpeedChange),
    /// A request the pilot takes as it is.
    Pilot(Intent),
    /// Something only the console does: the view, the log, the cursor, the prompt, files.
    Console(Handler),
}

/// The console's own handlers (run by `App::apply_to_console`).
#[derive(Clone, Debug, PartialEq)]
pub enum Handler {
    /// Stop the robot and end the session.
    Quit,
    Help,
    /// Zoom in (`true`) or out.
    Zoom(bool),
    /// Pan the map by one step in (x, y).
    Pan(f64, f64),
    CenterView,
    ToggleBraille,
    ToggleTruth,
    /// Off, all landmarks, gates and blocks only, off.
    CycleLandmarks,
    CycleCamera,
    ToggleScan,
    ToggleTrail,
    ToggleGraph,
    LogOlder,
    LogNewer,
    LogFilter,
    LogSource,
    LogSearch,
    /// Move the goal cursor one cell in (x, y); up and down pick a map in load mode.
    Cursor(f64, f64),
    /// Plan to the cursor; in load mode, load the picked map.
    PlanToCursor,
    PoseEstimate,
    /// Queue the goal cursor as a waypoint.
    AddWaypoint,
    /// A corner of a keepout (false) or speed (true) zone at the cursor.
    ZoneCorner(bool),
    CommandLine,
    SaveMap,
    /// Something for the fleet around the console: select a robot, stop them all.
    Fleet(crate::app::fleet_view::FleetAsk),
    /// Nothing at all.
    Nothing,
}

/// Declares every action once, each row `Variant: name, "help line" => route;`, and
/// generates the enum, `ALL` (in row order, the help overlay's), `name`, `from_name`,
/// `description` and `route`. Routes may use `Route`'s and `Handler`'s variants bare.
macro_rules! actions {
    ($(
        $(#[$attr:meta])*
        $variant:ident: $name:expr, $description:literal => $route:expr;
    )*) => {
        /// Everything a key can ask for. Keymap files name these in snake_case.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Action {
            $($(#[$attr])* $variant,)*
        }

        impl Action {
            const COUNT: usize = [$(stringify!($variant)),*].len();

            /// Every action, in the order the help overlay lists them.
            pub const ALL: [Action; Action::COUNT] = [$(Action::$variant),*];

            /// The name keymap files use.
            pub fn name(self) -> &'static str {
                match self {
                    $(Action::$variant => $name,)*
                }
            }

            /// One line for the help overlay.
            pub fn description(self) -> &'static str {
                match self {
                    $(Action::$variant => $description,)*
                }
            }

            /// Where the action goes.
            pub fn route(self) -> Route {
                use Handler::*;
                use Route::*;
                match self {
                    $(Action::$variant => $route,)*
                }
            }
        }
    };
}

actions! {
    // Modes of seed 001 ("Operating Modes").
    ModeManual: "mode_manual", "manual mode (drive by keys)" => Pilot(Intent::Mode(Mode::Manual));
    ModeExplore: "mode_explore", "exploration mode" => Pilot(Intent::Mode(Mode::Exploration));
    ModeThink: "mode_think", "thinking mode (plan a path)" => Pilot(Intent::Mode(Mode::Thinking));
    ModeFollow: "mode_follow", "path-following mode" => Pilot(Intent::Mode(Mode::PathFollowing));
    ModeRace: "mode_race", "race mode (fast, less SLAM)" => Pilot(Intent::Mode(Mode::Race));
    ModeLoad: "mode_load", "load a saved map" => Pilot(Intent::Mode(Mode::Load));
    ModeGripper: "mode_gripper", "gripper mode: the arm" => Pilot(Intent::Mode(Mode::Gripper));
    ModeLane: "mode_lane", "lane mode (lane, lights)" => Pilot(Intent::Mode(Mode::Lane));
    ModeRoute: "mode_route", "route mode (tag graph)" => Pilot(Intent::Mode(Mode::Route));
    GripperOpen: "gripper_open", "open the gripper" => Pilot(Intent::Gripper(GripperCommand::Open));
    GripperClose: "gripper_close", "close the gripper" => Pilot(Intent::Gripper(GripperCommand::Close));
    Quit: "quit", "stop and quit (also :quit)" => Console(Quit);
    // Driving: held keys move the robot; the deadman stops it when keys stop. Their
    // names are the pilot's own names for the drive keys.
    Forward: DriveKey::Forward.name(), "drive forward" => Drive(DriveKey::Forward);
    Backward: DriveKey::Backward.name(), "drive backward" => Drive(DriveKey::Backward);
    TurnLeft: DriveKey::TurnLeft.name(), "turn left on the spot" => Drive(DriveKey::TurnLeft);
    TurnRight: DriveKey::TurnRight.name(), "turn right on the spot" => Drive(DriveKey::TurnRight);
    ForwardLeft: DriveKey::ForwardLeft.name(), "forward, turning left" => Drive(DriveKey::ForwardLeft);
    ForwardRight: DriveKey::ForwardRight.name(), "forward, turning right" => Drive(DriveKey::ForwardRight);
    BackwardLeft: DriveKey::BackwardLeft.name(), "backward, turning left" => Drive(DriveKey::BackwardLeft);
    BackwardRight: DriveKey::BackwardRight.name(), "backward, turning right" => Drive(DriveKey::BackwardRight);
    Stop: "stop", "stop (autonomy: pause)" => Pilot(Intent::Stop);
    EmergencyStop: "emergency_stop", "emergency stop (any mode)" => Pilot(Intent::EmergencyStop);
    SpeedUp: "speed_up", "all speeds +10 %" => Speed(SpeedChange::SpeedUp);
    SpeedDown: "speed_down", "all speeds -10 %" => Speed(SpeedChange::SpeedDown);
    LinearUp: "linear_up", "linear speed +10 %" => Speed(SpeedChange::LinearUp);
    LinearDown: "linear_down", "linear speed -10 %" => Speed(SpeedChange::LinearDown);
    AngularUp: "angular_up", "turn rate +10 %" => Speed(SpeedChange::AngularUp);
    AngularDown: "angular_down", "turn rate -10 %" => Speed(SpeedChange::AngularDown);
    // The arm, in gripper mode: held keys move the tool.
    ArmForward: "arm_forward", "tool forward" => Pilot(Intent::ArmKey(ArmAxis::Reach, 1.0));
    ArmBack: "arm_back", "tool back" => Pilot(Intent::ArmKey(ArmAxis::Reach, -1.0));
    ArmLeft: "arm_left", "arm left (base joint)" => Pilot(Intent::ArmKey(ArmAxis::Turn, 1.0));
    ArmRight: "arm_right", "arm right (base joint)" => Pilot(Intent::ArmKey(ArmAxis::Turn, -1.0));
    ArmUp: "arm_up", "tool up" => Pilot(Intent::ArmKey(ArmAxis::Lift, 1.0));
    ArmDown: "arm_down", "tool down" => Pilot(Intent::ArmKey(ArmAxis::Lift, -1.0));
    ArmPitchUp: "arm_pitch_up", "tool pitch up" => Pilot(Intent::ArmKey(ArmAxis::Pitch, 1.0));
    ArmPitchDown: "arm_pitch_down", "tool pitch down" => Pilot(Intent::ArmKey(ArmAxis::Pitch, -1.0));
    ArmHome: "arm_home", "arm to home" => Pilot(Intent::ArmPose(ArmPose::Home));
    ArmReady: "arm_ready", "arm ready to pick" => Pilot(Intent::ArmPose(ArmPose::Ready));
    ArmStow: "arm_stow", "arm stowed" => Pilot(Intent::ArmPose(ArmPose::Stow));
    // The view.
    Help: "help", "show or hide this help" => Console(Help);
    ZoomIn: "zoom_in", "zoom in" => Console(Zoom(true));
    ZoomOut: "zoom_out", "zoom out" => Console(Zoom(false));
    PanLeft: "pan_left", "pan the map left" => Console(Pan(-1.0, 0.0));
    PanRight: "pan_right", "pan the map right" => Console(Pan(1.0, 0.0));
    PanUp: "pan_up", "pan the map up" => Console(Pan(0.0, 1.0));
    PanDown: "pan_down", "pan the map down" => Console(Pan(0.0, -1.0));
    CenterView: "center_view", "fit the whole world" => Console(CenterView);
    ToggleBraille: "toggle_braille", "braille / ASCII map" => Console(ToggleBraille);
    ToggleTruth: "toggle_truth", "show/hide the twin's truth" => Console(ToggleTruth);
    ToggleLandmarks: "toggle_landmarks", "landmarks: all/targets/off" => Console(CycleLandmarks);
    ToggleCamera: "toggle_camera", "camera panel, braille, off" => Console(CycleCamera);
    ToggleScan: "toggle_scan", "lidar scan on the map" => Console(ToggleScan);
    ToggleTrail: "toggle_trail", "driven trail on the map" => Console(ToggleTrail);
    ToggleGraph: "toggle_graph", "lidar SLAM's pose graph" => Console(ToggleGraph);
    // The log.
    LogOlder: "log_older", "log: page back" => Console(LogOlder);
    LogNewer: "log_newer", "log: page forward" => Console(LogNewer);
    LogFilter: "log_filter", "log: all, warnings, errors" => Console(LogFilter);
    LogSource: "log_source", "log: all, navdeck, robot" => Console(LogSource);
    LogSearch: "log_search", "log: lines containing …" => Console(LogSearch);
    // Planning and following.
    CursorLeft: "cursor_left", "goal cursor left" => Console(Cursor(-1.0, 0.0));
    CursorRight: "cursor_right", "goal cursor right" => Console(Cursor(1.0, 0.0));
    CursorUp: "cursor_up", "goal cursor up" => Console(Cursor(0.0, 1.0));
    CursorDown: "cursor_down", "goal cursor down" => Console(Cursor(0.0, -1.0));
    CursorLeftFast: "cursor_left_fast", "goal cursor 10 cells left" => Console(Cursor(-10.0, 0.0));
    CursorRightFast: "cursor_right_fast", "goal cursor 10 cells right" => Console(Cursor(10.0, 0.0));
    CursorUpFast: "cursor_up_fast", "goal cursor 10 cells up" => Console(Cursor(0.0, 10.0));
    CursorDownFast: "cursor_down_fast", "goal cursor 10 cells down" => Console(Cursor(0.0, -10.0));
    PlanToCursor: "plan_to_cursor", "plan a path to the cursor" => Console(PlanToCursor);
    /// RViz's "2D Pose Estimate": first press the position, second the heading.
    PoseEstimate: "pose_estimate", "set the pose at the cursor" => Console(PoseEstimate);
    /// Nav2's waypoint mode: the cursor joins the route (`:route start` drives it).
    AddWaypoint: "add_waypoint", "cursor as the next waypoint" => Console(AddWaypoint);
    /// RViz-style drawing: a corner at the cursor, the same key again at the opposite one.
    ZoneKeepout: "zone_keepout", "keepout corner at cursor" => Console(ZoneCorner(false));
    ZoneSpeed: "zone_speed", "speed zone corner at cursor" => Console(ZoneCorner(true));
    CommandLine: "command_line", "command (:goto x y …)" => Console(CommandLine);
    ClearRoute: "clear_route", "forget the planned path" => Pilot(Intent::ClearRoute);
    NextController: "next_controller", "next path controller" => Pilot(Intent::NextController);
    SaveMap: "save_map", "save the map (maps/saved)" => Console(SaveMap);
    UndoMapLoad: "undo_map_load", "undo the last map load" => Pilot(Intent::UndoMapLoad);
    // A fleet: several robots in one console.
    NextRobot: "next_robot", "select the next robot" => Console(Fleet(FleetAsk::Step(1)));
    PreviousRobot: "previous_robot", "select the robot before" => Console(Fleet(FleetAsk::Step(-1)));
    StopAll: "stop_all", "stop every robot (any mode)" => Console(Fleet(FleetAsk::StopAll));
    /// Unbinds a key that a lower layer of the keymap bound.
    Unbound: "none", "(unbound)" => Console(Nothing);
}

impl Action {
    /// Looks an action up by its keymap name.
    pub fn from_name(name: &str) -> Option<Action> {
        Action::ALL.into_iter().find(|a| a.name() == name)
    }

    /// For drive keys: which one.
    pub fn motion(self) -> Option<DriveKey> {
        match self.route() {
            Route::Drive(key) => Some(key),
            _ => None,
        }
    }

    /// The action that holds `key` down: the table's drive routes, read backwards.
    pub fn driving(key: DriveKey) -> Option<Action> {
        Action::ALL.into_iter().find(|a| a.motion() == Some(key))
    }

    /// The help line for this action in `mode`: where a key means something else in a
    /// mode (speed keys jog the arm in gripper mode, the cursor picks a map in load
    /// mode and a task or a tag in route mode), that mode's meaning.
    pub fn description_in(self, mode: Mode) -> &'static str {
        use Action::*;
        match (mode, self) {
            (Mode::Gripper, SpeedUp | LinearUp | AngularUp) => "arm jog speed +10 %",
            (Mode::Gripper, SpeedDown | LinearDown | AngularDown) => "arm jog speed -10 %",
            (Mode::Load, CursorUp) => "choose the map above",
            (Mode::Load, CursorDown) => "choose the map below",
            (Mode::Load, PlanToCursor) => "load the chosen map",
            (Mode::Route, CursorUp) => "choose the route above",
            (Mode::Route, CursorDown) => "choose the route below",
            (Mode::Route, PlanToCursor) => "drive the chosen route",
            _ => self.description(),
        }
    }

    /// The speed change a speed key asks for.
    pub fn speed_change(self) -> Option<SpeedChange> {
        match self.route() {
            Route::Speed(change) => Some(change),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descriptions_fit_a_help_column_at_80_columns() {
        for a in Action::ALL {
            for mode in Mode::ALL {
                let text = a.description_in(mode);
                assert!(text.chars().count() <= 27, "{text:?}");
            }
        }
    }

    #[test]
    fn speed_keys_say_they_jog_the_arm_in_gripper_mode() {
        assert_eq!(Action::SpeedUp.description(), "all speeds +10 %");
        assert_eq!(
            Action::SpeedUp.description_in(Mode::Gripper),
            "arm jog speed +10 %"
        );
        assert_eq!(
            Action::SpeedUp.description_in(Mode::Manual),
            "all speeds +10 %"
        );
    }

    #[test]
    fn every_drive_key_has_one_action_named_as_the_pilot_names_it() {
        let drives: Vec<Action> = Action::ALL
            .into_iter()
            .filter(|a| a.motion().is_some())
            .collect();
        assert_eq!(drives.len(), 8);
        for a in drives {
            let key = a.motion().unwrap();
            assert_eq!(Action::driving(key), Some(a));
            assert_eq!(a.name(), key.name());
        }
    }

    #[test]
    fn names_round_trip_and_are_unique() {
        let mut seen = std::collections::HashSet::new();
        for a in Action::ALL {
            assert_eq!(Action::from_name(a.name()), Some(a));
            assert!(seen.insert(a.name()), "duplicate name {}", a.name());
        }
        assert_eq!(Action::from_name("fly"), None);
    }
}
