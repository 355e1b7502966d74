//! Lidar SLAM's maps as a user keeps them: `S` saves the Nav2 map and the pose graph
//! beside it, `--estimator slam --map` continues mapping on them, `navdeck mission
//! --save-map` writes both headless, the runners report the graph, and a pose cannot be
//! set on a map being built.

use crate::common;

use common::{logged, navdeck, scratch};
use navdeck::app::App;
use navdeck::keymap::parse_key_sequence;
use navdeck::session::{LocalizeChoice, Session, SessionSpec};
use navdeck::slam::lidar::SavedGraph;
use navdeck::slam::mcl::config::Estimator;
use std::path::{Path, PathBuf};

/// The twin in the built-in arena mapped by lidar SLAM, continuing `map` when given.
fn slam_spec(map: Option<PathBuf>) -> SessionSpec {
    SessionSpec {
        localize: LocalizeChoice {
            estimator: Some(Estimator::Slam),
            map,
            initial_pose: None,
        },
        ..SessionSpec::twin(None)
    }
}

/// A console mapping with lidar SLAM, saving into `dir`.
fn slam_app(dir: &Path, map: Option<PathBuf>) -> App {
    let mut app = Session::load(&slam_spec(map))
        .expect("session loads")
        .into_app(0.0);
    app.set_maps_dir(dir.to_path_buf());
    app
}

fn run_keys(app: &mut App, keys: &str) {
    let keys = parse_key_sequence(keys).unwrap();
    navdeck::runners::headless::run(app, &keys, 10.0);
}

/// Every line the console logged.
fn said(app: &App) -> Vec<String> {
    app.log_book().iter().map(|e| e.text.clone()).collect()
}

fn read_graph(path: &Path) -> SavedGraph {
    SavedGraph::from_json(&std::fs::read_to_string(path).unwrap()).expect("the graph loads")
}

/// Drives forward and turns, then `S`: the map and its pose graph in `dir`.
fn drive_and_save(dir: &Path) -> App {
    let mut app = slam_app(dir, None);
    run_keys(&mut app, "wwwwwwwwwwddddwwwwwwS");
    app
}

#[test]
fn the_save_key_writes_the_nav2_map_and_the_pose_graph_beside_it() {
    let dir = scratch("save");
    let mut app = drive_and_save(&dir);
    run_keys(&mut app, ":save lab-1<enter>");
    for name in ["saved", "lab-1"] {
        let map = navdeck::map::io::load(&dir.join(format!("{name}.yaml"))).unwrap();
        assert!(map.grid.cells.contains(&navdeck::map::grid::OCCUPIED));
        let graph = read_graph(&dir.join(format!("{name}.posegraph.json")));
        let keyframes = app.pilot().lidar_slam().unwrap().slam.graph().poses.len();
        assert!(keyframes >= 2, "{keyframes} keyframes after driving");
        assert_eq!(graph.nodes.len(), keyframes, "{name}");
        assert_eq!(graph.edges.len(), keyframes - 1 + graph_loops(&graph));
    }
    // The log names both files.
    let json = dir.join("saved.posegraph.json").display().to_string();
    let yaml = dir.join("saved.yaml").display().to_string();
    let line = app.log_book().iter().find(|e| e.text.contains(&json));
    assert!(
        line.is_some_and(|e| e.text.contains(&yaml)),
        "{:?}",
        said(&app)
    );
    // Without lidar SLAM there is no graph to save.
    let ekf_dir = scratch("ekf");
    let mut ekf = Session::load(&SessionSpec::twin(None))
        .unwrap()
        .into_app(0.0);
    ekf.set_maps_dir(ekf_dir.clone());
    run_keys(&mut ekf, "wwwS");
    assert!(ekf_dir.join("saved.yaml").exists());
    assert!(!ekf_dir.join("saved.posegraph.json").exists());
}

fn graph_loops(g: &SavedGraph) -> usize {
    let loops = g
        .edges
        .iter()
        .filter(|e| e.kind == navdeck::slam::lidar::EdgeKind::Loop);
    loops.count()
}

