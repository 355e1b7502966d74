//! The three path followers driving a simulated unicycle, as a user would judge them: they
//! arrive, stay on the path, respect the limits, recover from a bad start.

use navdeck::control::{ControllerKind, FollowConfig, FollowStatus, FollowStep, Follower};
use navdeck::geometry::{Pose2, Twist, wrap_angle};
use navdeck::plan::trajectory::Trajectory;
use std::f64::consts::{FRAC_PI_2, PI};

mod sim;
use sim::{Unicycle, line, s_curve};

const DT: f64 = 0.1;
const MAX_LINEAR: f64 = 0.3;
const MAX_ANGULAR: f64 = 2.0;

struct Run {
    arrived: bool,
    steps: usize,
    goal_error: f64,
    rms: f64,
    /// Largest |cross-track| over the second half of the run, metres.
    late_cross_track: f64,
    max_linear: f64,
    max_angular: f64,
    min_linear: f64,
    poses: Vec<(Pose2, Twist)>,
}

fn run(kind: ControllerKind, trajectory: &Trajectory, start: Pose2) -> Run {
    let config = FollowConfig {
        controller: kind,
        ..FollowConfig::default()
    };
    let mut follower = Follower::new(config, MAX_LINEAR, MAX_ANGULAR);
    follower.set_trajectory(trajectory.clone());
    let mut robot = Unicycle::new(start);
    let mut out = Run {
        arrived: false,
        steps: 0,
        goal_error: f64::INFINITY,
        rms: 0.0,
        late_cross_track: 0.0,
        max_linear: 0.0,
        max_angular: 0.0,
        min_linear: 0.0,
        poses: Vec::new(),
    };
    let mut cross = Vec::new();
    // Four times the planned duration is plenty for any of them.
    let limit = (4.0 * trajectory.duration() / DT) as usize + 100;
    for step in 0..limit {
        let FollowStep { twist, status } = follower.step(robot.pose, DT);
        out.poses.push((robot.pose, twist));
        out.max_linear = out.max_linear.max(twist.linear.abs());
        out.min_linear = out.min_linear.min(twist.linear);
        out.max_angular = out.max_angular.max(twist.angular.abs());
        match status {
            FollowStatus::Arrived => {
                out.arrived = true;
                out.steps = step;
                assert!(twist.is_zero(), "{kind}: moving after arrival");
                // Arrival is final: the next step is still a stop.
                assert_eq!(follower.step(robot.pose, DT).twist, Twist::ZERO);
                break;
            }
            FollowStatus::Following { cross_track, .. } => cross.push(cross_track),
            FollowStatus::NoTrajectory => panic!("{kind}: lost its trajectory"),
            FollowStatus::Turning { .. } => panic!("{kind}: turning with no goal heading"),
        }
        robot.drive(twist, DT);
    }
    out.goal_error = robot.pose.position().distance(trajectory.goal().unwrap());
    out.rms = follower.cross_track_rms().unwrap_or(0.0);
    out.late_cross_track = cross[cross.len() / 2..]
        .iter()
        .fold(0.0_f64, |m, c| m.max(c.abs()));
    out
}

fn assert_arrives_within_limits(kind: ControllerKind, run: &Run, what: &str) {
    assert!(
        run.arrived,
        "{kind} on {what}: no arrival, {:.3} m from the goal",
        run.goal_error
    );
    assert!(
        run.goal_error <= 0.05,
        "{kind} on {what}: stopped {:.3} m off",
        run.goal_error
    );
    assert!(
        run.max_linear <= MAX_LINEAR + 1e-12,
        "{kind} on {what}: {} m/s",
        run.max_linear
    );
    assert!(
        run.max_angular <= MAX_ANGULAR + 1e-12,
        "{kind} on {what}: {} rad/s",
        run.max_angular
    );
    assert!(
        run.min_linear >= 0.0,
        "{kind} on {what}: reversed at {} m/s",
        run.min_linear
    );
}

#[test]
fn every_controller_follows_a_straight_line_to_the_goal() {
    let path = line(1.5);
    for kind in ControllerKind::ALL {
        let r = run(kind, &path, Pose2::new(0.0, 0.0, 0.0));
        assert_arrives_within_limits(kind, &r, "a line");
        assert!(
            r.rms < 0.005,
            "{kind}: {:.4} m RMS off a straight line",
            r.rms
        );
        // No crawling at the end. The PID runs at seed 001's distance-scaled speed, about
        // half the robot's top speed with waypoints 10 cm apart, so it is allowed longer.
        let planned = path.duration();
        let allowed = if kind == ControllerKind::Pid {
            2.0
        } else {
            1.3
        };
        assert!(
            (r.steps as f64) * DT < allowed * planned,
            "{kind}: {:.1} s for a {planned:.1} s plan",
            r.steps as f64 * DT
        );
    }
}

#[test]
fn every_controller_follows_the_s_curve_to_the_goal() {
    let path = s_curve();
    for kind in ControllerKind::ALL {
        let r = run(kind, &path, Pose2::new(0.0, 0.0, 0.0));
        assert_arrives_within_limits(kind, &r, "the S-curve");
        println!(
            "{kind:>12}: cross-track RMS {:.4} m, {:.1} s",
            r.rms,
            r.steps as f64 * DT
        );
    }
}

