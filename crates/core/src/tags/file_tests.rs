//! The tag map file: what it reads, and how a bad one is refused.
use super::*;

const SMALL: &str = "\
tags:
  508: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
  101: {x: 0.5, y: 0.0, type: pivot, zone: A}
  117: {x: 0.5, y: 0.5, type: shelf, zone: B}
edges:
  508:
    - {to: 101, direction: forward, type: straight}
  101:
    - {to: 117, direction: forward, type: pivot}
    - {to: 508, direction: backward, type: straight}
  117:
    - {to: 101, direction: backward, type: straight}
tasks:
  shelf: {waypoints: [508, 117, 508]}
parameters:
  speeds: {linear: 0.3, angular: 0.3}
";

/// `SMALL` with `from` replaced by `to`, which must be in it.
fn with(from: &str, to: &str) -> String {
    assert!(SMALL.contains(from), "{from}");
    SMALL.replacen(from, to, 1)
}

fn refused(text: &str) -> TagMapError {
    TagMap::parse(text).expect_err("refused")
}

#[test]
fn a_map_reads_its_tags_edges_tasks_and_parameters() {
    let m = TagMap::parse(SMALL).unwrap();
    assert_eq!(m.dock, 508);
    assert_eq!(m.tags[&117].zone, Zone::B);
    assert_eq!(m.tags[&117].kind, TagKind::Shelf);
    assert_eq!(m.edge(101, 117).unwrap().kind, EdgeKind::Pivot);
    assert_eq!(m.edge(117, 101).unwrap().direction, Direction::Backward);
    assert!(m.edge(508, 117).is_none());
    assert_eq!(m.tasks["shelf"], vec![508, 117, 508]);
    assert_eq!(m.param_f64("speeds.linear", 0.0), 0.3);
    assert_eq!(m.param_f64("speeds.missing", 0.7), 0.7);
    assert!(m.param("speeds.linear.deeper").is_none());
}

#[test]
fn zones_fix_the_heading_as_the_seed_gives_it() {
    use std::f64::consts::FRAC_PI_2;
    assert_eq!(Zone::A.heading(), 0.0);
    assert_eq!(Zone::Dock.heading(), 0.0);
    assert_eq!(Zone::D.heading(), FRAC_PI_2);
    assert_eq!(Zone::E.heading(), -FRAC_PI_2);
}

#[test]
fn an_edge_to_nowhere_names_both_tags_and_its_line() {
    let e = refused(&with(
        "{to: 117, direction: forward",
        "{to: 999, direction: forward",
    ));
    assert_eq!(e.line, Some(9), "{e}");
    assert_eq!(e.to_string(), "line 9: edge 101 -> 999: no tag 999 in tags");
}

#[test]
fn edges_from_an_unknown_tag_are_refused_at_their_key() {
    let e = refused(&with("  117:\n    - {to: 101", "  118:\n    - {to: 101"));
    assert_eq!(e.line, Some(11), "{e}");
    assert!(e.message.contains("no tag 118"), "{e}");
}

#[test]
fn a_leg_off_the_axes_or_onto_its_own_tag_is_refused() {
    let diagonal = refused(&with("117: {x: 0.5, y: 0.5", "117: {x: 1.0, y: 0.5"));
    assert_eq!(diagonal.line, Some(9), "{diagonal}");
    assert!(
        diagonal.message.contains("runs at 45 degrees"),
        "{diagonal}"
    );
    let own = refused(&with(
        "{to: 101, direction: forward",
        "{to: 508, direction: forward",
    ));
    assert!(own.message.contains("leads to itself"), "{own}");
    assert_eq!(own.line, Some(7), "{own}");
}

#[test]
fn a_task_whose_waypoints_do_not_connect_says_which_pair() {
    // No edge leaves 117 but back to 101; none reaches 117 once 101 -> 117 is gone.
    let cut = with("    - {to: 117, direction: forward, type: pivot}\n", "");
    let e = refused(&cut);
    assert_eq!(e.line, Some(13), "{e}");
    assert_eq!(
        e.message,
        "task shelf: no way along the edges from tag 508 to tag 117"
    );
    let unknown = refused(&with("[508, 117, 508]", "[508, 140, 508]"));
    assert!(
        unknown.message.contains("waypoint 140 is no tag"),
        "{unknown}"
    );
}

#[test]
fn one_dock_is_needed_and_bad_yaml_or_fields_name_their_line() {
    let none = refused(&with("type: dock", "type: waypoint"));
    assert!(none.message.contains("no tag has type dock"), "{none}");
    let two = refused(&with("type: shelf, zone: B", "type: dock, zone: B"));
    assert!(two.message.contains("[117, 508]"), "{two}");
    let zone = refused(&with("zone: B", "zone: F"));
    assert_eq!(zone.line, Some(4), "{zone}");
    let field = refused(&with(
        "type: pivot, zone: A}",
        "type: pivot, zone: A, z: 1}",
    ));
    assert!(field.message.contains("unknown field `z`"), "{field}");
    assert!(!field.message.contains("line"), "{field}");
    assert_eq!(field.line, Some(3), "{field}");
}

fn warehouse() -> TagMap {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../maps/tag_warehouse.yaml");
    TagMap::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn the_warehouse_has_73_tags_in_zones_a_to_e_and_every_one_is_a_round_trip_from_the_dock() {
    let m = warehouse();
    assert_eq!(m.tags.len(), 73);
    assert_eq!(m.dock, 508);
    for zone in [Zone::A, Zone::B, Zone::C, Zone::D, Zone::E] {
        assert!(m.tags.values().filter(|t| t.zone == zone).count() >= 14);
    }
    let none = Default::default();
    for &id in m.tags.keys() {
        let out = m.find_path(508, id, &none).unwrap();
        let back = m.find_path(id, 508, &none).unwrap();
        // A shelf is reached along its own zone's aisle: at most A's 16 tags and 14 more.
        assert!(
            out.len() <= 31 && back.len() == out.len(),
            "{id}: {out:?} {back:?}"
        );
    }
    for name in m.tasks.keys() {
        let route = m.task_route(name, &none).unwrap().unwrap();
        assert_eq!(route.tags.first(), Some(&508), "{name}");
        assert_eq!(route.tags.last(), Some(&508), "{name}");
    }
}

#[test]
fn a_blocked_aisle_in_the_warehouse_leaves_its_shelves_unreachable_and_says_so() {
    let m = warehouse();
    // Aisle B leaves zone A at pivot 104 only.
    let blocked = [(104, 117)].into();
    assert_eq!(
        m.find_path(508, 120, &blocked),
        Err(crate::tags::RouteError::NoPath { from: 508, to: 120 })
    );
    // Zone C is still reached past 104.
    assert!(m.find_path(508, 131, &blocked).is_ok());
}
