//! The console on a fleet (`--robots N`, `--ns` more than once), and its headless run.

use crate::Cli;
use anyhow::{Context, Result, bail};
use navdeck::clock::Clock;
use navdeck::console::{ConsoleOptions, run_fleet_console};
use navdeck::fleet::recruit::Recruiter;
use navdeck::fleet::{Fleet, Member};
use navdeck::keymap::parse_key_sequence;
use navdeck::session::{LinkChoice, Ros2Target, Session, SessionSpec, fleet};
use navdeck::tui::events::WallClock;
use navdeck::tui::signals::Signals;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

/// Opens the fleet's console, or runs it headless with --headless.
pub(crate) fn run(cli: &Cli, spec: &SessionSpec) -> Result<ExitCode> {
    // What a fleet does not take yet, refused by name before any link is opened.
    let refused = [
        ("--sim-camera", cli.twin.sim_camera),
        ("--camera", cli.camera.is_some()),
        ("--ros2", cli.ros2),
        ("--fault", !cli.twin.fault.is_empty()),
        ("--tags", cli.twin.tags.is_some()),
    ];
    if let Some((option, _)) = refused.iter().find(|(_, on)| *on) {
        bail!(
            "{option} drives one robot: it is not taken with a fleet (--robots N, --ns more than once)"
        );
    }
    let listed = match &spec.config {
        Some(path) if cli.robots.is_none() && cli.ns.is_empty() => {
            navdeck::config::Config::load(path)?.fleet
        }
        _ => Vec::new(),
    };
    // The fleet's ROS 2 robots share one participant, which also watches for new ones.
    let on_ros2 = match listed.is_empty() {
        true => matches!(spec.link, LinkChoice::Ros2(_)) && cli.robots.is_none(),
        false => (listed.iter()).any(|e| matches!(e.link_choice(), Ok(LinkChoice::Ros2(_)))),
    };
    let participant = match on_ros2 {
        true => Some(fleet::shared_participant(spec, cli.domain)?),
        false => None,
    };
    let members = match (&spec.link, cli.robots, &participant) {
        _ if !listed.is_empty() => {
            fleet::from_entries(spec, &listed, cli.domain, participant.as_ref())?
        }
        (LinkChoice::Sim, Some(n), _) => fleet::twins(spec, n)?,
        (LinkChoice::Ros2(_), None, Some(p)) => fleet::ros2(spec, &cli.ns, p)?,
        (LinkChoice::Ros2(_), Some(_), _) => {
            bail!("--robots puts twins in one world: a ROS 2 fleet is --ns given once per robot")
        }
        _ => bail!("--ns more than once needs --link ros2"),
    };
    let stopwatch: std::sync::Arc<dyn Clock> = std::sync::Arc::new(WallClock::start());
    let known: Vec<String> = match listed.is_empty() {
        true => cli.ns.clone(),
        false => listed.iter().filter_map(|e| e.namespace.clone()).collect(),
    };
    let recruiter = participant.map(|p| recruiter(spec, cli.domain, p, known, &stopwatch));
    // One file for the whole fleet, each robot under its own namespace.
    let folder = members
        .first()
        .and_then(|(_, s)| s.config.record.folder.clone());
    let record = match (&cli.record, folder) {
        (Some(path), _) => Some((path.clone(), super::console::recording_metadata(cli))),
        (None, Some(dir)) if !cli.headless => Some((
            navdeck::console::dated_recording(&dir),
            super::console::recording_metadata(cli),
        )),
        _ => None,
    };
    if !cli.headless {
        let options = ConsoleOptions {
            maps_dir: cli.maps_dir.clone(),
            log_dir: cli.log_dir.clone(),
            braille: cli.braille,
            record,
        };
        return Ok(ExitCode::from(run_fleet_console(
            members, recruiter, &options, stopwatch,
        )?));
    }
    let keys =
        parse_key_sequence(cli.keys.as_deref().unwrap_or("")).context("cannot read --keys")?;
    let mut apps = Vec::with_capacity(members.len());
    for (name, session) in members {
        let mut app = session.into_app(0.0);
        app.set_stopwatch(stopwatch.clone());
        if let Some(dir) = &cli.maps_dir {
            app.set_maps_dir(dir.join(&name));
        }
        apps.push(Member { name, app });
    }
    let mut fleet = Fleet::new(apps);
    if let Some(recruiter) = recruiter {
        fleet.set_recruiter(recruiter);
    }
    let started = Instant::now();
    let epoch = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64());
    // Robots on ROS 2 live on the wall clock: pace the run by it, and stop on a signal.
    let simulated = (fleet.members().iter()).all(|m| m.app.link().ground_truth().is_some());
    if let Some((path, meta)) = &record {
        let config = fleet.app().config().record.clone();
        fleet.record_to(
            path,
            &config,
            epoch - fleet.app().now(),
            meta.clone(),
            simulated,
        )?;
    }
    let signals = match simulated {
        true => None,
        false => Some(Signals::watch().context("cannot watch for signals")?),
    };
    let mut report = match &signals {
        None => navdeck::runners::fleet::run(&mut fleet, &keys, cli.key_rate, &mut |_| true, false),
        Some(signals) => {
            let mut pace = super::sweep::wall_pacer(started, signals);
            navdeck::runners::fleet::run(&mut fleet, &keys, cli.key_rate, &mut pace, true)
        }
    };
    navdeck::tui::deck::Deck::shutdown(&mut fleet, "headless run ended");
    match fleet.finish_recording() {
        Some(Ok(summary)) => report.recording = Some(summary),
        Some(Err(why)) => say_err!("navdeck: {why}"),
        None => {}
    }
    let wall = started.elapsed().as_secs_f64();
    report.wall_time_s = Some(wall);
    report.epoch_unix = signals.as_ref().map(|_| epoch);
    report.realtime_factor = Some(report.sim_time / wall.max(1e-9));
    print_report(&report, cli.json)?;
    let status = signals
        .as_ref()
        .and_then(Signals::pending)
        .map_or(0, |n| 128 + n as u8);
    drop(fleet);
    Ok(ExitCode::from(status))
}

