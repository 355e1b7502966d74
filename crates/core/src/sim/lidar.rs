//! A 360 degree laser scanner at the robot centre, laid out like sensor_msgs/LaserScan.
//!
//! Instead of casting every beam against every segment, each segment within range is
//! projected to the interval of beam indices it subtends from the sensor, and only those
//! beams are intersected with it, keeping the nearest hit per beam.
//! Ranges follow REP-117: +inf when nothing is within `range_max`, -inf when the surface
//! is closer than `range_min`.

use super::config::LidarConfig;
use super::shapes::dist2_to_segment;
use crate::data::LaserScan;
use crate::geometry::{Pose2, Segment, wrap_angle};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use std::f64::consts::PI;

#[derive(Clone, Debug)]
pub struct Lidar {
    increment: f64,
    /// Unit direction of each beam in the robot frame.
    dirs: Vec<(f64, f64)>,
    min_range: f64,
    max_range: f64,
    range_std: f64,
    /// Nearest hit per beam, reused between scans.
    nearest: Vec<f64>,
}

impl Lidar {
    pub fn new(cfg: &LidarConfig) -> Self {
        let beams = cfg.beams.max(1) as usize;
        let increment = 2.0 * PI / beams as f64;
        let dirs = (0..beams)
            .map(|i| (-PI + i as f64 * increment).sin_cos())
            .map(|(s, c)| (c, s))
            .collect();
        Self {
            increment,
            dirs,
            min_range: cfg.min_range,
            max_range: cfg.max_range,
            range_std: cfg.range_std.max(0.0),
            nearest: vec![f64::INFINITY; beams],
        }
    }

    /// One scan from `pose` against every segment of `solids`.
    pub fn scan(&mut self, pose: Pose2, solids: &[&[Segment]], rng: &mut ChaCha8Rng) -> LaserScan {
        self.nearest.fill(f64::INFINITY);
        let (s, c) = pose.theta.sin_cos();
        // Into the sensor frame: rotate the offset by -theta.
        let local = |x: f64, y: f64| {
            let (dx, dy) = (x - pose.x, y - pose.y);
            (c * dx + s * dy, -s * dx + c * dy)
        };
        for seg in solids.iter().flat_map(|set| set.iter()) {
            let far = self.max_range;
            if seg.a.x.min(seg.b.x) > pose.x + far
                || seg.a.x.max(seg.b.x) < pose.x - far
                || seg.a.y.min(seg.b.y) > pose.y + far
                || seg.a.y.max(seg.b.y) < pose.y - far
                || dist2_to_segment(pose.position(), seg.a, seg.b) > far * far
            {
                continue;
            }
            self.cast(local(seg.a.x, seg.a.y), local(seg.b.x, seg.b.y));
        }
        let mut ranges = Vec::with_capacity(self.nearest.len());
        for &d in &self.nearest {
            if d > self.max_range {
                ranges.push(f32::INFINITY);
                continue;
            }
            let noisy = if self.range_std > 0.0 {
                d + self.range_std * rng.sample::<f64, _>(StandardNormal)
            } else {
                d
            };
            ranges.push(if noisy < self.min_range {
                f32::NEG_INFINITY
            } else if noisy > self.max_range {
                f32::INFINITY
            } else {
                noisy as f32
            });
        }
        LaserScan {
            angle_min: -PI,
            angle_increment: self.increment,
            range_min: self.min_range,
            range_max: self.max_range,
            ranges,
        }
    }

    /// Intersects one segment (sensor frame, endpoints a and b) with the beams it subtends.
    fn cast(&mut self, a: (f64, f64), b: (f64, f64)) {
        let (angle_a, angle_b) = (a.1.atan2(a.0), b.1.atan2(b.0));
        // A segment not through the sensor subtends less than pi: walk the short way round.
        let sweep = wrap_angle(angle_b - angle_a);
        let from = if sweep >= 0.0 { angle_a } else { angle_b };
        let first = ((from + PI) / self.increment).floor() as i64;
        let last = ((from + sweep.abs() + PI) / self.increment).ceil() as i64;
        let (ex, ey) = (b.0 - a.0, b.1 - a.1);
        // Ray t * d meets a + u * e where t = (a x e) / (d x e), u = (a x d) / (d x e)
        // (Cramer's rule on the 2x2 system; cf. Goldman, Graphics Gems I, p. 304).
        let a_cross_e = a.0 * ey - a.1 * ex;
        let n = self.dirs.len();
        let mut i = first.rem_euclid(n as i64) as usize;
        for _ in first..=last {
            let (dx, dy) = self.dirs[i];
            let denom = dx * ey - dy * ex;
            if denom.abs() >= 1e-12 {
                let inv = 1.0 / denom;
                let t = a_cross_e * inv;
                let u = (a.0 * dy - a.1 * dx) * inv;
                if t >= 0.0 && (0.0..=1.0).contains(&u) && t < self.nearest[i] {
                    self.nearest[i] = t;
                }
            }
            i += 1;
            if i == n {
                i = 0;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use rand::SeedableRng;

    fn quiet() -> Lidar {
        Lidar::new(&LidarConfig {
            range_std: 0.0,
            ..LidarConfig::default()
        })
    }

    fn square(half: f64) -> Vec<Segment> {
        let c = [(-half, -half), (half, -half), (half, half), (-half, half)]
            .map(|(x, y)| Point2::new(x, y));
        (0..4).map(|k| Segment::new(c[k], c[(k + 1) % 4])).collect()
    }

    #[test]
    fn every_beam_agrees_with_brute_force_casting() {
        let mut lidar = quiet();
        let mut walls = square(1.5);
        walls.push(Segment::new(Point2::new(0.3, -0.4), Point2::new(0.8, 0.2)));
        walls.push(Segment::new(Point2::new(-0.9, 0.9), Point2::new(-0.2, 0.5)));
        let pose = Pose2::new(0.1, -0.2, 2.5);
        let scan = lidar.scan(pose, &[&walls], &mut ChaCha8Rng::seed_from_u64(0));
        for (i, &r) in scan.ranges.iter().enumerate() {
            let a = pose.theta + scan.angle_min + i as f64 * scan.angle_increment;
            let brute = walls
                .iter()
                .filter_map(|w| w.ray_hit(pose.position(), (a.cos(), a.sin())))
                .fold(f64::INFINITY, f64::min);
            assert!(
                (f64::from(r) - brute).abs() < 1e-5,
                "beam {i}: {r} vs {brute}"
            );
        }
    }

    #[test]
    fn nothing_in_range_reads_infinity_and_too_close_minus_infinity() {
        let mut lidar = quiet();
        let far = square(10.0);
        let scan = lidar.scan(Pose2::default(), &[&far], &mut ChaCha8Rng::seed_from_u64(0));
        assert!(scan.ranges.iter().all(|r| *r == f32::INFINITY));
        let near = square(0.08);
        let scan = lidar.scan(
            Pose2::default(),
            &[&near],
            &mut ChaCha8Rng::seed_from_u64(0),
        );
        assert!(scan.ranges.iter().all(|r| *r == f32::NEG_INFINITY));
    }
}
