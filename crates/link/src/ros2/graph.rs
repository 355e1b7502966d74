//! The ROS 2 graph as `navdeck ros2 topics` shows it: the endpoints DDS discovery found,
//! one row per topic (ROS name, ROS types, counts, QoS, rate) and the mismatches that
//! silently break a link (`ros2 topic info -v` shows the same QoS, one endpoint a block).
//! Pure: no network, no clock.

use super::config::Reliability;
use ros2_client::dds::rustdds::QosPolicies;
use ros2_client::dds::rustdds::discovery::{DiscoveredReaderData, DiscoveredWriterData};
use ros2_client::dds::rustdds::policy;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// Which side of a topic an endpoint is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Side {
    Publisher,
    Subscriber,
}

/// DDS durability, weakest first: a subscriber asking for more than a publisher offers
/// never matches it (DDS 1.4, 2.2.3.4 DURABILITY, "requested vs offered").
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Durability {
    Volatile,
    TransientLocal,
    Transient,
    Persistent,
}

/// One publisher or subscriber as discovery announced it.
#[derive(Clone, Debug, PartialEq)]
pub struct Endpoint {
    /// The DDS topic name, e.g. `rt/cmd_vel`.
    pub topic: String,
    /// The DDS type name, e.g. `geometry_msgs::msg::dds_::Twist_`.
    pub dds_type: String,
    pub side: Side,
    pub reliability: Reliability,
    pub durability: Durability,
    /// Keep-last depth: discovery does not carry it (as `ros2 topic info -v` says
    /// UNKNOWN), so only navdeck's own endpoints could know it.
    pub depth: Option<u32>,
}

impl Endpoint {
    /// A discovered publisher; unannounced QoS is the DDS default for a writer
    /// (reliable, volatile: DDS 1.4, 2.2.3 "Supported QoS" table).
    pub fn from_writer(w: &DiscoveredWriterData) -> Endpoint {
        let t = &w.publication_topic_data;
        Self::with_qos(
            &t.topic_name,
            &t.type_name,
            Side::Publisher,
            t.reliability,
            t.durability,
        )
    }

    /// A discovered subscriber; unannounced QoS is the DDS default for a reader
    /// (best effort, volatile: DDS 1.4, 2.2.3 "Supported QoS" table).
    pub fn from_reader(r: &DiscoveredReaderData) -> Endpoint {
        let t = &r.subscription_topic_data;
        let qos: QosPolicies = t.qos();
        Self::with_qos(
            t.topic_name(),
            t.type_name(),
            Side::Subscriber,
            qos.reliability(),
            qos.durability(),
        )
    }

    fn with_qos(
        topic: &str,
        dds_type: &str,
        side: Side,
        reliability: Option<policy::Reliability>,
        durability: Option<policy::Durability>,
    ) -> Endpoint {
        let reliability = match (reliability, side) {
            (Some(policy::Reliability::Reliable { .. }), _) | (None, Side::Publisher) => {
                Reliability::Reliable
            }
            (Some(policy::Reliability::BestEffort), _) | (None, Side::Subscriber) => {
                Reliability::BestEffort
            }
        };
        let durability = match durability {
            None | Some(policy::Durability::Volatile) => Durability::Volatile,
            Some(policy::Durability::TransientLocal) => Durability::TransientLocal,
            Some(policy::Durability::Transient) => Durability::Transient,
            Some(policy::Durability::Persistent) => Durability::Persistent,
        };
        Endpoint {
            topic: topic.to_string(),
            dds_type: dds_type.to_string(),
            side,
            reliability,
            durability,
            depth: None,
        }
    }
}

/// One QoS profile on one side of a topic, and how many endpoints use it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QosEntry {
    pub reliability: Reliability,
    pub durability: Durability,
    pub depth: Option<u32>,
    pub count: usize,
}

/// The QoS profiles of a topic's publishers and of its subscribers.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TopicQos {
    pub publishers: Vec<QosEntry>,
    pub subscribers: Vec<QosEntry>,
}

