//! The console on a real terminal: signals watched, the terminal entered, the main loop
//! run on the wall clock, and on the way out the robot stopped, the terminal restored
//! and the link closed within a deadline.

use crate::app::App;
use crate::clock::Clock;
use crate::session::Session;
use crate::tui::events::WallClock;
use crate::tui::input::TtyEvents;
use crate::tui::run::{Exit, RunError, RunStats, run};
use crate::tui::signals::{Signals, signal_name};
use crate::tui::terminal::TerminalGuard;
use crate::tui::theme::Theme;
use anyhow::{Context, Result};
use std::cell::RefCell;
use std::io::Write;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;

/// How long the console may take to end once the robot has been told to stop: restoring
/// the terminal and closing the link must fit in it, whatever they wait on.
const EXIT_DEADLINE: std::time::Duration = std::time::Duration::from_millis(800);

/// The exit deadline: `NAVDECK_EXIT_DEADLINE_MS` (tests lengthen it to tell an immediate
/// exit from the deadline's), else `EXIT_DEADLINE`.
pub fn exit_deadline() -> std::time::Duration {
    std::env::var("NAVDECK_EXIT_DEADLINE_MS")
        .ok()
        .and_then(|ms| ms.trim().parse::<u64>().ok())
        .map_or(EXIT_DEADLINE, std::time::Duration::from_millis)
}

/// What the console takes from the command line.
#[derive(Clone)]
pub struct ConsoleOptions {
    /// Where maps are saved; `maps` when not given.
    pub maps_dir: Option<PathBuf>,
    /// Where the session's log file goes; `logs` when not given.
    pub log_dir: Option<PathBuf>,
    /// Start with the braille map.
    pub braille: bool,
    /// Record the session to this MCAP file, with this metadata.
    pub record: Option<(PathBuf, std::collections::BTreeMap<String, String>)>,
}

/// Starts recording `app`'s session into `path` (which must not exist), stamped with the
/// wall clock; `session` says how it was started. `simulated`: the session runs on
/// simulated time, so the loop may wait for the writer rather than drop a message.
pub fn start_recording(
    app: &mut App,
    path: &std::path::Path,
    session: std::collections::BTreeMap<String, String>,
    simulated: bool,
) -> Result<()> {
    let epoch = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
        - app.now();
    let mut recorder = crate::record::Recorder::create(path, &app.config().record, epoch)?;
    recorder.wait_when_full(simulated);
    app.record_to(recorder, session);
    Ok(())
}

/// `dir/navdeck-STAMP-PID.mcap`: where `[record] folder` puts a session's recording.
pub fn dated_recording(dir: &std::path::Path) -> PathBuf {
    dated_file(dir, "", "mcap")
}

/// `dir/navdeck-STAMP-PIDSUFFIX.EXT`: STAMP the start time in UTC, RFC 3339 with the `:` left
/// out so the name works everywhere; the process ID keeps two consoles started in the
/// same second apart.
fn dated_file(dir: &std::path::Path, suffix: &str, ext: &str) -> PathBuf {
    let stamp = humantime::format_rfc3339_seconds(std::time::SystemTime::now())
        .to_string()
        .replace(':', "");
    dir.join(format!(
        "navdeck-{stamp}-{}{suffix}.{ext}",
        std::process::id()
    ))
}

/// Plays a recording on the real terminal until quit, a signal or a hang-up; opens on
/// the view as recorded (`as_recorded`) or the re-run. Returns the exit status.
pub fn run_replay_console<R: crate::replay::screen::played::Played>(
    replay: R,
    speed: f64,
    as_recorded: bool,
) -> Result<u8> {
    use crate::replay::playback::{Playback, View};
    let signals = Signals::watch().context("cannot watch signals")?;
    let theme = Theme::from_env(std::env::var_os("NO_COLOR"));
    let clock = WallClock::start();
    let view = if as_recorded {
        View::AsRecorded
    } else {
        View::Rerun
    };
    let step = replay.app().config().robot.control_period;
    let playback = Playback::new(replay.span(), speed, view, step);
    let mut player = crate::replay::screen::run::Player { replay, playback };
    let mut stats = RunStats::default();
    let outcome = on_terminal(&signals, |terminal, events| {
        crate::replay::screen::run::run(
            terminal,
            &mut player,
            events,
            &clock,
            signals.cell(),
            theme,
            &mut stats,
        )
    })?;
    let outcome = signalled_failure(outcome, &signals);
    if let Err(e) = &outcome {
        tell(&format!("navdeck: replay ended: {e}"));
    }
    Ok(exit_status(&outcome) as u8)
}

