//! navdeck against a robot on Eclipse Cyclone DDS (the DDS ROS 2 ships), played by
//! tests/interop/turtlebot_peer.py with ROS 2's wire types: headless navdeck drives it
//! over `--link ros2`, and both sides check what crossed (with `--room`, the peer's
//! scans of a room are mapped by lidar SLAM and it checks the map it gets back). tests/interop/amcl_peer.py
//! plays RViz beside MCL: pose estimates on /initialpose in, particles on /particlecloud
//! out, checked at the link itself. tests/interop/arm_peer.py plays an OpenManipulator-X
//! arm's controllers: trajectories and gripper goals in, joint states out.
//!
//! Needs a Python with the PyPI `cyclonedds` package: `NAVDECK_PYTHON` names it
//! (./scripts/test makes a virtualenv and sets it, with NAVDECK_REQUIRE_INTEROP=1 so
//! that a missing peer fails the run instead of skipping).

#[path = "common"]
mod common {
    pub mod scratch;
    pub use scratch::*;
}
mod cyclone_peer;
#[path = "interop_fleet.rs"]
mod fleet;
#[cfg(feature = "vision")]
#[path = "interop_lane_camera.rs"]
mod lane_camera;
mod python_support;
#[path = "interop_tag_graph.rs"]
mod tag_graph;
#[cfg(feature = "vision")]
#[path = "interop_tag_route.rs"]
mod tag_route;

use common::scratch;
use cyclone_peer::{CYCLONE_CONFIG, LinePeer, PATIENCE, python};

use navdeck::config::Config;
use navdeck::data::{ArmState, ArmTarget, GripperCommand};
use navdeck::geometry::Pose2;
use navdeck::link::ros2::config::{Qos, Reliability, Rmw};
use navdeck::link::ros2::{Ros2Link, Ros2Options};
use navdeck::link::{Picture, RobotLink, SensorFrame};
use serde_json::Value;
use std::ffi::OsString;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::Instant;

impl LinePeer {
    /// Tells the peer `line` on its stdin.
    fn say(&mut self, line: &str) {
        use std::io::Write;
        let stdin = self.stdin.as_mut().unwrap();
        writeln!(stdin, "{line}")
            .and_then(|_| stdin.flush())
            .unwrap();
    }
}

/// Runs the peer on `domain`, drives it with `keys` through headless navdeck, and
/// returns (navdeck's JSON report, the peer's JSON record).
fn drive(domain: u16, keys: &str, peer_args: &[&str], config: &str) -> Option<(Value, Value)> {
    drive_with(domain, keys, peer_args, config, &[])
}

/// `drive` with more arguments for navdeck.
fn drive_with(
    domain: u16,
    keys: &str,
    peer_args: &[&str],
    config: &str,
    navdeck_args: &[&str],
) -> Option<(Value, Value)> {
    let dir = scratch(&domain.to_string());
    let out = dir.join("peer.json");
    let cfg = dir.join("navdeck.toml");
    std::fs::write(&cfg, config).unwrap();
    let mut peer: Vec<OsString> = vec![out.clone().into()];
    peer.extend(peer_args.iter().map(OsString::from));
    let mut navdeck: Vec<OsString> = [
        "--link",
        "ros2",
        "--domain",
        &domain.to_string(),
        "--config",
    ]
    .map(OsString::from)
    .into();
    navdeck.push(cfg.into());
    navdeck.extend(navdeck_args.iter().map(OsString::from));
    navdeck.extend(["--headless", "--json", "--keys", keys].map(OsString::from));
    with_peer("turtlebot_peer.py", domain, &peer, &out, &navdeck)
}

