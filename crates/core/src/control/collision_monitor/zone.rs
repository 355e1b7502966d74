//! One zone's verdict on a command: what it lets through when enough points lie in it.
//!
//! A stop or slowdown zone only holds back motion that brings the robot towards the points
//! inside it: a point counts when the robot, driving straight the way `v` says, would
//! sweep its footprint over it (v and p.x of the same sign, and |p.y| within the
//! footprint's radius), so a wall alongside does not stop a robot passing it. Turning in
//! place closes on nothing, since navdeck's footprint is round (`[robot].footprint_radius`),
//! so a robot held at a wall can always turn, and back away. (Nav2's zones hold back any
//! motion; navdeck's rule is its own, for a console driven from the keyboard.)

use super::approach;
use super::config::{ActionType, PolygonConfig};
use super::shape::Shape;
use crate::geometry::{Point2, Twist};

/// A configured zone with its shape resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    pub config: PolygonConfig,
    pub shape: Shape,
    /// Half the width the footprint sweeps driving straight, metres.
    lane: f64,
}

/// What a zone lets through, when it acts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    pub command: Twist,
    /// `approach`: when the unchanged command would bring the shape into contact, s.
    pub contact_in: Option<f64>,
}

impl Zone {
    pub fn new(config: &PolygonConfig, footprint_radius: f64) -> Self {
        Self {
            shape: Shape::of(config, footprint_radius),
            config: config.clone(),
            lane: footprint_radius,
        }
    }

    /// What this zone does to `command` given the obstacle `points` (robot frame), or
    /// `None` when it lets the command through unchanged.
    pub fn apply(&self, command: Twist, points: &[Point2]) -> Option<Outcome> {
        let c = &self.config;
        if !c.enabled {
            return None;
        }
        let min_points = c.min_points as usize;
        let plain = |command: Twist| Outcome {
            command,
            contact_in: None,
        };
        let outcome = match c.action_type {
            ActionType::Stop => (self.in_the_way(command, points) >= min_points)
                .then(|| plain(Twist::new(0.0, command.angular))),
            ActionType::Slowdown => (self.in_the_way(command, points) >= min_points).then(|| {
                plain(Twist::new(
                    command.linear * c.slowdown_ratio,
                    command.angular * c.slowdown_ratio,
                ))
            }),
            ActionType::Limit => (self.inside(points) >= min_points).then(|| {
                plain(Twist::new(
                    cap(command.linear, c.linear_limit),
                    cap(command.angular, c.angular_limit),
                ))
            }),
            ActionType::Approach => {
                approach::predict(&self.shape, c, command, points).map(|p| Outcome {
                    command: Twist::new(command.linear * p.scale, command.angular * p.scale),
                    contact_in: Some(p.contact_in),
                })
            }
        };
        outcome.filter(|o| o.command != command)
    }

    /// Points inside the shape.
    fn inside(&self, points: &[Point2]) -> usize {
        points.iter().filter(|&&p| self.shape.contains(p)).count()
    }

    /// Points inside the shape that the footprint, driving straight the way the
    /// command's linear speed says, would sweep over.
    fn in_the_way(&self, command: Twist, points: &[Point2]) -> usize {
        if command.linear == 0.0 {
            return 0;
        }
        points
            .iter()
            .filter(|&&p| {
                command.linear * p.x > 0.0 && p.y.abs() <= self.lane && self.shape.contains(p)
            })
            .count()
    }
}

/// `value` with its size held to `limit`, its sign kept (Nav2's limit model).
fn cap(value: f64, limit: f64) -> f64 {
    value.clamp(-limit, limit)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall_at(x: f64) -> Vec<Point2> {
        (-10..=10)
            .map(|k| Point2::new(x, k as f64 * 0.01))
            .collect()
    }

    #[test]
    fn a_stop_zone_keeps_the_turn_and_drops_only_the_drive_towards_the_wall() {
        let zone = Zone::new(
            &PolygonConfig::new("stop", ActionType::Stop).circle(0.15),
            0.1,
        );
        let wall = wall_at(0.13);
        let forward_left = Twist::new(0.2, 1.0);
        let out = zone.apply(forward_left, &wall).unwrap();
        assert_eq!(out.command, Twist::new(0.0, 1.0));
        assert_eq!(zone.apply(Twist::new(-0.2, 1.0), &wall), None);
        assert_eq!(zone.apply(Twist::new(0.0, 2.0), &wall), None);
    }

    #[test]
    fn a_wall_alongside_does_not_stop_a_robot_passing_it() {
        let zone = Zone::new(
            &PolygonConfig::new("stop", ActionType::Stop).circle(0.15),
            0.1,
        );
        // A wall 0.13 m to the left, running along the robot's way.
        let alongside: Vec<Point2> = (-10..=10)
            .map(|k| Point2::new(k as f64 * 0.01, 0.13))
            .collect();
        assert_eq!(zone.apply(Twist::new(0.2, 0.0), &alongside), None);
        // A box corner ahead inside the lane still stops it.
        let corner: Vec<Point2> = (0..5)
            .map(|k| Point2::new(0.12, 0.05 + k as f64 * 0.01))
            .collect();
        assert!(zone.apply(Twist::new(0.2, 0.0), &corner).is_some());
    }

    #[test]
    fn a_limit_zone_caps_both_speeds_whichever_way_the_robot_goes() {
        let limit = PolygonConfig {
            linear_limit: 0.1,
            angular_limit: 0.5,
            ..PolygonConfig::new("limit", ActionType::Limit).circle(0.5)
        };
        let zone = Zone::new(&limit, 0.1);
        let wall = wall_at(0.4);
        let out = zone.apply(Twist::new(-0.2, -2.0), &wall).unwrap();
        assert_eq!(out.command, Twist::new(-0.1, -0.5));
        // Already within the limits: nothing to do.
        assert_eq!(zone.apply(Twist::new(0.05, 0.2), &wall), None);
    }

    #[test]
    fn a_disabled_zone_never_acts() {
        let stop = PolygonConfig {
            enabled: false,
            ..PolygonConfig::new("stop", ActionType::Stop).circle(0.15)
        };
        assert_eq!(
            Zone::new(&stop, 0.1).apply(Twist::new(0.2, 0.0), &wall_at(0.1)),
            None
        );
    }
}
