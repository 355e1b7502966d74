//! The measurement models that weigh a particle by how well the scan fits the map from
//! its pose: the likelihood field (Probabilistic Robotics table 6.3, AMCL's default) and
//! the beam model with a ray traced per beam (table 6.1, seed 002's "beam-model ... ray
//! tracing"). Both return a log-likelihood: a sum over beams, free of underflow.

use super::beam_memo::{BeamTable, RangeMemo};
use super::config::{MeasurementModel, SensorModel};
use super::known_map::KnownMap;
use crate::data::LaserScan;
use crate::geometry::Pose2;

/// The beams of a scan that are weighed: evenly spread, at most `max_beams`.
#[derive(Clone, Debug, Default)]
pub struct Beams {
    /// Direction of each beam in the robot's frame, as (cos, sin) and as an angle.
    pub directions: Vec<(f64, f64)>,
    pub angles: Vec<f64>,
    /// Measured range, metres; `max_range` where nothing was hit.
    pub ranges: Vec<f64>,
    pub max_range: f64,
}

impl Beams {
    /// Picks the beams to weigh (AMCL's stride over the scan); readings that are not a
    /// number or fall short of the sensor's least range are skipped.
    pub fn pick(scan: &LaserScan, max_beams: u32) -> Self {
        let n = scan.ranges.len();
        let stride = n.div_ceil(max_beams.max(1) as usize).max(1);
        let mut beams = Beams {
            max_range: scan.range_max,
            ..Beams::default()
        };
        for k in (0..n).step_by(stride) {
            let r = f64::from(scan.ranges[k]);
            if r.is_nan() || r < scan.range_min {
                continue;
            }
            // sensor_msgs/LaserScan: beam k points along angle_min + k * angle_increment.
            let a = scan.angle_min + k as f64 * scan.angle_increment;
            beams.directions.push((a.cos(), a.sin()));
            beams.angles.push(a);
            beams.ranges.push(r.min(scan.range_max));
        }
        beams
    }

    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }
}

/// A sensor model ready to weigh particles: the per-cell likelihoods of the field are
/// computed once per map and config.
#[derive(Clone, Debug)]
pub struct Weigher {
    model: SensorModel,
    /// Likelihood field: ln(z_hit · N(d; 0, σ) + z_rand / z_max) for each cell's distance d
    /// (table 6.3, line 8), over the map's window of kept distances; `off_map` for an end
    /// outside it, on the map or off (farther than the map's reach, which is at least the
    /// field's cap).
    field: Vec<f32>,
    off_map: f32,
    /// Beam model: ln p(z | z*) tabulated, and the ranges traced so far.
    table: Option<BeamTable>,
    memo: RangeMemo,
}

/// The Gaussian density N(x; 0, σ²).
fn gaussian(x: f64, sigma: f64) -> f64 {
    // Probabilistic Robotics (6.4): the hit's density.
    (-(x * x) / (2.0 * sigma * sigma)).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma)
}

impl Weigher {
    /// The weigher for `map`; `max_range` is the sensor's, for z_rand's density.
    pub fn new(map: &KnownMap, config: &MeasurementModel, max_range: f64) -> Self {
        let c = config;
        let cap = c.likelihood_max_dist;
        let q = |d: f64| (c.z_hit * gaussian(d.min(cap), c.sigma_hit) + c.z_rand / max_range).ln();
        let field = match c.model {
            SensorModel::LikelihoodField => (map.near_distances())
                .map(|d| q(f64::from(d)) as f32)
                .collect(),
            SensorModel::Beam => Vec::new(),
        };
        Self {
            model: c.model,
            field,
            off_map: q(cap) as f32,
            table: (c.model == SensorModel::Beam).then(|| BeamTable::new(c, max_range)),
            memo: RangeMemo::default(),
        }
    }

    /// ln p(scan | pose, map).
    pub fn log_likelihood(&mut self, map: &KnownMap, pose: Pose2, beams: &Beams) -> f64 {
        match self.model {
            SensorModel::LikelihoodField => self.field_log_likelihood(map, pose, beams),
            SensorModel::Beam => self.beam_log_likelihood(map, pose, beams),
        }
    }

