//! The marker sensor: what seed 001's ArUco pipeline would report, as (id, range, bearing).
//!
//! A marker is seen when it lies within the field of view and range, faces the camera
//! closely enough, and no wall, obstacle or block stands between. The camera sits at the
//! robot centre (seed 001's r and alpha are measured from there).

use super::Marker;
use super::config::CameraConfig;
use super::shapes::segments_cross;
use crate::data::MarkerSighting;
use crate::geometry::{Point2, Pose2, Segment, wrap_angle};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// Markers are looked at from this far in front of their surface, so the surface they are
/// stuck on does not hide them, metres.
const SURFACE_OFFSET: f64 = 1e-3;

/// True when no occluder crosses the line from `eye` to just in front of marker `m`.
pub fn clear_line(eye: Point2, m: &Marker, occluders: &[&[Segment]]) -> bool {
    let (ns, nc) = m.normal.sin_cos();
    let target = Point2::new(
        m.position.x + nc * SURFACE_OFFSET,
        m.position.y + ns * SURFACE_OFFSET,
    );
    let (lo_x, hi_x) = (eye.x.min(target.x), eye.x.max(target.x));
    let (lo_y, hi_y) = (eye.y.min(target.y), eye.y.max(target.y));
    !occluders.iter().flat_map(|set| set.iter()).any(|seg| {
        let off_box = seg.a.x.max(seg.b.x) < lo_x
            || seg.a.x.min(seg.b.x) > hi_x
            || seg.a.y.max(seg.b.y) < lo_y
            || seg.a.y.min(seg.b.y) > hi_y;
        !off_box && segments_cross(eye, target, seg.a, seg.b)
    })
}

#[derive(Clone, Debug)]
pub struct Camera {
    cos_half_fov: f64,
    min_range: f64,
    max_range: f64,
    cos_max_view: f64,
    dist_std: f64,
    angle_std: f64,
    miss_probability: f64,
}

impl Camera {
    pub fn new(cfg: &CameraConfig) -> Self {
        Self {
            cos_half_fov: (cfg.fov_deg.to_radians() / 2.0).cos(),
            min_range: cfg.min_range,
            max_range: cfg.max_range,
            cos_max_view: cfg.max_view_angle_deg.to_radians().cos(),
            dist_std: cfg.dist_std.max(0.0),
            angle_std: cfg.angle_std_deg.max(0.0).to_radians(),
            miss_probability: cfg.miss_probability.clamp(0.0, 1.0),
        }
    }

    /// The furthest a marker is seen from, metres (the rendered camera keeps to it).
    #[cfg(feature = "vision")]
    pub fn max_range(&self) -> f64 {
        self.max_range
    }

    /// True range and bearing of `m` from `pose` if the camera can see it past `occluders`.
    pub fn visible(&self, pose: Pose2, m: &Marker, occluders: &[&[Segment]]) -> Option<(f64, f64)> {
        let (dx, dy) = (m.position.x - pose.x, m.position.y - pose.y);
        let range2 = dx * dx + dy * dy;
        if range2 < self.min_range * self.min_range
            || range2 > self.max_range * self.max_range
            || range2 == 0.0
        {
            return None;
        }
        let range = range2.sqrt();
        let (s, c) = pose.theta.sin_cos();
        let (fx, fy) = (c * dx + s * dy, -s * dx + c * dy);
        // Inside the field of view: angle off the heading <= fov / 2, i.e. cos >= cos(fov / 2).
        if fx < range * self.cos_half_fov {
            return None;
        }
        let (ns, nc) = m.normal.sin_cos();
        // Seen from the front: angle between the normal and the way back to the camera.
        if -(nc * dx + ns * dy) < range * self.cos_max_view {
            return None;
        }
        if !clear_line(pose.position(), m, occluders) {
            return None;
        }
        Some((range, fy.atan2(fx)))
    }

