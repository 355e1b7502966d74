//! The console, and its headless run: navdeck with no subcommand.

use crate::Cli;
use anyhow::{Context, Result, bail};
use navdeck::clock::Clock;
use navdeck::console::{ConsoleOptions, run_console};
use navdeck::keymap::parse_key_sequence;
use navdeck::runners::headless;
use navdeck::session::{LinkChoice, Session, SessionSpec};
use navdeck::sim::CameraFrames;
use navdeck::tui::events::WallClock;
use navdeck::tui::signals::Signals;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Simulated seconds a headless run may spend pressing keys (two hours).
pub(crate) const MAX_HEADLESS_KEYS_TIME: f64 = 7200.0;

/// Opens the console, or runs headless with --headless.
pub(crate) fn run(cli: &Cli) -> Result<ExitCode> {
    // Refused before a robot's link is opened: faults are the twin's.
    if let (Some(fault), false) = (cli.twin.fault.first(), cli.link == LinkChoice::Sim) {
        bail!("--fault {fault} needs the twin (--link sim)");
    }
    let spec = SessionSpec {
        world: cli.twin.world.clone(),
        seed: cli.twin.seed,
        start: cli.twin.start,
        config: cli.config.clone(),
        keymap: cli.keymap.clone(),
        link: match &cli.link {
            LinkChoice::Ros2(_) => LinkChoice::Ros2(navdeck::session::Ros2Target {
                namespace: cli.ns.first().cloned(),
                domain: cli.domain,
            }),
            other => other.clone(),
        },
        localize: cli.localize.choice(),
    };
    if cli.robots.is_some_and(|n| n > 1) || cli.ns.len() > 1 {
        return super::fleet::run(cli, &spec);
    }
    // A config with a [[fleet]] opens the fleet it lists, unless the command line names
    // the robot.
    if let Some(path) = cli
        .config
        .as_deref()
        .filter(|_| cli.robots.is_none() && cli.ns.is_empty())
        && !navdeck::config::Config::load(path)?.fleet.is_empty()
    {
        return super::fleet::run(cli, &spec);
    }
    // One monotonic clock times planning and camera detection alike.
    let stopwatch: std::sync::Arc<dyn Clock> = std::sync::Arc::new(WallClock::start());
    // A ROS 2 robot's console joins on a participant that also watches the domain, so
    // that robots appearing on it are offered and can join as a fleet's.
    let grows = matches!(spec.link, LinkChoice::Ros2(_)) && !cli.headless;
    let participant = match grows && cli.twin.tags.is_none() {
        true => Some(navdeck::session::fleet::shared_participant(
            &spec, cli.domain,
        )?),
        false => None,
    };
    // Everything is loaded and validated before the terminal is touched.
    let mut session = match &participant {
        Some(p) => Session::load_on(&spec, p)?,
        None => Session::load_with_tags(&spec, cli.twin.tags.as_deref())?,
    };
    session.inject_faults(&cli.twin.fault, spec.seed)?;
    let growth = participant.map(|p| {
        let ns = cli.ns.first().cloned().unwrap_or_else(|| "/".into());
        let name = match ns.trim_matches('/') {
            "" => "robot1".to_string(),
            trimmed => trimmed.to_string(),
        };
        let recruiter = super::fleet::recruiter(&spec, cli.domain, p, vec![ns], &stopwatch);
        (name, recruiter)
    });
    if cli.twin.sim_camera {
        session.use_sim_camera(Some(stopwatch.clone()), CameraFrames::Whole)?;
    }
    // A track in the twin's world: lane mode (k) drives it through the lane camera.
    session.offer_lane_camera(spec.seed, Some(stopwatch.clone()));
    if let Some(source) = &cli.camera {
        session = session.with_camera(source, stopwatch.clone())?;
    }
    if cli.ros2 {
        session = session.with_ros2(&navdeck::session::Ros2Target {
            namespace: cli.ns.first().cloned(),
            domain: cli.domain,
        })?;
    }
    let record = match (&cli.record, &session.config.record.folder) {
        (Some(path), _) => Some((path.clone(), recording_metadata(cli))),
        (None, Some(dir)) if !cli.headless => Some((
            navdeck::console::dated_recording(dir),
            recording_metadata(cli),
        )),
        _ => None,
    };
    if cli.headless {
        return run_headless(session, cli, stopwatch, record);
    }
    let options = ConsoleOptions {
        maps_dir: cli.maps_dir.clone(),
        log_dir: cli.log_dir.clone(),
        braille: cli.braille,
        record,
    };
    Ok(ExitCode::from(run_console(
        session, &options, stopwatch, growth,
    )?))
}

