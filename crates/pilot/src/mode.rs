//! The operating modes of seed 001 ("Operating Modes": m e t p r l), and gripper mode
//! (h) for an arm, lane mode (k) of seed 000 and route mode (i) of seed 003.

/// What the console is doing with the robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Mode {
    Manual,
    Exploration,
    Thinking,
    PathFollowing,
    Race,
    Load,
    /// Jogging an arm's tool by keys (an `[arm]` in the config).
    Gripper,
    /// Following a lane by camera, stopping at lights and barriers (seed 000 §2-§3).
    Lane,
    /// Driving a route through a tag map's graph by its floor tags (seed 003).
    Route,
}

impl Mode {
    pub const ALL: [Mode; 9] = [
        Mode::Manual,
        Mode::Exploration,
        Mode::Thinking,
        Mode::PathFollowing,
        Mode::Race,
        Mode::Load,
        Mode::Gripper,
        Mode::Lane,
        Mode::Route,
    ];

    /// The keymap section that holds this mode's bindings.
    pub fn section(self) -> &'static str {
        match self {
            Mode::Manual => "manual",
            Mode::Exploration => "exploration",
            Mode::Thinking => "thinking",
            Mode::PathFollowing => "path_following",
            Mode::Race => "race",
            Mode::Load => "load",
            Mode::Gripper => "gripper",
            Mode::Lane => "lane",
            Mode::Route => "route",
        }
    }

    pub fn from_section(name: &str) -> Option<Mode> {
        Mode::ALL.into_iter().find(|m| m.section() == name)
    }

    /// Name shown in the status panel.
    pub fn label(self) -> &'static str {
        match self {
            Mode::Manual => "MANUAL",
            Mode::Exploration => "EXPLORATION",
            Mode::Thinking => "THINKING",
            Mode::PathFollowing => "PATH FOLLOWING",
            Mode::Race => "RACE",
            Mode::Load => "LOAD",
            Mode::Gripper => "GRIPPER",
            Mode::Lane => "LANE",
            Mode::Route => "ROUTE",
        }
    }

    /// Whether the keys drive the robot in this mode.
    pub fn drives_by_keys(self) -> bool {
        matches!(self, Mode::Manual | Mode::Race)
    }

    /// Whether this build can run the mode; the others log that they are not built yet.
    pub fn is_built(self) -> bool {
        matches!(
            self,
            Mode::Manual
                | Mode::Race
                | Mode::Thinking
                | Mode::PathFollowing
                | Mode::Exploration
                | Mode::Load
                | Mode::Gripper
                | Mode::Lane
                | Mode::Route
        )
    }
}
