//! Faults as a user injects them: `--fault` on `navdeck mission`, `navdeck tour` and the
//! headless console, each listed in the run's JSON with when it was in force; bad specs
//! refused with the bad part named; `:fault` at the console.

use crate::common;

use common::{command, default_app, logged, navdeck, run_to};
use navdeck::app::App;
use navdeck::sim::FaultKind;
use serde_json::{Value, json};

/// The JSON a run printed, whatever its exit code (a short mission delivers nothing).
fn json_of(args: &[&str]) -> Value {
    let out = navdeck(args);
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)))
}

#[test]
fn a_mission_lists_its_faults_and_when_each_was_in_force() {
    let r = json_of(&[
        "mission",
        "--seed",
        "2",
        "--time-limit",
        "12",
        "--fault",
        "camera@5+3",
        "--fault",
        "lidar@10",
        "--fault",
        "slip@30+5",
        "--json",
    ]);
    assert_eq!(
        r["faults"],
        json!([
            {"kind": "camera", "spec": "camera@5+3", "start_s": 5.0, "end_s": 8.0},
            {"kind": "lidar", "spec": "lidar@10", "start_s": 10.0, "end_s": null},
            {"kind": "slip", "spec": "slip@30+5:0.5", "start_s": null, "end_s": null},
        ]),
        "{r}"
    );
    let warnings = r["warnings"].to_string();
    assert!(
        warnings.contains("5.0 s: fault injected: camera dark for 3 s"),
        "{warnings}"
    );
    // A run without faults says nothing of them.
    let plain = json_of(&["mission", "--seed", "2", "--time-limit", "1", "--json"]);
    assert!(plain.get("faults").is_none(), "{plain}");
}

#[test]
fn a_sweep_injects_the_same_faults_into_every_run() {
    let r = json_of(&[
        "mission",
        "--sweep",
        "1..2",
        "--time-limit",
        "3",
        "--fault",
        "odom@1+1",
        "--json",
    ]);
    let runs = r["runs_detail"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for run in runs {
        assert_eq!(run["faults"][0]["spec"], "odom@1+1", "{run}");
        assert_eq!(run["faults"][0]["end_s"], 2.0, "{run}");
    }
}

#[test]
fn the_headless_console_and_a_tour_list_their_faults_too() {
    let r = json_of(&[
        "--headless",
        "--json",
        "--keys",
        "wwww",
        "--fault",
        "odom@0+0.2",
    ]);
    assert_eq!(r["faults"][0]["kind"], "odom", "{r}");
    assert_eq!(r["faults"][0]["start_s"], 0.0);
    assert_eq!(r["faults"][0]["end_s"], 0.2);
    let tour = json_of(&[
        "tour",
        "--duration",
        "2",
        "--fault",
        "lidar@1+0.5",
        "--json",
    ]);
    assert_eq!(tour["faults"][0]["spec"], "lidar@1+0.5", "{tour}");
    assert_eq!(tour["faults"][0]["end_s"], 1.5);
}

#[test]
fn a_bad_fault_is_refused_with_the_bad_part_named() {
    for (args, says) in [
        (
            vec!["mission", "--fault", "cmaera@60+20"],
            "fault `cmaera@60+20`: unknown sensor `cmaera`: expected camera, lidar, odom, arm or slip",
        ),
        (vec!["--headless", "--fault", "camera@soon"], "start `soon`"),
        (vec!["tour", "--fault", "slip@1+2:3"], "slip ratio `3`"),
        (
            vec!["mission", "--fault", "lidar@1:0.5"],
            "`lidar` takes no parameter",
        ),
        (
            vec!["--fault", "camera@1", "mission"],
            "--fault before `mission` is the console's option",
        ),
    ] {
        let out = navdeck(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(matches!(out.status.code(), Some(1..=99)), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

fn camera_dark(app: &App) -> bool {
    app.faults().unwrap().is_active(FaultKind::Camera)
}

#[test]
fn fault_at_the_console_darkens_the_camera_from_now_and_says_when_it_ends() {
    let mut app = default_app();
    run_to(&mut app, 3.0);
    command(&mut app, "fault camera+2");
    assert!(camera_dark(&app), "in force at once");
    run_to(&mut app, 3.2);
    assert!(logged(&app, "fault injected: camera dark for 2 s"));
    run_to(&mut app, 4.8);
    assert!(camera_dark(&app));
    assert!(!logged(&app, "fault cleared: camera"));
    run_to(&mut app, 5.2);
    assert!(!camera_dark(&app));
    assert!(logged(&app, "fault cleared: camera"));
    // On the twin's time: it began at 3 s and ended at 5 s.
    let record = &app.faults().unwrap().records()[0];
    let (began, ended) = (record.began.unwrap(), record.ended.unwrap());
    assert!((began - 3.0).abs() < 0.011 && (ended - 5.0).abs() < 0.011);
}

#[test]
fn fault_clear_ends_the_faults_in_force_and_forgets_those_to_come() {
    let mut app = default_app();
    run_to(&mut app, 1.0);
    command(&mut app, "fault lidar");
    command(&mut app, "fault odom@100+5");
    assert!(logged(&app, "fault odom@100+5 scheduled: begins in 99.0 s"));
    command(&mut app, "fault");
    assert!(logged(
        &app,
        "faults in force: lidar@1; to come: odom@100+5"
    ));
    run_to(&mut app, 2.0);
    command(&mut app, "fault clear");
    run_to(&mut app, 2.2);
    assert!(logged(&app, "fault cleared: lidar"));
    assert!(logged(&app, "fault clear: 1 still to come forgotten"));
    assert!(app.faults().unwrap().active_kinds().is_empty());
    command(&mut app, "fault cmaera+2");
    assert!(logged(&app, "unknown sensor `cmaera`"));
    command(&mut app, "fault camera@0+1");
    assert!(logged(
        &app,
        "fault camera@0+1 not injected: its time is over"
    ));
}
