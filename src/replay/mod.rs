//! `navdeck replay`: a recording played back. The console is re-run on it: today's
//! estimator and planner get the recorded sensor data and the recorded keys at their
//! recorded times, through a link that hands back the recorded frames. What was believed
//! at the time stays at hand (`recorded()`) for the as-recorded view and to compare.

pub mod playback;
pub mod screen;

use crate::app::{App, KeyKind};
use crate::config::Config;
use crate::geometry::{Pose2, wrap_angle};
use crate::keymap::{Key, Keymap};
use crate::link::replay::ReplayLink;
use crate::msgs::picture;
use crate::msgs::record::{INPUT_KEY, INPUT_RESIZE, INPUT_UPDATE, InputMsg};
use crate::pilot::localize::{InitialPose, Localizer};
use crate::record::encode;
use crate::record::recorded::Recorded;
use crate::sim::World;
use crate::slam::mcl::config::Estimator;
use anyhow::{Context, Result, bail};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What the command line changes for a re-run.
#[derive(Clone, Debug, Default)]
pub struct ReplayOptions {
    /// A config instead of the recorded one.
    pub config: Option<PathBuf>,
    pub estimator: Option<Estimator>,
    /// MCL's map (default: the recorded session's, if the file is still there).
    pub map: Option<PathBuf>,
    pub initial_pose: Option<InitialPose>,
}

/// A recording read from a file: what could be read, and what could not.
pub fn load(path: &Path) -> Result<Recorded> {
    let bytes = crate::data::files::read_limited(path, MAX_FILE)
        .with_context(|| format!("cannot read the recording {}", path.display()))?;
    let recorded = Recorded::decode(crate::record::reader::read(&bytes));
    if recorded.inputs.is_empty() && recorded.frames.is_empty() {
        let why = recorded.problems.first().cloned().unwrap_or_else(|| {
            format!(
                "no navdeck session in it ({} messages of other tools)",
                recorded.foreign
            )
        });
        bail!("{}: nothing to replay: {why}", path.display());
    }
    if recorded.inputs.is_empty() {
        // A re-run is driven by the recorded calls into the console: without one, it
        // would end at once having replayed nothing.
        let why = recorded
            .problems
            .first()
            .map_or(String::new(), |p| format!(" ({p})"));
        bail!(
            "{}: nothing to replay: no recorded inputs (the console's keys and ticks), {} frames{why}",
            path.display(),
            recorded.frames.len()
        );
    }
    Ok(recorded)
}

/// Recordings larger than this are refused (they are read whole), bytes.
pub const MAX_FILE: u64 = 2 << 30;

/// How a re-run compares with the recording, so far.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Comparison {
    /// Control ticks compared, and those whose estimate (pose and covariance) is the
    /// recorded one bit for bit.
    pub ticks: usize,
    pub identical: usize,
    /// The largest distance between the re-run's position and the recorded one, metres.
    pub max_position_difference: f64,
    /// Both estimates against the recorded truth (a twin's): RMSE in metres and degrees.
    pub recorded_position_rmse: Option<f64>,
    pub recorded_heading_rmse_deg: Option<f64>,
    pub rerun_position_rmse: Option<f64>,
    pub rerun_heading_rmse_deg: Option<f64>,
    /// The estimator each used.
    pub recorded_estimator: String,
    pub rerun_estimator: String,
}

#[derive(Clone, Debug, Default)]
struct Errors {
    n: usize,
    recorded: (f64, f64),
    rerun: (f64, f64),
}

/// A re-run in progress.
pub struct Replay {
    recorded: Arc<Recorded>,
    options: ReplayOptions,
    app: App,
    next_input: usize,
    next_estimate: usize,
    /// The terminal's size when a console shows the re-run (the recorded sizes are not
    /// applied then); None applies them (headless).
    screen: Option<(u16, u16)>,
    comparison: Comparison,
    errors: Errors,
}

impl Replay {
    /// Sets up a re-run of `recorded` from its start.
    pub fn new(recorded: Arc<Recorded>, options: ReplayOptions) -> Result<Replay> {
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
            Some(text) => Keymap::parse_overlay(text, Path::new("keymap (recorded)"))
                .unwrap_or_else(|e| {
                    notes.push(format!("recorded keymap not used: {e}"));
                    Keymap::default_map()
                }),
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
            Estimator::Mcl => Some(localizer(
                session,
                &options,
                first_truth,
                seed,
                &config.map,
            )?),
            Estimator::Slam => continued(session, &options, first_truth, &config)?,
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
        Ok(Replay {
            comparison: Comparison {
                recorded_estimator,
                rerun_estimator,
                ..Comparison::default()
            },
            recorded,
            options,
            app,
            next_input: 0,
            next_estimate: 0,
            screen: None,
            errors: Errors::default(),
        })
    }

