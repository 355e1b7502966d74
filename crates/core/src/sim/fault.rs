//! A fault to inject into the twin, as typed on the command line (`--fault`) or at the
//! console (`:fault`): `KIND@START[+DURATION][:PARAM]`, e.g. `camera@60+20` (the camera
//! dark from 60 s for 20 s) or `slip@30+10:0.5` (the wheels deliver half the commanded
//! travel). Times are seconds of simulated time; a fault without a duration lasts to the
//! end of the run (or until `:fault clear`).

use serde::Serialize;
use std::fmt;

/// Latest start and longest duration a fault may have, seconds (about eleven days).
pub const MAX_FAULT_TIME: f64 = 1.0e6;

/// The share of the commanded travel slipping wheels deliver when `:RATIO` is not given.
pub const DEFAULT_SLIP_RATIO: f64 = 0.5;

/// What goes wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FaultKind {
    /// The camera goes dark: frames keep coming, with nothing seen in them.
    Camera,
    /// The lidar goes silent: no scans.
    Lidar,
    /// The wheel odometry goes silent: no wheel travel, and what the wheels turn meanwhile
    /// is never reported.
    Odom,
    /// The arm stops answering: no joint states, and its commands are not carried out.
    Arm,
    /// The wheels slip: the robot moves only a share of what the odometry reports.
    Slip,
}

impl FaultKind {
    pub const ALL: [FaultKind; 5] = [
        FaultKind::Camera,
        FaultKind::Lidar,
        FaultKind::Odom,
        FaultKind::Arm,
        FaultKind::Slip,
    ];

    /// The name the spec uses: camera, lidar, odom, arm, slip.
    pub fn name(self) -> &'static str {
        match self {
            FaultKind::Camera => "camera",
            FaultKind::Lidar => "lidar",
            FaultKind::Odom => "odom",
            FaultKind::Arm => "arm",
            FaultKind::Slip => "slip",
        }
    }
}

impl fmt::Display for FaultKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One fault: what, from when, for how long, and for slip how much travel gets through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaultSpec {
    pub kind: FaultKind,
    /// Simulated seconds at which it begins.
    pub start_s: f64,
    /// With `@A..B`, the latest it may begin: each run draws its start from `start_s` to
    /// this (`drawn`), so a sweep meets the fault at a different moment in every run.
    pub start_latest: Option<f64>,
    /// Seconds it lasts; `None`: to the end of the run.
    pub duration_s: Option<f64>,
    /// Slip only: the share (0 to 1) of the commanded wheel travel the wheels really
    /// deliver; `None` for every other kind.
    pub slip_ratio: Option<f64>,
}

/// A spec that could not be read: the whole spec, and what is wrong with which part.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("fault `{spec}`: {problem}")]
pub struct FaultSpecError {
    pub spec: String,
    pub problem: FaultProblem,
}

/// The part of a spec that is wrong, and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FaultProblem {
    #[error("nothing to read: expected KIND@START[+DURATION][:PARAM], e.g. camera@60+20")]
    Empty,
    #[error("unknown sensor `{0}`: expected camera, lidar, odom, arm or slip")]
    UnknownKind(String),
    #[error(
        "start `{0}` is not a time in seconds from 0 to {MAX_FAULT_TIME}, or a window A..B of two such times, A before B"
    )]
    Start(String),
    #[error("duration `{0}` is not a number of seconds above 0 and at most {MAX_FAULT_TIME}")]
    Duration(String),
    #[error(
        "slip ratio `{0}` is not a number from 0 to 1 (the share of the commanded travel the wheels deliver)"
    )]
    SlipRatio(String),
    #[error(
        "`{kind}` takes no parameter, but `:{param}` was given (only slip does, e.g. slip@30+10:0.5)"
    )]
    NoParameter { kind: FaultKind, param: String },
}