    /// The share of the beams that hit something whose ends lie within `near` metres of
    /// a mapped obstacle, seen from `pose`: how much of the scan the map explains there
    /// (AMCL's beam skipping counts the same agreement, `beam_skip_distance`).
    pub fn agreement(map: &KnownMap, pose: Pose2, beams: &Beams, near: f64) -> Option<f64> {
        let (s, c) = pose.theta.sin_cos();
        let (mut hits, mut near_wall) = (0usize, 0usize);
        for (&(bc, bs), &r) in beams.directions.iter().zip(&beams.ranges) {
            if r >= beams.max_range {
                continue;
            }
            let (dc, ds) = (c * bc - s * bs, s * bc + c * bs);
            hits += 1;
            let d = map.distance_at(pose.x + r * dc, pose.y + r * ds);
            near_wall += usize::from(d.is_some_and(|d| f64::from(d) <= near));
        }
        (hits > 0).then(|| near_wall as f64 / hits as f64)
    }

    /// Table 6.3: each beam's end looked up in the field; readings at the maximum range
    /// are skipped (line 4).
    fn field_log_likelihood(&self, map: &KnownMap, pose: Pose2, beams: &Beams) -> f64 {
        let (s, c) = pose.theta.sin_cos();
        let mut sum = 0.0f32;
        for (&(bc, bs), &r) in beams.directions.iter().zip(&beams.ranges) {
            if r >= beams.max_range {
                continue;
            }
            // The beam's direction in the map: the robot's heading plus the beam's angle.
            let (dc, ds) = (c * bc - s * bs, s * bc + c * bs);
            sum += match map.near_index_at(pose.x + r * dc, pose.y + r * ds) {
                Some(k) => self.field[k],
                None => self.off_map,
            };
        }
        f64::from(sum)
    }

    /// Table 6.1: each beam against the range traced in the map from the particle's cell
    /// (remembered, see `beam_memo`).
    fn beam_log_likelihood(&mut self, map: &KnownMap, pose: Pose2, beams: &Beams) -> f64 {
        let max = beams.max_range;
        let table = self.table.as_ref().expect("built for the beam model");
        let Some(cell) = map.index_of(pose.x, pose.y) else {
            // Off the map nothing is hit: every beam expects the maximum range.
            let top = table.index(max);
            let sum: f32 = (beams.ranges.iter())
                .map(|&z| table.log_p(table.index(z), top))
                .sum();
            return f64::from(sum);
        };
        let mut sum = 0.0f32;
        for (&a, &z) in beams.angles.iter().zip(&beams.ranges) {
            let expected = self.memo.expected(map, table, cell, pose.theta + a, max);
            sum += table.log_p(table.index(z), expected);
        }
        f64::from(sum)
    }

    /// Forgets the ranges the beam model traced (for a benchmark of a cold start).
    pub fn forget_traced(&mut self) {
        self.memo.clear();
    }
}

