//! Monte-Carlo localisation as a user meets it: tracking, global localisation and a
//! kidnapped robot in the twin (scored against its truth by the tour runner), a `:goto`
//! on MCL alone, the console's pose commands, and bad input refused.

use crate::common;

use common::navdeck;
use navdeck::app::{App, KeyKind};
use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2};
use navdeck::keymap::Key;
use navdeck::pilot::localize::InitialPose;
use navdeck::runners::tour::{self, TourOptions, TourReport};
use navdeck::session::{LinkChoice, LocalizeChoice, Session, SessionSpec};
use navdeck::slam::mcl::config::Estimator;

const TB3: &str = "maps/turtlebot3_world.yaml";
const FLAT: &str = "maps/flat.yaml";

fn spec(world: &str, seed: u64, initial: Option<InitialPose>) -> SessionSpec {
    SessionSpec {
        world: Some(world.into()),
        seed,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: LocalizeChoice {
            estimator: Some(Estimator::Mcl),
            map: None,
            initial_pose: initial,
        },
    }
}

fn tour_of(
    spec: &SessionSpec,
    tweak: impl FnOnce(&mut Config),
    options: TourOptions,
) -> TourReport {
    let session = Session::load(spec).expect("session loads");
    let localizer = session.localizer.clone();
    let (mut config, link) = session.into_link();
    tweak(&mut config);
    tour::run(&config, link, localizer.as_ref(), &options).expect("the tour runs")
}

fn options(seed: u64, duration: f64) -> TourOptions {
    TourOptions {
        seed,
        duration,
        kidnap: None,
        goals: Vec::new(),
        random_start: false,
    }
}

#[test]
fn mcl_tracks_the_turtlebot3_world_to_centimetres_where_dead_reckoning_drifts() {
    let r = tour_of(&spec(TB3, 1, None), |_| {}, options(1, 120.0));
    let (pos, head) = (
        r.errors.position_rmse.unwrap(),
        r.errors.heading_rmse_deg.unwrap(),
    );
    assert!(pos < 0.03 && head < 1.5, "MCL RMSE {pos} m, {head}°");
    let dr = r.errors.dr_position_rmse.unwrap();
    assert!(dr > 2.0 * pos, "dead reckoning {dr} m against MCL {pos} m");
    assert_eq!(r.collisions, Some(0));
    assert!(r.arrivals.len() >= 3, "{r:?}");
}

#[test]
fn global_localisation_finds_the_robot_in_the_flat() {
    for seed in 1..=3 {
        let mut o = options(seed, 40.0);
        o.random_start = true;
        let r = tour_of(&spec(FLAT, seed, Some(InitialPose::Unknown)), |_| {}, o);
        let at = r.localised_at.unwrap_or(f64::INFINITY);
        assert!(at <= 30.0, "seed {seed}: localised at {at} s");
        assert_eq!(r.collisions, Some(0), "seed {seed}");
        assert_never_confidently_wrong(&r);
    }
}

/// MCL never said "localised" while more than 0.3 m or 10° from the twin's truth.
fn assert_never_confidently_wrong(r: &TourReport) {
    let s = &r.localisation;
    assert_eq!(s.confidently_wrong_s, 0.0, "seed {}: {s:?}", r.seed);
    assert!(!s.confidently_wrong, "seed {}: {s:?}", r.seed);
}

