//! The move that tells hypotheses apart: while MCL weighs several places the robot could
//! be, drive where they disagree most about what the lidar will see. A lidar that does
//! not see all round turns in place first (a full turn shows everything near); then the
//! robot heads for the open bearing along which the hypotheses' maps differ most (the
//! spread of the ranges ray-traced from each, weighted by its share: active
//! localisation's rule of going where the expected measurements differ, Fox, Burgard and
//! Thrun, "Active Markov Localization for Mobile Robots", 1998), a leg at a time.

use super::known_map::KnownMap;
use crate::data::LaserScan;
use crate::geometry::{Pose2, wrap_angle};

/// Bearings tried, every 10°, and the lidar's clearance read over ±15° of each.
const BEARING_STEP_DEG: f64 = 10.0;
const SECTOR_DEG: f64 = 15.0;
/// The longest leg driven before choosing again, metres.
const LEG_M: f64 = 1.0;
/// Hypotheses compared, heaviest first.
const MOST_HYPOTHESES: usize = 8;
/// Facing within this of the chosen bearing, the robot drives ahead.
const AIMED_DEG: f64 = 15.0;

/// What the move asks of the wheels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeekDrive {
    TurnLeft,
    TurnRight,
    Forward,
}

/// The move's state: how far it has turned in place, and the leg it is driving.
#[derive(Clone, Debug, Default)]
pub struct Seek {
    /// Odometry heading at the last step and the turn summed since the start.
    last_heading: Option<f64>,
    turned: f64,
    /// The leg: odometry heading to hold, where it started, how long it is.
    leg: Option<(f64, Pose2, f64)>,
}

impl Seek {
    /// The next drive, from the odometry pose, the newest scan, the filter's hypotheses
    /// and `clear` (metres the robot keeps from what is ahead: footprint and margin).
    pub fn step(
        &mut self,
        odom: Pose2,
        scan: &LaserScan,
        map: &KnownMap,
        hypotheses: &[(Pose2, f64)],
        clear: f64,
    ) -> SeekDrive {
        if let Some(last) = self.last_heading {
            self.turned += wrap_angle(odom.theta - last).abs();
        }
        self.last_heading = Some(odom.theta);
        let sees_all_round = scan.angle_increment.abs() * scan.ranges.len() as f64
            >= std::f64::consts::TAU - 2.0 * scan.angle_increment.abs();
        if !sees_all_round && self.turned < std::f64::consts::TAU {
            return SeekDrive::TurnLeft;
        }
        let done = self
            .leg
            .is_none_or(|(_, from, length)| from.position().distance(odom.position()) >= length);
        let blocked = clearance(scan, 0.0) < clear;
        if done || (blocked && self.aimed(odom)) {
            self.leg = best_bearing(scan, map, hypotheses, clear).map(|(b, open)| {
                (
                    wrap_angle(odom.theta + b),
                    odom,
                    (open - clear).clamp(0.1, LEG_M),
                )
            });
        }
        let Some((heading, _, _)) = self.leg else {
            return SeekDrive::TurnLeft;
        };
        let error = wrap_angle(heading - odom.theta);
        if error.abs() > AIMED_DEG.to_radians() || blocked {
            if error >= 0.0 {
                SeekDrive::TurnLeft
            } else {
                SeekDrive::TurnRight
            }
        } else {
            SeekDrive::Forward
        }
    }

    fn aimed(&self, odom: Pose2) -> bool {
        self.leg
            .is_some_and(|(h, _, _)| wrap_angle(h - odom.theta).abs() <= AIMED_DEG.to_radians())
    }
}

/// The smallest range the lidar reads within `SECTOR_DEG` of `bearing` (robot frame).
fn clearance(scan: &LaserScan, bearing: f64) -> f64 {
    let mut least = scan.range_max;
    for (k, &r) in scan.ranges.iter().enumerate() {
        let a = scan.angle_min + k as f64 * scan.angle_increment;
        let r = f64::from(r);
        if wrap_angle(a - bearing).abs() <= SECTOR_DEG.to_radians() && r >= scan.range_min {
            least = least.min(r);
        }
    }
    least
}

