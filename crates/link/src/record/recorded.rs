//! A recording decoded for replay: what the console was told and the robot reported
//! (to re-run the session) and what navdeck believed (to show it as recorded).

use super::reader::{RawMessage, RawRecording};
use super::{Topic, decode};
use nalgebra::Matrix3;
use navdeck_core::data::Level;
use navdeck_core::geometry::{Point2, Pose2};
use navdeck_core::map::grid::OccupancyGrid;
use navdeck_core::slam::ekf::LandmarkEstimate;
use navdeck_msgs::record::{FrameMsg, InputMsg, LogMsg, StringMsg, TruthMsg};
use navdeck_msgs::ros as msgs;
use std::collections::BTreeMap;

/// What navdeck believed at one control tick.
#[derive(Clone, Debug, PartialEq)]
pub struct Believed {
    pub time: f64,
    pub pose: Pose2,
    pub covariance: Matrix3<f64>,
    /// The message's header stamp and its bytes as recorded, to compare a re-run's
    /// byte for byte.
    pub stamp: msgs::Time,
    pub bytes: Vec<u8>,
}

/// A log line as /rosout carried it.
#[derive(Clone, Debug, PartialEq)]
pub struct LogLine {
    pub time: f64,
    pub level: Level,
    pub text: String,
    /// The robot's node that said it, or None for navdeck's own line.
    pub source: Option<String>,
}

/// Everything a replay uses, in time order, times in session seconds.
#[derive(Clone, Debug, Default)]
pub struct Recorded {
    /// How the session was started (`navdeck` metadata), and the attachments by name.
    pub session: BTreeMap<String, String>,
    pub attachments: BTreeMap<String, Vec<u8>>,
    pub inputs: Vec<InputMsg>,
    pub frames: Vec<FrameMsg>,
    pub truths: Vec<TruthMsg>,
    pub estimates: Vec<Believed>,
    pub landmarks: Vec<(f64, Vec<LandmarkEstimate>)>,
    pub maps: Vec<(f64, OccupancyGrid)>,
    pub plans: Vec<(f64, Vec<Point2>)>,
    pub commands: Vec<(f64, f64, f64)>,
    pub logs: Vec<LogLine>,
    pub modes: Vec<(f64, String)>,
    /// Wall time of session time 0, nanoseconds since the epoch.
    pub epoch_ns: u64,
    /// What could not be read: damage (with its byte offset) and undecodable messages.
    pub problems: Vec<String>,
    /// Messages on topics a replay does not use (another tool's topics).
    pub foreign: usize,
}

/// Undecodable messages named one by one at most; the rest are counted.
const NAMED_PROBLEMS: usize = 10;

impl Recorded {
    /// Decodes what `raw` holds; nothing in it can make this fail or panic.
    pub fn decode(raw: RawRecording) -> Recorded {
        let mut out = Recorded::default();
        for (name, entries) in raw.metadata {
            if name == "navdeck" {
                out.session = entries;
            }
        }
        out.attachments = raw.attachments.into_iter().collect();
        let start: f64 = out
            .session
            .get("start_time")
            .and_then(|s| s.parse().ok())
            .filter(|t: &f64| t.is_finite())
            .unwrap_or(0.0);
        // Session time 0 in wall time: the first input is at the session's start time.
        let first = raw
            .messages
            .iter()
            .find(|m| &*m.topic == Topic::Input.name())
            .map(|m| m.log_time);
        out.epoch_ns = first.map_or(0, |ns| {
            ns.saturating_sub((start.max(0.0) * 1e9).round() as u64)
        });
        let mut bad = 0usize;
        // Each message's bytes are let go once decoded, so the two never add up.
        for m in raw.messages {
            if let Err(why) = out.take(&m) {
                bad += 1;
                if bad <= NAMED_PROBLEMS {
                    let t = m.log_time.saturating_sub(out.epoch_ns) as f64 * 1e-9;
                    out.problems
                        .push(format!("{} at {t:.3} s not read: {why}", m.topic));
                }
            }
        }
        if bad > NAMED_PROBLEMS {
            out.problems
                .push(format!("{} more messages not read", bad - NAMED_PROBLEMS));
        }
        if let Some(damage) = raw.damage {
            out.problems.push(damage);
        }
        super::recorded_check::check(&mut out);
        out
    }

    fn time(&self, m: &RawMessage) -> f64 {
        m.log_time.saturating_sub(self.epoch_ns) as f64 * 1e-9
    }