#[test]
fn hybrid_tracks_the_s_curve_within_three_centimetres_rms() {
    let r = run(
        ControllerKind::Hybrid,
        &s_curve(),
        Pose2::new(0.0, 0.0, 0.0),
    );
    assert!(r.rms < 0.03, "hybrid RMS {:.4} m", r.rms);
}

#[test]
fn every_controller_converges_from_twenty_centimetres_off_the_path() {
    let path = line(3.0);
    for kind in ControllerKind::ALL {
        for side in [0.2, -0.2] {
            let r = run(kind, &path, Pose2::new(0.0, side, 0.0));
            assert_arrives_within_limits(kind, &r, "a line from 0.2 m off");
            println!(
                "{kind:>12} from {side:+} m: RMS {:.4} m, late max {:.4} m, {:.1} s",
                r.rms,
                r.late_cross_track,
                r.steps as f64 * DT
            );
            assert!(
                r.late_cross_track < 0.02,
                "{kind} from {side} m: still {:.3} m off in the second half",
                r.late_cross_track
            );
        }
    }
}

#[test]
fn facing_away_from_the_path_turns_in_place_before_driving() {
    let path = line(1.5);
    for (kind, threshold) in [
        (ControllerKind::Pid, 60.0_f64.to_radians()),
        (ControllerKind::Hybrid, FRAC_PI_2),
        (ControllerKind::PurePursuit, FRAC_PI_2),
    ] {
        let r = run(kind, &path, Pose2::new(0.0, 0.0, PI));
        assert_arrives_within_limits(kind, &r, "a line, starting backwards");
        let start = r.poses[0].0.position();
        // While the heading is off by more than the threshold the robot pivots on the spot.
        let turning: Vec<_> = r
            .poses
            .iter()
            .take_while(|(pose, _)| wrap_angle(pose.theta).abs() > threshold + 0.05)
            .collect();
        assert!(turning.len() > 3, "{kind}: never turned in place");
        for (pose, twist) in &turning {
            assert!(
                pose.position().distance(start) < 0.01,
                "{kind}: drove {:.3} m before facing the path",
                pose.position().distance(start)
            );
            assert_eq!(
                twist.linear, 0.0,
                "{kind}: asked to drive while facing away"
            );
        }
    }
}

#[test]
fn follower_without_a_trajectory_stands_still() {
    let mut follower = Follower::new(FollowConfig::default(), MAX_LINEAR, MAX_ANGULAR);
    let step = follower.step(Pose2::new(1.0, 2.0, 0.3), DT);
    assert_eq!(step.twist, Twist::ZERO);
    assert_eq!(step.status, FollowStatus::NoTrajectory);
    follower.set_trajectory(Trajectory::default());
    assert_eq!(
        follower.step(Pose2::default(), DT).status,
        FollowStatus::NoTrajectory
    );
    follower.set_trajectory(line(1.0));
    assert!(!follower.step(Pose2::default(), DT).twist.is_zero());
    follower.clear_trajectory();
    assert_eq!(follower.step(Pose2::default(), DT).twist, Twist::ZERO);
}

#[test]
fn switching_controller_mid_path_still_arrives() {
    let path = s_curve();
    let mut follower = Follower::new(FollowConfig::default(), MAX_LINEAR, MAX_ANGULAR);
    follower.set_trajectory(path.clone());
    let mut robot = Unicycle::new(Pose2::default());
    let mut arrived = false;
    for step in 0..400 {
        if step % 40 == 39 {
            let next = ControllerKind::ALL[(step / 40) % 3];
            follower.set_controller(next);
            assert_eq!(follower.controller(), next);
        }
        let out = follower.step(robot.pose, DT);
        if out.status == FollowStatus::Arrived {
            arrived = true;
            break;
        }
        robot.drive(out.twist, DT);
    }
    assert!(arrived, "stuck at {:?}", robot.pose);
    assert!(robot.pose.position().distance(path.goal().unwrap()) <= 0.05);
}

#[test]
fn status_reports_shrinking_remaining_distance_and_eta() {
    let path = line(1.5);
    let mut follower = Follower::new(FollowConfig::default(), MAX_LINEAR, MAX_ANGULAR);
    follower.set_trajectory(path.clone());
    let mut robot = Unicycle::new(Pose2::default());
    let mut last = (f64::INFINITY, f64::INFINITY);
    for _ in 0..30 {
        let out = follower.step(robot.pose, DT);
        let FollowStatus::Following { remaining, eta, .. } = out.status else {
            panic!("{:?}", out.status);
        };
        assert!(remaining <= last.0 && eta <= last.1);
        last = (remaining, eta);
        robot.drive(out.twist, DT);
    }
    assert!(last.0 < 1.4 && last.1 < path.duration() - 1.0, "{last:?}");
}

#[test]
fn runs_are_deterministic() {
    let a = run(
        ControllerKind::Hybrid,
        &s_curve(),
        Pose2::new(0.0, 0.1, 0.2),
    );
    let b = run(
        ControllerKind::Hybrid,
        &s_curve(),
        Pose2::new(0.0, 0.1, 0.2),
    );
    assert_eq!(a.poses, b.poses);
}
