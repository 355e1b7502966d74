//! `navdeck replay FILE.mcap`: the console on a recording, or (`--headless`) a re-run
//! of it to the end with the same report as a headless run.

use super::tour::LocalizeArgs;
use anyhow::Result;
use navdeck::replay::fleet::Opened;
use navdeck::replay::{Replay, ReplayOptions};
use navdeck::runners::headless;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub struct ReplayArgs {
    /// The recording (an MCAP file written with --record).
    pub file: PathBuf,
    /// Re-run to the end without a terminal and print the report of a headless run,
    /// with how the re-run's estimate compares with the recorded one.
    #[arg(long)]
    pub headless: bool,
    /// Headless: print the report as one JSON object.
    #[arg(long, requires = "headless")]
    pub json: bool,
    /// Re-run with this config instead of the recorded one.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    #[command(flatten)]
    pub localize: LocalizeArgs,
    /// Start playing at this speed (0.1 to 50 times real time).
    #[arg(long, default_value_t = 1.0, value_name = "X", value_parser = parse_speed)]
    pub speed: f64,
    /// Open on the re-run instead of the view as recorded.
    #[arg(long)]
    pub rerun: bool,
}

fn parse_speed(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    if !(0.1..=50.0).contains(&v) {
        return Err(format!("{v} is outside 0.1..=50"));
    }
    Ok(v)
}

pub fn run(args: &ReplayArgs) -> Result<ExitCode> {
    let choice = args.localize.choice();
    let options = ReplayOptions {
        config: args.config.clone(),
        estimator: choice.estimator,
        map: choice.map,
        initial_pose: choice.initial_pose,
    };
    let recorded = match navdeck::replay::fleet::open(&args.file)? {
        Opened::One(recorded) => Arc::new(recorded),
        Opened::Fleet(fleet) => return super::replay_fleet::run(args, Arc::new(fleet), options),
    };
    let mut replay = Replay::new(recorded, options)?;
    if !args.headless {
        let code = navdeck::console::run_replay_console(replay, args.speed, !args.rerun)?;
        return Ok(ExitCode::from(code));
    }
    let started = Instant::now();
    let (_, end) = replay.span();
    replay.run_to(end);
    let keys = replay
        .recorded()
        .inputs
        .iter()
        .filter(|i| i.kind == navdeck::msgs::record::INPUT_KEY)
        .count();
    let mut report = headless::report(replay.app(), keys);
    let wall = started.elapsed().as_secs_f64();
    report.wall_time_s = Some(wall);
    report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
    report.replay = Some(replay.comparison());
    let text = if args.json {
        serde_json::to_string(&report)? + "\n"
    } else {
        headless::human(&report)
    };
    let _ =
        std::io::stdout().write_all(navdeck::data::printable::printable(&text, None).as_bytes());
    Ok(ExitCode::SUCCESS)
}
