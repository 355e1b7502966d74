//! Where the robot is along a trajectory: projection, cross-track error, what is left.

use crate::geometry::{Point2, Pose2, wrap_angle};
use crate::plan::trajectory::{Trajectory, TrajectoryPoint};

/// The robot's progress along a trajectory, measured at its projection on the polyline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// The projection lies on the segment from point `index` to point `index + 1`.
    pub index: usize,
    /// Arc length at the projection, metres.
    pub s: f64,
    pub projection: Point2,
    /// Path heading at the projection, radians.
    pub heading: f64,
    /// Distance from the robot to the path, metres: positive when the path lies to the left
    /// of the robot as seen travelling along the path (the robot is right of it).
    pub cross_track: f64,
    /// Arc length left to the goal, metres.
    pub remaining: f64,
    /// Planned time left from the projection to the goal (the profile's `t`), seconds.
    pub eta: f64,
    /// Signed curvature at the projection, 1/m.
    pub curvature: f64,
    /// Reference speed at the projection, m/s.
    pub speed: f64,
    /// Straight-line distance from the robot to the goal, metres.
    pub goal_distance: f64,
}

impl Progress {
    /// The path point `distance` metres of arc ahead of the projection (the goal if past it).
    pub fn lookahead(&self, trajectory: &Trajectory, distance: f64) -> Point2 {
        sample_at(trajectory, self.s + distance).position
    }
}

/// The trajectory sample at arc length `s`, interpolated linearly; clamped to the ends.
/// Panics on an empty trajectory.
pub fn sample_at(trajectory: &Trajectory, s: f64) -> TrajectoryPoint {
    let pts = &trajectory.points;
    let i = pts.partition_point(|p| p.s <= s);
    if i == 0 {
        return pts[0];
    }
    if i == pts.len() {
        return pts[pts.len() - 1];
    }
    let (a, b) = (pts[i - 1], pts[i]);
    let ds = b.s - a.s;
    let u = if ds > 0.0 { (s - a.s) / ds } else { 0.0 };
    lerp(a, b, u)
}

fn lerp(a: TrajectoryPoint, b: TrajectoryPoint, u: f64) -> TrajectoryPoint {
    let mix = |x: f64, y: f64| x + (y - x) * u;
    TrajectoryPoint {
        position: Point2::new(
            mix(a.position.x, b.position.x),
            mix(a.position.y, b.position.y),
        ),
        heading: wrap_angle(a.heading + wrap_angle(b.heading - a.heading) * u),
        curvature: mix(a.curvature, b.curvature),
        s: mix(a.s, b.s),
        v: mix(a.v, b.v),
        t: mix(a.t, b.t),
    }
}

/// Finds the projection in a window ahead of the last one, so progress never runs backwards
/// and a path that crosses itself is followed in order. The first update after a reset
/// searches the whole path (the earliest of equally near points wins).
#[derive(Clone, Debug, PartialEq)]
pub struct ProgressTracker {
    index: usize,
    window: f64,
    fresh: bool,
}

impl Default for ProgressTracker {
    fn default() -> Self {
        Self::new(Self::WINDOW)
    }
}

impl ProgressTracker {
    /// Arc length searched ahead of the last projection, metres: a robot at 0.4 m/s covers
    /// 4 cm per 0.1 s step, so this leaves room for long steps and stalls alike.
    pub const WINDOW: f64 = 1.0;

    pub fn new(window: f64) -> Self {
        Self {
            index: 0,
            window,
            fresh: true,
        }
    }

    /// Starts again from the beginning of the path.
    pub fn reset(&mut self) {
        self.index = 0;
        self.fresh = true;
    }

    /// The progress of a robot at `pose`; `None` for an empty trajectory.
    pub fn update(&mut self, pose: Pose2, trajectory: &Trajectory) -> Option<Progress> {
        let pts = &trajectory.points;
        let last = pts.last()?;
        let robot = pose.position();
        if pts.len() == 1 {
            return Some(progress_at(trajectory, 0, *last, robot, 0.0));
        }
        let start = self.index.min(pts.len() - 2);
        let horizon = if self.fresh {
            f64::INFINITY
        } else {
            pts[start].s + self.window
        };
        self.fresh = false;
        let mut best = (f64::INFINITY, start, 0.0);
        for i in start..pts.len() - 1 {
            if i > start + 1 && pts[i].s > horizon {
                break;
            }
            let (distance, u) = project(pts[i].position, pts[i + 1].position, robot);
            if distance < best.0 {
                best = (distance, i, u);
            }
        }
        let (_, i, u) = best;
        self.index = i;
        let (a, b) = (pts[i], pts[i + 1]);
        let sample = lerp(a, b, u);
        // Signed offset: the robot-to-path vector against the segment's left normal.
        let (dx, dy) = (b.position.x - a.position.x, b.position.y - a.position.y);
        let len = dx.hypot(dy);
        let cross = if len > 0.0 {
            ((sample.position.x - robot.x) * -dy + (sample.position.y - robot.y) * dx) / len
        } else {
            0.0
        };
        Some(progress_at(trajectory, i, sample, robot, cross))
    }
}