#[test]
fn a_continued_map_joins_the_saved_graph_and_keeps_its_keyframes() {
    let dir = scratch("continue");
    drive_and_save(&dir);
    let saved = read_graph(&dir.join("saved.posegraph.json"));
    let mut app = slam_app(&dir, Some(dir.join("saved.yaml")));
    let continues = format!(
        "lidar SLAM continues {}: {} keyframes",
        dir.join("saved.posegraph.json").display(),
        saved.nodes.len()
    );
    // The planning map is drawn from the saved keyframes before the robot moves.
    let walls = |app: &App| {
        let grid = app.pilot().belief().occupancy_grid();
        grid.cells
            .iter()
            .filter(|&&c| c == navdeck::map::grid::OCCUPIED)
            .count()
    };
    assert!(walls(&app) > 0, "no walls drawn from the saved keyframes");
    // The robot starts where the saved session did: its first scan matches the saved map.
    run_keys(&mut app, "wwwdd");
    assert!(logged(&app, &continues), "{:?}", said(&app));
    assert!(
        logged(&app, "continuing the saved map: the first scan matched it"),
        "{:?}",
        said(&app)
    );
    let slam = &app.pilot().lidar_slam().unwrap().slam;
    assert_eq!(slam.loaded(), saved.nodes.len());
    assert!(slam.graph().poses.len() > saved.nodes.len());
    for (k, node) in saved.nodes.iter().enumerate() {
        let pose = slam.graph().poses[k];
        let moved = (pose.x - node.pose[0]).hypot(pose.y - node.pose[1]);
        assert!(moved < 0.05, "saved keyframe {k} moved {moved} m");
    }
    // Saved again, the continued map holds the old keyframes and the new ones.
    let keyframes = slam.graph().poses.len();
    run_keys(&mut app, "S");
    let again = read_graph(&dir.join("saved.posegraph.json"));
    assert_eq!(again.nodes.len(), keyframes);
    assert!(dir.join("saved.posegraph.json.bak").exists());
}

#[test]
fn a_missing_or_bad_pose_graph_is_refused_naming_the_file_and_the_field() {
    let dir = scratch("bad");
    drive_and_save(&dir);
    let refusal = |dir: &Path| {
        let spec = slam_spec(Some(dir.join("saved.yaml")));
        Session::load(&spec).err().expect("refused").to_string()
    };
    let graph = dir.join("saved.posegraph.json");
    let text = std::fs::read_to_string(&graph).unwrap();
    std::fs::write(&graph, text.replacen("\"version\":1", "\"version\":7", 1)).unwrap();
    let why = refusal(&dir);
    assert!(
        why.contains(&graph.display().to_string()) && why.contains("version 7"),
        "{why}"
    );
    std::fs::remove_file(&graph).unwrap();
    let why = refusal(&dir);
    assert!(
        why.contains(&graph.display().to_string()) && why.contains("no such file"),
        "{why}"
    );
    // A map is for MCL or for continuing lidar SLAM, not for the EKF.
    let ekf = SessionSpec {
        localize: LocalizeChoice {
            estimator: Some(Estimator::Ekf),
            map: Some(dir.join("saved.yaml")),
            initial_pose: None,
        },
        ..SessionSpec::twin(None)
    };
    let why = Session::load(&ekf).err().unwrap().to_string();
    assert!(why.contains("--estimator slam"), "{why}");
}

#[test]
fn a_pose_is_refused_while_lidar_slam_maps() {
    let dir = scratch("pose");
    let mut app = slam_app(&dir, None);
    run_keys(&mut app, "ww:pose 1 0.5 90<enter>:relocalize<enter>");
    assert!(
        logged(&app, "pose not set: lidar SLAM is mapping"),
        "{:?}",
        said(&app)
    );
    assert!(logged(&app, "relocalize needs MCL"));
    let pose = app.pilot().pose();
    assert!(
        pose.x < 0.9 || pose.y.abs() < 0.3,
        "the pose moved: {pose:?}"
    );
}

