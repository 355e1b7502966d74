//! The console records on a real terminal: `[record] folder` gives every session a dated
//! file of its own, and a console killed outright (SIGKILL: no chance to finish the
//! file) leaves a recording that plays up to its last chunk.

use crate::common;
use crate::pty_support;

use common::scratch;
use navdeck::record::reader::read;
use navdeck::record::recorded::Recorded;
use pty_support::{Console, Terminal};
use std::sync::Arc;

fn recorded(path: &std::path::Path) -> Recorded {
    Recorded::decode(read(&std::fs::read(path).unwrap_or_default()))
}

#[test]
fn a_record_folder_in_the_config_records_each_console_session_under_a_dated_name() {
    let dir = scratch("folder");
    let sessions = dir.join("sessions");
    let config = dir.join("navdeck.toml");
    std::fs::write(
        &config,
        format!("[record]\nfolder = {:?}\n", sessions.display().to_string()),
    )
    .unwrap();
    let logs = dir.join("logs");
    let mut console = Console::start(
        &[
            "--config",
            config.to_str().unwrap(),
            "--log-dir",
            logs.to_str().unwrap(),
        ],
        &[],
        Terminal::Plain,
    );
    console.wait_for(b"Status");
    console.hold_until(b"w", b"forward");
    console.send(b"q");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
    assert!(end.output.contains("session recorded in"), "{}", end.output);
    let files: Vec<_> = std::fs::read_dir(&sessions)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let name = files[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with("navdeck-20") && name.ends_with(".mcap"),
        "{name}"
    );
    let session = recorded(&files[0]);
    assert!(session.problems.is_empty(), "{:?}", session.problems);
    let keys: Vec<&str> = session
        .inputs
        .iter()
        .filter(|i| i.kind == navdeck::msgs::record::INPUT_KEY)
        .map(|i| i.key.as_str())
        .collect();
    assert!(keys.contains(&"w") && keys.last() == Some(&"q"), "{keys:?}");
    // The robot was told to drive forward, and to stop when the console quit.
    assert!(session.commands.iter().any(|c| c.1 > 0.0));
    assert_eq!(
        session.commands.last().map(|c| (c.1, c.2)),
        Some((0.0, 0.0))
    );
}

#[test]
fn a_killed_console_leaves_a_recording_that_plays_to_its_last_chunk() {
    let dir = scratch("kill");
    let file = dir.join("killed.mcap");
    let config = dir.join("navdeck.toml");
    std::fs::write(&config, "[record]\nchunk_period = 0.2\n").unwrap();
    let mut console = Console::start(
        &[
            "--config",
            config.to_str().unwrap(),
            "--record",
            file.to_str().unwrap(),
            "--log-dir",
            dir.join("logs").to_str().unwrap(),
        ],
        &[],
        Terminal::Plain,
    );
    console.wait_for(b"Status");
    console.hold_until(b"e", b"EXPLORATION");
    // Until a few chunks are on the disk: the file is read as a player would.
    console.hold_while_not(b"e", "30 frames on the disk", |_| {
        recorded(&file).frames.len() >= 30
    });
    console.signal(libc::SIGKILL);
    console.finish();
    let bytes = std::fs::read(&file).unwrap();
    let raw = read(&bytes);
    let damage = raw.damage.clone().expect("no footer after a kill");
    assert!(damage.starts_with("offset "), "{damage}");
    let session = Recorded::decode(raw);
    assert!(session.frames.len() >= 30);
    assert!(session.modes.iter().any(|m| m.1 == "EXPLORATION"));
    // What is there re-runs to its end.
    let mut replay = navdeck::replay::Replay::new(Arc::new(session), Default::default()).unwrap();
    let (_, end) = replay.span();
    replay.run_to(end);
    assert!(replay.at_end());
    let c = replay.comparison();
    assert_eq!(c.identical, c.ticks);
}

#[test]
fn the_replay_console_plays_a_recording_and_quits_on_q() {
    let dir = scratch("replay");
    let file = dir.join("session.mcap");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args([
            "--headless",
            "--keys",
            "wwwwaaaa",
            "--record",
            file.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let mut console = Console::start(&["replay", file.to_str().unwrap()], &[], Terminal::Plain);
    console.wait_for(b"as recorded");
    // Paused at the start, then on to the re-run view.
    console.send(b" ");
    console.send(b"r");
    console.wait_for(b"re-run");
    console.send(b"q");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
}
