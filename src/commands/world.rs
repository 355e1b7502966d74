//! `navdeck world ...` and the options every generated world is asked with (part of the
//! binary, beside main.rs): the command line's side of `navdeck::sim::generate`.

use anyhow::Result;
use navdeck::sim::generate::{self, Colours, GenerateError, GenerateOptions, Style};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// `navdeck world ...`.
#[derive(Debug, clap::Subcommand)]
pub enum WorldCommand {
    /// Generate a world from a seed (rooms, boxes, corridors, loop or a lane track) and write
    /// it as a world file.
    Generate(GenerateArgs),
}

/// `navdeck world generate`.
#[derive(Debug, clap::Args)]
pub struct GenerateArgs {
    /// Seed of the world: the same seed and options give the same world.
    #[arg(long, value_name = "N", value_parser = super::args::whole::<u64>)]
    seed: u64,
    #[command(flatten)]
    shape: ShapeArgs,
    /// The world file to write (TOML, the format of maps/arena.toml).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    /// Also write the world's true walls and boxes as a Nav2 map (FILE.yaml + FILE.pgm,
    /// 5 cm cells, the tour's ground truth): to localise on, or to set beside a SLAM map.
    #[arg(long, value_name = "FILE.yaml")]
    nav2_map: Option<PathBuf>,
}

/// The cell size of the true map `--nav2-map` writes: the 5 cm of the tour's raster and
/// of TurtleBot3's slam_toolbox maps.
const TRUE_MAP_RESOLUTION: f64 = 0.05;

/// What a generated world holds.
#[derive(Debug, clap::Args)]
pub struct ShapeArgs {
    /// Width and height in metres, W,H (default 4,4 for boxes, 5,4 for rooms and corridors,
    /// 6,4 for a loop; a track's is drawn from 4-8 m a side).
    #[arg(long, value_name = "W,H", value_parser = parse_size)]
    size: Option<(f64, f64)>,
    /// Blocks (default 3), red and blue in turn unless --colours says otherwise.
    #[arg(long, value_name = "K", allow_negative_numbers = true, value_parser = super::args::whole::<usize>)]
    blocks: Option<usize>,
    /// Box obstacles (default 3).
    #[arg(long, value_name = "K", allow_negative_numbers = true, value_parser = super::args::whole::<usize>)]
    obstacles: Option<usize>,
    /// rooms, boxes, corridors, loop (one corridor round an island) or track (a closed lane
    /// with traffic lights and barriers, no blocks or boxes); default boxes.
    #[arg(long, value_name = "STYLE")]
    style: Option<Style>,
    /// No markers on the walls and boxes (blocks and gates keep theirs); the same layout.
    #[arg(long)]
    no_wall_markers: bool,
    /// Ways round: a second doorway between rooms, corridor walls free at both ends.
    #[arg(long)]
    loops: bool,
    /// Metres between wall markers, 0.4 to 2 (default 0.5, as maps/arena.toml).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    marker_spacing: Option<f64>,
    /// The blocks' colours: alternating (default), random (seeded; at most 9 of one, a
    /// gate's drop places) or one (every block red).
    #[arg(long, value_name = "HOW")]
    colours: Option<Colours>,
    /// Every doorway between rooms and every corridor turn this wide, metres, 0.5 to 2
    /// (default: drawn from 0.8-1.1 and 0.8-1.2).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    doorway: Option<f64>,
    /// Rooms in a rooms world, 2 up to what its size holds (default: 2-4 drawn).
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = super::args::whole::<usize>)]
    rooms: Option<usize>,
}

impl ShapeArgs {
    pub fn options(&self, seed: u64) -> GenerateOptions {
        let default = GenerateOptions::default();
        GenerateOptions {
            seed,
            size: self.size,
            blocks: self.blocks.unwrap_or(default.blocks),
            obstacles: self.obstacles.unwrap_or(default.obstacles),
            style: self.style.unwrap_or(default.style),
            wall_markers: !self.no_wall_markers,
            loops: self.loops,
            marker_spacing: self.marker_spacing.unwrap_or(default.marker_spacing),
            colours: self.colours.unwrap_or(default.colours),
            doorway: self.doorway,
            rooms: self.rooms,
        }
    }