/// A terminal that failed because it hung up: the kernel's SIGHUP may reach the process
/// a moment after the failed read or write. Asked once the loop has ended and the robot
/// has been stopped, a signal that has arrived by then is why the console ended.
fn signalled_failure(outcome: Result<Exit, RunError>, signals: &Signals) -> Result<Exit, RunError> {
    match (&outcome, signals.pending()) {
        (Err(_), Some(n)) => Ok(Exit::Signal(n)),
        _ => outcome,
    }
}

/// Runs `loop_body` on the real terminal and its input. When it returns the robot has
/// been told to stop: from then the process ends within the deadline, and a second
/// signal ends it at once. The terminal is restored before this returns, so anything
/// printed after it reaches a normal screen.
fn on_terminal(
    signals: &Signals,
    loop_body: impl FnOnce(
        &mut ratatui::Terminal<
            ratatui::backend::CrosstermBackend<crate::tui::terminal::TerminalOut>,
        >,
        &mut TtyEvents,
    ) -> Result<Exit, RunError>,
) -> Result<Result<Exit, RunError>> {
    use std::io::IsTerminal;
    if !std::io::stdout().is_terminal() {
        anyhow::bail!("{NEEDS_A_TERMINAL}: its output is not a terminal{FOR_SCRIPTS}");
    }
    // Without a terminal to read keys from, the OS says only "Not a typewriter" or "No
    // such device or address": say what is missing instead.
    let mut guard = TerminalGuard::enter().map_err(|e| no_keyboard(&e))?;
    let mut events = TtyEvents::open(signals).map_err(|e| no_keyboard(&e))?;
    let outcome = loop_body(&mut guard.terminal, &mut events);
    signals.arm_immediate_exit(exit_deadline(), exit_status(&outcome));
    Ok(outcome)
}

const NEEDS_A_TERMINAL: &str = "navdeck's console needs a terminal";
const FOR_SCRIPTS: &str = "; run it in a terminal, or use --headless for scripts";

/// Why the console could not take the keyboard, naming what was missing.
fn no_keyboard(e: &std::io::Error) -> anyhow::Error {
    use std::io::IsTerminal;
    let missing = if std::io::stdin().is_terminal() {
        format!("its terminal cannot be set up to read keys ({e})")
    } else {
        "its input is not a terminal and it has no terminal to read keys from".to_string()
    };
    anyhow::anyhow!("{NEEDS_A_TERMINAL}: {missing}{FOR_SCRIPTS}")
}

/// Opens a new `dir/navdeck-STAMP-PID.log` (`dated_file`), making `dir` if needed.
fn open_log_file(dir: &std::path::Path, suffix: &str) -> std::io::Result<(PathBuf, std::fs::File)> {
    crate::data::replace::create_folder(dir)?;
    let path = dated_file(dir, suffix, "log");
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&path)?;
    Ok((path, file))
}

/// A ROS 2 console that grows into a fleet when a robot joins with `:robot add`: its
/// robot's name, and what watches the domain for others.
pub type Growth = (String, crate::fleet::recruit::Recruiter);

