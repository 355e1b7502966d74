//! `navdeck mission`: the whole mission in the twin on simulated time, or a sweep of seeds.

use super::args::{parse_pose, parse_time_limit};
use super::tour::LocalizeArgs;
use super::world::{ShapeArgs, generate_error};
use anyhow::{Result, bail};
use navdeck::geometry::Pose2;
use navdeck::runners::mission as mission_runner;
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::sim::generate::{self, GenerateOptions};
use navdeck::sim::{CameraFrames, FaultSpec};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub(crate) struct MissionArgs {
    /// The twin's noise seed.
    #[arg(
        long,
        default_value_t = 1,
        value_name = "N",
        allow_negative_numbers = true,
        value_parser = super::args::whole::<u64>
    )]
    seed: u64,
    /// Run every seed of a range, e.g. 1..50, on all cores, and print the summary.
    #[arg(long, value_name = "A..B", conflicts_with = "seed")]
    sweep: Option<String>,
    /// World for the twin: a world file (TOML) or a Nav2 map (YAML + PGM); default: the
    /// built-in arena.
    #[arg(long, value_name = "FILE")]
    world: Option<PathBuf>,
    /// Where the robot starts: X,Y,THETA_DEG (default: the world's start).
    #[arg(long, value_name = "X,Y,THETA_DEG", value_parser = parse_pose, allow_hyphen_values = true)]
    start: Option<Pose2>,
    #[command(flatten)]
    localize: LocalizeArgs,
    /// Each run on a world generated from its seed (as `navdeck world generate`).
    #[arg(long, conflicts_with = "world")]
    generated: bool,
    #[command(flatten)]
    shape: ShapeArgs,
    /// Parameters (TOML), e.g. [mission] target_rule.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Give up after this many simulated seconds.
    #[arg(long, default_value_t = 1200.0, value_name = "S", value_parser = parse_time_limit,
          allow_negative_numbers = true)]
    time_limit: f64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// The twin sees through a rendered camera and the ArUco detector (feature `vision`).
    #[arg(long)]
    sim_camera: bool,
    /// A fault injected into the twin: KIND@START[+DURATION][:PARAM], e.g. camera@60+20,
    /// lidar@100+5, odom@30+5, arm@10, slip@30+10:0.5 (see `navdeck --help`); the same
    /// faults in every run of a sweep, but for a start window A..B (camera@30..180+20),
    /// drawn from each run's seed. May be given again.
    #[arg(long, value_name = "KIND@START[+DURATION][:PARAM]")]
    fault: Vec<FaultSpec>,
    /// Also print every line the mission logged (one run; in the JSON as "log").
    #[arg(long, conflicts_with = "sweep")]
    log: bool,
    /// Save the final planning map as this Nav2 map (FILE.yaml + FILE.pgm), and with
    /// `--estimator slam` the pose graph beside it (FILE.posegraph.json), to continue
    /// mapping on or to localise on with MCL (one run).
    #[arg(long, value_name = "FILE.yaml", conflicts_with = "sweep")]
    save_map: Option<PathBuf>,
    /// N twins in one world explore and deliver together (blocks claimed one robot at a
    /// time, robots giving way to each other).
    #[arg(long, value_name = "N", value_parser = super::args::whole::<usize>)]
    robots: Option<usize>,
}

