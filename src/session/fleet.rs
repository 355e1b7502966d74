//! The sessions of a fleet: N twins in one world (`--robots N`), or one robot per ROS 2
//! namespace (`--ns` repeated), each a session of its own with a name.

use super::{LinkChoice, Robot, Ros2Target, Session, SessionSpec};
use crate::link::sim::SimLink;
use crate::sim::fleet::{FleetBoard, spread_starts};
use anyhow::{Result, bail};
use std::sync::{Arc, Mutex};

/// Most robots one console takes.
pub const MAX_ROBOTS: usize = 32;

/// `n` twins in the world of `spec`, robot 1 at the world's start (or `--start`) and the
/// others on free places nearest it; each twin's noise from `spec.seed + i`. Each sees
/// the others with its lidar and camera, runs into them, and finds blocks where the
/// others left them.
pub fn twins(spec: &SessionSpec, n: usize) -> Result<Vec<(String, Session)>> {
    if spec.link != LinkChoice::Sim {
        bail!("--robots needs the twin (--link sim); a ROS 2 fleet is --ns repeated");
    }
    if !(1..=MAX_ROBOTS).contains(&n) {
        bail!("--robots {n}: a console takes 1 to {MAX_ROBOTS} robots");
    }
    let first = Session::load(spec)?;
    let Robot::Twin(twin) = &first.robot else {
        bail!("--robots needs the twin (--link sim)");
    };
    let world = twin.world().clone();
    let radius = first.config.robot.footprint_radius;
    let starts = spread_starts(&world, n, radius).map_err(anyhow::Error::msg)?;
    let board = Arc::new(Mutex::new(FleetBoard::new(&world, &starts, radius)));
    let mut sessions = Vec::with_capacity(n);
    for (i, start) in starts.iter().enumerate() {
        let mut placed = world.clone();
        placed.start = *start;
        let own = SessionSpec {
            seed: spec.seed.wrapping_add(i as u64),
            start: Some(*start),
            ..spec.clone()
        };
        let mut session = Session::load_with_world(&own, placed)?;
        session.robot = match session.robot {
            Robot::Twin(twin) => {
                Robot::Link(Box::new(SimLink::in_fleet(*twin, 0.0, board.clone(), i)))
            }
            link => link,
        };
        sessions.push((format!("robot{}", i + 1), session));
    }
    Ok(sessions)
}

/// One robot per ROS 2 namespace in `namespaces` (at least two, all different), each
/// on its own DDS participant in the same domain; named by its namespace.
pub fn ros2(spec: &SessionSpec, namespaces: &[String]) -> Result<Vec<(String, Session)>> {
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
        sessions.push((name, Session::load(&own)?));
    }
    Ok(sessions)
}
