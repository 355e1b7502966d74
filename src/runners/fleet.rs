//! A fleet's headless run: keys pressed on the selected robot (and the fleet's own keys,
//! which select another or stop them all) on simulated time, or paced by the wall clock
//! for robots on ROS 2; then every robot's report.

use super::headless::{FOLLOW_TIMEOUT, LINK_WAIT, Report, SETTLE, report};
use crate::app::{KeyKind, LinkStatus};
use crate::fleet::Fleet;
use crate::keymap::Key;
use crate::tui::deck::Deck;
use serde::Serialize;

/// What a fleet's headless run did, robot by robot.
#[derive(Debug, Serialize)]
pub struct FleetReport {
    pub navdeck: &'static str,
    pub keys: usize,
    pub sim_time: f64,
    /// Which robot the keys went to at the end (its name).
    pub selected: String,
    pub robots: Vec<RobotReport>,
    /// Session times of each stop-all.
    pub stop_all_times: Vec<f64>,
    /// A run paced by the wall clock: UNIX time at session time 0, so that a peer's
    /// times can be set beside the session's.
    pub epoch_unix: Option<f64>,
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
    /// What the run's recording holds (`--record`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<crate::record::Summary>,
    /// A replay: the robots whose streams could not be replayed whole, and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub broken: Option<Vec<String>>,
}

/// One robot's report in a fleet's.
#[derive(Debug, Serialize)]
pub struct RobotReport {
    pub name: String,
    /// Contacts with another robot of the fleet (the twin's truth), also counted in the
    /// report's collisions.
    pub robot_hits: Option<u32>,
    #[serde(flatten)]
    pub report: Report,
}

/// Presses `keys` at `rate` a simulated second, calling `pace(t)` before the fleet
/// reaches time `t` (the wall clock's pacer for real robots; `|_| true` in the twin).
/// With `every_period` the fleet is brought up to date every control period between
/// keys. A `pace` that returns false ends the run with every robot stopped.
pub fn run(
    fleet: &mut Fleet,
    keys: &[Key],
    rate: f64,
    pace: &mut dyn FnMut(f64) -> bool,
    every_period: bool,
) -> FleetReport {
    let gap = 1.0 / rate;
    let period = fleet.app().config().robot.control_period;
    let start = fleet.app().now();
    let mut t = start;
    let mut step = |fleet: &mut Fleet, t: f64| {
        let go_on = pace(t);
        if go_on {
            fleet.update(t);
        } else {
            fleet.shutdown("headless run interrupted");
        }
        go_on
    };
    let real = |f: &Fleet| (f.members().iter()).any(|m| m.app.link().ground_truth().is_none());
    let all_up =
        |f: &Fleet| (f.members().iter()).all(|m| m.app.pilot().link_status() == &LinkStatus::Ok);
    if real(fleet) {
        // Real robots may take a moment to be discovered: keys wait for every robot.
        if !step(fleet, t) {
            return fleet_report(fleet, keys.len());
        }
        while !all_up(fleet) && t < start + LINK_WAIT {
            t += period;
            if !step(fleet, t) {
                return fleet_report(fleet, keys.len());
            }
        }
    }
    for key in keys {
        if !step(fleet, t) {
            return fleet_report(fleet, keys.len());
        }
        fleet.handle_key(*key, KeyKind::Press, t);
        if fleet.should_quit() {
            return fleet_report(fleet, keys.len());
        }
        let next = t + gap;
        while every_period && t + period < next - 1e-9 {
            t += period;
            if !step(fleet, t) {
                return fleet_report(fleet, keys.len());
            }
        }
        t = next;
    }
    if !step(fleet, t) {
        return fleet_report(fleet, keys.len());
    }
    let busy = |f: &Fleet| f.members().iter().any(|m| m.app.pilot().is_busy());
    let give_up = t + FOLLOW_TIMEOUT;
    while busy(fleet) && t < give_up {
        t += period;
        if !step(fleet, t) {
            return fleet_report(fleet, keys.len());
        }
    }
    let end = t + fleet.app().config().teleop.deadman_timeout + SETTLE;
    while t < end {
        t = (t + period).min(end);
        if !step(fleet, t) {
            break;
        }
    }
    fleet_report(fleet, keys.len())
}

/// Every robot's report as the fleet stands.
pub fn fleet_report(fleet: &Fleet, keys: usize) -> FleetReport {
    FleetReport {
        navdeck: env!("CARGO_PKG_VERSION"),
        keys,
        sim_time: fleet.app().now(),
        selected: fleet.members()[fleet.selected()].name.clone(),
        robots: (fleet.members().iter())
            .map(|m| RobotReport {
                name: m.name.clone(),
                robot_hits: m.app.link().ground_truth().map(|t| t.robot_hits()),
                report: report(&m.app, keys),
            })
            .collect(),
        stop_all_times: fleet.stop_all_times().to_vec(),
        epoch_unix: None,
        wall_time_s: None,
        realtime_factor: None,
        recording: None,
        broken: None,
    }
}
