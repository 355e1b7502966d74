//! A fleet recorded and played back: `navdeck --robots 3 --record FILE` writes one MCAP
//! file with each robot's stream under its own namespace and the fleet's own calls;
//! `navdeck replay FILE --headless` re-runs every robot to the pose the recorded run
//! ended at, selecting and stopping as the session did; a robot whose stream was cut
//! short is named and the others still play.

use crate::common;
use crate::python_support;

use common::{navdeck, scratch};
use serde_json::Value;
use std::path::Path;

/// The keys of the recorded run, ten a simulated second: robot 1 explores, robot 2 is
/// selected and explores, robot 3 likewise; twenty seconds of zooming in and out while
/// they explore; then every robot is stopped.
fn keys() -> String {
    format!("e<ctrl-n>e<ctrl-n>e{}X", "+-".repeat(100))
}

/// Runs three headless twins with `KEYS`, recording to `file`; the run's JSON report.
fn record(file: &Path) -> Value {
    let file = file.to_str().unwrap();
    let keys = keys();
    let out = navdeck(&[
        "--robots",
        "3",
        "--headless",
        "--json",
        "--keys",
        &keys,
        "--record",
        file,
    ]);
    assert!(
        out.status.success(),
        "navdeck failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the fleet's JSON report")
}

/// `navdeck replay FILE --headless --json`: its report and what it said on stderr.
fn replay(file: &Path) -> (Value, String) {
    let out = navdeck(&["replay", file.to_str().unwrap(), "--headless", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "replay failed: {stderr}");
    let report = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stdout)));
    (report, stderr)
}

fn robot<'a>(report: &'a Value, name: &str) -> &'a Value {
    (report["robots"].as_array().unwrap().iter())
        .find(|r| r["name"] == name)
        .unwrap_or_else(|| panic!("no robot {name} in {report}"))
}

/// The fleet run every test here plays, recorded once: (its report, its file).
fn recorded_run() -> &'static (Value, std::path::PathBuf) {
    static RUN: std::sync::OnceLock<(Value, std::path::PathBuf)> = std::sync::OnceLock::new();
    RUN.get_or_init(|| {
        let file = scratch("run").join("fleet.mcap");
        let report = record(&file);
        (report, file)
    })
}

#[test]
fn a_fleet_run_replays_every_robot_to_its_recorded_pose() {
    let (original, file) = recorded_run();
    let (again, stderr) = replay(file);
    assert_eq!(again["broken"], serde_json::json!([]), "{stderr}");
    // The keys that the fleet took replay too: robot 3 selected, one stop-all.
    assert_eq!(again["selected"], "robot3");
    assert_eq!(again["selected"], original["selected"]);
    assert_eq!(original["stop_all_times"].as_array().unwrap().len(), 1);
    assert_eq!(again["stop_all_times"], original["stop_all_times"]);
    assert_eq!(again["sim_time"], original["sim_time"]);
    for name in ["robot1", "robot2", "robot3"] {
        let (was, now) = (robot(original, name), robot(&again, name));
        assert_eq!(now["estimated_pose"], was["estimated_pose"], "{name}");
        assert_eq!(now["true_pose"], was["true_pose"], "{name}");
        assert_eq!(now["distance_driven"], was["distance_driven"], "{name}");
        assert_eq!(now["mode"], was["mode"], "{name}");
        assert!(
            was["distance_driven"].as_f64().unwrap() > 0.5,
            "{name} hardly moved: {was}"
        );
        // Every control tick's estimate as recorded, to the last bit.
        let c = &now["replay"];
        assert!(c["ticks"].as_u64().unwrap() > 200, "{name}: {c}");
        assert_eq!(c["identical"], c["ticks"], "{name}: {c}");
    }
}

