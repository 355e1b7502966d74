//! navdeck's command line: the console by default, or a headless run.

use anyhow::{Context, Result, bail};
use clap::Parser;
use navdeck::clock::Clock;
use navdeck::config::Config;
use navdeck::console::{ConsoleOptions, run_console};
use navdeck::geometry::{Point2, Pose2};
use navdeck::headless;
use navdeck::keymap::parse_key_sequence;
use navdeck::map::io as map_io;
use navdeck::map_report;
use navdeck::mission_runner;
use navdeck::plan_report::{self, Terrain};
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::sim::generate::{self, GenerateOptions};
use navdeck::sim::{CameraFrames, World};
use navdeck::tui::events::WallClock;
use navdeck::tui::signals::Signals;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use world_command::{ShapeArgs, WorldCommand, generate_error};

mod world_command;

/// Writes to standard output. A reader that has gone (`navdeck map show ... | head`, a
/// dropped SSH session) is no reason to panic: what it no longer reads is lost, nothing
/// else. Control characters (from a world's name, say) reach the terminal escaped.
macro_rules! say {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), None);
        let _ = write!(std::io::stdout(), "{text}");
    }};
}

/// `say!` with a newline.
macro_rules! sayln {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), None);
        let _ = writeln!(std::io::stdout(), "{text}");
    }};
}

/// A line on standard error, which may have gone with the terminal: escaped as `say!`
/// is, and each line cut to `ERROR_LINE` characters (an error may quote a whole input).
macro_rules! say_err {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), Some(ERROR_LINE));
        let _ = writeln!(std::io::stderr(), "{text}");
    }};
}

/// Characters of an error line shown.
const ERROR_LINE: usize = 400;

mod tour_command;
use tour_command::{LocalizeArgs, TourArgs};
mod arm_command;
use arm_command::ArmCommand;
mod replay_command;
use replay_command::ReplayArgs;
mod ros2_command;
use ros2_command::Ros2Command;

/// A terminal teleop-and-autonomy console for small differential-drive robots.
///
/// With no options it opens the console on the built-in digital twin in seed 001's
/// 4 m x 4 m arena. Drive with w a s d (held keys drive; the robot stops 0.5 s after
/// the last key), space is an emergency stop, ? lists every key, q quits.
#[derive(Debug, Parser)]
#[command(name = "navdeck", version, about, long_about)]
struct Cli {
    /// Robot to drive: `sim` (the built-in digital twin), `ros2`, or `serial:PATH[@BAUD]`.
    #[arg(long, default_value = "sim", value_name = "LINK")]
    link: LinkChoice,

    /// ROS 2: namespace of the robot's topics, e.g. /tb3 (over [ros2] namespace).
    #[arg(long, value_name = "NS")]
    ns: Option<String>,

    /// Join ROS 2 beside the twin or a serial robot: RViz draws the map, plan and pose,
    /// RViz's "2D Goal Pose" (/goal_pose) and "2D Pose Estimate" (/initialpose) act,
    /// /rosout carries the log both ways (`--link ros2` does all this already).
    #[arg(long)]
    ros2: bool,

    /// ROS 2: DDS domain ID (default: ROS_DOMAIN_ID, else 0).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(0..=232))]
    domain: Option<u16>,

    /// World for the twin: a world file (TOML, see maps/) or a Nav2 map (map_server
    /// YAML + PGM, its occupied cells walls); default: the built-in arena.
    #[arg(long, value_name = "FILE")]
    world: Option<PathBuf>,

    /// Where the twin's robot starts, metres and degrees in the world's frame, instead
    /// of the world's own start (a Nav2 map's is its roomiest free cell).
    #[arg(long, value_name = "X,Y,THETA_DEG", value_parser = parse_pose, allow_hyphen_values = true)]
    start: Option<Pose2>,

    #[command(flatten)]
    localize: LocalizeArgs,

