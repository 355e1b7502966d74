//! navdeck's recordings as a ROS 2 tool outside navdeck reads them: headless navdeck
//! explores the built-in twin with `--record`, then tests/interop/mcap_check.py decodes
//! the MCAP file with the PyPI `mcap` reader and `mcap-ros2-support` decoder, and what it
//! found is held against navdeck's own report. A recording cut short must still give up
//! its messages, to Python and to `navdeck replay`.
//!
//! Needs a Python with `mcap` and `mcap-ros2-support`: `NAVDECK_PYTHON` names it
//! (./scripts/test makes a virtualenv and sets it, with NAVDECK_REQUIRE_INTEROP=1 so that
//! a missing Python fails the run instead of skipping).

use crate::common;
use crate::python_support;

use common::scratch;
use navdeck::config::Config;
use serde_json::Value;
use std::f64::consts::PI;
use std::path::Path;
use std::process::Command;

fn python() -> Option<String> {
    python_support::python("the MCAP reader in Python", "mcap and mcap-ros2-support")
}

/// Runs headless navdeck on the twin with `keys`, recording to `file`; its JSON report.
fn record(keys: &str, file: &Path) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(["--headless", "--json", "--keys", keys, "--record"])
        .arg(file)
        .output()
        .expect("run navdeck");
    assert!(
        out.status.success(),
        "navdeck failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(file.is_file(), "no recording at {}", file.display());
    serde_json::from_slice(&out.stdout).expect("navdeck's JSON report")
}