    /// Takes one message; an error says why it could not be used.
    fn take(&mut self, m: &RawMessage) -> Result<(), String> {
        let Some(topic) = Topic::named(&m.topic) else {
            self.foreign += 1;
            return Ok(());
        };
        let expected = super::topics::TOPICS[topic.index()].2;
        let short = super::schema::short_name;
        if short(&m.schema) != short(expected) || &*m.encoding != "cdr" {
            self.foreign += 1;
            return Ok(());
        }
        let t = self.time(m);
        match topic {
            Topic::Input => self.inputs.push(decode(&m.data)?),
            Topic::Frame => self.frames.push(decode(&m.data)?),
            Topic::Truth => self.truths.push(decode(&m.data)?),
            Topic::Estimate => {
                let msg: msgs::PoseWithCovarianceStamped = decode(&m.data)?;
                let p = msg.pose.pose;
                let c = msg.pose.covariance.0;
                let slots = [0, 1, 5];
                let covariance = Matrix3::from_fn(|i, j| c[slots[i] * 6 + slots[j]]);
                self.estimates.push(Believed {
                    time: t,
                    pose: Pose2::new(p.position.x, p.position.y, p.orientation.yaw()),
                    covariance,
                    stamp: msg.header.stamp,
                    bytes: m.data.clone(),
                });
            }
            Topic::Landmarks => {
                let msg: msgs::MarkerArray<msgs::MarkerHumble> = decode(&m.data)?;
                self.landmarks
                    .push((t, super::landmarks::from_markers(&msg.markers)));
            }
            Topic::Map => {
                let msg: msgs::OccupancyGrid = decode(&m.data)?;
                self.maps.push((t, grid_of(msg)?));
            }
            Topic::Plan => {
                let msg: msgs::Path = decode(&m.data)?;
                let points = msg
                    .poses
                    .iter()
                    .map(|p| Point2::new(p.pose.position.x, p.pose.position.y));
                self.plans.push((t, points.collect()));
            }
            Topic::CmdVel => {
                let msg: msgs::Twist = decode(&m.data)?;
                self.commands.push((t, msg.linear.x, msg.angular.z));
            }
            Topic::Log => {
                let msg: LogMsg = decode(&m.data)?;
                let level = crate::ros2::rosout::level(msg.level);
                self.logs.push(LogLine {
                    time: t,
                    level,
                    text: msg.msg,
                    source: (msg.name != crate::ros2::NODE_NAME).then_some(msg.name),
                });
            }
            Topic::Mode => {
                let msg: StringMsg = decode(&m.data)?;
                self.modes.push((t, msg.data));
            }
            // Decoded only to check them: the re-run reads the exact frames instead.
            _ => {}
        }
        Ok(())
    }

    /// Session time the recording starts at: its first call into the console.
    pub fn start(&self) -> f64 {
        self.inputs.first().map_or(0.0, |i| i.time)
    }

    /// Session time of the last thing recorded.
    pub fn end(&self) -> f64 {
        let last_input = self.inputs.last().map_or(0.0, |i| i.time);
        let last_frame = self.frames.last().map_or(0.0, |f| f.time);
        last_input.max(last_frame)
    }

    /// How many entries of `list` (in time order, `time` giving each one's) were
    /// recorded at or before `t`.
    pub fn upto<T>(list: &[T], t: f64, time: impl Fn(&T) -> f64) -> usize {
        list.partition_point(|e| time(e) <= t + 1e-9)
    }

    /// The newest entry of `list` at or before `t`, of any time-ordered list.
    pub fn newest<T>(list: &[T], t: f64, time: impl Fn(&T) -> f64) -> Option<&T> {
        Self::upto(list, t, time).checked_sub(1).map(|i| &list[i])
    }

    /// The newest entry of a (time, value) list at or before `t`.
    pub fn at<T>(list: &[(f64, T)], t: f64) -> Option<&T> {
        Self::newest(list, t, |e| e.0).map(|e| &e.1)
    }

    /// The newest estimate at or before `t`.
    pub fn estimate_at(&self, t: f64) -> Option<&Believed> {
        Self::newest(&self.estimates, t, |e| e.time)
    }

    /// The newest truth at or before `t`.
    pub fn truth_at(&self, t: f64) -> Option<&TruthMsg> {
        Self::newest(&self.truths, t, |e| e.time)
    }

    /// An attachment's text, when it is there and is text.
    pub fn attachment_text(&self, name: &str) -> Option<&str> {
        self.attachments
            .get(name)
            .and_then(|b| std::str::from_utf8(b).ok())
    }
}

/// Cells a recorded grid may hold at most (64 M, as a planning map at most).
const MAX_CELLS: u64 = 1 << 26;

/// A nav_msgs/OccupancyGrid as the map module's grid, refused when its size lies.
fn grid_of(msg: msgs::OccupancyGrid) -> Result<OccupancyGrid, String> {
    let (w, h) = (msg.info.width as usize, msg.info.height as usize);
    let cells = u64::from(msg.info.width) * u64::from(msg.info.height);
    let data = msg.data.0;
    if cells > MAX_CELLS || data.len() as u64 != cells {
        return Err(format!(
            "a {w} x {h} grid with {} cells of data",
            data.len()
        ));
    }
    let resolution = f64::from(msg.info.resolution);
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(format!("grid resolution {resolution}"));
    }
    let o = msg.info.origin.position;
    let mut grid = OccupancyGrid::new(w, h, resolution, Point2::new(o.x, o.y), -1);
    grid.cells = data;
    Ok(grid)
}
