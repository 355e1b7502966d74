//! Helpers shared by the integration tests: scripted console sessions and a recording link.
#![allow(dead_code)]

use navdeck::app::App;
use navdeck::config::Config;
use navdeck::data::{Command, SensorFrame};
use navdeck::keymap::{Key, Keymap};
use navdeck::link::{LinkError, RobotLink};
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::tui::events::{Event, ManualClock, ScriptedEvents, Step};
use navdeck::tui::run::{Exit, RunStats, run};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, Mutex};

/// Runs the navdeck binary with `args`, without colour, and waits for it.
pub fn navdeck(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("navdeck runs")
}

/// The default session: the built-in arena, seed 1.
pub fn default_app() -> App {
    app_with(SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    })
}

pub fn app_with(spec: SessionSpec) -> App {
    Session::load(&spec).expect("session loads").into_app(0.0)
}

/// A scripted session's outcome.
pub struct Scripted {
    pub terminal: Terminal<TestBackend>,
    pub app: App,
    pub exit: Exit,
    pub stats: RunStats,
    pub clock: ManualClock,
}

/// Runs `app` in a `width` x `height` test terminal through `steps`, without colour.
pub fn run_script(app: App, width: u16, height: u16, steps: Vec<Step>) -> Scripted {
    run_script_with_signal(app, width, height, steps, &AtomicUsize::new(0))
}

pub fn run_script_with_signal(
    mut app: App,
    width: u16,
    height: u16,
    steps: Vec<Step>,
    signal: &AtomicUsize,
) -> Scripted {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let clock = ManualClock::default();
    let mut events = ScriptedEvents::new(clock.clone(), steps);
    let mut stats = RunStats::default();
    let exit = run(
        &mut terminal,
        &mut app,
        &mut events,
        &clock,
        signal,
        Theme { color: false },
        &mut stats,
    )
    .expect("the loop runs");
    Scripted {
        terminal,
        app,
        exit,
        stats,
        clock,
    }
}

/// Runs the console loop on any backend and event source, with no signal and no colour.
pub fn run_loop<B: ratatui::backend::Backend>(
    terminal: &mut Terminal<B>,
    app: &mut App,
    events: &mut dyn navdeck::tui::events::EventSource,
    clock: &ManualClock,
) -> (Result<Exit, navdeck::tui::run::RunError>, RunStats) {
    let mut stats = RunStats::default();
    let out = run(
        terminal,
        app,
        events,
        clock,
        &AtomicUsize::new(0),
        Theme { color: false },
        &mut stats,
    );
    (out, stats)
}

/// A key press step.
pub fn press(c: char) -> Step {
    Step::Event(Event::Key(Key::char(c), navdeck::app::KeyKind::Press))
}

pub fn key(name: &str) -> Key {
    name.parse().expect("key name")
}

/// Holds `c` for `seconds` as a terminal without release events does: a press, then
/// auto-repeats every 1/30 s.
pub fn hold(c: char, seconds: f64) -> Vec<Step> {
    let n = (seconds * 30.0).round() as usize;
    (0..n)
        .flat_map(|_| [press(c), Step::Wait(1.0 / 30.0)])
        .collect()
}

/// The screen as text, one line per row.
pub fn screen(terminal: &Terminal<TestBackend>) -> String {
    let buf = terminal.backend().buffer();
    let mut out = String::new();
    for y in 0..buf.area.height {
        for x in 0..buf.area.width {
            out.push_str(buf[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// The console drawn once on a 100x30 test terminal, as text.
pub fn render(app: &App) -> String {
    render_at(app, 100, 30)
}

/// The console drawn once on a `width` x `height` test terminal, as text.
pub fn render_at(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|frame| {
            navdeck::tui::draw::draw(frame, app, navdeck::tui::theme::Theme::from_env(None))
        })
        .unwrap();
    screen(&terminal)
}

/// A link that records what it was asked, for checking the console's side of the contract.
#[derive(Clone, Default)]
pub struct RecordingLink {
    pub sent: Arc<Mutex<Vec<Command>>>,
    pub stops: Arc<Mutex<usize>>,
}

impl RobotLink for RecordingLink {
    fn label(&self) -> String {
        "recording".into()
    }
    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.sent.lock().unwrap().push(*command);
        Ok(())
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        Ok(SensorFrame {
            stamp: now,
            ..SensorFrame::default()
        })
    }
    fn stop(&mut self) {
        *self.stops.lock().unwrap() += 1;
    }
}

/// A console on a recording link with the default keymap.
pub fn recording_app() -> (App, RecordingLink) {
    let link = RecordingLink::default();
    let app = App::new(
        Config::default(),
        Keymap::default_map(),
        Box::new(link.clone()),
        0.0,
    );
    (app, link)
}
