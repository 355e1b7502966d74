//! `navdeck route`: drive a tag map's task in the twin (seed 003) and score it against
//! the truth: each tag reached, each turn, the end on the last tag, blocked legs.

use anyhow::{Context, Result};
use navdeck::config::Config;
use navdeck::runners::route::{self as runner, RouteOptions, RouteReport};
use navdeck::runners::route_camera::TagSensor;
use navdeck::tags::{TagId, TagMap, generate};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub(crate) struct RouteArgs {
    /// The tag map (seed 003's map.yaml shape).
    #[arg(long, value_name = "FILE", required_unless_present = "sweep")]
    tags: Option<PathBuf>,
    /// Instead of a file: every task on generated tag grids A..B (random sizes, joins
    /// left out, a box on an edge in every third), each with its seed.
    #[arg(long, value_name = "A..B", conflicts_with_all = ["tags", "task"])]
    sweep: Option<String>,
    /// The task to drive, by name (every task of the map with --all-tasks).
    #[arg(long, value_name = "NAME", required_unless_present_any = ["all_tasks", "sweep"])]
    task: Option<String>,
    /// Drive every task of the map in turn.
    #[arg(long, conflicts_with = "task")]
    all_tasks: bool,
    /// The twin's seed (its odometry's and sensors' noise).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Put a box on the edge FROM-TO (repeatable): the collision monitor stops the
    /// robot there, the leg is marked blocked and the rest planned round it.
    #[arg(long, value_name = "FROM-TO", value_parser = super::tags::edge)]
    obstacle: Vec<(TagId, TagId)>,
    /// Simulated seconds a task may take.
    #[arg(long, default_value_t = 1800.0, value_name = "S", value_parser = super::args::parse_time_limit)]
    time_limit: f64,
    /// The control loop's rate, Hz (seed 003: 30).
    #[arg(long, default_value_t = runner::RATE_HZ, value_name = "HZ", value_parser = rate)]
    rate: f64,
    /// Parameters (TOML): the robot, the twin and the collision monitor's zones.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// See the tags in the rendered camera's frames (1280x720, each tag drawn as its
    /// AprilTag 36h11 pattern) with OpenCV's detector and solvePnP, instead of the ideal
    /// tag camera; the JSON adds the detection figures. Needs the `vision` feature.
    #[arg(long)]
    sim_camera: bool,
    /// Print one JSON object per task.
    #[arg(long)]
    json: bool,
}

/// A map to drive, the edges with a box on them, and the twin's seed.
type MapToDrive = (TagMap, Vec<(TagId, TagId)>, u64);

fn rate(s: &str) -> Result<f64, String> {
    super::args::bounded(s, 1.0, 200.0, "rate")
}

fn human(r: &RouteReport) -> String {
    let end = match (r.end_side_m, r.end_along_m, r.end_heading_deg) {
        (Some(side), Some(along), Some(heading)) => format!(
            "; on the last tag {:.1} mm to the side, {:.1} mm along, {:.2}° off",
            side * 1000.0,
            along * 1000.0,
            heading
        ),
        _ => String::new(),
    };
    let worst_turn = r.turn_errors_deg.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    let camera = r.detection.as_ref().map_or(String::new(), |d| {
        let lateral = d.lateral_error_m.map_or(0.0, |e| e.mean * 1000.0);
        let ms = d.detect_time.map_or(0.0, |t| t.mean_ms);
        format!(
            "; camera: {} of {} tags in view found, lateral error {lateral:.2} mm, {ms:.1} ms a frame",
            d.tags_found_in_view, d.tags_in_view
        )
    });
    format!(
        "task {} (seed {}): {} in {:.1} s, {} legs, {} turns (worst {:.2}°){}; blocked {:?}; collisions {}{camera}{}\n",
        r.task,
        r.seed,
        if r.completed { "done" } else { "NOT done" },
        r.sim_time,
        r.legs_driven,
        r.turn_errors_deg.len(),
        worst_turn,
        end,
        r.blocked,
        r.collisions,
        r.failure
            .as_ref()
            .map(|f| format!(" ({f})"))
            .unwrap_or_default(),
    )
}

pub(crate) fn run(args: &RouteArgs) -> Result<ExitCode> {
    #[cfg(not(feature = "vision"))]
    if args.sim_camera {
        anyhow::bail!("--sim-camera {}", navdeck::session::NEEDS_VISION);
    }
    let sensor = if args.sim_camera {
        TagSensor::Rendered
    } else {
        TagSensor::Ideal
    };
    let stopwatch = navdeck::tui::events::WallClock::start();
    let config = match &args.config {
        Some(path) => Config::load(path).with_context(|| format!("config {}", path.display()))?,
        None => Config::default(),
    };
    // (map, boxes on edges, seed) for each map to drive.
    let maps: Vec<MapToDrive> = match (&args.tags, &args.sweep) {
        (Some(path), _) => vec![(super::tags::load(path)?, args.obstacle.clone(), args.seed)],
        (None, Some(range)) => navdeck::runners::mission::parse_seeds(range)
            .map_err(anyhow::Error::msg)?
            .into_iter()
            .map(|seed| {
                let g = generate::grid(seed);
                (g.map, g.obstacles, seed)
            })
            .collect(),
        (None, None) => unreachable!("clap requires --tags or --sweep"),
    };
    let mut all_done = true;
    for (map, obstacles, seed) in &maps {
        let tasks: Vec<String> = match &args.task {
            Some(task) => vec![task.clone()],
            None => map.tasks.keys().cloned().collect(),
        };
        for task in tasks {
            let options = RouteOptions {
                task,
                seed: *seed,
                obstacles: obstacles.clone(),
                time_limit: args.time_limit,
                period: 1.0 / args.rate,
                sensor,
            };
            let started = Instant::now();
            let mut report = runner::run(&config, map, &options, Some(&stopwatch))
                .map_err(anyhow::Error::msg)?;
            let wall = started.elapsed().as_secs_f64();
            report.wall_time_s = Some(wall);
            report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
            all_done &= report.completed;
            if args.json {
                sayln!("{}", serde_json::to_string(&report)?);
            } else {
                say!("{}", human(&report));
            }
        }
    }
    Ok(if all_done {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
