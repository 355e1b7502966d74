//! Recording a session and playing it back: a twin session re-run on its recording gives
//! the same estimate bit for bit and the same report; a re-run on another estimator
//! scores both; files cut short, damaged or written by other tools play what they can
//! and say where the damage is.

use crate::common;

use common::scratch;
use navdeck::app::App;
use navdeck::console::start_recording;
use navdeck::keymap::parse_key_sequence;
use navdeck::record::reader::read;
use navdeck::record::recorded::Recorded;
use navdeck::record::{RecordConfig, Recorder};
use navdeck::replay::screen::played::Played;
use navdeck::replay::{Replay, ReplayOptions};
use navdeck::runners::headless;
use navdeck::session::{Session, SessionSpec};
use navdeck::slam::mcl::config::Estimator;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn spec(world: Option<&str>) -> SessionSpec {
    SessionSpec::twin(world.map(PathBuf::from))
}

/// Runs `keys` headless on `spec`'s twin, recording into `path`; the app and its report.
fn record(spec: &SessionSpec, keys: &str, path: &Path) -> (App, headless::Report) {
    let mut app = Session::load(spec).unwrap().into_app(0.0);
    let mut meta = BTreeMap::new();
    meta.insert("seed".to_string(), spec.seed.to_string());
    if let Some(w) = &spec.world {
        meta.insert("world".to_string(), w.display().to_string());
    }
    start_recording(&mut app, path, meta, true).unwrap();
    let keys = parse_key_sequence(keys).unwrap();
    let mut report = headless::run(&mut app, &keys, 10.0);
    report.recording = Some(app.finish_recording().unwrap().unwrap());
    (app, report)
}

fn rerun(path: &Path, options: ReplayOptions) -> Replay {
    let recorded = Arc::new(navdeck::replay::load(path).unwrap());
    let mut replay = Replay::new(recorded, options).unwrap();
    let (_, end) = replay.span();
    replay.run_to(end);
    replay
}

#[test]
fn an_exploration_re_run_on_its_recording_is_the_same_bit_for_bit() {
    let path = scratch("explore").join("explore.mcap");
    let (_, original) = record(&spec(None), "e", &path);
    let summary = original.recording.as_ref().unwrap();
    assert_eq!(summary.dropped, 0);
    let count = |topic: &str| summary.topics.iter().find(|t| t.0 == topic).unwrap().2;
    for topic in [
        "/odom",
        "/scan",
        "/cmd_vel",
        "/tf",
        "/map",
        "/rosout",
        "/navdeck/frame",
    ] {
        assert!(count(topic) > 0, "{topic} recorded nothing");
    }
    let replay = rerun(&path, ReplayOptions::default());
    let c = replay.comparison();
    // Every control tick's pose and covariance, as recorded, to the last bit.
    assert!(c.ticks > 2000, "{c:?}");
    assert_eq!(c.identical, c.ticks, "{c:?}");
    assert_eq!(c.max_position_difference, 0.0);
    // The same report as the headless run, bar the link's name and the wall clock.
    let again = headless::report(replay.app(), original.keys);
    assert_eq!(again.travel.estimated_pose, original.travel.estimated_pose);
    assert_eq!(again.sim_time, original.sim_time);
    assert_eq!(again.travel.true_pose, original.travel.true_pose);
    assert_eq!(again.landmarks, original.landmarks);
    assert_eq!(again.mode, original.mode);
    assert_eq!(
        again.travel.distance_driven,
        original.travel.distance_driven
    );
    assert_eq!(again.score.position_rmse, original.score.position_rmse);
    assert_eq!(again.link, format!("replay:{}", original.link));
}

