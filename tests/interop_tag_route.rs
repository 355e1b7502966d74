//! Route mode on a ROS 2 robot's own tag camera (seed 003 §1.2.2): a stand-in robot on
//! Eclipse Cyclone DDS (tests/interop/tag_robot_peer.py) integrates /cmd_vel, publishes
//! /odom, and draws the warehouse floor's AprilTags as its downward camera sees them,
//! published as mono8 on /rgb with /camera_info. Headless navdeck reads the tags from
//! those frames through the calibration it was sent, and drives a route to a tag; the
//! peer's own pose says where the robot came to rest.

use crate::common::scratch;
use crate::cyclone_peer::LinePeer;
use nalgebra::Vector3;
use navdeck::perception::tag_camera::TagCameraConfig;
use navdeck::perception::tag_patterns::TagPatterns;
use navdeck::tags::TagMap;
use serde_json::{Value, json};

use std::process::Command;

const WAREHOUSE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/tag_warehouse.yaml");

/// The peer's scene: the camera (a 640x360 image behind the tag camera's 76° lens and on
/// its mount) and every tag of the map with its cells, the robot on the dock.
fn scene(map: &TagMap, camera: &TagCameraConfig) -> Value {
    let mount = camera.mount();
    let axis = |v: Vector3<f64>| mount.rotate_to_robot(v);
    let (x, y, z) = (axis(Vector3::x()), axis(Vector3::y()), axis(Vector3::z()));
    let lens = mount.to_robot(Vector3::zeros());
    let (w, h) = (640.0, 360.0);
    // Pinhole focal length from the field of view (Hartley & Zisserman 6.1).
    let f = w / 2.0 / (camera.hfov_deg.to_radians() / 2.0).tan();
    let mut patterns = TagPatterns::new().unwrap();
    let tags: Vec<Value> = (map.tags.iter())
        .filter_map(|(id, tag)| {
            let cells = patterns.cells(*id)?;
            let heading = tag.zone.heading();
            let bits: String = cells.iter().map(|w| if *w { '1' } else { '0' }).collect();
            Some(json!({"id": id, "centre": [tag.x, tag.y],
                "up": [heading.cos(), heading.sin()], "cells": bits}))
        })
        .collect();
    let dock = &map.tags[&map.dock];
    let look = camera.look().unwrap();
    let heading = dock.zone.heading();
    json!({
        "width": w as u32, "height": h as u32, "fx": f, "fy": f, "cx": (w - 1.0) / 2.0, "cy": (h - 1.0) / 2.0,
        "mount_r": [[x.x, y.x, z.x], [x.y, y.y, z.y], [x.z, y.z, z.z]],
        "mount_t": [lens.x, lens.y, lens.z],
        "cell": camera.tag_side / 8.0,
        "tags": tags,
        "start": [dock.x - look * heading.cos(), dock.y - look * heading.sin(), heading],
        "rate": 15.0,
    })
}

#[test]
fn route_mode_drives_a_ros2_robot_to_a_tag_by_its_own_camera_and_camera_info() {
    let domain = 97u16;
    let map = TagMap::parse(&std::fs::read_to_string(WAREHOUSE).unwrap()).unwrap();
    let camera = TagCameraConfig::default();
    let dir = scratch("tag_route_peer");
    let scene_path = dir.join("scene.json");
    std::fs::write(&scene_path, scene(&map, &camera).to_string()).unwrap();
    let out = dir.join("peer.json");
    let cfg = dir.join("navdeck.toml");
    std::fs::write(
        &cfg,
        "[robot]\ntrack = 0.16\ncontrol_period = 0.0333\n[ros2]\ninterfaces = [\"127.0.0.1\"]\n",
    )
    .unwrap();
    let (scene_arg, out_arg) = (scene_path.to_str().unwrap(), out.to_str().unwrap());
    let Some(peer) = LinePeer::start_with("tag_robot_peer.py", domain, &[scene_arg, out_arg])
    else {
        return;
    };
    let navdeck = Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args([
            "--link",
            "ros2",
            "--domain",
            &domain.to_string(),
            "--config",
        ])
        .arg(&cfg)
        .args(["--tags", WAREHOUSE])
        .args(["--headless", "--json", "--key-rate", "4"])
        .args(["--keys", "i:route tag 117<enter>"])
        .output()
        .expect("run navdeck");
    assert!(peer.finish(), "the peer failed");
    assert!(
        navdeck.status.success(),
        "navdeck failed: {}",
        String::from_utf8_lossy(&navdeck.stderr)
    );
    let report: Value = serde_json::from_slice(&navdeck.stdout).unwrap();
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let route = report["route"].as_str().unwrap_or_default();
    assert_eq!(route, "route: tag 117 done, on tag 117", "{report:#}");
    // Where the robot came to rest, by the peer's own integration: tag 117 under the
    // camera's floor point, facing from 104 to 117 after the quarter turn at 104.
    let pose: Vec<f64> = serde_json::from_value(record["pose"].clone()).unwrap();
    let (tag, from) = (&map.tags[&117], &map.tags[&104]);
    let look = camera.look().unwrap();
    let (fx, fy) = (
        pose[0] + look * pose[2].cos(),
        pose[1] + look * pose[2].sin(),
    );
    let miss = (fx - tag.x).hypot(fy - tag.y);
    let (c, s) = (pose[2].cos(), pose[2].sin());
    let (along, side) = (
        (fx - tag.x) * c + (fy - tag.y) * s,
        -(fx - tag.x) * s + (fy - tag.y) * c,
    );
    // To the side within seed 003 §2.5's alignment bound; along the way the stop comes
    // on a frame that is a camera period and a transfer old, so later under load.
    assert!(
        side.abs() < 0.05,
        "{side:.3} m to the side of tag 117: {record}"
    );
    assert!(
        along.abs() < 0.08,
        "{along:.3} m along from tag 117: {record}"
    );
    let way = (tag.y - from.y).atan2(tag.x - from.x);
    let off = navdeck::geometry::wrap_angle(pose[2] - way)
        .abs()
        .to_degrees();
    assert!(off < 5.0, "heading {off:.2} degrees off: {pose:?}");
    // A frame may come before the first camera_info; no frame went unread for another
    // reason (a calibration refused, a frame of another size).
    let warnings: Vec<String> = serde_json::from_value(report["warnings"].clone()).unwrap();
    let waiting = "tag camera rgb: waiting for the camera's calibration (camera_info)";
    let camera = warnings
        .iter()
        .filter(|w| w.contains("tag camera") && *w != waiting);
    assert_eq!(camera.count(), 0, "{warnings:?}");
    eprintln!(
        "tag route over ROS 2: rest {miss:.4} m off ({along:.4} along, {side:.4} side), heading {off:.2} deg, {} frames, {route:?}",
        record["frames"]
    );
}
