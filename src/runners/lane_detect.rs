//! `navdeck lane --detection N` (feature `vision`): the lane pipeline's traffic-light and
//! barrier detection scored frame by frame against the twin's truth, per class and
//! lighting level, as seed 000 §6.2.1 tabulates it (precision, recall, F1), and the time
//! the pipeline takes per 640x480 frame beside §6.3.1's. Frames are drawn from poses on the
//! lane short of each light and barrier, at random times of their cycles.

use crate::data::{BarrierState, LightColour};
use crate::geometry::Pose2;
use crate::perception::lane::{LanePipeline, LaneVisionConfig};
use crate::perception::lane_camera::LaneCameraConfig;
use crate::sim::World;
use crate::sim::track::Lighting;
use crate::sim::track_render::TrackRenderer;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::collections::BTreeMap;
use std::time::Instant;

/// One class's counts and scores under one lighting.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ClassScore {
    pub true_positives: u32,
    pub false_positives: u32,
    pub false_negatives: u32,
    pub precision: Option<f64>,
    pub recall: Option<f64>,
    pub f1: Option<f64>,
}

impl ClassScore {
    fn finish(&mut self) {
        let (tp, fp, f_n) = (
            f64::from(self.true_positives),
            f64::from(self.false_positives),
            f64::from(self.false_negatives),
        );
        self.precision = (tp + fp > 0.0).then(|| tp / (tp + fp));
        self.recall = (tp + f_n > 0.0).then(|| tp / (tp + f_n));
        // F1 = 2PR / (P + R), the harmonic mean (van Rijsbergen 1979).
        self.f1 = self
            .precision
            .zip(self.recall)
            .filter(|(p, r)| p + r > 0.0)
            .map(|(p, r)| 2.0 * p * r / (p + r));
    }
}

/// Milliseconds per frame: mean, standard deviation, 95th percentile, most.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Timing {
    pub mean_ms: f64,
    pub std_ms: f64,
    pub p95_ms: f64,
    pub max_ms: f64,
}

impl Timing {
    fn of(ms: Vec<f64>) -> Self {
        let [mean_ms, std_ms, p95_ms, max_ms] = super::lane::spread(ms).unwrap_or_default();
        Self {
            mean_ms,
            std_ms,
            p95_ms,
            max_ms,
        }
    }
}

/// The whole report.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DetectionReport {
    pub frames: u32,
    /// Lighting -> class -> score.
    pub classes: BTreeMap<String, BTreeMap<String, ClassScore>>,
    /// The whole pipeline (`read`: lines, light, barrier) per frame.
    pub pipeline: Timing,
    /// Object recognition alone (light and barrier).
    pub objects: Timing,
    /// Drawing the frame (the twin's renderer).
    pub render: Timing,
}

fn light_class(c: LightColour) -> String {
    format!("light_{}", c.label())
}

fn barrier_class(s: BarrierState) -> String {
    format!("barrier_{}", s.label())
}

/// Scores `frames` frames under each of `lightings` over `worlds` (each with a track).
pub fn run(
    worlds: &[World],
    camera: &LaneCameraConfig,
    vision: &LaneVisionConfig,
    lightings: &[Lighting],
    frames: u32,
    seed: u64,
) -> Result<DetectionReport, String> {
    let mut report = DetectionReport::default();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut pipeline_ms, mut objects_ms, mut render_ms) = (Vec::new(), Vec::new(), Vec::new());
    for &lighting in lightings {
        let classes = report.classes.entry(lighting.name()).or_default();
        let mut renderers = Vec::with_capacity(worlds.len());
        for (i, world) in worlds.iter().enumerate() {
            let scene = world.track.as_ref().ok_or("a world without a track")?;
            let seed = seed + i as u64;
            renderers.push(TrackRenderer::new(
                scene,
                &world.walls,
                &[],
                camera,
                lighting,
                seed,
            ));
        }
        let mut pipeline = LanePipeline::new(vision, camera).map_err(|e| e.to_string())?;
        for k in 0..frames {
            let i = k as usize % worlds.len();
            let (scene, renderer) = (
                worlds[i].track.as_ref().expect("checked"),
                &mut renderers[i],
            );
            // A pose on the lane short of a light's post or a barrier's arm.
            let targets: Vec<f64> = (scene
                .lights
                .iter()
                .map(|l| l.along + crate::sim::track::LIGHT_BEYOND))
            .chain(scene.barriers.iter().map(|b| b.along))
            .collect();
            let target = targets[rng
                .random_range(0..targets.len().max(1))
                .min(targets.len() - 1)];
            let before = rng.random_range(0.4..1.6);
            let (p, heading) = scene.track.at(target - before);
            let (side, turn) = (rng.random_range(-0.04..0.04), rng.random_range(-0.1..0.1));
            let pose = Pose2::new(
                p.x - heading.sin() * side,
                p.y + heading.cos() * side,
                heading + turn,
            );
            let t = rng.random_range(0.0..120.0);
            let started = Instant::now();
            let frame = renderer.render(pose, t, &mut rng);
            render_ms.push(started.elapsed().as_secs_f64() * 1000.0);
            let truth = renderer.truth(pose, t);
            let started = Instant::now();
            let seen = pipeline.detect_objects(&frame);
            objects_ms.push(started.elapsed().as_secs_f64() * 1000.0);
            let started = Instant::now();
            let _ = pipeline.read(&frame, None);
            pipeline_ms.push(started.elapsed().as_secs_f64() * 1000.0);
            let mut tally = |truth: Option<String>, seen: Option<String>| {
                if let Some(t) = &truth {
                    let c = classes.entry(t.clone()).or_default();
                    if seen.as_ref() == Some(t) {
                        c.true_positives += 1;
                    } else {
                        c.false_negatives += 1;
                    }
                }
                if let Some(s) = seen.filter(|s| truth.as_ref() != Some(s)) {
                    classes.entry(s).or_default().false_positives += 1;
                }
            };
            tally(
                truth.light.map(|l| light_class(l.colour)),
                seen.light.map(|l| light_class(l.colour)),
            );
            tally(
                truth.barrier.map(|b| barrier_class(b.state)),
                seen.barrier.map(|b| barrier_class(b.state)),
            );
            report.frames += 1;
        }
        for c in classes.values_mut() {
            c.finish();
        }
    }
    report.pipeline = Timing::of(pipeline_ms);
    report.objects = Timing::of(objects_ms);
    report.render = Timing::of(render_ms);
    Ok(report)
}
