//! The pilot driven directly, without the console: keys, the deadman, the safety gate and
//! the mission, on the twin, through the same one-step-over-a-link the console uses.

use navdeck::config::Config;
use navdeck::data::{Command, GripperCommand, SensorFrame};
use navdeck::geometry::Pose2;
use navdeck::link::drive;
use navdeck::link::sim::SimLink;
use navdeck::link::{LinkError, RobotLink};
use navdeck::pilot::mode::Mode;
use navdeck::pilot::teleop::DriveKey;
use navdeck::pilot::{Due, Input, Intent, LinkStatus, Pilot};
use navdeck::sim::{Twin, World};

const PERIOD: f64 = 0.1;

/// The twin in the built-in arena, and a pilot that starts where it stands.
fn rig(seed: u64) -> (SimLink, Pilot) {
    let config = Config::default();
    let twin = Twin::new(World::default_arena(), &config.robot, &config.sim, seed);
    let link = SimLink::new(twin, 0.0);
    let pilot = drive::pilot_for(&link, config.pilot_settings(), 0.0);
    (link, pilot)
}

/// Asks `intent` at `t` and runs the control step it calls for, as the console does;
/// true when it called for one.
fn ask(link: &mut dyn RobotLink, pilot: &mut Pilot, t: f64, intent: Intent) -> bool {
    let truth = link.ground_truth().map(|g| g.pose());
    let out = pilot.step(Input::intent(t, intent, truth));
    if out.act_now {
        drive::step(link, pilot, t, Due::Command);
    }
    out.act_now
}

/// Control ticks from `from` (exclusive) to `to`; the largest commanded speed seen,
/// linear (m/s) or angular (rad/s).
fn ticks(link: &mut dyn RobotLink, pilot: &mut Pilot, from: f64, to: f64) -> f64 {
    let mut fastest: f64 = 0.0;
    let mut k = 1;
    while from + k as f64 * PERIOD <= to + 1e-9 {
        drive::step(link, pilot, from + k as f64 * PERIOD, Due::Tick);
        let twist = pilot.commanded();
        fastest = fastest.max(twist.linear.abs()).max(twist.angular.abs());
        k += 1;
    }
    fastest
}

#[test]
fn a_tapped_key_drives_until_the_deadman_then_the_robot_stops() {
    let (mut link, mut pilot) = rig(1);
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    assert!(
        ask(&mut link, &mut pilot, 0.0, down),
        "a drive key acts at once"
    );
    assert!(pilot.commanded().linear > 0.0, "the key drives forward");
    ticks(&mut link, &mut pilot, 0.0, 2.0);
    assert_eq!(
        pilot.commanded().linear,
        0.0,
        "the deadman stopped the robot"
    );
    let moved = link.ground_truth().unwrap().distance_driven();
    assert!(moved > 0.01, "the robot moved {moved} m");
}

#[test]
fn the_emergency_stop_holds_the_mission_still_until_a_drive_key() {
    let (mut link, mut pilot) = rig(2);
    ask(&mut link, &mut pilot, 0.0, Intent::Mode(Mode::Exploration));
    assert!(
        ticks(&mut link, &mut pilot, 0.0, 5.0) > 0.0,
        "the mission drives"
    );
    ask(&mut link, &mut pilot, 5.0, Intent::EmergencyStop);
    assert_eq!(pilot.mode(), Mode::Manual);
    assert!(pilot.estop());
    assert_eq!(ticks(&mut link, &mut pilot, 5.0, 8.0), 0.0, "nothing moves");
    let down = Intent::KeyDown {
        key: DriveKey::TurnLeft,
        repeat: false,
    };
    ask(&mut link, &mut pilot, 8.0, down.clone());
    assert!(pilot.estop(), "a drive key does not release the e-stop");
    assert_eq!(pilot.commanded().angular, 0.0);
    ask(&mut link, &mut pilot, 8.1, Intent::EmergencyStop);
    assert!(!pilot.estop(), "the e-stop key again releases it");
    assert_eq!(pilot.commanded().angular, 0.0, "releasing moves nothing");
    ask(&mut link, &mut pilot, 8.2, down);
    assert!(pilot.commanded().angular > 0.0);
}

