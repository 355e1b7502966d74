//! What DDS discovery shows of the robot's side: the other participants, the endpoints on
//! the topics navdeck needs, and which type cmd_vel's subscribers read (said in the log
//! when it is found, and warned about when `[ros2] cmd_vel_type` cannot match it).

use super::config::{CmdVelType, Ros2Config};
use super::dds_type;
use crate::{LinkError, Notice};
use ros2_client::dds::rustdds::GUID;
use ros2_client::{Context, NodeName};

/// How often discovery is asked which type cmd_vel's subscribers read, seconds: often
/// until one is found, then now and again.
const DISCOVERY_SEARCH: f64 = 0.05;
const DISCOVERY_EVERY: f64 = 1.0;

/// What discovery showed of the robot's side: other participants, and the endpoints on
/// the topics navdeck needs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Discovered {
    pub(super) participants: usize,
    pub(super) cmd_vel_readers: usize,
    pub(super) odom_writers: usize,
    pub(super) scan_writers: usize,
}

/// What cmd_vel's subscribers were seen to read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Peer {
    Unknown,
    Twist,
    Stamped,
}

/// The DDS names of navdeck's topics on the robot's side, what discovery last showed of
/// them, and when to ask again.
pub(super) struct Discovery {
    cmd_vel_dds: String,
    odom_dds: String,
    scan_dds: String,
    /// What discovery last showed of the other participants.
    pub(super) discovered: Discovered,
    pub(super) peer: Peer,
    next_discovery: f64,
}

impl Discovery {
    /// Nothing discovered yet; the topics of `config` as DDS names them, resolved in
    /// `namespace`.
    pub(super) fn new(
        namespace: &str,
        node_name: &NodeName,
        config: &Ros2Config,
    ) -> Result<Self, LinkError> {
        let c = config;
        let dds_name = |field: &str, topic: &str| {
            super::participant::topic_name(namespace, field, topic)
                .map(|t| t.to_dds_name("rt", node_name, ""))
        };
        let cmd_vel_dds = dds_name("cmd_vel_topic", &c.cmd_vel_topic)?;
        let odom_dds = dds_name("odom_topic", &c.odom_topic)?;
        let scan_dds = dds_name("scan_topic", &c.scan_topic)?;
        Ok(Self {
            cmd_vel_dds,
            odom_dds,
            scan_dds,
            discovered: Discovered::default(),
            peer: Peer::Unknown,
            next_discovery: 0.0,
        })
    }

    /// Asks discovery which type the robot's cmd_vel subscriber reads, and says so.
    /// `own` is one of navdeck's own endpoints: its participant is left out of the counts.
    pub(super) fn check(
        &mut self,
        now: f64,
        context: &Context,
        own: Option<GUID>,
        config: &Ros2Config,
        notices: &mut Vec<Notice>,
    ) {
        if now < self.next_discovery {
            return;
        }
        self.next_discovery = now
            + if self.peer == Peer::Unknown {
                DISCOVERY_SEARCH
            } else {
                DISCOVERY_EVERY
            };
        let own = own.map(|guid| guid.prefix);
        let participant = context.domain_participant();
        let readers = participant.discovered_readers();
        let writers = participant.discovered_writers();
        let mut peers: Vec<_> = readers
            .iter()
            .map(|r| r.reader_proxy.remote_reader_guid.prefix)
            .chain(
                writers
                    .iter()
                    .map(|w| w.writer_proxy.remote_writer_guid.prefix),
            )
            .filter(|p| Some(*p) != own)
            .collect();
        peers.sort();
        peers.dedup();
        let writing = |topic: &str| {
            writers
                .iter()
                .filter(|w| w.publication_topic_data.topic_name == topic)
                .count()
        };
        self.discovered = Discovered {
            participants: peers.len(),
            cmd_vel_readers: readers
                .iter()
                .filter(|r| {
                    r.subscription_topic_data.topic_name == self.cmd_vel_dds
                        && Some(r.reader_proxy.remote_reader_guid.prefix) != own
                })
                .count(),
            odom_writers: writing(&self.odom_dds),
            scan_writers: writing(&self.scan_dds),
        };
        let twist_type = dds_type("geometry_msgs", "Twist");
        let stamped_type = dds_type("geometry_msgs", "TwistStamped");
        let mut seen = Peer::Unknown;
        for r in readers.iter().filter(|r| {
            r.subscription_topic_data.topic_name == self.cmd_vel_dds
                && Some(r.reader_proxy.remote_reader_guid.prefix) != own
        }) {
            let kind = r.subscription_topic_data.type_name();
            if *kind == stamped_type {
                seen = Peer::Stamped;
            } else if *kind == twist_type && seen == Peer::Unknown {
                seen = Peer::Twist;
            }
        }
        if seen == self.peer || seen == Peer::Unknown {
            return;
        }
        self.peer = seen;
        let (found, wrong) = match seen {
            Peer::Stamped => ("TwistStamped", config.cmd_vel_type == CmdVelType::Twist),
            _ => ("Twist", config.cmd_vel_type == CmdVelType::TwistStamped),
        };
        notices.push(if wrong {
            Notice::warn(format!(
                "ROS 2: the robot's {} subscriber reads {found}, but [ros2] cmd_vel_type = {:?}: it will not move (set cmd_vel_type = \"auto\")",
                config.cmd_vel_topic, config.cmd_vel_type
            ))
        } else {
            Notice::info(format!(
                "ROS 2: the robot reads {found} on {}",
                config.cmd_vel_topic
            ))
        });
    }
}
