//! `--link ros2` against a fake robot on its own DDS participant: the whole loop from
//! keys to cmd_vel to odometry and back, the watchdog, bad messages, and RViz output.
//! Each test has its own DDS domain, so they run in parallel without cross-talk.

use crate::common;
use crate::ros2_support;

use common::logged;
use navdeck::app::{App, KeyKind, LinkStatus};
use navdeck::config::Config;
use navdeck::keymap::{Key, Keymap};
use navdeck::link::ros2::config::CmdVelType;
use navdeck::link::ros2::{Ros2Link, Ros2Options};
use ros2_support::{FakeOptions, FakeRobot};
use std::time::{Duration, Instant};

/// Upper bound on any wait for DDS (discovery on loopback takes well under a second).
const PATIENCE: f64 = 20.0;

/// A console on the ROS 2 link, run on the wall clock as the TUI runs it.
struct Console {
    app: App,
    started: Instant,
}

impl Console {
    fn open(domain: u16, tweak: impl FnOnce(&mut Config)) -> Console {
        let mut config = Config::default();
        config.ros2.interfaces = std::env::var("NAVDECK_TEST_IFACES")
            .map(|s| vec![s])
            .unwrap_or_default();
        config.robot.track = ros2_support::TRACK;
        tweak(&mut config);
        let link = Ros2Link::connect(Ros2Options {
            config: config.ros2.clone(),
            domain,
            track: config.robot.track,
            max_wheel_speed: config.robot.max_wheel_speed(),
        })
        .expect("ROS 2 link");
        let app = App::new(config, Keymap::default_map(), Box::new(link), 0.0);
        Console {
            app,
            started: Instant::now(),
        }
    }

