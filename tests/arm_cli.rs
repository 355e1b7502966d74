//! `navdeck arm ik|fk` as a user runs them: the joints for a reachable target, a clear
//! refusal for an unreachable one, the tool's pose for given joints, bad numbers refused.

use crate::common;

use common::navdeck;

fn stdout(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn json(out: &std::process::Output) -> serde_json::Value {
    serde_json::from_str(stdout(out).trim()).expect("one JSON object")
}

#[test]
fn ik_of_a_reachable_target_prints_joints_that_reach_it() {
    let out = navdeck(&["arm", "ik", "0.2", "0.05", "0.02", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v = json(&out);
    assert_eq!(v["reachable"], true);
    let residual = v["residual_m"].as_f64().unwrap();
    assert!(residual < 1e-4, "{v}");
    assert_eq!(v["joints"].as_array().unwrap().len(), 4);
    assert!(v["solve_time_us"].as_f64().unwrap() >= 0.0);
    // Fed back to fk, the joints put the tool on the target.
    let j: Vec<String> = v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_f64().unwrap().to_string())
        .collect();
    let mut args = vec!["arm", "fk"];
    args.extend(j.iter().map(String::as_str));
    args.push("--json");
    let p = json(&navdeck(&args));
    let (x, y, z) = (
        p["x"].as_f64().unwrap(),
        p["y"].as_f64().unwrap(),
        p["z"].as_f64().unwrap(),
    );
    let miss = ((x - 0.2).powi(2) + (y - 0.05).powi(2) + (z - 0.02).powi(2)).sqrt();
    assert!(miss < 1e-4, "{p}");
    assert_eq!(p["within_limits"], true);
}

#[test]
fn ik_in_text_names_the_branch_and_the_residual() {
    let out = navdeck(&["arm", "ik", "0.124", "0", "0.057", "--pitch", "90"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    // The right-angled elbow: upper arm vertical, forearm level, tool down.
    assert!(
        text.contains("joints    0.000000 -0.185348 0.185348 1.570796 rad"),
        "{text}"
    );
    assert!(text.contains("branch    elbow up"), "{text}");
    assert!(text.contains("residual  0.0000 mm"), "{text}");
}

#[test]
fn an_unreachable_target_exits_1_saying_why() {
    let out = navdeck(&["arm", "ik", "0.5", "0", "0.077"]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("target 0.500 m from the shoulder, the arm reaches 0.404 m"),
        "{err}"
    );
    let out = navdeck(&["arm", "ik", "0.5", "0", "0.077", "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let v = json(&out);
    assert_eq!(v["reachable"], false);
    assert_eq!(v["kind"], "too_far");
    // Within reach, but not with the tool pointing straight down.
    let out = navdeck(&["arm", "ik", "0.35", "0", "0.077", "--pitch", "90"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("pitch 90.0 deg"), "{}", stderr(&out));
}

#[test]
fn fk_of_zeros_is_the_zero_pose() {
    let out = navdeck(&["arm", "fk", "0", "0", "0", "0"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        stdout(&out).trim(),
        "x 0.297958 m  y 0.000000 m  z 0.204773 m  pitch 0.0 deg"
    );
    let v = json(&navdeck(&["arm", "fk", "0", "0", "0", "0", "--json"]));
    assert!((v["x"].as_f64().unwrap() - 0.297958).abs() < 1e-6, "{v}");
    assert!((v["z"].as_f64().unwrap() - 0.204773).abs() < 1e-6, "{v}");
    assert_eq!(v["within_limits"], true);
}

#[test]
fn fk_refuses_a_joint_outside_its_limits_naming_it_and_its_range() {
    let out = navdeck(&["arm", "fk", "0", "2", "0", "0"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        stderr(&out).trim(),
        "navdeck arm fk: J2 (shoulder) = 2 rad is outside its limits -1.79071..=1.5708 rad ([arm.limits] min[1], max[1])"
    );
    assert!(stdout(&out).is_empty(), "{}", stdout(&out));
    // The issue's: 1e308 everywhere printed NaN; now the first joint is refused, short.
    let out = navdeck(&["arm", "fk", "1e308", "1e308", "1e308", "1e308"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("J1 (base yaw) = 1e308 rad is outside its limits"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn ik_out_of_range_numbers_are_refused_with_the_range() {
    let out = navdeck(&["arm", "ik", "1e308", "0", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("for '<X>': 1e308 m is outside -7..=7"),
        "{}",
        stderr(&out)
    );
    let out = navdeck(&["arm", "ik", "0.2", "0", "0.1", "--pitch", "1e308"]);
    assert!(
        stderr(&out).contains("1e308 deg is outside -360..=360"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn ik_on_the_yaw_axis_warns_of_the_singularity() {
    let out = navdeck(&["arm", "ik", "0", "0", "0"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stdout(&out).contains("warning   near a singularity"),
        "{}",
        stdout(&out)
    );
    let v = json(&navdeck(&["arm", "ik", "0", "0", "0", "--json"]));
    assert_eq!(v["near_singular"], true);
    let v = json(&navdeck(&["arm", "ik", "0.2", "0.05", "0.02", "--json"]));
    assert_eq!(v["near_singular"], false);
}

#[test]
fn a_target_in_the_span_but_at_no_pitch_is_not_called_too_close() {
    let out = navdeck(&["arm", "ik", "-0.2", "0", "0.05", "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let v = json(&out);
    assert_eq!(v["kind"], "no_pitch");
    let reason = v["reason"].as_str().unwrap();
    assert!(!reason.contains("no closer than 0.000"), "{reason}");
}

#[test]
fn not_a_number_is_refused_naming_the_argument() {
    for (args, name) in [
        (vec!["arm", "ik", "nan", "0", "0.1"], "<X>"),
        (
            vec!["arm", "ik", "0.2", "0", "0.1", "--pitch", "inf"],
            "--pitch",
        ),
        (vec!["arm", "fk", "0", "0", "NaN", "0"], "<J3>"),
    ] {
        let out = navdeck(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains(name) && err.contains("not a finite number"),
            "{err}"
        );
    }
}

#[test]
fn a_config_without_an_arm_uses_the_defaults_and_a_bad_arm_is_refused() {
    let dir = std::env::temp_dir().join(format!("navdeck-arm-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, "[robot]\ntrack = 0.11\n").unwrap();
    let out = navdeck(&[
        "arm",
        "fk",
        "0",
        "0",
        "0",
        "0",
        "--config",
        plain.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stdout(&out).starts_with("x 0.297958 m"), "{}", stdout(&out));
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[arm]\nlinks = [0.13, -0.124, 0.15]\n").unwrap();
    let out = navdeck(&[
        "arm",
        "ik",
        "0.2",
        "0",
        "0.1",
        "--config",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("arm.links[1]"), "{}", stderr(&out));
    // The 2dof solver keeps its pitch and says so when asked for another.
    let two = dir.join("two.toml");
    std::fs::write(&two, "[arm]\nsolver = \"2dof\"\n").unwrap();
    let out = navdeck(&[
        "arm",
        "ik",
        "0.2",
        "0",
        "0.0",
        "--pitch",
        "0",
        "--json",
        "--config",
        two.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(json(&out)["kind"], "pitch_locked");
    std::fs::remove_dir_all(&dir).ok();
}