    /// One camera frame: every visible marker, each missed with `miss_probability`, with
    /// Gaussian noise on range and bearing (seed 001 `dist_std`, `angle_std`).
    pub fn observe<'a>(
        &self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) -> Vec<MarkerSighting> {
        let mut out = Vec::new();
        for m in markers {
            let Some((range, bearing)) = self.visible(pose, m, occluders) else {
                continue;
            };
            if self.miss_probability > 0.0 && rng.random::<f64>() < self.miss_probability {
                continue;
            }
            let (mut r, mut b) = (range, bearing);
            if self.dist_std > 0.0 {
                r += self.dist_std * rng.sample::<f64, _>(StandardNormal);
            }
            if self.angle_std > 0.0 {
                b += self.angle_std * rng.sample::<f64, _>(StandardNormal);
            }
            // Noise can take a marker at the near limit to no distance at all, which no
            // camera measures: it is not reported (the frame check would refuse it).
            if r < crate::data::frame_check::MIN_SIGHTING_RANGE {
                continue;
            }
            out.push(MarkerSighting {
                id: m.id,
                range: r,
                bearing: wrap_angle(b),
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use std::f64::consts::PI;

    fn camera() -> Camera {
        Camera::new(&CameraConfig {
            dist_std: 0.0,
            angle_std_deg: 0.0,
            miss_probability: 0.0,
            ..CameraConfig::default()
        })
    }

    fn marker(x: f64, y: f64, facing_deg: f64) -> Marker {
        Marker {
            id: 7,
            position: Point2::new(x, y),
            normal: facing_deg.to_radians(),
        }
    }

    #[test]
    fn marker_straight_ahead_reads_its_range_and_bearing() {
        let pose = Pose2::new(0.5, 0.5, PI / 2.0);
        let (r, b) = camera()
            .visible(pose, &marker(0.5, 1.7, -90.0), &[])
            .unwrap();
        assert!((r - 1.2).abs() < 1e-12 && b.abs() < 1e-12);
        // 20 degrees to the left is a positive bearing (REP-103, CCW positive).
        let (r, b) = camera()
            .visible(
                Pose2::default(),
                &marker(20f64.to_radians().cos(), 20f64.to_radians().sin(), 200.0),
                &[],
            )
            .unwrap();
        assert!((r - 1.0).abs() < 1e-12 && (b - 20f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn markers_behind_outside_the_view_or_too_far_are_not_seen() {
        let c = camera();
        let home = Pose2::default();
        assert!(
            c.visible(home, &marker(-1.0, 0.0, 0.0), &[]).is_none(),
            "behind"
        );
        assert!(
            c.visible(home, &marker(1.0, 1.0, 225.0), &[]).is_none(),
            "45 degrees off, fov is 68.4"
        );
        assert!(
            c.visible(home, &marker(1.0, 0.6, 210.0), &[]).is_some(),
            "31 degrees off is inside"
        );
        assert!(
            c.visible(home, &marker(3.5, 0.0, 180.0), &[]).is_none(),
            "beyond max_range"
        );
        assert!(
            c.visible(home, &marker(0.05, 0.0, 180.0), &[]).is_none(),
            "closer than min_range"
        );
    }

    #[test]
    fn markers_seen_edge_on_or_from_behind_are_not_seen() {
        let c = camera();
        let home = Pose2::default();
        assert!(
            c.visible(home, &marker(1.0, 0.0, 90.0), &[]).is_none(),
            "edge-on"
        );
        assert!(
            c.visible(home, &marker(1.0, 0.0, 0.0), &[]).is_none(),
            "facing away"
        );
        assert!(
            c.visible(home, &marker(1.0, 0.0, 110.0), &[]).is_some(),
            "70 degrees off face-on"
        );
    }

    #[test]
    fn a_wall_in_between_hides_a_marker_but_its_own_wall_does_not() {
        let c = camera();
        let home = Pose2::default();
        let own = [Segment::new(Point2::new(1.0, -1.0), Point2::new(1.0, 1.0))];
        let m = marker(1.0, 0.0, 180.0);
        assert!(c.visible(home, &m, &[&own]).is_some());
        let between = [Segment::new(Point2::new(0.5, -0.1), Point2::new(0.5, 0.1))];
        assert!(c.visible(home, &m, &[&own, &between]).is_none());
    }

    #[test]
    fn noise_and_misses_follow_the_config() {
        let noisy = Camera::new(&CameraConfig {
            miss_probability: 0.0,
            ..CameraConfig::default()
        });
        let m = [marker(1.0, 0.0, 180.0)];
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let n = 2000;
        let ranges: Vec<f64> = (0..n)
            .map(|_| noisy.observe(Pose2::default(), &m, &[], &mut rng)[0].range)
            .collect();
        let mean = ranges.iter().sum::<f64>() / n as f64;
        let std = (ranges.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        assert!(
            (mean - 1.0).abs() < 0.01 && (std - 0.1).abs() < 0.01,
            "mean {mean} std {std}"
        );
        let missing = Camera::new(&CameraConfig {
            miss_probability: 0.5,
            ..CameraConfig::default()
        });
        let seen = (0..n)
            .filter(|_| {
                !missing
                    .observe(Pose2::default(), &m, &[], &mut rng)
                    .is_empty()
            })
            .count();
        assert!((800..1200).contains(&seen), "{seen} of {n}");
    }
}
