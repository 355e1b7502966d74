//! Route mode's tag camera on a real robot (seed 003 §1.2.2): frames from a camera source
//! (a ROS 2 `/rgb` topic) read on threads of their own as the marker camera's pipeline
//! reads them, latest frame wins. Tags are read once the camera's calibration has come
//! (seed 003 waits for `/camera_info`), with the detector rebuilt when it changes; the
//! mount and what the detector accepts come from `[vision.tag_camera]`.

use super::pipeline::{FrameSource, Slot};
use super::tag_camera::TagCameraConfig;
use super::tag_detect::{TagDetector, TagFrame};
use crate::tags::TagMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

/// How long the reading thread waits for a frame before looking at the stop flag.
const WAIT: Duration = Duration::from_millis(100);

/// What the newest frame gave.
#[derive(Clone, Debug, PartialEq)]
pub enum TagReading {
    /// A frame read: the map's tags in it.
    Seen(TagFrame),
    /// A frame that could not be read, and why (no calibration yet, one refused, a
    /// frame of another size, the source failing).
    Unread(String),
}

/// The calibration as the source last gave it: None until one came.
type Calibration = Arc<Mutex<Option<Result<super::intrinsics::Intrinsics, String>>>>;

pub struct TagPipeline {
    results: Arc<Slot<TagReading>>,
    stop: Arc<AtomicBool>,
    threads: Vec<JoinHandle<()>>,
}

impl TagPipeline {
    /// Reads `map`'s tags, black squares `side` metres across, in `source`'s frames
    /// through `camera`'s mount.
    pub fn start(
        mut source: Box<dyn FrameSource>,
        camera: TagCameraConfig,
        side: f64,
        map: Arc<TagMap>,
    ) -> Self {
        let frames = Arc::new(Slot::<super::colour::CameraImage>::new());
        let results = Arc::new(Slot::new());
        let calibration: Calibration = Arc::new(Mutex::new(None));
        let stop = Arc::new(AtomicBool::new(false));
        let grabber = {
            let (frames, results, stop) = (frames.clone(), results.clone(), stop.clone());
            let calibration = calibration.clone();
            std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    if let Some(c) = source.take_calibration() {
                        *calibration.lock().unwrap() = Some(c);
                    }
                    match source.grab() {
                        Ok(Some(frame)) => {
                            frames.put(frame);
                        }
                        Ok(None) => {}
                        Err(e) => {
                            results.put(TagReading::Unread(format!("camera: {e}")));
                            // A camera that fails is asked again, not hammered.
                            std::thread::sleep(Duration::from_millis(500));
                        }
                    }
                }
            })
        };
        let reader = {
            let (results, stop) = (results.clone(), stop.clone());
            std::thread::spawn(move || {
                let mut detector: Option<(super::intrinsics::Intrinsics, TagDetector)> = None;
                while !stop.load(Ordering::SeqCst) {
                    let Some(frame) = frames.take_waiting(WAIT) else {
                        continue;
                    };
                    let latest = calibration.lock().unwrap().clone();
                    let reading = match latest {
                        None => TagReading::Unread(
                            "waiting for the camera's calibration (camera_info)".into(),
                        ),
                        Some(Err(e)) => TagReading::Unread(e),
                        Some(Ok(k)) => {
                            if detector.as_ref().is_none_or(|(had, _)| *had != k) {
                                detector = TagDetector::with_intrinsics(&camera, side, k.clone())
                                    .ok()
                                    .map(|d| (k, d));
                            }
                            match &detector {
                                None => TagReading::Unread(
                                    "the tag detector cannot be set up for this calibration".into(),
                                ),
                                Some((_, d)) => match d.detect(&frame.into_gray(), &map) {
                                    Ok(seen) => TagReading::Seen(seen),
                                    Err(e) => TagReading::Unread(e.to_string()),
                                },
                            }
                        }
                    };
                    results.put(reading);
                }
            })
        };
        Self {
            results,
            stop,
            threads: vec![grabber, reader],
        }
    }

    /// The newest reading not yet taken.
    pub fn take_latest(&self) -> Option<TagReading> {
        self.results.take()
    }

    /// The next reading, waiting at most `timeout` for one.
    pub fn next_reading(&self, timeout: Duration) -> Option<TagReading> {
        self.results.take_waiting(timeout)
    }
}

