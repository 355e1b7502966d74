//! The twin inside a Nav2 map: TurtleBot3's own world (map_server YAML + PGM, shipped in
//! maps/) becomes walls the lidar sees and the robot runs into, in the map's own frame.

use crate::common;

use common::navdeck;

use navdeck::config::Config;
use navdeck::geometry::Twist;
use navdeck::sim::{Twin, nav2_world};
use std::path::Path;

const MAP: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/turtlebot3_world.yaml");

#[test]
fn the_turtlebot3_world_becomes_walls_in_its_own_frame() {
    let world = nav2_world::load(Path::new(MAP), None).unwrap();
    // The map spans -10..9.2 m both ways: the world is centred on the map's origin.
    assert!((world.width - 20.0).abs() < 1e-9 && (world.height - 20.0).abs() < 1e-9);
    // Runs of cells are joined: a few hundred segments, not one per cell edge.
    assert!(
        (50..3000).contains(&world.walls.len()),
        "{} wall segments",
        world.walls.len()
    );
    // The robot starts on a free cell of the map, away from every wall.
    let start = world.start.position();
    let nearest = world
        .walls
        .iter()
        .map(|w| w.distance_to(start))
        .fold(f64::INFINITY, f64::min);
    assert!(
        nearest > 0.3,
        "start {start:?} is {nearest:.2} m from a wall"
    );
}

#[test]
fn the_lidar_sees_the_walls_and_driving_into_one_is_a_collision() {
    let config = Config::default();
    let world = nav2_world::load(Path::new(MAP), None).unwrap();
    let mut twin = Twin::new(world, &config.robot, &config.sim, 1);
    let mut hits = 0;
    let mut scans = 0;
    // Drive straight on until something stops the robot.
    twin.set_command(Twist::new(0.2, 0.0));
    for _ in 0..600 {
        twin.step(0.1);
        if let Some(scan) = twin.take_frame().scan {
            scans += 1;
            hits += scan.ranges.iter().filter(|r| r.is_finite()).count();
        }
        twin.set_command(Twist::new(0.2, 0.0));
    }
    assert!(scans > 100, "{scans} scans");
    assert!(
        hits as f64 > 0.2 * (scans * 360) as f64,
        "the walls answer: {hits} finite ranges in {scans} scans"
    );
    assert!(twin.collisions() >= 1, "60 s straight ahead ends at a wall");
}

#[test]
fn a_start_on_a_wall_or_off_the_map_is_refused_and_a_free_one_is_kept() {
    let bad = navdeck(&[
        "--world",
        MAP,
        "--start",
        "30,0,0",
        "--headless",
        "--keys",
        "w",
    ]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(2), "{err}");
    assert!(err.contains("start"), "{err}");
    // The map's origin corner is unknown space, not free.
    let bad = navdeck(&[
        "--world",
        MAP,
        "--start",
        "-9.9,-9.9,0",
        "--headless",
        "--keys",
        "w",
    ]);
    assert_eq!(bad.status.code(), Some(2));
    let good = navdeck(&[
        "--world",
        MAP,
        "--start",
        "-2.0,-0.5,0",
        "--headless",
        "--keys",
        "ww",
        "--json",
    ]);
    assert!(
        good.status.success(),
        "{}",
        String::from_utf8_lossy(&good.stderr)
    );
    let r: serde_json::Value = serde_json::from_slice(&good.stdout).unwrap();
    let x = r["true_pose"]["x"].as_f64().unwrap();
    assert!((x - -2.0).abs() < 0.2, "started at -2.0, now at {x}");
}

/// The console on the TurtleBot3 world: its walls (the twin's truth, dimmed) and the
/// first scan on the map.
#[test]
fn the_console_shows_the_turtlebot3_world() {
    use navdeck::session::{LinkChoice, Session, SessionSpec};
    let spec = SessionSpec {
        world: Some(MAP.into()),
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    };
    let mut app = Session::load(&spec).unwrap().into_app(0.0);
    app.resize(100, 30);
    for k in 1..=10 {
        app.update(0.1 * f64::from(k));
    }
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(100, 30)).unwrap();
    terminal
        .draw(|f| navdeck::tui::draw::draw(f, &app, navdeck::tui::theme::Theme { color: false }))
        .unwrap();
    let buf = terminal.backend().buffer();
    let screen: String = (0..30)
        .map(|y| (0..100).map(|x| buf[(x, y)].symbol()).collect::<String>() + "\n")
        .collect();
    assert!(screen.contains("sim:turtlebot3_world"), "{screen}");
    assert!(screen.matches('#').count() > 50, "walls drawn:\n{screen}");
    insta::assert_snapshot!(screen);
}