pub(crate) fn run(args: &MissionArgs) -> Result<ExitCode> {
    if !(args.time_limit.is_finite() && args.time_limit > 0.0) {
        bail!(
            "--time-limit {} must be a positive number of seconds",
            args.time_limit
        );
    }
    if let Some(path) = args
        .save_map
        .as_ref()
        .filter(|p| !navdeck::session::is_nav2_map(p))
    {
        bail!(
            "--save-map {}: a Nav2 map's file name ends in .yaml",
            path.display()
        );
    }
    if let (false, Some(flag)) = (args.generated, args.shape.given()) {
        bail!("{flag} needs --generated");
    }
    let generated = args.generated.then(|| args.shape.options(args.seed));
    let spec = |seed| SessionSpec {
        world: args.world.clone(),
        seed,
        start: args.start,
        config: args.config.clone(),
        keymap: None,
        link: LinkChoice::Sim,
        localize: args.localize.choice(),
    };
    let load = |seed: u64| -> Result<Session> {
        let mut session = match &generated {
            // Seed N: the world generated from N, and the twin's noise seeded with N.
            Some(options) => {
                let options = GenerateOptions {
                    seed,
                    ..options.clone()
                };
                let world = generate::generate(&options).map_err(generate_error)?;
                Session::load_with_world(&spec(seed), world)?
            }
            None => Session::load(&spec(seed))?,
        };
        if args.sim_camera {
            // No camera panel: only what the detector can read is drawn.
            session.use_sim_camera(None, CameraFrames::Readable)?;
        }
        session.inject_faults(&args.fault, seed)?;
        Ok(session)
    };
    if let Some(n) = args.robots.filter(|n| *n > 1) {
        let refused = [
            ("--sim-camera", args.sim_camera),
            ("--fault", !args.fault.is_empty()),
            ("--log", args.log),
            ("--save-map", args.save_map.is_some()),
        ];
        if let Some((option, _)) = refused.iter().find(|(_, on)| *on) {
            bail!("{option} is for one robot: it is not taken with --robots");
        }
        let twins = |seed: u64| -> Result<Vec<(String, Session)>> {
            match &generated {
                Some(options) => {
                    let options = GenerateOptions {
                        seed,
                        ..options.clone()
                    };
                    let world = generate::generate(&options).map_err(generate_error)?;
                    navdeck::session::fleet::twins_in(&spec(seed), world, n)
                }
                None => navdeck::session::fleet::twins(&spec(seed), n),
            }
        };
        return super::mission_fleet::run(
            twins,
            args.seed,
            args.sweep.as_deref(),
            args.time_limit,
            args.json,
        );
    }
    // Load once up front so a bad file is refused before anything runs.
    load(args.seed)?;
    let one = |seed: u64| -> Result<mission_runner::MissionReport> {
        let session = load(seed)?;
        let localizer = session.localizer.clone();
        let (config, link) = session.into_link();
        let started = Instant::now();
        let (mut report, saved) = mission_runner::run_saving(
            &config,
            link,
            localizer.as_ref(),
            seed,
            args.time_limit,
            args.log,
            args.save_map.as_deref(),
        );
        match saved {
            Some(Err(why)) => bail!("map not saved: {why}"),
            // The files written, for a person (the JSON's log holds it with --log).
            Some(Ok(line)) if !args.json => eprintln!("{line}"),
            _ => {}
        }
        let wall = started.elapsed().as_secs_f64();
        report.wall_time_s = Some(wall);
        report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
        Ok(report)
    };
    let Some(range) = &args.sweep else {
        let report = one(args.seed)?;
        if args.json {
            sayln!("{}", serde_json::to_string(&report)?);
        } else {
            say!("{}", mission_runner::human(&report));
        }
        return Ok(if report.success() {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        });
    };
    let seeds = mission_runner::parse_seeds(range).map_err(anyhow::Error::msg)?;
    let reports = super::sweep::on_all_cores(&seeds, one)
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    let summary = mission_runner::summarise(reports);
    if args.json {
        sayln!("{}", serde_json::to_string(&summary)?);
    } else {
        sayln!(
            "{} of {} runs delivered every block ({:.0} %); median {:.1} s simulated; worst seed {} at {:.1} s; {} collisions",
            summary.successes,
            summary.runs,
            summary.success_rate * 100.0,
            summary.median_sim_time,
            summary.worst_seed.map_or("-".into(), |s| s.to_string()),
            summary.worst_sim_time,
            summary.collisions
        );
        if let (Some(rmse), Some(max)) = (summary.position_rmse, summary.position_max_error) {
            sayln!(
                "position error: RMSE mean {:.3} m (worst {:.3}), max mean {:.3} m (worst {:.3})",
                rmse.mean,
                rmse.max,
                max.mean,
                max.max
            );
        }
        if let (Some(recall), Some(precision)) = (summary.wall_recall, summary.wall_precision) {
            sayln!(
                "map vs true walls: walls mapped {:.0} % (least {:.0} %), map on walls {:.0} % (least {:.0} %)",
                recall.mean * 100.0,
                recall.min * 100.0,
                precision.mean * 100.0,
                precision.min * 100.0
            );
        }
        if !summary.failed_seeds.is_empty() {
            sayln!("failed seeds: {:?}", summary.failed_seeds);
            let causes: Vec<String> = (summary.causes.iter())
                .map(|(cause, n)| format!("{cause} {n}"))
                .collect();
            sayln!("causes: {}", causes.join(", "));
        }
    }
    Ok(if summary.successes == summary.runs {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
