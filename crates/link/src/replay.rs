//! A recording as a robot: `poll` hands back, in order, the frames the robot reported
//! when the session was recorded, so today's estimator and planner re-run on them.
//! Commands go nowhere; a twin's ground truth (and its world) comes from the recording.

use super::{Command, LinkError, RobotLink, SensorFrame};
use navdeck_core::geometry::{Pose2, Twist};
use navdeck_core::sim::{BlockState, GroundTruth, World};
use navdeck_msgs::record::{FrameMsg, TruthMsg};

/// The twin's truth as recorded.
pub struct RecordedTruth {
    world: World,
    now: TruthMsg,
    blocks: Vec<BlockState>,
}

impl RecordedTruth {
    fn take(&mut self, msg: &TruthMsg) {
        for (state, b) in self.blocks.iter_mut().zip(&msg.blocks) {
            state.pose = Pose2::new(b.x, b.y, b.theta);
            state.held = b.held;
        }
        // The blocks live in `blocks`; the rest of the truth is the newest message's.
        self.now = TruthMsg {
            blocks: Vec::new(),
            ..msg.clone()
        };
    }
}

impl GroundTruth for RecordedTruth {
    fn world(&self) -> &World {
        &self.world
    }
    fn time(&self) -> f64 {
        self.now.time
    }
    fn pose(&self) -> Pose2 {
        self.now.pose()
    }
    fn velocity(&self) -> Twist {
        Twist::new(self.now.linear, self.now.angular)
    }
    fn command(&self) -> Twist {
        Twist::new(self.now.command_linear, self.now.command_angular)
    }
    fn blocks(&self) -> &[BlockState] {
        &self.blocks
    }
    fn collisions(&self) -> u32 {
        self.now.collisions
    }
    fn distance_driven(&self) -> f64 {
        self.now.distance_driven
    }
}

/// The recorded robot.
pub struct ReplayLink {
    label: String,
    frames: Vec<FrameMsg>,
    next_frame: usize,
    truths: Vec<TruthMsg>,
    next_truth: usize,
    truth: Option<RecordedTruth>,
}

impl ReplayLink {
    /// The robot of a recording: its frames and, for a twin, its world and truth (the
    /// first truth is where the robot started).
    pub fn new(
        label: String,
        frames: Vec<FrameMsg>,
        truths: Vec<TruthMsg>,
        world: Option<World>,
    ) -> Self {
        let mut link = Self {
            label,
            frames,
            next_frame: 0,
            truths,
            next_truth: 0,
            truth: None,
        };
        if let (Some(world), Some(first)) = (world, link.truths.first().cloned()) {
            let blocks = world.blocks.iter().map(BlockState::from_block).collect();
            let mut truth = RecordedTruth {
                world,
                now: first.clone(),
                blocks,
            };
            truth.take(&first);
            link.truth = Some(truth);
            link.next_truth = 1;
        }
        link
    }

    fn advance_truth(&mut self, now: f64) {
        let Some(truth) = self.truth.as_mut() else {
            return;
        };
        while let Some(msg) = self.truths.get(self.next_truth) {
            if msg.time > now + 1e-9 {
                break;
            }
            truth.take(msg);
            self.next_truth += 1;
        }
    }
}

impl RobotLink for ReplayLink {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn send(&mut self, _command: &Command) -> Result<(), LinkError> {
        Ok(())
    }

    /// The next recorded frame when it was polled at or before `now` (one poll, one
    /// frame, however many share its time); frames the re-run skipped over (a changed
    /// schedule) come merged with it; nothing due is an empty frame.
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        self.advance_truth(now);
        let rest = &self.frames[self.next_frame..];
        let skipped = rest.iter().take_while(|f| f.time < now - 1e-9).count();
        let due = skipped + usize::from(rest.get(skipped).is_some_and(|f| f.time <= now + 1e-9));
        let taken = &rest[..due];
        self.next_frame += due;
        match taken {
            [] => Ok(SensorFrame {
                stamp: now,
                ..SensorFrame::default()
            }),
            [one] => one.to_poll().map_err(LinkError::Replayed),
            many => Ok(merge(many)),
        }
    }

    fn stop(&mut self) {}

    fn ground_truth(&self) -> Option<&dyn GroundTruth> {
        self.truth.as_ref().map(|t| t as &dyn GroundTruth)
    }
}

/// Several frames as one: wheel travel and time add up, the newest of the rest counts.
fn merge(frames: &[FrameMsg]) -> SensorFrame {
    let mut out = SensorFrame::default();
    for f in frames {
        let Ok(frame) = f.to_poll() else { continue };
        out.stamp = frame.stamp;
        out.elapsed += frame.elapsed;
        if let Some(w) = frame.wheels {
            let sum = out.wheels.get_or_insert_default();
            sum.left += w.left;
            sum.right += w.right;
        }
        out.sightings = frame.sightings.or(out.sightings);
        out.scan = frame.scan.or(out.scan);
        out.gripper = frame.gripper.or(out.gripper);
        out.camera = frame.camera.or(out.camera);
        out.initial_pose = frame.initial_pose.or(out.initial_pose);
        out.goal = frame.goal.or(out.goal);
        out.arm = frame.arm.or(out.arm);
        out.tags = frame.tags.or(out.tags);
    }
    out
}