    /// Seed for the twin's sensor noise: the same seed replays the same run.
    #[arg(
        long,
        default_value_t = 1,
        value_name = "N",
        allow_negative_numbers = true
    )]
    seed: u64,

    /// Robot, teleop and twin parameters (TOML); unset fields keep seed 001's values.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,

    /// Keymap overlaid on the defaults, e.g. keymaps/teleop_twist_keyboard.toml.
    #[arg(long, value_name = "FILE")]
    keymap: Option<PathBuf>,

    /// The twin sees through a rendered camera and OpenCV's ArUco detector instead of its
    /// ideal marker sensor (needs a build with `--features vision`).
    #[arg(long)]
    sim_camera: bool,

    /// A camera beside the robot's link, read with OpenCV's ArUco detector on its own
    /// threads (feature `vision`): a V4L2 device (/dev/video0 or 0) or `ros2:TOPIC`
    /// (sensor_msgs/Image).
    #[arg(long, value_name = "SOURCE", conflicts_with = "sim_camera")]
    camera: Option<String>,

    /// Start with the braille map instead of ASCII.
    #[arg(long)]
    braille: bool,

    /// Run without a terminal: play --keys on simulated time, print a report.
    #[arg(long)]
    headless: bool,

    /// Headless: keys to press, e.g. "wwwwddd"; `<space>`, `<up>`, `<ctrl-c>` name keys.
    #[arg(long, value_name = "KEYS", requires = "headless")]
    keys: Option<String>,

    /// Headless: keys per second of simulated time.
    #[arg(long, default_value_t = 10.0, value_name = "HZ", requires = "headless",
          value_parser = parse_key_rate, allow_negative_numbers = true)]
    key_rate: f64,

    /// Headless: print the report as one JSON object.
    #[arg(long, requires = "headless")]
    json: bool,

    /// Where maps are saved (the save key S, :save NAME, autosave while exploring);
    /// default `maps` in the console, none in headless runs.
    #[arg(long, value_name = "DIR")]
    maps_dir: Option<PathBuf>,

    /// Record the session to this MCAP file (ROS 2 profile; `navdeck replay` plays it).
    /// `[record] folder` records every console session without it.
    #[arg(long, value_name = "FILE.mcap")]
    record: Option<PathBuf>,

    /// Where the console writes each session's log (navdeck-DATE-PID.log); default `logs`.
    #[arg(long, value_name = "DIR")]
    log_dir: Option<PathBuf>,

    #[command(subcommand)]
    command: Option<Subcommand>,
}

#[derive(Debug, clap::Subcommand)]
enum Subcommand {
    /// Plan one path (A*, shortcutting, smoothing, velocity profile) and print it.
    Plan(PlanArgs),
    /// Run the whole exploration-and-delivery mission in the twin on simulated time.
    Mission(MissionArgs),
    /// Drive the twin from goal to goal on simulated time and score the estimate against
    /// the truth (tracking, global localisation, a kidnapped robot).
    Tour(TourArgs),
    /// Look at a saved map (Nav2 map_server YAML + PGM).
    #[command(subcommand)]
    Map(MapCommand),
    /// Make twin worlds.
    #[command(subcommand)]
    World(WorldCommand),
    /// The arm's kinematics: joints for a tool position (ik) and back (fk).
    #[command(subcommand)]
    Arm(ArmCommand),
    /// Play a recording (--record): the console as it was, or re-run on today's code.
    Replay(ReplayArgs),
    /// Look at a ROS 2 domain: `ros2 topics` lists every topic with its types, counts,
    /// rate, QoS and mismatches.
    #[command(subcommand)]
    Ros2(Ros2Command),
}

#[derive(Debug, clap::Subcommand)]
enum MapCommand {
    /// Size, resolution, origin, landmark count and occupancy counts.
    Info {
        file: PathBuf,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Draw the map as text: '#' occupied, '.' free, blank unknown.
    Show {
        file: PathBuf,
        /// Columns of text.
        #[arg(long, default_value_t = 80, value_name = "N")]
        width: usize,
    },
}

#[derive(Debug, clap::Args)]
struct MissionArgs {
    /// The twin's noise seed.
    #[arg(
        long,
        default_value_t = 1,
        value_name = "N",
        allow_negative_numbers = true
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
    /// Also print every line the mission logged (one run; in the JSON as "log").
    #[arg(long, conflicts_with = "sweep")]
    log: bool,
}

#[derive(Debug, clap::Args)]
struct PlanArgs {
    /// Plan on a twin world file (TOML); default: the built-in arena.
    #[arg(long, value_name = "FILE", conflicts_with = "map")]
    world: Option<PathBuf>,
    /// Plan on a Nav2 map_server map (YAML naming a PGM).
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// Start, metres in the map frame: X,Y
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true)]
    from: Point2,
    /// Goal, metres in the map frame: X,Y
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true)]
    to: Point2,
    /// Planning parameters ([plan] and [map] sections).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Print the path, its length and cost and the planning time as one JSON object.
    #[arg(long)]
    json: bool,
}

