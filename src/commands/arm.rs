//! `navdeck arm ik|fk` (part of the binary, beside main.rs): the command line's side of
//! `navdeck::arm`. The solve is timed here; the kinematics read no clock.

use anyhow::Result;
use navdeck::arm::{self, ArmConfig, Joints, Solver, Target, Unreachable};
use navdeck::config::Config;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// `navdeck arm ...`: the arm's kinematics, from the [arm] section of --config (its
/// defaults, seed 000's arm, without one).
#[derive(Debug, clap::Subcommand)]
pub enum ArmCommand {
    /// Joints that put the tool on X Y Z (metres in the arm's base frame: x forward,
    /// y left, z up from joint 1's base), nearest the `home` pose; exit 1 if unreachable.
    Ik(IkArgs),
    /// Where the tool is with the joints at J1 J2 J3 J4 (radians, base to wrist).
    Fk(FkArgs),
    /// Pick a block many times in the twin, 20-45 cm ahead, placed by the camera's and the
    /// lidar's fused sightings, a missed grip retried: success and error per distance band.
    PickTest(PickTestArgs),
}

#[derive(Debug, clap::Args)]
pub struct PickTestArgs {
    /// How many picks, spread evenly over the five 5 cm bands.
    #[arg(long, default_value_t = 200, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=10_000))]
    picks: u64,
    /// Seed of the block placements and the twin's noise.
    #[arg(long, default_value_t = 1, value_name = "N", value_parser = super::args::whole::<u64>)]
    seed: u64,
    /// Robot, twin and [arm] parameters (TOML); without [arm], the default arm.
    #[arg(long, value_name = "FILE")]
    config: Option<std::path::PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct IkArgs {
    /// Forward, metres (within 7 m: no arm navdeck accepts reaches farther).
    #[arg(value_name = "X", value_parser = metres)]
    x: f64,
    /// Left, metres.
    #[arg(value_name = "Y", value_parser = metres)]
    y: f64,
    /// Up, metres.
    #[arg(value_name = "Z", value_parser = metres)]
    z: f64,
    /// The tool's pitch, degrees: 0 level, 90 straight down, within a turn either way
    /// (default: the pitch nearest [arm] preferred_pitch that reaches; the 2dof solver's
    /// is fixed).
    #[arg(long, value_name = "DEG", value_parser = pitch_degrees)]
    pitch: Option<f64>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// Parameters (TOML): the [arm] section.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
}

#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct FkArgs {
    /// Joint 1, the base's yaw, radians (within its [arm.limits]).
    #[arg(value_name = "J1", value_parser = joint_radians)]
    j1: f64,
    /// Joint 2, the shoulder, radians (within its [arm.limits]).
    #[arg(value_name = "J2", value_parser = joint_radians)]
    j2: f64,
    /// Joint 3, the elbow, radians (within its [arm.limits]).
    #[arg(value_name = "J3", value_parser = joint_radians)]
    j3: f64,
    /// Joint 4, the wrist, radians (within its [arm.limits]).
    #[arg(value_name = "J4", value_parser = joint_radians)]
    j4: f64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// Parameters (TOML): the [arm] section.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
}

/// A finite number (NaN and infinities refused, naming the argument) within lo..=hi.
fn finite_within(s: &str, lo: f64, hi: f64, unit: &str) -> Result<f64, String> {
    let v = s
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| format!("`{s}` is not a finite number"))?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(super::args::outside(v, lo, hi, unit))
    }
}

/// A target coordinate: no arm a config may describe reaches farther from its base
/// (`arm::config::FARTHEST_REACH`: the highest shoulder and three of the longest links).
fn metres(s: &str) -> Result<f64, String> {
    let far = navdeck::arm::config::FARTHEST_REACH;
    finite_within(s, -far, far, "m")
}

/// A tool pitch: within a turn either way (every angle has a name in that range).
fn pitch_degrees(s: &str) -> Result<f64, String> {
    finite_within(s, -360.0, 360.0, "deg")
}

/// A joint angle: a finite number here; its own `[arm.limits]` are checked once the
/// config is read, and name the joint and its range.
fn joint_radians(s: &str) -> Result<f64, String> {
    finite_within(s, f64::MIN, f64::MAX, "rad")
}

/// The joints' names, base to wrist, for messages.
const JOINT_NAMES: [&str; 4] = ["base yaw", "shoulder", "elbow", "wrist"];

/// The first of `joints` outside its `[arm.limits]`, as a sentence naming it, its value
/// and its range.
fn outside_limits(cfg: &ArmConfig, joints: &Joints) -> Option<String> {
    use navdeck::data::number::short;
    (0..4).find_map(|i| {
        let (lo, hi, v) = (cfg.limits.min[i], cfg.limits.max[i], joints.0[i]);
        (!(lo..=hi).contains(&v)).then(|| {
            format!(
                "J{} ({}) = {} rad is outside its limits {}..={} rad ([arm.limits] min[{i}], max[{i}])",
                i + 1,
                JOINT_NAMES[i],
                short(v),
                short(lo),
                short(hi)
            )
        })
    })
}

/// The [arm] section of `path`, or its defaults.
fn arm_config(path: Option<&Path>) -> Result<ArmConfig> {
    Ok(match path {
        Some(path) => Config::load(path)?.arm.unwrap_or_default(),
        None => ArmConfig::default(),
    })
}

