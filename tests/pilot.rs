//! The pilot driven directly, without the console: keys, the deadman, the safety gate and
//! the mission, on the twin, through the same runtime (`link::runtime`) the console uses.

use navdeck::config::Config;
use navdeck::data::{Command, GripperCommand, SensorFrame};
use navdeck::geometry::Pose2;
use navdeck::link::runtime::{Event, Runtime};
use navdeck::link::sim::SimLink;
use navdeck::link::{LinkError, RobotLink};
use navdeck::pilot::mode::Mode;
use navdeck::pilot::teleop::DriveKey;
use navdeck::pilot::{Intent, LinkStatus};
use navdeck::sim::{Twin, World};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

const PERIOD: f64 = 0.1;

/// The twin in the built-in arena behind `wrap`, and a runtime whose pilot starts where
/// it stands.
fn rig_with(seed: u64, wrap: impl FnOnce(SimLink) -> Box<dyn RobotLink>) -> Runtime {
    let config = Config::default();
    let twin = Twin::new(World::default_arena(), &config.robot, &config.sim, seed);
    let link = wrap(SimLink::new(twin, 0.0));
    Runtime::new(link, config.pilot_settings(), 0.0)
}

fn rig(seed: u64) -> Runtime {
    rig_with(seed, |link| Box::new(link))
}

/// Brings the robot up to `t`, then asks `intent` in one step, as the console does; true
/// when that step sent a command (the intent changed the motion).
fn ask(robot: &mut Runtime, t: f64, intent: Intent) -> bool {
    robot.tick(t, Vec::new());
    let stepped = robot.intend(intent);
    (stepped.events.iter()).any(|e| matches!(e, Event::Sent { .. }))
}

/// Control ticks from `from` (exclusive) to `to`; the largest commanded speed seen,
/// linear (m/s) or angular (rad/s).
fn ticks(robot: &mut Runtime, from: f64, to: f64) -> f64 {
    let mut fastest: f64 = 0.0;
    let mut k = 1;
    while from + k as f64 * PERIOD <= to + 1e-9 {
        robot.tick(from + k as f64 * PERIOD, Vec::new());
        let twist = robot.pilot().commanded();
        fastest = fastest.max(twist.linear.abs()).max(twist.angular.abs());
        k += 1;
    }
    fastest
}

#[test]
fn a_tapped_key_drives_until_the_deadman_then_the_robot_stops() {
    let mut robot = rig(1);
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    assert!(ask(&mut robot, 0.0, down), "a drive key acts at once");
    assert!(
        robot.pilot().commanded().linear > 0.0,
        "the key drives forward"
    );
    ticks(&mut robot, 0.0, 2.0);
    assert_eq!(
        robot.pilot().commanded().linear,
        0.0,
        "the deadman stopped the robot"
    );
    let moved = robot.link().ground_truth().unwrap().distance_driven();
    assert!(moved > 0.01, "the robot moved {moved} m");
}

#[test]
fn the_emergency_stop_holds_the_mission_still_until_a_drive_key() {
    let mut robot = rig(2);
    ask(&mut robot, 0.0, Intent::Mode(Mode::Exploration));
    assert!(ticks(&mut robot, 0.0, 5.0) > 0.0, "the mission drives");
    ask(&mut robot, 5.0, Intent::EmergencyStop);
    assert_eq!(robot.pilot().mode(), Mode::Manual);
    assert!(robot.pilot().estop());
    assert_eq!(ticks(&mut robot, 5.0, 8.0), 0.0, "nothing moves");
    let down = Intent::KeyDown {
        key: DriveKey::TurnLeft,
        repeat: false,
    };
    ask(&mut robot, 8.0, down.clone());
    assert!(
        robot.pilot().estop(),
        "a drive key does not release the e-stop"
    );
    assert_eq!(robot.pilot().commanded().angular, 0.0);
    ask(&mut robot, 8.1, Intent::EmergencyStop);
    assert!(!robot.pilot().estop(), "the e-stop key again releases it");
    assert_eq!(
        robot.pilot().commanded().angular,
        0.0,
        "releasing moves nothing"
    );
    ask(&mut robot, 8.2, down);
    assert!(robot.pilot().commanded().angular > 0.0);
}

