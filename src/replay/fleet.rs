//! A fleet's recording played back: every robot re-run through its own console on its
//! own stream (its frames, its config, its world), all of them in one fleet driven by the
//! fleet's recorded calls, so that the selection, stop-all and the twins' giving way
//! happen as they did. A robot whose stream is damaged or cut short is named; the others
//! play on.

use super::compare::{Comparer, Comparison};
use super::{ReplayOptions, key_kind};
use crate::app::App;
use crate::fleet::{Fleet, Member};
use crate::keymap::Key;
use crate::msgs::record::{INPUT_KEY, INPUT_RESIZE, INPUT_UPDATE, InputMsg};
use crate::record::fleet::{fleet_of, split};
use crate::record::reader::RawRecording;
use crate::record::recorded::Recorded;
use crate::session::fleet::MAX_ROBOTS;
use crate::tui::deck::Deck;
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::sync::Arc;

/// One robot's stream of a fleet's recording.
#[derive(Clone, Debug)]
pub struct RobotRecorded {
    pub name: String,
    /// The namespace its topics sit under, e.g. `/robot1`.
    pub namespace: String,
    pub recorded: Arc<Recorded>,
    /// Why its stream cannot be replayed whole, if it cannot.
    pub broken: Option<String>,
}

/// A fleet's recording decoded: the fleet's own calls and each robot's stream.
#[derive(Clone, Debug)]
pub struct FleetRecorded {
    /// The fleet's calls (its inputs), how it was started, the file's damage.
    pub fleet: Recorded,
    pub robots: Vec<RobotRecorded>,
}

impl FleetRecorded {
    /// Decodes a fleet's file, read as `raw`, of `robots` (name, namespace); `path`
    /// names it in errors. Fails only when the fleet's own calls cannot be read.
    pub fn decode(path: &Path, raw: RawRecording, robots: &[(String, String)]) -> Result<Self> {
        let parts = split(raw, robots);
        let fleet = Recorded::decode(parts.fleet);
        if fleet.inputs.is_empty() {
            let why = fleet
                .problems
                .first()
                .map_or(String::new(), |p| format!(" ({p})"));
            bail!(
                "{}: nothing to replay: a fleet's recording without the fleet's calls on {}{why}",
                path.display(),
                crate::record::fleet::FLEET_INPUT
            );
        }
        let last_tick = (fleet.inputs.iter().rev())
            .find(|i| i.kind == INPUT_UPDATE)
            .map_or(fleet.start(), |i| i.time);
        let robots = (parts.robots.into_iter())
            .map(|(name, namespace, raw)| {
                let recorded = Recorded::decode(raw);
                let broken = broken(&namespace, &recorded, last_tick);
                RobotRecorded {
                    name,
                    namespace,
                    recorded: Arc::new(recorded),
                    broken,
                }
            })
            .collect();
        Ok(FleetRecorded { fleet, robots })
    }

    /// Session time of the first and the last call into the fleet.
    pub fn span(&self) -> (f64, f64) {
        let start = self.fleet.start();
        (start, self.fleet.end().max(start))
    }

    /// The robots whose streams cannot be replayed whole: "name (namespace): why".
    pub fn broken(&self) -> Vec<String> {
        (self.robots.iter())
            .filter_map(|r| {
                let why = r.broken.as_ref()?;
                Some(format!("robot {} ({}): {why}", r.name, r.namespace))
            })
            .collect()
    }
}

/// Why a robot's stream cannot be replayed whole: nothing in it, messages that could
/// not be read, or its calls ending before the fleet's last tick (`last_tick`).
fn broken(namespace: &str, recorded: &Recorded, last_tick: f64) -> Option<String> {
    if recorded.inputs.is_empty() && recorded.frames.is_empty() {
        return Some(format!(
            "nothing recorded on {namespace}/navdeck/input or {namespace}/navdeck/frame"
        ));
    }
    if let Some(problem) = recorded.problems.first() {
        return Some(format!("{namespace}: {problem}"));
    }
    let ends = recorded.inputs.last().map_or(0.0, |i| i.time);
    (ends + 1e-6 < last_tick).then(|| {
        format!(
            "its stream ({namespace}/navdeck/input) ends at {ends:.3} s, the fleet's at {last_tick:.3} s (cut short?)"
        )
    })
}

/// What `navdeck replay` opens: one robot's recording or a fleet's.
pub enum Opened {
    One(Recorded),
    Fleet(FleetRecorded),
}

/// A recording read from a file, a fleet's or one robot's.
pub fn open(path: &Path) -> Result<Opened> {
    let bytes = crate::data::files::read_limited(path, super::MAX_FILE)
        .with_context(|| format!("cannot read the recording {}", path.display()))?;
    let raw = crate::record::reader::read(&bytes);
    match fleet_of(&raw) {
        None => super::checked(path, Recorded::decode(raw)).map(Opened::One),
        Some(Err(why)) => bail!(
            "{}: not a fleet's recording navdeck reads: {why}",
            path.display()
        ),
        Some(Ok(robots)) if robots.len() > MAX_ROBOTS => bail!(
            "{}: a fleet's recording of {} robots: a console takes at most {MAX_ROBOTS}",
            path.display(),
            robots.len()
        ),
        Some(Ok(robots)) => FleetRecorded::decode(path, raw, &robots).map(Opened::Fleet),
    }
}

