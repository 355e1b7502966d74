//! The binary from the outside: headless runs, help, and refusals of bad input.

use crate::common;

use common::{navdeck, scratch};

use serde_json::Value;
use std::path::PathBuf;
use std::process::Output;

fn headless_json(args: &[&str]) -> Value {
    let mut all = vec!["--headless", "--json"];
    all.extend_from_slice(args);
    let out = navdeck(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A file `name` holding `text`, in a scratch folder of its own.
fn scratch_file(name: &str, text: &str) -> PathBuf {
    let path = scratch(name).join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn headless_keys_drive_the_twin_and_report_json() {
    let r = headless_json(&["--keys", "wwwwwwddd", "--seed", "7"]);
    let truth = &r["true_pose"];
    let est = &r["estimated_pose"];
    assert!(r["distance_driven"].as_f64().unwrap() > 0.05, "{r}");
    assert_eq!(r["collisions"], 0);
    assert_eq!(r["keys"], 9);
    assert!(r["sim_time"].as_f64().unwrap() >= 0.9);
    // Odometry tracks the truth closely over such a short drive.
    let dx = truth["x"].as_f64().unwrap() - est["x"].as_f64().unwrap();
    let dy = truth["y"].as_f64().unwrap() - est["y"].as_f64().unwrap();
    assert!(dx.hypot(dy) < 0.05, "{r}");
    assert!(r["realtime_factor"].as_f64().unwrap() > 0.0);
    // Scored against the twin: the largest error bounds the RMSE, and the lidar's map
    // has found some of the arena's walls, mostly where they are.
    let (rmse, max) = (
        r["position_rmse"].as_f64(),
        r["position_max_error"].as_f64(),
    );
    assert!(max.unwrap() >= rmse.unwrap(), "{r}");
    let map = &r["map_vs_walls"];
    for share in ["wall_recall", "wall_precision"] {
        let v = map[share]
            .as_f64()
            .unwrap_or_else(|| panic!("{share}: {r}"));
        assert!(v > 0.0 && v <= 1.0, "{share}: {map}");
    }
}

#[test]
fn same_seed_same_run_other_seed_other_noise() {
    let strip = |mut v: Value| {
        v.as_object_mut().unwrap().remove("wall_time_s");
        v.as_object_mut().unwrap().remove("realtime_factor");
        v
    };
    let a = strip(headless_json(&["--keys", "wwwwwwwwaaaww", "--seed", "3"]));
    let b = strip(headless_json(&["--keys", "wwwwwwwwaaaww", "--seed", "3"]));
    let c = strip(headless_json(&["--keys", "wwwwwwwwaaaww", "--seed", "4"]));
    assert_eq!(a, b);
    assert_ne!(a["estimated_pose"], c["estimated_pose"]);
}

#[test]
fn headless_runs_the_larger_world_too() {
    let world = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/warehouse.toml");
    let r = headless_json(&["--world", world, "--keys", "wwww"]);
    assert!(r["link"].as_str().unwrap().starts_with("sim:"));
}

#[test]
fn help_documents_every_option() {
    let out = navdeck(&["--help"]);
    let text = String::from_utf8_lossy(&out.stdout);
    for option in [
        "--link",
        "--world",
        "--seed",
        "--config",
        "--keymap",
        "--braille",
        "--headless",
        "--keys",
        "--key-rate",
        "--json",
        "--help",
        "--version",
    ] {
        assert!(text.contains(option), "--help lacks {option}:\n{text}");
    }
}

#[test]
fn bad_keymap_is_refused_with_file_and_line_before_the_terminal() {
    let path = scratch_file(
        "bad-keymap.toml",
        "[manual]\nw = \"forward\"\nx = \"fly\"\n",
    );
    let out = navdeck(&["--keymap", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("bad-keymap.toml:3"), "{err}");
    assert!(err.contains("fly"), "{err}");
    // Nothing was drawn: no alternate screen was entered.
    assert!(!String::from_utf8_lossy(&out.stdout).contains("\x1b[?1049h"));
}

#[test]
fn bad_world_and_config_are_refused_with_names() {
    let world = scratch_file(
        "bad-world.toml",
        "name = \"w\"\nsize = [4.0, 4.0]\nbogus = 1\n",
    );
    let out = navdeck(&["--headless", "--world", world.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("bad-world.toml") && err.contains("bogus"),
        "{err}"
    );

    let config = scratch_file("bad-config.toml", "[teleop]\ndeadman_timeout = -1\n");
    let out = navdeck(&["--headless", "--config", config.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("teleop.deadman_timeout") && err.contains("-1"),
        "{err}"
    );
}

#[test]
fn unknown_keys_and_links_are_refused() {
    let out = navdeck(&["--headless", "--keys", "ww<bogus>"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("bogus"), "{}", stderr(&out));
    let out = navdeck(&["--link", "can0"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("can0"));
}

#[test]
fn plan_prints_path_length_cost_and_time_as_json() {
    let out = navdeck(&["plan", "--from", "-1,-1.5", "--to", "1.2,1.2", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let length = r["length"].as_f64().unwrap();
    // Longer than the straight line (3.48 m): it goes round the boxes.
    assert!(length > 3.48 && length < 4.5, "{length}");
    assert!(r["cost"].as_f64().unwrap() > length / 0.01);
    assert!(r["planning_time_ms"].as_f64().unwrap() > 0.0);
    let waypoints = r["waypoints"].as_array().unwrap();
    assert_eq!(waypoints.first().unwrap()["x"].as_f64(), Some(-1.0));
    assert_eq!(waypoints.last().unwrap()["y"].as_f64(), Some(1.2));
}

#[test]
fn plan_on_a_nav2_map_goes_round_the_wall() {
    let out = navdeck(&[
        "plan",
        "--map",
        "tests/maps/room.yaml",
        "--from",
        "-1,-0.5",
        "--to",
        "1,-0.5",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    // The wall at x = 0 leaves a gap only above y = 0.4: the path climbs to it.
    let length: f64 = text
        .split(": ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(length > 2.5, "{text}");
}

#[test]
fn plan_says_why_there_is_no_path() {
    let walled = navdeck(&[
        "plan",
        "--world",
        "tests/worlds/walled_garden.toml",
        "--from",
        "-1,-1",
        "--to",
        "0.9,0.9",
    ]);
    assert_eq!(walled.status.code(), Some(1));
    assert!(
        stderr(&walled).contains("unreachable"),
        "{}",
        stderr(&walled)
    );
    let inside = navdeck(&["plan", "--from", "-1,-1.5", "--to", "0.5,0.5"]);
    assert_eq!(inside.status.code(), Some(1));
    assert!(
        stderr(&inside).contains("inside an obstacle"),
        "{}",
        stderr(&inside)
    );
    let off = navdeck(&["plan", "--from", "-1,-1.5", "--to", "9,0"]);
    assert!(stderr(&off).contains("off the map"), "{}", stderr(&off));
    let bad = navdeck(&["plan", "--from", "-1;-1.5", "--to", "0,0"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        stderr(&bad).contains("`-1;-1.5` is not X,Y"),
        "{}",
        stderr(&bad)
    );
}

#[test]
fn a_bad_nav2_map_is_refused_naming_the_field() {
    let yaml = scratch_file(
        "bad.yaml",
        "image: room.pgm\nresolution: -0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    let out = navdeck(&[
        "plan",
        "--map",
        yaml.to_str().unwrap(),
        "--from",
        "0,0",
        "--to",
        "1,1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("field `resolution` = -0.05"),
        "{}",
        stderr(&out)
    );
    let missing = scratch_file(
        "missing.yaml",
        "image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    let out = navdeck(&[
        "plan",
        "--map",
        missing.to_str().unwrap(),
        "--from",
        "0,0",
        "--to",
        "1,1",
    ]);
    assert!(stderr(&out).contains("nowhere.pgm"), "{}", stderr(&out));
}

#[test]
fn map_info_and_show_describe_a_saved_map() {
    let out = navdeck(&["map", "info", "tests/maps/room.yaml", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let info: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (info["width"].as_u64(), info["height"].as_u64()),
        (Some(60), Some(40))
    );
    assert_eq!(info["unknown"], 0);
    assert!(info["occupied"].as_u64().unwrap() > 150);
    let shown = navdeck(&["map", "show", "tests/maps/room.yaml", "--width", "30"]);
    let text = String::from_utf8_lossy(&shown.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines.len(),
        10,
        "3 m x 2 m at 10 cm a column, 20 cm a row:\n{text}"
    );
    assert!(
        lines[0].chars().all(|c| c == '#'),
        "the north wall:\n{text}"
    );
    assert!(lines[5].contains('.') && lines[5].contains('#'), "{text}");
    let missing = navdeck(&["map", "info", "tests/maps/nothere.yaml"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(stderr(&missing).contains("cannot read map tests/maps/nothere.yaml"));
}