#[test]
fn a_gripper_key_in_manual_mode_goes_to_the_robot() {
    let mut robot = rig(3);
    let stepped = robot.intend(Intent::Gripper(GripperCommand::Close));
    let sent = (stepped.events.iter()).any(|e| matches!(e, Event::Sent { .. }));
    assert!(sent, "in manual mode the gripper key is the user's");
    assert!(
        stepped
            .log_lines()
            .any(|(_, _, text)| text == "gripper asked to close")
    );
    ticks(&mut robot, 0.0, 3.0);
    assert!(robot.pilot().gripper().is_some_and(|g| g.label() != "open"));
}

/// A link whose robot stops answering, then answers again.
struct Flaky {
    inner: SimLink,
    down: Arc<AtomicBool>,
}

impl RobotLink for Flaky {
    fn label(&self) -> String {
        "flaky".into()
    }
    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.inner.send(command)
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        if self.down.load(Ordering::Relaxed) {
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
    let down_now = Arc::new(AtomicBool::new(false));
    let switch = down_now.clone();
    let mut robot = rig_with(4, move |inner| {
        Box::new(Flaky {
            inner,
            down: switch,
        })
    });
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    ask(&mut robot, 0.0, down.clone());
    assert!(robot.pilot().commanded().linear > 0.0);
    down_now.store(true, Ordering::Relaxed);
    robot.tick(0.1, Vec::new());
    assert!(matches!(robot.pilot().link_status(), LinkStatus::Lost(_)));
    assert_eq!(
        robot.pilot().commanded().linear,
        0.0,
        "held keys are dropped"
    );
    down_now.store(false, Ordering::Relaxed);
    robot.tick(0.2, Vec::new());
    assert_eq!(robot.pilot().link_status(), &LinkStatus::Back);
    ask(&mut robot, 0.2, down.clone());
    assert_eq!(
        robot.pilot().commanded().linear,
        0.0,
        "no driving before the user resumes"
    );
    ask(&mut robot, 0.3, Intent::Resume);
    assert_eq!(robot.pilot().link_status(), &LinkStatus::Ok);
    ask(&mut robot, 0.3, down);
    assert!(
        robot.pilot().commanded().linear > 0.0,
        "driving again after resume"
    );
}

#[test]
fn after_halt_no_key_moves_the_robot() {
    let mut robot = rig(5);
    ask(&mut robot, 0.0, Intent::Halt);
    let down = Intent::KeyDown {
        key: DriveKey::Forward,
        repeat: false,
    };
    ask(&mut robot, 0.1, down);
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    assert_eq!(ticks(&mut robot, 0.1, 1.0), 0.0);
}

#[test]
fn the_mission_finds_landmarks_and_scores_against_the_truth_without_a_console() {
    let mut robot = rig(6);
    ask(&mut robot, 0.0, Intent::Mode(Mode::Exploration));
    ticks(&mut robot, 0.0, 60.0);
    assert!(
        robot.pilot().slam().landmark_count() >= 3,
        "landmarks found"
    );
    assert!(
        robot.pilot().accuracy().samples > 500,
        "one sample per tick"
    );
    let truth: Pose2 = robot.link().ground_truth().unwrap().pose();
    let error = truth
        .position()
        .distance(robot.pilot().estimated_pose().position());
    assert!(error < 0.1, "estimate {error:.3} m from the truth");
}

#[test]
fn a_goto_on_the_robots_map_plans_a_path_and_following_reaches_it() {
    let mut robot = rig(7);
    // Look around first so the map knows the walls near the start.
    ask(&mut robot, 0.0, Intent::Mode(Mode::Exploration));
    ticks(&mut robot, 0.0, 10.0);
    ask(&mut robot, 10.0, Intent::Mode(Mode::Manual));
    let here = robot.pilot().estimated_pose().position();
    let goal = navdeck::geometry::Point2::new(here.x + 0.3, here.y);
    let target = navdeck::pilot::navigation::Target::Point(goal);
    ask(&mut robot, 10.0, Intent::Goto(target));
    assert!(
        robot.pilot().route().is_some(),
        "a path to a free point 0.3 m away"
    );
    ask(&mut robot, 10.0, Intent::Mode(Mode::PathFollowing));
    ticks(&mut robot, 10.0, 40.0);
    assert!(robot.pilot().arrived(), "the follower arrived");
    let at = robot.pilot().estimated_pose().position();
    assert!(
        at.distance(goal) < 0.1,
        "stopped {:.3} m from the goal",
        at.distance(goal)
    );
}

#[test]
fn the_arbiter_says_which_behaviour_drives_and_logs_the_e_stop_once() {
    use navdeck::pilot::behaviours::Behaviour;
    let mut robot = rig(4);
    let winner = |robot: &Runtime| robot.pilot().arbiter().winner().map(|(b, _)| b);
    ticks(&mut robot, 0.0, 0.5);
    assert_eq!(
        winner(&robot),
        Some(Behaviour::Teleop),
        "manual mode: teleop"
    );
    ask(&mut robot, 0.5, Intent::Mode(Mode::Exploration));
    ticks(&mut robot, 0.5, 2.0);
    let task = winner(&robot);
    assert!(
        matches!(task, Some(Behaviour::Exploration | Behaviour::PickAndPlace)),
        "{task:?}"
    );
    // The e-stop wins at once and says so once however many ticks it holds.
    robot.tick(2.1, Vec::new());
    let stepped = robot.intend(Intent::EmergencyStop);
    let mut said: Vec<String> = (stepped.log_lines())
        .filter(|(_, _, text)| text.starts_with("behaviour: e-stop"))
        .map(|(_, _, text)| text.to_string())
        .collect();
    for k in 1..=20 {
        let stepped = robot.tick(2.1 + k as f64 * PERIOD, Vec::new());
        said.extend(
            (stepped.log_lines())
                .filter(|(_, _, text)| text.starts_with("behaviour: e-stop"))
                .map(|(_, _, text)| text.to_string()),
        );
    }
    let was = task.unwrap();
    assert_eq!(said, [format!("behaviour: e-stop (was {was}): pressed")]);
    assert_eq!(winner(&robot), Some(Behaviour::EmergencyStop));
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    // Released, teleop has control again, and the history holds every change in order.
    ask(&mut robot, 5.0, Intent::EmergencyStop);
    ticks(&mut robot, 5.0, 5.5);
    assert_eq!(winner(&robot), Some(Behaviour::Teleop));
    let changes: Vec<Option<Behaviour>> =
        robot.pilot().arbiter().history().map(|tr| tr.to).collect();
    assert_eq!(changes.first(), Some(&Some(Behaviour::Teleop)));
    assert_eq!(changes.last(), Some(&Some(Behaviour::Teleop)));
    assert!(changes.contains(&Some(Behaviour::EmergencyStop)));
}

#[test]
fn a_task_behaviour_switched_off_for_a_while_holds_the_robot_then_drives_again() {
    use navdeck::pilot::behaviours::Behaviour;
    let mut robot = rig(5);
    let off = Intent::Behaviour {
        behaviour: Behaviour::Teleop,
        on: false,
        seconds: Some(1.0),
    };
    ask(&mut robot, 0.0, off);
    let down = |repeat| Intent::KeyDown {
        key: DriveKey::TurnLeft,
        repeat,
    };
    ask(&mut robot, 0.1, down(false));
    assert_eq!(robot.pilot().commanded().angular, 0.0, "teleop is off");
    assert_eq!(robot.pilot().arbiter().winner(), None);
    ask(&mut robot, 1.2, down(true));
    assert!(robot.pilot().commanded().angular > 0.0, "teleop is back");
    // The e-stop cannot be switched off.
    let estop_off = Intent::Behaviour {
        behaviour: Behaviour::EmergencyStop,
        on: false,
        seconds: None,
    };
    robot.tick(1.3, Vec::new());
    let stepped = robot.intend(estop_off);
    assert!(
        (stepped.log_lines()).any(|(_, _, text)| text.contains("cannot be switched off")),
        "the refusal is logged"
    );
}
