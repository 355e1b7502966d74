//! The serial link against an emulated ROSArduinoBridge firmware on a pseudo-terminal:
//! the same code a real port runs, with faults injected on the wire.

use crate::common;
use crate::serial_emulator;

use common::until;
use navdeck::app::{App, KeyKind, LinkStatus};
use navdeck::config::Config;
use navdeck::data::{ArmTarget, Command, GripperCommand, GripperState, WheelTravel};
use navdeck::geometry::Twist;
use navdeck::keymap::{Key, Keymap};
use navdeck::link::RobotLink;
use navdeck::link::serial::SerialLink;
use navdeck::link::serial::config::ArmServo;
use serial_emulator::{Emulator, Options};
use std::io::{Read, Write};
use std::time::Duration;

/// Timing for tests on a busy machine: generous replies, quick reconnection.
fn config() -> Config {
    let mut c = Config::default();
    c.serial.reply_timeout = 0.2;
    c.serial.reconnect_every = 0.1;
    c.serial.boot_wait = 2.0;
    c
}

/// Waits (bounded) until the link has noted a line containing `text`.
fn until_note(link: &mut SerialLink, text: &str) {
    let mut notes = Vec::new();
    until(&format!("a note containing {text:?}"), || {
        notes.extend(link.take_notes());
        notes.iter().any(|n| n.text.contains(text))
    });
}

fn forward(v: f64) -> Command {
    Command {
        twist: Twist::new(v, 0.0),
        gripper: None,
        arm: None,
    }
}

/// Sends `command` and polls, as the console's control loop does, until `travel` has
/// covered `metres` on the left wheel.
fn drive(link: &mut SerialLink, emu: &Emulator, command: Command, metres: f64) -> WheelTravel {
    let mut total = WheelTravel::default();
    let mut t = 0.0;
    until("the robot cover the distance", || {
        link.send(&command).expect("link up");
        t += 0.1;
        if let Some(w) = link.poll(t).expect("link up").wheels {
            total.left += w.left;
            total.right += w.right;
        }
        emu.wait_frames(1);
        total.left.abs() >= metres
    });
    total
}

fn ask(port: &mut Box<dyn serialport::SerialPort>, request: &str) -> String {
    port.write_all(format!("{request}\r").as_bytes()).unwrap();
    let mut reply = Vec::new();
    let mut byte = [0u8; 1];
    while !reply.ends_with(b"\r\n") {
        port.read_exact(&mut byte).expect("a reply");
        reply.push(byte[0]);
    }
    String::from_utf8(reply).unwrap().trim_end().to_string()
}

#[test]
fn the_emulator_answers_as_the_firmware_does_and_stops_by_itself() {
    let emu = Emulator::start();
    let mut port = serialport::new(emu.path(), 57600)
        .timeout(Duration::from_secs(5))
        .open()
        .unwrap();
    assert_eq!(ask(&mut port, "b"), "57600");
    assert_eq!(ask(&mut port, "e"), "0 0");
    assert_eq!(ask(&mut port, "u 20:12:0:50"), "OK");
    assert_eq!(ask(&mut port, "x"), "Invalid Command");
    assert_eq!(ask(&mut port, "s 0 45"), "OK");
    assert_eq!(ask(&mut port, "m 10 -10"), "OK");
    // The servo sweeps 6 degrees a frame.
    emu.wait_frames(12);
    let reply = ask(&mut port, "e");
    let (l, r) = reply.split_once(' ').unwrap();
    let (l, r): (i64, i64) = (l.parse().unwrap(), r.parse().unwrap());
    // Counts are whole: the reverse wheel's floor lies one below.
    assert!(l > 10 && (r + l).abs() <= 1, "{reply}");
    assert_eq!(ask(&mut port, "t 0"), "45");
    // No motor command for 2 s: the firmware's auto-stop.
    emu.wait_for("the auto-stop", |s| s.auto_stops == 1 && !s.moving);
    assert_eq!(ask(&mut port, "r"), "OK");
    assert_eq!(ask(&mut port, "e"), "0 0");
}