/// How the session was started, for its recording (a replay re-runs it the same way).
pub(crate) fn recording_metadata(cli: &Cli) -> std::collections::BTreeMap<String, String> {
    let mut m = std::collections::BTreeMap::new();
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    m.insert("seed".into(), cli.twin.seed.to_string());
    let given = [
        ("world", path(&cli.twin.world)),
        ("tags", path(&cli.twin.tags)),
        ("config", path(&cli.config)),
        ("keymap", path(&cli.keymap)),
        (
            "start",
            cli.twin
                .start
                .map(|p| format!("{},{},{}", p.x, p.y, p.theta.to_degrees())),
        ),
        ("estimator", cli.localize.estimator_name()),
        ("map", cli.localize.map_name()),
        ("initial_pose", cli.localize.initial_pose_text()),
        (
            "sim_camera",
            cli.twin.sim_camera.then(|| "true".to_string()),
        ),
        (
            "faults",
            (!cli.twin.fault.is_empty()).then(|| {
                let specs: Vec<String> = cli.twin.fault.iter().map(|f| f.to_string()).collect();
                specs.join(" ")
            }),
        ),
        (
            "keymap_text",
            cli.keymap
                .as_ref()
                .and_then(|p| std::fs::read_to_string(p).ok()),
        ),
    ];
    for (key, value) in given {
        if let Some(v) = value {
            m.insert(key.into(), v);
        }
    }
    m
}

fn run_headless(
    session: Session,
    cli: &Cli,
    stopwatch: std::sync::Arc<dyn Clock>,
    record: Option<(PathBuf, std::collections::BTreeMap<String, String>)>,
) -> Result<ExitCode> {
    if !(cli.key_rate.is_finite() && cli.key_rate > 0.0) {
        bail!("--key-rate {} must be a positive number", cli.key_rate);
    }
    let keys =
        parse_key_sequence(cli.keys.as_deref().unwrap_or("")).context("cannot read --keys")?;
    let lasts = keys.len() as f64 / cli.key_rate;
    if lasts > MAX_HEADLESS_KEYS_TIME {
        bail!(
            "--keys: {} keys at {} a second take {lasts:.0} s, over the {MAX_HEADLESS_KEYS_TIME} s a headless run may press keys for",
            keys.len(),
            cli.key_rate
        );
    }
    let mut app = session.into_app(0.0);
    if let Some((path, meta)) = &record {
        let simulated = app.link().ground_truth().is_some();
        navdeck::console::start_recording(&mut app, path, meta.clone(), simulated)?;
    }
    let started = Instant::now();
    app.set_stopwatch(stopwatch);
    if let Some(dir) = &cli.maps_dir {
        app.set_maps_dir(dir.clone());
    }
    // A real robot moves in real time: keep the session clock on the wall clock, and
    // stop the robot on SIGINT, SIGTERM or SIGHUP.
    // So does a twin beside ROS 2: the other nodes live on the wall clock.
    let signals = match (app.link().ground_truth(), cli.ros2) {
        (Some(_), false) => None,
        _ => Some(Signals::watch().context("cannot watch for signals")?),
    };
    let mut report = match &signals {
        None => headless::run(&mut app, &keys, cli.key_rate),
        Some(signals) => {
            let mut pace = super::sweep::wall_pacer(started, signals);
            headless::run_paced(&mut app, &keys, cli.key_rate, &mut pace)
        }
    };
    // A run whose robot stopped answering did not do what it was asked.
    let lost = match app.pilot().link_status() {
        navdeck::app::LinkStatus::Lost(why) => Some(why.clone()),
        _ => None,
    };
    app.shutdown("headless run ended");
    let status = signals
        .as_ref()
        .and_then(Signals::pending)
        .map_or(0, |n| 128 + n as i32);
    if let Some(signals) = &signals {
        signals.arm_immediate_exit(navdeck::console::exit_deadline(), status);
    }
    let wall = started.elapsed().as_secs_f64();
    match app.finish_recording() {
        Some(Ok(summary)) => report.recording = Some(summary),
        Some(Err(why)) => say_err!("navdeck: {why}"),
        None => {}
    }
    report.wall_time_s = Some(wall);
    report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
    if cli.json {
        sayln!("{}", serde_json::to_string(&report)?);
    } else {
        say!("{}", headless::human(&report));
    }
    // A save that was asked for and failed fails the run (the log says why).
    if let Some(why) = &lost {
        say_err!("navdeck: the robot was not answering at the end: {why}");
    }
    let status = if status == 0 && (app.failed_saves() > 0 || lost.is_some()) {
        1
    } else {
        status
    };
    drop(app);
    Ok(ExitCode::from(status as u8))
}
