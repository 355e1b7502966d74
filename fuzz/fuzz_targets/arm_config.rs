//! Fuzzes the arm's config and the `navdeck arm` numbers. The input, as lossy UTF-8: its
//! first line holds the command line's numbers (fk's J1..J4, then ik's X Y Z and pitch in
//! degrees), the rest is a config file whose `[arm]` section is used. A config the reader
//! accepts must give finite results everywhere: forward kinematics at its named poses
//! and at in-limit joints, inverse kinematics of in-range targets (a solution within the
//! limits, or a reason with no NaN), moves no longer than `LONGEST_MOVE`, and a pick in
//! the twin that ends (every loop bounded) with finite figures.
#![no_main]

use libfuzzer_sys::fuzz_target;
use navdeck::arm::config::{FARTHEST_REACH, LONGEST_MOVE};
use navdeck::arm::{Joints, Target, check_limits, forward, inverse, manipulability, move_time};
use navdeck::config::Config;
use std::path::Path;

fn finite_pose(p: navdeck::arm::ToolPose, what: &str) {
    assert!(
        [p.x, p.y, p.z, p.pitch].iter().all(|v| v.is_finite()),
        "{what}: {p:?}"
    );
}

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let (numbers, toml) = text.split_once('\n').unwrap_or((&text, ""));
    let Ok(read) = Config::parse(toml, Path::new("fuzz.toml")) else {
        return;
    };
    let arm = read.arm.clone().unwrap_or_default();
    if let Err(e) = arm.validate() {
        panic!("an accepted [arm] fails validate: {e:?}");
    }
    // The command line's numbers, as its parsers read them; a default where one is missing.
    let words: Vec<f64> = numbers
        .split_whitespace()
        .take(8)
        .map(|w| w.parse().unwrap_or(f64::NAN))
        .collect();
    let number = |i: usize, default: f64| words.get(i).copied().unwrap_or(default);

    let home = arm.pose("home").unwrap_or_default();
    for name in ["home", "ready", "stow"] {
        let joints = arm.pose(name).unwrap_or_default();
        finite_pose(forward(&arm, &joints), name);
        assert!(manipulability(&arm, &joints).is_finite(), "{name}");
        let t = move_time(&arm, &home, &joints);
        assert!(t.is_finite() && t <= LONGEST_MOVE, "home to {name}: {t} s");
    }
    // fk: joints the command line accepts (finite, within [arm.limits]).
    let joints = Joints([
        number(0, 0.0),
        number(1, 0.0),
        number(2, 0.0),
        number(3, 0.0),
    ]);
    if joints.0.iter().all(|j| j.is_finite()) && check_limits(&arm, &joints).is_ok() {
        finite_pose(forward(&arm, &joints), "fk");
        let t = move_time(&arm, &home, &joints);
        assert!(t.is_finite() && t <= LONGEST_MOVE, "home to fk joints: {t} s");
    }
    // ik: a target within the command line's bounds.
    let (x, y, z) = (number(4, 0.2), number(5, 0.0), number(6, 0.1));
    let pitch = words.get(7).copied();
    let in_reach = |v: f64| v.is_finite() && v.abs() <= FARTHEST_REACH;
    let pitch_ok = pitch.is_none_or(|p| p.is_finite() && p.abs() <= 360.0);
    if in_reach(x) && in_reach(y) && in_reach(z) && pitch_ok {
        let target = Target {
            pitch: pitch.map(f64::to_radians),
            ..Target::point(x, y, z)
        };
        match inverse(&arm, &target, &home) {
            Ok(s) => {
                assert!(check_limits(&arm, &s.joints).is_ok(), "{s:?}");
                assert!(s.residual.is_finite() && s.manipulability.is_finite(), "{s:?}");
                finite_pose(forward(&arm, &s.joints), "ik");
                let t = move_time(&arm, &home, &s.joints);
                assert!(t.is_finite() && t <= LONGEST_MOVE, "home to ik joints: {t} s");
            }
            Err(e) => {
                let why = e.to_string();
                assert!(!why.contains("NaN") && why.len() < 400, "{why}");
            }
        }
    }
    // One pick in the twin with this arm and nothing else changed.
    let config = Config {
        arm: Some(arm),
        ..Config::default()
    };
    let (picks, bands) = navdeck::runners::arm_pick::run(&config, 1, 1);
    for p in &picks {
        assert!(p.error_mm.is_none_or(f64::is_finite), "{p:?}");
    }
    for b in &bands {
        assert!(b.mean_error_mm.is_none_or(f64::is_finite), "{b:?}");
    }
});
