//! `navdeck tags` as a user runs it: the warehouse checked, routes planned round a blocked
//! edge, a scan list turned into a route, and a bad map refused at its line.

use crate::common::{navdeck, scratch};

const WAREHOUSE: &str = "maps/tag_warehouse.yaml";

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn the_warehouse_checks_and_a_route_to_a_shelf_leaves_zone_a_at_its_aisle() {
    let out = navdeck(&["tags", "check", WAREHOUSE]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("73 tags"),
        "{}",
        text(&out.stdout)
    );
    let out = navdeck(&["tags", "route", WAREHOUSE, "--to", "150", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let tags: Vec<u64> = v["tags"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_u64().unwrap())
        .collect();
    assert_eq!(tags.first(), Some(&508));
    assert_eq!(tags.last(), Some(&150));
    // Into aisle D from its pivot, 112, with a turn.
    let at = tags.iter().position(|&t| t == 112).unwrap();
    assert_eq!(tags[at + 1], 145);
    assert_eq!(v["legs"][at]["type"], "pivot");
}

#[test]
fn a_blocked_aisle_is_refused_by_name_and_a_scan_list_routes_from_the_dock_and_back() {
    let out = navdeck(&[
        "tags",
        "route",
        WAREHOUSE,
        "--to",
        "120",
        "--blocked",
        "104-117",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("from tag 508 to tag 120"),
        "{}",
        text(&out.stderr)
    );
    let csv = scratch("scan").join("scan.csv");
    std::fs::write(&csv, "item,group_id\nbox,20\nbox,20\ncrate,36\n").unwrap();
    let out = navdeck(&[
        "tags",
        "route-from-scan",
        WAREHOUSE,
        csv.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["scan_tags"], serde_json::json!([120, 136]));
    assert_eq!(v["waypoints"], serde_json::json!([508, 120, 136, 508]));
}

#[test]
fn a_map_with_an_edge_to_nowhere_is_refused_with_the_file_and_line() {
    let bad = scratch("bad").join("bad.yaml");
    let map = std::fs::read_to_string(WAREHOUSE).unwrap().replacen(
        "- {to: 117, direction: forward",
        "- {to: 917, direction: forward",
        1,
    );
    std::fs::write(&bad, &map).unwrap();
    let line = map.lines().position(|l| l.contains("to: 917")).unwrap() + 1;
    let out = navdeck(&["tags", "check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(err.contains("bad.yaml"), "{err}");
    assert!(
        err.contains(&format!("line {line}: edge 104 -> 917: no tag 917")),
        "{err}"
    );
}