fn progress_at(
    trajectory: &Trajectory,
    index: usize,
    sample: TrajectoryPoint,
    robot: Point2,
    cross_track: f64,
) -> Progress {
    let goal = trajectory.points[trajectory.points.len() - 1];
    Progress {
        index,
        s: sample.s,
        projection: sample.position,
        heading: sample.heading,
        cross_track,
        remaining: (goal.s - sample.s).max(0.0),
        eta: (goal.t - sample.t).max(0.0),
        curvature: sample.curvature,
        speed: sample.v,
        goal_distance: robot.distance(goal.position),
    }
}

/// Distance from `p` to the segment a-b and the projection's parameter in [0, 1].
fn project(a: Point2, b: Point2, p: Point2) -> (f64, f64) {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len2 = dx * dx + dy * dy;
    let u = if len2 > 0.0 {
        (((p.x - a.x) * dx + (p.y - a.y) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = Point2::new(a.x + u * dx, a.y + u * dy);
    (p.distance(q), u)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::test_paths::{line, path};
    use std::f64::consts::PI;

    #[test]
    fn cross_track_is_positive_when_the_path_is_to_the_left() {
        let mut t = ProgressTracker::default();
        let p = t.update(Pose2::new(0.5, -0.1, 0.0), &line(2.0)).unwrap();
        assert!((p.cross_track - 0.1).abs() < 1e-12);
        let mut t = ProgressTracker::default();
        let p = t.update(Pose2::new(0.5, 0.1, PI), &line(2.0)).unwrap();
        assert!(
            (p.cross_track + 0.1).abs() < 1e-12,
            "the robot's heading is irrelevant"
        );
    }

    #[test]
    fn remaining_eta_and_lookahead_are_read_at_the_projection() {
        let traj = line(2.0);
        let mut t = ProgressTracker::default();
        let p = t.update(Pose2::new(0.52, 0.03, 0.0), &traj).unwrap();
        assert!((p.s - 0.52).abs() < 1e-12);
        assert!((p.remaining - 1.48).abs() < 1e-12);
        assert!((p.eta - 1.48 / 0.2).abs() < 1e-9);
        assert!((p.speed - 0.2).abs() < 1e-12);
        let ahead = p.lookahead(&traj, 0.33);
        assert!((ahead.x - 0.85).abs() < 1e-12 && ahead.y.abs() < 1e-12);
        assert_eq!(p.lookahead(&traj, 5.0), traj.goal().unwrap());
    }

    #[test]
    fn self_crossing_path_is_followed_in_order() {
        // A circle of radius 0.5 m run one and a half times: every point is passed twice.
        let r = 0.5;
        let traj = path(3.0 * PI * r, |s| {
            let a = s / r;
            (Point2::new(r * a.sin(), r - r * a.cos()), a, 1.0 / r)
        });
        let mut t = ProgressTracker::default();
        let mut last_s = 0.0;
        for k in 0..=150 {
            let a = 3.0 * PI * k as f64 / 150.0;
            let pose = Pose2::new(r * a.sin(), r - r * a.cos(), a);
            let p = t.update(pose, &traj).unwrap();
            assert!(
                p.s >= last_s,
                "went backwards at step {k}: {} < {last_s}",
                p.s
            );
            assert!(
                (p.s - a * r).abs() < 0.02,
                "step {k}: s {} for {}",
                p.s,
                a * r
            );
            last_s = p.s;
        }
        assert!(last_s > 4.6);
    }

    #[test]
    fn curvature_and_speed_interpolate_between_samples() {
        let mut traj = line(2.0);
        traj.points[10].curvature = 1.0;
        traj.points[10].v = 0.4;
        let mut t = ProgressTracker::default();
        let p = t.update(Pose2::new(0.525, 0.0, 0.0), &traj).unwrap();
        assert!((p.curvature - 0.5).abs() < 1e-9);
        assert!((p.speed - 0.3).abs() < 1e-9);
    }

    #[test]
    fn first_update_finds_a_robot_far_along_the_path() {
        let mut t = ProgressTracker::default();
        let p = t.update(Pose2::new(1.8, 0.05, 0.0), &line(2.0)).unwrap();
        assert!((p.s - 1.8).abs() < 1e-12, "{}", p.s);
        t.reset();
        let p = t.update(Pose2::new(0.1, 0.0, 0.0), &line(2.0)).unwrap();
        assert!((p.s - 0.1).abs() < 1e-12, "{}", p.s);
    }

    #[test]
    fn empty_trajectory_has_no_progress() {
        let mut t = ProgressTracker::default();
        assert!(t.update(Pose2::default(), &Trajectory::default()).is_none());
    }
}
