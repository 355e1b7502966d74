//! `navdeck ros2 topics` against a small ROS 2 graph on Eclipse Cyclone DDS, played by
//! tests/interop/topics_peer.py with ROS 2's wire types: /odom at 20 Hz, and the three
//! mismatches that silently break a link (two types on /cmd_vel, a reliable subscriber
//! of a best-effort /scan, a transient-local subscriber of a volatile /map). Also the
//! refusals of a bad domain or config, which need no peer.
//!
//! Needs a Python with the PyPI `cyclonedds` package: `NAVDECK_PYTHON` names it
//! (./scripts/test sets it, with NAVDECK_REQUIRE_INTEROP=1 so that a missing peer fails
//! the run instead of skipping).

use crate::common;
use crate::cyclone_peer;

use common::scratch;
use cyclone_peer::LinePeer;
use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

/// A domain no other test joins.
const DOMAIN: u16 = 147;

/// navdeck on loopback only, as the peer.
const LOOPBACK: &str = "[ros2]\ninterfaces = [\"127.0.0.1\"]\n";

fn config(name: &str, text: &str) -> PathBuf {
    let path = scratch(name).join("navdeck.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn navdeck(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_navdeck"));
    c.args(args).env_remove("ROS_DOMAIN_ID");
    c
}

fn run(c: &mut Command) -> Output {
    c.output().expect("run navdeck")
}

fn topic<'a>(report: &'a Value, name: &str) -> &'a Value {
    (report["topics"].as_array().unwrap().iter())
        .find(|t| t["name"] == name)
        .unwrap_or_else(|| panic!("no {name} in {report:#}"))
}

fn flags(topic: &Value) -> Vec<&str> {
    (topic["flags"].as_array().unwrap().iter())
        .map(|f| f.as_str().unwrap())
        .collect()
}

#[test]
fn the_table_shows_every_topic_its_rate_and_each_mismatch() {
    let Some(_peer) = LinePeer::start("topics_peer.py", DOMAIN) else {
        return;
    };
    let cfg = config("graph", LOOPBACK);
    let domain = DOMAIN.to_string();
    let out = run(navdeck(&[
        "ros2",
        "topics",
        "--domain",
        &domain,
        "--duration",
        "2",
        "--json",
        "--config",
    ])
    .arg(&cfg));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "navdeck failed: {stderr}");
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["domain"], DOMAIN);
    // Only ROS topics without --all: no DDS built-ins, no ros_discovery_info, no services.
    for t in report["topics"].as_array().unwrap() {
        let name = t["name"].as_str().unwrap();
        assert!(name.starts_with('/'), "{name} is not a ROS topic");
    }

    let odom = topic(&report, "/odom");
    assert_eq!(odom["types"], serde_json::json!(["nav_msgs/msg/Odometry"]));
    assert_eq!(
        (odom["publishers"].as_u64(), odom["subscribers"].as_u64()),
        (Some(1), Some(0))
    );
    let rate = odom["rate_hz"].as_f64().expect("a rate for /odom");
    assert!(
        (12.0..=28.0).contains(&rate),
        "/odom at {rate} Hz, the peer sends 20"
    );
    assert_eq!(odom["qos"]["publishers"][0]["reliability"], "reliable");
    assert_eq!(odom["qos"]["publishers"][0]["durability"], "volatile");
    assert!(flags(odom).is_empty(), "{odom:#}");

    let cmd_vel = topic(&report, "/cmd_vel");
    assert_eq!(
        cmd_vel["types"],
        serde_json::json!(["geometry_msgs/msg/Twist", "geometry_msgs/msg/TwistStamped"])
    );
    assert_eq!(
        (
            cmd_vel["publishers"].as_u64(),
            cmd_vel["subscribers"].as_u64()
        ),
        (Some(1), Some(1))
    );
    assert_eq!(flags(cmd_vel), ["type: Twist pub vs TwistStamped sub"]);

    let scan = topic(&report, "/scan");
    assert_eq!(scan["qos"]["publishers"][0]["reliability"], "best_effort");
    assert_eq!(scan["qos"]["subscribers"][0]["reliability"], "reliable");
    assert_eq!(
        flags(scan),
        ["reliability: reliable sub vs best-effort pub (never match)"]
    );

    let map = topic(&report, "/map");
    assert_eq!(
        map["qos"]["subscribers"][0]["durability"],
        "transient_local"
    );
    assert_eq!(
        flags(map),
        ["durability: transient-local sub vs volatile pub (never match)"]
    );

    // A subscriber alone is counted, not flagged, and has no rate.
    let goal = topic(&report, "/goal_pose");
    assert_eq!(
        (goal["publishers"].as_u64(), goal["subscribers"].as_u64()),
        (Some(0), Some(1))
    );
    assert!(flags(goal).is_empty(), "{goal:#}");
    assert!(goal["rate_hz"].is_null());

    // The same as a table.
    let out = run(navdeck(&[
        "ros2",
        "topics",
        "--domain",
        &domain,
        "--duration",
        "2",
        "--config",
    ])
    .arg(&cfg));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    for column in ["TOPIC", "TYPE", "PUB", "SUB", "HZ", "QOS", "FLAGS"] {
        assert!(header.contains(column), "{text}");
    }
    let odom = lines
        .find(|l| l.starts_with("/odom "))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(odom.contains("nav_msgs/msg/Odometry"), "{text}");
    assert!(
        text.contains("type: Twist pub vs TwistStamped sub"),
        "{text}"
    );
}

