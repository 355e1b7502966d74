//! `navdeck tour` and the localisation options the console and the runners share (part
//! of the binary, beside main.rs): the command line's side of `navdeck::runners::tour`.

use anyhow::{Result, bail};
use navdeck::geometry::{Point2, Pose2};
use navdeck::pilot::localize::InitialPose;
use navdeck::runners::tour::{self, TourOptions, TourReport};
use navdeck::session::{LinkChoice, LocalizeChoice, Session, SessionSpec};
use navdeck::slam::mcl::config::Estimator;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// How the robot is localised.
#[derive(Debug, Default, clap::Args)]
pub struct LocalizeArgs {
    /// Estimator: `ekf` (EKF-SLAM on markers), `mcl` (Monte-Carlo localisation with the
    /// lidar on a known map) or `slam` (lidar SLAM: maps as it goes, no markers needed);
    /// over [localization] estimator.
    #[arg(long, value_name = "ekf|mcl|slam")]
    estimator: Option<Estimator>,
    /// The map MCL localises on (a Nav2 map_server YAML + PGM; default: the twin's
    /// world when it is a Nav2 map), or with `slam` the saved map to continue mapping on
    /// (its pose graph FILE.posegraph.json beside it).
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// Where MCL (or continued lidar SLAM) starts, metres and degrees in the map frame,
    /// or `unknown` for MCL's global localisation; default: the twin's start, else
    /// unknown (lidar SLAM: the origin).
    #[arg(long, value_name = "X,Y,THETA_DEG|unknown", allow_hyphen_values = true)]
    initial_pose: Option<InitialPose>,
}

impl LocalizeArgs {
    pub fn choice(&self) -> LocalizeChoice {
        LocalizeChoice {
            estimator: self.estimator,
            map: self.map.clone(),
            initial_pose: self.initial_pose,
        }
    }

    /// `--estimator` as typed, for a recording's metadata.
    pub fn estimator_name(&self) -> Option<String> {
        self.estimator.map(|e| match e {
            Estimator::Ekf => "ekf".to_string(),
            Estimator::Mcl => "mcl".to_string(),
            Estimator::Slam => "slam".to_string(),
        })
    }

    pub fn map_name(&self) -> Option<String> {
        self.map.as_ref().map(|p| p.display().to_string())
    }

    /// `--initial-pose` as it would be typed.
    pub fn initial_pose_text(&self) -> Option<String> {
        self.initial_pose.map(|i| match i {
            InitialPose::Unknown => "unknown".to_string(),
            InitialPose::At(p) => format!("{},{},{}", p.x, p.y, p.theta.to_degrees()),
        })
    }

    /// The first option given, for refusing them where they do nothing.
    pub fn given(&self) -> Option<&'static str> {
        [
            ("--estimator", self.estimator.is_some()),
            ("--map", self.map.is_some()),
            ("--initial-pose", self.initial_pose.is_some()),
        ]
        .into_iter()
        .find_map(|(name, on)| on.then_some(name))
    }
}

/// `navdeck tour`.
#[derive(Debug, clap::Args)]
pub struct TourArgs {
    /// The twin's noise seed, and the seed of the goals and the filter.
    #[arg(long, default_value_t = 1, value_name = "N", value_parser = super::args::whole::<u64>)]
    seed: u64,
    /// Run every seed of a range, e.g. 1..10, on all cores, one JSON line each.
    #[arg(long, value_name = "A..B", conflicts_with = "seed")]
    sweep: Option<String>,
    /// World for the twin: a world file (TOML) or a Nav2 map (YAML + PGM).
    #[arg(long, value_name = "FILE")]
    world: Option<PathBuf>,
    /// Where the robot truly starts: X,Y,THETA_DEG (default: the world's start).
    #[arg(long, value_name = "X,Y,THETA_DEG", value_parser = navdeck::geometry::parse_pose_degrees, allow_hyphen_values = true)]
    start: Option<Pose2>,
    #[command(flatten)]
    localize: LocalizeArgs,
    /// Parameters (TOML).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Simulated seconds to drive: 0.1 (one control period of the default robot) to 7200.
    #[arg(long, default_value_t = 300.0, value_name = "S", value_parser = parse_duration)]
    duration: f64,
    /// Goals to visit in turn, X,Y;X,Y;... (default: random reachable ones).
    #[arg(long, value_name = "X,Y;...", allow_hyphen_values = true)]
    goals: Option<String>,
    /// Kidnap the robot: at T seconds carry it to X,Y,THETA_DEG unknown to its odometry.
    #[arg(long, value_name = "T@X,Y,THETA_DEG", allow_hyphen_values = true)]
    kidnap: Option<String>,
    /// Start each run at a random reachable pose drawn from its seed.
    #[arg(long, conflicts_with = "start")]
    random_start: bool,
    /// Print one JSON object per run.
    #[arg(long)]
    json: bool,
    /// A fault injected into the twin: KIND@START[+DURATION][:PARAM], e.g. lidar@60+20
    /// (see `navdeck --help`); the same faults in every run of a sweep. May be given again.
    #[arg(long, value_name = "KIND@START[+DURATION][:PARAM]")]
    fault: Vec<navdeck::sim::FaultSpec>,
}