/// Runs the console on the real terminal until quit, a signal, a hang-up or a terminal
/// error; the robot stopped and the link closed in every case. Returns the exit status.
/// With `growth`, robots that appear are offered and join as a fleet's do.
pub fn run_console(
    session: Session,
    options: &ConsoleOptions,
    stopwatch: Arc<dyn Clock>,
    growth: Option<Growth>,
) -> Result<u8> {
    let signals = Signals::watch().context("cannot watch signals")?;
    let mut app = session.into_app(0.0);
    prepare(&mut app, options, stopwatch.clone());
    if let Some((path, session)) = &options.record {
        start_recording(&mut app, path, session.clone(), false)?;
    }
    let log_dir = (options.log_dir.clone()).unwrap_or_else(|| PathBuf::from("logs"));
    let mut log_files: Vec<PathBuf> = log_into(&mut app, &log_dir, "").into_iter().collect();
    let (outcome, mut app, joined) = match growth {
        None => (run_on_wall_clock(&mut app, &signals)?, app, Vec::new()),
        Some((name, mut recruiter)) => {
            let logs = Rc::new(RefCell::new(Vec::new()));
            let (dir, kept) = (log_dir.clone(), logs.clone());
            recruiter.add = prepared(recruiter.add, options, stopwatch, dir, kept);
            let mut fleet = crate::fleet::Fleet::new(vec![crate::fleet::Member { name, app }]);
            fleet.set_recruiter(recruiter);
            let outcome = run_on_wall_clock(&mut fleet, &signals)?;
            let mut members = fleet.into_members();
            log_files.extend(logs.take());
            let first = members.remove(0).app;
            (outcome, first, members)
        }
    };
    let mut label = app.link().label();
    for m in &joined {
        label += &format!(", {} on {}", m.name, m.app.link().label());
    }
    let recorded = app.finish_recording();
    // Closes the links: the serial port, the DDS participant.
    drop(app);
    drop(joined);
    let outcome = signalled_failure(outcome, &signals);
    tell(&format!(
        "navdeck: robot on {label} stopped; {}",
        why_ended(&outcome)
    ));
    tell_recorded(recorded, options, "session");
    for path in log_files {
        tell(&format!("navdeck: session log in {}", path.display()));
    }
    Ok(exit_status(&outcome) as u8)
}

/// Runs a fleet's console on the real terminal, as `run_console` runs one robot's: every
/// robot stopped and every link closed however it ends, a log file per robot.
pub fn run_fleet_console(
    members: Vec<(String, Session)>,
    recruiter: Option<crate::fleet::recruit::Recruiter>,
    options: &ConsoleOptions,
    stopwatch: Arc<dyn Clock>,
) -> Result<u8> {
    let signals = Signals::watch().context("cannot watch signals")?;
    let log_dir = (options.log_dir.clone()).unwrap_or_else(|| PathBuf::from("logs"));
    let mut logs = Vec::new();
    let mut fleet_members = Vec::with_capacity(members.len());
    for (name, session) in members {
        let mut app = session.into_app(0.0);
        prepare(&mut app, options, stopwatch.clone());
        logs.extend(log_into(&mut app, &log_dir, &format!("-{name}")));
        fleet_members.push(crate::fleet::Member { name, app });
    }
    let mut fleet = crate::fleet::Fleet::new(fleet_members);
    let joined = Rc::new(RefCell::new(Vec::new()));
    if let Some(mut recruiter) = recruiter {
        let (dir, logs) = (log_dir.clone(), joined.clone());
        recruiter.add = prepared(recruiter.add, options, stopwatch.clone(), dir, logs);
        fleet.set_recruiter(recruiter);
    }
    if let Some((path, session)) = &options.record {
        let epoch = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0.0, |d| d.as_secs_f64())
            - fleet.app().now();
        let config = fleet.app().config().record.clone();
        fleet.record_to(path, &config, epoch, session.clone(), false)?;
    }
    let outcome = run_on_wall_clock(&mut fleet, &signals)?;
    let labels: Vec<String> = (fleet.members().iter())
        .map(|m| format!("{} on {}", m.name, m.app.link().label()))
        .collect();
    let recorded = fleet.finish_recording();
    // Closes every link.
    drop(fleet);
    logs.extend(joined.take());
    let outcome = signalled_failure(outcome, &signals);
    tell(&format!(
        "navdeck: robots {} stopped; {}",
        labels.join(", "),
        why_ended(&outcome)
    ));
    tell_recorded(recorded, options, "fleet");
    for path in logs {
        tell(&format!("navdeck: session log in {}", path.display()));
    }
    Ok(exit_status(&outcome) as u8)
}

/// Says where `what` (the session, the fleet) was recorded and how big the file is, or
/// why the recording failed.
fn tell_recorded(
    recorded: Option<std::result::Result<crate::record::Summary, String>>,
    options: &ConsoleOptions,
    what: &str,
) {
    match (recorded, &options.record) {
        (Some(Ok(summary)), Some((path, _))) => tell(&format!(
            "navdeck: {what} recorded in {} ({} bytes)",
            path.display(),
            summary.bytes
        )),
        (Some(Err(why)), _) => tell(&format!("navdeck: {why}")),
        _ => {}
    }
}

