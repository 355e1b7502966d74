//! Waypoint following with a heading PID (seed 001 section 6).

use super::config::PidFollowConfig;
use super::controller::{Limits, PathController};
use super::pid::{Pid, PidGains};
use super::tracking::{Progress, sample_at};
use crate::geometry::{Point2, Pose2, Twist, wrap_angle};
use crate::plan::trajectory::Trajectory;

/// Steers at the next waypoint, stops to turn when it lies far off the nose.
#[derive(Clone, Debug)]
pub struct PidFollower {
    config: PidFollowConfig,
    limits: Limits,
    pid: Pid,
    /// The trajectory decimated every `waypoint_spacing`, with each waypoint's arc length.
    waypoints: Vec<(Point2, f64)>,
    next: usize,
}

impl PidFollower {
    pub fn new(config: PidFollowConfig, limits: Limits) -> Self {
        let pid = Pid::new(PidGains {
            kp: config.kp,
            ki: config.ki,
            kd: config.kd,
            integral_limit: config.integral_limit,
            output_limit: limits.max_angular,
        });
        Self {
            config,
            limits,
            pid,
            waypoints: Vec::new(),
            next: 0,
        }
    }

    /// The waypoint being steered at, once the first step has decimated the path.
    pub fn target(&self) -> Option<Point2> {
        self.waypoints.get(self.next).map(|w| w.0)
    }

    fn decimate(&mut self, trajectory: &Trajectory) {
        let length = trajectory.length();
        let spacing = self.config.waypoint_spacing;
        let count = (length / spacing).ceil().max(1.0) as usize;
        self.waypoints = (1..=count)
            .map(|k| {
                let s = (k as f64 * spacing).min(length);
                (sample_at(trajectory, s).position, s)
            })
            .collect();
        self.next = 0;
    }
}

impl PathController for PidFollower {
    fn step(
        &mut self,
        pose: Pose2,
        trajectory: &Trajectory,
        progress: &Progress,
        dt: f64,
    ) -> Twist {
        if trajectory.is_empty() {
            return Twist::ZERO;
        }
        if self.waypoints.is_empty() {
            self.decimate(trajectory);
        }
        let robot = pose.position();
        // Follow waypoints in sequence, dropping one within 5 cm (seed 001 section 6) or once
        // the robot's projection has passed it; the goal itself is never dropped here.
        while self.next + 1 < self.waypoints.len() {
            let (w, s) = self.waypoints[self.next];
            if robot.distance(w) < self.config.waypoint_radius || s <= progress.s {
                self.next += 1;
            } else {
                break;
            }
        }
        let (target, _) = self.waypoints[self.next];
        let distance = robot.distance(target);
        // Desired heading atan2(wy - y, wx - x), error wrapped (seed 001 section 6).
        let error = wrap_angle((target.y - pose.y).atan2(target.x - pose.x) - pose.theta);
        let turn = self.pid.update(error, dt);
        // speed = 5 + 10 min(d, 1) of 15 motor units (seed 001 section 6), capped by the profile.
        let scaled = self.limits.max_linear * (5.0 + 10.0 * distance.min(1.0)) / 15.0;
        let mut speed = progress.speed.min(scaled);
        // if |turn| > 60 deg: speed = 0, stop and turn (seed 001 section 6, on the error).
        if error.abs() > self.config.stop_turn_deg.to_radians() {
            speed = 0.0;
        }
        Twist::new(speed, turn)
    }

    fn reset(&mut self) {
        self.pid.reset();
        self.waypoints.clear();
        self.next = 0;
    }

    fn name(&self) -> &'static str {
        "pid"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::test_paths::line;
    use crate::control::tracking::ProgressTracker;

    fn follower() -> PidFollower {
        let limits = Limits {
            max_linear: 0.4,
            max_angular: 4.0,
        };
        PidFollower::new(PidFollowConfig::default(), limits)
    }

    fn step(pid: &mut PidFollower, pose: Pose2) -> Twist {
        let traj = line(2.0);
        let progress = ProgressTracker::default().update(pose, &traj).unwrap();
        pid.step(pose, &traj, &progress, 0.1)
    }

    #[test]
    fn speed_scales_with_the_distance_to_the_waypoint() {
        let mut pid = follower();
        let twist = step(&mut pid, Pose2::new(0.0, 0.0, 0.0));
        assert_eq!(pid.target(), Some(Point2::new(0.1, 0.0)));
        // 0.4 m/s * (5 + 10 * 0.1) / 15 = 0.16 m/s, under the profile's 0.2.
        assert!((twist.linear - 0.16).abs() < 1e-12);
        assert_eq!(twist.angular, 0.0);
    }

    #[test]
    fn waypoint_within_five_centimetres_is_dropped() {
        let mut pid = follower();
        step(&mut pid, Pose2::new(0.0, -0.04, 0.0));
        assert_eq!(pid.target(), Some(Point2::new(0.1, 0.0)));
        step(&mut pid, Pose2::new(0.06, 0.0, 0.0));
        assert_eq!(pid.target(), Some(Point2::new(0.2, 0.0)));
    }

    #[test]
    fn stops_to_turn_above_sixty_degrees() {
        let mut pid = follower();
        let turning = step(&mut pid, Pose2::new(0.0, 0.0, 61.0_f64.to_radians()));
        assert_eq!(turning.linear, 0.0);
        assert!(turning.angular < 0.0);
        let mut pid = follower();
        let driving = step(&mut pid, Pose2::new(0.0, 0.0, 59.0_f64.to_radians()));
        assert!(driving.linear > 0.1 && driving.angular < 0.0);
    }

    #[test]
    fn reset_forgets_the_waypoints() {
        let mut pid = follower();
        step(&mut pid, Pose2::default());
        pid.reset();
        assert_eq!(pid.target(), None);
    }
}
