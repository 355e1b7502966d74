//! `navdeck ros2 topics` (part of the binary, beside main.rs): joins the DDS domain as
//! `--link ros2` does, listens for a while on the wall clock, and prints every topic
//! with its types, publishers, subscribers, rate, QoS and mismatches (what
//! `ros2 topic list -v` and `ros2 topic info -v` tell, in one table).

use anyhow::{Context, Result};
use navdeck::config::Config;
use navdeck::link::ros2::domain_from;
use navdeck::link::ros2::graph::{self, QosEntry, TopicRow};
use navdeck::link::ros2::raw::Listener;
use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// How often the readers are drained, seconds.
const POLL: f64 = 0.01;

/// How often discovery is asked for new publishers to measure, seconds.
const DISCOVERY_EVERY: f64 = 0.1;

/// `navdeck ros2 ...`: looking at a ROS 2 domain.
#[derive(Debug, clap::Subcommand)]
pub enum Ros2Command {
    /// Every topic on the domain: ROS type, publishers, subscribers, rate, QoS, and the
    /// mismatches that silently keep publishers and subscribers apart.
    Topics(TopicsArgs),
    /// The robots on the domain: namespaces in which something publishes Odometry on
    /// `odom` or reads Twist / TwistStamped on `cmd_vel` (several TurtleBot3s each under
    /// its own namespace), with their odometry's rate, cmd_vel's type, scan and camera.
    Robots(super::ros2_robots::RobotsArgs),
}

/// `navdeck ros2 topics`.
#[derive(Debug, clap::Args)]
pub struct TopicsArgs {
    /// DDS domain ID (default: ROS_DOMAIN_ID, else 0).
    #[arg(long, value_name = "N", value_parser = super::args::parse_domain)]
    domain: Option<u16>,
    /// Namespace of navdeck's own node (over [ros2] namespace); every topic is listed.
    #[arg(long, value_name = "NS")]
    ns: Option<String>,
    /// The [ros2] section (e.g. `interfaces`), as for `--link ros2`.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Seconds to listen: discovery and rates are taken over this time.
    #[arg(long, default_value_t = 2.0, value_name = "SECONDS", value_parser = parse_duration,
          allow_negative_numbers = true)]
    duration: f64,
    /// Also list ROS's own plumbing: ros_discovery_info and services' rq/ and rr/ topics.
    #[arg(long)]
    all: bool,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

/// Seconds to listen: 0.1 to an hour.
pub(super) fn parse_duration(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number of seconds"))?;
    if (0.1..=3600.0).contains(&v) {
        Ok(v)
    } else {
        Err(super::args::outside(v, 0.1, 3600.0, "s"))
    }
}

/// What `--json` prints.
#[derive(Serialize)]
struct Report {
    domain: u16,
    duration_s: f64,
    topics: Vec<TopicRow>,
}

/// Runs a `navdeck ros2 ...` command.
pub fn run(command: &Ros2Command) -> Result<ExitCode> {
    match command {
        Ros2Command::Topics(args) => topics(args),
        Ros2Command::Robots(args) => super::ros2_robots::robots(args),
    }
}

/// Joins the domain as `--link ros2` does (config `config`, navdeck's node under `ns`)
/// and listens for `duration` seconds on the wall clock: the listener, the time it
/// stopped and the domain.
pub(super) fn listen(
    config: Option<&std::path::Path>,
    ns: Option<&str>,
    domain: Option<u16>,
    duration: f64,
    all: bool,
) -> Result<(Listener, f64, u16)> {
    let mut config = match config {
        Some(path) => Config::load(path)?,
        None => Config::default(),
    };
    if let Some(ns) = ns {
        super::args::check_namespace("--ns", ns)?;
        config.ros2.namespace = ns.to_string();
    }
    let domain =
        domain_from(domain, std::env::var("ROS_DOMAIN_ID").ok()).map_err(anyhow::Error::msg)?;
    let mut listener = Listener::join(&config.ros2, domain, all)
        .with_context(|| format!("cannot join DDS domain {domain}"))?;
    // The edge's wall clock: the listener is told the time, it reads none.
    let started = Instant::now();
    let mut next_discovery = 0.0;
    let now = loop {
        let now = started.elapsed().as_secs_f64();
        let discover = now >= next_discovery;
        if discover {
            next_discovery = now + DISCOVERY_EVERY;
        }
        listener.poll(now, discover);
        if now >= duration {
            break now;
        }
        std::thread::sleep(Duration::from_secs_f64(POLL.min(duration - now)));
    };
    for (topic, why) in listener.failures() {
        say_err!("navdeck: no rate for {topic}: {why}");
    }
    Ok((listener, now, domain))
}

fn topics(args: &TopicsArgs) -> Result<ExitCode> {
    let (listener, now, domain) = listen(
        args.config.as_deref(),
        args.ns.as_deref(),
        args.domain,
        args.duration,
        args.all,
    )?;
    let rows = graph::rows(&listener.endpoints(), &listener.rates(now), args.all);
    if args.json {
        let report = Report {
            domain,
            duration_s: args.duration,
            topics: rows,
        };
        sayln!("{}", serde_json::to_string(&report)?);
    } else if rows.is_empty() {
        sayln!(
            "no topics in DDS domain {domain} after {:.1} s (check --domain, ROS_DOMAIN_ID and [ros2] interfaces)",
            args.duration
        );
    } else {
        say!("{}", table(&rows));
    }
    Ok(ExitCode::SUCCESS)
}

