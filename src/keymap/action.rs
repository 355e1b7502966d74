//! The one enum through which keys change the console's state.

use crate::pilot::teleop::{DriveKey, SpeedChange};

/// Everything a key can ask for. Keymap files name these in snake_case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Action {
    // Modes of seed 001 ("Operating Modes").
    ModeManual,
    ModeExplore,
    ModeThink,
    ModeFollow,
    ModeRace,
    ModeLoad,
    ModeGripper,
    GripperOpen,
    GripperClose,
    Quit,
    // Driving: held keys move the robot; the deadman stops it when keys stop.
    Forward,
    Backward,
    TurnLeft,
    TurnRight,
    ForwardLeft,
    ForwardRight,
    BackwardLeft,
    BackwardRight,
    Stop,
    EmergencyStop,
    SpeedUp,
    SpeedDown,
    LinearUp,
    LinearDown,
    AngularUp,
    AngularDown,
    // The arm, in gripper mode: held keys move the tool.
    ArmForward,
    ArmBack,
    ArmLeft,
    ArmRight,
    ArmUp,
    ArmDown,
    ArmPitchUp,
    ArmPitchDown,
    ArmHome,
    ArmReady,
    ArmStow,
    // The view.
    Help,
    ZoomIn,
    ZoomOut,
    PanLeft,
    PanRight,
    PanUp,
    PanDown,
    CenterView,
    ToggleBraille,
    ToggleTruth,
    ToggleLandmarks,
    ToggleCamera,
    ToggleScan,
    ToggleTrail,
    // The log.
    LogOlder,
    LogNewer,
    LogFilter,
    LogSource,
    LogSearch,
    // Planning and following.
    CursorLeft,
    CursorRight,
    CursorUp,
    CursorDown,
    PlanToCursor,
    /// RViz's "2D Pose Estimate": first press the position, second the heading.
    PoseEstimate,
    CommandLine,
    ClearRoute,
    NextController,
    SaveMap,
    /// Unbinds a key that a lower layer of the keymap bound.
    Unbound,
}

impl Action {
    /// Every action, in the order the help overlay lists them.
    pub const ALL: [Action; 67] = [
        Action::ModeManual,
        Action::ModeExplore,
        Action::ModeThink,
        Action::ModeFollow,
        Action::ModeRace,
        Action::ModeLoad,
        Action::ModeGripper,
        Action::GripperOpen,
        Action::GripperClose,
        Action::Quit,
        Action::Forward,
        Action::Backward,
        Action::TurnLeft,
        Action::TurnRight,
        Action::ForwardLeft,
        Action::ForwardRight,
        Action::BackwardLeft,
        Action::BackwardRight,
        Action::Stop,
        Action::EmergencyStop,
        Action::SpeedUp,
        Action::SpeedDown,
        Action::LinearUp,
        Action::LinearDown,
        Action::AngularUp,
        Action::AngularDown,
        Action::ArmForward,
        Action::ArmBack,
        Action::ArmLeft,
        Action::ArmRight,
        Action::ArmUp,
        Action::ArmDown,
        Action::ArmPitchUp,
        Action::ArmPitchDown,
        Action::ArmHome,
        Action::ArmReady,
        Action::ArmStow,
        Action::Help,
        Action::ZoomIn,
        Action::ZoomOut,
        Action::PanLeft,
        Action::PanRight,
        Action::PanUp,
        Action::PanDown,
        Action::CenterView,
        Action::ToggleBraille,
        Action::ToggleTruth,
        Action::ToggleLandmarks,
        Action::ToggleCamera,
        Action::ToggleScan,
        Action::ToggleTrail,
        Action::LogOlder,
        Action::LogNewer,
        Action::LogFilter,
        Action::LogSource,
        Action::LogSearch,
        Action::CursorLeft,
        Action::CursorRight,
        Action::CursorUp,
        Action::CursorDown,
        Action::PlanToCursor,
        Action::PoseEstimate,
        Action::CommandLine,
        Action::ClearRoute,
        Action::NextController,
        Action::SaveMap,
        Action::Unbound,
    ];

