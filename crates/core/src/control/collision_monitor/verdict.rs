//! What the collision monitor decided about one command, and the line a user reads.

use super::config::ActionType;
use super::sources::SourceKind;
use super::zone::Outcome;
use crate::data::number::fixed;
use crate::geometry::Twist;

/// The zone that changed the command.
#[derive(Clone, Debug, PartialEq)]
pub struct Acted {
    /// The zone's `name`.
    pub polygon: String,
    pub action: ActionType,
}

/// The command to send and why it differs from the one asked, if it does.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// What to send to the robot.
    pub command: Twist,
    /// The zone that changed the command, if one did.
    pub acted: Option<Acted>,
    /// The obstacle data was missing or too old and `block_if_invalid` stopped the robot.
    pub blocked: bool,
    /// The nearest obstacle point on the side the command drives to (ahead, or behind
    /// when reversing), from the robot's centre, metres; `None` with no point there.
    pub nearest_ahead: Option<f64>,
    /// One line for the log, e.g. "collision monitor: slowing to 0.08 m/s, obstacle
    /// 0.42 m ahead in `slowdown`"; `None` when the command went through unchanged.
    pub reason: Option<String>,
}

impl Verdict {
    /// The command sent as asked.
    pub fn clear(command: Twist, nearest_ahead: Option<f64>) -> Self {
        Self {
            command,
            acted: None,
            blocked: false,
            nearest_ahead,
            reason: None,
        }
    }
}

/// "collision monitor: stopping, obstacle 0.14 m ahead in `stop`", and the like for the
/// other zones: what the zone did to `asked`, where the nearest obstacle is.
pub fn zone_reason(
    acted: &Acted,
    asked: Twist,
    outcome: &Outcome,
    nearest_ahead: Option<f64>,
) -> String {
    let sent = outcome.command;
    // The linear speed when one was asked, else the turn.
    let speed = |t: Twist| {
        if asked.linear != 0.0 {
            format!("{} m/s", fixed(t.linear.abs(), 2))
        } else {
            format!("{} rad/s", fixed(t.angular.abs(), 2))
        }
    };
    let stopped = asked.linear != 0.0 && sent.linear == 0.0;
    let doing = match acted.action {
        ActionType::Stop => "stopping".to_string(),
        ActionType::Slowdown => format!("slowing to {}", speed(sent)),
        ActionType::Limit => format!("limiting to {}", speed(sent)),
        ActionType::Approach => {
            // The contact is predicted at the speed asked, not the speed sent.
            let contact = outcome.contact_in.map_or(String::new(), |t| {
                format!(" (contact in {} s at {})", fixed(t, 2), speed(asked))
            });
            if stopped {
                format!("stopping{contact}")
            } else {
                format!("slowing to {}{contact}", speed(sent))
            }
        }
    };
    let side = if asked.linear < 0.0 {
        "behind"
    } else {
        "ahead"
    };
    let obstacle = nearest_ahead.map_or(String::new(), |d| {
        format!(", obstacle {} m {side}", fixed(d, 2))
    });
    format!(
        "collision monitor: {doing}{obstacle} in `{}`",
        acted.polygon
    )
}

/// "collision monitor: no scan for 0.6 s: motion blocked" (or "no scan yet", or "not
/// checked" when `block_if_invalid` is off).
pub fn stale_reason(age: Option<f64>, source: SourceKind, blocked: bool) -> String {
    let missing = source.missing();
    let when = match age {
        Some(a) if a.is_finite() => format!("no {missing} for {} s", fixed(a, 1)),
        _ => format!("no {missing} yet"),
    };
    let what = if blocked {
        "motion blocked"
    } else {
        "not checked"
    };
    format!("collision monitor: {when}: {what}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn acted(name: &str, action: ActionType) -> Acted {
        Acted {
            polygon: name.into(),
            action,
        }
    }

    #[test]
    fn each_zone_says_what_it_did_and_where_the_obstacle_is() {
        let asked = Twist::new(0.16, 0.0);
        let slowed = Outcome {
            command: Twist::new(0.08, 0.0),
            contact_in: None,
        };
        let line = zone_reason(
            &acted("slowdown", ActionType::Slowdown),
            asked,
            &slowed,
            Some(0.42),
        );
        assert_eq!(
            line,
            "collision monitor: slowing to 0.08 m/s, obstacle 0.42 m ahead in `slowdown`"
        );
        let stopped = Outcome {
            command: Twist::ZERO,
            contact_in: None,
        };
        let line = zone_reason(
            &acted("stop", ActionType::Stop),
            asked,
            &stopped,
            Some(0.18),
        );
        assert_eq!(
            line,
            "collision monitor: stopping, obstacle 0.18 m ahead in `stop`"
        );
        let approached = Outcome {
            command: Twist::new(0.05, 0.0),
            contact_in: Some(0.64),
        };
        let reversing = Twist::new(-0.16, 0.0);
        let line = zone_reason(
            &acted("approach", ActionType::Approach),
            reversing,
            &approached,
            None,
        );
        assert_eq!(
            line,
            "collision monitor: slowing to 0.05 m/s (contact in 0.64 s at 0.16 m/s) in `approach`"
        );
    }

    #[test]
    fn missing_data_is_named_with_its_age() {
        assert_eq!(
            stale_reason(Some(0.61), SourceKind::Scan, true),
            "collision monitor: no scan for 0.6 s: motion blocked"
        );
        assert_eq!(
            stale_reason(None, SourceKind::Map, false),
            "collision monitor: no pose on the map yet: not checked"
        );
    }
}
