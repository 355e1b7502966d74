//! The session as it runs, into a recording (`--record`, `[record]`): what each control
//! step polled and sent, the twin's truth after it, and at each control tick what navdeck
//! believed (estimate, tf, odometry, mode, landmarks, plan, map). The console records its
//! own calls and log lines beside these (`navdeck` package, `app/recording.rs`).

use super::frames::Frames;
use crate::record::Recorder;
use crate::record::Topic;
use crate::record::config::RecordConfig;
use navdeck_core::data::robot::RobotConfig;
use navdeck_core::data::{Command, SensorFrame};
use navdeck_core::geometry::{Point2, Pose2};
use navdeck_core::sim::GroundTruth;
use navdeck_msgs::picture;
use navdeck_msgs::record::{BlockMsg, FrameMsg, SightingMsg, SightingsMsg, StringMsg, TruthMsg};
use navdeck_msgs::ros::{self as msgs, Header};
use navdeck_pilot::mode::Mode;
use navdeck_pilot::{Output, Pilot};
use std::sync::Arc;

/// A recording in progress and when its throttled topics last went out.
pub struct Recording {
    recorder: Recorder,
    robot: RobotConfig,
    config: RecordConfig,
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
    /// Session time the recording started.
    started: f64,
    /// The frames its messages are in.
    frames: Arc<Frames>,
}

/// A path told apart from another: its points' count, first and last point, and the
/// sum of its coordinates.
type PathShape = Option<(usize, Option<Point2>, Option<Point2>, f64)>;

impl Recording {
    /// Records into `recorder` from session time `now`; `blocks` as the truth last
    /// recorded showed them; `shared_map`: the robot's map frame is its fleet's one world.
    pub fn new(
        recorder: Recorder,
        robot: RobotConfig,
        config: RecordConfig,
        (blocks, now): (Vec<BlockMsg>, f64),
        shared_map: bool,
    ) -> Self {
        let frames = Arc::new(Frames::under(recorder.name_prefix(), shared_map));
        Self {
            frames,
            recorder,
            robot,
            config,
            map_at: f64::NEG_INFINITY,
            map_revision: None,
            picture_at: f64::NEG_INFINITY,
            image_at: f64::NEG_INFINITY,
            mode: None,
            path: None,
            blocks,
            truth_at: now,
            started: now,
            wheel_angles: [0.0; 2],
            twist: (0.0, 0.0),
        }
    }

    pub fn recorder(&mut self) -> &mut Recorder {
        &mut self.recorder
    }

    /// Where the recording is being written.
    pub fn path(&self) -> &std::path::Path {
        self.recorder.path()
    }

    /// Session time the recording started.
    pub fn started(&self) -> f64 {
        self.started
    }

    /// Bytes in the recording's file so far.
    pub fn bytes_written(&self) -> u64 {
        self.recorder.bytes_written()
    }

    pub fn into_recorder(self) -> Recorder {
        self.recorder
    }