    /// The name keymap files use.
    pub fn name(self) -> &'static str {
        match self {
            Action::ModeManual => "mode_manual",
            Action::ModeExplore => "mode_explore",
            Action::ModeThink => "mode_think",
            Action::ModeFollow => "mode_follow",
            Action::ModeRace => "mode_race",
            Action::ModeLoad => "mode_load",
            Action::ModeGripper => "mode_gripper",
            Action::ArmForward => "arm_forward",
            Action::ArmBack => "arm_back",
            Action::ArmLeft => "arm_left",
            Action::ArmRight => "arm_right",
            Action::ArmUp => "arm_up",
            Action::ArmDown => "arm_down",
            Action::ArmPitchUp => "arm_pitch_up",
            Action::ArmPitchDown => "arm_pitch_down",
            Action::ArmHome => "arm_home",
            Action::ArmReady => "arm_ready",
            Action::ArmStow => "arm_stow",
            Action::GripperOpen => "gripper_open",
            Action::GripperClose => "gripper_close",
            Action::Quit => "quit",
            Action::Forward => "forward",
            Action::Backward => "backward",
            Action::TurnLeft => "turn_left",
            Action::TurnRight => "turn_right",
            Action::ForwardLeft => "forward_left",
            Action::ForwardRight => "forward_right",
            Action::BackwardLeft => "backward_left",
            Action::BackwardRight => "backward_right",
            Action::Stop => "stop",
            Action::EmergencyStop => "emergency_stop",
            Action::SpeedUp => "speed_up",
            Action::SpeedDown => "speed_down",
            Action::LinearUp => "linear_up",
            Action::LinearDown => "linear_down",
            Action::AngularUp => "angular_up",
            Action::AngularDown => "angular_down",
            Action::Help => "help",
            Action::ZoomIn => "zoom_in",
            Action::ZoomOut => "zoom_out",
            Action::PanLeft => "pan_left",
            Action::PanRight => "pan_right",
            Action::PanUp => "pan_up",
            Action::PanDown => "pan_down",
            Action::CenterView => "center_view",
            Action::ToggleBraille => "toggle_braille",
            Action::ToggleTruth => "toggle_truth",
            Action::ToggleLandmarks => "toggle_landmarks",
            Action::ToggleCamera => "toggle_camera",
            Action::ToggleScan => "toggle_scan",
            Action::ToggleTrail => "toggle_trail",
            Action::LogOlder => "log_older",
            Action::LogNewer => "log_newer",
            Action::LogFilter => "log_filter",
            Action::LogSource => "log_source",
            Action::LogSearch => "log_search",
            Action::CursorLeft => "cursor_left",
            Action::CursorRight => "cursor_right",
            Action::CursorUp => "cursor_up",
            Action::CursorDown => "cursor_down",
            Action::PlanToCursor => "plan_to_cursor",
            Action::PoseEstimate => "pose_estimate",
            Action::CommandLine => "command_line",
            Action::ClearRoute => "clear_route",
            Action::NextController => "next_controller",
            Action::SaveMap => "save_map",
            Action::Unbound => "none",
        }
    }

    /// Looks an action up by its keymap name.
    pub fn from_name(name: &str) -> Option<Action> {
        Action::ALL.into_iter().find(|a| a.name() == name)
    }

    /// One line for the help overlay.
    pub fn description(self) -> &'static str {
        match self {
            Action::ModeManual => "manual mode (drive by keys)",
            Action::ModeExplore => "exploration mode",
            Action::ModeThink => "thinking mode (plan a path)",
            Action::ModeFollow => "path-following mode",
            Action::ModeRace => "race mode (fast, less SLAM)",
            Action::ModeLoad => "load a saved map",
            Action::ModeGripper => "gripper mode: the arm",
            Action::ArmForward => "tool forward",
            Action::ArmBack => "tool back",
            Action::ArmLeft => "arm left (base joint)",
            Action::ArmRight => "arm right (base joint)",
            Action::ArmUp => "tool up",
            Action::ArmDown => "tool down",
            Action::ArmPitchUp => "tool pitch up",
            Action::ArmPitchDown => "tool pitch down",
            Action::ArmHome => "arm to home",
            Action::ArmReady => "arm ready to pick",
            Action::ArmStow => "arm stowed",
            Action::GripperOpen => "open the gripper",
            Action::GripperClose => "close the gripper",
            Action::Quit => "stop the robot and quit",
            Action::Forward => "drive forward",
            Action::Backward => "drive backward",
            Action::TurnLeft => "turn left on the spot",
            Action::TurnRight => "turn right on the spot",
            Action::ForwardLeft => "forward, turning left",
            Action::ForwardRight => "forward, turning right",
            Action::BackwardLeft => "backward, turning left",
            Action::BackwardRight => "backward, turning right",
            Action::Stop => "stop (autonomy: pause)",
            Action::EmergencyStop => "emergency stop (any mode)",
            Action::SpeedUp => "all speeds +10 %",
            Action::SpeedDown => "all speeds -10 %",
            Action::LinearUp => "linear speed +10 %",
            Action::LinearDown => "linear speed -10 %",
            Action::AngularUp => "turn rate +10 %",
            Action::AngularDown => "turn rate -10 %",
            Action::Help => "show or hide this help",
            Action::ZoomIn => "zoom in",
            Action::ZoomOut => "zoom out",
            Action::PanLeft => "pan the map left",
            Action::PanRight => "pan the map right",
            Action::PanUp => "pan the map up",
            Action::PanDown => "pan the map down",
            Action::CenterView => "fit the whole world",
            Action::ToggleBraille => "braille / ASCII map",
            Action::ToggleTruth => "show/hide the twin's truth",
            Action::ToggleLandmarks => "landmarks: all/targets/off",
            Action::ToggleCamera => "camera panel, braille, off",
            Action::ToggleScan => "lidar scan on the map",
            Action::ToggleTrail => "driven trail on the map",
            Action::LogOlder => "log: page back",
            Action::LogNewer => "log: page forward",
            Action::LogFilter => "log: all, warnings, errors",
            Action::LogSource => "log: all, navdeck, robot",
            Action::LogSearch => "log: lines containing …",
            Action::CursorLeft => "goal cursor left",
            Action::CursorRight => "goal cursor right",
            Action::CursorUp => "goal cursor up",
            Action::CursorDown => "goal cursor down",
            Action::PlanToCursor => "plan a path to the cursor",
            Action::PoseEstimate => "set the pose at the cursor",
            Action::CommandLine => "command (:goto x y …)",
            Action::ClearRoute => "forget the planned path",
            Action::NextController => "next path controller",
            Action::SaveMap => "save the map (maps/saved)",
            Action::Unbound => "(unbound)",
        }
    }

    /// For drive keys: which one.
    pub fn motion(self) -> Option<DriveKey> {
        match self {
            Action::Forward => Some(DriveKey::Forward),
            Action::Backward => Some(DriveKey::Backward),
            Action::TurnLeft => Some(DriveKey::TurnLeft),
            Action::TurnRight => Some(DriveKey::TurnRight),
            Action::ForwardLeft => Some(DriveKey::ForwardLeft),
            Action::ForwardRight => Some(DriveKey::ForwardRight),
            Action::BackwardLeft => Some(DriveKey::BackwardLeft),
            Action::BackwardRight => Some(DriveKey::BackwardRight),
            _ => None,
        }
    }

    /// The speed change a speed key asks for.
    pub fn speed_change(self) -> Option<SpeedChange> {
        match self {
            Action::SpeedUp => Some(SpeedChange::SpeedUp),
            Action::SpeedDown => Some(SpeedChange::SpeedDown),
            Action::LinearUp => Some(SpeedChange::LinearUp),
            Action::LinearDown => Some(SpeedChange::LinearDown),
            Action::AngularUp => Some(SpeedChange::AngularUp),
            Action::AngularDown => Some(SpeedChange::AngularDown),
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
            assert!(
                a.description().chars().count() <= 27,
                "{:?}",
                a.description()
            );
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