/// p(z | z*) of the beam model: a hit near the expected range, a short reading from
/// something unmapped, a maximum-range reading and random noise (Probabilistic Robotics
/// (6.2)-(6.12), the normalisers of the hit and short terms as there).
pub fn beam_probability(z: f64, expected: f64, max: f64, c: &MeasurementModel) -> f64 {
    let p_hit = if (0.0..=max).contains(&z) {
        gaussian(z - expected, c.sigma_hit)
    } else {
        0.0
    };
    // (6.7)-(6.8): η = 1 / (1 - e^(-λ z*)).
    let p_short = if z <= expected && expected > 0.0 {
        let eta = 1.0 / (1.0 - (-c.lambda_short * expected).exp());
        eta * c.lambda_short * (-c.lambda_short * z).exp()
    } else {
        0.0
    };
    let p_max = if z >= max { 1.0 } else { 0.0 };
    let p_rand = if z < max { 1.0 / max } else { 0.0 };
    c.z_hit * p_hit + c.z_short * p_short + c.z_max * p_max + c.z_rand * p_rand
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use crate::map::grid::OccupancyGrid;

    #[test]
    fn the_beam_model_against_hand_worked_values() {
        let c = MeasurementModel::default();
        // z = z* = 2 m, range 3.5 m, σ 0.2, λ 0.1:
        // hit 0.5 · 1/(√(2π) 0.2) = 0.997356; short 0.05 · 0.1 e^-0.2 / (1 - e^-0.2) =
        // 0.05 · 0.1 · 0.818731 / 0.181269 = 0.022583; rand 0.5 / 3.5 = 0.142857.
        let p = beam_probability(2.0, 2.0, 3.5, &c);
        assert!((p - (0.997356 + 0.022583 + 0.142857)).abs() < 1e-5, "{p}");
        // A maximum-range reading where the map has a wall at 1 m: only z_max remains.
        let p = beam_probability(3.5, 1.0, 3.5, &c);
        assert!((p - 0.05).abs() < 1e-12, "{p}");
        // 0.4 m beyond the expected range: the hit term at two σ, no short term.
        let p = beam_probability(1.4, 1.0, 3.5, &c);
        let hit = 0.5 * (-2.0f64).exp() / ((2.0 * std::f64::consts::PI).sqrt() * 0.2);
        assert!((p - (hit + 0.5 / 3.5)).abs() < 1e-12, "{p}");
    }

    fn wall_map() -> KnownMap {
        // 4 m x 2 m at 0.05 m, a wall at x = 2 m (column 40) and free elsewhere.
        let mut g = OccupancyGrid::new(80, 40, 0.05, Point2::new(0.0, 0.0), 0);
        for y in 0..40 {
            g.set(40, y, 100);
        }
        KnownMap::new(&g).unwrap()
    }

    fn one_beam(range: f64) -> Beams {
        Beams {
            directions: vec![(1.0, 0.0)],
            angles: vec![0.0],
            ranges: vec![range],
            max_range: 3.5,
        }
    }

    #[test]
    fn the_likelihood_field_against_hand_worked_values() {
        let map = wall_map();
        let c = MeasurementModel::default();
        let mut w = Weigher::new(&map, &c, 3.5);
        // From (1.025, 1.025) facing +x a 0.99 m reading ends in the wall's cell: d = 0.
        let on = w.log_likelihood(&map, Pose2::new(1.025, 1.025, 0.0), &one_beam(0.99));
        let expected = (0.5 / ((2.0 * std::f64::consts::PI).sqrt() * 0.2) + 0.5 / 3.5).ln();
        assert!((on - expected).abs() < 1e-5, "{on} vs {expected}");
        // Ending 0.2 m (4 cells) short of the wall: one σ.
        let short = w.log_likelihood(&map, Pose2::new(1.025, 1.025, 0.0), &one_beam(0.79));
        let g = 0.5 * (-0.5f64).exp() / ((2.0 * std::f64::consts::PI).sqrt() * 0.2);
        assert!((short - (g + 0.5 / 3.5).ln()).abs() < 1e-5, "{short}");
        // A maximum-range reading says nothing.
        assert_eq!(
            w.log_likelihood(&map, Pose2::new(1.0, 1.0, 0.0), &one_beam(3.5)),
            0.0
        );
    }

    #[test]
    fn both_models_prefer_the_true_pose() {
        let map = wall_map();
        for model in [SensorModel::LikelihoodField, SensorModel::Beam] {
            let c = MeasurementModel {
                model,
                ..MeasurementModel::default()
            };
            let mut w = Weigher::new(&map, &c, 3.5);
            let beams = Beams {
                angles: vec![0.0, 0.6f64.atan2(0.8), (-0.6f64).atan2(0.8)],
                directions: vec![(1.0, 0.0), (0.8, 0.6), (0.8, -0.6)],
                ranges: vec![1.0, 1.25, 1.25],
                max_range: 3.5,
            };
            let truth = w.log_likelihood(&map, Pose2::new(1.0, 1.0, 0.0), &beams);
            let off = w.log_likelihood(&map, Pose2::new(0.7, 1.0, 0.0), &beams);
            assert!(truth > off + 0.5, "{model:?}: {truth} vs {off}");
        }
    }

    #[test]
    fn beams_are_picked_evenly_and_bad_readings_skipped() {
        let scan = LaserScan {
            angle_min: 0.0,
            angle_increment: std::f64::consts::TAU / 360.0,
            range_min: 0.12,
            range_max: 3.5,
            ranges: (0..360)
                .map(|k| match k {
                    6 => f32::NAN,
                    12 => 0.05,
                    18 => f32::INFINITY,
                    _ => 1.0,
                })
                .collect(),
        };
        let b = Beams::pick(&scan, 60);
        // Every 6th beam: 60, less the NaN and the one under range_min.
        assert_eq!(b.len(), 58);
        assert_eq!(b.ranges[1], 3.5, "no hit reads as the maximum range");
    }
}