#[test]
fn a_gripper_key_in_manual_mode_goes_to_the_robot() {
    let (mut link, mut pilot) = rig(3);
    let out = pilot.step(Input::intent(
        0.0,
        Intent::Gripper(GripperCommand::Close),
        None,
    ));
    assert!(out.act_now, "in manual mode the gripper key is the user's");
    assert!(out.log.iter().any(|l| l.text == "closing gripper"));
    drive::step(&mut link, &mut pilot, 0.0, Due::Command);
    ticks(&mut link, &mut pilot, 0.0, 3.0);
    assert!(pilot.gripper().is_some_and(|g| g.label() != "open"));
}

/// A link whose robot stops answering, then answers again.
struct Flaky {
    inner: SimLink,
    down: bool,
}

impl RobotLink for Flaky {
    fn label(&self) -> String {
        "flaky".into()
    }
    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.inner.send(command)
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        if self.down {
            return Err(LinkError::Lost("no odometry for 0.5 s".into()));
        }
        self.inner.poll(now)
    }
    fn stop(&mut self) {
        self.inner.stop();
    }
}

#[test]
fn a_lost_link_stops_the_robot_and_control_returns_only_on_the_users_word() {
    let (inner, mut pilot) = rig(4);
    let mut link = Flaky { inner, down: false };
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    ask(&mut link, &mut pilot, 0.0, down.clone());
    assert!(pilot.commanded().linear > 0.0);
    link.down = true;
    drive::step(&mut link, &mut pilot, 0.1, Due::Tick);
    assert!(matches!(pilot.link_status(), LinkStatus::Lost(_)));
    assert_eq!(pilot.commanded().linear, 0.0, "held keys are dropped");
    link.down = false;
    drive::step(&mut link, &mut pilot, 0.2, Due::Tick);
    assert_eq!(pilot.link_status(), &LinkStatus::Back);
    ask(&mut link, &mut pilot, 0.2, down.clone());
    assert_eq!(
        pilot.commanded().linear,
        0.0,
        "no driving before the user resumes"
    );
    ask(&mut link, &mut pilot, 0.3, Intent::Resume);
    assert_eq!(pilot.link_status(), &LinkStatus::Ok);
    ask(&mut link, &mut pilot, 0.3, down);
    assert!(pilot.commanded().linear > 0.0, "driving again after resume");
}

#[test]
fn after_halt_no_key_moves_the_robot() {
    let (mut link, mut pilot) = rig(5);
    ask(&mut link, &mut pilot, 0.0, Intent::Halt);
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    ask(&mut link, &mut pilot, 0.1, down);
    assert_eq!(pilot.commanded().linear, 0.0);
    assert_eq!(ticks(&mut link, &mut pilot, 0.1, 1.0), 0.0);
}

#[test]
fn the_mission_finds_landmarks_and_scores_against_the_truth_without_a_console() {
    let (mut link, mut pilot) = rig(6);
    ask(&mut link, &mut pilot, 0.0, Intent::Mode(Mode::Exploration));
    ticks(&mut link, &mut pilot, 0.0, 60.0);
    assert!(pilot.slam().landmark_count() >= 3, "landmarks found");
    assert!(pilot.accuracy().samples > 500, "one sample per tick");
    let truth: Pose2 = link.ground_truth().unwrap().pose();
    let error = truth.position().distance(pilot.estimated_pose().position());
    assert!(error < 0.1, "estimate {error:.3} m from the truth");
}

#[test]
fn a_goto_on_the_robots_map_plans_a_path_and_following_reaches_it() {
    let (mut link, mut pilot) = rig(7);
    // Look around first so the map knows the walls near the start.
    ask(&mut link, &mut pilot, 0.0, Intent::Mode(Mode::Exploration));
    ticks(&mut link, &mut pilot, 0.0, 10.0);
    ask(&mut link, &mut pilot, 10.0, Intent::Mode(Mode::Manual));
    let here = pilot.estimated_pose().position();
    let goal = navdeck::geometry::Point2::new(here.x + 0.3, here.y);
    let target = navdeck::pilot::navigation::Target::Point(goal);
    ask(&mut link, &mut pilot, 10.0, Intent::Goto(target));
    assert!(pilot.route().is_some(), "a path to a free point 0.3 m away");
    ask(
        &mut link,
        &mut pilot,
        10.0,
        Intent::Mode(Mode::PathFollowing),
    );
    ticks(&mut link, &mut pilot, 10.0, 40.0);
    assert!(pilot.arrived(), "the follower arrived");
    let at = pilot.estimated_pose().position();
    assert!(
        at.distance(goal) < 0.1,
        "stopped {:.3} m from the goal",
        at.distance(goal)
    );
}
