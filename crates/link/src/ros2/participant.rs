//! Joining ROS 2: the DDS participant on the configured interfaces, the node in its
//! namespace, topic names resolved against it, publishers and subscriptions with the
//! configured QoS, and bounded reads.

use super::config::{Qos, Reliability, Ros2Config};
use super::environment::{RosEnvironment, built_distro};
use super::inbox::{Inbox, Urgency};
use crate::{LinkError, Notice};
use ros2_client::{
    Context, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher, QosProfile,
    Subscription,
};
use serde::Serialize;
use serde::de::DeserializeOwned;

/// Messages taken from one topic in one poll at most: a flood cannot stall the console.
const MAX_TAKE: usize = 1000;

/// The DDS type name ROS 2 gives a message: `pkg::msg::dds_::Name_`.
pub fn dds_type(package: &str, name: &str) -> String {
    MessageTypeName::new(package, name).dds_msg_type()
}

/// The ROS 2 domain: `--domain`, else ROS_DOMAIN_ID, else 0 (ros2-client reads no
/// environment itself).
pub fn domain_from(flag: Option<u16>, env: Option<String>) -> Result<u16, String> {
    match (flag, env) {
        (Some(d), _) => Ok(d),
        (None, Some(text)) if !text.trim().is_empty() => text
            .trim()
            .parse::<u16>()
            .ok()
            .filter(|d| *d <= 232)
            .ok_or_else(|| format!("ROS_DOMAIN_ID = {text:?}: expected a number 0..=232")),
        _ => Ok(0),
    }
}

/// Every message waiting on `sub` (at most MAX_TAKE); an unreadable one is a warning.
pub fn take_all<M: DeserializeOwned + 'static>(
    sub: &Subscription<M>,
    topic: &str,
    notices: &mut Vec<Notice>,
) -> Vec<M> {
    let mut out = Vec::new();
    for _ in 0..MAX_TAKE {
        match sub.take() {
            Ok(Some((msg, _))) => out.push(msg),
            Ok(None) => break,
            Err(e) => notices.push(Notice::warn(format!("ROS 2: unreadable {topic}: {e:?}"))),
        }
    }
    out
}

pub fn qos_profile(q: Qos, durable: bool) -> QosProfile {
    use ros2_client::qos::{Durability, History, WhenFull};
    let p = QosProfile::publisher_default()
        .history(History::KeepLast {
            depth: q.depth as usize,
        })
        .durability(if durable {
            Durability::TransientLocal
        } else {
            Durability::Volatile
        });
    match q.reliability {
        Reliability::Reliable => p.reliability_reliable(WhenFull::DEFAULT),
        Reliability::BestEffort => p.reliability_best_effort(),
    }
}

pub(super) fn fail(what: impl std::fmt::Display, e: impl std::fmt::Debug) -> LinkError {
    LinkError::Lost(format!("ROS 2: cannot {what}: {e:?}"))
}

/// A topic name from config, resolved against the namespace when relative (done here:
/// ros2-client would write the root namespace as a double slash).
pub(super) fn topic_name(namespace: &str, field: &str, text: &str) -> Result<Name, LinkError> {
    let bad = |e: &dyn std::fmt::Debug| {
        LinkError::Lost(format!(
            "[ros2] {field} = {text:?} is not a ROS 2 topic name: {e:?}"
        ))
    };
    let absolute = if text.starts_with('/') {
        text.to_string()
    } else {
        format!("{}/{text}", namespace.trim_end_matches('/'))
    };
    match absolute[1..].rsplit_once('/') {
        Some((ns, base)) => Name::new(&format!("/{ns}"), base),
        None => Name::new("/", &absolute[1..]),
    }
    .map_err(|e| bad(&e))
}

/// Makes navdeck's topics, publishers and subscriptions on one node, names resolved
/// against the namespace, refusals naming the config field.
pub struct Factory<'a> {
    pub node: &'a mut Node,
    pub config: &'a Ros2Config,
    pub namespace: &'a str,
}

impl Factory<'_> {
    pub fn topic(
        &mut self,
        field: &str,
        name: &str,
        package: &str,
        kind: &str,
        qos: &QosProfile,
    ) -> Result<ros2_client::dds::rustdds::Topic, LinkError> {
        self.node
            .create_topic(
                &topic_name(self.namespace, field, name)?,
                MessageTypeName::new(package, kind),
                qos,
            )
            .map_err(|e| fail(format!("create topic {name}"), e))
    }

    pub fn publisher<M: Serialize>(
        &mut self,
        field: &str,
        name: &str,
        package: &str,
        kind: &str,
        qos: QosProfile,
    ) -> Result<Publisher<M>, LinkError> {
        let topic = self.topic(field, name, package, kind, &qos)?;
        self.node
            .create_publisher(&topic, Some(qos))
            .map_err(|e| fail(format!("publish {name}"), e))
    }

    pub fn subscription<M: DeserializeOwned + 'static>(
        &mut self,
        field: &str,
        name: &str,
        package: &str,
        kind: &str,
        qos: QosProfile,
    ) -> Result<Subscription<M>, LinkError> {
        let topic = self.topic(field, name, package, kind, &qos)?;
        self.node
            .create_subscription(&topic, Some(qos))
            .map_err(|e| fail(format!("subscribe {name}"), e))
    }

    /// A subscription read by a task on the links' runtime (`inbox`).
    pub fn inbox<M: DeserializeOwned + Send + Sync + 'static>(
        &mut self,
        field: &str,
        name: &str,
        (package, kind): (&str, &str),
        qos: QosProfile,
        urgency: Urgency,
    ) -> Result<Inbox<M>, LinkError> {
        let subscription = self.subscription(field, name, package, kind, qos)?;
        Inbox::read(subscription, urgency)
    }

    pub fn qos(&self) -> QosProfile {
        qos_profile(self.config.qos, false)
    }
}