#[test]
fn a_mission_saves_its_map_and_pose_graph_and_reports_the_graph() {
    let dir = scratch("mission");
    let yaml = dir.join("m.yaml");
    let args = [
        "mission",
        "--generated",
        "--style",
        "rooms",
        "--size",
        "6,5",
        "--seed",
        "2",
        "--estimator",
        "slam",
        "--time-limit",
        "30",
        "--json",
        "--save-map",
    ];
    let out = navdeck(&[&args[..], &[yaml.to_str().unwrap()]].concat());
    let report: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!(report["estimator"], "slam");
    let keyframes = report["keyframes"].as_u64().unwrap();
    assert!(keyframes >= 2, "{report}");
    assert!(report["loop_closures"].is_u64() && report["false_loop_closures"].is_u64());
    let map = navdeck::map::io::load(&yaml).expect("the saved map loads");
    assert!(map.grid.cells.contains(&navdeck::map::grid::OCCUPIED));
    let graph = read_graph(&dir.join("m.posegraph.json"));
    assert_eq!(graph.nodes.len() as u64, keyframes);
    // Without lidar SLAM the figures are null, and no graph is written.
    let ekf_yaml = dir.join("ekf.yaml");
    let ekf = [
        "mission",
        "--estimator",
        "ekf",
        "--time-limit",
        "5",
        "--json",
        "--save-map",
        ekf_yaml.to_str().unwrap(),
    ];
    let out = navdeck(&ekf);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["estimator"], "ekf");
    assert!(report["keyframes"].is_null() && report["loop_closures"].is_null());
    assert!(report["false_loop_closures"].is_null());
    assert!(ekf_yaml.exists() && !dir.join("ekf.posegraph.json").exists());
    // A name that is not a Nav2 map's is refused.
    let out = navdeck(&["mission", "--save-map", "m.png"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("--save-map m.png"));
}

#[test]
fn the_sweep_and_headless_reports_carry_the_graph_figures() {
    let out = navdeck(&[
        "mission",
        "--sweep",
        "1..2",
        "--estimator",
        "slam",
        "--time-limit",
        "10",
        "--json",
    ]);
    let s: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(s["estimator"], "slam", "{s}");
    assert!(
        s["loop_closures"].is_u64() && s["false_loop_closures"].is_u64(),
        "{s}"
    );
    for run in s["runs_detail"].as_array().unwrap() {
        assert!(run["keyframes"].as_u64().unwrap() >= 1, "{run}");
    }
    let out = navdeck(&[
        "--headless",
        "--estimator",
        "slam",
        "--keys",
        "wwwdd",
        "--json",
    ]);
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["estimator"], "slam");
    assert!(r["keyframes"].as_u64().unwrap() >= 1, "{r}");
    let out = navdeck(&["--headless", "--keys", "ww", "--json"]);
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["estimator"], "ekf");
    assert!(r["keyframes"].is_null(), "{r}");
}

#[test]
fn a_replay_of_a_continued_map_continues_it_again_bit_for_bit() {
    let dir = scratch("replay");
    drive_and_save(&dir);
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
            .args(args)
            .current_dir(&dir)
            .env("NO_COLOR", "1")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    run(&[
        "--headless",
        "--estimator",
        "slam",
        "--map",
        "saved.yaml",
        "--keys",
        "wwwdd",
        "--record",
        "continued.mcap",
    ]);
    let replayed = run(&["replay", "continued.mcap", "--headless"]);
    // "re-run  N of N control ticks' estimates identical to the recording".
    let line = (replayed.lines())
        .find(|l| l.contains("estimates identical"))
        .unwrap_or_else(|| panic!("{replayed}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[1], words[3], "{line}");
    // Without its graph the recording's map cannot be continued, and the replay says so.
    std::fs::remove_file(dir.join("saved.posegraph.json")).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(["replay", "continued.mcap", "--headless"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains("saved.posegraph.json"));
}
