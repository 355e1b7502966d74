//! Recording the session (`--record`, `[record]`): what the console was told, what the
//! robot reported, what was commanded and what navdeck believed, as MCAP (`record/`).
//! `navdeck replay` reads it back.

use super::App;
use super::log::Level;
use super::mode::Mode;
use crate::data::robot::RobotConfig;
use crate::data::{Command, SensorFrame};
use crate::geometry::{Point2, Pose2};
use crate::link::ConsoleLine;
use crate::link::drive::Stepped;
use crate::link::ros2::{NODE_NAME, rosout};
use crate::msgs::picture;
use crate::msgs::record::{
    BlockMsg, FrameMsg, InputMsg, LogMsg, SightingMsg, SightingsMsg, StringMsg, TruthMsg,
};
use crate::msgs::ros::{self as msgs, Header};
use crate::record::{Recorder, Summary, Topic};
use std::collections::BTreeMap;
use std::sync::Arc;

/// A recording in progress and when its throttled topics last went out.
pub(super) struct Recording {
    recorder: Recorder,
    map_at: f64,
    map_revision: Option<u64>,
    picture_at: f64,
    image_at: f64,
    mode: Option<Mode>,
    /// The planned path last recorded: its points' count and ends (none: no path).
    path: Option<PathShape>,
    /// The blocks as last recorded (the truth carries them only when they moved).
    blocks: Vec<BlockMsg>,
    /// Session time of the truth last recorded.
    truth_at: f64,
    /// Each wheel's angle so far, radians (sensor_msgs/JointState positions).
    wheel_angles: [f64; 2],
    /// The newest body twist the wheels showed (nav_msgs/Odometry's twist).
    twist: (f64, f64),
}

/// A path told apart from another: its points' count, first and last point, and the
/// sum of its coordinates.
type PathShape = Option<(usize, Option<Point2>, Option<Point2>, f64)>;

/// The estimate at one control tick: session time, pose, covariance.
pub type TickEstimate = (f64, Pose2, nalgebra::Matrix3<f64>);

/// Frame names (REP-105).
const MAP: &str = "map";
const ODOM: &str = "odom";
const BASE: &str = "base_link";

impl App {
    /// Records the session from now on into `recorder`: the config and the twin's world
    /// as attachments, `session` (how it was started) as metadata.
    pub fn record_to(&mut self, mut recorder: Recorder, mut session: BTreeMap<String, String>) {
        let config = toml::to_string(&self.config).unwrap_or_default();
        let mut blocks = Vec::new();
        recorder.attach("config.toml", "application/toml", config.into_bytes());
        if let Some(truth) = self.link.ground_truth() {
            recorder.attach(
                "world.toml",
                "application/toml",
                truth.world().to_toml().into_bytes(),
            );
            let first = TruthMsg::of(self.now, truth);
            blocks = first.blocks.clone();
            recorder.publish(Topic::Truth, self.now, first);
        }
        session.insert("navdeck".into(), env!("CARGO_PKG_VERSION").into());
        session.insert("link".into(), self.link.label());
        session.insert("start_time".into(), format!("{}", self.now));
        recorder.metadata("navdeck", session);
        let (width, height) = self.screen;
        let resize = InputMsg::resize(self.now, width, height);
        recorder.publish(Topic::Input, self.now, resize);
        // Lines not yet passed to the link go to it alone; the recording takes the whole
        // book so far, then every new line with the link.
        self.pass_log();
        let earlier = self.log.expanded();
        self.log.keep_fresh();
        self.recording = Some(Recording {
            recorder,
            map_at: f64::NEG_INFINITY,
            map_revision: None,
            picture_at: f64::NEG_INFINITY,
            image_at: f64::NEG_INFINITY,
            mode: None,
            path: None,
            blocks,
            truth_at: self.now,
            wheel_angles: [0.0; 2],
            twist: (0.0, 0.0),
        });
        self.record_lines(earlier);
        self.pass_log();
    }

