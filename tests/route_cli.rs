//! `navdeck route` as a user runs it: a warehouse task driven in the twin and back on the
//! dock within seed 003's 5 cm, a box on an aisle's only way named as the leg that
//! failed, and generated grids where a box is driven round.

use crate::common::navdeck;

const WAREHOUSE: &str = "maps/tag_warehouse.yaml";

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn reports(stdout: &[u8]) -> Vec<serde_json::Value> {
    text(stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn a_warehouse_task_is_driven_there_and_back_onto_the_dock() {
    let out = navdeck(&["route", "--tags", WAREHOUSE, "--task", "task3", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r = &reports(&out.stdout)[0];
    assert_eq!(r["completed"], true, "{r}");
    assert_eq!(r["collisions"], 0);
    // 508 -> 112 along zone A, into aisle D to 150, and back: 2 x 18 legs, 2 turns.
    assert_eq!(r["legs_driven"], 36);
    let turns = r["turn_errors_deg"].as_array().unwrap();
    assert_eq!(turns.len(), 2);
    assert!(turns.iter().all(|t| t.as_f64().unwrap().abs() < 5.0), "{r}");
    let side = r["end_side_m"].as_f64().unwrap();
    assert!(side.abs() < 0.05, "{side} m to the side of the dock");
    assert!(r["end_heading_deg"].as_f64().unwrap().abs() < 5.0, "{r}");
}

#[test]
fn a_box_on_an_aisles_only_way_fails_that_leg_by_name() {
    let out = navdeck(&[
        "route",
        "--tags",
        WAREHOUSE,
        "--task",
        "task1",
        "--obstacle",
        "118-119",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let said = text(&out.stdout);
    assert!(said.contains("NOT done"), "{said}");
    assert!(said.contains("leg 118-119 is blocked"), "{said}");
    assert!(said.contains("collisions 0"), "{said}");
}

#[test]
fn on_generated_grids_a_boxed_edge_is_driven_round_and_every_task_ends_on_the_dock() {
    // Grids 3 and 6 have a box on an edge of their first task.
    let out = navdeck(&["route", "--sweep", "3..6", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let runs = reports(&out.stdout);
    assert_eq!(runs.len(), 12);
    let mut rounded = 0;
    for r in &runs {
        assert_eq!(r["completed"], true, "{r}");
        assert_eq!(r["collisions"], 0, "{r}");
        assert!(r["end_side_m"].as_f64().unwrap().abs() < 0.05, "{r}");
        rounded += usize::from(!r["blocked"].as_array().unwrap().is_empty());
    }
    assert!(rounded >= 2, "{rounded} runs went round a box");
}

#[test]
fn a_box_between_tags_no_edge_joins_is_refused_by_name() {
    let out = navdeck(&[
        "route",
        "--tags",
        WAREHOUSE,
        "--task",
        "task1",
        "--obstacle",
        "101-117",
    ]);
    assert_ne!(out.status.code(), Some(0));
    let said = text(&out.stderr);
    assert!(said.contains("no edge 101-117"), "{said}");
}

/// `--sim-camera`: the tags drawn in the rendered camera's frames and read by OpenCV.
#[cfg(feature = "vision")]
#[test]
fn a_warehouse_task_is_driven_seeing_the_tags_in_rendered_frames() {
    let out = navdeck(&[
        "route",
        "--tags",
        WAREHOUSE,
        "--task",
        "task1",
        "--sim-camera",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r = &reports(&out.stdout)[0];
    assert_eq!(r["sensor"], "rendered", "{r}");
    assert_eq!(r["completed"], true, "{r}");
    assert_eq!(r["collisions"], 0);
    assert!(r["end_side_m"].as_f64().unwrap().abs() < 0.05, "{r}");
    let d = &r["detection"];
    // Every tag shown whole was found, and each one found within a millimetre and a
    // degree of the truth (seed 003 §2.5 aligns to 0.5° and 5 cm).
    let (in_view, found) = (
        d["tags_in_view"].as_u64().unwrap(),
        d["tags_found_in_view"].as_u64().unwrap(),
    );
    assert!(in_view > 100 && found == in_view, "{d}");
    assert!(d["lateral_error_m"]["max"].as_f64().unwrap() < 0.001, "{d}");
    assert!(d["ahead_error_m"]["max"].as_f64().unwrap() < 0.001, "{d}");
    assert!(d["align_error_deg"]["max"].as_f64().unwrap() < 1.0, "{d}");
    assert_eq!(d["unknown_ids"], 0);
    assert!(d["detect_time"]["mean_ms"].as_f64().unwrap() > 0.0, "{d}");
}

/// Without OpenCV, `--sim-camera` says what to build rather than driving blind.
#[cfg(not(feature = "vision"))]
#[test]
fn sim_camera_without_the_vision_feature_says_how_to_build() {
    let out = navdeck(&[
        "route",
        "--tags",
        WAREHOUSE,
        "--task",
        "task1",
        "--sim-camera",
    ]);
    assert_ne!(out.status.code(), Some(0));
    let said = text(&out.stderr);
    assert!(said.contains("--sim-camera"), "{said}");
    assert!(said.contains("cargo build --features vision"), "{said}");
    assert!(out.stdout.is_empty(), "{}", text(&out.stdout));
}

#[test]
fn the_ideal_camera_is_named_and_adds_no_detection_figures() {
    let out = navdeck(&["route", "--tags", WAREHOUSE, "--task", "task1", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r = &reports(&out.stdout)[0];
    assert_eq!(r["sensor"], "ideal", "{r}");
    assert!(r.get("detection").is_none(), "{r}");
}