/// The open bearing (robot frame) along which the hypotheses disagree most, and the
/// lidar's clearance along it; the most open bearing when they agree everywhere.
pub fn best_bearing(
    scan: &LaserScan,
    map: &KnownMap,
    hypotheses: &[(Pose2, f64)],
    clear: f64,
) -> Option<(f64, f64)> {
    let steps = (360.0 / BEARING_STEP_DEG).round() as usize;
    let top = &hypotheses[..hypotheses.len().min(MOST_HYPOTHESES)];
    let mut best: Option<(f64, f64, f64)> = None;
    for k in 0..steps {
        let b = wrap_angle((k as f64 * BEARING_STEP_DEG).to_radians());
        let open = clearance(scan, b);
        if open < clear + 0.1 {
            continue;
        }
        // The weighted spread of the ranges each hypothesis's map shows along b.
        let (mut sum, mut sum_sq, mut total) = (0.0, 0.0, 0.0);
        for &(h, w) in top {
            let a = h.theta + b;
            let r = map.ray_cast(h.x, h.y, a.cos(), a.sin(), scan.range_max);
            sum += w * r;
            sum_sq += w * r * r;
            total += w;
        }
        let spread = if total > 0.0 {
            (sum_sq / total - (sum / total).powi(2)).max(0.0)
        } else {
            0.0
        };
        // Ties (hypotheses that agree) go to the more open bearing.
        let score = (spread, open);
        if best.is_none_or(|(s, o, _)| score.0 > s + 1e-9 || (score.0 >= s - 1e-9 && score.1 > o)) {
            best = Some((score.0, score.1, b));
        }
    }
    best.map(|(_, open, b)| (b, open))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use crate::map::grid::OccupancyGrid;

    /// A 6 m x 2 m corridor; one hypothesis at each end, facing +x.
    fn corridor() -> KnownMap {
        let mut g = OccupancyGrid::new(120, 40, 0.05, Point2::new(0.0, 0.0), 0);
        for x in 0..120 {
            g.set(x, 0, 100);
            g.set(x, 39, 100);
        }
        for y in 0..40 {
            g.set(0, y, 100);
            g.set(119, y, 100);
        }
        KnownMap::new(&g).unwrap()
    }

    fn open_scan() -> LaserScan {
        LaserScan {
            angle_min: 0.0,
            angle_increment: std::f64::consts::TAU / 360.0,
            range_min: 0.12,
            range_max: 3.5,
            ranges: vec![0.9; 360],
        }
    }

    #[test]
    fn the_move_heads_where_the_hypotheses_disagree() {
        let map = corridor();
        // Near the west end the wall ahead (+x) is 4.5 m off, near the east end 0.5 m:
        // they disagree ahead and behind, and agree sideways (the walls 0.9 m off).
        let hyps = [
            (Pose2::new(1.0, 1.0, 0.0), 0.5),
            (Pose2::new(5.0, 1.0, 0.0), 0.5),
        ];
        let (b, _) = best_bearing(&open_scan(), &map, &hyps, 0.3).unwrap();
        let along = b.cos().abs();
        assert!(along > 0.9, "bearing {b}");
        let mut seek = Seek::default();
        let drive = seek.step(Pose2::new(0.0, 0.0, 0.0), &open_scan(), &map, &hyps, 0.3);
        assert!(matches!(
            drive,
            SeekDrive::Forward | SeekDrive::TurnLeft | SeekDrive::TurnRight
        ));
    }

    #[test]
    fn a_lidar_that_sees_only_ahead_turns_in_place_first() {
        let map = corridor();
        let mut narrow = open_scan();
        narrow.ranges.truncate(90);
        let hyps = [(Pose2::new(1.0, 1.0, 0.0), 1.0)];
        let mut seek = Seek::default();
        for k in 0..10 {
            let odom = Pose2::new(0.0, 0.0, 0.5 * k as f64);
            assert_eq!(
                seek.step(odom, &narrow, &map, &hyps, 0.3),
                SeekDrive::TurnLeft
            );
        }
    }
}