#[test]
fn driving_forward_sends_equal_tick_targets_and_reads_equal_travel() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot)
        .expect("the emulator answers");
    assert_eq!(link.label(), format!("serial:{}@57600", emu.path()));
    let travel = drive(&mut link, &emu, forward(0.1), 0.05);
    assert!((travel.left - travel.right).abs() < 1e-9, "{travel:?}");
    // 0.1 m/s on seed 001's 0.027216 m wheel with 3436 counts/rev at 30 Hz: 66.97 ticks/frame.
    let targets = emu.state().motor_targets(0);
    let moving: Vec<_> = targets.iter().filter(|t| **t != (0, 0)).collect();
    assert!(!moving.is_empty(), "{targets:?}");
    assert!(
        moving.iter().all(|(l, r)| l == r && (66..=68).contains(l)),
        "{targets:?}"
    );
    let sent = emu.state().requests.len();
    link.stop();
    emu.wait_for("m 0 0 after stop", |s| {
        s.motor_targets(sent).contains(&(0, 0))
    });
    assert!(link.stats().readings > 2);
    drop(link);
    emu.wait_for("the robot at rest", |s| !s.moving);
}

#[test]
fn turning_on_the_spot_sends_opposite_targets() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    let turn = Command {
        twist: Twist::new(0.0, 1.0),
        gripper: None,
        arm: None,
    };
    let travel = drive(&mut link, &emu, turn, 0.01);
    // Equal and opposite within a few counts (one count is 0.05 mm here).
    assert!(
        travel.left < 0.0 && (travel.left + travel.right).abs() < 1.5e-4,
        "{travel:?}"
    );
}

#[test]
fn holding_w_in_the_console_drives_the_robot_and_quitting_stops_it() {
    let emu = Emulator::start();
    let config = config();
    let link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let mut app = App::new(config, Keymap::default_map(), Box::new(link), 0.0);
    let mut t = 0.0;
    until("the console drive the robot", || {
        t += 0.1;
        app.handle_key(Key::char('w'), KeyKind::Press, t);
        app.update(t);
        emu.wait_frames(3);
        app.pilot().odometry_distance() > 0.02
    });
    let targets = emu.state().motor_targets(0);
    assert!(
        targets.iter().any(|(l, r)| l == r && *l > 0),
        "no forward command in {targets:?}"
    );
    assert!(
        targets.iter().all(|(l, r)| l == r && *l >= 0),
        "{targets:?}"
    );
    let sent = emu.state().requests.len();
    app.shutdown("quit by user");
    emu.wait_for("m 0 0 on quit", |s| s.motor_targets(sent).contains(&(0, 0)));
    drop(app);
    let last = *emu.state().motor_targets(0).last().unwrap();
    assert_eq!(last, (0, 0));
}

#[test]
fn a_quiet_console_stops_the_robot() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    link.send(&forward(0.1)).unwrap();
    emu.wait_for("a forward command", |s| s.moving);
    // No further command: the link's own watchdog stops the robot (well before the
    // firmware's 2 s auto-stop, which would count).
    emu.wait_for("the stop", |s| !s.moving);
    assert_eq!(emu.state().auto_stops, 0);
    until_note(&mut link, "no command from the console");
}

#[test]
fn garbage_on_the_wire_is_counted_and_driving_goes_on() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    emu.inject_garbage(b"\xff\xfe#!\r\n12 3");
    until("garbage counted", || link.stats().garbage >= 1);
    let readings = link.stats().readings;
    until("more readings", || link.stats().readings >= readings + 5);
    let travel = drive(&mut link, &emu, forward(0.1), 0.02);
    assert!(travel.right > 0.0);
    until_note(&mut link, "garbage line");
}

#[test]
fn a_dropped_reply_is_asked_again() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    emu.drop_next_reply();
    until("a timeout and a retry", || {
        let s = link.stats();
        s.timeouts >= 1 && s.retries >= 1
    });
    let readings = link.stats().readings;
    until("more readings", || link.stats().readings >= readings + 3);
    assert!(link.poll(1.0).is_ok());
}

