//! `navdeck mission`: the whole exploration-and-delivery mission on simulated time, once
//! or over many seeds, reported for people or as JSON.

use super::slam_figures::{EstimatorFigures, SweepEstimatorFigures};
use crate::config::Config;
use crate::data::Level;
use crate::link::RobotLink;
use crate::link::runtime::{Runtime, Stepped};
use crate::pilot::mode::Mode;
use crate::pilot::{Intent, LogLine, Pilot};
use crate::runners::score::TruthScore;
use serde::Serialize;
use std::path::Path;

/// A delivered block lies within this of its gate's centre in the twin, metres: the
/// region the mission's drop places are laid out in (mission/drop_places.rs).
use crate::mission::drop_places::AT_GATE;

/// One block's story.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BlockTimes {
    pub markers: [u32; 2],
    pub found: f64,
    pub picked: Option<f64>,
    pub delivered: Option<f64>,
}

/// The outcome of one mission.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MissionReport {
    pub world: String,
    pub seed: u64,
    /// Blocks the mission delivered, blocks the twin has at their gates, blocks in the world.
    pub delivered: usize,
    pub true_delivered: Option<usize>,
    pub total: usize,
    /// "delivered all", "finished" (exploration complete with blocks left), "time limit" or
    /// "handed to manual".
    pub outcome: String,
    /// Why a run that did not deliver everything ended: "time limit", "ended with blocks
    /// left", or the mission's reason for handing over ("unreachable target", "lost",
    /// "pickup failed", "delivery failed", "blocks left without a gate"); with a collision
    /// on the way, "collision". None for a success.
    pub cause: Option<String>,
    pub sim_time: f64,
    pub collisions: Option<u32>,
    pub replans: usize,
    pub recoveries: usize,
    /// The estimate's and the map's agreement with the twin's truth.
    #[serde(flatten)]
    pub score: TruthScore,
    pub timeline: Vec<BlockTimes>,
    /// Warnings and errors the session logged, with their session times.
    pub warnings: Vec<String>,
    /// Filled in by the caller, which owns the clock.
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
    /// Every line the session logged, "time level text" (`navdeck mission --log`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub log: Vec<String>,
    /// The estimator and, with lidar SLAM, its pose graph's figures.
    #[serde(flatten)]
    pub estimator: EstimatorFigures,
    /// The faults injected into the twin (`--fault`) and when each was in force; the
    /// sensors the pilot lost, and when each came back.
    #[serde(flatten)]
    pub faults: super::faults::FaultFigures,
}

impl MissionReport {
    pub fn success(&self) -> bool {
        self.outcome == "delivered all"
    }
}

/// Runs the mission on `link` with a pilot of `config`'s settings, from session time 0
/// until it ends or `time_limit` simulated seconds pass. No console: the pilot is driven
/// directly, a control step every period. With `keep_log`, the report carries every line
/// the session logged. With a `localizer`, MCL places the robot.
pub fn run(
    config: &Config,
    link: Box<dyn RobotLink>,
    localizer: Option<&crate::pilot::localize::Localizer>,
    seed: u64,
    time_limit: f64,
    keep_log: bool,
) -> MissionReport {
    run_saving(config, link, localizer, seed, time_limit, keep_log, None).0
}

/// `run`, then with `save_map` the final planning map saved there as a Nav2 map (and,
/// when lidar SLAM ran, its pose graph beside it): the log line naming the files, or why
/// nothing was written.
pub fn run_saving(
    config: &Config,
    link: Box<dyn RobotLink>,
    localizer: Option<&crate::pilot::localize::Localizer>,
    seed: u64,
    time_limit: f64,
    keep_log: bool,
    save_map: Option<&Path>,
) -> (MissionReport, Option<Result<String, String>>) {
    let mut robot = Runtime::new(link, config.pilot_settings(), 0.0);
    let mut log = Vec::new();
    if let Some((Err(why), l)) = localizer.map(|l| (l.apply(robot.pilot_mut()), l)) {
        let text = format!("{} not started: {why}", l.label());
        let (time, level) = (0.0, Level::Error);
        log.push(LogLine { time, level, text });
    }
    take_log(&mut log, robot.intend(Intent::Mode(Mode::Exploration)));
    // The first control period starts at once, as the console's does.
    take_log(&mut log, robot.tick(0.0, Vec::new()));
    let period = config.robot.control_period;
    let mut t = 0.0;
    while t < time_limit && robot.pilot().mode() == Mode::Exploration && robot.pilot().is_busy() {
        t += period;
        take_log(&mut log, robot.tick(t, Vec::new()));
    }
    let saved = save_map.map(|path| {
        let created = format!("navdeck mission seed {seed}, session time {t:.1} s");
        let block_size = config.mission.block_size;
        let saved = crate::app::save_map_files(path, robot.pilot(), block_size, created);
        let (level, text) = match &saved {
            Ok(line) => (Level::Success, line.clone()),
            Err(why) => (Level::Error, format!("map not saved: {why}")),
        };
        log.push(LogLine {
            time: t,
            level,
            text,
        });
        saved
    });
    let mut report = report(robot.pilot(), robot.link(), &log, config, seed, t);
    if keep_log {
        report.log = (log.iter())
            .map(|e| format!("{:7.1} s {} {}", e.time, e.level.tag(), e.text))
            .collect();
    }
    (report, saved)
}

