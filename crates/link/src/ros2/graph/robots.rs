//! The robots on a ROS 2 domain as `navdeck ros2 robots` lists them: every namespace in
//! which something publishes nav_msgs/Odometry on `odom` or reads Twist or TwistStamped
//! on `cmd_vel` (a TurtleBot3's bringup, namespaced as several robots on one domain run
//! it: `/tb3_0/odom`, `/tb3_0/cmd_vel`). Pure: no network, no clock.

use super::{Endpoint, Side, ros_name, ros_type};
use serde::Serialize;
use std::collections::BTreeMap;

const ODOMETRY: &str = "nav_msgs/msg/Odometry";
const TWISTS: [&str; 2] = ["geometry_msgs/msg/Twist", "geometry_msgs/msg/TwistStamped"];

/// One robot: its namespace and what it offers there.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RobotRow {
    /// `/tb3_0`, or `/` for a robot in the root namespace.
    pub namespace: String,
    /// Publishers of Odometry on `NS/odom`, and their rate when measured, Hz.
    pub odom_publishers: usize,
    pub odom_rate_hz: Option<f64>,
    /// The types `NS/cmd_vel`'s subscribers read (Twist on Humble, TwistStamped on Jazzy).
    pub cmd_vel_types: Vec<String>,
    /// Whether `NS/scan` and a camera (`NS/rgb`, `NS/camera/...`) are published.
    pub scan: bool,
    pub camera: bool,
}

/// The namespace and last name of a ROS topic name: `/tb3_0/odom` is (`/tb3_0`, `odom`).
fn split(name: &str) -> (String, &str) {
    match name.rsplit_once('/') {
        Some(("", last)) => ("/".to_string(), last),
        Some((ns, last)) => (ns.to_string(), last),
        None => ("/".to_string(), name),
    }
}

/// The robots `endpoints` show, by namespace, with the rates measured (by DDS topic).
pub fn robots(endpoints: &[Endpoint], rates: &BTreeMap<String, f64>) -> Vec<RobotRow> {
    let ros: Vec<(&Endpoint, String, String, String)> = (endpoints.iter())
        .filter(|e| e.topic.starts_with("rt/"))
        .map(|e| {
            let name = ros_name(&e.topic);
            let (ns, last) = split(&name);
            (e, ns, last.to_string(), ros_type(&e.dds_type))
        })
        .collect();
    let mut found: BTreeMap<String, RobotRow> = BTreeMap::new();
    for (e, ns, last, kind) in &ros {
        let odom = last == "odom" && e.side == Side::Publisher && kind == ODOMETRY;
        let drive =
            last == "cmd_vel" && e.side == Side::Subscriber && TWISTS.contains(&kind.as_str());
        if !(odom || drive) {
            continue;
        }
        let row = found.entry(ns.clone()).or_insert_with(|| RobotRow {
            namespace: ns.clone(),
            ..RobotRow::default()
        });
        if odom {
            row.odom_publishers += 1;
            row.odom_rate_hz = rates.get(&e.topic).copied().or(row.odom_rate_hz);
        } else if !row.cmd_vel_types.contains(kind) {
            row.cmd_vel_types.push(kind.clone());
            row.cmd_vel_types.sort();
        }
    }
    for (e, ns, last, _) in ros.iter().filter(|(e, ..)| e.side == Side::Publisher) {
        if last == "scan"
            && let Some(row) = found.get_mut(ns)
        {
            row.scan = true;
        }
        // A camera's topics: `NS/rgb` (seed 003's) or anything under `NS/camera/`.
        let name = ros_name(&e.topic);
        for row in found.values_mut() {
            let base = row.namespace.trim_end_matches('/');
            let camera =
                name == format!("{base}/rgb") || name.starts_with(&format!("{base}/camera/"));
            row.camera |= camera;
        }
    }
    found.into_values().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ros2::config::Reliability;
    use crate::ros2::graph::Durability;

    fn end(topic: &str, kind: &str, side: Side) -> Endpoint {
        Endpoint {
            topic: format!("rt{topic}"),
            dds_type: kind.to_string(),
            side,
            reliability: Reliability::Reliable,
            durability: Durability::Volatile,
            depth: None,
        }
    }

    const ODOM: &str = "nav_msgs::msg::dds_::Odometry_";
    const TWIST: &str = "geometry_msgs::msg::dds_::Twist_";
    const STAMPED: &str = "geometry_msgs::msg::dds_::TwistStamped_";
    const SCAN: &str = "sensor_msgs::msg::dds_::LaserScan_";
    const IMAGE: &str = "sensor_msgs::msg::dds_::Image_";

    #[test]
    fn namespaced_turtlebots_are_found_each_with_what_it_offers() {
        let ends = [
            end("/tb3_0/odom", ODOM, Side::Publisher),
            end("/tb3_0/cmd_vel", TWIST, Side::Subscriber),
            end("/tb3_0/scan", SCAN, Side::Publisher),
            end("/tb3_1/odom", ODOM, Side::Publisher),
            end("/tb3_1/cmd_vel", STAMPED, Side::Subscriber),
            end("/tb3_1/camera/image_raw", IMAGE, Side::Publisher),
            // A teleop's publisher and a chatter are no robots.
            end("/tb3_1/cmd_vel", TWIST, Side::Publisher),
            end("/chatter", "std_msgs::msg::dds_::String_", Side::Publisher),
            // Odometry on a topic of another name, or the wrong type on odom, neither.
            end("/fleet/odometry", ODOM, Side::Publisher),
            end("/other/odom", TWIST, Side::Publisher),
        ];
        let rates = BTreeMap::from([("rt/tb3_0/odom".to_string(), 29.5)]);
        let found = robots(&ends, &rates);
        let names: Vec<&str> = found.iter().map(|r| r.namespace.as_str()).collect();
        assert_eq!(names, ["/tb3_0", "/tb3_1"]);
        let (a, b) = (&found[0], &found[1]);
        assert_eq!((a.odom_publishers, a.odom_rate_hz), (1, Some(29.5)));
        assert_eq!(a.cmd_vel_types, ["geometry_msgs/msg/Twist"]);
        assert!(a.scan && !a.camera);
        assert_eq!(b.cmd_vel_types, ["geometry_msgs/msg/TwistStamped"]);
        assert!(b.camera && !b.scan && b.odom_rate_hz.is_none());
    }

    #[test]
    fn a_robot_in_the_root_namespace_is_slash_and_one_that_only_drives_counts() {
        let ends = [
            end("/odom", ODOM, Side::Publisher),
            end("/rgb", IMAGE, Side::Publisher),
            end("/bare/cmd_vel", TWIST, Side::Subscriber),
        ];
        let found = robots(&ends, &BTreeMap::new());
        assert_eq!(found[0].namespace, "/");
        assert!(found[0].camera);
        assert_eq!(
            (found[1].namespace.as_str(), found[1].odom_publishers),
            ("/bare", 0)
        );
    }
}
