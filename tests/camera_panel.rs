//! The camera panel: `v` shows the camera's rate, detection latency and IDs in view with
//! a thumbnail in half blocks, again in braille, and once more hides it.

use crate::common;

use common::render;
use navdeck::app::{App, KeyKind};
use navdeck::config::Config;
use navdeck::data::{Command, SensorFrame};
use navdeck::keymap::{Key, Keymap};
use navdeck::link::{LinkError, RobotLink};
use navdeck::perception::frame::{CameraStatus, Thumbnail};

/// A robot whose camera sends a frame every 0.1 s: left half black, right half white.
struct CameraLink;

impl RobotLink for CameraLink {
    fn label(&self) -> String {
        "camera".into()
    }
    fn send(&mut self, _: &Command) -> Result<(), LinkError> {
        Ok(())
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        let (w, h) = (96, 54);
        let pixels = (0..w * h)
            .map(|i| if i % w < w / 2 { 0 } else { 255 })
            .collect();
        Ok(SensorFrame {
            stamp: now,
            camera: Some(CameraStatus {
                ids: vec![3, 12, 421],
                accepted: 3,
                rejected: 1,
                latency: Some(0.0074),
                thumbnail: Some(Thumbnail {
                    width: w,
                    height: h,
                    pixels,
                }),
                error: None,
            }),
            ..SensorFrame::default()
        })
    }
    fn stop(&mut self) {}
}

fn braille_cells(screen: &str) -> usize {
    screen
        .chars()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
        .count()
}

#[test]
fn v_cycles_the_camera_panel_through_half_blocks_braille_and_off() {
    let mut app = App::new(
        Config::default(),
        Keymap::default_map(),
        Box::new(CameraLink),
        0.0,
    );
    let mut t = 0.0;
    for _ in 0..20 {
        t += 0.1;
        app.update(t);
    }
    assert!(!render(&app).contains("Camera (v)"), "hidden at first");

    app.handle_key(Key::char('v'), KeyKind::Press, t);
    let screen = render(&app);
    assert!(screen.contains("Camera (v)"), "{screen}");
    assert!(screen.contains("10.0 Hz  detect 7.4 ms"), "{screen}");
    assert!(screen.contains("IDs 3 12 421 (1 refused)"), "{screen}");
    assert!(
        screen.matches('▀').count() >= 32 * 9,
        "a 32x9 half-block thumbnail"
    );

    app.handle_key(Key::char('v'), KeyKind::Press, t);
    let screen = render(&app);
    // The black half is full braille cells, the white half blank ones.
    assert!(screen.matches('⣿').count() >= 16 * 9, "{screen}");
    assert!(braille_cells(&screen) >= 16 * 9);

    app.handle_key(Key::char('v'), KeyKind::Press, t);
    assert!(!render(&app).contains("Camera (v)"));
}

#[cfg(feature = "vision")]
#[test]
fn the_twins_camera_shows_the_markers_it_sees_as_dots_not_noise() {
    use navdeck::session::{Session, SessionSpec};
    let mut session = Session::load(&SessionSpec::twin(None)).unwrap();
    session
        .use_sim_camera(None, navdeck::sim::CameraFrames::Whole)
        .unwrap();
    let mut app = session.into_app(0.0);
    let mut t = 0.0;
    for _ in 0..5 {
        t += 0.1;
        app.update(t);
    }
    app.handle_key(Key::char('v'), KeyKind::Press, t);
    app.handle_key(Key::char('v'), KeyKind::Press, t);
    let screen = render(&app);
    assert!(
        screen.contains("IDs 5 6 9"),
        "markers in view at the start: {screen}"
    );
    let inked = braille_cells(&screen);
    // Eight markers a few pixels each: dots where they are, not a panel of noise.
    assert!((4..=60).contains(&inked), "{inked} inked cells\n{screen}");
}