fn solver_name(solver: Solver) -> &'static str {
    match solver {
        Solver::FourDof => "4dof",
        Solver::TwoDof => "2dof",
    }
}

/// A short name for why a target is unreachable, for JSON.
fn kind(e: &Unreachable) -> &'static str {
    match e {
        Unreachable::TooFar { .. } => "too_far",
        Unreachable::TooClose { .. } => "too_close",
        Unreachable::NoPitch { .. } => "no_pitch",
        Unreachable::PitchOutOfReach { .. } => "pitch_out_of_reach",
        Unreachable::JointLimit { .. } => "joint_limit",
        Unreachable::Singular { .. } => "singular",
        Unreachable::NotANumber { .. } => "not_a_number",
        Unreachable::PitchLocked { .. } => "pitch_locked",
    }
}

pub fn run(command: &ArmCommand) -> Result<ExitCode> {
    match command {
        ArmCommand::Ik(args) => ik(args),
        ArmCommand::Fk(args) => fk(args),
        ArmCommand::PickTest(args) => pick_test(args),
    }
}

fn pick_test(args: &PickTestArgs) -> Result<ExitCode> {
    let config = match &args.config {
        Some(path) => navdeck::config::Config::load(path)?,
        None => navdeck::config::Config::default(),
    };
    let started = std::time::Instant::now();
    let (picks, bands) = navdeck::runners::arm_pick::run(&config, args.picks as usize, args.seed);
    let wall = started.elapsed().as_secs_f64();
    if args.json {
        let out = serde_json::json!({ "bands": bands, "picks": picks, "wall_time_s": wall });
        sayln!("{out}");
    } else {
        for b in &bands {
            let band = format!("{:.2}-{:.2} m", b.from_m, b.to_m);
            if b.picks == 0 {
                sayln!("{band}: no picks in this band");
                continue;
            }
            let error = b.mean_error_mm.map_or_else(
                || "the camera never saw the block".to_string(),
                |e| format!("mean error {e:.1} mm"),
            );
            let time = b
                .mean_time_s
                .map_or_else(String::new, |t| format!(", {t:.1} s each"));
            sayln!(
                "{band}: {}/{} picked ({:.1} %), {error}{time}, {} missed reaches retried in {} picks",
                b.successes,
                b.picks,
                b.success_rate * 100.0,
                b.misses,
                b.retried,
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn ik(args: &IkArgs) -> Result<ExitCode> {
    let cfg = arm_config(args.config.as_deref())?;
    let target = Target {
        pitch: args.pitch.map(f64::to_radians),
        ..Target::point(args.x, args.y, args.z)
    };
    let current = Joints(cfg.poses.home);
    let started = Instant::now();
    let solved = arm::inverse(&cfg, &target, &current);
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let solver = solver_name(cfg.solver);
    let s = match solved {
        Ok(s) => s,
        Err(e) => {
            if args.json {
                let out = serde_json::json!({
                    "reachable": false,
                    "solver": solver,
                    "kind": kind(&e),
                    "reason": e.to_string(),
                    "solve_time_us": micros,
                });
                sayln!("{out}");
            } else {
                say_err!("navdeck arm ik: unreachable: {e}");
            }
            return Ok(ExitCode::from(1));
        }
    };
    let pose = arm::forward(&cfg, &s.joints);
    let near_singular = arm::near_singular(&cfg, s.manipulability);
    if args.json {
        let out = serde_json::json!({
            "reachable": true,
            "solver": solver,
            "joints": s.joints,
            "branch": s.branch,
            "pose": pose,
            "residual_m": s.residual,
            "manipulability": s.manipulability,
            "near_singular": near_singular,
            "iterations": s.iterations,
            "solve_time_us": micros,
        });
        sayln!("{out}");
    } else {
        let [a, b, c, d] = s.joints.0;
        sayln!("joints    {a:.6} {b:.6} {c:.6} {d:.6} rad");
        sayln!("branch    {}", s.branch);
        sayln!("pitch     {:.1} deg", pose.pitch.to_degrees());
        sayln!(
            "residual  {:.4} mm (the tool at these joints to the target)",
            s.residual * 1e3
        );
        sayln!(
            "solved    in {micros:.1} us ({solver}, {} refinement steps), manipulability {:.2e} m^3",
            s.iterations,
            s.manipulability
        );
        if near_singular {
            sayln!(
                "warning   near a singularity: the tool cannot move in every direction here and a small change of target may swing a joint far ([arm] min_manipulability refuses such poses)"
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn fk(args: &FkArgs) -> Result<ExitCode> {
    let cfg = arm_config(args.config.as_deref())?;
    let joints = Joints([args.j1, args.j2, args.j3, args.j4]);
    if let Some(why) = outside_limits(&cfg, &joints) {
        say_err!("navdeck arm fk: {why}");
        return Ok(ExitCode::from(1));
    }
    let pose = arm::forward(&cfg, &joints);
    if args.json {
        let out = serde_json::json!({
            "x": pose.x,
            "y": pose.y,
            "z": pose.z,
            "pitch": pose.pitch,
            "pitch_deg": pose.pitch.to_degrees(),
            "within_limits": true,
        });
        sayln!("{out}");
    } else {
        sayln!(
            "x {:.6} m  y {:.6} m  z {:.6} m  pitch {:.1} deg",
            pose.x,
            pose.y,
            pose.z,
            pose.pitch.to_degrees()
        );
    }
    Ok(ExitCode::SUCCESS)
}