impl FaultSpec {
    /// Reads `KIND[@START][+DURATION][:PARAM]`; a spec without `@START` begins at `now`
    /// (simulated seconds: 0 on the command line, the present at the console). START and
    /// DURATION are seconds, optionally written with an `s`.
    pub fn parse_at(text: &str, now: f64) -> Result<FaultSpec, FaultSpecError> {
        let fail = |problem| FaultSpecError {
            spec: text.to_string(),
            problem,
        };
        let spec = text.trim();
        if spec.is_empty() {
            return Err(fail(FaultProblem::Empty));
        }
        let (head, param) = match spec.split_once(':') {
            Some((head, param)) => (head, Some(param.trim())),
            None => (spec, None),
        };
        let (kind_and_start, duration) = match head.split_once('+') {
            Some((k, d)) => (k, Some(d.trim())),
            None => (head, None),
        };
        let (kind, start) = match kind_and_start.split_once('@') {
            Some((k, s)) => (k.trim(), Some(s.trim())),
            None => (kind_and_start.trim(), None),
        };
        let kind = FaultKind::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(kind))
            .ok_or_else(|| fail(FaultProblem::UnknownKind(kind.to_string())))?;
        let time = |s: &str| seconds(s).filter(|v| (0.0..=MAX_FAULT_TIME).contains(v));
        let (start_s, start_latest) = match start {
            Some(s) => match s.split_once("..") {
                Some((a, b)) => time(a.trim())
                    .zip(time(b.trim()))
                    .filter(|(a, b)| a < b)
                    .map(|(a, b)| (a, Some(b))),
                None => time(s).map(|a| (a, None)),
            }
            .ok_or_else(|| fail(FaultProblem::Start(s.to_string())))?,
            None => (now, None),
        };
        let duration_s = duration
            .map(|d| {
                seconds(d)
                    .filter(|v| *v > 0.0 && *v <= MAX_FAULT_TIME)
                    .ok_or_else(|| fail(FaultProblem::Duration(d.to_string())))
            })
            .transpose()?;
        let slip_ratio = match (kind, param) {
            (FaultKind::Slip, None) => Some(DEFAULT_SLIP_RATIO),
            (FaultKind::Slip, Some(p)) => Some(
                p.parse::<f64>()
                    .ok()
                    .filter(|v| (0.0..=1.0).contains(v))
                    .ok_or_else(|| fail(FaultProblem::SlipRatio(p.to_string())))?,
            ),
            (_, None) => None,
            (kind, Some(p)) => {
                let param = p.to_string();
                return Err(fail(FaultProblem::NoParameter { kind, param }));
            }
        };
        Ok(FaultSpec {
            kind,
            start_s,
            start_latest,
            duration_s,
            slip_ratio,
        })
    }

    /// The spec with its start drawn from its window (`@A..B`) by a generator seeded with
    /// `seed` (a run's seed: the same run meets the same fault), to a tenth of a second; a
    /// spec with one start time is itself.
    pub fn drawn(self, seed: u64) -> FaultSpec {
        use rand::{Rng, SeedableRng};
        let Some(latest) = self.start_latest else {
            return self;
        };
        // Each kind draws apart, so two faults of one run do not begin together; the seed
        // is spread over every bit first (Fibonacci hashing's 2^64 / φ), so that seeds one
        // apart do not trade draws between kinds.
        let stream = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (0x5eed_fa17 + self.kind as u64);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(stream);
        let start = self.start_s + rng.random::<f64>() * (latest - self.start_s);
        FaultSpec {
            start_s: ((start * 10.0).round() / 10.0).min(latest),
            start_latest: None,
            ..self
        }
    }

    /// Simulated seconds at which it ends, if it ends.
    pub fn end_s(&self) -> Option<f64> {
        self.duration_s.map(|d| self.start_s + d)
    }

    /// Whether it is in force at simulated time `t`: from its start, up to (not at) its end.
    pub fn active(&self, t: f64) -> bool {
        t >= self.start_s && self.end_s().is_none_or(|end| t < end)
    }

    /// What the fault does, for the log: "camera dark", "wheels slipping (0.5 of the
    /// commanded travel)".
    pub fn effect(&self) -> String {
        match self.kind {
            FaultKind::Camera => "camera dark".into(),
            FaultKind::Lidar => "lidar silent".into(),
            FaultKind::Odom => "odometry silent".into(),
            FaultKind::Arm => "arm not answering".into(),
            FaultKind::Slip => format!(
                "wheels slipping ({} of the commanded travel)",
                self.slip_ratio.unwrap_or(DEFAULT_SLIP_RATIO)
            ),
        }
    }

    /// How long it lasts, for the log: "for 20 s", "until cleared".
    pub fn lasting(&self) -> String {
        match self.duration_s {
            Some(d) => format!("for {} s", crate::data::number::short(d)),
            None => "until cleared".into(),
        }
    }
}

/// Seconds written as a plain number, optionally followed by `s`; `None` when it is not
/// a finite number.
fn seconds(text: &str) -> Option<f64> {
    let digits = text.strip_suffix('s').unwrap_or(text).trim();
    digits.parse::<f64>().ok().filter(|v| v.is_finite())
}

impl std::str::FromStr for FaultSpec {
    type Err = FaultSpecError;
    /// As `parse_at` from time 0: the command line's `--fault`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        FaultSpec::parse_at(s, 0.0)
    }
}