#[test]
fn a_re_run_on_another_estimator_scores_both_against_the_truth() {
    let path = scratch("ekf-then-mcl").join("ekf-then-mcl.mcap");
    let world = "maps/turtlebot3_world.yaml";
    let (_, original) = record(&spec(Some(world)), ":goto 1.5 0<enter>p", &path);
    assert!(original.following.arrived);
    let options = ReplayOptions {
        estimator: Some(Estimator::Mcl),
        ..ReplayOptions::default()
    };
    let replay = rerun(&path, options);
    let c = replay.comparison();
    assert_eq!(c.recorded_estimator, "EKF-SLAM");
    assert_eq!(c.rerun_estimator, "MCL");
    assert_eq!(
        c.identical, 0,
        "another estimator cannot give the same bits"
    );
    let (recorded, rerun) = (
        c.recorded_position_rmse.unwrap(),
        c.rerun_position_rmse.unwrap(),
    );
    assert!(recorded < 0.05 && rerun < 0.05, "{c:?}");
    assert_ne!(recorded, rerun);
    // The recorded figure is the one the original run scored its estimate with.
    assert!(
        (recorded - original.score.position_rmse.unwrap()).abs() < 0.002,
        "{c:?}"
    );
}

#[test]
fn a_file_cut_anywhere_plays_up_to_the_cut_and_names_the_offset() {
    let path = scratch("cut-source").join("cut-source.mcap");
    record(&spec(None), "wwwwaaaawwww", &path);
    let bytes = std::fs::read(&path).unwrap();
    let whole = Recorded::decode(read(&bytes));
    assert!(whole.problems.is_empty(), "{:?}", whole.problems);
    let mut last = 0;
    for k in 1..=12 {
        let cut = bytes.len() * k / 13;
        let raw = read(&bytes[..cut]);
        let damage = raw.damage.clone();
        let part = Recorded::decode(raw);
        // More of the file never gives fewer frames.
        assert!(part.frames.len() >= last, "cut at {cut}");
        last = part.frames.len();
        match damage {
            Some(damage) => {
                assert!(damage.starts_with("offset "), "{damage}");
                assert!(part.frames.len() < whole.frames.len());
            }
            // Cut in the summary after the data: every message is there.
            None => assert_eq!(part.frames.len(), whole.frames.len(), "cut at {cut}"),
        }
    }
    assert!(last > 0, "the chunks before the cut are readable");
}

#[test]
fn a_damaged_chunk_is_named_and_what_came_before_it_plays() {
    let path = scratch("damaged").join("damaged.mcap");
    // An exploration: many chunks, so the damage lands with some before it.
    record(&spec(None), "e", &path);
    let mut bytes = std::fs::read(&path).unwrap();
    let whole = Recorded::decode(read(&bytes)).frames.len();
    // The chunk records (opcode 0x06) of the file, by their offsets.
    let mut chunks = Vec::new();
    let mut at = 8;
    while at + 9 <= bytes.len() {
        let len = u64::from_le_bytes(bytes[at + 1..at + 9].try_into().unwrap()) as usize;
        if bytes[at] == 0x06 {
            chunks.push(at);
        }
        at += 9 + len;
    }
    assert!(chunks.len() > 10, "{} chunks", chunks.len());
    // Garble the compressed records of the middle chunk.
    let middle = chunks[chunks.len() / 2];
    for b in &mut bytes[middle + 200..middle + 264] {
        *b ^= 0x5a;
    }
    let damaged = scratch("damaged-copy").join("damaged-copy.mcap");
    std::fs::write(&damaged, &bytes).unwrap();
    let recorded = navdeck::replay::load(&damaged).unwrap();
    assert!(
        recorded.frames.len() < whole && !recorded.frames.is_empty(),
        "{} of {whole}: {:?}",
        recorded.frames.len(),
        recorded.problems
    );
    let problem = recorded.problems.join("; ");
    assert!(problem.contains(&format!("offset {middle}: ")), "{problem}");
    // The readable part re-runs, and the log names the damage, after a seek back too.
    let mut replay = rerun(&damaged, ReplayOptions::default());
    assert!(replay.at_end());
    replay.seek(0.0).unwrap();
    let logged = |r: &Replay| {
        let book = r.app().log_book();
        book.iter()
            .any(|e| e.text.starts_with("recording: offset "))
    };
    assert!(logged(&replay));
}