/// Starts the peer `script` (tests/interop/) on `domain` with `peer_args` after the
/// domain, waits for its "ready", runs navdeck with `navdeck_args` (a headless run
/// printing JSON), then closes the peer's stdin, which makes it write its record to
/// `out` and leave. Returns navdeck's report and the peer's record; None when there is
/// no Python with Cyclone DDS.
fn with_peer(
    script: &str,
    domain: u16,
    peer_args: &[OsString],
    out: &std::path::Path,
    navdeck_args: &[OsString],
) -> Option<(Value, Value)> {
    let python = python()?;
    let script = format!("{}/tests/interop/{script}", env!("CARGO_MANIFEST_DIR"));
    let mut peer = Command::new(&python)
        .arg(script)
        .arg(domain.to_string())
        .args(peer_args)
        .env("CYCLONEDDS_URI", CYCLONE_CONFIG)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("start the Cyclone DDS peer");
    let mut line = String::new();
    BufReader::new(peer.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert_eq!(line.trim(), "ready", "the peer did not start");
    let navdeck = Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(navdeck_args)
        .output()
        .expect("run navdeck");
    // Closing its stdin tells the peer to write down what it got and leave.
    drop(peer.stdin.take());
    assert!(peer.wait().unwrap().success(), "the peer failed");
    assert!(
        navdeck.status.success(),
        "navdeck failed: {}",
        String::from_utf8_lossy(&navdeck.stderr)
    );
    let report: Value = serde_json::from_slice(&navdeck.stdout).unwrap();
    let record: Value = serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
    Some((report, record))
}

const LOOPBACK: &str = "[robot]\ntrack = 0.16\n[ros2]\ninterfaces = [\"127.0.0.1\"]\n";

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn navdeck_drives_a_cyclone_dds_turtlebot_and_reads_its_odometry() {
    let Some((report, record)) = drive(91, "wwwwwwwwwwwwwww", &[], LOOPBACK) else {
        return;
    };
    let cmds = record["cmd_vel"].as_array().unwrap();
    let forward: Vec<&Value> = cmds.iter().filter(|c| f(&c[0]) > 0.0).collect();
    // The first volatile messages may be lost while discovery settles.
    assert!(forward.len() >= 5, "cmd_vel the peer got: {cmds:?}");
    assert!(
        forward
            .iter()
            .all(|c| (f(&c[0]) - 0.15).abs() < 1e-9 && f(&c[1]) == 0.0),
        "0.15 m/s straight ahead (the default teleop speed): {forward:?}"
    );
    let last = cmds.last().unwrap();
    assert_eq!((f(&last[0]), f(&last[1])), (0.0, 0.0), "left stopped");
    // Odometry and wheel joints came back: navdeck knows where the peer drove.
    let peer_x = f(&record["pose"][0]);
    let est_x = f(&report["estimated_pose"]["x"]);
    assert!(peer_x > 0.1, "the peer moved {peer_x:.3} m");
    assert!(
        (est_x - peer_x).abs() < 0.03,
        "navdeck {est_x:.3} vs peer {peer_x:.3}"
    );
    // And RViz's map arrived at a Cyclone reader: 4 m x 4 m at 1 cm.
    let maps = record["maps"].as_array().unwrap();
    assert!(
        maps.iter()
            .any(|m| m[0] == 400 && m[1] == 400 && m[3] == 160_000),
        "maps: {maps:?}"
    );
}

/// A robot's /scan and /odom build navdeck's map under lidar SLAM: the peer, in a room,
/// gets /map with its walls occupied where they are (through the map -> odom transform it
/// also gets on /tf, which stays near identity over the peer's exact odometry). The drive
/// is straight: a scan is paired with the odometry of the poll that takes it, not of its
/// stamp, so turning at teleop's 1.5 rad/s slips the map's heading (2.7° after a quarter
/// turn against this peer's 5 Hz scans, though the first scan after the turn is matched).
#[test]
fn lidar_slam_maps_a_cyclone_turtlebots_room_from_its_scan_and_odometry() {
    let keys = "wwwwwwwwwwwwwwwwwwwwwwwwww";
    let Some((report, record)) =
        drive_with(96, keys, &["--room"], LOOPBACK, &["--estimator", "slam"])
    else {
        return;
    };
    let tf = record["map_to_odom"].as_array().unwrap();
    assert!(!tf.is_empty(), "no map -> odom on /tf: {record}");
    let last = &tf[tf.len() - 1];
    assert!(
        f(&last[0]).hypot(f(&last[1])) < 0.05 && f(&last[2]).abs() < 2f64.to_radians(),
        "map -> odom strays from the exact odometry: {last:?}"
    );
    let check = &record["map_check"];
    // The lidar's map at 5 cm cells, as slam_toolbox publishes it.
    assert!(f(&check["occupied"]) > 100.0, "walls mapped: {check}");
    assert!(
        f(&check["near_walls"]) > 0.9,
        "occupied cells lie on the room's walls (within 5 cm): {check}"
    );
    assert!(
        f(&check["walls_seen"]) > 0.6,
        "the walls are mapped along their length: {check}"
    );
    // navdeck's estimate follows the peer's drive.
    let (px, py) = (f(&record["pose"][0]), f(&record["pose"][1]));
    let (ex, ey) = (
        f(&report["estimated_pose"]["x"]),
        f(&report["estimated_pose"]["y"]),
    );
    assert!(px.hypot(py) > 0.2, "the peer moved: {px:.2} {py:.2}");
    assert!(
        (ex - px).hypot(ey - py) < 0.05,
        "navdeck ({ex:.3}, {ey:.3}) vs peer ({px:.3}, {py:.3})"
    );
}

#[test]
fn a_jazzy_style_peer_gets_twist_stamped() {
    let Some((report, record)) = drive(92, "wwwwwwwwww", &["--stamped"], LOOPBACK) else {
        return;
    };
    let cmds = record["cmd_vel"].as_array().unwrap();
    assert!(
        cmds.iter().filter(|c| f(&c[0]) > 0.0).count() >= 3,
        "TwistStamped commands: {cmds:?}"
    );
    let warnings = report["warnings"].as_array().unwrap();
    assert!(
        warnings.is_empty(),
        "no warnings on a matched link: {warnings:?}"
    );
}

/// navdeck's ROS 2 link on loopback, as `LOOPBACK` configures the headless runs, with
/// `tweak` applied to its config.
fn connect_loopback(
    domain: u16,
    tweak: impl FnOnce(&mut Config),
) -> Result<Ros2Link, navdeck::link::LinkError> {
    let mut config = Config::default();
    config.ros2.interfaces = vec!["127.0.0.1".into()];
    tweak(&mut config);
    Ros2Link::connect(Ros2Options {
        config: config.ros2,
        domain,
        track: config.robot.track,
        max_wheel_speed: config.robot.max_wheel_speed(),
    })
}

fn loopback_link(domain: u16) -> Ros2Link {
    connect_loopback(domain, |_| {}).expect("ROS 2 link")
}

/// What the link reported while polled.
#[derive(Default)]
struct Polled {
    frames: Vec<SensorFrame>,
    notes: Vec<String>,
}

impl Polled {
    fn initial_poses(&self) -> Vec<Pose2> {
        self.frames.iter().filter_map(|f| f.initial_pose).collect()
    }
}

/// Polls `link` every 5 ms, as the console's loop runs, until `done` holds for what it
/// reported; panics with `what` after PATIENCE seconds.
fn poll_until(link: &mut Ros2Link, what: &str, mut done: impl FnMut(&Polled) -> bool) -> Polled {
    let started = Instant::now();
    let mut polled = Polled::default();
    loop {
        let now = started.elapsed().as_secs_f64();
        if let Ok(frame) = link.poll(now) {
            polled.frames.push(frame);
        }
        polled
            .notes
            .extend(link.take_notes().into_iter().map(|n| n.text));
        if done(&polled) {
            return polled;
        }
        assert!(
            now < PATIENCE,
            "gave up waiting for {what}; notes: {:?}; pose estimates: {:?}",
            polled.notes,
            polled.initial_poses()
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

#[test]
fn rviz_pose_estimates_reach_the_link_and_bad_ones_are_refused_with_a_warning() {
    let Some(mut peer) = LinePeer::start("amcl_peer.py", 73) else {
        return;
    };
    let mut link = loopback_link(73);
    poll_until(&mut link, "odometry from the peer", |p| {
        !p.frames.is_empty()
    });

    peer.say("pose map 1.25 -0.5 2.0");
    assert_eq!(peer.next_line("sent"), "sent");
    let got = poll_until(&mut link, "the pose estimate", |p| {
        !p.initial_poses().is_empty()
    });
    let pose = got.initial_poses()[0];
    assert!(
        (pose.x - 1.25).abs() < 1e-6
            && (pose.y + 0.5).abs() < 1e-6
            && (pose.theta - 2.0).abs() < 1e-6,
        "{pose:?}"
    );
    // Applied once: the next frame carries none.
    let next = poll_until(&mut link, "the next frame", |p| !p.frames.is_empty());
    assert_eq!(next.initial_poses(), vec![], "{:?}", next.notes);

    for (line, says) in [
        ("pose odom 3.0 3.0 0.0", "header.frame_id = \"odom\""),
        ("pose map nan 0.0 0.0", "position.x = NaN"),
    ] {
        peer.say(line);
        assert_eq!(peer.next_line("sent"), "sent");
        let refused = poll_until(&mut link, says, |p| {
            p.notes
                .iter()
                .any(|n| n.contains("initialpose") && n.contains(says))
        });
        assert_eq!(refused.initial_poses(), vec![], "{line} was applied");
    }
    assert!(link.label().contains("2 dropped"), "{}", link.label());

    // An empty frame_id counts as the map.
    peer.say("pose - -0.75 0.5 -1.0");
    assert_eq!(peer.next_line("sent"), "sent");
    let got = poll_until(&mut link, "the frameless estimate", |p| {
        !p.initial_poses().is_empty()
    });
    let pose = got.initial_poses()[0];
    assert!(
        (pose.x + 0.75).abs() < 1e-6
            && (pose.y - 0.5).abs() < 1e-6
            && (pose.theta + 1.0).abs() < 1e-6,
        "{pose:?}"
    );
}

#[test]
fn mcl_particles_reach_a_cyclone_reader_as_a_pose_array() {
    let Some(peer) = LinePeer::start("amcl_peer.py", 74) else {
        return;
    };
    // A topic name ROS 2 refuses is refused by its field, before anything is published.
    let err = connect_loopback(74, |c| {
        c.ros2.particle_cloud_topic = "particle cloud".into()
    })
    .err()
    .expect("a bad topic name")
    .to_string();
    assert!(
        err.contains("particle_cloud_topic") && err.contains("\"particle cloud\""),
        "{err}"
    );
    let mut link = loopback_link(74);
    let particles = vec![
        Pose2::new(0.5, 0.25, 0.3),
        Pose2::new(-1.0, 2.0, -2.5),
        Pose2::new(0.0, -0.125, 3.0),
    ];
    let picture = Picture {
        particles: Some(particles.clone()),
        ..Picture::default()
    };
    // Best effort and volatile: clouds shown before discovery matched are lost, so show
    // one a control period until the peer reports one.
    let give_up = Instant::now() + std::time::Duration::from_secs_f64(PATIENCE);
    let cloud = loop {
        link.show(&picture);
        match peer
            .lines
            .recv_timeout(std::time::Duration::from_millis(100))
        {
            Ok(line) => break serde_json::from_str::<Value>(&line).unwrap()["cloud"].clone(),
            Err(_) => assert!(
                Instant::now() < give_up,
                "no particle cloud reached the peer"
            ),
        }
    };
    assert_eq!(cloud["frame"], "map");
    let poses = cloud["poses"].as_array().unwrap();
    assert_eq!(poses.len(), particles.len(), "{poses:?}");
    for (got, want) in poses.iter().zip(&particles) {
        let (x, y, yaw) = (f(&got[0]), f(&got[1]), f(&got[2]));
        assert!(
            (x - want.x).abs() < 1e-9
                && (y - want.y).abs() < 1e-9
                && (yaw - want.theta).abs() < 1e-9,
            "{got:?} vs {want:?}"
        );
    }
}

/// Polls `link` as `poll_until` does until the peer prints a JSON line with `key`, and
/// returns its value; panics with `what` after PATIENCE seconds.
fn poll_until_line(link: &mut Ros2Link, peer: &LinePeer, key: &str, what: &str) -> Value {
    let started = Instant::now();
    loop {
        // Notes stay with the link for a later `poll_until`.
        let _ = link.poll(started.elapsed().as_secs_f64());
        if let Ok(line) = peer.lines.recv_timeout(std::time::Duration::from_millis(5)) {
            let record: Value = serde_json::from_str(&line)
                .unwrap_or_else(|e| panic!("the peer said {line:?}: {e}"));
            if let Some(v) = record.get(key) {
                return v.clone();
            }
        }
        assert!(
            started.elapsed().as_secs_f64() < PATIENCE,
            "gave up waiting for {what}"
        );
    }
}

fn arm_of(polled: &Polled) -> Vec<ArmState> {
    polled.frames.iter().filter_map(|f| f.arm).collect()
}

#[test]
fn an_arm_target_reaches_a_cyclone_controller_and_its_joints_come_back_by_name() {
    let Some(mut peer) = LinePeer::start("arm_peer.py", 75) else {
        return;
    };
    let mut link = connect_loopback(75, |c| c.ros2.arm = true).expect("ROS 2 link");
    poll_until(&mut link, "odometry from the peer", |p| {
        !p.frames.is_empty()
    });

    let target = ArmTarget {
        joints: [0.125, -1.0 / 3.0, 0.7, -0.3],
        within: 2.5,
    };
    let reach = navdeck::data::Command {
        arm: Some(target),
        ..navdeck::data::Command::STOP
    };
    link.send(&reach).unwrap();
    let got = poll_until_line(&mut link, &peer, "trajectory", "the arm trajectory");
    assert_eq!(
        got["names"],
        serde_json::json!(["joint1", "joint2", "joint3", "joint4"])
    );
    let points = got["points"].as_array().unwrap();
    assert_eq!(points.len(), 1, "{got}");
    let positions: Vec<f64> = points[0]["positions"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    assert_eq!(positions.len(), 4, "{got}");
    for (p, want) in positions.iter().zip(target.joints) {
        assert!(
            (p - want).abs() < 1e-9,
            "{positions:?} vs {:?}",
            target.joints
        );
    }
    assert_eq!(
        points[0]["time_from_start"],
        serde_json::json!([2, 500_000_000])
    );
    // Zero: "start on receipt", whatever the robot's clock says.
    assert_eq!(got["stamp"], serde_json::json!([0, 0]));

    // Out of order, beside another joint: matched by name.
    peer.say("joints joint3=0.3 wheel_left_joint=5.0 joint1=0.1 joint4=-0.4 joint2=-0.2");
    assert_eq!(peer.next_line("sent"), "sent");
    let got = poll_until(&mut link, "the arm's joints", |p| !arm_of(p).is_empty());
    assert_eq!(
        arm_of(&got),
        vec![ArmState {
            joints: [0.1, -0.2, 0.3, -0.4]
        }]
    );

    for (line, says) in [
        (
            "joints joint1=0.5 joint2=nan joint3=0 joint4=0",
            "position[1] (joint2) = NaN",
        ),
        (
            "joints joint1=0.5 joint2=0 joint4=0",
            "name lacks \"joint3\"",
        ),
    ] {
        peer.say(line);
        assert_eq!(peer.next_line("sent"), "sent");
        let refused = poll_until(&mut link, says, |p| {
            p.notes
                .iter()
                .any(|n| n.contains("joint_states") && n.contains(says))
        });
        assert_eq!(arm_of(&refused), vec![], "{line} was reported");
    }
    assert!(link.label().contains("2 dropped"), "{}", link.label());
}

#[test]
fn gripper_orders_reach_a_cyclone_action_server_as_goals() {
    let Some(peer) = LinePeer::start("arm_peer.py", 76) else {
        return;
    };
    let mut link = connect_loopback(76, |c| {
        c.ros2.arm = true;
        c.ros2.gripper_max_effort = 2.5;
    })
    .expect("ROS 2 link");
    for (order, position) in [(GripperCommand::Open, 0.01), (GripperCommand::Close, -0.01)] {
        let command = navdeck::data::Command {
            gripper: Some(order),
            ..navdeck::data::Command::STOP
        };
        link.send(&command).unwrap();
        let goal = poll_until_line(&mut link, &peer, "goal", "the gripper goal");
        assert_eq!(
            (f(&goal["position"]), f(&goal["max_effort"])),
            (position, 2.5),
            "{order:?}"
        );
    }
}

#[test]
fn a_gripper_goal_refused_by_an_rmw_cyclonedds_server_is_warned() {
    let Some(peer) = LinePeer::start_with("arm_peer.py", 78, &["--cyclone-mapping", "--reject"])
    else {
        return;
    };
    let mut link = connect_loopback(78, |c| {
        c.ros2.arm = true;
        c.ros2.gripper_action_rmw = Rmw::CycloneDds;
    })
    .expect("ROS 2 link");
    let close = navdeck::data::Command {
        gripper: Some(GripperCommand::Close),
        ..navdeck::data::Command::STOP
    };
    link.send(&close).unwrap();
    let goal = poll_until_line(&mut link, &peer, "goal", "the gripper goal");
    assert_eq!(f(&goal["position"]), -0.01);
    poll_until(&mut link, "the refusal", |p| {
        p.notes
            .iter()
            .any(|n| n.contains("gripper_controller/gripper_cmd refused the gripper goal (close)"))
    });
}

/// Reads the peer's JSON lines until `done` says it has seen enough of them (all lines so
/// far, oldest first); panics with `what` after PATIENCE seconds.
fn peer_lines_until(peer: &LinePeer, what: &str, done: impl Fn(&[Value]) -> bool) -> Vec<Value> {
    let started = Instant::now();
    let mut seen = Vec::new();
    while !done(&seen) {
        let left = PATIENCE - started.elapsed().as_secs_f64();
        assert!(
            left > 0.0,
            "gave up waiting for {what}; the peer said {seen:?}"
        );
        if let Ok(line) = peer
            .lines
            .recv_timeout(std::time::Duration::from_secs_f64(left))
            && let Ok(v) = serde_json::from_str::<Value>(&line)
        {
            seen.push(v);
        }
    }
    seen
}

#[test]
fn a_goal_pose_drives_the_twin_beside_ros2_with_rosout_both_ways_on_localhost_only() {
    let distro = navdeck::link::ros2::environment::built_distro();
    let Some(mut peer) = LinePeer::start_with("graph_peer.py", 93, &[distro]) else {
        return;
    };
    // The peer holds lines and goals until navdeck's readers match.
    peer.say("log 30 turtlebot3_node battery low: 11.1 V");
    peer.say("log 10 turtlebot3_node motor tick");
    peer.say("goal odom 1.0 0.5 0.0");
    peer.say("goal map 1.0 0.5 1.5707963");
    let dir = scratch("graph");
    let cfg = dir.join("navdeck.toml");
    // No [ros2] interfaces: ROS_LOCALHOST_ONLY alone keeps navdeck on loopback.
    std::fs::write(&cfg, "").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(["--ros2", "--domain", "93", "--config"])
        .arg(&cfg)
        .args([
            "--headless",
            "--json",
            "--keys",
            "ffffff",
            "--key-rate",
            "1",
        ])
        .env("ROS_LOCALHOST_ONLY", "1")
        .env_remove("ROS_DISTRO")
        .output()
        .expect("run navdeck");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: Value = serde_json::from_str(&stdout).expect("one JSON report");
    // RViz's goal: planned to and driven, ending facing its heading (within Nav2's 0.25 rad).
    let pose = &report["true_pose"];
    let (x, y, theta) = (f(&pose["x"]), f(&pose["y"]), f(&pose["theta"]));
    assert!(
        (x - 1.0).hypot(y - 0.5) < 0.1,
        "ended at ({x:.2}, {y:.2}): {report}"
    );
    assert!(
        (theta - std::f64::consts::FRAC_PI_2).abs() < 0.3,
        "ended facing {theta:.2} rad"
    );
    let warnings: Vec<&str> = report["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    // The robot's own warning reached the console's log, named by its node; its debug
    // line did not (below [ros2] rosout_level); the goal in another frame was refused.
    assert!(
        warnings.contains(&"[turtlebot3_node] battery low: 11.1 V"),
        "{warnings:?}"
    );
    assert!(!warnings.iter().any(|w| w.contains("motor tick")));
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("ignored a goal on goal_pose") && w.contains("\"odom\"")),
        "{warnings:?}"
    );
    // What the peer saw: navdeck on the node list of its distribution, its log lines on
    // /rosout with their levels, and its state up to the arrival.
    let seen = peer_lines_until(
        &peer,
        "navdeck's node, its arrival and its log of it",
        |seen| {
            let node = seen.iter().any(|v| v["node"] == "/navdeck");
            let arrived = seen.iter().any(|v| {
                v["state"]
                    .as_str()
                    .is_some_and(|s| s.contains("\"navigation\":\"arrived\""))
            });
            // The arrival's /rosout line travels on its own topic: it may come after the state.
            let arrival_logged = seen.iter().any(|v| {
                v["rosout"]["msg"]
                    .as_str()
                    .is_some_and(|m| m.contains("Destination arrived"))
            });
            node && arrived && arrival_logged
        },
    );
    let navdeck_lines: Vec<&Value> = seen
        .iter()
        .filter_map(|v| v.get("rosout"))
        .filter(|r| r["name"] == "navdeck")
        .collect();
    let level_of = |text: &str| {
        navdeck_lines
            .iter()
            .find(|r| r["msg"].as_str().unwrap_or("").contains(text))
            .map(|r| r["level"].as_u64().unwrap())
    };
    assert_eq!(
        level_of("goal pose received"),
        Some(20),
        "{navdeck_lines:?}"
    );
    assert_eq!(level_of("ignored a goal"), Some(30), "{navdeck_lines:?}");
    assert_eq!(level_of("Destination arrived"), Some(20));
    assert_eq!(level_of("discovery on this host only"), Some(20));
    // The robot's lines are not sent back out under navdeck's name.
    assert_eq!(level_of("battery low"), None);
    let states: Vec<Value> = seen
        .iter()
        .filter_map(|v| v["state"].as_str())
        .map(|s| serde_json::from_str(s).unwrap())
        .collect();
    let following = states
        .iter()
        .find(|s| s["navigation"] == "following")
        .expect("a following state");
    assert_eq!(following["mode"], "path_following");
    assert!((f(&following["goal"]["x"]) - 1.0).abs() < 1e-9);
    assert!((f(&following["goal"]["theta"]) - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    assert_eq!(states.last().unwrap()["navigation"], "arrived");
}

/// The pattern big_peer.py fills a 384 x 384 map with (seed 1 in, 2 out).
fn map_cells(seed: usize) -> Vec<i8> {
    (0..384 * 384)
        .map(|i| (((i * 31 + (i / 384) * 7 + seed) % 102) as i64 - 1) as i8)
        .collect()
}

/// The pattern big_peer.py fills images with (seed 3 mono in, 4 rgb in, 5 rgb out).
fn pixels(count: usize, seed: usize) -> Vec<u8> {
    (0..count)
        .map(|i| ((i * 13 + (i / 640) * 5 + seed) & 0xFF) as u8)
        .collect()
}

/// A full-size map and VGA images both ways with `reliability`: navdeck's own map
/// publisher and camera subscription, and the link's endpoints for the rest.
fn big_messages(domain: u16, reliability: Reliability) {
    use navdeck::link::ros2::participant::{Factory, Joined, join, qos_profile, take_all};
    use navdeck::msgs::ros as msgs;
    let name = match reliability {
        Reliability::Reliable => "reliable",
        Reliability::BestEffort => "best_effort",
    };
    let Some(peer) = LinePeer::start_with("big_peer.py", domain, &[name]) else {
        return;
    };
    let qos = Qos {
        reliability,
        depth: 2,
    };
    let mut link = connect_loopback(domain, |c| c.ros2.qos = qos).expect("ROS 2 link");
    let mut config = Config::default();
    config.ros2.interfaces = vec!["127.0.0.1".into()];
    let Joined {
        context: _context,
        namespace,
        mut node,
        ..
    } = join(&config.ros2, domain, "navdeck_big").expect("a second node");
    let mut factory = Factory {
        node: &mut node,
        config: &config.ros2,
        namespace: &namespace,
    };
    let profile = qos_profile(qos, false);
    let map_in = factory
        .subscription::<msgs::OccupancyGrid>(
            "t",
            "big/map_in",
            "nav_msgs",
            "OccupancyGrid",
            profile.clone(),
        )
        .unwrap();
    let rgb_in = factory
        .subscription::<msgs::Image>("t", "big/image_in", "sensor_msgs", "Image", profile.clone())
        .unwrap();
    let rgb_out = factory
        .publisher::<msgs::Image>("t", "big/image_out", "sensor_msgs", "Image", profile)
        .unwrap();
    #[cfg(feature = "vision")]
    let mut camera = {
        let mut c = config.ros2.clone();
        c.scan_qos = qos;
        navdeck::link::ros2::image::Ros2ImageSource::connect(&c, domain, "camera/image_raw")
            .expect("the camera subscription")
    };
    let mut grid = navdeck::map::grid::OccupancyGrid::new(
        384,
        384,
        0.05,
        navdeck::geometry::Point2::new(-10.0, -10.0),
        -1,
    );
    grid.cells = map_cells(2);
    let picture = Picture {
        map: Some(grid),
        ..Picture::default()
    };
    let image = msgs::Image {
        header: msgs::Header::new(msgs::Time::default(), "camera"),
        height: 480,
        width: 640,
        encoding: "rgb8".into(),
        is_bigendian: 0,
        step: 640 * 3,
        data: pixels(640 * 480 * 3, 5),
    };
    let (want_map, want_rgb) = (map_cells(1), pixels(640 * 480 * 3, 4));
    #[cfg(feature = "vision")]
    let want_mono = pixels(640 * 480, 3);
    let (mut map_ok, mut rgb_ok, mut out_map_ok, mut out_image_ok) = (false, false, false, false);
    // Without OpenCV there is no camera subscription to check.
    #[cfg(feature = "vision")]
    let mut mono_ok = false;
    #[cfg(not(feature = "vision"))]
    let mono_ok = true;
    let mut notes = Vec::new();
    let started = Instant::now();
    // Each side sends again every few tenths until the other has one intact copy: best
    // effort may lose a fragment, and so the whole sample, now and then.
    while !(map_ok && rgb_ok && mono_ok && out_map_ok && out_image_ok) {
        assert!(
            started.elapsed().as_secs_f64() < PATIENCE,
            "{name}: map in {map_ok}, image in {rgb_ok}, camera {mono_ok}, map out {out_map_ok}, image out {out_image_ok}"
        );
        link.show(&picture);
        rgb_out.publish(image.clone()).unwrap();
        for m in take_all(&map_in, "map", &mut notes) {
            assert_eq!((m.info.width, m.info.height), (384, 384), "{name}");
            assert!(
                m.data.0 == want_map,
                "{name}: a map arrived with other bytes"
            );
            map_ok = true;
        }
        for m in take_all(&rgb_in, "image", &mut notes) {
            assert_eq!((m.width, m.height, m.step), (640, 480, 1920), "{name}");
            assert!(
                m.data == want_rgb,
                "{name}: an image arrived with other bytes"
            );
            rgb_ok = true;
        }
        #[cfg(feature = "vision")]
        {
            use navdeck::perception::pipeline::FrameSource;
            if let Some(frame) = camera.grab().expect("a readable camera frame") {
                let frame = frame.into_gray();
                assert_eq!((frame.width, frame.height), (640, 480));
                assert!(frame.data == want_mono, "{name}: a frame with other pixels");
                mono_ok = true;
            }
        }
        while let Ok(line) = peer
            .lines
            .recv_timeout(std::time::Duration::from_millis(200))
        {
            let v: Value = serde_json::from_str(&line).unwrap();
            for (key, ok) in [
                ("map_out", &mut out_map_ok),
                ("image_out", &mut out_image_ok),
            ] {
                if let Some(r) = v.get(key) {
                    assert_eq!(r["intact"], true, "{name}: {line}");
                    *ok = true;
                }
            }
        }
    }
    assert!(notes.is_empty(), "{name}: {notes:?}");
}

#[test]
fn a_full_size_map_and_vga_images_cross_both_ways_reliable() {
    big_messages(94, Reliability::Reliable);
}

#[test]
fn a_full_size_map_and_vga_images_cross_both_ways_best_effort() {
    big_messages(95, Reliability::BestEffort);
}
