//! `navdeck mission --robots N`: one fleet mission, or a sweep of seeds on all cores.

use anyhow::Result;
use navdeck::runners::fleet_mission::{self, FleetMissionReport};
use navdeck::runners::mission::parse_seeds;
use navdeck::session::Session;
use serde::Serialize;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

/// A sweep's figures.
#[derive(Serialize)]
struct Summary {
    runs: usize,
    robots: usize,
    /// Runs with every block delivered and no contact.
    successes: usize,
    all_delivered: usize,
    collisions: u32,
    robot_hits: u32,
    median_sim_time: f64,
    worst_sim_time: f64,
    failed_seeds: Vec<u64>,
    runs_detail: Vec<FleetMissionReport>,
}

/// Runs the fleet mission of `twins(seed)` for `seed`, or for every seed of `sweep`.
pub(crate) fn run(
    twins: impl Fn(u64) -> Result<Vec<(String, Session)>> + Sync,
    seed: u64,
    sweep: Option<&str>,
    time_limit: f64,
    json: bool,
) -> Result<ExitCode> {
    let one = |seed: u64| -> Result<FleetMissionReport> {
        let members = twins(seed)?;
        let started = Instant::now();
        let mut report = fleet_mission::run(members, seed, time_limit);
        report.wall_time_s = Some(started.elapsed().as_secs_f64());
        Ok(report)
    };
    let Some(range) = sweep else {
        let report = one(seed)?;
        match json {
            true => sayln!("{}", serde_json::to_string(&report)?),
            false => sayln!("{}", line(&report)),
        }
        return Ok(ExitCode::from(u8::from(!report.success())));
    };
    let seeds = parse_seeds(range).map_err(anyhow::Error::msg)?;
    twins(seeds[0])?;
    let mut reports =
        (super::sweep::on_all_cores(&seeds, one).into_iter()).collect::<Result<Vec<_>>>()?;
    reports.sort_by_key(|r| r.seed);
    let summary = summarise(reports);
    if json {
        sayln!("{}", serde_json::to_string(&summary)?);
    } else {
        for r in &summary.runs_detail {
            sayln!("{}", line(r));
        }
        sayln!(
            "{} of {} runs delivered every block without a contact; {} delivered all; {} collisions ({} between robots); median {:.1} s simulated, worst {:.1} s",
            summary.successes,
            summary.runs,
            summary.all_delivered,
            summary.collisions,
            summary.robot_hits,
            summary.median_sim_time,
            summary.worst_sim_time
        );
    }
    Ok(ExitCode::from(u8::from(summary.successes < summary.runs)))
}

fn line(r: &FleetMissionReport) -> String {
    format!(
        "seed {}: {} robots, {}/{} delivered ({}), {:.1} s simulated, {} collisions ({} between robots), by robot {:?}",
        r.seed,
        r.robots,
        r.true_delivered,
        r.total,
        r.outcome,
        r.sim_time,
        r.collisions,
        r.robot_hits,
        r.delivered_by
    )
}

fn summarise(reports: Vec<FleetMissionReport>) -> Summary {
    let mut times: Vec<f64> = reports.iter().map(|r| r.sim_time).collect();
    times.sort_by(f64::total_cmp);
    Summary {
        runs: reports.len(),
        robots: reports.first().map_or(0, |r| r.robots),
        successes: reports.iter().filter(|r| r.success()).count(),
        all_delivered: (reports.iter())
            .filter(|r| r.true_delivered == r.total)
            .count(),
        collisions: reports.iter().map(|r| r.collisions).sum(),
        robot_hits: reports.iter().map(|r| r.robot_hits).sum(),
        median_sim_time: times.get(times.len() / 2).copied().unwrap_or(0.0),
        worst_sim_time: times.last().copied().unwrap_or(0.0),
        failed_seeds: (reports.iter())
            .filter(|r| !r.success())
            .map(|r| r.seed)
            .collect(),
        runs_detail: reports,
    }
}
