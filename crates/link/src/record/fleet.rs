//! A fleet's recording: one MCAP file in which each robot's stream sits under its own
//! namespace (`/robot1/odom`, `/tb3_0/navdeck/input`, ...), beside the fleet's own calls
//! (`/navdeck/fleet/input`: the ticks, keys and terminal sizes the fleet was given, so
//! that selection and stop-all replay too). One writer thread writes the file for all.
//!
//! Reading it back splits the file into one recording per robot, each as a one-robot
//! recording holds it, and the fleet's own.

use super::reader::RawRecording;
use super::topics::{TOPICS, Topic};
use super::writer::Channel;
use super::{RecordConfig, RecordError, Recorder};
use std::collections::BTreeMap;
use std::path::Path;

/// The fleet's own calls: its ticks, keys and terminal sizes.
pub const FLEET_INPUT: &str = "/navdeck/fleet/input";
/// The metadata record naming the fleet's robots.
pub const FLEET_METADATA: &str = "navdeck_fleet";

/// The namespace a fleet robot's stream sits under: `/NAME`, or `/robotN` (from 1) for
/// a robot whose name has nothing but slashes (the root namespace's).
pub fn prefix_for(name: &str, index: usize) -> String {
    let trimmed = name.trim_matches('/');
    match trimmed.is_empty() {
        true => format!("/robot{}", index + 1),
        false => format!("/{trimmed}"),
    }
}

/// The recorders of a fleet's file: the fleet's own stream and one per robot.
pub struct FleetRecorders {
    pub fleet: Recorder,
    pub robots: Vec<Recorder>,
}

impl Recorder {
    /// Starts recording a fleet to `path` (which must not exist): one stream per name in
    /// `names`, under `prefix_for` each, and the fleet's own. `epoch` as for `create`.
    pub fn create_fleet(
        path: &Path,
        config: &RecordConfig,
        epoch: f64,
        names: &[String],
    ) -> Result<FleetRecorders, RecordError> {
        let prefixes: Vec<String> = (names.iter().enumerate())
            .map(|(i, n)| prefix_for(n, i))
            .collect();
        for (i, p) in prefixes.iter().enumerate() {
            if prefixes[..i].contains(p) {
                return Err(RecordError::Open {
                    path: path.to_path_buf(),
                    why: format!("two robots of the fleet would record under {p}"),
                });
            }
        }
        let mut channels: Vec<Channel> = Vec::new();
        for p in &prefixes {
            channels.extend(
                TOPICS
                    .iter()
                    .map(|(_, name, ty)| (format!("{p}{name}"), *ty)),
            );
        }
        let input_type = TOPICS[Topic::Input.index()].2;
        channels.push((FLEET_INPUT.to_string(), input_type));
        let fleet_channel = channels.len() - 1;
        let started = Self::start(path, config, channels, prefixes.len() + 1)?;
        let robots = (prefixes.iter().enumerate())
            .map(|(r, p)| {
                let own = (0..TOPICS.len()).map(|i| Some(r * TOPICS.len() + i));
                let attached = format!("{}/", p.trim_start_matches('/'));
                Self::stream(path, &started, own.collect(), attached, epoch)
            })
            .collect();
        let mut only_input = vec![None; TOPICS.len()];
        only_input[Topic::Input.index()] = Some(fleet_channel);
        let fleet = Self::stream(path, &started, only_input, String::new(), epoch);
        Ok(FleetRecorders { fleet, robots })
    }
}

/// The fleet's metadata: its robots' names and namespaces, in the fleet's order, and
/// the session time its recording started at.
pub fn fleet_entries(names: &[String], start_time: f64) -> BTreeMap<String, String> {
    let prefixes: Vec<String> = (names.iter().enumerate())
        .map(|(i, n)| prefix_for(n, i))
        .collect();
    let mut entries = BTreeMap::new();
    entries.insert("names".to_string(), names.join(" "));
    entries.insert("prefixes".to_string(), prefixes.join(" "));
    entries.insert("start_time".to_string(), format!("{start_time}"));
    entries.insert("navdeck".to_string(), env!("CARGO_PKG_VERSION").to_string());
    entries
}

/// A fleet's file split: each robot's recording (name, namespace, its messages with the
/// namespace taken off) and the fleet's own calls, as one-robot recordings hold them.
#[derive(Clone, Debug, Default)]
pub struct FleetRaw {
    pub fleet: RawRecording,
    pub robots: Vec<(String, String, RawRecording)>,
}

/// The robots' names and namespaces a recording's fleet metadata gives, when it is a
/// fleet's. Names and namespaces are one word each, as many of one as of the other.
pub fn fleet_of(raw: &RawRecording) -> Option<Result<Vec<(String, String)>, String>> {
    let (_, entries) = raw.metadata.iter().find(|(n, _)| n == FLEET_METADATA)?;
    let words = |key: &str| -> Vec<String> {
        entries
            .get(key)
            .map(|v| v.split_whitespace().map(str::to_string).collect())
            .unwrap_or_default()
    };
    let (names, prefixes) = (words("names"), words("prefixes"));
    if names.is_empty() || names.len() != prefixes.len() {
        return Some(Err(format!(
            "metadata {FLEET_METADATA}: names = {:?} and prefixes = {:?} do not name the same robots",
            entries.get("names").map_or("", String::as_str),
            entries.get("prefixes").map_or("", String::as_str)
        )));
    }
    if let Some(p) = prefixes.iter().find(|p| !p.starts_with('/') || p.len() < 2) {
        return Some(Err(format!(
            "metadata {FLEET_METADATA}: prefix {p:?} is not a namespace"
        )));
    }
    Some(Ok(names.into_iter().zip(prefixes).collect()))
}