/// Watches `participant`'s domain for robots not in the fleet (`known`), and opens a
/// console on the one `:robot add NS` names.
pub(crate) fn recruiter(
    spec: &SessionSpec,
    domain: Option<u16>,
    participant: navdeck::link::ros2::Participant,
    known: Vec<String>,
    stopwatch: &std::sync::Arc<dyn Clock>,
) -> Recruiter {
    let watched = participant.clone();
    let spec = spec.clone();
    let stopwatch = stopwatch.clone();
    Recruiter {
        seen: Box::new(move || navdeck::link::ros2::raw::robots_seen(&watched)),
        add: Box::new(move |ns: &str, now: f64| {
            let own = SessionSpec {
                link: LinkChoice::Ros2(Ros2Target {
                    namespace: Some(ns.to_string()),
                    domain,
                }),
                ..spec.clone()
            };
            let mut app = Session::load_on(&own, &participant)?.into_app(now);
            app.set_stopwatch(stopwatch.clone());
            let name = ns.trim_start_matches('/');
            let name = if name.is_empty() { "/" } else { name };
            Ok(Member {
                name: name.to_string(),
                app,
            })
        }),
        known,
        looked_at: f64::NEG_INFINITY,
    }
}

/// A fleet's headless report: one JSON object with `json`, else a line per robot.
pub(crate) fn print_report(
    report: &navdeck::runners::fleet::FleetReport,
    json: bool,
) -> Result<()> {
    if json {
        sayln!("{}", serde_json::to_string(report)?);
        return Ok(());
    }
    for r in &report.robots {
        say!(
            "{}: {}",
            r.name,
            navdeck::runners::headless::human(&r.report)
        );
    }
    Ok(())
}