#[test]
fn a_slow_reply_times_out_and_the_link_carries_on() {
    let emu = Emulator::start();
    let mut config = config();
    config.serial.reply_timeout = 0.1;
    let mut link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    emu.delay_next_reply(Duration::from_millis(300));
    until("a timeout", || link.stats().timeouts >= 1);
    let travel = drive(&mut link, &emu, forward(0.1), 0.02);
    assert!((travel.left - travel.right).abs() < 1e-9);
    assert!(link.poll(9.0).is_ok());
}

#[test]
fn an_encoder_jump_is_rejected_not_driven() {
    let emu = Emulator::start();
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    let readings = link.stats().readings;
    until("a baseline reading", || link.stats().readings > readings);
    emu.jump_left(1.0e6);
    until("the jump rejected", || link.stats().jumps == 1);
    let frame = link.poll(1.0).unwrap();
    let left = frame.wheels.map_or(0.0, |w| w.left);
    assert!(left.abs() < 1e-9, "a standing robot travelled {left} m");
    until_note(&mut link, "encoder jump");
}

#[test]
fn counters_wrapping_round_are_still_travel() {
    let emu = Emulator::start();
    emu.set_counts(2_147_483_000.0, -2_147_483_000.0);
    let mut link = SerialLink::open(&emu.path(), &config().serial, &config().robot).unwrap();
    let travel = drive(&mut link, &emu, forward(0.1), 0.05);
    let (l, _) = emu.state().counts();
    assert!(l < 0, "the left counter has wrapped: {l}");
    assert!((travel.left - travel.right).abs() < 1e-9 && travel.left > 0.0);
    assert_eq!(link.stats().jumps, 0);
}

#[test]
fn the_gripper_is_reported_moving_then_where_the_servo_says() {
    let emu = Emulator::start();
    let mut config = config();
    config.serial.gripper_servo = Some(1);
    let mut link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let open = Command {
        twist: Twist::ZERO,
        gripper: Some(GripperCommand::Open),
        arm: None,
    };
    link.send(&open).unwrap();
    let mut seen = Vec::new();
    until("the gripper open", || {
        let g = link.poll(0.0).unwrap().gripper;
        if seen.last() != Some(&g) {
            seen.push(g);
        }
        g == Some(GripperState::Open)
    });
    assert!(seen.contains(&Some(GripperState::Opening)), "{seen:?}");
    assert!(emu.state().requests.iter().any(|r| r == "s 1 90"));
    assert_eq!(emu.state().servo_angle[1], 90.0);
}

/// Four arm servos: indices 4..=7, zeros and directions that differ.
fn arm_servos() -> Vec<ArmServo> {
    [(4, 90.0, 1), (5, 90.0, -1), (6, 30.0, 1), (7, 150.0, -1)]
        .map(|(index, zero_deg, direction)| ArmServo {
            index,
            zero_deg,
            direction,
        })
        .to_vec()
}

#[test]
fn an_arm_target_becomes_one_servo_write_per_joint_and_a_clamped_one_is_warned() {
    let emu = Emulator::start();
    let mut config = config();
    config.serial.gripper_servo = Some(1);
    config.serial.arm_servos = arm_servos();
    config.validate(std::path::Path::new("arm.toml")).unwrap();
    let mut link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let reach = Command {
        arm: Some(ArmTarget {
            joints: [
                std::f64::consts::FRAC_PI_4,
                std::f64::consts::FRAC_PI_4,
                -0.5,
                std::f64::consts::FRAC_PI_6,
            ],
            within: 1.5,
        }),
        ..forward(0.1)
    };
    // Every control period repeats the target while the robot drives.
    let travel = drive(&mut link, &emu, reach, 0.02);
    assert!(travel.left > 0.0);
    // 90 + 45, 90 - 45, 30 - 28.6 (-0.5 rad), 150 - 30: once each, however often asked.
    let want = vec![(4, 135), (5, 45), (6, 1), (7, 120)];
    assert_eq!(emu.state().servo_writes, want);

    // 2 rad on joint 1 is 90 + 114.6 degrees: beyond the servo, so 180 and a warning.
    let far = Command {
        arm: Some(ArmTarget {
            joints: [2.0, std::f64::consts::FRAC_PI_4, -0.5, 0.52],
            within: 1.5,
        }),
        ..forward(0.0)
    };
    link.send(&far).unwrap();
    until_note(&mut link, "clamped to 180");
    emu.wait_for("the clamped write", |s| s.servo_writes.len() > want.len());
    // Joint 4 moved 0.24 degrees (0.52 rad is 29.79): not worth a write.
    assert_eq!(emu.state().servo_writes[want.len()..], [(4, 180)]);
    emu.wait_for("servo 4 at its end stop", |s| s.servo_angle[4] == 180.0);
    assert_eq!(emu.state().servo_angle[5], 45.0);
}

