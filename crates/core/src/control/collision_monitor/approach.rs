//! The approach model: drive the shape forward in time along the command and find when
//! obstacle points would first lie inside it; if that is sooner than
//! `time_before_collision`, scale the command so the contact stays that far away (Nav2's
//! approach model: "the robot will slow such that it is now at least
//! time_before_collision seconds to collision").

use super::config::PolygonConfig;
use super::shape::Shape;
use crate::geometry::{Point2, Pose2, Twist};

/// A contact predicted within the zone's horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    /// The first simulated time with `min_points` points inside the shape, s.
    pub contact_in: f64,
    /// The share of the command to keep, 0..1: the last contact-free time over
    /// `time_before_collision`, so at the scaled speed the contact is that far off.
    pub scale: f64,
}

/// When `command`, held, brings `min_points` of `points` (robot frame) inside `shape`
/// within the zone's `time_before_collision`, checked every `simulation_time_step`.
/// Points already inside are not counted: they are for a stop zone to judge, and a
/// robot in contact must still be able to drive away from them.
pub fn predict(
    shape: &Shape,
    zone: &PolygonConfig,
    command: Twist,
    points: &[Point2],
) -> Option<Prediction> {
    if command.is_zero() {
        return None;
    }
    let (horizon, step) = (zone.time_before_collision, zone.simulation_time_step);
    let min_points = zone.min_points as usize;
    // A point farther than the shape's reach plus the distance driven cannot be met.
    let reach = shape.reach() + command.linear.abs() * horizon;
    let candidates: Vec<Point2> = points
        .iter()
        .copied()
        .filter(|p| p.x * p.x + p.y * p.y <= reach * reach && !shape.contains(*p))
        .collect();
    if candidates.len() < min_points {
        return None;
    }
    let steps = (horizon / step).ceil() as usize;
    (1..=steps).find_map(|k| {
        let t = (k as f64 * step).min(horizon);
        let robot = pose_after(command, t);
        let mut met = 0;
        let contact = candidates.iter().any(|&p| {
            met += usize::from(shape.contains(robot.inverse_transform_point(p)));
            met >= min_points
        });
        contact.then(|| Prediction {
            contact_in: t,
            scale: ((k - 1) as f64 * step / horizon).clamp(0.0, 1.0),
        })
    })
}

/// The robot's pose after holding `command` for `t` seconds from the origin: a straight
/// line, or an arc of radius v / w (the unicycle's exact motion; Thrun, Burgard and Fox,
/// Probabilistic Robotics, eq. 5.9).
pub fn pose_after(command: Twist, t: f64) -> Pose2 {
    let (v, w) = (command.linear, command.angular);
    let theta = w * t;
    if w.abs() < 1e-9 {
        return Pose2::new(v * t, 0.0, theta);
    }
    let r = v / w;
    Pose2::new(r * theta.sin(), r * (1.0 - theta.cos()), theta)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::collision_monitor::config::ActionType;

    #[test]
    fn a_quarter_turn_arc_ends_a_radius_ahead_and_a_radius_aside() {
        let p = pose_after(Twist::new(0.2, 0.5), std::f64::consts::PI);
        // Radius 0.4 m; a quarter turn (0.5 rad/s for pi s) ends at (0.4, 0.4), facing left.
        assert!(
            (p.x - 0.4).abs() < 1e-12 && (p.y - 0.4).abs() < 1e-12,
            "{p:?}"
        );
        assert!((p.theta - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn a_wall_one_second_off_at_full_speed_halves_the_command_under_two_seconds() {
        let zone = PolygonConfig {
            simulation_time_step: 0.01,
            ..PolygonConfig::new("approach", ActionType::Approach)
        };
        let footprint = Shape::of(&zone, 0.1);
        // A wall 0.3 m ahead of the centre: 0.2 m from the footprint, 1 s at 0.2 m/s.
        let wall: Vec<Point2> = (-10..=10)
            .map(|k| Point2::new(0.3, k as f64 * 0.005))
            .collect();
        let p = predict(&footprint, &zone, Twist::new(0.2, 0.0), &wall).unwrap();
        assert!((p.contact_in - 1.0).abs() <= 0.01 + 1e-9, "{p:?}");
        assert!((p.scale - 0.5).abs() <= 0.01, "{p:?}");
        // Reversing, or turning in place, meets nothing.
        assert_eq!(
            predict(&footprint, &zone, Twist::new(-0.2, 0.0), &wall),
            None
        );
        assert_eq!(
            predict(&footprint, &zone, Twist::new(0.0, 1.0), &wall),
            None
        );
        // Three seconds off: beyond the horizon.
        assert_eq!(
            predict(&footprint, &zone, Twist::new(0.2 / 3.0, 0.0), &wall),
            None
        );
    }
}
