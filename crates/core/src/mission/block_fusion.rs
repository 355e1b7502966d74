//! A block's centre from many looks, before the arm reaches for it. One camera sighting
//! is too coarse to pick by (seed 001's camera model: 10 cm in range, 4 degrees in
//! bearing), so the pick fuses every sighting of the block's markers and the lidar's
//! outline of it. Each is a Gaussian measurement of the centre in the world frame, and
//! they are summed in information form: the information matrix is the sum of the
//! inverse covariances and the estimate solves it against the sum of the weighted
//! measurements (inverse-variance weighting; Thrun, Probabilistic Robotics 3.5.1).
//! Pure: the caller hands in the poses, sightings and scans, and no clock is read.

use super::block_fit::{SquareFit, outline_fit};
use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::{Matrix2, Vector2};

/// How precisely the camera measures a marker: standard deviations of its range (metres)
/// and bearing (radians), as the twin's `[sim.camera]` `dist_std` and `angle_std_deg`
/// (seed 001's measurement noise) describe it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraNoise {
    pub range_std: f64,
    pub bearing_std: f64,
}

/// How precisely the lidar measures its ranges (metres), as `[sim.lidar]` `range_std`
/// describes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LidarNoise {
    pub range_std: f64,
}

/// The sightings of the block from one standing pose.
#[derive(Clone, Copy, Debug, PartialEq)]
struct View {
    pose: Pose2,
    noise: CameraNoise,
    /// Bearings are summed relative to the first, so none wraps round.
    first_bearing: f64,
    range_sum: f64,
    bearing_sum: f64,
    count: u32,
}

/// Whether a robot at `b` stands where it stood at `a`: within a millimetre and a tenth
/// of a degree (navdeck's; odometry of a robot at rest moves by less).
fn still(a: Pose2, b: Pose2) -> bool {
    a.position().distance(b.position()) <= 1e-3
        && wrap_angle(a.theta - b.theta).abs() <= 0.1f64.to_radians()
}

/// Each beam's summed ranges and count over the scans from one standing pose.
#[derive(Clone, Debug, PartialEq)]
struct Beams {
    pose: Pose2,
    sums: Vec<(f64, u32)>,
    /// Scans taken from `pose`.
    scans: u32,
}

/// The information (inverse covariance) and weighted sum of one kind of measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Information {
    matrix: Matrix2<f64>,
    vector: Vector2<f64>,
}

impl Information {
    const NONE: Information = Information {
        matrix: Matrix2::new(0.0, 0.0, 0.0, 0.0),
        vector: Vector2::new(0.0, 0.0),
    };

    /// Adds a measurement `z` with covariance `cov`; a covariance that cannot be inverted
    /// adds nothing.
    fn add(&mut self, z: Point2, cov: Matrix2<f64>) {
        if let Some(inv) = cov.try_inverse() {
            self.matrix += inv;
            self.vector += inv * Vector2::new(z.x, z.y);
        }
    }

    /// The fused measurement and its covariance.
    fn solve(&self) -> Option<(Point2, Matrix2<f64>)> {
        let cov = self.matrix.try_inverse()?;
        let x = cov * self.vector;
        (x.iter().all(|v| v.is_finite())).then_some((Point2::new(x.x, x.y), cov))
    }
}

/// A covariance with standard deviations `along` and `across` the direction `angle`.
fn oriented(angle: f64, along: f64, across: f64) -> Matrix2<f64> {
    let (s, c) = angle.sin_cos();
    let rotation = Matrix2::new(c, -s, s, c);
    rotation * Matrix2::new(along * along, 0.0, 0.0, across * across) * rotation.transpose()
}

/// The looks at one block so far. See the module comment.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockFusion {
    /// The block's side, metres.
    size: f64,
    /// The camera's sightings, by the pose they were taken from.
    views: Vec<View>,
    /// The lidar's newest outline fit from where the robot stands, with its covariance,
    /// and the last fit from each place it stood before (independent looks: other beams).
    outline: Option<(SquareFit, Matrix2<f64>)>,
    earlier: Vec<(SquareFit, Matrix2<f64>)>,
    /// The lidar's beams averaged over the scans from where the robot stands.
    beams: Option<Beams>,
}

