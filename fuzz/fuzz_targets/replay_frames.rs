//! Fuzzes what a replay hands the pilot: the input's bytes are read as recorded inputs,
//! frames and truths whose every number may be NaN, infinite, huge, tiny or any bit
//! pattern, and whose times may go back or jump. They are encoded as navdeck records
//! them, decoded as `navdeck replay` decodes them, and re-run through the console for a
//! bounded stretch of session time. Nothing may panic, and the re-run's pose and every
//! figure of its report must be finite.
#![no_main]

use libfuzzer_sys::fuzz_target;
use navdeck::msgs::record::{FrameMsg, InputMsg, SightingMsg, TruthMsg};
use navdeck::record::reader::{RawMessage, RawRecording};
use navdeck::record::recorded::Recorded;
use navdeck::record::topics::TOPICS;
use navdeck::record::{Topic, encode};
use navdeck::replay::{Replay, ReplayOptions};
use navdeck::runners::headless;
use navdeck::sim::World;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Session seconds re-run at most: a bounded number of control ticks per input.
const RERUN: f64 = 20.0;
/// Records made from one input at most.
const MAX_RECORDS: usize = 300;

/// The fuzzer's bytes as field values.
struct Values<'a> {
    bytes: &'a [u8],
    clock: f64,
}

impl Values<'_> {
    fn byte(&mut self) -> u8 {
        let Some((&b, rest)) = self.bytes.split_first() else {
            return 0;
        };
        self.bytes = rest;
        b
    }

    fn count(&mut self, most: usize) -> usize {
        usize::from(self.byte()) % (most + 1)
    }

    /// A number: one of the values that break code, a small one, or any bit pattern.
    fn number(&mut self) -> f64 {
        match self.byte() % 16 {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => f64::NEG_INFINITY,
            3 => 1e308,
            4 => -1e308,
            5 => 1e-300,
            6 => 0.0,
            7 => 1e17,
            8 => 1e6,
            12 => {
                let mut b = [0u8; 8];
                b.iter_mut().for_each(|x| *x = self.byte());
                f64::from_le_bytes(b)
            }
            _ => (f64::from(self.byte()) - 128.0) / 32.0,
        }
    }

    /// A time: mostly a little after the last one, sometimes any number.
    fn time(&mut self) -> f64 {
        if self.byte() % 8 == 0 {
            return self.number();
        }
        self.clock += f64::from(self.byte()) / 200.0;
        self.clock
    }

    fn pose(&mut self) -> [f64; 3] {
        [self.number(), self.number(), self.number()]
    }

    fn input(&mut self) -> InputMsg {
        let time = self.time();
        match self.byte() % 4 {
            0 => {
                let keys = ["w", "a", "d", "s", "space", "p", "e", "x", "g"];
                let key = keys[usize::from(self.byte()) % keys.len()].to_string();
                InputMsg::key(time, key, self.byte() % 3)
            }
            1 => InputMsg::resize(time, u16::from(self.byte()), u16::from(self.byte())),
            _ => InputMsg::update(time),
        }
    }

    fn frame(&mut self) -> FrameMsg {
        let time = self.time();
        let mut f = FrameMsg {
            time,
            stamp: if self.byte() % 4 == 0 { self.number() } else { time },
            elapsed: if self.byte() % 4 == 0 { self.number() } else { 0.1 },
            ..FrameMsg::default()
        };
        let parts = self.byte();
        if parts & 1 != 0 {
            f.has_wheels = true;
            f.wheel_left = self.number() / 64.0;
            f.wheel_right = self.number() / 64.0;
        }
        if parts & 2 != 0 {
            f.has_sightings = true;
            let n = self.count(8);
            f.sightings = (0..n)
                .map(|_| SightingMsg {
                    id: u32::from(self.byte()),
                    range: self.number(),
                    bearing: self.number(),
                })
                .collect();
        }
        if parts & 4 != 0 {
            f.has_scan = true;
            f.scan_angle_min = self.number();
            f.scan_angle_increment = self.number();
            f.scan_range_min = self.number();
            f.scan_range_max = self.number();
            let n = self.count(255) * 4;
            let range = self.number() as f32;
            f.scan_ranges = (0..n).map(|k| range * (1.0 + k as f32 / 64.0)).collect();
        }
        if parts & 8 != 0 {
            f.has_initial_pose = true;
            f.initial_pose = self.pose();
        }
        if parts & 16 != 0 {
            f.has_goal = true;
            f.goal = self.pose();
        }
        if parts & 32 != 0 {
            f.has_arm = true;
            f.arm_joints = [self.number(), self.number(), self.number(), self.number()];
        }
        if parts & 64 != 0 {
            f.has_camera = true;
            f.camera_ids = (0..self.count(16)).map(|k| k as u32).collect();
            f.camera_latency = self.number();
        }
        if parts & 128 != 0 {
            f.failed = true;
            f.failure = if self.byte() % 2 == 0 { String::new() } else { "lost".into() };
        }
        f.gripper = self.byte() % 7;
        f
    }

    fn truth(&mut self) -> TruthMsg {
        let [x, y, theta] = self.pose();
        TruthMsg {
            time: self.time(),
            x,
            y,
            theta,
            linear: self.number(),
            angular: self.number(),
            distance_driven: self.number(),
            ..TruthMsg::default()
        }
    }
}