/// Splits `raw`, a fleet's recording of `robots` (name, namespace), into each robot's
/// and the fleet's own. The file's damage stays with the fleet's.
pub fn split(raw: RawRecording, robots: &[(String, String)]) -> FleetRaw {
    let blank = || RawRecording {
        profile: raw.profile.clone(),
        library: raw.library.clone(),
        ..RawRecording::default()
    };
    let mut out = FleetRaw {
        fleet: blank(),
        robots: (robots.iter())
            .map(|(n, p)| (n.clone(), p.clone(), blank()))
            .collect(),
    };
    out.fleet.damage = raw.damage;
    let input: std::sync::Arc<str> = Topic::Input.name().into();
    for mut m in raw.messages {
        if &*m.topic == FLEET_INPUT {
            m.topic = input.clone();
            out.fleet.messages.push(m);
            continue;
        }
        match owner(&out.robots, &m.topic, true) {
            Some((i, len)) => {
                m.topic = m.topic[len..].into();
                out.robots[i].2.messages.push(m);
            }
            None => out.fleet.messages.push(m),
        }
    }
    for (name, data) in raw.attachments {
        match owner(&out.robots, &name, false) {
            Some((i, len)) => out.robots[i].2.attachments.push((name[len..].into(), data)),
            None => out.fleet.attachments.push((name, data)),
        }
    }
    for (name, entries) in raw.metadata {
        match owner(&out.robots, &name, false) {
            Some((i, len)) => out.robots[i].2.metadata.push((name[len..].into(), entries)),
            None if name == FLEET_METADATA => {
                out.fleet.metadata.push(("navdeck".to_string(), entries))
            }
            None => out.fleet.metadata.push((name, entries)),
        }
    }
    out
}

/// The robot whose namespace `name` is under, the longest one (`/a/b/odom` is `/a/b`'s,
/// not `/a`'s), and how many bytes of `name` the namespace takes: a topic's (`topic`:
/// `/NS` then `/...`) or an attachment's or metadata record's (`NS/...`).
fn owner(
    robots: &[(String, String, RawRecording)],
    name: &str,
    topic: bool,
) -> Option<(usize, usize)> {
    (robots.iter().enumerate())
        .filter_map(|(i, (_, p, _))| {
            let len = match topic {
                true => name
                    .strip_prefix(p.as_str())?
                    .starts_with('/')
                    .then_some(p.len())?,
                false => {
                    let dir = p.trim_start_matches('/');
                    let rest = name.strip_prefix(dir)?.strip_prefix('/')?;
                    name.len() - rest.len()
                }
            };
            Some((i, len))
        })
        .max_by_key(|(_, len)| *len)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_robot_gets_its_own_namespace_and_the_root_one_a_number() {
        assert_eq!(prefix_for("robot1", 0), "/robot1");
        assert_eq!(prefix_for("tb3_0", 1), "/tb3_0");
        assert_eq!(prefix_for("/", 2), "/robot3");
    }

    fn message(topic: &str) -> super::super::reader::RawMessage {
        super::super::reader::RawMessage {
            topic: topic.into(),
            schema: "navdeck_msgs/msg/Input".into(),
            encoding: "cdr".into(),
            log_time: 0,
            data: Vec::new(),
        }
    }

    #[test]
    fn each_message_goes_to_the_robot_of_the_longest_namespace_it_is_under() {
        let mut raw = RawRecording::default();
        for topic in ["/a/odom", "/a/b/odom", "/ab/odom", FLEET_INPUT, "/other"] {
            raw.messages.push(message(topic));
        }
        raw.attachments
            .push(("a/b/config.toml".into(), b"b".to_vec()));
        raw.metadata.push(("a/navdeck".into(), BTreeMap::new()));
        raw.damage = Some("offset 9: cut short".into());
        let robots = [
            ("a".to_string(), "/a".to_string()),
            ("b".to_string(), "/a/b".to_string()),
        ];
        let parts = split(raw, &robots);
        let topics = |r: &RawRecording| -> Vec<String> {
            r.messages.iter().map(|m| m.topic.to_string()).collect()
        };
        assert_eq!(topics(&parts.robots[0].2), ["/odom"]);
        assert_eq!(topics(&parts.robots[1].2), ["/odom"]);
        assert_eq!(
            topics(&parts.fleet),
            ["/ab/odom", "/navdeck/input", "/other"]
        );
        assert_eq!(parts.robots[1].2.attachments[0].0, "config.toml");
        assert_eq!(parts.robots[0].2.metadata[0].0, "navdeck");
        assert_eq!(parts.fleet.damage.as_deref(), Some("offset 9: cut short"));
    }

    #[test]
    fn metadata_that_does_not_name_the_robots_is_refused_with_its_values() {
        let mut raw = RawRecording::default();
        let mut entries = BTreeMap::new();
        entries.insert("names".to_string(), "a b".to_string());
        entries.insert("prefixes".to_string(), "/a".to_string());
        raw.metadata.push((FLEET_METADATA.to_string(), entries));
        let err = fleet_of(&raw).unwrap().unwrap_err();
        assert!(err.contains("\"a b\"") && err.contains("\"/a\""), "{err}");
        assert!(fleet_of(&RawRecording::default()).is_none());
    }
}
