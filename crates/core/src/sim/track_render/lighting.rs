//! Shadows (seed 000 §2.1.1: "shadows from pillars or furniture partially obscure
//! lanes"; §6.4.2's lighting tests), placed once from the renderer's seed as hard-edged
//! polygons fixed on the floor, some across the lane. The glare is `glare`'s.

use crate::geometry::{Point2, Pose2};
use crate::sim::track::Track;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Shadows laid across the lane, and elsewhere on the floor.
const SHADOWS_ON_LANE: usize = 3;
const SHADOWS_ELSEWHERE: usize = 3;
/// Hard shadows: convex parallelograms, half of them centred on the lane.
pub fn shadows(rng: &mut ChaCha8Rng, track: &Track, lo: Point2, hi: Point2) -> Vec<Vec<Point2>> {
    (0..SHADOWS_ON_LANE + SHADOWS_ELSEWHERE)
        .map(|i| {
            let centre = if i < SHADOWS_ON_LANE {
                track.at(rng.random_range(0.0..track.length())).0
            } else {
                Point2::new(rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y))
            };
            let length = rng.random_range(0.3..0.9);
            let width = rng.random_range(0.12..0.4);
            let shear = rng.random_range(-0.4..0.4);
            let turn = rng.random_range(0.0..std::f64::consts::TAU);
            let pose = Pose2::new(centre.x, centre.y, turn);
            let (l, w) = (length / 2.0, width / 2.0);
            [
                (-l - shear * w, -w),
                (l - shear * w, -w),
                (l + shear * w, w),
                (-l + shear * w, w),
            ]
            .map(|(x, y)| pose.transform_point(Point2::new(x, y)))
            .to_vec()
        })
        .collect()
}