/// A robot that joins with `:robot add` is prepared as those the console opened with:
/// maps folder, clocks, braille, and a log file of its own (its path kept in `logs`).
pub fn prepared(
    mut add: crate::fleet::recruit::Enlist,
    options: &ConsoleOptions,
    stopwatch: Arc<dyn Clock>,
    log_dir: PathBuf,
    logs: Rc<RefCell<Vec<PathBuf>>>,
) -> crate::fleet::recruit::Enlist {
    let options = ConsoleOptions {
        record: None,
        ..options.clone()
    };
    Box::new(move |ns: &str, now: f64| {
        let mut member = add(ns, now)?;
        prepare(&mut member.app, &options, stopwatch.clone());
        // A file name: the root namespace's robot ("/") is "root", a nested one's
        // slashes become underscores.
        let suffix = match member.name.trim_matches('/') {
            "" => "-root".to_string(),
            name => format!("-{}", name.replace('/', "_")),
        };
        logs.borrow_mut()
            .extend(log_into(&mut member.app, &log_dir, &suffix));
        Ok(member)
    })
}

/// Runs `deck`'s main loop on the real terminal, its session time on the wall clock from
/// now, until quit, a signal in `signals`, a hang-up or a terminal error.
fn run_on_wall_clock<D: crate::tui::deck::Deck>(
    deck: &mut D,
    signals: &Signals,
) -> Result<Result<Exit, RunError>> {
    let theme = Theme::from_env(std::env::var_os("NO_COLOR"));
    let clock = WallClock::start();
    let mut stats = RunStats::default();
    on_terminal(signals, |terminal, events| {
        run(
            terminal,
            deck,
            events,
            &clock,
            signals.cell(),
            theme,
            &mut stats,
        )
    })
}

/// What every console on a terminal sets up: the planning stopwatch, the maps folder, the
/// wall-clock date for file names and the braille map when asked for.
fn prepare(app: &mut App, options: &ConsoleOptions, stopwatch: Arc<dyn Clock>) {
    app.set_stopwatch(stopwatch);
    app.set_maps_dir(
        options
            .maps_dir
            .clone()
            .unwrap_or_else(|| PathBuf::from("maps")),
    );
    app.set_date_source(Box::new(|| {
        humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string()
    }));
    if options.braille {
        app.apply(crate::keymap::Action::ToggleBraille);
    }
}

/// Sends `app`'s log to a new dated file in `log_dir` (its name ending in `suffix`);
/// a warning in the log when it cannot. Returns the file's path.
fn log_into(app: &mut App, log_dir: &std::path::Path, suffix: &str) -> Option<PathBuf> {
    match open_log_file(log_dir, suffix) {
        Ok((path, file)) => match app.log_to(Box::new(file)) {
            Ok(()) => Some(path),
            Err(e) => {
                app.warn(format!("no log file: cannot write {}: {e}", path.display()));
                None
            }
        },
        Err(e) => {
            app.warn(format!("no log file in {}: {e}", log_dir.display()));
            None
        }
    }
}

fn why_ended(outcome: &Result<Exit, RunError>) -> String {
    match outcome {
        Ok(Exit::Quit) => "quit by user".to_string(),
        Ok(Exit::InputClosed) => "the terminal hung up".to_string(),
        Ok(Exit::Signal(n)) => format!("{} received", signal_name(*n)),
        Err(e) => e.to_string(),
    }
}

/// Writes `text` and a newline to standard error, its control characters escaped (a
/// folder's name from the config may hold an escape sequence); a terminal that has gone
/// is no reason to fail.
fn tell(text: &str) {
    let _ = writeln!(
        std::io::stderr(),
        "{}",
        crate::data::printable::printable(text, None)
    );
}

/// The process's exit status: 128 + the signal's number for a signal, as shells expect.
/// The terminal's input ends only when it hangs up (in raw mode ctrl-d is a key), which
/// the kernel signals with SIGHUP: that status too, whichever of the two came first.
fn exit_status(outcome: &Result<Exit, RunError>) -> i32 {
    match outcome {
        Ok(Exit::Quit) => 0,
        Ok(Exit::InputClosed) => 128 + signal_hook::consts::SIGHUP,
        Ok(Exit::Signal(n)) => 128 + *n as i32,
        Err(_) => 1,
    }
}