#[test]
fn a_firmware_without_servos_is_named_and_driving_goes_on() {
    let emu = Emulator::start_with(Options {
        servos: false,
        ..Options::default()
    });
    let mut config = config();
    config.serial.gripper_servo = Some(0);
    let mut link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let close = Command {
        twist: Twist::ZERO,
        gripper: Some(GripperCommand::Close),
        arm: None,
    };
    link.send(&close).unwrap();
    until_note(&mut link, "USE_SERVOS");
    assert!(link.stats().refused >= 1);
    let travel = drive(&mut link, &emu, forward(0.1), 0.02);
    assert!(travel.left > 0.0);
}

#[test]
fn unplugging_loses_the_link_and_plugging_back_in_restores_it_without_moving() {
    let emu = Emulator::start();
    let config = config();
    let link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let mut app = App::new(config, Keymap::default_map(), Box::new(link), 0.0);
    let mut t = 0.0;
    let mut step = |app: &mut App, key: Option<char>| {
        t += 0.1;
        if let Some(c) = key {
            app.handle_key(Key::char(c), KeyKind::Press, t);
        }
        app.update(t);
        emu.wait_frames(3);
    };
    until("driving", || {
        step(&mut app, Some('w'));
        app.pilot().odometry_distance() > 0.02
    });
    let driven = app.pilot().odometry_distance();
    emu.unplug();
    until("LINK LOST", || {
        step(&mut app, Some('w'));
        matches!(app.pilot().link_status(), LinkStatus::Lost(_))
    });
    assert_eq!(app.pilot().commanded(), Twist::ZERO);
    emu.replug();
    let plugged_at = emu.state().requests.len();
    until("the link back", || {
        step(&mut app, None);
        *app.pilot().link_status() == LinkStatus::Back
    });
    // Data flows again but nothing moves until the user presses a key.
    for _ in 0..5 {
        step(&mut app, None);
    }
    let after = emu.state().motor_targets(plugged_at);
    assert!(after.iter().all(|t| *t == (0, 0)), "{after:?}");
    assert!(!emu.state().moving);
    // The session goes on: what was driven is kept, and a key drives again.
    assert!(app.pilot().odometry_distance() >= driven);
    until("driving again", || {
        step(&mut app, Some('w'));
        emu.state().moving
    });
    assert_eq!(*app.pilot().link_status(), LinkStatus::Ok);
    let log: Vec<String> = app.log_book().iter().map(|e| e.text.clone()).collect();
    assert!(log.iter().any(|l| l.contains("link back")), "{log:?}");
    assert!(log.iter().any(|l| l.contains("reconnected")), "{log:?}");
}

#[test]
fn a_wrong_path_or_a_silent_device_is_refused_with_a_reason() {
    let e = SerialLink::open(
        "/dev/nonexistent-navdeck-tty",
        &config().serial,
        &config().robot,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("/dev/nonexistent-navdeck-tty"), "{e}");
    let silent = Emulator::start_with(Options {
        silent: true,
        ..Options::default()
    });
    let mut config = config();
    config.serial.boot_wait = 0.5;
    let e = SerialLink::open(&silent.path(), &config.serial, &config.robot)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("no answer to `b`") && e.contains("57600"), "{e}");
}