/// A tour's length: at least one control period of the default robot (0.1 s; a shorter
/// tour takes no step) and at most two simulated hours, as a mission's time limit.
fn parse_duration(s: &str) -> Result<f64, String> {
    super::args::bounded(s, 0.1, 7200.0, "s")
}

fn parse_goals(text: &str) -> Result<Vec<Point2>> {
    text.split(';')
        .map(|g| {
            let parts: Vec<f64> = g
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| anyhow::anyhow!("--goals: `{g}` is not X,Y"))?;
            match parts.as_slice() {
                [x, y] if x.is_finite() && y.is_finite() => Ok(Point2::new(*x, *y)),
                _ => bail!("--goals: `{g}` is not X,Y"),
            }
        })
        .collect()
}

fn parse_kidnap(text: &str) -> Result<(f64, Pose2)> {
    let Some((t, pose)) = text.split_once('@') else {
        bail!("--kidnap: `{text}` is not T@X,Y,THETA_DEG");
    };
    let t: f64 = t
        .trim()
        .parse()
        .ok()
        .filter(|t: &f64| t.is_finite() && *t >= 0.0)
        .ok_or_else(|| anyhow::anyhow!("--kidnap: `{t}` is not a time in seconds"))?;
    let pose = navdeck::geometry::parse_pose_degrees(pose)
        .map_err(|e| anyhow::anyhow!("--kidnap: {e}"))?;
    Ok((t, pose))
}

pub fn run(args: &TourArgs) -> Result<ExitCode> {
    let goals = match &args.goals {
        Some(text) => parse_goals(text)?,
        None => Vec::new(),
    };
    let kidnap = args.kidnap.as_deref().map(parse_kidnap).transpose()?;
    let spec = |seed| SessionSpec {
        world: args.world.clone(),
        seed,
        start: args.start,
        config: args.config.clone(),
        keymap: None,
        link: LinkChoice::Sim,
        localize: args.localize.choice(),
    };
    // Load once up front so a bad file is refused before anything runs.
    Session::load(&spec(args.seed))?;
    let one = |seed: u64| -> Result<TourReport> {
        let mut session = Session::load(&spec(seed))?;
        session.inject_faults(&args.fault, seed)?;
        let localizer = session.localizer.clone();
        let (config, link) = session.into_link();
        let options = TourOptions {
            seed,
            duration: args.duration,
            kidnap,
            goals: goals.clone(),
            random_start: args.random_start,
        };
        let started = Instant::now();
        let mut report =
            tour::run(&config, link, localizer.as_ref(), &options).map_err(anyhow::Error::msg)?;
        let wall = started.elapsed().as_secs_f64();
        report.wall_time_s = Some(wall);
        report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
        Ok(report)
    };
    let seeds = match &args.sweep {
        Some(range) => navdeck::runners::mission::parse_seeds(range).map_err(anyhow::Error::msg)?,
        None => vec![args.seed],
    };
    let mut reports = super::sweep::on_all_cores(&seeds, one)
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    reports.sort_by_key(|r| r.seed);
    for report in &reports {
        if args.json {
            sayln!("{}", serde_json::to_string(report)?);
        } else {
            say!("{}", tour::human(report));
        }
    }
    let collided = reports.iter().any(|r| r.collisions.unwrap_or(0) > 0);
    Ok(if collided {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