#[test]
fn a_bad_domain_or_config_is_refused_by_name() {
    let refused = |out: Output, names: &[&str]| {
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "accepted; stderr {err}");
        assert!(!err.contains("panicked"), "{err}");
        for name in names {
            assert!(err.contains(name), "{name} not in: {err}");
        }
    };
    refused(
        run(&mut navdeck(&["ros2", "topics", "--domain", "999"])),
        &["--domain", "999"],
    );
    refused(
        run(navdeck(&["ros2", "topics"]).env("ROS_DOMAIN_ID", "lab")),
        &["ROS_DOMAIN_ID", "lab"],
    );
    refused(
        run(&mut navdeck(&["--domain", "5", "ros2", "topics"])),
        &["--domain", "ros2 topics"],
    );
    refused(
        run(&mut navdeck(&["ros2", "topics", "--duration", "0"])),
        &["--duration"],
    );
    let cfg = config("bad", "[ros2]\ninterfaces = [\"lab-router\"]\n");
    refused(
        run(navdeck(&[
            "ros2",
            "topics",
            "--domain",
            &DOMAIN.to_string(),
            "--config",
        ])
        .arg(&cfg)),
        &["interfaces", "lab-router"],
    );
}

#[test]
fn ros2_robots_lists_each_namespaced_turtlebot_and_no_other_topic() {
    let domain = 148u16;
    let Some(_peer) = LinePeer::start("fleet_peer.py", domain) else {
        return;
    };
    let cfg = config("fleet", LOOPBACK);
    let d = domain.to_string();
    let args = [
        "ros2",
        "robots",
        "--domain",
        &d,
        "--duration",
        "2",
        "--config",
    ];
    let out = run(navdeck(&args).arg(&cfg).arg("--json"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    let robots = report["robots"].as_array().unwrap();
    let names: Vec<&str> = robots
        .iter()
        .map(|r| r["namespace"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["/tb3_0", "/tb3_1"], "{report:#}");
    let rate = robots[0]["odom_rate_hz"].as_f64().expect("odometry's rate");
    assert!(
        (12.0..=28.0).contains(&rate),
        "{rate} Hz, the peer sends 20"
    );
    assert_eq!(
        robots[0]["cmd_vel_types"],
        serde_json::json!(["geometry_msgs/msg/Twist"])
    );
    assert_eq!(
        robots[1]["cmd_vel_types"],
        serde_json::json!(["geometry_msgs/msg/TwistStamped"])
    );
    assert_eq!(
        (robots[0]["scan"].as_bool(), robots[0]["camera"].as_bool()),
        (Some(true), Some(false))
    );
    assert_eq!(robots[1]["camera"].as_bool(), Some(true));
    // The table says how to drive each.
    let out = run(navdeck(&args).arg(&cfg));
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(table.contains("--link ros2 --ns /tb3_1"), "{table}");
    assert!(!table.contains("chatter"), "{table}");
}