#[test]
fn files_that_hold_no_session_are_refused_with_the_reason() {
    let text = scratch("not-mcap").join("not-mcap.mcap");
    std::fs::write(&text, "hello").unwrap();
    let err = format!("{:#}", navdeck::replay::load(&text).unwrap_err());
    assert!(err.contains("not an MCAP file"), "{err}");
    // Another tool's recording: a std_msgs/String topic.
    let foreign = scratch("foreign").join("foreign.mcap");
    let mut writer = mcap::Writer::new(std::io::BufWriter::new(
        std::fs::File::create(&foreign).unwrap(),
    ))
    .unwrap();
    let schema = writer
        .add_schema("std_msgs/String", "ros2msg", b"string data\n")
        .unwrap();
    let channel = writer
        .add_channel(schema, "/chatter", "cdr", &BTreeMap::new())
        .unwrap();
    let header = mcap::records::MessageHeader {
        channel_id: channel,
        sequence: 0,
        log_time: 1,
        publish_time: 1,
    };
    writer
        .write_to_known_channel(&header, &[0, 1, 0, 0, 3, 0, 0, 0, b'h', b'i', 0, 0])
        .unwrap();
    writer.finish().unwrap();
    drop(writer);
    let err = format!("{:#}", navdeck::replay::load(&foreign).unwrap_err());
    assert!(
        err.contains("no navdeck session in it (1 messages of other tools)"),
        "{err}"
    );
}

#[test]
fn a_recording_never_overwrites_a_file() {
    let path = scratch("taken").join("taken.mcap");
    std::fs::write(&path, "keep me").unwrap();
    let err = Recorder::create(&path, &RecordConfig::default(), 0.0)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("exists"), "{err}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "keep me");
}

#[test]
fn seeking_back_re_runs_from_the_start_to_the_same_place() {
    let path = scratch("seek").join("seek.mcap");
    record(&spec(None), "e", &path);
    let recorded = Arc::new(navdeck::replay::load(&path).unwrap());
    let mut replay = Replay::new(recorded, ReplayOptions::default()).unwrap();
    replay.seek(120.0).unwrap();
    let there = replay.app().pilot().estimated_pose();
    replay.seek(60.0).unwrap();
    assert!(
        (replay.position() - 60.0).abs() < 0.2,
        "{}",
        replay.position()
    );
    replay.seek(120.0).unwrap();
    assert_eq!(replay.app().pilot().estimated_pose(), there);
    let c = replay.comparison();
    assert_eq!(c.identical, c.ticks);
}

#[cfg(feature = "vision")]
#[test]
fn a_camera_session_records_its_pictures_at_the_image_period() {
    let path = scratch("camera").join("camera.mcap");
    let mut session = Session::load(&spec(None)).unwrap();
    session
        .use_sim_camera(None, navdeck::sim::CameraFrames::Whole)
        .unwrap();
    let mut app = session.into_app(0.0);
    start_recording(&mut app, &path, BTreeMap::new(), true).unwrap();
    let keys = parse_key_sequence("wwwwwwwwwwaaaaa").unwrap();
    let report = headless::run(&mut app, &keys, 10.0);
    let summary = app.finish_recording().unwrap().unwrap();
    let images = summary
        .topics
        .iter()
        .find(|t| t.0 == "/camera/image")
        .unwrap()
        .2;
    // One a second (`[record] image_period`), give or take the ends.
    assert!(
        (images as f64 - report.sim_time).abs() <= 2.0,
        "{images} images in {} s",
        report.sim_time
    );
    let raw = read(&std::fs::read(&path).unwrap());
    let image = raw
        .messages
        .iter()
        .find(|m| &*m.topic == "/camera/image")
        .unwrap();
    let msg: navdeck::msgs::ros::Image = navdeck::record::decode(&image.data).unwrap();
    assert_eq!(&*msg.encoding, "mono8");
    assert_eq!(msg.data.len(), (msg.width * msg.height) as usize);
    assert!(msg.width > 0);
}