/// One row of the table: a topic as a ROS user names it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TopicRow {
    /// The ROS name (`/cmd_vel`), or the DDS name of a topic ROS hides.
    pub name: String,
    /// ROS types (`geometry_msgs/msg/Twist`), sorted; more than one is a mismatch.
    pub types: Vec<String>,
    pub publishers: usize,
    pub subscribers: usize,
    /// Messages a second, when the topic has publishers and was measured.
    pub rate_hz: Option<f64>,
    pub qos: TopicQos,
    /// Mismatches that keep publishers and subscribers apart; empty when none.
    pub flags: Vec<String>,
}

/// Whether a DDS topic is shown: ROS topics (`rt/`) always; ROS's own plumbing
/// (`ros_discovery_info`, services' `rq/` and `rr/`) and other DDS topics with `all`;
/// DDS's built-in topics (`DCPS...`) never.
pub fn shown(dds_topic: &str, all: bool) -> bool {
    if dds_topic.starts_with("DCPS") {
        return false;
    }
    dds_topic.starts_with("rt/") || all
}

/// The ROS name of a DDS topic: `rt/foo` is `/foo`; anything else keeps its DDS name.
pub fn ros_name(dds_topic: &str) -> String {
    match dds_topic.strip_prefix("rt/") {
        Some(rest) => format!("/{rest}"),
        None => dds_topic.to_string(),
    }
}

/// The ROS type of a DDS type (the reverse of `dds_type`):
/// `geometry_msgs::msg::dds_::Twist_` is `geometry_msgs/msg/Twist`; a name without the
/// `dds_` part is kept as it is.
pub fn ros_type(dds_type: &str) -> String {
    let parts: Vec<&str> = dds_type.split("::").collect();
    match parts.as_slice() {
        [package, kind, "dds_", name] if !name.is_empty() => {
            format!(
                "{package}/{kind}/{}",
                name.strip_suffix('_').unwrap_or(name)
            )
        }
        _ => dds_type.to_string(),
    }
}

/// The rows for `endpoints` (navdeck's own already left out) with the rates measured
/// (by DDS topic name), sorted by name; topics `shown` refuses are left out.
pub fn rows(endpoints: &[Endpoint], rates: &BTreeMap<String, f64>, all: bool) -> Vec<TopicRow> {
    let mut by_topic: BTreeMap<&str, Vec<&Endpoint>> = BTreeMap::new();
    for e in endpoints.iter().filter(|e| shown(&e.topic, all)) {
        by_topic.entry(&e.topic).or_default().push(e);
    }
    let mut rows: Vec<TopicRow> = by_topic
        .into_iter()
        .map(|(topic, ends)| {
            let count = |side| ends.iter().filter(|e| e.side == side).count();
            let publishers = count(Side::Publisher);
            let types: BTreeSet<String> = ends.iter().map(|e| ros_type(&e.dds_type)).collect();
            TopicRow {
                name: ros_name(topic),
                types: types.into_iter().collect(),
                publishers,
                subscribers: count(Side::Subscriber),
                rate_hz: (publishers > 0)
                    .then(|| rates.get(topic).copied())
                    .flatten(),
                qos: TopicQos {
                    publishers: profiles(&ends, Side::Publisher),
                    subscribers: profiles(&ends, Side::Subscriber),
                },
                flags: flags(&ends),
            }
        })
        .collect();
    rows.sort_by(|a, b| a.name.cmp(&b.name));
    rows
}

/// The distinct QoS profiles on one side, most used first.
fn profiles(ends: &[&Endpoint], side: Side) -> Vec<QosEntry> {
    let mut seen: BTreeMap<(bool, Durability, Option<u32>), usize> = BTreeMap::new();
    for e in ends.iter().filter(|e| e.side == side) {
        let reliable = e.reliability == Reliability::Reliable;
        *seen.entry((reliable, e.durability, e.depth)).or_default() += 1;
    }
    let mut out: Vec<QosEntry> = seen
        .into_iter()
        .rev()
        .map(|((reliable, durability, depth), count)| QosEntry {
            reliability: if reliable {
                Reliability::Reliable
            } else {
                Reliability::BestEffort
            },
            durability,
            depth,
            count,
        })
        .collect();
    out.sort_by_key(|e| std::cmp::Reverse(e.count));
    out
}