/// What tests/interop/mcap_check.py makes of `file`.
pub(crate) fn check(python: &str, file: &Path) -> Value {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/interop/mcap_check.py");
    let out = Command::new(python)
        .arg(script)
        .arg(file)
        .output()
        .expect("run the Python MCAP check");
    assert!(
        out.status.success(),
        "mcap_check.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("mcap_check.py's JSON")
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn n(v: &Value) -> u64 {
    v.as_u64().unwrap_or_else(|| panic!("not a count: {v}"))
}

/// The difference of two angles, in (-π, π].
fn angle_diff(a: f64, b: f64) -> f64 {
    let d = a - b;
    d.sin().atan2(d.cos())
}

/// The transform `parent` -> `child` of the last /tf message: (x, y, yaw).
fn transform(tf: &Value, parent: &str, child: &str) -> (f64, f64, f64) {
    let t = tf
        .as_array()
        .expect("a /tf message")
        .iter()
        .find(|t| t["parent"] == parent && t["child"] == child)
        .unwrap_or_else(|| panic!("no {parent} -> {child} in the last /tf: {tf}"));
    (f(&t["x"]), f(&t["y"]), f(&t["yaw"]))
}

#[test]
fn python_decodes_a_recorded_exploration_as_ros2() {
    let Some(python) = python() else {
        return;
    };
    let dir = scratch("explore");
    let file = dir.join("explore.mcap");
    let report = record("e", &file);
    let got = check(&python, &file);
    let defaults = Config::default();

    assert_eq!(got["profile"], "ros2", "{got}");
    assert!(
        got["library"].as_str().unwrap().starts_with("navdeck"),
        "{}",
        got["library"]
    );
    assert_eq!(
        got["recovered"], false,
        "a whole file needs no recovery: {got}"
    );
    assert_eq!(got["decode_errors"], Value::Array(vec![]));

    // Every channel: a ros2msg schema and CDR messages.
    let channels = got["channels"].as_object().unwrap();
    assert!(!channels.is_empty());
    for (topic, c) in channels {
        assert_eq!(c["schema_encoding"], "ros2msg", "{topic}");
        assert_eq!(c["message_encoding"], "cdr", "{topic}");
    }

    // The same topics, types and counts as the report says were written.
    let topics = report["recording"]["topics"].as_array().unwrap();
    let mut total = 0;
    for entry in topics {
        let (topic, ty, count) = (entry[0].as_str().unwrap(), &entry[1], n(&entry[2]));
        total += count;
        let decoded = got["counts"].get(topic).map_or(0, n);
        assert_eq!(
            decoded, count,
            "{topic}: Python decoded {decoded}, navdeck wrote {count}"
        );
        if count > 0 {
            assert_eq!(&channels[topic]["schema"], ty, "{topic}");
        }
    }
    for topic in got["counts"].as_object().unwrap().keys() {
        assert!(
            topics.iter().any(|e| e[0] == topic.as_str()),
            "{topic} is not in the report"
        );
    }
    assert_eq!(n(&got["messages"]), total);
    // navdeck's own reader finds the same messages and no damage.
    let raw = navdeck::record::reader::read(&std::fs::read(&file).unwrap());
    assert_eq!(raw.damage, None);
    assert_eq!(raw.messages.len() as u64, total);

    // The last estimate is the pose the report ends on.
    let estimate = &got["estimate"];
    let pose = &report["estimated_pose"];
    assert_eq!(estimate["frame_id"], "map");
    assert!(
        (f(&estimate["x"]) - f(&pose["x"])).abs() < 1e-12,
        "{estimate} vs {pose}"
    );
    assert!(
        (f(&estimate["y"]) - f(&pose["y"])).abs() < 1e-12,
        "{estimate} vs {pose}"
    );
    assert!(
        angle_diff(f(&estimate["yaw"]), f(&pose["theta"])).abs() < 1e-9,
        "{estimate} vs {pose}"
    );

    // map -> odom after odom -> base_link puts the robot at the estimate (REP-105).
    let (mx, my, myaw) = transform(&got["tf"], "map", "odom");
    let (ox, oy, oyaw) = transform(&got["tf"], "odom", "base_link");
    let x = mx + myaw.cos() * ox - myaw.sin() * oy;
    let y = my + myaw.sin() * ox + myaw.cos() * oy;
    assert!(
        (x - f(&pose["x"])).abs() < 1e-9,
        "tf gives x {x}, estimate {pose}"
    );
    assert!(
        (y - f(&pose["y"])).abs() < 1e-9,
        "tf gives y {y}, estimate {pose}"
    );
    assert!(
        angle_diff(myaw + oyaw, f(&pose["theta"])).abs() < 1e-9,
        "tf gives yaw {}, estimate {pose}",
        myaw + oyaw
    );

    // /odom is the wheels' dead reckoning, the same pose as odom -> base_link.
    let odom = &got["odom"];
    assert_eq!(odom["frame_id"], "odom");
    assert_eq!(odom["child_frame_id"], "base_link");
    assert!((f(&odom["x"]) - ox).abs() < 1e-12 && (f(&odom["y"]) - oy).abs() < 1e-12);
    assert!(angle_diff(f(&odom["yaw"]), oyaw).abs() < 1e-9);

    // The robot drove, within its limits: exploration cruises at [plan] max_speed
    // (0.2 m/s by default), under the base's max_linear.
    let cmd = &got["cmd_vel"];
    let (linear, angular) = (f(&cmd["max_abs_linear_x"]), f(&cmd["max_abs_angular_z"]));
    assert!(linear > 0.0, "the robot never drove: {cmd}");
    assert!(linear <= 0.26, "{cmd}");
    assert!(linear <= defaults.robot.max_linear + 1e-9, "{cmd}");
    assert!(angular <= defaults.robot.max_angular + 1e-9, "{cmd}");

    // The twin's lidar, as its defaults say: a full turn of beams from -π.
    let lidar = &defaults.sim.lidar;
    let scan = &got["scan"];
    assert_eq!(n(&scan["ranges"]), u64::from(lidar.beams), "{scan}");
    assert_eq!(lidar.beams, 360);
    assert!(
        (f(&scan["range_max"]) - lidar.max_range).abs() < 1e-6,
        "{scan}"
    );
    assert!((f(&scan["range_max"]) - 3.5).abs() < 1e-6, "{scan}");
    assert!(
        (f(&scan["range_min"]) - lidar.min_range).abs() < 1e-6,
        "{scan}"
    );
    assert!((f(&scan["angle_min"]) + PI).abs() < 1e-6, "{scan}");
    assert!(
        (f(&scan["angle_increment"]) - 2.0 * PI / f64::from(lidar.beams)).abs() < 1e-6,
        "{scan}"
    );
    assert!(n(&scan["finite_ranges"]) > 0, "every beam missed: {scan}");

    // The belief map: consistent sizes, the [map] resolution, walls and free floor.
    let map = &got["map"];
    assert_eq!(map["frame_id"], "map");
    assert_eq!(
        n(&map["width"]) * n(&map["height"]),
        n(&map["data"]),
        "{map}"
    );
    assert!(
        (f(&map["resolution"]) - defaults.map.resolution).abs() < 1e-6,
        "{map}"
    );
    assert!(n(&map["occupied"]) > 0, "{map}");
    assert!(n(&map["free"]) > 0, "{map}");
    assert_eq!(
        n(&map["unknown"]) + n(&map["free"]) + n(&map["occupied"]),
        n(&map["data"]),
        "cells outside -1..=100: {map}"
    );

    // /rosout opens with navdeck's greeting, at INFO.
    let first = &got["rosout"]["first"][0];
    assert_eq!(n(&first[0]), 20, "{first}");
    assert!(
        first[1].as_str().unwrap().starts_with("navdeck "),
        "{first}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_recording_cut_short_still_reads_in_python_and_replays() {
    let Some(python) = python() else {
        return;
    };
    let dir = scratch("cut");
    let whole = dir.join("whole.mcap");
    let report = record("e", &whole);
    let bytes = std::fs::read(&whole).unwrap();
    assert_eq!(n(&report["recording"]["bytes"]), bytes.len() as u64);
    let written: u64 = report["recording"]["topics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| n(&e[2]))
        .sum();
    // As a crash would leave it: no summary, no footer, the last record torn.
    let cut = dir.join("cut.mcap");
    let keep = bytes.len() * 6 / 10;
    std::fs::write(&cut, &bytes[..keep]).unwrap();

    let got = check(&python, &cut);
    assert_eq!(got["profile"], "ros2", "{got}");
    assert_eq!(got["recovered"], true, "the footer is gone: {got}");
    assert!(got["summary_error"].is_string(), "{got}");
    let messages = n(&got["messages"]);
    assert!(messages > 0, "nothing recovered: {got}");
    assert!(
        messages < written,
        "{messages} of {written} from 60% of the file"
    );
    assert_eq!(got["decode_errors"], Value::Array(vec![]));
    // Python and navdeck's forgiving reader stop at the same torn record.
    let raw = navdeck::record::reader::read(&bytes[..keep]);
    assert_eq!(raw.messages.len() as u64, messages);
    let damage = raw.damage.expect("the cut is named");
    assert!(damage.starts_with("offset "), "{damage}");

    let out = Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .arg("replay")
        .arg(&cut)
        .args(["--headless", "--json"])
        .output()
        .expect("run navdeck replay");
    assert!(
        out.status.success(),
        "replay of a cut recording failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let replayed: Value = serde_json::from_slice(&out.stdout).expect("replay's JSON report");
    let warnings = replayed["warnings"].as_array().expect("warnings");
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().is_some_and(|w| w.contains("offset"))),
        "no warning names the damage: {warnings:?}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
