//! Lane mode (seed 000 §2-§3): the twin's colour camera and the OpenCV lane pipeline
//! drive the robot round a track, a red light and a lowered barrier hold it, a box on the
//! lane stops it, and a robot without a lane camera says why lane mode cannot start.

use crate::common;
use common::*;
use navdeck::app::KeyKind;
use navdeck::app::mode::Mode;

fn log_text(app: &navdeck::app::App) -> String {
    let lines: Vec<String> = (app.log_book().iter()).map(|e| e.text.clone()).collect();
    lines.join("\n")
}

#[test]
fn a_robot_without_a_lane_camera_says_why_lane_mode_cannot_start() {
    let mut app = default_app();
    app.handle_key(key("k"), KeyKind::Press, 0.1);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(
        logged(&app, "lane mode cannot start: no lane camera"),
        "{}",
        log_text(&app)
    );
}

#[cfg(feature = "vision")]
mod driving {
    use super::*;
    use navdeck::runners::lane::{self, LaneOptions, LaneReport};
    use navdeck::session::{Session, SessionSpec};
    use navdeck::sim::World;
    use navdeck::sim::track::Lighting;
    use std::path::Path;

    /// The built-in course's text with `edit` applied to it.
    fn course(edit: impl Fn(String) -> String) -> World {
        let text = edit(include_str!("../maps/track.toml").to_string());
        World::from_toml(&text, Path::new("course.toml")).unwrap()
    }

    fn drive(world: World, seconds: f64) -> LaneReport {
        let mut session = Session::load_with_world(&SessionSpec::twin(None), world).unwrap();
        session.use_lane_camera(Lighting::NORMAL, 1, None).unwrap();
        let (config, link) = session.into_link();
        let options = LaneOptions {
            seed: 1,
            laps: 5.0,
            time_limit: seconds,
            lighting: "normal".into(),
        };
        lane::run(&config, link, &options).unwrap()
    }

    #[test]
    fn the_robot_keeps_its_lane_round_the_bends() {
        // The first 80 s take the long straight, the tight bend and the sweeping one.
        let r = drive(World::default_track(), 80.0);
        assert!(r.figures.laps > 0.45, "{r:?}");
        assert_eq!(r.figures.out_of_lane_s, 0.0, "{r:?}");
        assert!(r.figures.lateral_max_m < r.figures.in_lane_bound_m, "{r:?}");
        assert_eq!(r.collisions, 0);
        assert!(r.detections.lane_found as f64 > 0.95 * r.detections.frames as f64);
    }

    #[test]
    fn a_red_light_holds_the_robot_before_its_stop_line_until_green() {
        let world = course(|t| {
            t.replace(
                "cycle = { red = 6, green = 8, yellow = 2, offset = 0 }",
                "sequence = [[\"red\", 30], [\"green\", 1000]]",
            )
        });
        let r = drive(world, 45.0);
        assert_eq!(r.figures.red_lights_run, 0, "{r:?}");
        assert!(r.holds.light_stops >= 1, "{r:?}");
        assert!(
            r.detections.light_red > 0 && r.detections.light_green > 0,
            "{r:?}"
        );
        // Held for most of the red, then through the stop line on green.
        assert!(r.holds.held_s > 10.0, "{r:?}");
        assert_eq!(r.figures.lights_passed, 1, "{r:?}");
    }

    #[test]
    fn a_lowered_barrier_holds_the_robot_until_it_rises_and_is_never_touched() {
        let world = course(|t| {
            t.replace("at = 8.2", "at = 2.4").replace(
                "cycle = { down = 5, moving = 2, up = 9, offset = 3 }",
                "cycle = { down = 25, moving = 2, up = 30, offset = 0 }",
            )
        });
        let scene = world.track.clone().unwrap();
        let r = drive(world, 45.0);
        assert_eq!((r.barrier_hits, r.collisions), (0, 0), "{r:?}");
        assert!(r.holds.barrier_stops >= 1, "{r:?}");
        assert!(
            r.detections.barrier_down > 0 && r.detections.barrier_up > 0,
            "{r:?}"
        );
        // Past the arm by the end: 2.4 m round from a start 0.9 m round the course.
        let start_along = scene
            .track
            .project(World::default_track().start.position())
            .along;
        assert!(
            r.figures.laps * scene.track.length() > 2.4 - start_along + 0.3,
            "{r:?}"
        );
    }

    #[test]
    fn a_box_on_the_lane_stops_the_robot_short_of_it() {
        let world = course(|t| {
            t.replace(
                "\n[track]\n",
                "\n[[obstacles]]\ncenter = [0.9, -1.5]\nsize = [0.12, 0.12]\n\n[track]\n",
            )
        });
        let r = drive(world, 30.0);
        assert_eq!(r.collisions, 0, "{r:?}");
        // Stopped before the box: 1.5 m ahead of the start, less the robot and the box.
        assert!(r.distance > 0.8 && r.distance < 1.5 - 0.06, "{r:?}");
    }

    #[test]
    fn the_console_drives_the_track_in_lane_mode_and_its_panel_shows_the_lane() {
        let mut session =
            Session::load_with_world(&SessionSpec::twin(None), World::default_track()).unwrap();
        session.offer_lane_camera(1, None);
        let mut app = session.into_app(0.0);
        app.handle_key(key("k"), KeyKind::Press, 0.05);
        assert_eq!(app.pilot().mode(), Mode::Lane, "{}", log_text(&app));
        let start = app.pilot().estimated_pose();
        for k in 1..=100 {
            app.update(0.05 + f64::from(k) * 0.1);
        }
        let moved = app
            .pilot()
            .estimated_pose()
            .position()
            .distance(start.position());
        assert!(moved > 0.7, "10 s in lane mode moved {moved:.2} m");
        // v shows the lane camera's panel in lane mode (the camera panel elsewhere).
        app.handle_key(key("v"), KeyKind::Press, 10.1);
        let screen = render_at(&app, 120, 40);
        assert!(screen.contains("Lane (v)"), "{screen}");
        assert!(screen.contains("lateral"), "{screen}");
        assert!(screen.contains("LANE"), "{screen}");
        // x stops lane mode, as every autonomous mode.
        app.handle_key(key("x"), KeyKind::Press, 10.3);
        assert_eq!(app.pilot().mode(), Mode::Manual);
    }
}
