//! The screen states the truth and cuts no text it cannot show: status rows wrap and keep
//! the ones a user needs most at any size, a delivered block is where it was put down,
//! the Path row does not outlive its goal, a recording shows in the header, a link that
//! never answered is awaited rather than lost, a replay's re-run says it is one, and MCL
//! shows its real particle count, effective sample size and whether it knows the pose.

use crate::common;

use common::*;
use navdeck::app::{App, KeyKind};
use navdeck::keymap::Key;

/// The sizes each screen is checked at: the smallest common one, a roomy one, a very wide one.
const SIZES: [(u16, u16); 3] = [(80, 24), (120, 40), (240, 60)];

/// Runs `app` a control period at a time from its time until `done` or `limit` seconds.
fn run_until(app: &mut App, limit: f64, done: impl Fn(&App) -> bool) {
    let mut t = app.now();
    while !done(app) && t < limit {
        t += 0.1;
        app.update(t);
    }
}

fn press_at(app: &mut App, name: &str) {
    let t = app.now();
    app.handle_key(key(name), KeyKind::Press, t);
}

/// The console drawn at `width` x `height`, laid out for that size.
fn drawn(app: &mut App, width: u16, height: u16) -> String {
    app.resize(width, height);
    render_at(app, width, height)
}

/// The status panel's rows (the right-hand panel's text on a wide screen).
fn status_text(screen: &str, width: u16) -> String {
    let from = usize::from(width - navdeck::app::screen::status_width(width));
    screen
        .lines()
        .map(|l| l.chars().skip(from).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

fn exploring(seconds: f64) -> App {
    let mut app = default_app();
    press_at(&mut app, "e");
    run_until(&mut app, seconds, |_| false);
    app
}

#[test]
fn at_80x24_exploring_the_status_keeps_speed_gripper_and_hits_and_says_blocks_in_words() {
    let mut app = exploring(40.0);
    let screen = drawn(&mut app, 80, 24);
    let status = status_text(&screen, 80);
    for label in [
        "Mode", "Mission", "Link", "Pose", "Speed", "Gripper", "Hits",
    ] {
        assert!(status.contains(label), "{label} missing:\n{screen}");
    }
    assert!(
        status.contains("delivered") && status.contains("found"),
        "{screen}"
    );
    assert!(!status.contains("done"), "no cryptic Blocks row:\n{screen}");
}

#[test]
fn at_60x20_the_status_keeps_mode_link_pose_and_mission() {
    let mut app = exploring(20.0);
    let screen = drawn(&mut app, 60, 20);
    for label in ["Mode", "Mission", "Link", "Pose"] {
        assert!(screen.contains(label), "{label} missing:\n{screen}");
    }
}

#[test]
fn a_long_seen_row_wraps_instead_of_being_cut() {
    let mut app = default_app();
    run_until(&mut app, 0.5, |_| false);
    let seen: Vec<String> = app.in_view().iter().map(|id| id.to_string()).collect();
    assert!(seen.len() >= 7, "{seen:?}");
    let screen = drawn(&mut app, 80, 24);
    // Every ID in view is on the screen, none cut with an ellipsis.
    let status = status_text(&screen, 80);
    let words: Vec<&str> = status.split_whitespace().collect();
    for id in &seen {
        assert!(words.contains(&id.as_str()), "{id} missing:\n{screen}");
    }
    assert!(!status.contains('…'), "{screen}");
}

/// Exploration until the mission has moved on from a goal it reached: the status has no
/// "arrived at" left from it.
#[test]
fn the_path_row_is_cleared_when_the_mission_moves_on() {
    let mut app = default_app();
    press_at(&mut app, "e");
    run_until(&mut app, 60.0, |a| logged(a, "Destination arrived"));
    assert!(logged(&app, "Destination arrived"), "reached a goal");
    let t = app.now() + 1.0;
    run_until(&mut app, t, |_| false);
    assert!(
        app.pilot().route().is_none(),
        "the reached goal's route is gone"
    );
    for (w, h) in SIZES {
        let screen = drawn(&mut app, w, h);
        assert!(!screen.contains("arrived at"), "{screen}");
        insta::assert_snapshot!(format!("no_stale_path_row_{w}x{h}"), screen);
    }
}

/// The first delivered block: drawn and listed where it was put down, as the twin has it.
#[test]
fn a_delivered_block_is_listed_and_drawn_where_it_was_put_down() {
    let mut app = default_app();
    press_at(&mut app, "e");
    run_until(&mut app, 240.0, |a| {
        a.pilot().mission().is_some_and(|m| m.delivered() >= 1)
    });
    let mission = app.pilot().mission().unwrap();
    let block = *mission
        .delivered_blocks()
        .next()
        .expect("a block delivered");
    let twin = app.link().ground_truth().unwrap();
    let truth = twin
        .blocks()
        .iter()
        .find(|b| block.markers.contains(&b.markers[0]))
        .map(|b| b.pose.position())
        .expect("the twin's block");
    assert!(
        block.position.distance(truth) < 0.1,
        "drawn at {:?}, the twin has it at {truth:?}",
        block.position
    );
    let id = block.markers[0];
    assert_eq!(app.delivered_at(id), Some(block.position));
    app.handle_key(
        Key::new(navdeck::keymap::KeyCode::Tab),
        KeyKind::Press,
        app.now(),
    );
    for (w, h) in SIZES {
        let screen = drawn(&mut app, w, h);
        // The table lists gates first: at 80x24 its few rows may not reach the block.
        let row = screen.lines().find(|l| {
            ["red", "blue"]
                .iter()
                .any(|c| l.contains(&format!(" {id} {c} block")))
        });
        assert!(row.is_some() || w == 80, "{screen}");
        assert!(row.is_none_or(|r| r.contains("delivered")), "{screen}");
        insta::assert_snapshot!(format!("delivered_block_{w}x{h}"), screen);
    }
}

/// Recording shows in the header as it runs: a mark, the file's size, the time it has run.
#[test]
fn a_recording_shows_in_the_header_with_its_size_and_time() {
    let dir = scratch("rec-mark");
    let path = dir.join("session.mcap");
    let mut app = default_app();
    run_until(&mut app, 2.0, |_| false);
    navdeck::console::start_recording(&mut app, &path, Default::default(), true).unwrap();
    run_until(&mut app, 44.5, |_| false);
    app.wait_for_recording();
    let (bytes, elapsed) = app.recording_progress().expect("recording");
    assert!((elapsed - 42.5).abs() < 0.2, "{elapsed}");
    assert!(bytes > 0, "chunks written so far");
    for (w, h) in SIZES {
        let screen = drawn(&mut app, w, h);
        let title = screen.lines().next().unwrap().to_string();
        assert!(title.contains("● REC") && title.contains("0:42"), "{title}");
        // The size depends on compression: the snapshot keeps its place, not its digits.
        let size = navdeck::tui::widgets::title::size_text(bytes);
        let screen = screen.replacen(&size, &"9".repeat(size.chars().count()), 1);
        insta::assert_snapshot!(format!("rec_mark_{w}x{h}"), screen);
    }
    app.finish_recording().unwrap().unwrap();
    let screen = drawn(&mut app, 80, 24);
    assert!(!screen.contains("REC"), "the mark goes with the recording");
}

#[test]
fn a_link_that_never_answered_is_awaited_and_only_a_lost_one_is_lost() {
    let (mut app, alive) = common::switched_app("ros2", "no odometry on /odom for 2.0 s", false);
    run_until(&mut app, 1.0, |_| false);
    for (w, h) in SIZES {
        let screen = drawn(&mut app, w, h);
        let title = screen.lines().next().unwrap();
        assert!(title.contains("NO LINK"), "{title}");
        assert!(!screen.contains("LOST"), "{screen}");
        assert!(screen.contains("waiting for robot"), "{screen}");
        insta::assert_snapshot!(format!("no_link_yet_{w}x{h}"), screen);
    }
    alive.store(true, std::sync::atomic::Ordering::SeqCst);
    run_until(&mut app, 1.5, |_| false);
    alive.store(false, std::sync::atomic::Ordering::SeqCst);
    run_until(&mut app, 2.0, |_| false);
    let screen = drawn(&mut app, 80, 24);
    assert!(
        screen.lines().next().unwrap().contains("LINK LOST"),
        "{screen}"
    );
    assert!(!screen.contains("NO LINK"), "{screen}");
}

/// The camera panel says where the markers in view come from when there are no images.
#[test]
fn without_camera_images_the_camera_panel_says_where_sightings_come_from() {
    let mut app = default_app();
    run_until(&mut app, 0.5, |_| false);
    press_at(&mut app, "v");
    let screen = drawn(&mut app, 120, 40);
    assert!(screen.contains("Seen"), "{screen}");
    assert!(screen.contains("twin's marker"), "{screen}");
    assert!(!screen.contains("no camera frames"), "{screen}");
}

fn mcl_spec(
    initial: Option<navdeck::pilot::localize::InitialPose>,
) -> navdeck::session::SessionSpec {
    navdeck::session::SessionSpec {
        world: Some("maps/turtlebot3_world.yaml".into()),
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: navdeck::session::LinkChoice::Sim,
        localize: navdeck::session::LocalizeChoice {
            estimator: Some(navdeck::slam::mcl::config::Estimator::Mcl),
            map: None,
            initial_pose: initial,
        },
    }
}

/// MCL's rows: the particle count it has now and the bounds it keeps, the effective sample
/// size of the last weighing (under the count), no SLAM landmark row.
#[test]
fn mcl_rows_show_the_real_count_and_effective_sample_size() {
    let mut app = app_with(mcl_spec(None));
    let mut ess_below_count = false;
    let mut t = 0.0;
    while t < 3.0 {
        t += 0.1;
        app.update(t);
        if t > 1.0 && t < 2.0 {
            app.handle_key(Key::char('w'), KeyKind::Press, t);
        }
        let st = app.pilot().mcl().unwrap().status();
        ess_below_count |= st.updates > 0 && st.effective < st.particles as f64 - 0.5;
    }
    assert!(ess_below_count, "the ESS is the weights', not the count");
    for (w, h) in SIZES {
        let screen = drawn(&mut app, w, h);
        let status = status_text(&screen, w);
        let st = app.pilot().mcl().unwrap().status();
        assert!(
            status.contains(&format!("{} particles", st.particles)),
            "{screen}"
        );
        assert!(
            status.contains("KLD") && status.contains("500-5000"),
            "{screen}"
        );
        assert!(!status.contains("SLAM"), "{screen}");
        insta::assert_snapshot!(format!("mcl_rows_{w}x{h}"), screen);
    }
}

#[test]
fn mcl_without_an_initial_pose_shows_the_pose_unknown_until_localised() {
    let mut app = app_with(mcl_spec(Some(
        navdeck::pilot::localize::InitialPose::Unknown,
    )));
    run_until(&mut app, 0.3, |_| false);
    assert!(!app.pilot().mcl().unwrap().status().converged);
    let screen = drawn(&mut app, 120, 40);
    let status = status_text(&screen, 120);
    assert!(status.contains("unknown: not localised"), "{screen}");
}

/// Ten seconds of exploration recorded, for the replay's tests.
fn explored_recording(name: &str) -> std::path::PathBuf {
    let path = scratch(name).join("explore.mcap");
    let mut app = default_app();
    navdeck::console::start_recording(&mut app, &path, Default::default(), true).unwrap();
    navdeck::runners::headless::run(&mut app, &[key("e")], 10.0);
    app.finish_recording().unwrap().unwrap();
    path
}

/// The replay's first seconds: the recording holds the map and the landmarks the log
/// already names, not only every five seconds.
#[test]
fn a_replay_shows_the_map_and_landmarks_of_its_first_second() {
    let recorded = navdeck::replay::load(&explored_recording("first-second")).unwrap();
    let first_line = recorded
        .logs
        .iter()
        .find(|l| l.text.contains("new landmark"))
        .expect("a landmark logged");
    let t = first_line.time + 1.0;
    assert!(t < 2.0, "{t}");
    let landmarks = navdeck::record::recorded::Recorded::at(&recorded.landmarks, t);
    assert!(landmarks.is_some_and(|l| !l.is_empty()), "landmarks by {t}");
    let map = navdeck::record::recorded::Recorded::at(&recorded.maps, t);
    assert!(
        map.is_some_and(|g| g.cells.iter().any(|&c| c > 50)),
        "walls by {t}"
    );
}

/// The re-run view (`r`) keeps the REPLAY label the recorded view has.
#[test]
fn the_re_run_view_of_a_replay_says_replay() {
    use navdeck::replay::playback::View;
    use navdeck::tui::events::Step;
    let recorded =
        std::sync::Arc::new(navdeck::replay::load(&explored_recording("re-run")).unwrap());
    for (w, h) in SIZES {
        let steps = vec![
            Step::Wait(0.5),
            press('5'),
            press(' '),
            press('r'),
            Step::Wait(0.2),
        ];
        let (text, player, _) =
            common::replay_played(recorded.clone(), View::AsRecorded, false, (w, h), steps);
        assert_eq!(player.playback.view, View::Rerun);
        let title = text.lines().next().unwrap();
        assert!(title.contains("REPLAY · re-run"), "{title}");
        insta::assert_snapshot!(format!("replay_re_run_{w}x{h}"), text);
    }
}

/// Under MCL the map fits the place the known map maps, not its whole image, and driving
/// paints no free space beyond its walls.
#[test]
fn on_a_known_map_the_view_fits_its_walls_and_scans_stay_inside_them() {
    let mut app = app_with(mcl_spec(None));
    run_until(&mut app, 0.5, |_| false);
    let (_, (w, h)) = app.world_extent();
    assert!(w < 10.0 && h < 10.0 && w > 2.0, "fits {w} x {h} m");
    let mut t = app.now();
    app.handle_key(Key::char('a'), KeyKind::Press, t);
    while t < 3.0 {
        t += 0.1;
        app.update(t);
        let key = if t < 1.5 { 'a' } else { 'w' };
        app.handle_key(Key::char(key), KeyKind::Press, t);
    }
    let known = app.pilot().mcl().unwrap().map().clone();
    let grid = app.pilot().belief().occupancy_grid();
    let outside = (0..grid.cells.len())
        .filter(|&i| grid.cells[i] == 0)
        .filter(|&i| {
            let (cx, cy) = (i % grid.width, i / grid.width);
            let p = navdeck::geometry::Point2::new(
                grid.origin.x + (cx as f64 + 0.5) * grid.resolution,
                grid.origin.y + (cy as f64 + 0.5) * grid.resolution,
            );
            !known.is_known(p)
        })
        .count();
    assert_eq!(outside, 0, "free cells where the known map knows nothing");
}

/// The arm panel's warning is shown whole, wrapped under the joints.
#[test]
fn the_arm_panels_warning_wraps_instead_of_being_cut() {
    let config = scratch("arm").join("arm.toml");
    std::fs::write(&config, "[arm]\n").unwrap();
    let app = navdeck::session::Session::load(&navdeck::session::SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: Some(config),
        keymap: None,
        link: navdeck::session::LinkChoice::Sim,
        localize: Default::default(),
    })
    .unwrap()
    .into_app(0.0);
    let mut steps = vec![
        press('h'),
        press('2'),
        navdeck::tui::events::Step::Wait(2.0),
    ];
    steps.extend(hold('w', 6.0));
    let out = run_script(app, 120, 40, steps);
    let why = out
        .app
        .pilot()
        .arm()
        .unwrap()
        .at_edge
        .clone()
        .expect("stopped at the edge");
    let screen = screen(&out.terminal);
    let last = why.split_whitespace().last().unwrap();
    assert!(screen.contains(last), "'{why}' not shown whole:\n{screen}");
}

/// The load list's columns line up whatever the maps' sizes (`19.2 x 19.2 m` beside
/// `4.0 x 4.0 m`).
#[test]
fn the_load_lists_columns_line_up() {
    let mut app = default_app();
    app.set_maps_dir("maps".into());
    for name in ["l", "down", "up"] {
        press_at(&mut app, name);
    }
    let (entries, _) = app.map_picker().expect("the picker is open");
    assert!(entries.len() >= 2, "{entries:?}");
    let screen = drawn(&mut app, 120, 40);
    let columns: Vec<usize> = screen
        .lines()
        .filter(|l| l.contains(" landmarks "))
        .map(|l| l.find(" m  ").expect("the size column"))
        .collect();
    assert!(columns.len() >= 2, "{screen}");
    assert!(
        columns.windows(2).all(|w| w[0] == w[1]),
        "{columns:?}\n{screen}"
    );
}