/// A number within lo..=hi, or why not.
fn bounded(s: &str, lo: f64, hi: f64, unit: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v:?} {unit} is outside {lo}..={hi}"))
    }
}

/// Simulated seconds a headless run may spend pressing keys (two hours).
const MAX_HEADLESS_KEYS_TIME: f64 = 7200.0;

/// Headless keys per second of simulated time: 0.1 to 1000.
fn parse_key_rate(s: &str) -> Result<f64, String> {
    bounded(s, 0.1, 1000.0, "keys a second")
}

/// A mission's time limit: up to two simulated hours.
fn parse_time_limit(s: &str) -> Result<f64, String> {
    bounded(s, 1.0, 7200.0, "s")
}

/// A pose as X,Y,THETA_DEG: metres and degrees, finite.
fn parse_pose(s: &str) -> Result<Pose2, String> {
    navdeck::geometry::parse_pose_degrees(s)
}

fn parse_point(s: &str) -> Result<Point2, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y] = parts.as_slice() else {
        return Err(format!("`{s}` is not X,Y"));
    };
    let number = |v: &str| {
        v.parse::<f64>()
            .ok()
            .filter(|n| n.is_finite())
            .ok_or_else(|| format!("`{v}` in `{s}` is not a number of metres"))
    };
    Ok(Point2::new(number(x)?, number(y)?))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match real_main(cli) {
        Ok(code) => code,
        Err(e) => {
            say_err!("navdeck: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn real_main(cli: Cli) -> Result<ExitCode> {
    if let Some(command) = &cli.command {
        // The console's own options do nothing for a subcommand: say so, never ignore.
        let given = [
            ("--config", cli.config.is_some()),
            ("--world", cli.world.is_some()),
            ("--start", cli.start.is_some()),
            ("--keymap", cli.keymap.is_some()),
            ("--sim-camera", cli.sim_camera),
            ("--headless", cli.headless),
            ("--camera", cli.camera.is_some()),
            ("--ros2", cli.ros2),
            ("--record", cli.record.is_some()),
            ("--estimator", cli.localize.given() == Some("--estimator")),
            ("--map", cli.localize.given() == Some("--map")),
            (
                "--initial-pose",
                cli.localize.given() == Some("--initial-pose"),
            ),
        ];
        if let Some((option, _)) = given.iter().find(|(_, on)| *on) {
            let name = match command {
                Subcommand::Plan(_) => "plan",
                Subcommand::Mission(_) => "mission",
                Subcommand::Tour(_) => "tour",
                Subcommand::Map(_) => "map",
                Subcommand::World(_) => "world",
                Subcommand::Arm(_) => "arm",
                Subcommand::Replay(_) => "replay",
                Subcommand::Ros2(_) => "ros2",
            };
            anyhow::bail!(
                "{option} before `{name}` is the console's option: give the subcommand's own after it (navdeck {name} --help lists them)"
            );
        }
    }
    match &cli.command {
        Some(Subcommand::Plan(args)) => return run_plan(args),
        Some(Subcommand::Mission(args)) => return run_mission(args),
        Some(Subcommand::Tour(args)) => return tour_command::run(args),
        Some(Subcommand::Map(command)) => return run_map(command),
        Some(Subcommand::World(command)) => return world_command::run(command),
        Some(Subcommand::Arm(command)) => return arm_command::run(command),
        Some(Subcommand::Replay(args)) => return replay_command::run(args),
        Some(Subcommand::Ros2(command)) => {
            if let Some(option) = [
                ("--domain", cli.domain.is_some()),
                ("--ns", cli.ns.is_some()),
            ]
            .iter()
            .find_map(|(name, on)| on.then_some(name))
            {
                bail!(
                    "{option} before `ros2` is the console's option: give it after `ros2 topics`"
                );
            }
            return ros2_command::run(command);
        }
        None => {}
    }
    let spec = SessionSpec {
        world: cli.world.clone(),
        seed: cli.seed,
        start: cli.start,
        config: cli.config.clone(),
        keymap: cli.keymap.clone(),
        link: match &cli.link {
            LinkChoice::Ros2(_) => LinkChoice::Ros2(navdeck::session::Ros2Target {
                namespace: cli.ns.clone(),
                domain: cli.domain,
            }),
            other => other.clone(),
        },
        localize: cli.localize.choice(),
    };
    // Everything is loaded and validated before the terminal is touched.
    let mut session = Session::load(&spec)?;
    // One monotonic clock times planning and camera detection alike.
    let stopwatch: std::sync::Arc<dyn Clock> = std::sync::Arc::new(WallClock::start());
    if cli.sim_camera {
        session.use_sim_camera(Some(stopwatch.clone()), CameraFrames::Whole)?;
    }
    if let Some(source) = &cli.camera {
        session = session.with_camera(source, stopwatch.clone())?;
    }
    if cli.ros2 {
        session = session.with_ros2(&navdeck::session::Ros2Target {
            namespace: cli.ns.clone(),
            domain: cli.domain,
        })?;
    }
    let record = match (&cli.record, &session.config.record.folder) {
        (Some(path), _) => Some((path.clone(), recording_metadata(&cli))),
        (None, Some(dir)) if !cli.headless => Some((
            navdeck::console::dated_recording(dir),
            recording_metadata(&cli),
        )),
        _ => None,
    };
    if cli.headless {
        return run_headless(session, &cli, stopwatch, record);
    }
    let options = ConsoleOptions {
        maps_dir: cli.maps_dir.clone(),
        log_dir: cli.log_dir.clone(),
        braille: cli.braille,
        record,
    };
    Ok(ExitCode::from(run_console(session, &options, stopwatch)?))
}

/// How the session was started, for its recording (a replay re-runs it the same way).
fn recording_metadata(cli: &Cli) -> std::collections::BTreeMap<String, String> {
    let mut m = std::collections::BTreeMap::new();
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    m.insert("seed".into(), cli.seed.to_string());
    let given = [
        ("world", path(&cli.world)),
        ("config", path(&cli.config)),
        ("keymap", path(&cli.keymap)),
        (
            "start",
            cli.start
                .map(|p| format!("{},{},{}", p.x, p.y, p.theta.to_degrees())),
        ),
        ("estimator", cli.localize.estimator_name()),
        ("map", cli.localize.map_name()),
        ("initial_pose", cli.localize.initial_pose_text()),
        ("sim_camera", cli.sim_camera.then(|| "true".to_string())),
        (
            "keymap_text",
            cli.keymap
                .as_ref()
                .and_then(|p| std::fs::read_to_string(p).ok()),
        ),
    ];
    for (key, value) in given {
        if let Some(v) = value {
            m.insert(key.into(), v);
        }
    }
    m
}

fn run_headless(
    session: Session,
    cli: &Cli,
    stopwatch: std::sync::Arc<dyn Clock>,
    record: Option<(PathBuf, std::collections::BTreeMap<String, String>)>,
) -> Result<ExitCode> {
    if !(cli.key_rate.is_finite() && cli.key_rate > 0.0) {
        bail!("--key-rate {} must be a positive number", cli.key_rate);
    }
    let keys =
        parse_key_sequence(cli.keys.as_deref().unwrap_or("")).context("cannot read --keys")?;
    let lasts = keys.len() as f64 / cli.key_rate;
    if lasts > MAX_HEADLESS_KEYS_TIME {
        bail!(
            "--keys: {} keys at {} a second take {lasts:.0} s, over the {MAX_HEADLESS_KEYS_TIME} s a headless run may press keys for",
            keys.len(),
            cli.key_rate
        );
    }
    let mut app = session.into_app(0.0);
    if let Some((path, meta)) = &record {
        let simulated = app.link().ground_truth().is_some();
        navdeck::console::start_recording(&mut app, path, meta.clone(), simulated)?;
    }
    let started = Instant::now();
    app.set_stopwatch(stopwatch);
    if let Some(dir) = &cli.maps_dir {
        app.set_maps_dir(dir.clone());
    }
    // A real robot moves in real time: keep the session clock on the wall clock, and
    // stop the robot on SIGINT, SIGTERM or SIGHUP.
    // So does a twin beside ROS 2: the other nodes live on the wall clock.
    let signals = match (app.link().ground_truth(), cli.ros2) {
        (Some(_), false) => None,
        _ => Some(Signals::watch().context("cannot watch for signals")?),
    };
    let mut report = match &signals {
        None => headless::run(&mut app, &keys, cli.key_rate),
        Some(signals) => {
            let mut pace = |t: f64| {
                let ahead = t - started.elapsed().as_secs_f64();
                if ahead > 0.0 {
                    std::thread::sleep(std::time::Duration::from_secs_f64(ahead));
                }
                signals.pending().is_none()
            };
            headless::run_paced(&mut app, &keys, cli.key_rate, &mut pace)
        }
    };
    // A run whose robot stopped answering did not do what it was asked.
    let lost = match app.pilot().link_status() {
        navdeck::app::LinkStatus::Lost(why) => Some(why.clone()),
        _ => None,
    };
    app.shutdown("headless run ended");
    let status = signals
        .as_ref()
        .and_then(Signals::pending)
        .map_or(0, |n| 128 + n as i32);
    if let Some(signals) = &signals {
        signals.arm_immediate_exit(navdeck::console::exit_deadline(), status);
    }
    let wall = started.elapsed().as_secs_f64();
    match app.finish_recording() {
        Some(Ok(summary)) => report.recording = Some(summary),
        Some(Err(why)) => say_err!("navdeck: {why}"),
        None => {}
    }
    report.wall_time_s = Some(wall);
    report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
    if cli.json {
        sayln!("{}", serde_json::to_string(&report)?);
    } else {
        say!("{}", headless::human(&report));
    }
    // A save that was asked for and failed fails the run (the log says why).
    if let Some(why) = &lost {
        say_err!("navdeck: the robot was not answering at the end: {why}");
    }
    let status = if status == 0 && (app.failed_saves() > 0 || lost.is_some()) {
        1
    } else {
        status
    };
    drop(app);
    Ok(ExitCode::from(status as u8))
}

fn run_plan(args: &PlanArgs) -> Result<ExitCode> {
    let config = match &args.config {
        Some(path) => Config::load(path)?,
        None => Config::default(),
    };
    let terrain = match (&args.map, &args.world) {
        (Some(map), _) => Terrain::Map(map_io::load(map)?.grid),
        (None, Some(world)) => Terrain::World(
            World::load(world).with_context(|| format!("cannot use world {}", world.display()))?,
        ),
        (None, None) => Terrain::World(World::default_arena()),
    };
    let map = plan_report::survey(&terrain, &config.map);
    let started = Instant::now();
    let result = plan_report::plan(&map, args.from, args.to, &config);
    let took = started.elapsed().as_secs_f64() * 1e3;
    let mut report = match result {
        Ok(report) => report,
        Err(e) => {
            say_err!("navdeck plan: no path: {e}");
            return Ok(ExitCode::from(1));
        }
    };
    report.planning_time_ms = Some(took);
    if args.json {
        sayln!("{}", serde_json::to_string(&report)?);
    } else {
        say!("{}", plan_report::human(&report));
    }
    Ok(ExitCode::SUCCESS)
}

fn run_mission(args: &MissionArgs) -> Result<ExitCode> {
    if !(args.time_limit.is_finite() && args.time_limit > 0.0) {
        bail!(
            "--time-limit {} must be a positive number of seconds",
            args.time_limit
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
        Ok(session)
    };
    // Load once up front so a bad file is refused before anything runs.
    load(args.seed)?;
    let one = |seed: u64| -> Result<mission_runner::MissionReport> {
        let session = load(seed)?;
        let localizer = session.localizer.clone();
        let (config, link) = session.into_link();
        let started = Instant::now();
        let mut report = mission_runner::run(
            &config,
            link,
            localizer.as_ref(),
            seed,
            args.time_limit,
            args.log,
        );
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
    let next = std::sync::atomic::AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get());
    let results = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&seed) = seeds.get(k) else { break };
                    let report = one(seed);
                    results.lock().expect("no worker panicked").push(report);
                }
            });
        }
    });
    let reports = results
        .into_inner()
        .expect("no worker panicked")
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

fn run_map(command: &MapCommand) -> Result<ExitCode> {
    match command {
        MapCommand::Info { file, json } => {
            let info = map_report::info(&map_io::load(file)?);
            if *json {
                sayln!("{}", serde_json::to_string(&info)?);
            } else {
                say!("{}", map_report::human(&info));
            }
        }
        MapCommand::Show { file, width } => {
            if *width == 0 || *width > 2000 {
                bail!("--width {width} must lie in 1..=2000");
            }
            say!("{}", map_report::show(&map_io::load(file)?.grid, *width));
        }
    }
    Ok(ExitCode::SUCCESS)
}