    fn now(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Runs the console loop (as the TUI does, a tick every few ms) until `done` holds;
    /// panics with `what` after PATIENCE seconds.
    fn until(&mut self, what: &str, mut done: impl FnMut(&App) -> bool) {
        let give_up = self.now() + PATIENCE;
        loop {
            let now = self.now();
            self.app.update(now);
            if done(&self.app) {
                return;
            }
            assert!(
                now < give_up,
                "gave up waiting for {what}; log:\n{}",
                log_text(&self.app)
            );
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Keeps the console running for `seconds`, pressing `key` (if any) every 50 ms as
    /// a terminal's auto-repeat does.
    fn run_for(&mut self, seconds: f64, key: Option<char>) {
        let end = self.now() + seconds;
        let mut next_key = 0.0;
        while self.now() < end {
            let now = self.now();
            if let Some(c) = key
                && now >= next_key
            {
                self.app.handle_key(Key::char(c), KeyKind::Press, now);
                next_key = now + 0.05;
            }
            self.app.update(now);
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Runs the console until the robot's first data brings the link up.
    fn until_up(&mut self) {
        self.until("the link to come up", |a| {
            a.pilot().link_status() == &LinkStatus::Ok
        });
    }

    fn press(&mut self, c: char) {
        let now = self.now();
        self.app.handle_key(Key::char(c), KeyKind::Press, now);
    }

    fn logged(&self, text: &str) -> bool {
        logged(&self.app, text)
    }
}

/// The console's log, a line each, for failure messages.
fn log_text(app: &App) -> String {
    app.log_book()
        .iter()
        .map(|e| e.text.as_str())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn holding_w_drives_the_robot_over_ros2_and_its_odometry_comes_back() {
    let robot = FakeRobot::start(FakeOptions::new(61));
    let mut c = Console::open(61, |_| {});
    c.until("the link to come up", |a| {
        a.pilot().link_status() == &LinkStatus::Ok
            && a.pilot().measured().linear == 0.0
            && a.now() > 0.5
    });
    assert!(c.logged("link up"));
    c.run_for(1.5, Some('w'));
    let seen = robot.seen();
    let forward: Vec<_> = seen.cmd_vel.iter().filter(|m| m.1 > 0.0).collect();
    assert!(
        forward.len() >= 5,
        "cmd_vel received: {}",
        seen.cmd_vel.len()
    );
    let speed = c.app.config().teleop.linear_speed;
    assert!(
        forward.iter().all(|m| m.1 <= speed + 1e-9 && m.2 == 0.0),
        "straight ahead at most {speed} m/s"
    );
    // Let go: the deadman stops the robot, with a few zeros and then silence.
    c.run_for(1.5, None);
    let seen = robot.seen();
    let last_moving = seen.cmd_vel.iter().rposition(|m| m.1 != 0.0).unwrap();
    let zeros = &seen.cmd_vel[last_moving + 1..];
    assert!(
        (1..=3).contains(&zeros.len()) && zeros.iter().all(|m| m.1 == 0.0 && m.2 == 0.0),
        "zeros after stopping: {}",
        zeros.len()
    );
    // The wheel joints carried the motion back: navdeck's estimate follows the robot.
    let (x, y, _) = seen.pose;
    assert!(x > 0.1, "the fake robot drove {x:.3} m");
    let est = c.app.pilot().estimated_pose();
    assert!(
        (est.x - x).abs() < 0.03 && (est.y - y).abs() < 0.03,
        "estimate ({:.3}, {:.3}) vs robot ({x:.3}, {y:.3})",
        est.x,
        est.y
    );
    assert!(c.logged("wheel travel from joint states"));
    drop(c);
}

#[test]
fn without_joint_states_the_odometry_deltas_drive_the_estimate() {
    let robot = FakeRobot::start(FakeOptions {
        joints: false,
        ..FakeOptions::new(62)
    });
    let mut c = Console::open(62, |_| {});
    c.until_up();
    c.run_for(1.0, Some('d'));
    c.run_for(1.0, None);
    let (x, y, th) = robot.seen().pose;
    assert!(th < -0.3, "the robot turned right: {th:.2} rad");
    let est = c.app.pilot().estimated_pose();
    assert!(
        (est.theta - th).abs() < 0.02 && (est.x - x).abs() < 0.02 && (est.y - y).abs() < 0.02,
        "estimate {est:?} vs robot ({x:.3}, {y:.3}, {th:.3})"
    );
}

#[test]
fn a_jazzy_robot_gets_twist_stamped_and_a_wrong_setting_is_called_out() {
    let robot = FakeRobot::start(FakeOptions {
        stamped: true,
        ..FakeOptions::new(63)
    });
    let mut c = Console::open(63, |_| {});
    c.until_up();
    c.until("discovery of the subscriber", |a| {
        logged(a, "reads TwistStamped")
    });
    c.run_for(0.6, Some('w'));
    assert!(
        robot.seen().cmd_vel.iter().any(|m| m.1 > 0.0),
        "the TwistStamped robot moved"
    );
    drop(c);

    let mut wrong = Console::open(63, |cfg| cfg.ros2.cmd_vel_type = CmdVelType::Twist);
    wrong.until("the mismatch warning", |a| logged(a, "it will not move"));
}

#[test]
fn odometry_silence_stops_the_robot_until_data_and_a_key_return() {
    let options = FakeOptions::new(64);
    let odom_paused = options.odom_paused.clone();
    let robot = FakeRobot::start(options);
    let mut c = Console::open(64, |_| {});
    c.until_up();
    c.run_for(0.5, Some('w'));
    odom_paused.store(true, std::sync::atomic::Ordering::SeqCst);
    let paused_at = Instant::now();
    // Keys keep coming, but the watchdog wins.
    c.until("LINK LOST", |a| {
        matches!(a.pilot().link_status(), LinkStatus::Lost(_))
    });
    let lost_after = paused_at.elapsed().as_secs_f64();
    assert!(lost_after < 2.0, "noticed after {lost_after:.2} s");
    c.run_for(0.5, Some('w'));
    let seen = robot.seen();
    assert_eq!(
        seen.cmd_vel.last().map(|m| (m.1, m.2)),
        Some((0.0, 0.0)),
        "the last command the robot heard is a stop"
    );
    odom_paused.store(false, std::sync::atomic::Ordering::SeqCst);
    c.until("data to return", |a| {
        a.pilot().link_status() == &LinkStatus::Back
    });
    let heard = robot.seen().cmd_vel.len();
    c.run_for(0.5, None);
    assert_eq!(
        robot.seen().cmd_vel.len(),
        heard,
        "silent while waiting for a key"
    );
    c.press('x');
    c.run_for(0.5, Some('w'));
    assert_eq!(c.app.pilot().link_status(), &LinkStatus::Ok);
    assert!(
        robot.seen().cmd_vel.last().unwrap().1 > 0.0,
        "driving again"
    );
}

#[test]
fn bad_odometry_is_dropped_and_counted_not_estimated() {
    let robot = FakeRobot::start(FakeOptions {
        bad_odom_every: Some(5),
        joints: false,
        ..FakeOptions::new(65)
    });
    let mut c = Console::open(65, |_| {});
    c.until_up();
    c.run_for(1.0, Some('w'));
    assert!(
        c.app.link().label().contains("dropped"),
        "{}",
        c.app.link().label()
    );
    assert!(c.logged("dropped a odometry message (non-finite value"));
    let est = c.app.pilot().estimated_pose();
    assert!(
        est.x.is_finite() && est.x > 0.05,
        "{est:?}; robot at {:?}; log:\n{}",
        robot.seen().pose,
        log_text(&c.app)
    );
}

#[test]
fn rviz_gets_the_map_pose_transform_landmarks_and_plan() {
    let robot = FakeRobot::start(FakeOptions::new(66));
    let mut c = Console::open(66, |_| {});
    c.until_up();
    for key in ":goto 0.5 0".chars() {
        c.press(key);
    }
    let now = c.now();
    c.app.handle_key(
        Key::new(navdeck::keymap::KeyCode::Enter),
        KeyKind::Press,
        now,
    );
    c.run_for(2.5, None);
    let seen = robot.seen();
    let (w, h, res) = *seen.maps.last().expect("a map");
    assert!(
        w >= 400 && h >= 400 && (res - 0.01).abs() < 1e-6,
        "{w}x{h} at {res}"
    );
    assert!(!seen.poses.is_empty(), "estimated poses");
    assert!(
        seen.transforms
            .iter()
            .any(|(p, ch)| p == "map" && ch == "odom"),
        "map -> odom on /tf"
    );
    assert!(
        seen.paths.iter().any(|&n| n > 2),
        "a plan: {:?}",
        seen.paths
    );
    assert!(!seen.landmark_arrays.is_empty(), "landmark markers");
}

#[test]
fn gripper_keys_publish_the_configured_positions_and_quit_stops_the_robot() {
    let robot = FakeRobot::start(FakeOptions::new(67));
    let mut c = Console::open(67, |_| {});
    c.until_up();
    c.press('o');
    c.run_for(0.3, None);
    // In manual mode c stops (as in seed 001); elsewhere it closes the gripper.
    c.press('t');
    c.press('c');
    c.run_for(0.3, None);
    c.run_for(0.5, Some('w'));
    c.app.shutdown("test over");
    let open = c.app.config().ros2.gripper_open;
    let closed = c.app.config().ros2.gripper_closed;
    let give_up = Instant::now() + Duration::from_secs(10);
    while robot.seen().cmd_vel.last().map(|m| m.1) != Some(0.0) {
        assert!(Instant::now() < give_up, "no stop after shutdown");
        std::thread::sleep(Duration::from_millis(5));
    }
    let seen = robot.seen();
    assert_eq!(
        seen.gripper,
        vec![open, closed],
        "log:\n{}",
        log_text(&c.app)
    );
}

/// The console drawn once at `width` x `height`, as text.
fn drawn(app: &App, width: u16, height: u16) -> String {
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| navdeck::tui::draw::draw(f, app, navdeck::tui::theme::Theme { color: false }))
        .unwrap();
    let buf = terminal.backend().buffer();
    (0..height)
        .map(|y| (0..width).map(|x| buf[(x, y)].symbol()).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The link's status-panel value for `label`.
fn detail(app: &App, label: &str) -> String {
    app.link()
        .details(app.now())
        .into_iter()
        .find(|(l, _)| *l == label)
        .map(|(_, v)| v)
        .unwrap_or_else(|| panic!("no {label} detail"))
}

#[test]
fn the_status_panel_says_what_discovery_found_with_a_waiting_time_that_counts() {
    // No robot on the domain yet: the panel says why nothing moves, and the wait counts.
    let mut c = Console::open(68, |_| {});
    c.run_for(0.3, None);
    let reason = |app: &App| match app.pilot().link_status() {
        LinkStatus::Lost(why) => why.clone(),
        other => panic!("link {other:?}"),
    };
    let first = reason(&c.app);
    assert!(
        first.contains("nothing publishes it in domain 68"),
        "{first}"
    );
    c.run_for(0.3, None);
    assert_ne!(reason(&c.app), first, "the waiting time counts up");
    assert_eq!(detail(&c.app, "cmd_vel"), "no subscriber");
    assert_eq!(detail(&c.app, "Odom"), "odom no publisher");
    assert_eq!(detail(&c.app, "DDS"), "domain 68 · 0 peers");
    let screen = drawn(&c.app, 120, 40);
    assert!(screen.contains("cmd_vel no subscriber"), "{screen}");
    // The robot joins: its participant, topics, rates and cmd_vel reader show up.
    let _robot = FakeRobot::start(FakeOptions::new(68));
    c.until("the robot to be discovered and measured", |a| {
        let odom = detail(a, "Odom");
        let hz: f64 = odom
            .split_whitespace()
            .rev()
            .nth(1)
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0);
        hz > 5.0
            && detail(a, "Scan").ends_with(" Hz")
            && detail(a, "cmd_vel") == "1 reader (Twist)"
            && !detail(a, "DDS").ends_with(" 0 peers")
    });
    let screen = drawn(&c.app, 120, 40);
    assert!(screen.contains("Odom    odom "), "{screen}");
}

/// Publishes `goal` on /goal_pose from a node of its own, again every 100 ms, until the
/// links' wake socket turns readable (the console's input wait would return) or PATIENCE
/// runs out; whether it did.
fn publish_until_woken(domain: u16, goal: &navdeck::msgs::ros::PoseStamped) -> bool {
    use ros2_client::{MessageTypeName, Name, NodeName, NodeOptions};
    use rustix::event::{PollFd, PollFlags, Timespec, poll};
    let wake = navdeck::link::tasks::wake::global().expect("a wake socket");
    let context = ros2_support::context(domain, false);
    let mut node = context
        .new_node(
            NodeName::new("/", "rviz_stand_in").unwrap(),
            NodeOptions::new().enable_rosout(false),
        )
        .unwrap();
    let qos = navdeck::link::ros2::participant::qos_profile(Default::default(), false);
    let topic = node
        .create_topic(
            &Name::parse("/goal_pose").unwrap(),
            MessageTypeName::new("geometry_msgs", "PoseStamped"),
            &qos,
        )
        .unwrap();
    let publisher = node.create_publisher(&topic, None).unwrap();
    let started = Instant::now();
    while started.elapsed().as_secs_f64() < PATIENCE {
        publisher.publish(goal.clone()).unwrap();
        let mut fds = [PollFd::from_borrowed_fd(wake.fd(), PollFlags::IN)];
        let tenth = Timespec {
            tv_sec: 0,
            tv_nsec: 100_000_000,
        };
        if poll(&mut fds, Some(&tenth)).unwrap_or(0) > 0 {
            return true;
        }
    }
    false
}

#[test]
fn a_goal_from_rviz_wakes_the_console_at_once_and_the_next_poll_takes_it() {
    use navdeck::link::RobotLink;
    use navdeck::msgs::ros::{Header, Pose, PoseStamped, Quaternion};
    let _robot = FakeRobot::start(FakeOptions::new(69));
    let mut link = Ros2Link::connect(Ros2Options {
        config: Default::default(),
        domain: 69,
        track: ros2_support::TRACK,
        max_wheel_speed: 0.3,
    })
    .expect("ROS 2 link");
    let mut goal = PoseStamped {
        header: Header {
            frame_id: "map".into(),
            ..Default::default()
        },
        pose: Pose::default(),
    };
    goal.pose.position.x = 1.5;
    goal.pose.position.y = -0.5;
    goal.pose.orientation = Quaternion::from_yaw(0.0);
    assert!(
        publish_until_woken(69, &goal),
        "no wake within {PATIENCE} s of publishing a goal"
    );
    // The link answers once the robot's odometry flows; the goal waits for that poll.
    let started = Instant::now();
    let taken = loop {
        let now = started.elapsed().as_secs_f64();
        if let Ok(frame) = link.poll(now) {
            break frame.goal.expect("the goal that woke the console");
        }
        assert!(now < PATIENCE, "the link never came up");
        std::thread::sleep(Duration::from_millis(5));
    };
    assert!((taken.x - 1.5).abs() < 1e-9 && (taken.y + 0.5).abs() < 1e-9);
}
