//! Recordings for `navdeck replay` whose frames, inputs and truths lie: made from a real
//! recording of a short twin session (navdeck's own recorder), edited, and written again
//! with navdeck's own recorder. Each must end under the runner's limits, naming what it
//! skipped, or play the rest cleanly.

use super::{Case, case};
use crate::common::scratch;
use navdeck::console::start_recording;
use navdeck::data::frame_check::MAX_BEAMS;
use navdeck::keymap::parse_key_sequence;
use navdeck::msgs::record::{FrameMsg, InputMsg, SightingMsg, TruthMsg};
use navdeck::msgs::ros::PoseWithCovarianceStamped;
use navdeck::record::recorded::Recorded;
use navdeck::record::{RecordConfig, Recorder, Topic, decode};
use navdeck::runners::headless;
use navdeck::session::{Session, SessionSpec};
use std::collections::BTreeMap;
use std::path::Path;

/// What an edited recording holds: each list with its entries' original times, which
/// stay their log times whatever the edit does to the times inside the messages.
#[derive(Clone)]
struct Source {
    session: BTreeMap<String, String>,
    attachments: BTreeMap<String, Vec<u8>>,
    inputs: Vec<(f64, InputMsg)>,
    frames: Vec<(f64, FrameMsg)>,
    truths: Vec<(f64, TruthMsg)>,
    /// What was believed each tick, for the replay's comparison.
    estimates: Vec<(f64, PoseWithCovarianceStamped)>,
}

/// A short twin session driven to a goal and recorded, read back.
fn real_recording(dir: &Path) -> Source {
    let path = dir.join("real.mcap");
    let mut app = Session::load(&SessionSpec::twin(None))
        .unwrap()
        .into_app(0.0);
    let mut meta = BTreeMap::new();
    meta.insert("seed".to_string(), "1".to_string());
    start_recording(&mut app, &path, meta, true).unwrap();
    // A planned route followed to its end: every figure of the report is a number.
    let keys = parse_key_sequence(":goto -0.6 -1.2<enter>p").unwrap();
    headless::run(&mut app, &keys, 10.0);
    app.finish_recording().unwrap().unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let r = Recorded::decode(navdeck::record::reader::read(&bytes));
    assert!(r.problems.is_empty(), "{:?}", r.problems);
    Source {
        session: r.session,
        attachments: r.attachments,
        inputs: r.inputs.into_iter().map(|i| (i.time, i)).collect(),
        frames: r.frames.into_iter().map(|f| (f.time, f)).collect(),
        truths: r.truths.into_iter().map(|t| (t.time, t)).collect(),
        estimates: (r.estimates.iter())
            .map(|e| (e.time, decode(&e.bytes).unwrap()))
            .collect(),
    }
}

/// `source` written as a recording, its bytes.
fn written(source: &Source, path: &Path) -> Vec<u8> {
    let _ = std::fs::remove_file(path);
    let mut r = Recorder::create(path, &RecordConfig::default(), 0.0).unwrap();
    r.wait_when_full(true);
    r.metadata("navdeck", source.session.clone());
    for (name, data) in &source.attachments {
        r.attach(name, "text/plain", data.clone());
    }
    for (t, msg) in &source.inputs {
        r.publish(Topic::Input, *t, msg.clone());
    }
    for (t, msg) in &source.frames {
        r.publish(Topic::Frame, *t, msg.clone());
    }
    for (t, msg) in &source.truths {
        r.publish(Topic::Truth, *t, msg.clone());
    }
    for (t, msg) in &source.estimates {
        r.publish(Topic::Estimate, *t, msg.clone());
    }
    r.finish().unwrap();
    std::fs::read(path).unwrap()
}

/// Values a hostile edit tries for every number it edits; some cases add their own
/// (1e-300, 0, 1e6).
const WILD: [f64; 5] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e308, -1e308];