/// A fleet's re-run in progress.
pub struct FleetReplay {
    recorded: Arc<FleetRecorded>,
    options: ReplayOptions,
    fleet: Fleet,
    /// Each robot's comparison with its stream, in the fleet's order.
    comparers: Vec<Comparer>,
    next_input: usize,
    /// The terminal's size when a console shows the re-run; None applies the recorded
    /// sizes (headless).
    screen: Option<(u16, u16)>,
    /// The robot the console shows, when the user chose one (`ctrl-n`, `ctrl-p`);
    /// None follows the robot selected in the recording.
    shown: Option<usize>,
}

impl FleetReplay {
    /// Sets up a re-run of the fleet from its start.
    pub fn new(recorded: Arc<FleetRecorded>, options: ReplayOptions) -> Result<FleetReplay> {
        let mut members = Vec::with_capacity(recorded.robots.len());
        let mut comparers = Vec::with_capacity(recorded.robots.len());
        for robot in &recorded.robots {
            let (mut app, comparer) = super::rerun_app::rerun_app(&robot.recorded, &options)
                .with_context(|| format!("robot {} ({})", robot.name, robot.namespace))?;
            if let Some(why) = &robot.broken {
                app.warn(format!("recording: robot {}: {why}", robot.name));
            }
            members.push(Member {
                name: robot.name.clone(),
                app,
            });
            comparers.push(comparer);
        }
        if members.is_empty() {
            bail!("a fleet's recording with no robots in it");
        }
        let mut fleet = Fleet::new(members);
        for problem in &recorded.fleet.problems {
            fleet.members_mut()[0]
                .app
                .warn(format!("recording: {problem}"));
        }
        Ok(FleetReplay {
            recorded,
            options,
            fleet,
            comparers,
            next_input: 0,
            screen: None,
            shown: None,
        })
    }

    /// The console's terminal size: from now on the recorded sizes are not applied.
    pub fn show_on_screen(&mut self, width: u16, height: u16) {
        self.screen = Some((width, height));
        self.fleet.resize(width, height);
    }

    pub fn fleet(&self) -> &Fleet {
        &self.fleet
    }

    pub fn fleet_mut(&mut self) -> &mut Fleet {
        &mut self.fleet
    }

    pub fn recorded(&self) -> &FleetRecorded {
        &self.recorded
    }

    /// The robot the console shows: the one chosen, else the one selected as recorded.
    pub fn shown(&self) -> usize {
        self.shown.unwrap_or(self.fleet.selected())
    }

    /// Shows the robot `by` places after (or before) the one shown; the recording's
    /// selection is left as it was.
    pub fn show_next(&mut self, by: i8) {
        let n = self.recorded.robots.len() as i64;
        let next = (self.shown() as i64 + i64::from(by)).rem_euclid(n);
        self.shown = Some(next as usize);
    }

    /// The shown robot's console and stream.
    pub fn app(&self) -> &App {
        &self.fleet.members()[self.shown()].app
    }

    pub fn app_mut(&mut self) -> &mut App {
        let shown = self.shown();
        &mut self.fleet.members_mut()[shown].app
    }

    pub fn shown_recorded(&self) -> &Recorded {
        &self.recorded.robots[self.shown()].recorded
    }

    pub fn span(&self) -> (f64, f64) {
        self.recorded.span()
    }

    /// Session time the re-run has reached.
    pub fn position(&self) -> f64 {
        match self.next_input.checked_sub(1) {
            Some(i) => self.recorded.fleet.inputs[i].time,
            None => self.span().0,
        }
    }

    pub fn at_end(&self) -> bool {
        self.next_input >= self.recorded.fleet.inputs.len()
    }

    /// Makes every recorded call into the fleet up to session time `t`, in order.
    pub fn run_to(&mut self, t: f64) {
        while let Some(input) = self.recorded.fleet.inputs.get(self.next_input) {
            if input.time > t + 1e-9 {
                break;
            }
            let input = input.clone();
            self.next_input += 1;
            self.apply(&input);
            let members = self.fleet.members_mut().iter_mut();
            for ((m, comparer), robot) in
                members.zip(&mut self.comparers).zip(&self.recorded.robots)
            {
                comparer.take(&mut m.app, &robot.recorded);
            }
        }
    }

    fn apply(&mut self, input: &InputMsg) {
        match input.kind {
            INPUT_UPDATE => self.fleet.update(input.time),
            INPUT_KEY => match input.key.parse::<Key>() {
                Ok(key) => self
                    .fleet
                    .handle_key(key, key_kind(input.key_event), input.time),
                Err(e) => {
                    let text = format!("recorded key {:?} not replayed: {e}", input.key);
                    let selected = self.fleet.selected();
                    self.fleet.members_mut()[selected].app.warn(text);
                }
            },
            INPUT_RESIZE if self.screen.is_none() => self.fleet.resize(input.width, input.height),
            _ => {}
        }
    }

    /// Back to the start (a seek backwards re-runs from there).
    pub fn restart(&mut self) -> Result<()> {
        let (screen, shown) = (self.screen, self.shown);
        *self = FleetReplay::new(self.recorded.clone(), self.options.clone())?;
        self.shown = shown;
        if let Some((w, h)) = screen {
            self.show_on_screen(w, h);
        }
        Ok(())
    }

    /// Each robot's comparison with its stream so far, in the fleet's order.
    pub fn comparisons(&self) -> Vec<Comparison> {
        self.comparers.iter().map(Comparer::comparison).collect()
    }
}