/// A node on the graph, and what the log should say about how it joined.
pub struct Joined {
    pub context: Context,
    /// The namespace the node is in ("/" for the root).
    pub namespace: String,
    pub node: Node,
    /// The environment's distribution and discovery settings, where they need a word.
    pub notes: Vec<Notice>,
}

/// Joins the DDS domain on the configured interfaces (or loopback alone, when the ROS 2
/// environment asks) and makes a node `name` in the configured namespace.
pub fn join(config: &Ros2Config, domain: u16, name: &str) -> Result<Joined, LinkError> {
    let (context, notes) = participant(config, domain)?;
    join_on(context, notes, config, name)
}

/// A node `name` in the configured namespace on a participant already in the domain: a
/// fleet's robots share one participant, as the nodes of one ROS 2 process do.
pub fn join_on(
    context: Context,
    notes: Vec<Notice>,
    config: &Ros2Config,
    name: &str,
) -> Result<Joined, LinkError> {
    let namespace = if config.namespace.is_empty() {
        "/".to_string()
    } else {
        config.namespace.clone()
    };
    let node_name = NodeName::new(&namespace, name).map_err(|e| {
        LinkError::Lost(format!(
            "[ros2] namespace = {:?} is not a ROS 2 namespace: {e:?}",
            config.namespace
        ))
    })?;
    let node = context
        .new_node(node_name, NodeOptions::new().enable_rosout(false))
        .map_err(|e| fail(format!("create the {name} node"), e))?;
    Ok(Joined {
        context,
        namespace,
        node,
        notes,
    })
}

/// A participant in DDS `domain` on the configured interfaces (or loopback alone, when
/// the ROS 2 environment asks), and what the log should say about the environment.
pub fn participant(config: &Ros2Config, domain: u16) -> Result<(Context, Vec<Notice>), LinkError> {
    let mut builder = ros2_client::dds::rustdds::DomainParticipantBuilder::new(domain);
    let scope = RosEnvironment::from_process().scope(built_distro());
    if scope.localhost_only {
        // ROS_LOCALHOST_ONLY=1 / ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST: loopback only.
        builder = builder.with_only_networks([std::net::IpAddr::from([127, 0, 0, 1])]);
    } else if !config.interfaces.is_empty() {
        let mut addresses = Vec::new();
        for text in &config.interfaces {
            let ip: std::net::IpAddr = text.parse().map_err(|_| {
                LinkError::Lost(format!("[ros2] interfaces: {text:?} is not an IP address"))
            })?;
            addresses.push(ip);
        }
        builder = builder.with_only_networks(addresses);
    }
    let participant = builder
        .build()
        .map_err(|e| fail(format!("join DDS domain {domain}"), e))?;
    let context = Context::from_domain_participant(participant)
        .map_err(|e| fail("start a ROS 2 context", e))?;
    Ok((context, scope.notes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_domain_comes_from_the_flag_then_the_environment() {
        assert_eq!(domain_from(Some(7), Some("3".into())), Ok(7));
        assert_eq!(domain_from(None, Some(" 3 ".into())), Ok(3));
        assert_eq!(domain_from(None, None), Ok(0));
        assert_eq!(domain_from(None, Some(String::new())), Ok(0));
        let err = domain_from(None, Some("lab".into())).unwrap_err();
        assert!(
            err.contains("ROS_DOMAIN_ID") && err.contains("lab"),
            "{err}"
        );
    }

    #[test]
    fn ros_type_names_follow_the_dds_mangling() {
        assert_eq!(
            dds_type("geometry_msgs", "Twist"),
            "geometry_msgs::msg::dds_::Twist_"
        );
    }

    #[test]
    fn bad_topic_names_are_refused_by_field() {
        let err = topic_name("/", "odom_topic", "odom topic")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("odom_topic") && err.contains("odom topic"),
            "{err}"
        );
        let node = NodeName::new("/", "navdeck").unwrap();
        let dds = |ns, t| topic_name(ns, "t", t).unwrap().to_dds_name("rt", &node, "");
        assert_eq!(dds("/", "odom"), "rt/odom");
        assert_eq!(dds("/tb3", "odom"), "rt/tb3/odom");
        assert_eq!(dds("/tb3", "/odom"), "rt/odom");
        assert_eq!(dds("/", "gripper/position"), "rt/gripper/position");
    }
}