/// A generated flat of `size` (W,H metres) saved as a Nav2 map in a fresh folder.
fn generated_flat(seed: u64, size: &str) -> (std::path::PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("navdeck-mcl-flat-{}-{seed}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (world, map) = (dir.join("flat.toml"), dir.join("flat.yaml"));
    let out = navdeck(&[
        "world",
        "generate",
        "--style",
        "rooms",
        "--size",
        size,
        "--seed",
        &seed.to_string(),
        "-o",
        world.to_str().unwrap(),
        "--nav2-map",
        map.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, map.to_str().unwrap().to_string())
}

/// Global localisation from random starts on `map`: (seed, report) per seed.
fn global_runs(map: &str, seeds: std::ops::RangeInclusive<u64>) -> Vec<TourReport> {
    seeds
        .map(|seed| {
            let mut o = options(seed, 40.0);
            o.random_start = true;
            tour_of(&spec(map, seed, Some(InitialPose::Unknown)), |_| {}, o)
        })
        .collect()
}

/// The TurtleBot3 world's walls match themselves turned a half or a quarter turn on most
/// cells: the few that differ, summed over the scans, must tell the turned copies apart
/// (seeds that stayed at "localising: 4 hypotheses" for the whole 40 s before).
#[test]
fn global_localisation_tells_the_turtlebot3_worlds_turned_copies_apart() {
    for r in global_runs(TB3, 1..=2) {
        let at = r.localised_at.unwrap_or(f64::INFINITY);
        assert!(at <= 30.0, "seed {}: localised at {at} s: {r:?}", r.seed);
        assert_never_confidently_wrong(&r);
    }
}

#[test]
fn global_localisation_finds_the_robot_in_a_generated_flat_and_never_claims_a_wrong_pose() {
    let (dir, map) = generated_flat(7, "10,8");
    for r in global_runs(&map, 1..=2) {
        let at = r.localised_at.unwrap_or(f64::INFINITY);
        assert!(at <= 30.0, "seed {}: localised at {at} s: {r:?}", r.seed);
        assert_never_confidently_wrong(&r);
        assert_eq!(r.localisation.localisation.as_deref(), Some("localised"));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The global-localisation bar, 50 random starts on each of four maps (`maps/flat.yaml`,
/// the TurtleBot3 world and generated flats of 10 x 8 m and 12 x 9 m): localised within
/// 30 s on at least 95 % of each, and never "localised" while wrong. Minutes of work:
/// `cargo test --release --all-features --test suite mcl::global_localisation_sweep --
/// --ignored --nocapture`.
#[test]
#[ignore]
fn global_localisation_sweep() {
    let flats = [generated_flat(7, "10,8"), generated_flat(11, "12,9")];
    let maps = [
        FLAT.to_string(),
        TB3.to_string(),
        flats[0].1.clone(),
        flats[1].1.clone(),
    ];
    for map in &maps {
        let runs = global_runs(map, 1..=50);
        let found = runs
            .iter()
            .filter(|r| r.localised_at.is_some_and(|t| t <= 30.0))
            .count();
        let wrong = runs
            .iter()
            .filter(|r| r.localisation.confidently_wrong_s > 0.0)
            .count();
        println!("{map}: localised within 30 s on {found}/50, confidently wrong in {wrong}");
        assert!(found >= 48, "{map}: {found}/50");
        assert_eq!(wrong, 0, "{map}");
    }
    for (dir, _) in flats {
        std::fs::remove_dir_all(dir).unwrap();
    }
}

/// A 12 × 9 m flat with an 8 m room: from its middle the 3.5 m lidar sees nothing. Such
/// scans weigh nothing, so they must not make the filter call itself lost (before, seeds
/// 1 and 2 were `lost` at 6.8 s and ended 3.3 and 11.6 m off, tracking from a known
/// start).
#[test]
fn tracking_through_a_room_wider_than_the_lidar_reaches_is_never_lost() {
    let (dir, map) = generated_flat(101, "12,9");
    for seed in 1..=2 {
        let mut o = options(seed, 30.0);
        o.random_start = true;
        let r = tour_of(&spec(&map, seed, None), |_| {}, o);
        let s = &r.localisation;
        assert_eq!(s.lost_at, None, "seed {seed}: {s:?} {:?}", r.warnings);
        assert!(s.final_error_m < 0.15, "seed {seed}: {s:?}");
        assert_never_confidently_wrong(&r);
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_kidnapped_robot_says_it_is_lost_then_finds_itself_again() {
    let kidnaps = [
        (30.0, Pose2::new(0.5, -1.3, std::f64::consts::FRAC_PI_2)),
        (20.0, Pose2::new(-1.5, 1.0, 0.0)),
        (25.0, Pose2::new(1.5, 1.5, std::f64::consts::PI)),
    ];
    for kidnap in kidnaps {
        let mut o = options(1, 70.0);
        o.kidnap = Some(kidnap);
        let r = tour_of(&spec(FLAT, 1, None), |_| {}, o);
        let at = r.kidnapped_at.expect("kidnapped");
        // The status says "lost" within a few scans of the robot being carried off.
        let lost = r.localisation.lost_at.unwrap_or(f64::INFINITY);
        assert!(
            lost - at <= 3.0,
            "{kidnap:?}: lost noticed at {lost} s: {r:?}"
        );
        let after = r.recovered_after.unwrap_or(f64::INFINITY);
        assert!(
            after <= 30.0,
            "{kidnap:?}: recovered after {after} s: {r:?}"
        );
        assert_eq!(r.localisation.localisation.as_deref(), Some("localised"));
    }
}

#[test]
fn a_goto_across_the_turtlebot3_world_on_mcl_alone_arrives_within_5_cm() {
    let goals = vec![
        Point2::new(1.8, 0.0),
        Point2::new(-1.8, 0.0),
        Point2::new(0.0, 1.6),
        Point2::new(0.0, -1.6),
    ];
    let mut o = options(2, 200.0);
    o.goals = goals.clone();
    // The follower stops within its goal tolerance of where MCL puts the robot.
    let r = tour_of(&spec(TB3, 2, None), |c| c.follow.goal_tolerance = 0.02, o);
    assert_eq!(r.collisions, Some(0));
    assert!(r.arrivals.len() >= goals.len(), "{r:?}");
    for a in &r.arrivals {
        assert!(a.true_error < 0.05, "{a:?}");
    }
}

fn mcl_console(world: &str) -> App {
    let mut app = common::app_with(spec(world, 1, None));
    app.resize(120, 40);
    // Zoomed in on the robot, as far as the TurtleBot3 world's walls.
    for _ in 0..4 {
        app.handle_key(Key::char('+'), KeyKind::Press, 0.0);
    }
    for k in 1..=10 {
        app.update(0.1 * f64::from(k));
    }
    app
}

fn type_line(app: &mut App, line: &str) {
    let t = app.now();
    app.handle_key(Key::char(':'), KeyKind::Press, t);
    for c in line.chars() {
        app.handle_key(Key::char(c), KeyKind::Press, t);
    }
    app.handle_key(common::key("enter"), KeyKind::Press, t);
}

#[test]
fn the_console_shows_particles_and_the_filter_state() {
    let app = mcl_console(TB3);
    let screen = common::render_at(&app, 120, 40);
    assert!(screen.contains("MCL"), "{screen}");
    assert!(screen.contains("localised"), "{screen}");
    assert!(
        screen.contains('▓') || screen.contains('▒') || screen.contains('░'),
        "particles shade the map:\n{screen}"
    );
    insta::assert_snapshot!(screen);
}

#[test]
fn pose_and_relocalize_commands_place_the_particles() {
    let mut app = mcl_console(TB3);
    type_line(&mut app, "pose -1.5 0.2 90");
    let p = app.pilot().estimated_pose();
    assert!((p.x + 1.5).abs() < 0.2 && (p.y - 0.2).abs() < 0.2, "{p:?}");
    assert!((p.theta - std::f64::consts::FRAC_PI_2).abs() < 0.2, "{p:?}");
    let text: Vec<&str> = app.log_book().iter().map(|e| e.text.as_str()).collect();
    assert!(
        text.iter()
            .any(|t| t.contains("pose set to (-1.50, 0.20) 90°")),
        "{text:?}"
    );
    type_line(&mut app, "pose 50 50 0");
    let last = app.log_book().last().unwrap().text.clone();
    assert!(last.contains("off the map"), "{last}");
    type_line(&mut app, "relocalize");
    let mcl = app.pilot().mcl().unwrap();
    let max = app.config().localization.particles.global_max_particles as usize;
    assert_eq!(mcl.status().particles, max);
    assert!(!mcl.status().converged);
}

#[test]
fn the_pose_estimate_key_takes_a_position_then_a_heading() {
    let mut app = mcl_console(TB3);
    let t = app.now();
    app.handle_key(Key::char('t'), KeyKind::Press, t);
    // The cursor starts at the robot; P there, three cells up, P again: facing +y.
    app.handle_key(Key::char('P'), KeyKind::Press, t);
    let at = app.pose_anchor().expect("position placed");
    for _ in 0..3 {
        app.handle_key(common::key("up"), KeyKind::Press, t);
    }
    app.handle_key(Key::char('P'), KeyKind::Press, t);
    let p = app.pilot().estimated_pose();
    assert!(p.position().distance(at) < 0.2, "{p:?} vs {at:?}");
    assert!((p.theta - std::f64::consts::FRAC_PI_2).abs() < 0.2, "{p:?}");
}

fn refused(args: &[&str]) -> String {
    let out = navdeck(args);
    assert_eq!(out.status.code(), Some(2), "{args:?} should be refused");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn bad_localisation_input_is_refused_with_the_field_and_value() {
    let why = refused(&["--headless", "--estimator", "mcl"]);
    assert!(why.contains("--map"), "{why}");
    let why = refused(&[
        "--headless",
        "--world",
        TB3,
        "--estimator",
        "mcl",
        "--initial-pose",
        "50,50,0",
    ]);
    assert!(why.contains("off the map"), "{why}");
    let why = refused(&["--headless", "--map", TB3]);
    assert!(why.contains("--estimator mcl"), "{why}");
    let why = refused(&["--headless", "--estimator", "pf"]);
    assert!(why.contains("pf"), "{why}");
    let dir = std::env::temp_dir().join(format!("navdeck-mcl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let config = dir.join("zero.toml");
    std::fs::write(&config, "[localization]\nmin_particles = 0\n").unwrap();
    let why = refused(&["--headless", "--config", config.to_str().unwrap()]);
    assert!(
        why.contains("localization.min_particles") && why.contains(":2"),
        "{why}"
    );
    // A map with no free cell: nowhere for a particle to be.
    std::fs::write(
        dir.join("solid.pgm"),
        b"P5\n4 4\n255\n\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0",
    )
    .unwrap();
    std::fs::write(
        dir.join("solid.yaml"),
        "image: solid.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    .unwrap();
    let map = dir.join("solid.yaml");
    let why = refused(&[
        "--headless",
        "--estimator",
        "mcl",
        "--map",
        map.to_str().unwrap(),
    ]);
    assert!(why.contains("no known free cell"), "{why}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_mission_on_mcl_is_not_lost_for_want_of_markers() {
    // The TurtleBot3 world has no markers: on the EKF alone the mission would call the
    // robot lost; MCL vouches for its pose, and exploration runs to its end.
    let session = Session::load(&spec(TB3, 1, None)).unwrap();
    let localizer = session.localizer.clone();
    let (config, link) = session.into_link();
    let r = navdeck::runners::mission::run(&config, link, localizer.as_ref(), 1, 400.0, false);
    assert_eq!(r.outcome, "delivered all", "{r:?}");
    assert_eq!(r.collisions, Some(0));
    assert!(
        r.warnings.iter().all(|w| !w.contains("lost")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn a_pose_off_the_map_is_refused_with_the_ekf_as_with_mcl() {
    let mut app = common::app_with(SessionSpec::twin(None));
    for k in 1..=5 {
        app.update(0.1 * f64::from(k));
    }
    let before = app.pilot().estimated_pose();
    type_line(&mut app, "pose 100 100 0");
    let last = app.log_book().last().unwrap().text.clone();
    assert!(
        last.contains("pose not set") && last.contains("off the map"),
        "{last}"
    );
    assert_eq!(app.pilot().estimated_pose(), before);
}

#[test]
fn a_kidnap_into_a_wall_is_refused_as_a_start_there_is() {
    let spec = spec(FLAT, 1, None);
    let session = Session::load(&spec).expect("session loads");
    let localizer = session.localizer.clone();
    let (config, link) = session.into_link();
    let into_wall = TourOptions {
        kidnap: Some((1.0, Pose2::new(-100.0, 0.0, 0.0))),
        ..options(1, 2.0)
    };
    let why = tour::run(&config, link, localizer.as_ref(), &into_wall).unwrap_err();
    assert!(
        why.contains("--kidnap") && why.contains("outside the world"),
        "{why}"
    );
}

#[test]
fn a_goal_off_the_map_is_warned_once_with_a_count() {
    let far = TourOptions {
        goals: vec![Point2::new(100.0, 100.0)],
        ..options(1, 5.0)
    };
    let r = tour_of(&spec(FLAT, 1, None), |_| {}, far);
    let off: Vec<&String> = r
        .warnings
        .iter()
        .filter(|w| w.contains("off the map"))
        .collect();
    assert_eq!(off.len(), 1, "{:?}", r.warnings);
    assert!(off[0].contains(" times)"), "{off:?}");
}

fn logged(app: &App, text: &str) -> bool {
    app.log_book().iter().any(|e| e.text.contains(text))
}

#[test]
fn localise_drives_until_mcl_localises_then_stops_and_a_drive_key_takes_over() {
    let mut app = common::app_with(spec(FLAT, 3, Some(InitialPose::Unknown)));
    app.resize(120, 40);
    app.update(0.1);
    let start = app.true_pose().expect("the twin");
    assert!(!app.pilot().mcl().unwrap().status().converged);
    type_line(&mut app, "localise");
    assert!(
        logged(&app, "localise: driving"),
        "{:?}",
        app.log_book().last()
    );
    let mut t = app.now();
    while t < 60.0 && !logged(&app, "MCL has localised, the move stops") {
        t += 0.1;
        app.update(t);
    }
    assert!(
        logged(&app, "MCL has localised, the move stops"),
        "not localised in 60 s"
    );
    let truth = app.true_pose().unwrap();
    let turned = navdeck::geometry::wrap_angle(truth.theta - start.theta).abs();
    let moved = truth.position().distance(start.position());
    assert!(
        moved > 0.05 || turned > 0.1,
        "the move drove: {start:?} to {truth:?}"
    );
    let estimate = app.pilot().estimated_pose();
    assert!(
        estimate.position().distance(truth.position()) < 0.15,
        "{estimate:?} vs {truth:?}"
    );
    // The move's key is released: the robot comes to rest.
    for _ in 0..10 {
        t += 0.1;
        app.update(t);
    }
    assert!(
        app.pilot().commanded().is_zero(),
        "{:?}",
        app.pilot().commanded()
    );
    type_line(&mut app, "localise");
    assert!(logged(&app, "MCL has localised already"));

    // Looking again, then taking the keys: the move stops at once, the log says so.
    type_line(&mut app, "relocalize");
    type_line(&mut app, "localise");
    for _ in 0..5 {
        t += 0.1;
        app.update(t);
    }
    app.handle_key(Key::char('s'), KeyKind::Press, t);
    assert!(logged(&app, "localise: stopped, taken over"));
}

#[test]
fn localise_without_mcl_says_what_it_needs() {
    let mut app = common::app_with(SessionSpec {
        localize: LocalizeChoice {
            estimator: None,
            map: None,
            initial_pose: None,
        },
        ..spec(FLAT, 1, None)
    });
    app.update(0.1);
    type_line(&mut app, "localise");
    assert!(logged(&app, "localise needs MCL"));
}