impl Drop for TagPipeline {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::perception::colour::CameraImage;
    use crate::perception::frame::GrayFrame;
    use crate::perception::intrinsics::Intrinsics;
    use crate::tags::TagMap;

    /// Blank frames of `size`, with a calibration of `calibrated` from the `after`th on.
    struct Blank {
        size: (usize, usize),
        calibrated: Option<Result<Intrinsics, String>>,
        after: usize,
        grabbed: usize,
    }

    impl FrameSource for Blank {
        fn grab(&mut self) -> Result<Option<CameraImage>, String> {
            self.grabbed += 1;
            let (width, height) = self.size;
            let data = vec![128; width * height];
            Ok(Some(CameraImage::Gray(GrayFrame {
                width,
                height,
                data,
            })))
        }

        fn take_calibration(&mut self) -> Option<Result<Intrinsics, String>> {
            (self.grabbed >= self.after)
                .then(|| self.calibrated.take())
                .flatten()
        }
    }

    fn map() -> Arc<TagMap> {
        let text = include_str!("../../../../maps/tag_warehouse.yaml");
        Arc::new(TagMap::parse(text).unwrap())
    }

    /// The readings until one satisfies `done` (at most 200, each waited for 5 s).
    fn readings_until(
        pipeline: &TagPipeline,
        done: impl Fn(&TagReading) -> bool,
    ) -> Vec<TagReading> {
        let mut out = Vec::new();
        while out.len() < 200 {
            let r = pipeline
                .next_reading(Duration::from_secs(5))
                .expect("a reading");
            let stop = done(&r);
            out.push(r);
            if stop {
                break;
            }
        }
        out
    }

    fn camera_of(width: u32, height: u32) -> Intrinsics {
        Intrinsics {
            width,
            height,
            ..TagCameraConfig::default().intrinsics()
        }
    }

    #[test]
    fn frames_wait_for_the_calibration_then_are_read() {
        let k = TagCameraConfig::default().intrinsics();
        let source = Blank {
            size: (1280, 720),
            calibrated: Some(Ok(k)),
            after: 3,
            grabbed: 0,
        };
        let pipeline =
            TagPipeline::start(Box::new(source), TagCameraConfig::default(), 0.05, map());
        let seen = readings_until(&pipeline, |r| matches!(r, TagReading::Seen(_)));
        assert!(matches!(seen.last(), Some(TagReading::Seen(f)) if f.detections.is_empty()));
        for r in &seen[..seen.len() - 1] {
            assert_eq!(
                r,
                &TagReading::Unread("waiting for the camera's calibration (camera_info)".into())
            );
        }
    }

    #[test]
    fn a_refused_calibration_or_a_frame_of_another_size_is_said_not_read() {
        let refused = Blank {
            size: (1280, 720),
            calibrated: Some(Err("camera_info /camera_info: roi = 10x10: cropped".into())),
            after: 0,
            grabbed: 0,
        };
        let pipeline =
            TagPipeline::start(Box::new(refused), TagCameraConfig::default(), 0.05, map());
        let said = readings_until(
            &pipeline,
            |r| matches!(r, TagReading::Unread(w) if w.contains("roi")),
        );
        assert!(said.iter().all(|r| matches!(r, TagReading::Unread(_))));
        drop(pipeline);
        let smaller = Blank {
            size: (640, 360),
            calibrated: Some(Ok(camera_of(1280, 720))),
            after: 0,
            grabbed: 0,
        };
        let pipeline =
            TagPipeline::start(Box::new(smaller), TagCameraConfig::default(), 0.05, map());
        let said = readings_until(
            &pipeline,
            |r| matches!(r, TagReading::Unread(w) if w.contains("640x360")),
        );
        let TagReading::Unread(why) = said.last().unwrap() else {
            unreachable!()
        };
        assert!(why.contains("1280x720"), "{why}");
    }
}