    /// The first option given, if any.
    pub fn given(&self) -> Option<&'static str> {
        [
            (self.size.is_some(), "--size"),
            (self.blocks.is_some(), "--blocks"),
            (self.obstacles.is_some(), "--obstacles"),
            (self.style.is_some(), "--style"),
            (self.no_wall_markers, "--no-wall-markers"),
            (self.loops, "--loops"),
            (self.marker_spacing.is_some(), "--marker-spacing"),
            (self.colours.is_some(), "--colours"),
            (self.doorway.is_some(), "--doorway"),
            (self.rooms.is_some(), "--rooms"),
        ]
        .into_iter()
        .find_map(|(given, flag)| given.then_some(flag))
    }
}

/// `W,H` in metres, e.g. `5,4`.
fn parse_size(s: &str) -> Result<(f64, f64), String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [w, h] = parts.as_slice() else {
        return Err(format!("`{s}` is not W,H (metres, e.g. 5,4)"));
    };
    let number = |v: &str| {
        v.parse::<f64>()
            .ok()
            .filter(|n| n.is_finite() && *n > 0.0)
            .ok_or_else(|| format!("`{v}` in `{s}` is not a positive number of metres"))
    };
    Ok((number(w)?, number(h)?))
}

/// A generator error, naming the command-line flag when an option was refused.
pub fn generate_error(e: GenerateError) -> anyhow::Error {
    match e {
        GenerateError::Option {
            option,
            value,
            reason,
        } => anyhow::anyhow!("--{option} {value}: {reason}"),
        other => other.into(),
    }
}

/// Runs a `navdeck world` command.
pub fn run(command: &WorldCommand) -> Result<ExitCode> {
    match command {
        WorldCommand::Generate(args) => run_generate(args),
    }
}

fn run_generate(args: &GenerateArgs) -> Result<ExitCode> {
    if let Some(map) = args
        .nav2_map
        .as_ref()
        .filter(|m| !navdeck::session::is_nav2_map(m))
    {
        anyhow::bail!(
            "--nav2-map {}: a Nav2 map's file name ends in .yaml",
            map.display()
        );
    }
    let options = args.shape.options(args.seed);
    if options.style == Style::Track {
        let flags = [
            (args.shape.blocks.is_some(), "--blocks"),
            (args.shape.obstacles.is_some(), "--obstacles"),
        ];
        if let Some((_, flag)) = flags.into_iter().find(|(given, _)| *given) {
            anyhow::bail!("{flag}: track worlds have no blocks and no boxes");
        }
    }
    let world = generate::generate(&options).map_err(generate_error)?;
    let text = format!(
        "# {}\n# The format is described at the top of maps/arena.toml.\n{}",
        options.command(),
        world.to_toml()
    );
    let out = &args.output;
    let kept = std::fs::symlink_metadata(out).is_ok();
    // As a map save: atomically, never through a link planted at the name, the file
    // replaced kept as .bak.
    navdeck::data::replace::replace_file(out, text.into_bytes()).map_err(|(_, e)| {
        anyhow::anyhow!(
            "cannot write {}: {}",
            out.display(),
            navdeck::map::io::io_reason(&e)
        )
    })?;
    let backup = if kept {
        format!(" (the file it replaced kept as {}.bak)", out.display())
    } else {
        String::new()
    };
    sayln!(
        "wrote {}{backup}: {}",
        out.display(),
        generate::describe(&world)
    );
    if let Some(map) = &args.nav2_map {
        let file = navdeck::map::io::MapFile {
            grid: world.rasterize(TRUE_MAP_RESOLUTION),
            extras: None,
        };
        navdeck::map::io::save(map, &file).map_err(|e| anyhow::anyhow!("{e}"))?;
        sayln!("wrote the world's true map as {}", map.display());
    }
    Ok(ExitCode::SUCCESS)
}
