//! navdeck's command line: the console by default, or a headless run.

use anyhow::{Result, bail};
use clap::Parser;
use commands::args::{parse_domain, parse_key_rate, whole};
use commands::arm::ArmCommand;
use commands::map::MapCommand;
use commands::mission::MissionArgs;
use commands::plan::PlanArgs;
use commands::replay::ReplayArgs;
use commands::ros2::Ros2Command;
use commands::tour::{LocalizeArgs, TourArgs};
use commands::twin_args::TwinArgs;
use commands::world::WorldCommand;
use navdeck::session::LinkChoice;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[macro_use]
mod commands;

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

    /// ROS 2: namespace of the robot's topics, e.g. /tb3 (over [ros2] namespace). Given
    /// more than once, one console drives a fleet: a robot per namespace.
    #[arg(long, value_name = "NS")]
    ns: Vec<String>,

    /// Put N twins in one world, a fleet in one console: each with its own pilot, seen by
    /// the others' lidars and cameras, able to run into them; robot 1 at the world's
    /// start, the others on free places nearest it.
    #[arg(long, value_name = "N", value_parser = whole::<usize>)]
    robots: Option<usize>,

    /// Join ROS 2 beside the twin or a serial robot: RViz draws the map, plan and pose,
    /// RViz's "2D Goal Pose" (/goal_pose) and "2D Pose Estimate" (/initialpose) act,
    /// /rosout carries the log both ways (`--link ros2` does all this already).
    #[arg(long)]
    ros2: bool,

    /// ROS 2: DDS domain ID (default: ROS_DOMAIN_ID, else 0).
    #[arg(long, value_name = "N", value_parser = parse_domain)]
    domain: Option<u16>,

    #[command(flatten)]
    twin: TwinArgs,

    #[command(flatten)]
    localize: LocalizeArgs,

    /// Robot, teleop and twin parameters (TOML); unset fields keep seed 001's values.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,

    /// Keymap overlaid on the defaults, e.g. keymaps/teleop_twist_keyboard.toml.
    #[arg(long, value_name = "FILE")]
    keymap: Option<PathBuf>,

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
    /// Follow a track's lane in the twin on simulated time (seed 000: lane lines, traffic
    /// lights, barriers) and score the run against the truth.
    Lane(commands::lane::LaneArgs),
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
    /// Tag maps (seed 003): check one, and plan BFS routes through it.
    #[command(subcommand)]
    Tags(commands::tags::TagsCommand),
    /// Drive a tag map's task in the twin (seed 003) and score it against the truth.
    Route(commands::route::RouteArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return refused_command_line(e),
    };
    match real_main(cli) {
        Ok(code) => code,
        Err(e) => {
            say_err!("navdeck: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// clap's answer to a command line it cannot take. Help and version are printed as they
/// are; a refusal quotes the value as typed, so it is escaped and cut as every error is.
fn refused_command_line(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    let code = u8::try_from(e.exit_code()).unwrap_or(2);
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = e.print();
        return ExitCode::from(code);
    }
    let text = e.render().to_string();
    say_err!("{}", text.trim_end());
    ExitCode::from(code)
}

fn real_main(cli: Cli) -> Result<ExitCode> {
    if let Some(command) = &cli.command {
        // The console's own options do nothing for a subcommand: say so, never ignore.
        let given = [
            ("--config", cli.config.is_some()),
            ("--world", cli.twin.world.is_some()),
            ("--start", cli.twin.start.is_some()),
            ("--tags", cli.twin.tags.is_some()),
            ("--keymap", cli.keymap.is_some()),
            ("--sim-camera", cli.twin.sim_camera),
            ("--fault", !cli.twin.fault.is_empty()),
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
                Subcommand::Lane(_) => "lane",
                Subcommand::Map(_) => "map",
                Subcommand::World(_) => "world",
                Subcommand::Arm(_) => "arm",
                Subcommand::Replay(_) => "replay",
                Subcommand::Ros2(_) => "ros2",
                Subcommand::Tags(_) => "tags",
                Subcommand::Route(_) => "route",
            };
            anyhow::bail!(
                "{option} before `{name}` is the console's option: give the subcommand's own after it (navdeck {name} --help lists them)"
            );
        }
    }
    match &cli.command {
        Some(Subcommand::Plan(args)) => return commands::plan::run(args),
        Some(Subcommand::Mission(args)) => return commands::mission::run(args),
        Some(Subcommand::Tour(args)) => return commands::tour::run(args),
        Some(Subcommand::Lane(args)) => return commands::lane::run(args),
        Some(Subcommand::Map(command)) => return commands::map::run(command),
        Some(Subcommand::World(command)) => return commands::world::run(command),
        Some(Subcommand::Arm(command)) => return commands::arm::run(command),
        Some(Subcommand::Replay(args)) => return commands::replay::run(args),
        Some(Subcommand::Tags(command)) => return commands::tags::run(command),
        Some(Subcommand::Route(args)) => return commands::route::run(args),
        Some(Subcommand::Ros2(command)) => {
            if let Some(option) = [
                ("--domain", cli.domain.is_some()),
                ("--ns", !cli.ns.is_empty()),
            ]
            .iter()
            .find_map(|(name, on)| on.then_some(name))
            {
                bail!(
                    "{option} before `ros2` is the console's option: give it after `ros2 topics`"
                );
            }
            return commands::ros2::run(command);
        }
        None => {}
    }
    for ns in &cli.ns {
        commands::args::check_namespace("--ns", ns)?;
    }
    commands::console::run(&cli)
}
