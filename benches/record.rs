//! What recording costs the control loop, and how long a replay frame takes.
//!
//! - `session_60s/plain` and `session_60s/recording`: the control loop's CPU time for a
//!   minute of exploration in the twin (600 control ticks) without and with `--record`;
//!   the difference is what the loop pays (building messages and handing them over; the
//!   writer encodes, compresses and writes on its own thread). As in a real session, the
//!   writer catches up between hand-overs instead of competing with the loop for the CPU.
//! - `replay_frame_200x60_50x_*`: one frame of `navdeck replay` at 50x on a ten-minute
//!   exploration (a generated 10 m x 8 m world of rooms, seed 7): the re-run moves on
//!   1/30 s x 50 of session time and the 200x60 screen is drawn. At 30 frames a second it
//!   must stay under 33 ms for no frame to be dropped.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::app::App;
use navdeck::keymap::Key;
use navdeck::replay::playback::{Playback, View};
use navdeck::replay::{Replay, ReplayOptions};
use navdeck::session::{Session, SessionSpec};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

fn app_with(config: Option<PathBuf>) -> App {
    let spec = SessionSpec {
        config,
        ..SessionSpec::twin(None)
    };
    Session::load(&spec).unwrap().into_app(0.0)
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("navdeck-bench-record-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

static FILES: AtomicUsize = AtomicUsize::new(0);

/// CPU time of the calling thread: what the control loop spent, whatever else the
/// machine (the writer's thread, other programs) was doing meanwhile.
fn thread_cpu() -> std::time::Duration {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec into the one we pass.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    std::time::Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// A minute of exploration, recorded when `record` (real-time hand-over: never waits);
/// the control loop's CPU time. Closing the file (the writer's work) is not counted.
fn minute(record: bool, dir: &std::path::Path, config: Option<PathBuf>) -> std::time::Duration {
    let mut app = app_with(config);
    // Without a recording, the same pause every half second: a round trip to a thread
    // that does nothing, so both runs are interrupted alike.
    let (ask, asked) = std::sync::mpsc::channel::<std::sync::mpsc::Sender<()>>();
    let idle = std::thread::spawn(move || {
        for done in asked {
            let _ = done.send(());
        }
    });
    if record {
        let n = FILES.fetch_add(1, Ordering::SeqCst);
        let path = dir.join(format!("{n}.mcap"));
        navdeck::console::start_recording(&mut app, &path, Default::default(), false).unwrap();
    }
    let mut took = std::time::Duration::ZERO;
    let mut started = thread_cpu();
    app.handle_key(Key::char('e'), navdeck::app::KeyKind::Press, 0.0);
    for i in 1..=600 {
        app.update(f64::from(i) * 0.1);
        if i % 5 == 0 {
            // As in real time, the writer has half a second to itself between hand-overs:
            // its work is not counted, and does not run beside the control loop's.
            took += thread_cpu() - started;
            if record {
                app.wait_for_recording();
            } else {
                let (done, answered) = std::sync::mpsc::channel();
                ask.send(done).unwrap();
                answered.recv().unwrap();
            }
            started = thread_cpu();
        }
    }
    took += thread_cpu() - started;
    drop(ask);
    idle.join().unwrap();
    if let Some(path) = app.recording_path().map(PathBuf::from) {
        app.finish_recording();
        let _ = std::fs::remove_file(path);
    }
    took
}

fn session(c: &mut Criterion) {
    let dir = scratch();
    let mut group = c.benchmark_group("session_60s");
    group.sample_size(10);
    let raw = dir.join("uncompressed.toml");
    std::fs::write(&raw, "[record]\ncompression = \"none\"\n").unwrap();
    let small = dir.join("level9.toml");
    std::fs::write(&small, "[record]\nlevel = 9\n").unwrap();
    for (name, record, config) in [
        ("plain", false, None),
        ("recording", true, None),
        ("recording_uncompressed", true, Some(raw)),
        ("recording_zstd9", true, Some(small)),
    ] {
        group.bench_function(name, |b| {
            b.iter_custom(|n| (0..n).map(|_| minute(record, &dir, config.clone())).sum())
        });
    }
    group.finish();
}

fn replay_frame(c: &mut Criterion) {
    let dir = scratch();
    let path = dir.join("replay-source.mcap");
    let _ = std::fs::remove_file(&path);
    let world = navdeck::sim::generate::generate(&navdeck::sim::generate::GenerateOptions {
        seed: 7,
        size: Some((10.0, 8.0)),
        blocks: 4,
        style: navdeck::sim::generate::Style::Rooms,
        ..Default::default()
    })
    .unwrap();
    let spec = SessionSpec::twin(None);
    let mut app = Session::load_with_world(&spec, world)
        .unwrap()
        .into_app(0.0);
    navdeck::console::start_recording(&mut app, &path, Default::default(), true).unwrap();
    navdeck::runners::headless::run(&mut app, &[Key::char('e')], 10.0);
    app.finish_recording().unwrap().unwrap();
    eprintln!("replaying {:.1} s of session", app.now());
    let recorded = Arc::new(navdeck::replay::load(&path).unwrap());
    let theme = Theme { color: true };
    for view in [View::AsRecorded, View::Rerun] {
        let mut replay = Replay::new(recorded.clone(), ReplayOptions::default()).unwrap();
        replay.show_on_screen(200, 59);
        let mut playback = Playback::new(replay.span(), 50.0, view, 0.1);
        let mut terminal = Terminal::new(TestBackend::new(200, 60)).unwrap();
        let name = match view {
            View::AsRecorded => "replay_frame_200x60_50x_as_recorded",
            View::Rerun => "replay_frame_200x60_50x_rerun",
        };
        c.bench_function(name, |b| {
            b.iter(|| {
                playback.advance(1.0 / 30.0);
                if playback.paused {
                    // The end: back to the start (a re-run from scratch, as a seek back).
                    playback.go_to(playback.span().0);
                    playback.paused = false;
                    replay.restart().unwrap();
                    replay.show_on_screen(200, 59);
                }
                replay.run_to(playback.position());
                terminal.clear().unwrap();
                terminal
                    .draw(|f| navdeck::replay::screen::draw(f, &replay, &playback, theme))
                    .unwrap();
            })
        });
    }
}

criterion_group!(benches, session, replay_frame);
criterion_main!(benches);
