//! A fleet over ROS 2 namespaces: headless navdeck with `--ns` once per robot drives N
//! stand-in TurtleBot3s (tests/interop/fleet_drive_peer.py, robot k under /tb3_k) on
//! Eclipse Cyclone DDS. Each gets a goal and reaches it; robot 0 goes silent on the way
//! and the others drive on; the stop-all key brings every robot's cmd_vel to zero.

use crate::common::scratch;
use serde_json::Value;
use std::ffi::OsString;

/// Most time from the stop-all key to a robot's first zero cmd_vel (the bar).
const STOP_WITHIN: f64 = 0.2;

/// Runs `n` robots on `domain` (robot 0 going silent 2 s after it starts moving, when
/// `lose`); returns navdeck's report and the peer's record.
fn fleet_run(domain: u16, n: usize, keys: &str, lose: bool) -> Option<(Value, Value)> {
    run_peer(domain, n, n, keys, lose)
}

/// `n` robots on `domain`, of which navdeck starts with the first `driven`.
fn fleet_run_some(domain: u16, n: usize, driven: usize, keys: &str) -> Option<(Value, Value)> {
    run_peer(domain, n, driven, keys, false)
}

/// The fleet peer with `n` robots on `domain` beside navdeck over `--link ros2` driving
/// the first `driven` robots, one `--ns` each.
fn run_peer(
    domain: u16,
    n: usize,
    driven: usize,
    keys: &str,
    lose: bool,
) -> Option<(Value, Value)> {
    let ns: Vec<String> = (0..driven)
        .flat_map(|k| ["--ns".to_string(), format!("/tb3_{k}")])
        .collect();
    let mut args: Vec<&str> = vec!["--link", "ros2"];
    args.extend(ns.iter().map(String::as_str));
    run_beside(domain, n, "", lose, &args, keys)
}