#[test]
fn each_robot_records_under_its_own_namespace_in_one_file() {
    let (original, file) = recorded_run();
    let raw = navdeck::record::reader::read(&std::fs::read(file).unwrap());
    assert_eq!(raw.damage, None);
    let mut per_robot = [0usize; 3];
    for m in &raw.messages {
        let topic = &*m.topic;
        if topic == "/navdeck/fleet/input" {
            continue;
        }
        let i = ["/robot1/", "/robot2/", "/robot3/"]
            .iter()
            .position(|p| topic.starts_with(p))
            .unwrap_or_else(|| panic!("{topic} is under no robot's namespace"));
        per_robot[i] += 1;
    }
    assert!(per_robot.iter().all(|&n| n > 1000), "{per_robot:?}");
    // Each robot's tf tree is its own under the twins' one map, as RViz and Foxglove
    // need to draw the robots apart.
    let holds = |topic: &str, text: &str| {
        (raw.messages.iter())
            .any(|m| &*m.topic == topic && m.data.windows(text.len()).any(|w| w == text.as_bytes()))
    };
    for r in ["robot1", "robot2", "robot3"] {
        let tf = format!("/{r}/tf");
        for frame in [format!("{r}/odom"), format!("{r}/base_link"), "map".into()] {
            assert!(
                holds(&tf, &format!("{frame}\0")),
                "{tf} has no frame {frame}"
            );
        }
        assert!(
            !holds(&tf, &format!("{r}/map")),
            "{tf}: the twins share one map"
        );
        assert!(
            holds(&format!("/{r}/scan"), &format!("{r}/base_scan")),
            "{r}'s scan frame"
        );
    }
    let summary = &original["recording"];
    let count = |topic: &str| {
        (summary["topics"].as_array().unwrap().iter())
            .find(|t| t[0] == topic)
            .unwrap_or_else(|| panic!("no {topic} in {summary}"))[2]
            .as_u64()
            .unwrap()
    };
    for r in ["robot1", "robot2", "robot3"] {
        for topic in [
            "odom",
            "scan",
            "cmd_vel",
            "rosout",
            "navdeck/input",
            "navdeck/frame",
        ] {
            assert!(count(&format!("/{r}/{topic}")) > 0, "/{r}/{topic}");
        }
    }
    assert!(count("/navdeck/fleet/input") > 0);
    // One robot's replay does not take a fleet's file: it says what it is.
    let err = format!("{:#}", navdeck::replay::load(file).unwrap_err());
    assert!(err.contains("a fleet's recording (3 robots)"), "{err}");
    // A tool outside navdeck reads every robot's topics and decodes every message.
    let Some(python) =
        python_support::python("the MCAP reader in Python", "mcap and mcap-ros2-support")
    else {
        return;
    };
    let seen = crate::record_python::check(&python, file);
    assert_eq!(seen["decode_errors"], serde_json::json!([]), "{seen}");
    assert_eq!(seen["profile"], "ros2");
    for r in ["robot1", "robot2", "robot3"] {
        for topic in ["odom", "scan", "tf", "navdeck/frame"] {
            let name = format!("/{r}/{topic}");
            assert_eq!(seen["counts"][&name].as_u64(), Some(count(&name)), "{name}");
        }
    }
    assert!(seen["counts"].get("/odom").is_none(), "{}", seen["counts"]);
}

/// Copies the recording `from` to `to` leaving out the messages on topics starting with
/// `cut` recorded more than `at` seconds after its first: that stream cut short.
fn cut_robot(from: &Path, to: &Path, cut: &str, at: f64) {
    let bytes = std::fs::read(from).unwrap();
    let raw = navdeck::record::reader::read(&bytes);
    let mut writer = mcap::Writer::with_options(
        std::io::BufWriter::new(std::fs::File::create(to).unwrap()),
        mcap::WriteOptions::new().profile("ros2"),
    )
    .unwrap();
    let start = raw.messages.first().unwrap().log_time;
    let limit = start.saturating_add_signed((at * 1e9) as i64);
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        if m.channel.topic.starts_with(cut) && m.log_time > limit {
            continue;
        }
        writer.write(&m).unwrap();
    }
    for (name, entries) in raw.metadata {
        let metadata = mcap::records::Metadata {
            name,
            metadata: entries,
        };
        writer.write_metadata(&metadata).unwrap();
    }
    for (name, data) in raw.attachments {
        let attachment = mcap::Attachment {
            log_time: start,
            create_time: start,
            name,
            media_type: "application/toml".into(),
            data: data.into(),
        };
        writer.attach(&attachment).unwrap();
    }
    writer.finish().unwrap();
}

