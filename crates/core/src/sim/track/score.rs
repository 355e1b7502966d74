//! A lane run scored against the twin's truth (seed 000 §6.1.1: lateral error against
//! the true lane centre, its RMS and maximum, the time within tolerance): laps driven,
//! time out of lane, and red lights run.

use super::TrackScene;
use crate::data::LightColour;
use crate::geometry::Pose2;
use serde::Serialize;

/// What a lane run did, as the truth saw it.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LaneFigures {
    /// Whole and part laps driven forward along the lane.
    pub laps: f64,
    pub lateral_rms_m: f64,
    pub lateral_max_m: f64,
    /// Seconds with the footprint over a line: |lateral| above half the lane width less
    /// the footprint's radius.
    pub out_of_lane_s: f64,
    /// The bound |lateral| must stay under, metres.
    pub in_lane_bound_m: f64,
    /// Stop lines crossed while their light showed red.
    pub red_lights_run: u32,
    /// Stop lines crossed at all.
    pub lights_passed: u32,
}

/// See the module comment.
#[derive(Clone, Debug)]
pub struct LaneScore {
    /// Metres driven along the lane, forward positive, from the start.
    progress: f64,
    last_along: f64,
    sum_sq: f64,
    samples: u64,
    figures: LaneFigures,
}

impl LaneScore {
    /// Scoring starts at `start`, with a footprint of `radius`.
    pub fn new(scene: &TrackScene, start: Pose2, radius: f64) -> Self {
        let along = scene.track.project(start.position()).along;
        Self {
            progress: 0.0,
            last_along: along,
            sum_sq: 0.0,
            samples: 0,
            figures: LaneFigures {
                in_lane_bound_m: scene.track.lane_width / 2.0 - radius,
                ..LaneFigures::default()
            },
        }
    }

    /// Takes in the true pose at `t`, `dt` seconds after the last.
    pub fn observe(&mut self, scene: &TrackScene, t: f64, dt: f64, pose: Pose2) {
        let length = scene.track.length();
        let here = scene.track.project(pose.position());
        // The step along the lane, taken the short way round.
        let step = (here.along - self.last_along + length / 2.0).rem_euclid(length) - length / 2.0;
        let (before, after) = (self.progress, self.progress + step);
        for light in &scene.lights {
            // Each crossing of the stop line going forward, on any lap.
            let start = self.first_along_since(light.along, length);
            let crossed = ((before - start) / length).floor() < ((after - start) / length).floor();
            if crossed && step > 0.0 {
                self.figures.lights_passed += 1;
                if light.cycle.colour_at(t) == LightColour::Red {
                    self.figures.red_lights_run += 1;
                }
            }
        }
        self.progress = after;
        self.last_along = here.along;
        let lateral = here.offset.abs();
        self.sum_sq += lateral * lateral;
        self.samples += 1;
        let f = &mut self.figures;
        f.lateral_max_m = f.lateral_max_m.max(lateral);
        if lateral > f.in_lane_bound_m {
            f.out_of_lane_s += dt;
        }
    }

    /// The progress at which the lane position `along` is first reached.
    fn first_along_since(&self, along: f64, length: f64) -> f64 {
        // Progress p sits at lane position (start + p) mod length.
        let start_along = (self.last_along - self.progress).rem_euclid(length);
        (along - start_along).rem_euclid(length)
    }

    pub fn laps(&self, scene: &TrackScene) -> f64 {
        self.progress / scene.track.length()
    }

    /// The figures so far.
    pub fn figures(&self, scene: &TrackScene) -> LaneFigures {
        let mut f = self.figures.clone();
        f.laps = self.laps(scene);
        f.lateral_rms_m = (self.sum_sq / self.samples.max(1) as f64).sqrt();
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::World;
    use std::path::Path;

    fn scene() -> TrackScene {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../maps/track.toml"
        ));
        *World::load(path).unwrap().track.unwrap()
    }

    #[test]
    fn driving_the_centreline_once_round_is_one_lap_in_lane() {
        let s = scene();
        let (p, h) = s.track.at(0.3);
        let mut score = LaneScore::new(&s, Pose2::new(p.x, p.y, h), 0.08);
        let n = 1000;
        for k in 1..=n {
            let along = 0.3 + s.track.length() * k as f64 / n as f64;
            let (p, h) = s.track.at(along);
            score.observe(&s, k as f64 * 0.1, 0.1, Pose2::new(p.x, p.y, h));
        }
        let f = score.figures(&s);
        assert!((f.laps - 1.0).abs() < 1e-6, "{f:?}");
        assert!(f.lateral_max_m < 0.01 && f.out_of_lane_s == 0.0, "{f:?}");
        assert_eq!(f.lights_passed, 1);
    }

    #[test]
    fn crossing_the_stop_line_on_red_is_a_run_and_drifting_is_out_of_lane() {
        let s = scene();
        let light = &s.lights[0];
        let red_at = (0..100)
            .map(|k| k as f64 * 0.5)
            .find(|&t| light.cycle.colour_at(t) == LightColour::Red)
            .unwrap();
        let (p, h) = s.track.at(light.along - 0.05);
        let mut score = LaneScore::new(&s, Pose2::new(p.x, p.y, h), 0.08);
        let (q, h) = s.track.at(light.along + 0.05);
        // 0.15 m to the left: over the yellow line's inside edge less the footprint.
        let left = Pose2::new(q.x - h.sin() * 0.15, q.y + h.cos() * 0.15, h);
        score.observe(&s, red_at, 0.1, left);
        let f = score.figures(&s);
        assert_eq!((f.red_lights_run, f.lights_passed), (1, 1), "{f:?}");
        assert!((f.out_of_lane_s - 0.1).abs() < 1e-12 && (f.lateral_max_m - 0.15).abs() < 1e-6);
    }
}