    /// The console's terminal size: from now on the recorded sizes are not applied.
    pub fn show_on_screen(&mut self, width: u16, height: u16) {
        self.screen = Some((width, height));
        self.app.resize(width, height);
    }

    pub fn app(&self) -> &App {
        &self.app
    }

    pub fn app_mut(&mut self) -> &mut App {
        &mut self.app
    }

    pub fn recorded(&self) -> &Recorded {
        &self.recorded
    }

    /// Session time of the first and the last thing recorded.
    pub fn span(&self) -> (f64, f64) {
        let start = self.recorded.start();
        (start, self.recorded.end().max(start))
    }

    /// Session time the re-run has reached.
    pub fn position(&self) -> f64 {
        match self.next_input.checked_sub(1) {
            Some(i) => self.recorded.inputs[i].time,
            None => self.span().0,
        }
    }

    pub fn at_end(&self) -> bool {
        self.next_input >= self.recorded.inputs.len()
    }

    /// Makes every recorded call up to session time `t`, in order.
    pub fn run_to(&mut self, t: f64) {
        while let Some(input) = self.recorded.inputs.get(self.next_input) {
            if input.time > t + 1e-9 {
                break;
            }
            let input = input.clone();
            self.next_input += 1;
            self.apply(&input);
            self.compare();
        }
    }

    /// Back to the start (a seek backwards re-runs from there).
    pub fn restart(&mut self) -> Result<()> {
        let screen = self.screen;
        *self = Replay::new(self.recorded.clone(), self.options.clone())?;
        if let Some((w, h)) = screen {
            self.show_on_screen(w, h);
        }
        Ok(())
    }

    /// Goes to session time `t`, forwards or (re-running from the start) backwards.
    pub fn seek(&mut self, t: f64) -> Result<()> {
        if t + 1e-9 < self.position() {
            self.restart()?;
        }
        self.run_to(t);
        Ok(())
    }

    fn apply(&mut self, input: &InputMsg) {
        match input.kind {
            INPUT_UPDATE => self.app.update(input.time),
            INPUT_KEY => {
                let kind = match input.key_event {
                    1 => KeyKind::Repeat,
                    2 => KeyKind::Release,
                    _ => KeyKind::Press,
                };
                match input.key.parse::<Key>() {
                    Ok(key) => self.app.handle_key(key, kind, input.time),
                    Err(e) => self
                        .app
                        .warn(format!("recorded key {:?} not replayed: {e}", input.key)),
                }
            }
            INPUT_RESIZE if self.screen.is_none() => self.app.resize(input.width, input.height),
            _ => {}
        }
    }

    /// Compares the ticks the re-run has made with the recorded ones.
    fn compare(&mut self) {
        for (t, pose, cov) in self.app.take_tick_estimates() {
            let Some(recorded) = self.recorded.estimates.get(self.next_estimate) else {
                continue;
            };
            if (recorded.time - t).abs() > 1e-6 {
                continue;
            }
            self.next_estimate += 1;
            let c = &mut self.comparison;
            c.ticks += 1;
            let mine = encode(&picture::pose_with_covariance(
                pose,
                &cov,
                recorded.stamp,
                "map",
            ));
            if mine == recorded.bytes {
                c.identical += 1;
            }
            let gap = pose.position().distance(recorded.pose.position());
            c.max_position_difference = c.max_position_difference.max(gap);
            if let Some(truth) = self.recorded.truth_at(t) {
                let truth = truth.pose();
                let e = &mut self.errors;
                e.n += 1;
                add_error(&mut e.recorded, recorded.pose, truth);
                add_error(&mut e.rerun, pose, truth);
            }
        }
    }

    /// How the re-run compares so far.
    pub fn comparison(&self) -> Comparison {
        let mut c = self.comparison.clone();
        let e = &self.errors;
        if e.n > 0 {
            let n = e.n as f64;
            c.recorded_position_rmse = Some((e.recorded.0 / n).sqrt());
            c.recorded_heading_rmse_deg = Some((e.recorded.1 / n).sqrt().to_degrees());
            c.rerun_position_rmse = Some((e.rerun.0 / n).sqrt());
            c.rerun_heading_rmse_deg = Some((e.rerun.1 / n).sqrt().to_degrees());
        }
        c
    }
}

/// Adds the squared position and heading errors of `estimate` against `truth`.
fn add_error(sums: &mut (f64, f64), estimate: Pose2, truth: Pose2) {
    sums.0 += estimate.position().distance(truth.position()).powi(2);
    sums.1 += wrap_angle(estimate.theta - truth.theta).powi(2);
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
