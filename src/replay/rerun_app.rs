//! The console a re-run makes its calls into: the recorded config, keymap and world (or
//! the command line's), a link on the recorded frames, and the estimator the session
//! localised with (MCL on its map, lidar SLAM continuing a saved map).

use super::ReplayOptions;
use super::compare::Comparer;
use crate::app::App;
use crate::config::Config;
use crate::geometry::Pose2;
use crate::keymap::Keymap;
use crate::link::replay::ReplayLink;
use crate::pilot::localize::{InitialPose, Localizer};
use crate::record::recorded::Recorded;
use crate::sim::World;
use crate::slam::mcl::config::Estimator;
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};

/// The console a re-run of `recorded` makes its calls into, at its start, on a link
/// that hands back the recorded frames; and its comparison with the recording.
pub fn rerun_app(recorded: &Recorded, options: &ReplayOptions) -> Result<(App, Comparer)> {
    let mut notes = Vec::new();
    let session = &recorded.session;
    let mut config = match (&options.config, recorded.attachment_text("config.toml")) {
        (Some(path), _) => Config::load(path)?,
        (None, Some(text)) => match Config::parse(text, Path::new("config.toml (recorded)")) {
            Ok(c) => c,
            Err(e) => {
                notes.push(format!("recorded config not used: {e}"));
                Config::default()
            }
        },
        (None, None) => Config::default(),
    };
    let recorded_estimator = estimator_name(config.localization.estimator);
    if let Some(e) = options.estimator {
        config.localization.estimator = e;
    }
    let keymap = match session.get("keymap_text") {
        Some(text) => {
            Keymap::parse_overlay(text, Path::new("keymap (recorded)")).unwrap_or_else(|e| {
                notes.push(format!("recorded keymap not used: {e}"));
                Keymap::default_map()
            })
        }
        None => Keymap::default_map(),
    };
    let world = match recorded.attachment_text("world.toml") {
        Some(text) => match World::from_toml(text, Path::new("world.toml (recorded)")) {
            Ok(w) => Some(w),
            Err(e) => {
                notes.push(format!("recorded world not used: {e}"));
                None
            }
        },
        None => None,
    };
    let label = format!(
        "replay:{}",
        session.get("link").map_or("robot", String::as_str)
    );
    let link = ReplayLink::new(
        label,
        recorded.frames.clone(),
        recorded.truths.clone(),
        world,
    );
    let start = recorded.start();
    let seed = session
        .get("seed")
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let first_truth = recorded.truths.first().map(|t| t.pose());
    let rerun_estimator = estimator_name(config.localization.estimator);
    let localizer = match config.localization.estimator {
        Estimator::Mcl => Some(localizer(session, options, first_truth, seed, &config.map)?),
        Estimator::Slam => continued(session, options, first_truth, &config)?,
        Estimator::Ekf => None,
    };
    let mut app = App::new(config, keymap, Box::new(link), start);
    if let Some(localizer) = &localizer {
        app.localize(localizer);
    }
    // What could not be read or used goes in the log, and comes back with every
    // restart (a seek backwards).
    for problem in &recorded.problems {
        app.warn(format!("recording: {problem}"));
    }
    for note in notes {
        app.warn(note);
    }
    app.watch_estimates();
    Ok((app, Comparer::new(recorded_estimator, rerun_estimator)))
}

fn estimator_name(e: Estimator) -> String {
    e.label().to_string()
}

/// MCL's map and start for a re-run: the command line's, else the recorded session's.
fn localizer(
    session: &std::collections::BTreeMap<String, String>,
    options: &ReplayOptions,
    first_truth: Option<Pose2>,
    seed: u64,
    map_config: &crate::map::config::MapConfig,
) -> Result<Localizer> {
    let recorded_map = session.get("map").map(PathBuf::from).or_else(|| {
        session
            .get("world")
            .map(PathBuf::from)
            .filter(|w| crate::session::is_nav2_map(w))
    });
    let path = match (options.map.clone(), recorded_map) {
        (Some(given), _) => given,
        (None, Some(recorded)) => {
            recorded_reference(&recorded)?;
            recorded
        }
        (None, None) => {
            bail!("re-running with MCL needs the map it localises on: --map FILE.yaml (a Nav2 map)")
        }
    };
    let map = crate::map::io::load(&path).map_err(|e| {
        anyhow::anyhow!(
            "cannot read the map {} for MCL: {}",
            path.display(),
            e.reason()
        )
    })?;
    let recorded_initial = session
        .get("initial_pose")
        .and_then(|s| s.parse::<InitialPose>().ok());
    let initial = options
        .initial_pose
        .or(recorded_initial)
        .or(first_truth.map(InitialPose::At))
        .unwrap_or(InitialPose::Unknown);
    Localizer::new(
        map.grid,
        initial,
        seed,
        path.display().to_string(),
        map_config,
    )
    .map_err(anyhow::Error::msg)
}

/// For a re-run with lidar SLAM of a session that continued a saved map: the map and
/// its pose graph (the command line's `--map`, else the recorded one), from the same
/// start; None for a session that mapped from nothing.
fn continued(
    session: &std::collections::BTreeMap<String, String>,
    options: &ReplayOptions,
    first_truth: Option<Pose2>,
    config: &Config,
) -> Result<Option<Localizer>> {
    let path = match (options.map.clone(), session.get("map").map(PathBuf::from)) {
        (Some(given), _) => given,
        (None, Some(recorded)) => {
            recorded_reference(&recorded)?;
            recorded
        }
        (None, None) => return Ok(None),
    };
    let recorded_initial = session
        .get("initial_pose")
        .and_then(|s| s.parse::<InitialPose>().ok());
    let initial = (options.initial_pose.or(recorded_initial))
        .or(first_truth.map(InitialPose::At))
        .unwrap_or(InitialPose::Unknown);
    crate::session::continuing(&path, initial, config).map(Some)
}

/// A map a recording names is read only as the relative path the recorder wrote, inside
/// the folder the replay runs in: a recording is a file from anywhere, and its metadata
/// must not point navdeck at `/etc/passwd` or `../../secret`.
fn recorded_reference(path: &Path) -> Result<()> {
    use std::path::Component;
    let inside = path
        .components()
        .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if inside && !path.as_os_str().is_empty() {
        return Ok(());
    }
    bail!(
        "the recording's map {} is not read: a recording may name its map only by a path \
         inside the current folder (no absolute path, no `..`); give the map with --map FILE.yaml",
        path.display()
    )
}