    /// Where the session is being recorded, if it is.
    pub fn recording_path(&self) -> Option<&std::path::Path> {
        self.recording.as_ref().map(|r| r.recorder.path())
    }

    /// Waits until the recording's writer has written everything so far (benchmarks).
    pub fn wait_for_recording(&mut self) {
        if let Some(r) = self.recording.as_mut() {
            r.recorder.wait_for_writer();
        }
    }

    /// Closes the recording and says what it holds.
    pub fn finish_recording(&mut self) -> Option<Result<Summary, String>> {
        self.pass_log();
        self.recording.take().map(|r| r.recorder.finish())
    }

    /// One call into the console, so a replay can make it again.
    pub(super) fn record_input(&mut self, msg: InputMsg) {
        if let Some(r) = self.recording.as_mut() {
            let t = msg.time;
            r.recorder.publish(Topic::Input, t, msg);
        }
    }

    /// The log lines written since the last call, to the link that passes them on
    /// (/rosout) and into the recording as /rosout carries them.
    pub(super) fn pass_log(&mut self) {
        if self.recording.is_none() && !self.link.takes_log() {
            return;
        }
        let fresh = self.log.take_fresh();
        if self.link.takes_log() && !fresh.is_empty() {
            let lines: Vec<ConsoleLine> = fresh
                .iter()
                .map(|e| ConsoleLine {
                    level: e.level,
                    text: e.text.clone(),
                    source: e.source.clone(),
                })
                .collect();
            self.link.log(&lines);
        }
        self.record_lines(fresh);
    }

    fn record_lines(&mut self, lines: Vec<super::log::Entry>) {
        let Some(r) = self.recording.as_mut() else {
            return;
        };
        if let Some(why) = r.recorder.take_problem() {
            self.log.push(self.now, Level::Warn, why);
        }
        for e in lines {
            let msg = LogMsg {
                stamp: r.recorder.stamp(e.time),
                level: rosout::severity(e.level),
                name: e.source.unwrap_or_else(|| NODE_NAME.into()),
                msg: e.text,
                ..LogMsg::default()
            };
            r.recorder.publish(Topic::Log, e.time, msg);
        }
        r.recorder.hand_over_due(self.now);
    }

    /// What one control step polled and sent, and the twin's truth after it.
    pub(super) fn record_step(&mut self, t: f64, stepped: &Stepped) {
        let Some(r) = self.recording.as_mut() else {
            return;
        };
        // One copy of what the poll brought, shared by the messages built from it on the
        // writer's thread.
        let frame = Arc::new(stepped.frame.clone());
        let failure = stepped.failure.clone().unwrap_or_default();
        let polled = frame.clone();
        r.recorder.publish_with(Topic::Frame, t, move || {
            let polled = polled.as_ref().as_ref().ok_or(failure.as_str());
            FrameMsg::from_poll(t, polled)
        });
        if let Some(status) = frame.as_ref().as_ref().and_then(|f| f.camera.as_ref())
            && let Some(thumb) = &status.thumbnail
        {
            let period = self.config.record.image_period;
            if period > 0.0 && t - r.image_at >= period - 1e-9 {
                r.image_at = t;
                let image = msgs::Image {
                    header: Header::new(r.recorder.stamp(t), "camera"),
                    height: thumb.height as u32,
                    width: thumb.width as u32,
                    encoding: "mono8".into(),
                    is_bigendian: 0,
                    step: thumb.width as u32,
                    data: thumb.pixels.clone(),
                };
                r.recorder.publish(Topic::Image, t, image);
            }
        }
        r.sensors(t, frame, &self.config.robot);
        if let Some(command) = &stepped.command {
            r.command(t, command);
        }
        // The truth when it may have changed: time passed, or a block moved.
        if let Some(truth) = self.link.ground_truth() {
            let blocks = truth.blocks();
            let moved = blocks.len() != r.blocks.len()
                || blocks.iter().zip(&r.blocks).any(|(b, m)| !m.is(b));
            if moved {
                r.blocks = blocks.iter().map(BlockMsg::of).collect();
            }
            if moved || t > r.truth_at {
                r.truth_at = t;
                let mut msg = TruthMsg::pose_of(t, truth);
                if moved {
                    msg.blocks = r.blocks.clone();
                }
                r.recorder.publish(Topic::Truth, t, msg);
            }
        }
    }

