//! navdeck against a robot on Eclipse Cyclone DDS (the DDS ROS 2 ships), played by
//! tests/interop/turtlebot_peer.py with ROS 2's wire types: headless navdeck drives it
//! over `--link ros2`, and both sides check what crossed.
//!
//! Needs a Python with the PyPI `cyclonedds` package: `NAVDECK_PYTHON` names it
//! (./scripts/test makes a virtualenv and sets it, with NAVDECK_REQUIRE_INTEROP=1 so
//! that a missing peer fails the run instead of skipping).

use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// Cyclone on loopback only: no multicast, unicast discovery to 127.0.0.1.
const CYCLONE_CONFIG: &str = "<CycloneDDS><Domain Id=\"any\"><General><Interfaces>\
<NetworkInterface name=\"lo\"/></Interfaces><AllowMulticast>false</AllowMulticast>\
</General><Discovery><ParticipantIndex>auto</ParticipantIndex>\
<MaxAutoParticipantIndex>20</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/>\
</Peers></Discovery></Domain></CycloneDDS>";

fn python() -> Option<String> {
    match std::env::var("NAVDECK_PYTHON") {
        Ok(p) if !p.is_empty() => Some(p),
        _ => {
            assert!(
                std::env::var_os("NAVDECK_REQUIRE_INTEROP").is_none(),
                "NAVDECK_PYTHON is not set: the Cyclone DDS peer cannot run"
            );
            eprintln!(
                "skipped: set NAVDECK_PYTHON to a Python with cyclonedds (./scripts/test does)"
            );
            None
        }
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("navdeck-interop-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the peer on `domain`, drives it with `keys` through headless navdeck, and
/// returns (navdeck's JSON report, the peer's JSON record).
fn drive(domain: u16, keys: &str, peer_args: &[&str], config: &str) -> Option<(Value, Value)> {
    let python = python()?;
    let dir = scratch(&domain.to_string());
    let out = dir.join("peer.json");
    let cfg = dir.join("navdeck.toml");
    std::fs::write(&cfg, config).unwrap();
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/interop/turtlebot_peer.py"
    );
    let mut peer = Command::new(&python)
        .arg(script)
        .arg(domain.to_string())
        .arg(&out)
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
        .args([
            "--link",
            "ros2",
            "--domain",
            &domain.to_string(),
            "--config",
        ])
        .arg(&cfg)
        .args(["--headless", "--json", "--keys", keys])
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
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
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
