//! `navdeck replay`: a recording played back. The console is re-run on it: today's
//! estimator and planner get the recorded sensor data and the recorded keys at their
//! recorded times, through a link that hands back the recorded frames. What was believed
//! at the time stays at hand (`recorded()`) for the as-recorded view and to compare.

pub mod compare;
pub mod fleet;
pub mod playback;
mod rerun_app;
pub mod screen;

use crate::app::{App, KeyKind};
use crate::keymap::Key;
use crate::msgs::record::{INPUT_KEY, INPUT_RESIZE, INPUT_UPDATE, InputMsg};
use crate::pilot::localize::InitialPose;
use crate::record::recorded::Recorded;
use crate::slam::mcl::config::Estimator;
use anyhow::{Result, bail};
use compare::Comparer;
pub use compare::Comparison;
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

/// A recording read from a file: what could be read, and what could not. A fleet's
/// recording is refused here (`fleet::open` reads both kinds).
pub fn load(path: &Path) -> Result<Recorded> {
    match fleet::open(path)? {
        fleet::Opened::One(recorded) => Ok(recorded),
        fleet::Opened::Fleet(f) => bail!(
            "{}: a fleet's recording ({} robots): navdeck replay plays it as a fleet",
            path.display(),
            f.robots.len()
        ),
    }
}

/// `recorded`, read from `path`, when it has something to replay.
fn checked(path: &Path, recorded: Recorded) -> Result<Recorded> {
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

/// A re-run in progress.
pub struct Replay {
    recorded: Arc<Recorded>,
    options: ReplayOptions,
    app: App,
    next_input: usize,
    /// The terminal's size when a console shows the re-run (the recorded sizes are not
    /// applied then); None applies them (headless).
    screen: Option<(u16, u16)>,
    comparer: Comparer,
}

impl Replay {
    /// Sets up a re-run of `recorded` from its start.
    pub fn new(recorded: Arc<Recorded>, options: ReplayOptions) -> Result<Replay> {
        let (app, comparer) = rerun_app::rerun_app(&recorded, &options)?;
        Ok(Replay {
            recorded,
            options,
            app,
            next_input: 0,
            screen: None,
            comparer,
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
            apply(&mut self.app, &input, self.screen.is_none());
            self.comparer.take(&mut self.app, &self.recorded);
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

    /// How the re-run compares so far.
    pub fn comparison(&self) -> Comparison {
        self.comparer.comparison()
    }
}

/// Makes one recorded call into `app`: a tick, a key, or (`sizes`: no terminal shows
/// the re-run) a terminal size.
pub(crate) fn apply(app: &mut App, input: &InputMsg, sizes: bool) {
    match input.kind {
        INPUT_UPDATE => app.update(input.time),
        INPUT_KEY => match input.key.parse::<Key>() {
            Ok(key) => app.handle_key(key, key_kind(input.key_event), input.time),
            Err(e) => app.warn(format!("recorded key {:?} not replayed: {e}", input.key)),
        },
        INPUT_RESIZE if sizes => app.resize(input.width, input.height),
        _ => {}
    }
}

/// A recorded key event's kind.
pub(crate) fn key_kind(event: u8) -> KeyKind {
    match event {
        1 => KeyKind::Repeat,
        2 => KeyKind::Release,
        _ => KeyKind::Press,
    }
}
