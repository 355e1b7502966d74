//! The rows and flags `ros2 topics` shows, from hand-made endpoints.

use super::*;

fn end(topic: &str, kind: &str, side: Side, r: Reliability, d: Durability) -> Endpoint {
    Endpoint {
        topic: format!("rt/{topic}"),
        dds_type: kind.to_string(),
        side,
        reliability: r,
        durability: d,
        depth: None,
    }
}

const TWIST: &str = "geometry_msgs::msg::dds_::Twist_";
const STAMPED: &str = "geometry_msgs::msg::dds_::TwistStamped_";
use Durability::{TransientLocal, Volatile};
use Reliability::{BestEffort, Reliable};
use Side::{Publisher, Subscriber};

fn one(endpoints: &[Endpoint]) -> TopicRow {
    let rows = rows(endpoints, &BTreeMap::new(), false);
    assert_eq!(rows.len(), 1, "{rows:?}");
    rows.into_iter().next().unwrap()
}

#[test]
fn names_and_types_are_ros_ones() {
    assert_eq!(ros_name("rt/cmd_vel"), "/cmd_vel");
    assert_eq!(ros_name("rt/tb3/odom"), "/tb3/odom");
    assert_eq!(ros_name("ros_discovery_info"), "ros_discovery_info");
    assert_eq!(ros_type(TWIST), "geometry_msgs/msg/Twist");
    assert_eq!(
        ros_type("rcl_interfaces::srv::dds_::ListParameters_Request_"),
        "rcl_interfaces/srv/ListParameters_Request"
    );
    assert_eq!(ros_type("SomeDdsType"), "SomeDdsType");
    // The reverse of the link's own mangling.
    assert_eq!(
        ros_type(&super::super::participant::dds_type("nav_msgs", "Odometry")),
        "nav_msgs/msg/Odometry"
    );
}

#[test]
fn plumbing_is_shown_only_with_all_and_builtins_never() {
    assert!(shown("rt/odom", false));
    for hidden in [
        "ros_discovery_info",
        "rq/navdeck/get_parametersRequest",
        "rr/navdeck/get_parametersReply",
    ] {
        assert!(!shown(hidden, false), "{hidden}");
        assert!(shown(hidden, true), "{hidden}");
    }
    assert!(!shown("DCPSParticipant", true));
}

#[test]
fn twist_against_twist_stamped_is_flagged_by_side() {
    let row = one(&[
        end("cmd_vel", TWIST, Publisher, Reliable, Volatile),
        end("cmd_vel", STAMPED, Subscriber, Reliable, Volatile),
    ]);
    assert_eq!(row.name, "/cmd_vel");
    assert_eq!(
        row.types,
        ["geometry_msgs/msg/Twist", "geometry_msgs/msg/TwistStamped"]
    );
    assert_eq!((row.publishers, row.subscribers), (1, 1));
    assert_eq!(row.flags, ["type: Twist pub vs TwistStamped sub"]);
    // A Twist reader beside it still reads the wrong type for the stamped one.
    let row = one(&[
        end("cmd_vel", TWIST, Publisher, Reliable, Volatile),
        end("cmd_vel", TWIST, Subscriber, Reliable, Volatile),
        end("cmd_vel", STAMPED, Subscriber, Reliable, Volatile),
    ]);
    assert_eq!(row.flags, ["type: Twist pub+sub vs TwistStamped sub"]);
    // Two packages' Twist are told apart by their full names.
    let row = one(&[
        end("t", TWIST, Publisher, Reliable, Volatile),
        end(
            "t",
            "other::msg::dds_::Twist_",
            Subscriber,
            Reliable,
            Volatile,
        ),
    ]);
    assert_eq!(
        row.flags,
        ["type: geometry_msgs/msg/Twist pub vs other/msg/Twist sub"]
    );
}

#[test]
fn a_reliable_subscriber_never_hears_best_effort_publishers() {
    let row = one(&[
        end("scan", TWIST, Publisher, BestEffort, Volatile),
        end("scan", TWIST, Subscriber, Reliable, Volatile),
    ]);
    assert_eq!(
        row.flags,
        ["reliability: reliable sub vs best-effort pub (never match)"]
    );
    // The other way round matches (best effort asks for less).
    let row = one(&[
        end("scan", TWIST, Publisher, Reliable, Volatile),
        end("scan", TWIST, Subscriber, BestEffort, Volatile),
    ]);
    assert!(row.flags.is_empty(), "{:?}", row.flags);
    // One best-effort publisher of two is missed, and said so.
    let row = one(&[
        end("scan", TWIST, Publisher, BestEffort, Volatile),
        end("scan", TWIST, Publisher, Reliable, Volatile),
        end("scan", TWIST, Subscriber, Reliable, Volatile),
    ]);
    assert_eq!(
        row.flags,
        ["reliability: reliable sub misses 1 of 2 pub (best effort)"]
    );
}

#[test]
fn a_latched_subscriber_never_hears_volatile_publishers() {
    let row = one(&[
        end("map", TWIST, Publisher, Reliable, Volatile),
        end("map", TWIST, Subscriber, Reliable, TransientLocal),
    ]);
    assert_eq!(
        row.flags,
        ["durability: transient-local sub vs volatile pub (never match)"]
    );
    let row = one(&[
        end("map", TWIST, Publisher, Reliable, TransientLocal),
        end("map", TWIST, Subscriber, Reliable, Volatile),
    ]);
    assert!(row.flags.is_empty(), "{:?}", row.flags);
}

#[test]
fn a_side_with_nobody_is_no_mismatch() {
    let row = one(&[end("goal", TWIST, Subscriber, Reliable, TransientLocal)]);
    assert_eq!((row.publishers, row.subscribers), (0, 1));
    assert!(row.flags.is_empty());
    assert_eq!(row.rate_hz, None);
    let row = one(&[end("odom", TWIST, Publisher, BestEffort, Volatile)]);
    assert_eq!((row.publishers, row.subscribers), (1, 0));
    assert!(row.flags.is_empty());
}

#[test]
fn rows_are_sorted_with_rates_and_qos_grouped() {
    let endpoints = [
        end("odom", TWIST, Publisher, Reliable, Volatile),
        end("odom", TWIST, Publisher, Reliable, Volatile),
        end("odom", TWIST, Subscriber, BestEffort, Volatile),
        end("cmd_vel", TWIST, Subscriber, Reliable, Volatile),
        Endpoint {
            topic: "ros_discovery_info".into(),
            ..end("x", TWIST, Publisher, Reliable, TransientLocal)
        },
    ];
    let rates = BTreeMap::from([("rt/odom".to_string(), 19.5)]);
    let got = rows(&endpoints, &rates, false);
    let names: Vec<&str> = got.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["/cmd_vel", "/odom"]);
    assert_eq!(got[1].rate_hz, Some(19.5));
    assert_eq!(
        got[1].qos.publishers,
        [QosEntry {
            reliability: Reliable,
            durability: Volatile,
            depth: None,
            count: 2
        }]
    );
    assert_eq!(got[1].qos.subscribers[0].reliability, BestEffort);
    let all = rows(&endpoints, &rates, true);
    assert_eq!(all.len(), 3);
    assert_eq!(all[2].name, "ros_discovery_info");
}
