//! Keepout and speed zones as a console user meets them: typed with `:zone`, drawn in
//! thinking mode with the cursor (z or Z at one corner, again at the opposite one),
//! listed, drawn on the map, refused as a goal, saved with the map as Nav2 filter masks
//! and loaded back.

use crate::common;

use common::{default_app, logged, render_at, scratch};
use navdeck::app::App;
use navdeck::keymap::parse_key_sequence;
use navdeck::map::zones::ZoneKind;
use navdeck::runners::headless;

fn play(app: &mut App, keys: &str) {
    headless::run(app, &parse_key_sequence(keys).unwrap(), 2.0);
}

fn typed_app() -> App {
    let mut app = default_app();
    play(
        &mut app,
        ":zone keepout 0.6 -0.3 1.0 0.3<enter>:zone speed 0.1 -1.0 -1.0 -0.4 -0.5<enter>",
    );
    app
}

#[test]
fn typed_zones_are_listed_drawn_and_a_goal_inside_keepout_is_refused() {
    let mut app = typed_app();
    assert_eq!(app.pilot().zones().len(), 2);
    play(&mut app, ":zone list<enter>:goto 0.8 0<enter>");
    assert!(logged(&app, "zone 1: keepout (0.60, -0.30)..(1.00, 0.30)"));
    assert!(logged(
        &app,
        "zone 2: speed 0.10 m/s (-1.00, -1.00)..(-0.40, -0.50)"
    ));
    assert!(logged(
        &app,
        "no path to (0.80, 0.00): it is inside keepout zone 1"
    ));
    let screen = render_at(&app, 120, 40);
    assert!(screen.contains('░') && screen.contains('='), "{screen}");
    play(
        &mut app,
        ":zone delete 1<enter>:zone speed 0 0 0 1 1<enter>",
    );
    assert_eq!(app.pilot().zones().len(), 1);
    assert!(matches!(
        app.pilot().zones().zones()[0].kind,
        ZoneKind::Speed(_)
    ));
    assert!(
        logged(&app, "zone field `speed` = 0"),
        "a bad zone names its field"
    );
    play(&mut app, ":zone clear<enter>");
    assert!(app.pilot().zones().is_empty());
}

fn drawn_app() -> App {
    let mut app = default_app();
    // Thinking mode: the cursor four rows up and two columns right, z; four columns
    // right and two rows up, z again: a keepout zone. Then Z at a corner to the left and
    // Z again three columns left and two rows down: a speed zone.
    play(&mut app, "tkkkkllzllllkkzhhhhhhhhhhhZhhhjjZ");
    app
}

#[test]
fn zones_are_drawn_with_the_cursor_as_rviz_tools_draw() {
    let app = drawn_app();
    let zones = app.pilot().zones().zones();
    assert_eq!(zones.len(), 2, "{zones:?}");
    assert_eq!(zones[0].kind, ZoneKind::Keepout);
    assert!(matches!(zones[1].kind, ZoneKind::Speed(_)));
    assert!(zones[0].rect.width() > 0.0 && zones[0].rect.height() > 0.0);
    assert!(logged(&app, "keepout zone: corner at"));
}

#[test]
fn drawn_zones_80x24() {
    insta::assert_snapshot!(render_at(&drawn_app(), 80, 24));
}

#[test]
fn zones_are_saved_with_the_map_as_nav2_masks_and_load_back() {
    let dir = scratch("saved");
    let mut app = typed_app();
    app.set_maps_dir(dir.clone());
    play(&mut app, ":save lab<enter>");
    for file in [
        "lab.keepout.yaml",
        "lab.keepout.pgm",
        "lab.keepout_filter_info.yaml",
        "lab.speed.yaml",
        "lab.speed.pgm",
        "lab.speed_filter_info.yaml",
    ] {
        assert!(dir.join(file).is_file(), "{file} written");
    }
    assert!(logged(&app, "2 zones as Nav2 filter masks"));
    // A fresh console loads them beside the map, and `:zone load` takes a Nav2 filter.
    let mut fresh = default_app();
    fresh.load_zones_beside(&dir.join("lab.yaml"));
    assert_eq!(fresh.pilot().zones().len(), 2);
    let mut other = default_app();
    other.set_maps_dir(dir.clone());
    play(&mut other, ":zone load lab.keepout_filter_info.yaml<enter>");
    assert_eq!(other.pilot().zones().len(), 1);
    // Cleared and saved again: the masks are rewritten empty, and load as no zones.
    play(&mut app, ":zone clear<enter>:save lab<enter>");
    let mut again = default_app();
    again.load_zones_beside(&dir.join("lab.yaml"));
    assert!(again.pilot().zones().is_empty());
    // A broken mask is named, never a panic.
    std::fs::write(dir.join("lab.speed.pgm"), b"P5 1 1").unwrap();
    let mut broken = default_app();
    broken.load_zones_beside(&dir.join("lab.yaml"));
    assert!(logged(&broken, "lab.speed.pgm"), "the bad file is named");
}

/// Inside a speed zone the status panel says which limit holds the robot back.
#[test]
fn the_status_panel_names_the_speed_limit_being_kept() {
    let mut app = default_app();
    play(&mut app, "wwwww");
    let before = render_at(&app, 100, 40);
    assert!(!before.contains("speed limit"), "{before}");
    play(&mut app, ":zone speed 0.05 -5 -5 5 5<enter>wwwww");
    let screen = render_at(&app, 100, 40);
    assert!(screen.contains("speed limit 0.05 m/s"), "{screen}");
}
