//! Pure pursuit of a look-ahead point on the path (seed 003 `calculate_forward`).

use super::config::PurePursuitConfig;
use super::controller::PathController;
use super::tracking::Progress;
use crate::geometry::{Pose2, Twist};
use crate::plan::trajectory::Trajectory;
use std::f64::consts::FRAC_PI_2;

/// Drives the arc through the point `min_lookahead` ahead along the path.
#[derive(Clone, Debug)]
pub struct PurePursuit {
    config: PurePursuitConfig,
}

impl PurePursuit {
    pub fn new(config: PurePursuitConfig) -> Self {
        Self { config }
    }
}

impl PathController for PurePursuit {
    fn step(
        &mut self,
        pose: Pose2,
        trajectory: &Trajectory,
        progress: &Progress,
        _dt: f64,
    ) -> Twist {
        if trajectory.is_empty() {
            return Twist::ZERO;
        }
        let c = &self.config;
        let v = progress.speed;
        let target = pose.inverse_transform_point(progress.lookahead(trajectory, c.min_lookahead));
        // L_eff = max(distance, 0.4) (seed 003).
        let l_eff = target.x.hypot(target.y).max(c.min_lookahead);
        // alpha: bearing of the look-ahead point in the robot frame (seed 003, for a path).
        let alpha = target.y.atan2(target.x);
        // A look-ahead point behind the robot: sin(alpha) would shrink again and the deadband
        // would read "straight ahead", so rotate towards it in place first (the seed has no
        // such case; Nav2's Regulated Pure Pursuit rotates to heading the same way).
        if alpha.abs() > FRAC_PI_2 {
            return Twist::new(0.0, alpha.signum() * c.max_angular);
        }
        let sin_alpha = alpha.sin();
        // kappa = 2 sin(alpha) / L_eff; omega = v kappa gain (seed 003; Coulter 1992).
        let mut omega = v * 2.0 * sin_alpha / l_eff * c.gain;
        // Deadband on the look-ahead point's lateral offset (seed 003: 0.005 m).
        if target.y.abs() < c.deadband {
            omega = 0.0;
        }
        omega = omega.clamp(-c.max_angular, c.max_angular);
        // distance < 0.3 m: omega scaled by distance / 0.3 (seed 003).
        if progress.goal_distance < c.slow_radius {
            omega *= progress.goal_distance / c.slow_radius;
        }
        Twist::new(v, omega)
    }

    fn reset(&mut self) {}

    fn name(&self) -> &'static str {
        "pure_pursuit"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::test_paths::line;
    use crate::control::tracking::ProgressTracker;
    use std::f64::consts::PI;

    fn command(config: PurePursuitConfig, pose: Pose2) -> Twist {
        let traj = line(2.0);
        let progress = ProgressTracker::default().update(pose, &traj).unwrap();
        PurePursuit::new(config).step(pose, &traj, &progress, 0.1)
    }

    #[test]
    fn on_the_line_it_drives_straight_at_the_profile_speed() {
        let twist = command(PurePursuitConfig::default(), Pose2::new(0.5, 0.002, 0.0));
        assert_eq!(twist, Twist::new(0.2, 0.0), "inside the 5 mm deadband");
    }

    #[test]
    fn off_the_line_it_steers_the_arc_through_the_lookahead_point() {
        // Look-ahead (0.9, 0) seen from (0.5, -0.1): local (0.4, 0.1), l^2 = 0.17,
        // omega = v 2 sin(alpha) / l = 0.2 * 2 * 0.1 / 0.17.
        let twist = command(PurePursuitConfig::default(), Pose2::new(0.5, -0.1, 0.0));
        assert!((twist.angular - 0.04 / 0.17).abs() < 1e-9, "{twist:?}");
    }

    #[test]
    fn seed_clip_and_goal_slowdown_limit_the_turn() {
        let seed = PurePursuitConfig {
            max_angular: 0.3,
            ..PurePursuitConfig::default()
        };
        let twist = command(seed, Pose2::new(0.5, -0.4, 0.0));
        assert_eq!(twist.angular, 0.3);
        // 0.15 m from the goal: half the turn rate of a robot not yet slowing down.
        let pose = Pose2::new(1.85, -0.0, 0.3);
        let far = command(
            PurePursuitConfig {
                slow_radius: 0.01,
                ..PurePursuitConfig::default()
            },
            pose,
        );
        let near = command(PurePursuitConfig::default(), pose);
        assert!(
            (near.angular - far.angular * 0.5).abs() < 1e-9,
            "{near:?} {far:?}"
        );
    }

    #[test]
    fn facing_away_it_rotates_in_place_towards_the_path() {
        // Heading 3.0 rad: the path's direction is 3.0 rad clockwise, 3.28 anticlockwise.
        let twist = command(PurePursuitConfig::default(), Pose2::new(0.5, 0.0, 3.0));
        assert_eq!(twist, Twist::new(0.0, -1.5));
        // Exactly backwards the look-ahead point is inside the deadband, yet it turns.
        let twist = command(PurePursuitConfig::default(), Pose2::new(0.5, 0.0, PI));
        assert_eq!(twist.linear, 0.0);
        assert_eq!(twist.angular.abs(), 1.5);
    }
}