/// The fleet peer with `n` robots on `domain` (robot 0 going silent 2 s after it starts
/// moving, when `lose`), and navdeck headless with the config `extra` (after the
/// loopback settings), `args` and `keys`.
fn run_beside(
    domain: u16,
    n: usize,
    extra: &str,
    lose: bool,
    args: &[&str],
    keys: &str,
) -> Option<(Value, Value)> {
    let dir = scratch(&format!("fleet{domain}"));
    let out = dir.join("peer.json");
    let cfg = dir.join("navdeck.toml");
    std::fs::write(&cfg, format!("{}{extra}", super::LOOPBACK)).unwrap();
    let mut peer: Vec<OsString> = vec![n.to_string().into(), out.clone().into()];
    if lose {
        peer.extend(["--lose", "0@2"].map(OsString::from));
    }
    let mut navdeck: Vec<OsString> = vec!["--domain".into(), domain.to_string().into()];
    navdeck.extend(["--config".into(), cfg.into()]);
    navdeck.extend(args.iter().map(OsString::from));
    navdeck.extend(["--headless", "--json", "--keys", keys].map(OsString::from));
    super::with_peer("fleet_drive_peer.py", domain, &peer, &out, &navdeck)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// Robot k's goal: 1.2 to 1.6 m ahead, to the left or the right.
fn goal(k: usize) -> (f64, f64) {
    (
        1.2 + 0.1 * (k % 5) as f64,
        if k.is_multiple_of(2) { 0.3 } else { -0.3 },
    )
}

fn fleet_drives_stops_and_outlives_a_lost_robot(domain: u16, n: usize) {
    // Each robot a goal (typed, then p follows it), then the next robot; after the last,
    // two seconds on, the stop-all key.
    let mut keys = String::new();
    for k in 0..n {
        let (x, y) = goal(k);
        keys += &format!(":goto<space>{x}<space>{y}<enter>p<ctrl-n>");
    }
    keys += &"0".repeat(20);
    keys += "X";
    let Some((report, record)) = fleet_run(domain, n, &keys, true) else {
        return;
    };
    let key_time = f(&report["epoch_unix"]) + f(&report["stop_all_times"][0]);
    let lost_at = f(&record["lost_at"]);
    let robots = report["robots"].as_array().unwrap();
    assert_eq!(robots.len(), n);
    let mut driving_at_key = 0;
    let mut worst = 0.0f64;
    for (k, peer) in record["robots"].as_array().unwrap().iter().enumerate() {
        let cmds: Vec<(f64, f64, f64)> = (peer["cmd_vel"].as_array().unwrap().iter())
            .map(|c| (f(&c[0]), f(&c[1]), f(&c[2])))
            .collect();
        let name = format!("tb3_{k}");
        let moving = |c: &&(f64, f64, f64)| c.1 != 0.0 || c.2 != 0.0;
        // Nothing moves a robot from the stop-all's bound on.
        let late: Vec<_> = (cmds.iter())
            .filter(|c| c.0 > key_time + STOP_WITHIN && moving(c))
            .collect();
        assert!(
            late.is_empty(),
            "{name} was still driven after stop-all: {late:?}"
        );
        let last = cmds.last().expect("commands");
        assert!(!moving(&last), "{name}'s last cmd_vel {last:?}");
        // A robot moving at the key got its zero in time.
        let before = cmds.iter().rev().find(|c| c.0 <= key_time);
        if k != 0 && before.is_some_and(|c| moving(&c)) {
            driving_at_key += 1;
            let zero = (cmds.iter())
                .find(|c| c.0 > key_time && !moving(c))
                .unwrap_or_else(|| panic!("{name} never got a zero after stop-all"));
            worst = worst.max(zero.0 - key_time);
        }
        if k == 0 {
            continue;
        }
        // Robot 0's loss left this one driving on.
        let at_loss = &record["poses_at_loss"][k];
        let end = &peer["pose"];
        let on = (f(&end[0]) - f(&at_loss[0])).hypot(f(&end[1]) - f(&at_loss[1]));
        assert!(on > 0.1, "{name} drove {on:.2} m after robot 0 was lost");
        assert!(robots[k]["link"].as_str().unwrap().contains(&name));
    }
    assert!(
        driving_at_key >= 1,
        "no robot was driving at the stop-all key"
    );
    assert!(worst <= STOP_WITHIN, "stop-all took {worst:.3} s");
    println!(
        "fleet of {n}: stop-all reached {driving_at_key} driving robots within {:.0} ms; robot 0 lost at {:.1} s",
        worst * 1000.0,
        lost_at - f(&report["epoch_unix"])
    );
    // Robot 0 is marked lost; the others are not.
    let lost: Vec<&str> = (robots.iter())
        .filter(|r| {
            (r["warnings"].as_array().unwrap().iter()).any(|w| {
                w.as_str().unwrap().contains("link lost") && !w.as_str().unwrap().contains("robot ")
            })
        })
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(lost, ["tb3_0"], "robots whose own log says link lost");
}

fn fleet_reaches_its_goals(domain: u16, n: usize) {
    let mut keys = String::new();
    for k in 0..n {
        let (x, y) = goal(k);
        keys += &format!(":goto<space>{}<space>{}<enter>p<ctrl-n>", x - 0.6, y);
    }
    let Some((report, record)) = fleet_run(domain, n, &keys, false) else {
        return;
    };
    let robots = report["robots"].as_array().unwrap();
    for (k, peer) in record["robots"].as_array().unwrap().iter().enumerate() {
        let (x, y) = goal(k);
        let p = &peer["pose"];
        let off = (f(&p[0]) - (x - 0.6)).hypot(f(&p[1]) - y);
        assert!(
            robots[k]["arrived"].as_bool().unwrap(),
            "tb3_{k} did not arrive"
        );
        assert!(off < 0.1, "tb3_{k} stopped {off:.3} m from its goal");
    }
}

#[test]
fn two_namespaced_robots_reach_goals_stop_together_and_outlive_a_lost_one() {
    fleet_drives_stops_and_outlives_a_lost_robot(131, 2);
    fleet_reaches_its_goals(133, 2);
}

#[test]
fn ten_namespaced_robots_reach_goals_stop_together_and_outlive_a_lost_one() {
    fleet_drives_stops_and_outlives_a_lost_robot(132, 10);
    fleet_reaches_its_goals(134, 10);
}

#[test]
fn a_config_fleet_mixes_a_twin_and_a_namespaced_ros2_robot() {
    let fleet = "[[fleet]]\nname = \"twin\"\n\n[[fleet]]\nname = \"tb3\"\nlink = \"ros2\"\nnamespace = \"/tb3_0\"\n";
    let keys = "wwwwwwwwww<ctrl-n>wwwwwwwwww";
    let Some((report, record)) = run_beside(135, 1, fleet, false, &[], keys) else {
        return;
    };
    let robots = report["robots"].as_array().unwrap();
    let names: Vec<&str> = robots.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["twin", "tb3"]);
    assert!(robots[0]["link"].as_str().unwrap().starts_with("sim:"));
    assert!(f(&robots[0]["distance_driven"]) > 0.1, "the twin drove");
    // The ROS 2 robot drove on its own keys, in its own odometry frame.
    let x = f(&record["robots"][0]["pose"][0]);
    assert!(x > 0.1, "the TurtleBot drove {x} m");
}

#[test]
fn a_robot_that_appears_is_named_and_joins_on_robot_add() {
    let domain = 136u16;
    // Three robots on the domain; the console starts with two.
    let keys = format!(
        "{}:robot<space>add<space>/tb3_2<enter>:robot<space>tb3_2<enter>wwwwwwwwwwww",
        "0".repeat(30)
    );
    let Some((report, record)) = fleet_run_some(domain, 3, 2, &keys) else {
        return;
    };
    let robots = report["robots"].as_array().unwrap();
    let names: Vec<&str> = robots.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["tb3_0", "tb3_1", "tb3_2"]);
    assert_eq!(report["selected"], "tb3_2");
    let x = f(&record["robots"][2]["pose"][0]);
    assert!(x > 0.1, "the robot that joined drove {x} m");
    for k in [0, 1] {
        let x = f(&record["robots"][k]["pose"][0]);
        assert!(x.abs() < 1e-9, "tb3_{k} was not driven, yet moved {x} m");
    }
}