    /// What one control step polled and sent, and the twin's truth after it.
    pub(super) fn step(&mut self, t: f64, out: &Output, truth: Option<&dyn GroundTruth>) {
        let r = self;
        // One copy of what the poll brought, shared by the messages built from it on the
        // writer's thread.
        let frame = Arc::new(out.frame.clone());
        let failure = out.failure.clone().unwrap_or_default();
        let polled = frame.clone();
        r.recorder.publish_with(Topic::Frame, t, move || {
            let polled = polled.as_ref().as_ref().ok_or(failure.as_str());
            FrameMsg::from_poll(t, polled)
        });
        if let Some(status) = frame.as_ref().as_ref().and_then(|f| f.camera.as_ref())
            && let Some(thumb) = &status.thumbnail
        {
            let period = r.config.image_period;
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
        r.sensors(t, frame);
        if let Some(command) = &out.command {
            r.command(t, command);
        }
        // The truth when it may have changed: time passed, or a block moved.
        if let Some(truth) = truth {
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

    /// What navdeck believed at a control tick: the pose every tick, the rest throttled.
    pub(super) fn tick(&mut self, t: f64, pilot: &Pilot) {
        let r = self;
        let stamp = r.recorder.stamp(t);
        let pose = pilot.estimated_pose();
        let cov = pilot.pose_covariance();
        let f = r.frames.clone();
        r.recorder.publish_with(Topic::Estimate, t, move || {
            picture::pose_with_covariance(pose, &cov, stamp, &f.map)
        });
        let odom = pilot.odometry_pose();
        let f = r.frames.clone();
        r.recorder.publish_with(Topic::Tf, t, move || {
            let to_odom = picture::map_to_odom(pose, odom);
            let mut tf = picture::transform(&f.map, &f.odom, to_odom, stamp);
            tf.transforms
                .extend(picture::transform(&f.odom, &f.base, odom, stamp).transforms);
            tf
        });
        let (twist, f) = (r.twist, r.frames.clone());
        r.recorder
            .publish_with(Topic::Odometry, t, move || odometry(odom, twist, stamp, &f));
        let mode = pilot.mode();
        if r.mode != Some(mode) {
            r.mode = Some(mode);
            let data = mode.label().to_string();
            r.recorder.publish(Topic::Mode, t, StringMsg { data });
        }
        let config = &r.config;
        // The first seconds are recorded more often, the gap doubling from half a second
        // up to the period: a replay's first seconds then show the map and landmarks the
        // log speaks of.
        let started = r.started;
        let ramp = |period: f64, last: f64| period.min((last - started).max(0.5));
        if t - r.picture_at >= ramp(config.picture_period, r.picture_at) - 1e-9 {
            r.picture_at = t;
            let landmarks: Vec<_> = pilot.slam().landmarks().collect();
            let f = r.frames.clone();
            r.recorder
                .publish_with(Topic::Landmarks, t, move || msgs::MarkerArray {
                    markers: crate::record::landmarks::markers(&landmarks, stamp, &f.map),
                });
        }
        // The path only when it changed: told apart by its points' count, ends and the sum
        // of its coordinates, without copying it every tick.
        let points = pilot.route().map(|route| &route.plan.trajectory.points);
        let shape = points.map(|p| {
            let end =
                |q: Option<&navdeck_core::plan::trajectory::TrajectoryPoint>| q.map(|q| q.position);
            let sum: f64 = p.iter().map(|q| q.position.x + q.position.y).sum();
            (p.len(), end(p.first()), end(p.last()), sum)
        });
        if r.path != Some(shape) {
            r.path = Some(shape);
            let points: Vec<_> = points.into_iter().flatten().map(|p| p.position).collect();
            let f = r.frames.clone();
            r.recorder.publish_with(Topic::Plan, t, move || {
                picture::path(&points, stamp, &f.map)
            });
        }
        let belief = pilot.belief();
        if r.map_revision != Some(belief.revision())
            && t - r.map_at >= ramp(config.map_period, r.map_at) - 1e-9
        {
            r.map_at = t;
            r.map_revision = Some(belief.revision());
            // Two arrays copied here; the grid is made on the writer's thread.
            let evidence = belief.evidence_snapshot();
            let f = r.frames.clone();
            r.recorder.publish_with(Topic::Map, t, move || {
                picture::grid(&evidence.into_grid(), stamp, &f.map)
            });
        }
    }

    /// The standard sensor topics for what `frame` brought.
    fn sensors(&mut self, t: f64, polled: Arc<Option<SensorFrame>>) {
        let robot = &self.robot;
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
            let (wheels, arm, f) = (self.wheel_angles, frame.arm, self.frames.clone());
            self.recorder.publish_with(Topic::JointStates, t, move || {
                joint_states(wheels, arm, stamp, &f.base)
            });
        }
        if frame.scan.is_some() {
            let (polled, frames) = (polled.clone(), self.frames.clone());
            self.recorder.publish_with(Topic::Scan, t, move || {
                let scan = polled.as_ref().as_ref().and_then(|f| f.scan.as_ref());
                scan.map(|s| laser_scan(s, stamp, &frames.scan))
                    .unwrap_or_default()
            });
        }
        if frame.sightings.is_some() {
            let frames = self.frames.clone();
            self.recorder.publish_with(Topic::Sightings, t, move || {
                let list = polled.as_ref().as_ref().and_then(|f| f.sightings.as_ref());
                SightingsMsg {
                    header: Header::new(stamp, &frames.base),
                    sightings: list.into_iter().flatten().map(SightingMsg::from).collect(),
                }
            });
        }
    }

    /// A command sent at `t` (a control step's, or the zero velocity of a stop).
    pub fn command(&mut self, t: f64, command: &Command) {
        let twist = msgs::Twist::planar(command.twist.linear, command.twist.angular);
        self.recorder.publish(Topic::CmdVel, t, twist);
    }
}

/// sensor_msgs/JointState: the wheels' angles (radians), then an arm's joints.
fn joint_states(
    wheels: [f64; 2],
    arm: Option<navdeck_core::data::ArmState>,
    stamp: msgs::Time,
    base: &str,
) -> msgs::JointState {
    let mut joints = msgs::JointState {
        header: Header::new(stamp, base),
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
fn laser_scan(
    scan: &navdeck_core::data::LaserScan,
    stamp: msgs::Time,
    frame: &str,
) -> msgs::LaserScan {
    let n = scan.ranges.len().max(1) as f64;
    msgs::LaserScan {
        header: Header::new(stamp, frame),
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
fn odometry(odom: Pose2, twist: (f64, f64), stamp: msgs::Time, f: &Frames) -> msgs::Odometry {
    msgs::Odometry {
        header: Header::new(stamp, &f.odom),
        child_frame_id: f.base.clone(),
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