impl fmt::Display for FaultSpec {
    /// The spec in the syntax it is read in, e.g. `camera@60+20`, `slip@30+10:0.5`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}@{}", self.kind, self.start_s)?;
        if let Some(latest) = self.start_latest {
            write!(f, "..{latest}")?;
        }
        if let Some(d) = self.duration_s {
            write!(f, "+{d}")?;
        }
        if let Some(r) = self.slip_ratio {
            write!(f, ":{r}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> FaultSpec {
        text.parse().unwrap()
    }

    #[test]
    fn a_start_window_is_drawn_per_seed_within_it() {
        let window = spec("lidar@30..180+20");
        assert_eq!(window.to_string(), "lidar@30..180+20");
        let starts: Vec<f64> = (1..=50).map(|seed| window.drawn(seed).start_s).collect();
        assert!(starts.iter().all(|s| (30.0..=180.0).contains(s)));
        assert_eq!(
            window.drawn(7),
            window.drawn(7),
            "a seed draws the same start"
        );
        let (lo, hi) = (
            starts.iter().copied().fold(f64::INFINITY, f64::min),
            starts.iter().copied().fold(0.0, f64::max),
        );
        assert!(
            lo < 60.0 && hi > 150.0,
            "spread over the window: {lo}..{hi}"
        );
        let drawn = window.drawn(3);
        assert_eq!((drawn.start_latest, drawn.duration_s), (None, Some(20.0)));
        assert_eq!(spec("camera@60+20").drawn(3), spec("camera@60+20"));
        for bad in ["lidar@90..30", "lidar@30..30", "lidar@..30", "lidar@30..x"] {
            let e = FaultSpec::parse_at(bad, 0.0).unwrap_err();
            assert!(matches!(e.problem, FaultProblem::Start(_)), "{bad}: {e}");
        }
    }

    #[test]
    fn reads_the_issue_examples_and_writes_them_back() {
        let camera = spec("camera@60+20");
        assert_eq!(camera.kind, FaultKind::Camera);
        assert_eq!((camera.start_s, camera.duration_s), (60.0, Some(20.0)));
        assert_eq!(camera.slip_ratio, None);
        let slip = spec("slip@30+10:0.5");
        assert_eq!(slip.slip_ratio, Some(0.5));
        assert_eq!(spec("lidar@100").duration_s, None);
        for text in [
            "camera@60+20",
            "lidar@100+5",
            "odom@0.5+2.25",
            "arm@7",
            "slip@30+10:0.25",
        ] {
            assert_eq!(spec(text).to_string(), text);
            assert_eq!(spec(&spec(text).to_string()), spec(text));
        }
        // The default slip ratio is written out.
        assert_eq!(spec("slip@30+10").to_string(), "slip@30+10:0.5");
        assert_eq!(spec(" Camera@60s+20s ").to_string(), "camera@60+20");
    }

    #[test]
    fn a_spec_without_a_start_begins_now() {
        let now = FaultSpec::parse_at("camera+20", 95.5).unwrap();
        assert_eq!((now.start_s, now.duration_s), (95.5, Some(20.0)));
        let absolute = FaultSpec::parse_at("camera@60+20", 95.5).unwrap();
        assert_eq!(absolute.start_s, 60.0);
        assert_eq!(spec("odom").start_s, 0.0);
    }

    #[test]
    fn active_from_the_start_up_to_the_end() {
        let s = spec("lidar@10+5");
        assert!(!s.active(9.99));
        assert!(s.active(10.0) && s.active(14.99));
        assert!(!s.active(15.0));
        assert!(spec("lidar@10").active(1e9));
    }

    #[test]
    fn bad_specs_name_the_bad_part() {
        let err = |text: &str| text.parse::<FaultSpec>().unwrap_err().to_string();
        assert_eq!(
            err("cmaera@60+20"),
            "fault `cmaera@60+20`: unknown sensor `cmaera`: expected camera, lidar, odom, arm or slip"
        );
        assert!(err("camera@soon+20").contains("start `soon`"));
        assert!(err("camera@-5+20").contains("start `-5`"));
        assert!(err("camera@nan").contains("start `nan`"));
        assert!(err("camera@1e300").contains("start `1e300`"));
        assert!(err("camera@60+0").contains("duration `0`"));
        assert!(err("camera@60+inf").contains("duration `inf`"));
        assert!(err("slip@30+10:1.5").contains("slip ratio `1.5`"));
        assert!(err("slip@30+10:").contains("slip ratio ``"));
        assert!(err("lidar@30:0.5").contains("`lidar` takes no parameter"));
        assert!(err("  ").contains("nothing to read"));
        assert!(err("@60").contains("unknown sensor ``"));
    }
}