/// The log lines of what a runner's step brought.
pub fn take_log(log: &mut Vec<LogLine>, stepped: Stepped) {
    let lines = stepped.log_lines();
    log.extend(lines.map(|(time, level, text)| LogLine {
        time,
        level,
        text: text.to_string(),
    }));
}

fn report(
    pilot: &Pilot,
    link: &dyn RobotLink,
    log: &[LogLine],
    config: &Config,
    seed: u64,
    sim_time: f64,
) -> MissionReport {
    let twin = link.ground_truth();
    let total = twin.map_or(config.mission.total_blocks as usize, |t| t.blocks().len());
    let mission = pilot.mission();
    let delivered = mission.map_or(0, |m| m.delivered());
    let finished = mission.is_some_and(|m| m.is_done());
    let outcome = if finished && delivered >= total {
        "delivered all"
    } else if finished {
        "finished"
    } else if pilot.mode() != Mode::Exploration {
        "handed to manual"
    } else {
        "time limit"
    };
    let true_delivered = twin.map(|twin| {
        let world = twin.world();
        twin.blocks()
            .iter()
            .filter(|b| !b.held)
            .filter(|b| {
                world.gates.iter().filter(|g| g.color == b.color).any(|g| {
                    world
                        .gate_pose(g)
                        .is_some_and(|p| p.position().distance(b.pose.position()) < AT_GATE)
                })
            })
            .count()
    });
    let collided = twin.is_some_and(|t| t.collisions() > 0);
    let cause = match outcome {
        "delivered all" => None,
        _ if collided => Some("collision".to_string()),
        "finished" => Some("ended with blocks left".to_string()),
        "time limit" => Some("time limit".to_string()),
        _ => Some(
            mission
                .and_then(|m| m.handover_cause())
                .unwrap_or("handed to manual")
                .to_string(),
        ),
    };
    MissionReport {
        world: twin.map_or("none".into(), |t| t.world().name.clone()),
        seed,
        delivered,
        true_delivered,
        total,
        outcome: outcome.into(),
        cause,
        sim_time,
        collisions: twin.map(|t| t.collisions()),
        replans: mission.map_or(0, |m| m.replans()) + pilot.replans(),
        recoveries: mission.map_or(0, |m| m.recoveries()),
        score: TruthScore::of(pilot, twin),
        timeline: mission.map_or(Vec::new(), |m| {
            m.timeline()
                .iter()
                .map(|&(odd, found, picked, delivered)| {
                    // The mission's clock stands while it is held: back to session time.
                    let session = |m: Option<f64>| m.map(|m| pilot.session_time_of(m));
                    BlockTimes {
                        markers: [odd, odd + 1],
                        found: pilot.session_time_of(found),
                        picked: session(picked),
                        delivered: session(delivered),
                    }
                })
                .collect()
        }),
        warnings: (log.iter())
            .filter(|e| e.level >= Level::Warn)
            .map(|e| format!("{:.1} s: {}", e.time, e.text))
            .collect(),
        wall_time_s: None,
        realtime_factor: None,
        log: Vec::new(),
        estimator: EstimatorFigures::of(pilot),
        faults: super::faults::FaultFigures::of(link, pilot),
    }
}

/// Many missions summed up.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepSummary {
    pub runs: usize,
    pub successes: usize,
    pub success_rate: f64,
    pub median_sim_time: f64,
    pub worst_seed: Option<u64>,
    pub worst_sim_time: f64,
    pub collisions: u32,
    pub failed_seeds: Vec<u64>,
    /// Runs that did not deliver everything, by cause.
    pub causes: std::collections::BTreeMap<String, usize>,
    /// Over the runs with a twin: the absolute trajectory error's RMSE and largest error,
    /// metres, and the map's agreement with the true walls (shares, 0-1).
    pub position_rmse: Option<Spread>,
    pub position_max_error: Option<Spread>,
    pub wall_recall: Option<Spread>,
    pub wall_precision: Option<Spread>,
    pub runs_detail: Vec<MissionReport>,
    /// The runs' estimator and their loop closures added up.
    #[serde(flatten)]
    pub estimator: SweepEstimatorFigures,
}

