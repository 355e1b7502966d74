//! What the console is doing, in a form other programs can follow: published by the
//! ROS 2 link on `[ros2] state_topic` as JSON in a std_msgs/String.

use navdeck_pilot::Pilot;
use navdeck_pilot::mode::Mode;
use serde::Serialize;

/// The console's state: its mode, the goal it drives to and how far it has come, and the
/// mission's step while it explores.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MissionState {
    /// The mode's name: manual, exploration, thinking, path_following, race, load, gripper.
    pub mode: String,
    /// Where the planned path leads: x, y (m) and, for a goal pose, the heading (rad).
    pub goal: Option<Goal>,
    /// idle, planned, following, turning (to the goal's heading), arrived.
    pub navigation: &'static str,
    /// Path left to drive while following, metres, to the decimetre (so that the state
    /// changes, and goes out, a few times a second at most).
    pub remaining: Option<f64>,
    /// The exploration mission's step ("scan 40%", "deliver red block 421 …"), or
    /// "paused" out of exploration; None before a mission starts.
    pub mission: Option<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Goal {
    pub x: f64,
    pub y: f64,
    pub theta: Option<f64>,
}

impl MissionState {
    pub fn of(pilot: &Pilot) -> Self {
        let mode = pilot.mode();
        let route = pilot.route();
        let following = mode == Mode::PathFollowing;
        let navigation = match route {
            None => "idle",
            Some(_) if !following => "planned",
            Some(_) if pilot.arrived() => "arrived",
            Some(_) if pilot.follower().is_turning_to_heading() => "turning",
            Some(_) => "following",
        };
        let cm = |v: f64| (v * 100.0).round() / 100.0;
        Self {
            mode: mode.label().to_lowercase().replace(' ', "_"),
            goal: route.map(|r| Goal {
                x: cm(r.goal.x),
                y: cm(r.goal.y),
                theta: r.target.heading(),
            }),
            navigation,
            remaining: pilot
                .following()
                .map(|f| (f.remaining * 10.0).round() / 10.0),
            mission: pilot.mission().map(|m| {
                if mode == Mode::Exploration {
                    m.state_label()
                } else {
                    "paused".to_string()
                }
            }),
        }
    }

    /// The state as the topic carries it: one JSON object.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_reads_as_documented_json() {
        let state = MissionState {
            mode: "path_following".into(),
            goal: Some(Goal {
                x: 1.0,
                y: 0.5,
                theta: Some(1.5),
            }),
            navigation: "following",
            remaining: Some(0.6),
            mission: None,
        };
        assert_eq!(
            state.to_json(),
            r#"{"mode":"path_following","goal":{"x":1.0,"y":0.5,"theta":1.5},"navigation":"following","remaining":0.6,"mission":null}"#
        );
    }
}