#[test]
fn the_headless_runner_drives_a_serial_robot_and_stops_it() {
    let emu = Emulator::start();
    let dir = std::env::temp_dir().join(format!("navdeck-headless-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let config = dir.join("serial.toml");
    std::fs::write(&config, "[serial]\nreply_timeout = 0.2\n").unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(["--link", &format!("serial:{}@57600", emu.path())])
        .args(["--config", config.to_str().unwrap()])
        .args(["--headless", "--keys", "wwwwwwww", "--json"])
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert!(
        report["link"].as_str().unwrap().starts_with("serial:"),
        "{report}"
    );
    assert!(
        report["odometry_distance"].as_f64().unwrap() > 0.01,
        "{report}"
    );
    let state = emu.state();
    let targets = state.motor_targets(0);
    assert!(targets.iter().any(|(l, r)| l == r && *l > 0), "{targets:?}");
    assert_eq!(targets.last(), Some(&(0, 0)));
    assert!(!state.moving);
}

#[test]
fn the_readme_serial_config_parses() {
    let readme = include_str!("../README.md");
    let start = readme
        .find("```toml\n[robot]\nwheel_radius")
        .expect("the serial example")
        + "```toml\n".len();
    let len = readme[start..].find("```").unwrap();
    let config = Config::parse(
        &readme[start..start + len],
        std::path::Path::new("README.md"),
    )
    .unwrap();
    assert_eq!(config.serial.counts_per_rev, 1320.0);
    assert_eq!(config.serial.gripper_servo, Some(0));
}

#[test]
fn bad_serial_settings_are_refused_by_name() {
    let path = std::path::Path::new("robot.toml");
    for (text, field) in [
        ("[serial]\ncounts_per_rev = 0\n", "serial.counts_per_rev"),
        ("[serial]\nrefresh = 3.0\n", "serial.refresh"),
        (
            "[serial]\ngripper_open_deg = 200\n",
            "serial.gripper_open_deg",
        ),
        ("[serial]\npoll_hz = -5\n", "serial.poll_hz"),
        ("[serial]\npoll_hz = 0.5\n", "serial.poll_hz"),
        ("[serial]\nreply_timeout = 1e300\n", "serial.reply_timeout"),
    ] {
        let e = Config::parse(text, path).unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
    let e = Config::parse("[serial]\ngripper_servo = 300\n", path)
        .unwrap_err()
        .to_string();
    assert!(e.contains("gripper_servo"), "{e}");
    // Arm servos: four or none, each named with its value when it is wrong.
    let servo = |i: i64, zero: f64, dir: i64| {
        format!("{{ index = {i}, zero_deg = {zero:?}, direction = {dir} }}")
    };
    let arm = |servos: &[String]| format!("[serial]\narm_servos = [{}]\n", servos.join(", "));
    let good: Vec<String> = (0..4).map(|i| servo(4 + i, 90.0, 1)).collect();
    assert_eq!(
        Config::parse(&arm(&good), path)
            .unwrap()
            .serial
            .arm_servos
            .len(),
        4
    );
    for (k, bad, field, value) in [
        (0, servo(16, 90.0, 1), "serial.arm_servos[0].index", "= 16:"),
        (
            2,
            servo(6, 200.0, 1),
            "serial.arm_servos[2].zero_deg",
            "= 200:",
        ),
        (
            3,
            servo(7, 90.0, 0),
            "serial.arm_servos[3].direction",
            "= 0:",
        ),
        (1, servo(4, 90.0, 1), "serial.arm_servos[1].index", "= 4:"),
    ] {
        let mut servos = good.clone();
        servos[k] = bad;
        let e = Config::parse(&arm(&servos), path).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains(value), "{e}");
    }
    let e = Config::parse(&arm(&good[..3]), path)
        .unwrap_err()
        .to_string();
    assert!(e.contains("serial.arm_servos") && e.contains("= 3:"), "{e}");
}
