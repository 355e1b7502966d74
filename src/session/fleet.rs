//! The sessions of a fleet: N twins in one world (`--robots N`), or one robot per ROS 2
//! namespace (`--ns` repeated), each a session of its own with a name.

use super::{LinkChoice, LocalizeChoice, Robot, Ros2Target, Session, SessionSpec};
use crate::fleet::config::FleetEntry;
use crate::link::sim::SimLink;
use crate::sim::World;
use crate::sim::fleet::{FleetBoard, spread_starts};
use anyhow::{Context, Result, bail};
use std::sync::{Arc, Mutex};

/// Most robots one console takes.
pub const MAX_ROBOTS: usize = 32;

/// `n` twins in the world of `spec`, robot 1 at the world's start (or `--start`) and the
/// others on free places nearest it; each twin's noise from `spec.seed + i`. Each sees
/// the others with its lidar and camera, runs into them, and finds blocks where the
/// others left them.
pub fn twins(spec: &SessionSpec, n: usize) -> Result<Vec<(String, Session)>> {
    if !(1..=MAX_ROBOTS).contains(&n) {
        bail!("--robots {n}: a console takes 1 to {MAX_ROBOTS} robots");
    }
    let named: Vec<(String, LocalizeChoice)> = (1..=n)
        .map(|i| (format!("robot{i}"), spec.localize.clone()))
        .collect();
    named_twins(spec, None, &named)
}

/// `twins`, in `world` (one made in memory, e.g. generated) instead of `spec.world`.
pub fn twins_in(spec: &SessionSpec, world: World, n: usize) -> Result<Vec<(String, Session)>> {
    let named: Vec<(String, LocalizeChoice)> = (1..=n)
        .map(|i| (format!("robot{i}"), spec.localize.clone()))
        .collect();
    named_twins(spec, Some(world), &named)
}

/// Twins in the world of `spec` as `twins` places them, each with its name and how it
/// is localised.
fn named_twins(
    spec: &SessionSpec,
    given: Option<World>,
    named: &[(String, LocalizeChoice)],
) -> Result<Vec<(String, Session)>> {
    if spec.link != LinkChoice::Sim {
        bail!("--robots needs the twin (--link sim); a ROS 2 fleet is --ns repeated");
    }
    let first = match given {
        Some(world) => Session::load_with_world(spec, world)?,
        None => Session::load(spec)?,
    };
    let Robot::Twin(twin) = &first.robot else {
        bail!("--robots needs the twin (--link sim)");
    };
    let world = twin.world().clone();
    let radius = first.config.robot.footprint_radius;
    let starts = spread_starts(&world, named.len(), radius).map_err(anyhow::Error::msg)?;
    let board = Arc::new(Mutex::new(FleetBoard::new(&world, &starts, radius)));
    let mut sessions = Vec::with_capacity(named.len());
    for (i, (start, (name, localize))) in starts.iter().zip(named).enumerate() {
        let mut placed = world.clone();
        placed.start = *start;
        let own = SessionSpec {
            seed: spec.seed.wrapping_add(i as u64),
            start: Some(*start),
            localize: localize.clone(),
            ..spec.clone()
        };
        let mut session = Session::load_with_world(&own, placed)?;
        session.robot = match session.robot {
            Robot::Twin(twin) => {
                Robot::Link(Box::new(SimLink::in_fleet(*twin, 0.0, board.clone(), i)))
            }
            link => link,
        };
        sessions.push((name.clone(), session));
    }
    Ok(sessions)
}

/// The robots of the config's `[[fleet]]`, in its order: its twins share one world,
/// each ROS 2 robot has its own participant on `domain` (`--domain`; else
/// ROS_DOMAIN_ID), each serial robot its own port.
pub fn from_entries(
    spec: &SessionSpec,
    entries: &[FleetEntry],
    domain: Option<u16>,
    participant: Option<&crate::link::ros2::Participant>,
) -> Result<Vec<(String, Session)>> {
    if entries.len() > MAX_ROBOTS {
        bail!(
            "[[fleet]]: a console takes at most {MAX_ROBOTS} robots, not {}",
            entries.len()
        );
    }
    let mut sims = Vec::new();
    for e in entries {
        if e.link_choice().map_err(anyhow::Error::msg)? == LinkChoice::Sim {
            sims.push((e.name.clone(), e.localize().map_err(anyhow::Error::msg)?));
        }
    }
    let twin_spec = SessionSpec {
        link: LinkChoice::Sim,
        ..spec.clone()
    };
    let mut twins = match sims.is_empty() {
        true => Vec::new(),
        false => named_twins(&twin_spec, None, &sims)?,
    }
    .into_iter();
    let mut sessions = Vec::with_capacity(entries.len());
    for e in entries {
        let localize = e.localize().map_err(anyhow::Error::msg)?;
        let link = match e.link_choice().map_err(anyhow::Error::msg)? {
            LinkChoice::Sim => {
                sessions.extend(twins.next());
                continue;
            }
            LinkChoice::Ros2(_) => LinkChoice::Ros2(Ros2Target {
                namespace: e.namespace.clone(),
                domain,
            }),
            serial => serial,
        };
        let own = SessionSpec {
            link,
            localize,
            ..spec.clone()
        };
        let session = match (&own.link, participant) {
            (LinkChoice::Ros2(_), Some(shared)) => Session::load_on(&own, shared),
            _ => Session::load(&own),
        }
        .with_context(|| format!("[[fleet]] robot {}", e.name))?;
        sessions.push((e.name.clone(), session));
    }
    Ok(sessions)
}

/// One robot per ROS 2 namespace in `namespaces` (at least two, all different), each
/// on its own DDS participant in the same domain; named by its namespace.
pub fn ros2(
    spec: &SessionSpec,
    namespaces: &[String],
    participant: &crate::link::ros2::Participant,
) -> Result<Vec<(String, Session)>> {
    let LinkChoice::Ros2(target) = &spec.link else {
        bail!("--ns more than once needs --link ros2");
    };
    if namespaces.len() > MAX_ROBOTS {
        bail!(
            "--ns: a console takes at most {MAX_ROBOTS} robots, not {}",
            namespaces.len()
        );
    }
    for (i, ns) in namespaces.iter().enumerate() {
        if namespaces[..i].contains(ns) {
            bail!("--ns {ns} is given twice: each robot needs its own namespace");
        }
    }
    let mut sessions = Vec::with_capacity(namespaces.len());
    for ns in namespaces {
        let own = SessionSpec {
            link: LinkChoice::Ros2(Ros2Target {
                namespace: Some(ns.clone()),
                domain: target.domain,
            }),
            ..spec.clone()
        };
        let name = ns.trim_start_matches('/').to_string();
        let name = if name.is_empty() {
            "/".to_string()
        } else {
            name
        };
        sessions.push((name, Session::load_on(&own, participant)?));
    }
    Ok(sessions)
}

/// The one DDS participant a fleet's ROS 2 robots share, in `domain` (else
/// ROS_DOMAIN_ID) on the config's interfaces.
pub fn shared_participant(
    spec: &SessionSpec,
    domain: Option<u16>,
) -> Result<crate::link::ros2::Participant> {
    let config = match &spec.config {
        Some(path) => crate::config::Config::load(path)?,
        None => crate::config::Config::default(),
    };
    let domain = crate::link::ros2::domain_from(domain, std::env::var("ROS_DOMAIN_ID").ok())
        .map_err(anyhow::Error::msg)?;
    let (participant, _) = crate::link::ros2::participant::participant(&config.ros2, domain)
        .context("cannot join ROS 2")?;
    Ok(participant)
}
