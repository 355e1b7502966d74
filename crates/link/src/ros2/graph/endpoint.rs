//! One publisher or subscriber as DDS discovery announced it, with the QoS it offers or
//! asks for (a DDS default where it announced none).

use crate::ros2::config::Reliability;
use ros2_client::dds::rustdds::QosPolicies;
use ros2_client::dds::rustdds::discovery::{DiscoveredReaderData, DiscoveredWriterData};
use ros2_client::dds::rustdds::policy;
use serde::Serialize;

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

#[cfg(test)]
mod tests {
    use super::*;

    const TWIST: &str = "geometry_msgs::msg::dds_::Twist_";
    use Durability::{TransientLocal, Volatile};
    use Reliability::{BestEffort, Reliable};
    use Side::{Publisher, Subscriber};

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
