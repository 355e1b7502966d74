//! The ROS 2 graph as `navdeck ros2 topics` shows it: the endpoints DDS discovery found,
//! one row per topic (ROS name, ROS types, counts, QoS, rate) and the mismatches that
//! silently break a link (`ros2 topic info -v` shows the same QoS, one endpoint a block).
//! Pure: no network, no clock.

mod endpoint;
pub mod robots;
#[cfg(test)]
mod tests;

use super::config::Reliability;
pub use endpoint::{Durability, Endpoint, Side};
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

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
