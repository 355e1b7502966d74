//! A camera beside any link (`--camera`): the robot's link drives and senses as before,
//! and the camera pipeline's newest detection rides along in each frame.

use super::{Command, ConsoleLine, LinkError, Notice, Picture, RobotLink, SensorFrame};
use navdeck_core::perception::pipeline::CameraPipeline;

pub struct WithCamera {
    inner: Box<dyn RobotLink>,
    pipeline: CameraPipeline,
    source: String,
}

impl WithCamera {
    pub fn new(inner: Box<dyn RobotLink>, pipeline: CameraPipeline, source: String) -> Self {
        Self {
            inner,
            pipeline,
            source,
        }
    }
}

impl RobotLink for WithCamera {
    fn label(&self) -> String {
        format!("{} + camera {}", self.inner.label(), self.source)
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.inner.send(command)
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        let mut frame = self.inner.poll(now)?;
        if let Some((sightings, status, lane)) = self.pipeline.take_latest() {
            frame.sightings = Some(sightings);
            frame.camera = Some(status);
            frame.lane = lane;
        }
        Ok(frame)
    }

    fn stop(&mut self) {
        self.inner.stop();
    }

    fn picture_period(&self) -> Option<f64> {
        self.inner.picture_period()
    }

    fn show(&mut self, picture: &Picture) {
        self.inner.show(picture);
    }

    fn ground_truth(&self) -> Option<&dyn navdeck_core::sim::GroundTruth> {
        self.inner.ground_truth()
    }

    fn faults(&self) -> Option<&navdeck_core::sim::Faults> {
        self.inner.faults()
    }

    fn faults_mut(&mut self) -> Option<&mut navdeck_core::sim::Faults> {
        self.inner.faults_mut()
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        self.inner.take_notes()
    }

    fn details(&self, now: f64) -> Vec<(&'static str, String)> {
        self.inner.details(now)
    }

    fn teleport(&mut self, pose: navdeck_core::geometry::Pose2) -> bool {
        self.inner.teleport(pose)
    }

    fn takes_log(&self) -> bool {
        self.inner.takes_log()
    }

    fn log(&mut self, lines: &[ConsoleLine]) {
        self.inner.log(lines);
    }
}
