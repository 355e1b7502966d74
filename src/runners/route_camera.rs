//! `navdeck route --sim-camera`'s figures: how the rendered tag camera and OpenCV's
//! detector did over a run, every tag found set against the ideal camera's noise-free
//! truth for it (the same ahead, lateral and angle from the true pose), and the time
//! each frame took to draw and to read.

// The tally and its figures are filled only by the rendered camera (feature `vision`).
#![cfg_attr(not(feature = "vision"), allow(dead_code))]

use crate::clock::Clock;
use crate::geometry::Pose2;
use crate::perception::tag_camera::TagCameraConfig;
#[cfg(feature = "vision")]
use crate::sim::rendered_tag_camera::RenderedTagCamera;
use crate::sim::tag_camera::TagCamera;
use crate::tags::TagMap;
use crate::tags::drive::TagSighting;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// The mean and the largest of some errors.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct MeanMax {
    pub mean: f64,
    pub max: f64,
}

impl MeanMax {
    fn of(values: &[f64]) -> Option<Self> {
        (!values.is_empty()).then(|| Self {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            max: values.iter().fold(0.0f64, |m, v| m.max(*v)),
        })
    }
}

/// The mean and the nearest-rank 95th percentile of some times, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct MeanP95 {
    pub mean_ms: f64,
    pub p95_ms: f64,
}

impl MeanP95 {
    fn of(ms: Vec<f64>) -> Option<Self> {
        super::lane::spread(ms).map(|[mean_ms, _, p95_ms, _]| Self { mean_ms, p95_ms })
    }
}

/// The rendered camera's figures over one run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DetectionFigures {
    /// Control periods, one frame each, and the frames drawn and read: a frame in which
    /// no tag reaches the image shows bare floor and is skipped.
    pub frames: usize,
    pub frames_drawn: usize,
    /// Map tags shown whole (their black square inside the image's edge margin), summed
    /// over the frames, and how many of those the detector found.
    pub tags_in_view: usize,
    pub tags_found_in_view: usize,
    /// Every tag of the map reported, and those refused (pose off the floor, corners
    /// not reprojected, at the image's edge) or with ids the map does not hold.
    pub tags_detected: usize,
    pub tags_refused: usize,
    pub unknown_ids: usize,
    /// Each tag found against the truth: metres ahead and lateral, degrees of angle
    /// (absolute errors).
    pub ahead_error_m: Option<MeanMax>,
    pub lateral_error_m: Option<MeanMax>,
    pub align_error_deg: Option<MeanMax>,
    /// Time per frame drawn to draw it and to find and measure its tags.
    pub render_time: Option<MeanP95>,
    pub detect_time: Option<MeanP95>,
}

/// Errors and times gathered frame by frame.
#[derive(Clone, Debug, Default)]
pub struct DetectionTally {
    figures: DetectionFigures,
    ahead: Vec<f64>,
    lateral: Vec<f64>,
    align_deg: Vec<f64>,
    render_ms: Vec<f64>,
    detect_ms: Vec<f64>,
}

/// One frame's counts: whether it was drawn, tags shown whole, of those found, found
/// in all, refused, unknown.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameCounts {
    pub drawn: bool,
    pub in_view: usize,
    pub found_in_view: usize,
    pub detected: usize,
    pub refused: usize,
    pub unknown: usize,
}

impl DetectionTally {
    /// Notes one frame: its counts, and how long it took to draw and read, seconds.
    pub fn frame(&mut self, counts: FrameCounts, render_s: Option<f64>, detect_s: Option<f64>) {
        let f = &mut self.figures;
        f.frames += 1;
        f.frames_drawn += usize::from(counts.drawn);
        f.tags_in_view += counts.in_view;
        f.tags_found_in_view += counts.found_in_view;
        f.tags_detected += counts.detected;
        f.tags_refused += counts.refused;
        f.unknown_ids += counts.unknown;
        self.render_ms.extend(render_s.map(|s| s * 1000.0));
        self.detect_ms.extend(detect_s.map(|s| s * 1000.0));
    }

    /// Notes one tag found, off the truth by `ahead` and `lateral` metres and `align`
    /// radians.
    pub fn error(&mut self, ahead: f64, lateral: f64, align: f64) {
        self.ahead.push(ahead.abs());
        self.lateral.push(lateral.abs());
        self.align_deg.push(align.abs().to_degrees());
    }

    pub fn figures(self) -> DetectionFigures {
        DetectionFigures {
            ahead_error_m: MeanMax::of(&self.ahead),
            lateral_error_m: MeanMax::of(&self.lateral),
            align_error_deg: MeanMax::of(&self.align_deg),
            render_time: MeanP95::of(self.render_ms),
            detect_time: MeanP95::of(self.detect_ms),
            ..self.figures
        }
    }
}

/// Which tag sensor a run drives with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TagSensor {
    /// The ideal tag camera: the tags' true offsets with a little noise.
    #[default]
    Ideal,
    /// The rendered camera's frames read by OpenCV (`--sim-camera`, feature `vision`).
    Rendered,
}

/// The tag sensor of one run.
pub enum Eyes {
    Ideal(TagCamera),
    #[cfg(feature = "vision")]
    Rendered(Box<Rendered>),
}