fn message(topic: Topic, time: f64, data: Vec<u8>) -> RawMessage {
    RawMessage {
        topic: topic.name().into(),
        schema: TOPICS[topic.index()].2.into(),
        encoding: "cdr".into(),
        log_time: (time.clamp(0.0, 1e9) * 1e9) as u64,
        data,
    }
}

fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

fuzz_target!(|data: &[u8]| {
    let mut v = Values {
        bytes: data,
        clock: 0.0,
    };
    let mut messages = Vec::new();
    while !v.bytes.is_empty() && messages.len() < MAX_RECORDS {
        messages.push(match v.byte() % 3 {
            0 => {
                let m = v.input();
                message(Topic::Input, m.time, encode(&m))
            }
            1 => {
                let m = v.frame();
                message(Topic::Frame, m.time, encode(&m))
            }
            _ => {
                let m = v.truth();
                message(Topic::Truth, m.time, encode(&m))
            }
        });
    }
    let mut session = BTreeMap::new();
    session.insert("link".to_string(), "sim:arena".to_string());
    let raw = RawRecording {
        messages,
        metadata: vec![("navdeck".to_string(), session)],
        attachments: vec![(
            "world.toml".to_string(),
            World::default_arena().to_toml().into_bytes(),
        )],
        ..RawRecording::default()
    };
    let recorded = Recorded::decode(raw);
    // `navdeck replay` refuses a recording with no inputs before re-running it.
    if recorded.inputs.is_empty() {
        return;
    }
    let mut replay = Replay::new(Arc::new(recorded), ReplayOptions::default()).unwrap();
    let (start, end) = replay.span();
    assert!(start.is_finite() && end.is_finite(), "span {start} .. {end}");
    replay.run_to(end.min(start + RERUN));
    let report = headless::report(replay.app(), 0);
    let p = report.travel.estimated_pose;
    assert!(finite(&[p.x, p.y, p.theta]), "estimate {p:?}");
    if let Some(t) = report.travel.true_pose {
        assert!(finite(&[t.x, t.y, t.theta]), "truth {t:?}");
    }
    let figures = [
        report.sim_time,
        report.travel.distance_driven,
        report.travel.odometry_distance,
    ];
    assert!(finite(&figures), "{figures:?}");
    let optional = [
        report.score.position_rmse,
        report.score.heading_rmse_deg,
        report.score.mean_nees,
        report.following.path_length,
        report.following.cross_track_rms,
    ];
    assert!(optional.iter().flatten().all(|v| v.is_finite()), "{optional:?}");
    let c = replay.comparison();
    assert!(c.max_position_difference.is_finite(), "{c:?}");
});