/// The mean, least and greatest of one figure over a sweep's runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spread {
    pub mean: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// `None` when there are no values.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Spread> {
        let values: Vec<f64> = values.into_iter().collect();
        let first = *values.first()?;
        let (min, max) =
            (values.iter()).fold((first, first), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        Some(Spread { mean, min, max })
    }
}

/// Sums up `reports` (one per seed).
pub fn summarise(mut reports: Vec<MissionReport>) -> SweepSummary {
    reports.sort_by_key(|r| r.seed);
    let successes = reports.iter().filter(|r| r.success()).count();
    let mut times: Vec<f64> = reports.iter().map(|r| r.sim_time).collect();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    // The worst run: a failure if any (the longest of them), else the slowest.
    let worst = reports.iter().max_by(|a, b| {
        (!a.success(), a.sim_time)
            .partial_cmp(&(!b.success(), b.sim_time))
            .unwrap()
    });
    let maps = || reports.iter().filter_map(|r| r.score.map_vs_walls);
    SweepSummary {
        runs: reports.len(),
        successes,
        success_rate: successes as f64 / reports.len().max(1) as f64,
        median_sim_time: median,
        worst_seed: worst.map(|r| r.seed),
        worst_sim_time: worst.map_or(0.0, |r| r.sim_time),
        collisions: reports.iter().filter_map(|r| r.collisions).sum(),
        failed_seeds: reports
            .iter()
            .filter(|r| !r.success())
            .map(|r| r.seed)
            .collect(),
        causes: reports.iter().filter_map(|r| r.cause.clone()).fold(
            Default::default(),
            |mut counts, cause| {
                *counts.entry(cause).or_default() += 1;
                counts
            },
        ),
        position_rmse: Spread::of(reports.iter().filter_map(|r| r.score.position_rmse)),
        position_max_error: Spread::of(reports.iter().filter_map(|r| r.score.position_max_error)),
        wall_recall: Spread::of(maps().map(|m| m.wall_recall)),
        wall_precision: Spread::of(maps().map(|m| m.wall_precision)),
        estimator: SweepEstimatorFigures::of(reports.iter().map(|r| &r.estimator)),
        runs_detail: reports,
    }
}

/// A report as a person reads it.
pub fn human(r: &MissionReport) -> String {
    let cause = r.cause.as_ref().map_or(String::new(), |c| format!(", {c}"));
    let mut out: String = r.log.iter().map(|line| format!("{line}\n")).collect();
    out += &format!(
        "mission on {} seed {}: {}{cause} ({} of {} blocks delivered) in {:.1} s simulated\n",
        r.world, r.seed, r.outcome, r.delivered, r.total, r.sim_time
    );
    out += &format!(
        "collisions {}, replans {}, recoveries {}\n",
        r.collisions.map_or("-".into(), |c| c.to_string()),
        r.replans,
        r.recoveries
    );
    if let Some(line) = r.score.line() {
        out += &format!("error vs truth {line}\n");
    }
    out += &r.faults.human();
    for b in &r.timeline {
        let at = |t: Option<f64>| t.map_or("-".to_string(), |t| format!("{t:.1} s"));
        out += &format!(
            "  block {}/{}: found {:.1} s, picked {}, delivered {}\n",
            b.markers[0],
            b.markers[1],
            b.found,
            at(b.picked),
            at(b.delivered)
        );
    }
    if let (Some(w), Some(f)) = (r.wall_time_s, r.realtime_factor) {
        out += &format!("wall time {w:.2} s ({f:.0}x real time)\n");
    }
    out
}

/// Most runs one sweep makes.
pub const MAX_SWEEP: u64 = 1000;

/// Reads a seed range `A..B` (inclusive) of at most `MAX_SWEEP` seeds, or a single seed.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, String> {
    let bad = || format!("`{text}` is not a seed range like 1..50");
    match text.split_once("..") {
        Some((a, b)) => {
            let a: u64 = a.trim().parse().map_err(|_| bad())?;
            let b: u64 = b
                .trim()
                .trim_start_matches('=')
                .parse()
                .map_err(|_| bad())?;
            if a > b {
                return Err(format!(
                    "`{text}` runs backwards: the first seed must not be above the last ({b}..{a}?)"
                ));
            }
            if b - a >= MAX_SWEEP {
                return Err(format!(
                    "`{text}` is {} runs: a sweep runs at most {MAX_SWEEP}",
                    u128::from(b - a) + 1
                ));
            }
            Ok((a..=b).collect())
        }
        None => text.trim().parse().map(|s| vec![s]).map_err(|_| bad()),
    }
}