impl BlockFusion {
    /// No looks yet at a block of side `size` metres.
    pub fn new(size: f64) -> Self {
        Self {
            size,
            views: Vec::new(),
            outline: None,
            earlier: Vec::new(),
            beams: None,
        }
    }

    /// Camera sightings fused so far.
    pub fn sightings(&self) -> usize {
        self.views.iter().map(|v| v.count as usize).sum()
    }

    /// A sighting of one of the block's markers, `range` metres away at `bearing` from the
    /// camera of a robot at `pose` (the camera at the robot's centre, as the twin's and
    /// seed 001's r and alpha are). Sightings from one standing pose are averaged in range
    /// and bearing first: every line of sight from there passes through the camera, and
    /// fusing them one by one, each turned by its own noisy bearing, would pull the
    /// estimate towards it.
    pub fn add_sighting(&mut self, pose: Pose2, range: f64, bearing: f64, noise: CameraNoise) {
        if !(range.is_finite() && bearing.is_finite() && range > 0.0) {
            return;
        }
        match self.views.last_mut() {
            Some(view) if still(view.pose, pose) => {
                view.range_sum += range;
                view.bearing_sum += wrap_angle(bearing - view.first_bearing);
                view.count += 1;
            }
            _ => self.views.push(View {
                pose,
                noise,
                first_bearing: bearing,
                range_sum: range,
                bearing_sum: 0.0,
                count: 1,
            }),
        }
    }

    /// The fused sightings, without the face's turn: each standing pose's mean range and
    /// bearing is a measurement of the marker, and the centre lies half a side further
    /// along the line of sight, with range noise along it and bearing noise times the range
    /// across it (the linearised measurement model of seed 001's EKF), both over the count.
    fn camera_information(&self) -> Information {
        let mut info = Information::NONE;
        for view in &self.views {
            let n = f64::from(view.count);
            let range = view.range_sum / n;
            let angle = view.pose.theta + view.first_bearing + view.bearing_sum / n;
            let reach = range + self.size / 2.0;
            let (x, y) = (view.pose.x, view.pose.y);
            let z = Point2::new(x + reach * angle.cos(), y + reach * angle.sin());
            let along = view.noise.range_std / n.sqrt();
            let across = (range * view.noise.bearing_std / n.sqrt()).max(1e-6);
            info.add(z, oriented(angle, along.max(1e-6), across));
        }
        info
    }

    /// The fused sightings alone: their mean and covariance, with the face's turn added
    /// once (see `add_sighting`).
    pub fn camera_estimate(&self) -> Option<(Point2, Matrix2<f64>)> {
        let (z, cov) = self.camera_information().solve()?;
        // A face turned by a uniform angle within +-45 degrees: E[sin^2] = 1/2 - 1/pi.
        let turn_var = (self.size / 2.0).powi(2) * (0.5 - std::f64::consts::FRAC_1_PI);
        Some((z, cov + Matrix2::identity() * turn_var))
    }