#[test]
fn a_robot_whose_stream_is_cut_short_is_named_and_the_others_replay() {
    let (original, file) = recorded_run();
    let cut = scratch("cut").join("cut.mcap");
    cut_robot(file, &cut, "/robot2/", 10.0);
    let (again, stderr) = replay(&cut);
    let broken = again["broken"].as_array().unwrap();
    assert_eq!(broken.len(), 1, "{broken:?}");
    let why = broken[0].as_str().unwrap();
    assert!(why.starts_with("robot robot2 (/robot2): "), "{why}");
    assert!(
        why.contains("(/robot2/navdeck/input) ends at 10.000 s"),
        "{why}"
    );
    assert!(stderr.contains(why), "{stderr}");
    // The robots whose streams are whole end where they did.
    for name in ["robot1", "robot3"] {
        let (was, now) = (robot(original, name), robot(&again, name));
        assert_eq!(now["estimated_pose"], was["estimated_pose"], "{name}");
        assert_eq!(now["true_pose"], was["true_pose"], "{name}");
        let c = &now["replay"];
        assert_eq!(c["identical"], c["ticks"], "{name}: {c}");
    }
    // The cut robot replays up to its cut.
    let c = &robot(&again, "robot2")["replay"];
    assert!(c["ticks"].as_u64().unwrap() > 50, "{c}");
}

#[test]
fn the_replay_console_shows_the_fleet_panel_and_the_robot_selected_as_recorded() {
    use navdeck::replay::fleet::{FleetReplay, Opened, open};
    use navdeck::replay::playback::{Playback, View};
    use navdeck::replay::screen::run::{Player, run};
    use navdeck::tui::events::{ManualClock, ScriptedEvents, Step};
    let (_, file) = recorded_run();
    let Opened::Fleet(recorded) = open(file).unwrap() else {
        panic!("{} opened as one robot's recording", file.display());
    };
    let replay = FleetReplay::new(std::sync::Arc::new(recorded), Default::default()).unwrap();
    let playback = Playback::new(replay.span(), 1.0, View::Rerun, 0.1);
    let mut player = Player { replay, playback };
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(120, 40)).unwrap();
    let clock = ManualClock::default();
    // To the end (`end`), then a moment for the last frame.
    let end = navdeck::tui::events::Event::Key(common::key("end"), navdeck::app::KeyKind::Press);
    let next =
        navdeck::tui::events::Event::Key(common::key("ctrl-n"), navdeck::app::KeyKind::Press);
    let steps = vec![Step::Event(end), Step::Wait(0.2)];
    let mut events = ScriptedEvents::new(clock.clone(), steps);
    run(
        &mut terminal,
        &mut player,
        &mut events,
        &clock,
        &std::sync::atomic::AtomicUsize::new(0),
        navdeck::tui::theme::Theme { color: false },
        &mut Default::default(),
    )
    .unwrap();
    let text = common::screen(&terminal);
    assert!(player.replay.at_end(), "{text}");
    // Robot 3 was selected when the session ended: its row is marked, every robot has one.
    assert_eq!(player.replay.fleet().selected(), 2);
    assert!(text.contains("> 3 robot3"), "{text}");
    for name in ["robot1", "robot2", "robot3"] {
        assert!(text.contains(name), "no row for {name}:\n{text}");
    }
    assert!(text.contains("REPLAY"), "{text}");
    assert!(text.contains("replay:sim:arena #3"), "{text}");
    // ctrl-n shows robot 1 (the one after robot 3); the recorded selection stays.
    let mut events = ScriptedEvents::new(clock.clone(), vec![Step::Event(next), Step::Wait(0.2)]);
    run(
        &mut terminal,
        &mut player,
        &mut events,
        &clock,
        &std::sync::atomic::AtomicUsize::new(0),
        navdeck::tui::theme::Theme { color: false },
        &mut Default::default(),
    )
    .unwrap();
    let text = common::screen(&terminal);
    assert_eq!(player.replay.shown(), 0);
    assert_eq!(player.replay.fleet().selected(), 2);
    assert!(text.contains("replay:sim:arena #1"), "{text}");
    assert!(text.contains("> 3 robot3"), "{text}");
}

#[test]
fn a_fleet_file_without_the_fleets_calls_is_refused_naming_the_file_and_topic() {
    let (_, file) = recorded_run();
    let cut = scratch("no-calls").join("no-calls.mcap");
    cut_robot(file, &cut, "/navdeck/fleet/input", -1.0);
    let out = navdeck(&["replay", cut.to_str().unwrap(), "--headless", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // navdeck refuses the file as it refuses any bad input: status 2, no panic.
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("no-calls.mcap"), "{stderr}");
    assert!(
        stderr.contains("without the fleet's calls on /navdeck/fleet/input"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}
