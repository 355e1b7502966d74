//! Route mode's tag graph in RViz: a runtime on navdeck's ROS 2 link, with a tag map laid
//! and a route asked for, publishes the graph as visualization_msgs/MarkerArray on
//! navdeck/tag_graph, and a Cyclone DDS reader in the built distribution's Marker layout
//! (tests/interop/tag_graph_peer.py, standing in for RViz) gets the tags, their labels
//! and the route's strip through them in order; a graph with a blocked edge then brings
//! the edge in red.

use crate::connect_loopback;
use crate::cyclone_peer::{LinePeer, PATIENCE};
use navdeck::config::Config;
use navdeck::geometry::Point2;
use navdeck::link::ros2::config::Distro;
use navdeck::link::runtime::Runtime;
use navdeck::link::{Picture, TagGraphPicture};
use navdeck::pilot::Intent;
use navdeck::pilot::tag_route::TagGoal;
use navdeck::tags::TagMap;
use navdeck::tags::drive::DriveSetup;
use serde_json::Value;
use std::sync::Arc;
use std::time::{Duration, Instant};

const DOMAIN: u16 = 98;

/// Three tags east of the dock, the robot on the dock (the origin, looking east).
const MAP: &str = "tags:
  1: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
  2: {x: 0.6, y: 0.0, type: waypoint, zone: A}
  3: {x: 1.2, y: 0.0, type: waypoint, zone: A}
edges:
  1: [{to: 2, direction: forward, type: straight}]
  2: [{to: 1, direction: backward, type: straight}, {to: 3, direction: forward, type: straight}]
  3: [{to: 2, direction: backward, type: straight}]
";

/// The peer's next graph report for which `done` holds, while `step` runs between
/// lines; panics after PATIENCE seconds.
fn graph_until(
    peer: &LinePeer,
    what: &str,
    mut step: impl FnMut(),
    done: impl Fn(&Value) -> bool,
) -> Value {
    let give_up = Instant::now() + Duration::from_secs_f64(PATIENCE);
    loop {
        step();
        if let Ok(line) = peer.lines.recv_timeout(Duration::from_millis(20)) {
            let record: Value = serde_json::from_str(&line)
                .unwrap_or_else(|e| panic!("the peer said {line:?}: {e}"));
            if done(&record["graph"]) {
                return record["graph"].clone();
            }
        }
        assert!(Instant::now() < give_up, "no {what} reached the peer");
    }
}

fn points(v: &Value) -> Vec<(f64, f64)> {
    (v.as_array().unwrap_or(&Vec::new()).iter())
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect()
}

#[test]
fn route_modes_tag_graph_and_route_reach_an_rviz_reader_as_markers() {
    let distro = match Config::default().ros2.distro {
        Distro::Humble => "humble",
        Distro::Jazzy => "jazzy",
    };
    let Some(peer) = LinePeer::start_with("tag_graph_peer.py", DOMAIN, &[distro]) else {
        return;
    };
    let config = Config::default();
    let link = connect_loopback(DOMAIN, |_| {}).expect("ROS 2 link");
    let mut robot = Runtime::new(Box::new(link), config.pilot_settings(), 0.0);
    let map = Arc::new(TagMap::parse(MAP).unwrap());
    robot
        .pilot_mut()
        .set_tag_map(Some(map), DriveSetup::default());
    robot.tick(0.0, vec![Intent::TagRoute(TagGoal::Tag(3))]);
    let started = Instant::now();
    let graph = graph_until(
        &peer,
        "graph with a route",
        || {
            robot.tick(started.elapsed().as_secs_f64(), Vec::new());
        },
        |g| !g["route"].is_null(),
    );
    assert_eq!(graph["first_action"], 3, "DELETEALL first: {graph}");
    assert_eq!(graph["frame"], "map");
    // DELETEALL, the tags, the edges, the route, the next tag, three labels.
    assert_eq!(graph["count"], 1 + 4 + 3, "{graph}");
    assert_eq!(graph["kinds"]["tag_graph/0"], 6, "a CUBE_LIST: {graph}");
    assert_eq!(graph["kinds"]["tag_graph/1"], 5, "a LINE_LIST: {graph}");
    assert_eq!(
        points(&graph["route"]),
        vec![(0.0, 0.0), (0.6, 0.0), (1.2, 0.0)]
    );
    let green = &graph["route_rgb"];
    assert!(
        green[1].as_f64().unwrap() > green[0].as_f64().unwrap(),
        "{green}"
    );
    // On the first leg: heading for tag 2.
    assert_eq!(graph["next"][0], 0.6, "{graph}");
    assert_eq!(graph["labels"], serde_json::json!(["1", "2", "3"]));
    assert!(graph["blocked"].is_null(), "{graph}");

    // A graph with the edge 2-3 found blocked, shown by hand: the edge comes in red.
    let blocked = TagGraphPicture {
        tags: vec![
            (1, Point2::new(0.0, 0.0)),
            (2, Point2::new(0.6, 0.0)),
            (3, Point2::new(1.2, 0.0)),
        ],
        edges: vec![(1, 2), (2, 1), (2, 3), (3, 2)],
        route: vec![2, 1],
        leg: Some(0),
        blocked: vec![(2, 3)],
    };
    let picture = Picture {
        tag_graph: Some(blocked),
        ..Picture::default()
    };
    let graph = graph_until(
        &peer,
        "graph with a blocked edge",
        || robot.link_mut().show(&picture),
        |g| !g["blocked"].is_null(),
    );
    assert_eq!(points(&graph["blocked"]), vec![(0.6, 0.0), (1.2, 0.0)]);
    assert_eq!(graph["blocked_rgb"], serde_json::json!([1.0, 0.1, 0.1]));
    assert_eq!(points(&graph["route"]), vec![(0.6, 0.0), (0.0, 0.0)]);
    assert_eq!(graph["next"][0], 0.0, "{graph}");
}