    /// From now on each control tick's estimate is kept for `take_tick_estimates`.
    pub fn watch_estimates(&mut self) {
        self.watched = Some(Vec::new());
    }

    /// The estimates of the control ticks since the last call (with `watch_estimates`).
    pub fn take_tick_estimates(&mut self) -> Vec<TickEstimate> {
        self.watched
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    /// The zero velocity `stop` sent outside a control step (quit, signal, lost input).
    pub(super) fn record_stop(&mut self) {
        let t = self.now;
        if let Some(r) = self.recording.as_mut() {
            r.command(t, &Command::STOP);
        }
    }

    /// What navdeck believed at a control tick: the pose every tick, the rest throttled.
    pub(super) fn record_tick(&mut self, t: f64) {
        if let Some(watched) = self.watched.as_mut() {
            let pilot = &self.pilot;
            watched.push((t, pilot.estimated_pose(), pilot.pose_covariance()));
        }
        let Some(r) = self.recording.as_mut() else {
            return;
        };
        let pilot = &self.pilot;
        let stamp = r.recorder.stamp(t);
        let pose = pilot.estimated_pose();
        let cov = pilot.pose_covariance();
        r.recorder.publish_with(Topic::Estimate, t, move || {
            picture::pose_with_covariance(pose, &cov, stamp, MAP)
        });
        let odom = pilot.odometry_pose();
        r.recorder.publish_with(Topic::Tf, t, move || {
            let mut tf = picture::transform(MAP, ODOM, picture::map_to_odom(pose, odom), stamp);
            tf.transforms
                .extend(picture::transform(ODOM, BASE, odom, stamp).transforms);
            tf
        });
        let twist = r.twist;
        r.recorder
            .publish_with(Topic::Odometry, t, move || odometry(odom, twist, stamp));
        let mode = pilot.mode();
        if r.mode != Some(mode) {
            r.mode = Some(mode);
            let data = mode.label().to_string();
            r.recorder.publish(Topic::Mode, t, StringMsg { data });
        }
        let config = &self.config.record;
        if t - r.picture_at >= config.picture_period - 1e-9 {
            r.picture_at = t;
            let landmarks: Vec<_> = pilot.slam().landmarks().collect();
            r.recorder
                .publish_with(Topic::Landmarks, t, move || msgs::MarkerArray {
                    markers: crate::record::landmarks::markers(&landmarks, stamp, MAP),
                });
        }
        // The path only when it changed: told apart by its points' count, ends and the sum
        // of its coordinates, without copying it every tick.
        let points = pilot.route().map(|route| &route.plan.trajectory.points);
        let shape = points.map(|p| {
            let end = |q: Option<&crate::plan::trajectory::TrajectoryPoint>| q.map(|q| q.position);
            let sum: f64 = p.iter().map(|q| q.position.x + q.position.y).sum();
            (p.len(), end(p.first()), end(p.last()), sum)
        });
        if r.path != Some(shape) {
            r.path = Some(shape);
            let points: Vec<_> = points.into_iter().flatten().map(|p| p.position).collect();
            r.recorder
                .publish_with(Topic::Plan, t, move || picture::path(&points, stamp, MAP));
        }
        let belief = pilot.belief();
        if r.map_revision != Some(belief.revision()) && t - r.map_at >= config.map_period - 1e-9 {
            r.map_at = t;
            r.map_revision = Some(belief.revision());
            // Two arrays copied here; the grid is made on the writer's thread.
            let evidence = belief.evidence_snapshot();
            r.recorder.publish_with(Topic::Map, t, move || {
                picture::grid(&evidence.into_grid(), stamp, MAP)
            });
        }
    }
}

impl Recording {
    /// The standard sensor topics for what `frame` brought.
    fn sensors(&mut self, t: f64, polled: Arc<Option<SensorFrame>>, robot: &RobotConfig) {
        let Some(frame) = polled.as_ref() else {
            return;
        };
        let stamp = self.recorder.stamp(t);
        if let Some(w) = frame.wheels.filter(|_| frame.elapsed > 0.0) {
            self.wheel_angles[0] += w.left / robot.wheel_radius;
            self.wheel_angles[1] += w.right / robot.wheel_radius;
            // Differential drive: v = (l + r) / 2, ω = (r − l) / track (seed 001, 2.1).
            let v = 0.5 * (w.left + w.right) / frame.elapsed;
            let omega = (w.right - w.left) / robot.track / frame.elapsed;
            self.twist = (v, omega);
            let (wheels, arm) = (self.wheel_angles, frame.arm);
            self.recorder.publish_with(Topic::JointStates, t, move || {
                joint_states(wheels, arm, stamp)
            });
        }
        if frame.scan.is_some() {
            let polled = polled.clone();
            self.recorder.publish_with(Topic::Scan, t, move || {
                let scan = polled.as_ref().as_ref().and_then(|f| f.scan.as_ref());
                scan.map(|s| laser_scan(s, stamp)).unwrap_or_default()
            });
        }
        if frame.sightings.is_some() {
            self.recorder.publish_with(Topic::Sightings, t, move || {
                let list = polled.as_ref().as_ref().and_then(|f| f.sightings.as_ref());
                SightingsMsg {
                    header: Header::new(stamp, BASE),
                    sightings: list.into_iter().flatten().map(SightingMsg::from).collect(),
                }
            });
        }
    }