/// What keeps a topic's publishers and subscribers apart: more than one type, a
/// reliable subscriber offered only best effort, a subscriber asking for more
/// durability than is offered. A side with nobody on it is no mismatch.
pub fn flags(ends: &[&Endpoint]) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(flag) = type_flag(ends) {
        out.push(flag);
    }
    let side =
        |side| -> Vec<&Endpoint> { ends.iter().copied().filter(|e| e.side == side).collect() };
    let (pubs, subs) = (side(Side::Publisher), side(Side::Subscriber));
    if pubs.is_empty() {
        return out;
    }
    let best_effort = (pubs.iter())
        .filter(|p| p.reliability == Reliability::BestEffort)
        .count();
    let reliable_subs = (subs.iter())
        .filter(|s| s.reliability == Reliability::Reliable)
        .count();
    if reliable_subs > 0 && best_effort > 0 {
        out.push(if best_effort == pubs.len() {
            "reliability: reliable sub vs best-effort pub (never match)".to_string()
        } else {
            format!(
                "reliability: reliable sub misses {best_effort} of {} pub (best effort)",
                pubs.len()
            )
        });
    }
    // The most durable subscriber against what the publishers offer.
    if let Some(wanted) = subs.iter().map(|s| s.durability).max() {
        let short = pubs.iter().filter(|p| p.durability < wanted).count();
        if short > 0 {
            let offered = (pubs.iter().map(|p| p.durability))
                .filter(|d| *d < wanted)
                .max()
                .unwrap_or(Durability::Volatile);
            let (wanted, offered) = (durability_word(wanted), durability_word(offered));
            out.push(if short == pubs.len() {
                format!("durability: {wanted} sub vs {offered} pub (never match)")
            } else {
                format!(
                    "durability: {wanted} sub misses {short} of {} pub",
                    pubs.len()
                )
            });
        }
    }
    out
}

/// "type: Twist pub vs TwistStamped sub" when a topic carries more than one type; short
/// names unless two packages share one.
fn type_flag(ends: &[&Endpoint]) -> Option<String> {
    let mut sides: BTreeMap<String, BTreeSet<Side>> = BTreeMap::new();
    for e in ends {
        sides
            .entry(ros_type(&e.dds_type))
            .or_default()
            .insert(e.side);
    }
    if sides.len() < 2 {
        return None;
    }
    let short = |t: &str| t.rsplit('/').next().unwrap_or(t).to_string();
    let shorts: BTreeSet<String> = sides.keys().map(|t| short(t)).collect();
    let unique = shorts.len() == sides.len();
    let parts: Vec<String> = sides
        .iter()
        .map(|(t, on)| {
            let name = if unique { short(t) } else { t.clone() };
            let side = match (
                on.contains(&Side::Publisher),
                on.contains(&Side::Subscriber),
            ) {
                (true, true) => "pub+sub",
                (true, false) => "pub",
                _ => "sub",
            };
            format!("{name} {side}")
        })
        .collect();
    Some(format!("type: {}", parts.join(" vs ")))
}

/// A durability as `ros2 topic info -v` would say it, in lower case.
pub fn durability_word(d: Durability) -> &'static str {
    match d {
        Durability::Volatile => "volatile",
        Durability::TransientLocal => "transient-local",
        Durability::Transient => "transient",
        Durability::Persistent => "persistent",
    }
}

/// A reliability in the table's words.
pub fn reliability_word(r: Reliability) -> &'static str {
    match r {
        Reliability::Reliable => "reliable",
        Reliability::BestEffort => "best-effort",
    }
}

#[cfg(test)]
mod tests {
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

    #[test]
    fn unannounced_qos_is_the_dds_default_for_its_side() {
        let w = Endpoint::with_qos("rt/a", TWIST, Publisher, None, None);
        assert_eq!((w.reliability, w.durability), (Reliable, Volatile));
        let r = Endpoint::with_qos("rt/a", TWIST, Subscriber, None, None);
        assert_eq!((r.reliability, r.durability), (BestEffort, Volatile));
        let r = Endpoint::with_qos(
            "rt/a",
            TWIST,
            Subscriber,
            Some(policy::Reliability::Reliable {
                max_blocking_time: ros2_client::dds::rustdds::Duration::ZERO,
            }),
            Some(policy::Durability::TransientLocal),
        );
        assert_eq!((r.reliability, r.durability), (Reliable, TransientLocal));
    }
}
