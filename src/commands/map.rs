//! `navdeck map`: look at a saved map.

use anyhow::{Result, bail};
use navdeck::map::io as map_io;
use navdeck::runners::map_report;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Debug, clap::Subcommand)]
pub(crate) enum MapCommand {
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
        #[arg(long, default_value_t = 80, value_name = "N", value_parser = super::args::whole::<usize>)]
        width: usize,
    },
}

pub(crate) fn run(command: &MapCommand) -> Result<ExitCode> {
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