    fn command(&mut self, t: f64, command: &Command) {
        let twist = msgs::Twist::planar(command.twist.linear, command.twist.angular);
        self.recorder.publish(Topic::CmdVel, t, twist);
    }
}

/// sensor_msgs/JointState: the wheels' angles (radians), then an arm's joints.
fn joint_states(
    wheels: [f64; 2],
    arm: Option<crate::data::ArmState>,
    stamp: msgs::Time,
) -> msgs::JointState {
    let mut joints = msgs::JointState {
        header: Header::new(stamp, BASE),
        name: vec!["wheel_left_joint".into(), "wheel_right_joint".into()],
        position: wheels.to_vec(),
        ..msgs::JointState::default()
    };
    if let Some(arm) = arm {
        joints
            .name
            .extend(["joint1", "joint2", "joint3", "joint4"].map(String::from));
        joints.position.extend(arm.joints);
    }
    joints
}

/// A scan as sensor_msgs/LaserScan (its angles narrowed to float32).
fn laser_scan(scan: &crate::data::LaserScan, stamp: msgs::Time) -> msgs::LaserScan {
    let n = scan.ranges.len().max(1) as f64;
    msgs::LaserScan {
        header: Header::new(stamp, "base_scan"),
        angle_min: scan.angle_min as f32,
        angle_max: (scan.angle_min + (n - 1.0) * scan.angle_increment) as f32,
        angle_increment: scan.angle_increment as f32,
        range_min: scan.range_min as f32,
        range_max: scan.range_max as f32,
        ranges: scan.ranges.clone(),
        ..msgs::LaserScan::default()
    }
}

/// nav_msgs/Odometry of the wheels' dead reckoning.
fn odometry(odom: Pose2, twist: (f64, f64), stamp: msgs::Time) -> msgs::Odometry {
    msgs::Odometry {
        header: Header::new(stamp, ODOM),
        child_frame_id: BASE.into(),
        pose: msgs::PoseWithCovariance {
            pose: picture::pose(odom),
            ..msgs::PoseWithCovariance::default()
        },
        twist: msgs::TwistWithCovariance {
            twist: msgs::Twist::planar(twist.0, twist.1),
            ..msgs::TwistWithCovariance::default()
        },
    }
}
