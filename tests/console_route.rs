//! Route mode in the console (seed 003): `--tags` lays the tag warehouse on the twin's
//! floor, `i` enters route mode, the arrows and enter choose and drive a task, `:route`
//! names a task or a tag, and the map, the route panel and the status panel show the
//! graph, the route and what the run is doing. Without a tag map route mode says what
//! to pass.

use crate::common;
use common::*;
use navdeck::app::{App, KeyKind};
use navdeck::keymap::{Action, Keymap};
use navdeck::pilot::mode::Mode;
use navdeck::pilot::tag_route::TagGoal;
use navdeck::session::{Session, SessionSpec};
use std::path::Path;

/// The console on the twin with the tag warehouse on its floor, as
/// `navdeck --tags maps/tag_warehouse.yaml` opens it.
fn warehouse_app() -> App {
    let spec = SessionSpec::twin(None);
    let tags = Path::new(env!("CARGO_MANIFEST_DIR")).join("maps/tag_warehouse.yaml");
    let session = Session::load_with_tags(&spec, Some(&tags)).expect("session loads");
    session.into_app(0.0)
}

fn press_key(app: &mut App, name: &str) {
    let t = app.now();
    app.handle_key(key(name), KeyKind::Press, t);
}

#[test]
fn i_is_route_mode_in_every_mode_that_does_not_bind_it_and_the_arrows_choose_there() {
    let map = Keymap::default_map();
    for mode in Mode::ALL {
        let bound = map.lookup(mode, key("i"));
        assert_eq!(bound, Some(Action::ModeRoute), "{mode:?}");
    }
    assert_eq!(map.lookup(Mode::Route, key("up")), Some(Action::CursorUp));
    assert_eq!(
        map.lookup(Mode::Route, key("enter")),
        Some(Action::PlanToCursor)
    );
    assert_eq!(map.lookup(Mode::Route, key("ctrl-up")), Some(Action::PanUp));
    assert_eq!(map.lookup(Mode::Route, key("x")), Some(Action::Stop));
    assert_eq!(
        Action::CursorDown.description_in(Mode::Route),
        "choose the route below"
    );
}

#[test]
fn without_a_tag_map_route_mode_says_to_pass_tags() {
    let mut app = default_app();
    press_key(&mut app, "i");
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(logged(
        &app,
        "route mode needs a tag map: start navdeck with --tags FILE"
    ));
    command(&mut app, "route task1");
    assert_eq!(app.pilot().mode(), Mode::Manual);
}

#[test]
fn a_task_chosen_from_the_list_is_planned_and_driven() {
    let mut app = warehouse_app();
    assert!(logged(&app, "tag map: 73 tags, 6 tasks; i for route mode"));
    press_key(&mut app, "i");
    assert_eq!(app.pilot().mode(), Mode::Route);
    assert!(logged(&app, "route mode: choose a task or a tag"));
    // Tasks by name first: all_zones, end_of_a, task1, ...
    let choices = app.route_choices();
    assert_eq!(choices[2], TagGoal::Task("task1".into()));
    assert_eq!(choices.len(), 6 + 73);
    press_key(&mut app, "down");
    press_key(&mut app, "down");
    assert_eq!(app.route_pick(), 2);
    press_key(&mut app, "enter");
    assert!(
        logged(&app, "route planned: task task1 by 508 → 101"),
        "{:?}",
        app.log_book().iter().map(|e| &e.text).collect::<Vec<_>>()
    );
    run_to(&mut app, 6.0);
    assert!(logged(&app, "route: at tag 10"));
    let routing = app.pilot().tag_route();
    let (leg, _, _) = routing.current_leg().expect("a leg");
    assert!(leg >= 1, "on leg {leg}");
    assert!(routing.resets() > 0);
    assert!(routing.driving());
}

#[test]
fn route_tag_drives_to_one_tag_and_stop_pauses_it() {
    let mut app = warehouse_app();
    command(&mut app, "route tag 104");
    assert_eq!(app.pilot().mode(), Mode::Route);
    run_to(&mut app, 40.0);
    assert!(
        logged(&app, "route: tag 104 done, on tag 104"),
        "{:?}",
        app.log_book().iter().map(|e| &e.text).collect::<Vec<_>>()
    );
    command(&mut app, "route tag 120");
    run_to(&mut app, 45.0);
    press_key(&mut app, "x");
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(logged(&app, "i drives the route on"));
}

/// Route mode after `seconds` of task1: the panel, the graph with its route, the rows.
fn driving_screen(width: u16, height: u16, seconds: f64) -> String {
    let mut app = warehouse_app();
    app.resize(width, height);
    command(&mut app, "route task1");
    run_to(&mut app, seconds);
    render_at(&app, width, height)
}

#[test]
fn route_panel_graph_and_rows_120x40() {
    let screen = driving_screen(120, 40, 8.0);
    assert!(screen.contains("Route (i)"), "{screen}");
    assert!(screen.contains("═"), "the route is drawn: {screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn route_mode_without_a_run_lists_the_choices_80x24() {
    let mut app = warehouse_app();
    app.resize(80, 24);
    press_key(&mut app, "i");
    run_to(&mut app, 0.5);
    let screen = render_at(&app, 80, 24);
    assert!(screen.contains("> task all_zones"), "{screen}");
    insta::assert_snapshot!(screen);
}
