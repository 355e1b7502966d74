//! `navdeck plan`: plan one path and print it.

use super::args::parse_point;
use anyhow::{Context, Result};
use navdeck::config::Config;
use navdeck::geometry::Point2;
use navdeck::map::io as map_io;
use navdeck::runners::plan_report::{self, Terrain};
use navdeck::sim::World;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub(crate) struct PlanArgs {
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

pub(crate) fn run(args: &PlanArgs) -> Result<ExitCode> {
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
