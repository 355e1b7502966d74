//! `navdeck lane`: lane mode in the twin on simulated time (seed 000 §2-§3), one run or a
//! sweep over generated tracks and lighting variants.

use anyhow::{Result, bail};
use navdeck::runners::lane::{self as lane_runner, LaneOptions, LaneReport};
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::sim::generate::{self, GenerateOptions, Style};
use navdeck::sim::track::Lighting;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub(crate) struct LaneArgs {
    /// The twin's noise seed (and with --generated the track's).
    #[arg(long, default_value_t = 1, value_name = "N", value_parser = super::args::whole::<u64>)]
    seed: u64,
    /// Run every seed of a range, e.g. 1..50, on all cores, one JSON line each.
    #[arg(long, value_name = "A..B", conflicts_with = "seed")]
    sweep: Option<String>,
    /// A world file with a [track] (default: the built-in maps/track.toml).
    #[arg(long, value_name = "FILE", conflicts_with = "generated")]
    world: Option<PathBuf>,
    /// Each run on a track generated from its seed (as `navdeck world generate --style track`).
    #[arg(long)]
    generated: bool,
    /// Laps to drive.
    #[arg(long, default_value_t = 3.0, value_name = "N", value_parser = parse_laps)]
    laps: f64,
    /// The lighting: bright, normal, dark, shadows or glare, joined by + (dark+glare), or
    /// `all` to run each of the five in turn.
    #[arg(long, default_value = "normal", value_name = "NAME")]
    lighting: String,
    /// Give up after this many simulated seconds.
    #[arg(long, default_value_t = 900.0, value_name = "S", value_parser = super::args::parse_time_limit)]
    time_limit: f64,
    /// Parameters (TOML), e.g. [lane.drive] max_speed.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Print one JSON object per run.
    #[arg(long)]
    json: bool,
    /// Instead of driving: score the light and barrier detection on N frames per
    /// lighting level (bright, normal, dark; with --lighting all also shadows and glare)
    /// against the twin's truth, over the built-in track and generated tracks 1..10 (or
    /// --sweep's), and time the pipeline per frame (feature `vision`).
    #[arg(long, value_name = "N", value_parser = super::args::whole::<u32>)]
    detection: Option<u32>,
}

fn parse_laps(s: &str) -> Result<f64, String> {
    super::args::bounded(s, 0.01, 1000.0, "laps")
}

pub(crate) fn run(args: &LaneArgs) -> Result<ExitCode> {
    if let Some(frames) = args.detection {
        return detection(args, frames);
    }
    let lightings: Vec<Lighting> = if args.lighting == "all" {
        (Lighting::VARIANTS.iter())
            .map(|v| Lighting::parse(v).expect("the variants parse"))
            .collect()
    } else {
        vec![Lighting::parse(&args.lighting).map_err(|e| anyhow::anyhow!("--lighting: {e}"))?]
    };
    let spec = |seed| SessionSpec {
        world: args.world.clone(),
        seed,
        start: None,
        config: args.config.clone(),
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    };
    let one = |seed: u64, lighting: Lighting| -> Result<LaneReport> {
        let mut session = if args.generated {
            let options = GenerateOptions {
                seed,
                style: Style::Track,
                ..GenerateOptions::default()
            };
            let world = generate::generate(&options).map_err(super::world::generate_error)?;
            Session::load_with_world(&spec(seed), world)?
        } else if args.world.is_none() {
            Session::load_with_world(&spec(seed), navdeck::sim::World::default_track())?
        } else {
            Session::load(&spec(seed))?
        };
        let stopwatch: std::sync::Arc<dyn navdeck::clock::Clock> =
            std::sync::Arc::new(navdeck::tui::events::WallClock::start());
        session.use_lane_camera(lighting, seed, Some(stopwatch))?;
        let (config, link) = session.into_link();
        let options = LaneOptions {
            seed,
            laps: args.laps,
            time_limit: args.time_limit,
            lighting: lighting.name(),
        };
        let started = Instant::now();
        // On one of rayon's threads, the renderer's and the pipeline's parallel passes
        // share the frame with the other thread directly rather than each waking the pool.
        let mut report = rayon::scope(|_| lane_runner::run(&config, link, &options))
            .map_err(anyhow::Error::msg)?;
        let wall = started.elapsed().as_secs_f64();
        report.wall_time_s = Some(wall);
        report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
        Ok(report)
    };
    let seeds = match &args.sweep {
        Some(range) => navdeck::runners::mission::parse_seeds(range).map_err(anyhow::Error::msg)?,
        None => vec![args.seed],
    };
    // A bad file or world is refused before anything runs.
    if args.world.is_some() {
        Session::load(&spec(seeds[0]))?;
    }
    let runs: Vec<(u64, Lighting)> = (seeds.iter())
        .flat_map(|&s| lightings.iter().map(move |&l| (s, l)))
        .collect();
    let reports = (super::sweep::on_all_cores(&runs, |(seed, lighting)| one(seed, lighting))
        .into_iter())
    .collect::<Result<Vec<_>>>()?;
    for report in &reports {
        if args.json {
            sayln!("{}", serde_json::to_string(report)?);
        } else {
            say!("{}", lane_runner::human(report));
        }
    }
    let failed = reports.iter().any(|r| {
        !r.completed || r.collisions > 0 || r.figures.red_lights_run > 0 || r.barrier_hits > 0
    });
    if reports.is_empty() {
        bail!("no runs");
    }
    Ok(if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// `--detection N`: detection scored against the truth, and the pipeline timed.
fn detection(args: &LaneArgs, frames: u32) -> Result<ExitCode> {
    #[cfg(feature = "vision")]
    {
        let config = match &args.config {
            Some(path) => navdeck::config::Config::load(path)?,
            None => navdeck::config::Config::default(),
        };
        let seeds = match &args.sweep {
            Some(range) => {
                navdeck::runners::mission::parse_seeds(range).map_err(anyhow::Error::msg)?
            }
            None => (1..=10).collect(),
        };
        let mut worlds = vec![navdeck::sim::World::default_track()];
        for seed in seeds {
            let options = GenerateOptions {
                seed,
                style: Style::Track,
                ..GenerateOptions::default()
            };
            worlds.push(generate::generate(&options).map_err(super::world::generate_error)?);
        }
        let names: &[&str] = if args.lighting == "all" {
            &Lighting::VARIANTS
        } else {
            &["bright", "normal", "dark"]
        };
        let lightings: Vec<Lighting> = (names.iter())
            .map(|n| Lighting::parse(n).expect("the variants parse"))
            .collect();
        let lane = &config.lane;
        let report = navdeck::runners::lane_detect::run(
            &worlds,
            &lane.camera,
            &lane.vision,
            &lightings,
            frames,
            args.seed,
        )
        .map_err(anyhow::Error::msg)?;
        sayln!("{}", serde_json::to_string(&report)?);
        Ok(ExitCode::SUCCESS)
    }
    #[cfg(not(feature = "vision"))]
    {
        let _ = (args, frames);
        bail!(
            "navdeck lane --detection needs navdeck built with the `vision` feature (cargo build --release --features vision)"
        )
    }
}