/// The rendered camera, the ideal one over the same floor point for the truth, and the
/// figures so far.
#[cfg(feature = "vision")]
pub struct Rendered {
    camera: RenderedTagCamera,
    truth: TagCamera,
    tally: DetectionTally,
}

impl Eyes {
    /// The sensor `sensor` over `map`, its tags' black squares `side` metres across
    /// (the rendered camera's), its floor from `seed`.
    pub fn new(
        sensor: TagSensor,
        map: &TagMap,
        camera: &TagCameraConfig,
        side: f64,
        seed: u64,
    ) -> Result<Self, String> {
        match sensor {
            TagSensor::Ideal => Ok(Self::Ideal(TagCamera::default())),
            #[cfg(feature = "vision")]
            TagSensor::Rendered => {
                let rendered = RenderedTagCamera::new(map, camera, side, seed)
                    .map_err(|e| format!("the rendered tag camera: {e}"))?;
                if let Some(id) = rendered.unpainted().first() {
                    return Err(format!(
                        "tag {id} cannot be painted on the twin's floor: AprilTag 36h11 has ids 0 to 586"
                    ));
                }
                let truth = TagCamera {
                    look: rendered.look(),
                    ..TagCamera::default()
                };
                Ok(Self::Rendered(Box::new(Rendered {
                    camera: rendered,
                    truth,
                    tally: DetectionTally::default(),
                })))
            }
            #[cfg(not(feature = "vision"))]
            TagSensor::Rendered => {
                let _ = (map, camera, side, seed);
                Err(format!("--sim-camera {}", crate::session::NEEDS_VISION))
            }
        }
    }

    /// The ideal camera looking where this sensor looks: the floor point its sightings
    /// are measured from, and the truth they are scored against.
    pub fn ideal(&self) -> &TagCamera {
        match self {
            Self::Ideal(camera) => camera,
            #[cfg(feature = "vision")]
            Self::Rendered(r) => &r.truth,
        }
    }

    /// The tags of `map` seen from the true pose `truth`.
    pub fn see(
        &mut self,
        map: &TagMap,
        truth: Pose2,
        rng: &mut ChaCha8Rng,
        stopwatch: Option<&dyn Clock>,
    ) -> Result<Vec<TagSighting>, String> {
        match self {
            Self::Ideal(camera) => {
                let _ = stopwatch;
                Ok(camera.sightings(map, truth, rng))
            }
            #[cfg(feature = "vision")]
            Self::Rendered(r) => {
                let Rendered {
                    camera,
                    truth: ideal,
                    tally,
                } = r.as_mut();
                let captured = (camera.capture(map, truth, rng, stopwatch))
                    .map_err(|e| format!("the rendered tag camera: {e}"))?;
                let found = &captured.seen.detections;
                let counts = FrameCounts {
                    drawn: captured.drawn,
                    in_view: captured.in_view.len(),
                    found_in_view: (captured.in_view.iter())
                        .filter(|id| found.iter().any(|d| d.sighting.id == **id))
                        .count(),
                    detected: found.len(),
                    refused: captured.seen.refused,
                    unknown: captured.seen.unknown,
                };
                tally.frame(counts, captured.render_s, captured.detect_s);
                for d in found {
                    let s = d.sighting;
                    let exact = ideal.exact(s.id, &map.tags[&s.id], truth);
                    // Both angles fold into ±45°: a tag seen at 44.9° and its truth at
                    // -44.9° differ by 0.2°, not 89.8°.
                    let quarter = std::f64::consts::FRAC_PI_2;
                    let off = crate::geometry::wrap_angle(s.align - exact.align);
                    let align = off - (off / quarter).round() * quarter;
                    tally.error(s.ahead - exact.ahead, s.lateral - exact.lateral, align);
                }
                Ok(found.iter().map(|d| d.sighting).collect())
            }
        }
    }

    /// The sensor that ran, and the rendered camera's figures.
    pub fn finish(self) -> (TagSensor, Option<DetectionFigures>) {
        match self {
            Self::Ideal(_) => (TagSensor::Ideal, None),
            #[cfg(feature = "vision")]
            Self::Rendered(r) => (TagSensor::Rendered, Some(r.tally.figures())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tally_sums_counts_and_takes_absolute_errors() {
        let mut t = DetectionTally::default();
        let counts = FrameCounts {
            drawn: true,
            in_view: 1,
            found_in_view: 1,
            detected: 1,
            ..FrameCounts::default()
        };
        t.frame(counts, Some(0.002), Some(0.010));
        t.frame(FrameCounts::default(), Some(0.004), Some(0.020));
        t.error(-0.001, 0.003, -0.01);
        t.error(0.003, -0.001, 0.0);
        let f = t.figures();
        assert_eq!(
            (f.frames, f.frames_drawn, f.tags_in_view, f.tags_detected),
            (2, 1, 1, 1)
        );
        let ahead = f.ahead_error_m.unwrap();
        assert!((ahead.mean - 0.002).abs() < 1e-12 && (ahead.max - 0.003).abs() < 1e-12);
        assert!((f.align_error_deg.unwrap().max - 0.01f64.to_degrees()).abs() < 1e-12);
        // Nearest rank: the 95th percentile of two times is the larger.
        let render = f.render_time.unwrap();
        assert!((render.mean_ms - 3.0).abs() < 1e-9 && (render.p95_ms - 4.0).abs() < 1e-9);
    }
}
