//! A camera on its own threads, as seed 001 runs it ("Camera Thread -> LifoQueue -> Main
//! Loop (latest frame)"): one thread grabs frames into a one-frame slot, a second takes
//! the newest, detects the markers and leaves its result in another slot for the console.
//! A frame not yet detected when a newer one arrives is dropped: latest frame wins.

use super::aruco::Detector;
use super::colour::CameraImage;
use super::frame::CameraStatus;
use super::lane::LanePipeline;
use crate::clock::Clock;
use crate::data::LaneSighting;
use crate::data::MarkerSighting;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

/// How long the detection thread waits for a frame before looking at the stop flag.
const WAIT: Duration = Duration::from_millis(100);

/// Where frames come from: a V4L2 device, a ROS 2 image topic, a test.
pub trait FrameSource: Send + 'static {
    /// The next frame; `Ok(None)` when none came within the source's own timeout.
    fn grab(&mut self) -> Result<Option<CameraImage>, String>;

    /// The camera's calibration as its driver publishes it (ROS 2's camera_info), when
    /// a new one came since the last call: `Err` for one that cannot be used. Sources
    /// without one give None.
    fn take_calibration(&mut self) -> Option<Result<super::intrinsics::Intrinsics, String>> {
        None
    }
}

/// A one-value mailbox: putting replaces what was not yet taken.
pub(super) struct Slot<T> {
    value: Mutex<Option<T>>,
    filled: Condvar,
}

impl<T> Slot<T> {
    pub(super) fn new() -> Self {
        Self {
            value: Mutex::new(None),
            filled: Condvar::new(),
        }
    }

    /// Stores `v`; true when it replaced a value nobody took.
    pub(super) fn put(&self, v: T) -> bool {
        let replaced = self.value.lock().unwrap().replace(v).is_some();
        self.filled.notify_one();
        replaced
    }

    pub(super) fn take(&self) -> Option<T> {
        self.value.lock().unwrap().take()
    }

    pub(super) fn take_waiting(&self, timeout: Duration) -> Option<T> {
        let guard = self.value.lock().unwrap();
        let (mut guard, _) = self
            .filled
            .wait_timeout_while(guard, timeout, |v| v.is_none())
            .unwrap();
        guard.take()
    }
}

/// Frames counted by the pipeline.
#[derive(Debug, Default)]
pub struct PipelineCounts {
    pub grabbed: AtomicU64,
    /// Frames replaced by a newer one before detection got to them.
    pub dropped: AtomicU64,
    pub detected: AtomicU64,
}

/// What one frame gave: the markers and the camera's status, and the lane pipeline's
/// sighting when lane mode reads the same camera.
type Result_ = (Vec<MarkerSighting>, CameraStatus, Option<LaneSighting>);

pub struct CameraPipeline {
    results: Arc<Slot<Result_>>,
    counts: Arc<PipelineCounts>,
    stop: Arc<AtomicBool>,
    threads: Vec<JoinHandle<()>>,
}

impl CameraPipeline {
    pub fn start(
        mut source: Box<dyn FrameSource>,
        detector: Detector,
        mut lane: Option<LanePipeline>,
        stopwatch: Option<Arc<dyn Clock>>,
    ) -> Self {
        let frames = Arc::new(Slot::<CameraImage>::new());
        let results = Arc::new(Slot::new());
        let counts = Arc::new(PipelineCounts::default());
        let stop = Arc::new(AtomicBool::new(false));
        let grabber = {
            let (frames, results, counts, stop) = (
                frames.clone(),
                results.clone(),
                counts.clone(),
                stop.clone(),
            );
            std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    match source.grab() {
                        Ok(Some(frame)) => {
                            counts.grabbed.fetch_add(1, Ordering::SeqCst);
                            if frames.put(frame) {
                                counts.dropped.fetch_add(1, Ordering::SeqCst);
                            }
                        }
                        Ok(None) => {}
                        Err(e) => {
                            let lane = Some(LaneSighting::failed(e.clone()));
                            results.put((Vec::new(), CameraStatus::failed(e), lane));
                            // A camera that fails is asked again, not hammered.
                            std::thread::sleep(Duration::from_millis(500));
                        }
                    }
                }
            })
        };
        let detecting = {
            let (frames, results, counts, stop) =
                (frames, results.clone(), counts.clone(), stop.clone());
            std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    let Some(frame) = frames.take_waiting(WAIT) else {
                        continue;
                    };
                    let watch = stopwatch.as_deref();
                    let sighting = lane.as_mut().map(|l| l.read(&frame.to_colour(), watch));
                    let (markers, status) = detector.read(&frame.into_gray(), watch);
                    counts.detected.fetch_add(1, Ordering::SeqCst);
                    results.put((markers, status, sighting));
                }
            })
        };
        Self {
            results,
            counts,
            stop,
            threads: vec![grabber, detecting],
        }
    }

    /// The newest detection not yet taken.
    pub fn take_latest(&self) -> Option<(Vec<MarkerSighting>, CameraStatus, Option<LaneSighting>)> {
        self.results.take()
    }

    pub fn counts(&self) -> &PipelineCounts {
        &self.counts
    }
}

impl Drop for CameraPipeline {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }
}

/// A V4L2 camera through OpenCV's videoio, asked for the calibration's frame size.
pub struct V4l2Source {
    capture: opencv::videoio::VideoCapture,
    bgr: opencv::core::Mat,
}

impl V4l2Source {
    /// `device` is a path such as /dev/video0 or an index such as 0.
    pub fn open(device: &str, width: u32, height: u32) -> Result<Self, String> {
        use opencv::prelude::*;
        use opencv::videoio::{self, VideoCapture};
        let fail = |e: opencv::Error| format!("camera {device}: {e}");
        let mut capture = match device.parse::<i32>() {
            Ok(index) => VideoCapture::new(index, videoio::CAP_V4L2),
            Err(_) => VideoCapture::from_file(device, videoio::CAP_V4L2),
        }
        .map_err(fail)?;
        if !capture.is_opened().map_err(fail)? {
            return Err(format!("camera {device}: cannot open it"));
        }
        capture
            .set(videoio::CAP_PROP_FRAME_WIDTH, f64::from(width))
            .map_err(fail)?;
        capture
            .set(videoio::CAP_PROP_FRAME_HEIGHT, f64::from(height))
            .map_err(fail)?;
        // Keep the driver's queue short: the newest frame is the one wanted.
        let _ = capture.set(videoio::CAP_PROP_BUFFERSIZE, 1.0);
        Ok(Self {
            capture,
            bgr: opencv::core::Mat::default(),
        })
    }
}

impl FrameSource for V4l2Source {
    fn grab(&mut self) -> Result<Option<CameraImage>, String> {
        use opencv::prelude::*;
        let e = |e: opencv::Error| e.to_string();
        if !self.capture.read(&mut self.bgr).map_err(e)? {
            return Err("the camera returned no frame".into());
        }
        let (w, h) = (self.bgr.cols() as usize, self.bgr.rows() as usize);
        if self.bgr.channels() != 3 {
            return Err(format!(
                "the camera gave {} channels, not 3",
                self.bgr.channels()
            ));
        }
        let data = self.bgr.data_bytes().map_err(e)?.to_vec();
        Ok(Some(CameraImage::Colour(super::colour::BgrFrame {
            width: w,
            height: h,
            data,
        })))
    }
}