    /// A lidar scan taken with the robot at `pose`. While the robot stands still each
    /// beam hits the same spot, so each beam's ranges are averaged over the scans (their
    /// noise falls as 1/sqrt(n)); a robot that moved starts the averages again. The
    /// block's outline is then fitted to the averaged returns near the estimate, once they
    /// are steady enough. Returns whether an outline of the block's size was found.
    pub fn add_scan(&mut self, pose: Pose2, scan: &LaserScan, noise: LidarNoise) -> bool {
        let Some((near, _)) = self.estimate() else {
            return false;
        };
        let moved = (self.beams.as_ref())
            .is_none_or(|b| !still(b.pose, pose) || b.sums.len() != scan.ranges.len());
        if moved {
            self.earlier.extend(self.outline.take());
            self.beams = Some(Beams {
                pose,
                sums: vec![(0.0, 0); scan.ranges.len()],
                scans: 0,
            });
        }
        let Some(beams) = self.beams.as_mut() else {
            return false;
        };
        for (k, &r) in scan.ranges.iter().enumerate() {
            let r = f64::from(r);
            if r >= scan.range_min && r <= scan.range_max {
                beams.sums[k].0 += r;
                beams.sums[k].1 += 1;
            }
        }
        beams.scans += 1;
        let scans = beams.scans;
        // Only beams that returned in every scan: a surface near the lidar's least or
        // greatest range returns only when the noise takes it inside, and the mean of
        // those returns would be pushed away from the limit.
        let returns: Vec<Point2> = (beams.sums.iter().enumerate())
            .filter(|(_, (_, n))| *n == scans)
            .map(|(k, &(sum, n))| {
                let a = pose.theta + scan.angle_min + k as f64 * scan.angle_increment;
                let r = sum / f64::from(n);
                Point2::new(pose.x + r * a.cos(), pose.y + r * a.sin())
            })
            .collect();
        // Where the block may be: three standard deviations of the estimate so far, and
        // never less than the block's own size (navdeck's).
        let search = (3.0 * self.std().unwrap_or(0.0)).max(self.size);
        let viewer = pose.position();
        let spread = noise.range_std / f64::from(scans.max(1)).sqrt();
        // Fitted once a face's averaged returns spread (4 standard deviations) over at
        // most half the extent that counts as two ends seen, so a face is told from a span.
        if 4.0 * spread > 0.3 * self.size {
            return false;
        }
        let Some(fit) = outline_fit(&returns, near, self.size, search, viewer, spread) else {
            return false;
        };
        let gap = fit.centre.distance(viewer) * scan.angle_increment.abs();
        let n = fit.points.max(1) as f64;
        // One face seen: the square is turned as that face's returns lie, a line fitted
        // to n points over a side, whose slope has standard deviation spread /
        // (side * sqrt(n / 12)) (least squares), and the centre half a side behind the
        // face swings sideways by half a side times that.
        let one_face = fit.spanned[0] != fit.spanned[1];
        let tilt = if one_face {
            spread / (self.size * (n / 12.0).sqrt())
        } else {
            0.0
        };
        // Per axis of the square: an axis whose two ends were seen is placed midway
        // between them, each end off by up to a beam gap (uniform: variance gap^2/12),
        // and by the tilt; an axis seen as one face is placed from the mean of its
        // averaged returns.
        let face = |spanned: bool| {
            if spanned {
                (gap * gap / 12.0 + (self.size / 2.0 * tilt).powi(2)).sqrt()
            } else {
                spread / n.sqrt()
            }
        };
        let cov = oriented(fit.turn, face(fit.spanned[0]), face(fit.spanned[1]));
        self.outline = Some((fit, cov));
        true
    }

    /// The centre as every look so far places it, and its covariance: the camera's fused
    /// sightings and the lidar's outline, weighted by their inverse covariances.
    pub fn estimate(&self) -> Option<(Point2, Matrix2<f64>)> {
        let mut all = Information::NONE;
        if let Some((z, cov)) = self.camera_estimate() {
            all.add(z, cov);
        }
        for (fit, cov) in self.earlier.iter().chain(&self.outline) {
            all.add(fit.centre, *cov);
        }
        all.solve()
    }

    /// The estimate's largest standard deviation (along its worst direction), metres.
    pub fn std(&self) -> Option<f64> {
        let (_, cov) = self.estimate()?;
        let eigen = cov.symmetric_eigenvalues();
        Some(eigen.max().max(0.0).sqrt())
    }

    /// Whether the lidar has outlined the block.
    pub fn outlined(&self) -> bool {
        self.outline.is_some() || !self.earlier.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, Normal};

    const CAMERA: CameraNoise = CameraNoise {
        range_std: 0.1,
        bearing_std: 0.0698,
    };