/// The recordings: the cases and variants of each, all values of `WILD` where
/// a number is edited.
pub fn cases() -> Vec<Case> {
    let dir = scratch("replay-frames");
    let real = real_recording(&dir);
    let path = dir.join("edited.mcap");
    let mut out = Vec::new();
    let mut add = |names: &str, clean: bool, edit: &dyn Fn(&mut Source)| {
        let mut source = real.clone();
        edit(&mut source);
        let body = written(&source, &path);
        let c = case(
            "replay frames",
            &["replay", "r.mcap", "--headless", "--json"],
            names,
        )
        .file("r.mcap", body);
        out.push(if clean { c.or_clean() } else { c });
    };
    let middle = real.inputs.len() / 2;
    let every_frame = |s: &mut Source, f: &dyn Fn(&mut FrameMsg)| {
        s.frames.iter_mut().for_each(|(_, m)| f(m));
    };
    for v in WILD {
        // One input's time, the last input's time, every input's time.
        add("input", true, &|s| s.inputs[middle].1.time = v);
        add("input", true, &|s| s.inputs.last_mut().unwrap().1.time = v);
        // Wheel travel, stamps and elapsed time on every frame.
        add("wheels", true, &|s| {
            every_frame(s, &|m| {
                m.has_wheels = true;
                m.wheel_left = v;
            })
        });
        // Every other frame: with none left the gripper is never reported.
        add("stamp", true, &|s| {
            s.frames
                .iter_mut()
                .skip(1)
                .step_by(2)
                .for_each(|(_, m)| m.stamp = v)
        });
        add("elapsed", true, &|s| every_frame(s, &|m| m.elapsed = v));
        add("frame", true, &|s| s.frames[3].1.time = v);
        // A scan claiming to reach `v` with ranges of 1e8, or holding `v` ranges.
        add("scan", true, &|s| {
            every_frame(s, &|m| {
                m.scan_range_max = v;
                m.scan_ranges.iter_mut().for_each(|r| *r = 1e8);
            })
        });
        add("scan", true, &|s| {
            every_frame(s, &|m| m.scan_ranges.iter_mut().for_each(|r| *r = v as f32))
        });
        add("scan", true, &|s| every_frame(s, &|m| m.scan_range_min = v));
        add("scan", true, &|s| {
            every_frame(s, &|m| m.scan_angle_increment = v)
        });
        // Sightings whose range or bearing is `v`.
        add("sightings", true, &|s| {
            every_frame(s, &|m| {
                m.has_sightings = true;
                m.sightings = vec![SightingMsg {
                    id: 3,
                    range: v,
                    bearing: v,
                }];
            })
        });
        add("sightings", true, &|s| {
            every_frame(s, &|m| {
                m.has_sightings = true;
                m.sightings = vec![SightingMsg {
                    id: 4,
                    range: 1.0,
                    bearing: v,
                }];
            })
        });
        // Poses handed in: an initial pose and a goal.
        add("initial_pose", true, &|s| {
            let m = &mut s.frames[5].1;
            m.has_initial_pose = true;
            m.initial_pose = [v, 0.0, 0.0];
        });
        // Placed where the robot is, facing `v` when that is no angle (a finite heading
        // is wrapped and taken, and a placed pose rightly drops the route).
        if !v.is_finite() {
            add("initial_pose", true, &|s| {
                let start = s.truths[0].1.pose();
                let m = &mut s.frames[5].1;
                m.has_initial_pose = true;
                m.initial_pose = [start.x, start.y, v];
            });
        }
        add("goal", true, &|s| {
            let m = &mut s.frames[5].1;
            m.has_goal = true;
            m.goal = [1.0, v, 0.0];
        });
        add("arm", true, &|s| {
            every_frame(s, &|m| {
                m.has_arm = true;
                m.arm_joints = [0.0, v, 0.0, 0.0];
            })
        });
        // The recorded truth: every other one (with none left there is no truth to
        // score against, and the report has no figures for it).
        let odd_truths = |s: &mut Source, f: &dyn Fn(&mut TruthMsg)| {
            s.truths
                .iter_mut()
                .skip(1)
                .step_by(2)
                .for_each(|(_, t)| f(t));
        };
        add("truth", true, &|s| odd_truths(s, &|t| t.x = v));
        add("truth", true, &|s| odd_truths(s, &|t| t.theta = v));
        add("truth", true, &|s| {
            odd_truths(s, &|t| t.distance_driven = v)
        });
        add("truth", true, &|s| s.truths[2].1.time = v);
    }
    // Wheel travel a little and much beyond top speed, sightings too near.
    for v in [1e6, 0.2, -3.0] {
        add("wheels", true, &|s| every_frame(s, &|m| m.wheel_right = v));
    }
    for v in [1e-300, 0.0, -1.0, 1e4] {
        add("sightings", true, &|s| {
            every_frame(s, &|m| {
                m.has_sightings = true;
                m.sightings = vec![SightingMsg {
                    id: 5,
                    range: v,
                    bearing: 0.5,
                }];
            })
        });
    }
    add("camera", true, &|s| {
        every_frame(s, &|m| {
            m.has_camera = true;
            m.camera_latency = f64::INFINITY;
        })
    });
    // Every input at NaN, or none at all: nothing to replay, said so.
    add("no recorded inputs", false, &|s| {
        s.inputs.iter_mut().for_each(|(_, i)| i.time = f64::NAN)
    });
    add("no recorded inputs", false, &|s| s.inputs.clear());
    // Inputs going back in time, and an input well past the last frame.
    add("input", true, &|s| s.inputs[middle].1.time = 0.0);
    add("input", true, &|s| {
        let end = s.frames.last().unwrap().0;
        s.inputs.last_mut().unwrap().1.time = end + 100.0;
    });
    // 20 M beams, one beam too many, and 5000 sightings and camera ids in one frame.
    add("20000", true, &|s| {
        let m = &mut s.frames[4].1;
        m.has_scan = true;
        m.scan_ranges = vec![1.0; 20_000_000];
    });
    add("scan", true, &|s| {
        let m = &mut s.frames[4].1;
        m.has_scan = true;
        m.scan_ranges = vec![1.0; MAX_BEAMS + 1];
    });
    add("sightings", true, &|s| {
        let m = &mut s.frames[6].1;
        {
            m.has_sightings = true;
            m.sightings = (0..5000)
                .map(|id| SightingMsg {
                    id,
                    range: 1e308,
                    bearing: 1e308,
                })
                .collect();
            m.has_camera = true;
            m.camera_ids = (0..5000).collect();
        }
    });
    add("sightings", true, &|s| {
        let m = &mut s.frames[6].1;
        m.has_sightings = true;
        m.sightings = (0..1000)
            .map(|id| SightingMsg {
                id,
                range: 1.0 + f64::from(id) * 0.001,
                bearing: f64::from(id) * 0.006,
            })
            .collect();
    });
    // A failure recorded with no words, and one with an escape in them: the human
    // report (a lost link rightly drops the route, so the JSON has no path figure).
    add("failed", true, &|s| {
        let m = &mut s.frames[7].1;
        m.failed = true;
        m.failure = String::new();
    });
    add("failed", true, &|s| {
        let m = &mut s.frames[7].1;
        m.failed = true;
        m.failure = "\u{1b}]2;owned\u{7}".to_string();
    });
    let failures = out.len() - 2;
    for c in &mut out[failures..] {
        c.args.retain(|a| a != "--json");
    }
    out
}