/// The rows as an aligned text table with a header.
fn table(rows: &[TopicRow]) -> String {
    let mut cells: Vec<Vec<String>> = vec![
        ["TOPIC", "TYPE", "PUB", "SUB", "HZ", "QOS", "FLAGS"]
            .map(String::from)
            .to_vec(),
    ];
    for r in rows {
        cells.push(vec![
            r.name.clone(),
            r.types.join(", "),
            r.publishers.to_string(),
            r.subscribers.to_string(),
            r.rate_hz.map_or("-".into(), |hz| format!("{hz:.1}")),
            qos_text(&r.qos.publishers, &r.qos.subscribers),
            if r.flags.is_empty() {
                "-".into()
            } else {
                r.flags.join("; ")
            },
        ]);
    }
    // Counts and rates are right-aligned.
    aligned(&cells, &[2, 3, 4])
}

/// `cells` (a header row first) as columns two spaces apart, those in `right`
/// right-aligned.
pub(super) fn aligned(cells: &[Vec<String>], right: &[usize]) -> String {
    let columns = cells.iter().map(Vec::len).max().unwrap_or(0);
    let mut widths = vec![0usize; columns];
    for row in cells {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let mut out = String::new();
    for row in cells {
        let mut line = String::new();
        for (k, (cell, &w)) in row.iter().zip(&widths).enumerate() {
            if k > 0 {
                line.push_str("  ");
            }
            if right.contains(&k) {
                line.push_str(&format!("{cell:>w$}"));
            } else {
                line.push_str(&format!("{cell:<w$}"));
            }
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// "pub reliable/volatile, sub best-effort/volatile": each side's profiles, counted when
/// a side has more than one.
fn qos_text(publishers: &[QosEntry], subscribers: &[QosEntry]) -> String {
    let side = |label: &str, entries: &[QosEntry]| {
        let many = entries.len() > 1;
        let parts: Vec<String> = (entries.iter())
            .map(|e| {
                let depth = e.depth.map_or(String::new(), |d| format!("/{d}"));
                let words = format!(
                    "{}/{}{depth}",
                    graph::reliability_word(e.reliability),
                    graph::durability_word(e.durability)
                );
                if many {
                    format!("{} {words}", e.count)
                } else {
                    words
                }
            })
            .collect();
        (!parts.is_empty()).then(|| format!("{label} {}", parts.join(" + ")))
    };
    let sides: Vec<String> = [side("pub", publishers), side("sub", subscribers)]
        .into_iter()
        .flatten()
        .collect();
    sides.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use navdeck::link::ros2::config::Reliability;
    use navdeck::link::ros2::graph::{Durability, TopicQos};

    fn entry(reliability: Reliability, durability: Durability, count: usize) -> QosEntry {
        QosEntry {
            reliability,
            durability,
            depth: None,
            count,
        }
    }

    #[test]
    fn the_table_is_aligned_under_its_header() {
        let rows = [
            TopicRow {
                name: "/cmd_vel".into(),
                types: vec![
                    "geometry_msgs/msg/Twist".into(),
                    "geometry_msgs/msg/TwistStamped".into(),
                ],
                publishers: 1,
                subscribers: 1,
                rate_hz: Some(0.0),
                qos: TopicQos {
                    publishers: vec![entry(Reliability::Reliable, Durability::Volatile, 1)],
                    subscribers: vec![entry(Reliability::Reliable, Durability::Volatile, 1)],
                },
                flags: vec!["type: Twist pub vs TwistStamped sub".into()],
            },
            TopicRow {
                name: "/odom".into(),
                types: vec!["nav_msgs/msg/Odometry".into()],
                publishers: 2,
                subscribers: 0,
                rate_hz: Some(19.96),
                qos: TopicQos {
                    publishers: vec![
                        entry(Reliability::Reliable, Durability::Volatile, 1),
                        entry(Reliability::BestEffort, Durability::Volatile, 1),
                    ],
                    subscribers: vec![],
                },
                flags: vec![],
            },
        ];
        let text = table(&rows);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].starts_with("TOPIC     TYPE"), "{text}");
        let column = |line: &str, word: &str| line.find(word).unwrap();
        assert_eq!(column(lines[0], "QOS"), column(lines[1], "pub reliable"));
        assert_eq!(column(lines[0], "FLAGS"), column(lines[1], "type: Twist"));
        assert!(lines[2].contains(" 20.0  "), "{text}");
        assert!(
            lines[2].contains("pub 1 reliable/volatile + 1 best-effort/volatile  -"),
            "{text}"
        );
        assert!(lines[1].contains("pub reliable/volatile, sub reliable/volatile"));
    }

    #[test]
    fn durations_outside_a_tenth_of_a_second_to_an_hour_are_refused() {
        assert_eq!(parse_duration("2"), Ok(2.0));
        assert!(parse_duration("0").unwrap_err().contains("0.1..=3600"));
        assert!(parse_duration("soon").unwrap_err().contains("soon"));
    }
}