    #[test]
    fn sightings_from_one_place_shrink_the_error_as_their_count_grows() {
        // A block 0.3 m ahead, its marker 0.275 m away, read 100 times with seed 001's noise.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let range = Normal::new(0.275, CAMERA.range_std).unwrap();
        let bearing = Normal::new(0.0, CAMERA.bearing_std).unwrap();
        let mut fusion = BlockFusion::new(0.05);
        let mut spread = Vec::new();
        for k in 1..=100 {
            let (r, b) = (range.sample(&mut rng), bearing.sample(&mut rng));
            fusion.add_sighting(Pose2::default(), r, b, CAMERA);
            if k == 1 || k == 100 {
                let (_, cov) = fusion.camera_information().solve().unwrap();
                spread.push(cov[(0, 0)].sqrt());
            }
        }
        // Along the line of sight the standard deviation falls as 1/sqrt(n).
        assert!(
            (spread[0] - 0.1).abs() < 0.01 && (spread[1] - 0.01).abs() < 0.001,
            "{spread:?}"
        );
        let (at, _) = fusion.camera_information().solve().unwrap();
        assert!(at.distance(Point2::new(0.3, 0.0)) < 0.03, "{at:?}");
        assert_eq!(fusion.sightings(), 100);
    }

    #[test]
    fn sightings_from_two_sides_meet_where_their_lines_of_sight_cross() {
        // Exact bearings from two places at right angles, ranges 10 cm too long: the
        // bearings, 20 times surer at this range, win.
        let centre = Point2::new(1.0, 1.0);
        let mut fusion = BlockFusion::new(0.05);
        for pose in [Pose2::new(0.7, 1.0, 0.0), Pose2::new(1.0, 0.7, 1.0)] {
            let to = (centre.y - pose.y).atan2(centre.x - pose.x);
            let range = pose.position().distance(centre) - 0.025 + 0.1;
            for _ in 0..10 {
                fusion.add_sighting(pose, range, to - pose.theta, CAMERA);
            }
        }
        let (at, _) = fusion.camera_information().solve().unwrap();
        assert!(at.distance(centre) < 0.01, "{at:?}");
    }

    /// A scan from the origin with 1 degree beams: those within `half` of straight ahead
    /// hit a face `at` metres ahead, with 1 cm noise; the rest see nothing.
    fn face_scan(at: f64, half: f64, rng: &mut ChaCha8Rng) -> LaserScan {
        let noise = Normal::new(0.0, 0.01).unwrap();
        let increment = 1f64.to_radians();
        let ranges = (0..360)
            .map(|k| -std::f64::consts::PI + f64::from(k) * increment)
            .map(|a| {
                if a.abs() <= half {
                    (at / a.cos() + noise.sample(rng)) as f32
                } else {
                    f32::INFINITY
                }
            })
            .collect();
        LaserScan {
            angle_min: -std::f64::consts::PI,
            angle_increment: increment,
            range_min: 0.12,
            range_max: 3.5,
            ranges,
        }
    }

    #[test]
    fn the_lidar_outline_outweighs_the_camera_and_places_the_centre_to_millimetres() {
        // A 5 cm block 0.3 m ahead, face on: its near face at x = 0.275 (5.2 degrees
        // either side); the camera's sightings put the block 4 cm to the side.
        let centre = Point2::new(0.3, 0.0);
        let lidar = LidarNoise { range_std: 0.01 };
        let mut fusion = BlockFusion::new(0.05);
        for _ in 0..5 {
            fusion.add_sighting(Pose2::default(), 0.275, 0.04 / 0.3, CAMERA);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let scans = (0..12)
            .filter(|_| fusion.add_scan(Pose2::default(), &face_scan(0.275, 0.09, &mut rng), lidar))
            .count();
        // Averaged over 8 scans, a face's returns are steady enough to fit.
        assert_eq!(scans, 5);
        assert!(fusion.outlined());
        let (at, _) = fusion.estimate().unwrap();
        assert!(at.distance(centre) < 0.004, "{at:?}");
        assert!(fusion.std().unwrap() < 0.004);
    }

    #[test]
    fn nothing_seen_places_nothing() {
        let mut fusion = BlockFusion::new(0.05);
        assert!(fusion.estimate().is_none() && fusion.std().is_none());
        fusion.add_sighting(Pose2::default(), f64::NAN, 0.0, CAMERA);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let scan = face_scan(0.3, 0.01, &mut rng);
        assert!(!fusion.add_scan(Pose2::default(), &scan, LidarNoise { range_std: 0.01 }));
        assert_eq!(fusion.sightings(), 0);
    }
}
