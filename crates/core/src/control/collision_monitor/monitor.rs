//! The collision monitor: every zone weighs the command against the obstacle points and
//! the most restrictive acting zone decides (Nav2: "When multiple zones trigger at once,
//! the most aggressive one is used"): a stop before all others, then the slowest result.

use super::config::{ActionType, SafetyConfig};
use super::sources::Obstacles;
use super::verdict::{Acted, Verdict, stale_reason, zone_reason};
use super::zone::{Outcome, Zone};
use crate::geometry::{Point2, Twist};
use std::cmp::Ordering;

/// `[safety]` resolved for one robot: its zones' shapes and the data's age limit.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionMonitor {
    zones: Vec<Zone>,
    source_timeout: f64,
    block_if_invalid: bool,
}

impl CollisionMonitor {
    /// The monitor for a robot whose footprint is a circle of `footprint_radius` (the
    /// `[robot]` section's), which zones without a shape of their own take.
    pub fn new(config: &SafetyConfig, footprint_radius: f64) -> Self {
        Self {
            zones: config
                .polygons
                .iter()
                .map(|p| Zone::new(p, footprint_radius))
                .collect(),
            source_timeout: config.source_timeout,
            block_if_invalid: config.block_if_invalid,
        }
    }

    /// The zones, in config order (to draw them).
    pub fn zones(&self) -> &[Zone] {
        &self.zones
    }

    /// What to send instead of `command`, given the obstacles around the robot.
    pub fn check(&self, command: Twist, obstacles: &Obstacles) -> Verdict {
        if !(command.linear.is_finite() && command.angular.is_finite()) {
            return Verdict {
                command: Twist::ZERO,
                acted: None,
                blocked: true,
                nearest_ahead: None,
                reason: Some("collision monitor: command not a number: motion blocked".into()),
            };
        }
        // Written so that an age that is not a number is too old.
        let fresh = obstacles.age.is_some_and(|age| age <= self.source_timeout);
        if command.is_zero() {
            let nearest = fresh.then(|| nearest_ahead(command, obstacles.points));
            return Verdict::clear(command, nearest.flatten());
        }
        if !fresh {
            let reason = stale_reason(obstacles.age, obstacles.source, self.block_if_invalid);
            return Verdict {
                command: if self.block_if_invalid {
                    Twist::ZERO
                } else {
                    command
                },
                acted: None,
                blocked: self.block_if_invalid,
                nearest_ahead: None,
                reason: Some(reason),
            };
        }
        let points = obstacles.points;
        let nearest = nearest_ahead(command, points);
        let decisive = self
            .zones
            .iter()
            .filter_map(|zone| Some((zone, zone.apply(command, points)?)))
            .min_by(more_restrictive);
        let Some((zone, outcome)) = decisive else {
            return Verdict::clear(command, nearest);
        };
        let acted = Acted {
            polygon: zone.config.name.clone(),
            action: zone.config.action_type,
        };
        Verdict {
            command: outcome.command,
            reason: Some(zone_reason(&acted, command, &outcome, nearest)),
            acted: Some(acted),
            blocked: false,
            nearest_ahead: nearest,
        }
    }
}

/// Which of two zones' outcomes holds back more (it sorts first): a stop, then the
/// slower linear speed, then the slower turn.
fn more_restrictive(a: &(&Zone, Outcome), b: &(&Zone, Outcome)) -> Ordering {
    let not_stop = |zone: &Zone| zone.config.action_type != ActionType::Stop;
    let (x, y) = (a.1.command, b.1.command);
    not_stop(a.0)
        .cmp(&not_stop(b.0))
        .then(x.linear.abs().total_cmp(&y.linear.abs()))
        .then(x.angular.abs().total_cmp(&y.angular.abs()))
}

/// The distance from the robot's centre to the nearest point on the side `command`
/// drives to: ahead (x > 0), or behind when it reverses.
pub fn nearest_ahead(command: Twist, points: &[Point2]) -> Option<f64> {
    let reversing = command.linear < 0.0;
    points
        .iter()
        .filter(|p| if reversing { p.x < 0.0 } else { p.x > 0.0 })
        .map(|p| p.x.hypot(p.y))
        .filter(|d| d.is_finite())
        .min_by(f64::total_cmp)
}
