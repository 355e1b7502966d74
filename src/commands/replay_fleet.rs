//! `navdeck replay FILE.mcap` on a fleet's recording: the fleet's console on it, or
//! (`--headless`) a re-run of every robot to the end with a report per robot.

use super::replay::ReplayArgs;
use anyhow::Result;
use navdeck::msgs::record::INPUT_KEY;
use navdeck::replay::ReplayOptions;
use navdeck::replay::fleet::{FleetRecorded, FleetReplay};
use std::io::Write;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

pub fn run(
    args: &ReplayArgs,
    recorded: Arc<FleetRecorded>,
    options: ReplayOptions,
) -> Result<ExitCode> {
    let broken = recorded.broken();
    let mut replay = FleetReplay::new(recorded, options)?;
    if !args.headless {
        let code = navdeck::console::run_replay_console(replay, args.speed, !args.rerun)?;
        return Ok(ExitCode::from(code));
    }
    let started = Instant::now();
    let (_, end) = replay.span();
    replay.run_to(end);
    let keys = (replay.recorded().fleet.inputs.iter())
        .filter(|i| i.kind == INPUT_KEY)
        .count();
    let mut report = navdeck::runners::fleet::fleet_report(replay.fleet(), keys);
    for (robot, comparison) in report.robots.iter_mut().zip(replay.comparisons()) {
        robot.report.replay = Some(comparison);
    }
    let wall = started.elapsed().as_secs_f64();
    report.wall_time_s = Some(wall);
    report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
    for why in &broken {
        say_err!("navdeck: {why}");
    }
    report.broken = Some(broken);
    super::fleet::print_report(&report, args.json)?;
    Ok(ExitCode::SUCCESS)
}
