//! The twin's marker camera (ideal, or rendered and read by the ArUco detector) and its
//! lidar: when each is due, and what each saw last until the next frame is taken.

use crate::data::{LaserScan, MarkerSighting};
use crate::geometry::{Pose2, Segment};
use crate::perception::frame::CameraStatus;
use crate::sim::Marker;
use crate::sim::camera::Camera;
use crate::sim::clock::SensorClock;
use crate::sim::config::SimConfig;
use crate::sim::lidar::Lidar;
use rand_chacha::ChaCha8Rng;

/// What the camera reports of a frame while a camera fault lasts.
const DARK: &str = "camera dark (injected fault)";

/// The camera and lidar, their clocks, and their newest readings not yet taken.
#[derive(Clone, Debug)]
pub(super) struct Sensors {
    camera: Camera,
    camera_clock: SensorClock,
    lidar: Option<(Lidar, SensorClock)>,
    sightings: Option<Vec<MarkerSighting>>,
    camera_status: Option<CameraStatus>,
    /// The rendered camera and ArUco detector replacing the ideal marker sensor.
    #[cfg(feature = "vision")]
    rendered: Option<Box<crate::sim::rendered_camera::RenderedCamera>>,
    scan: Option<LaserScan>,
    /// The lane camera's newest sighting not yet taken.
    pub(super) lane: Option<crate::data::LaneSighting>,
    /// The lane camera and its clock, on a world with a track.
    #[cfg(feature = "vision")]
    pub(super) lane_rig: Option<super::lane::LaneRig>,
    /// The tag map on the floor and the tag camera, when tags are laid (`tags.rs`).
    pub(super) tag_rig: Option<super::tags::TagRig>,
}

impl Sensors {
    /// The sensors of `sim`; a lidar that is not enabled is left out.
    pub(super) fn new(sim: &SimConfig) -> Self {
        let lidar = sim
            .lidar
            .enabled
            .then(|| (Lidar::new(&sim.lidar), SensorClock::new(sim.lidar.rate_hz)));
        Self {
            camera: Camera::new(&sim.camera),
            camera_clock: SensorClock::new(sim.camera.rate_hz),
            lidar,
            sightings: None,
            camera_status: None,
            #[cfg(feature = "vision")]
            rendered: None,
            scan: None,
            lane: None,
            #[cfg(feature = "vision")]
            lane_rig: None,
            tag_rig: None,
        }
    }

    /// Whether a camera frame is due at twin time `now`.
    pub(super) fn camera_due(&mut self, now: f64) -> bool {
        self.camera_clock.due(now)
    }

    /// Whether there is a lidar and a scan is due at twin time `now`.
    pub(super) fn lidar_due(&mut self, now: f64) -> bool {
        self.lidar.as_mut().is_some_and(|(_, clock)| clock.due(now))
    }

    /// A camera frame from `pose`: the rendered camera's, else the ideal sensor's.
    pub(super) fn capture_camera<'a>(
        &mut self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) {
        #[cfg(feature = "vision")]
        if let Some(camera) = self.rendered.as_mut() {
            let (sightings, status) = camera.capture(pose, markers, occluders, rng);
            self.sightings = Some(sightings);
            self.camera_status = Some(status);
            return;
        }
        self.sightings = Some(self.camera.observe(pose, markers, occluders, rng));
    }

    /// A frame from a dark (or covered) camera: nothing seen in it, and a status saying it
    /// was dark, as a real pipeline's brightness check would.
    pub(super) fn capture_dark(&mut self) {
        self.sightings = Some(Vec::new());
        self.camera_status = Some(CameraStatus::failed(DARK));
    }

    /// A lidar scan from `pose`, when there is a lidar.
    pub(super) fn capture_scan(
        &mut self,
        pose: Pose2,
        solids: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) {
        if let Some((lidar, _)) = self.lidar.as_mut() {
            self.scan = Some(lidar.scan(pose, solids, rng));
        }
    }

    pub(super) fn take_sightings(&mut self) -> Option<Vec<MarkerSighting>> {
        self.sightings.take()
    }

    pub(super) fn take_scan(&mut self) -> Option<LaserScan> {
        self.scan.take()
    }

    pub(super) fn take_lane(&mut self) -> Option<crate::data::LaneSighting> {
        self.lane.take()
    }

    pub(super) fn take_camera_status(&mut self) -> Option<CameraStatus> {
        self.camera_status.take()
    }

    /// Replaces the ideal marker sensor by a rendered camera drawing `frames`, which sees
    /// no further than the ideal sensor did. Returns the camera's detector.
    #[cfg(feature = "vision")]
    pub(super) fn use_rendered_camera(
        &mut self,
        vision: &crate::perception::config::VisionConfig,
        stopwatch: Option<std::sync::Arc<dyn crate::clock::Clock>>,
        frames: crate::sim::CameraFrames,
    ) -> Result<&crate::perception::aruco::Detector, crate::perception::aruco::VisionError> {
        let mut camera = crate::sim::rendered_camera::RenderedCamera::new(
            vision,
            self.camera.max_range(),
            stopwatch,
        )?;
        camera.set_frames(frames);
        Ok(self.rendered.insert(Box::new(camera)).detector())
    }
}
