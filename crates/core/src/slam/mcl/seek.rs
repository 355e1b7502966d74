//! The move that tells hypotheses apart: while MCL weighs several places the robot could
//! be, drive to where they disagree most about what the lidar will see. A lidar that does
//! not see all round turns in place first (a full turn shows everything near); then the
//! robot picks, among the places it can reach in a straight line through the space its
//! lidar sees open, the one where the hypotheses' views differ in the most beams for the
//! driving it costs (active localisation's rule of going where the expected
//! measurements differ, Fox, Burgard and Thrun, "Active Markov Localization for Mobile
//! Robots", 1998), and drives there, a leg at a time.

use super::known_map::KnownMap;
use crate::data::LaserScan;
use crate::geometry::{Pose2, wrap_angle};

/// Bearings tried, every 10°, and the lidar's clearance read over ±15° of each.
const BEARING_STEP_DEG: f64 = 10.0;
const SECTOR_DEG: f64 = 15.0;
/// Places tried along a bearing, every half metre up to the longest leg.
const LEG_STEP_M: f64 = 0.5;
const LONGEST_LEG_M: f64 = 3.0;
/// A hypothesis's view of a place: this many beams over the lidar's field of view.
const VIEW_BEAMS: usize = 36;
/// Two views differ in a beam whose ranges are this far apart (several of the
/// likelihood field's σ_hit of 0.2 m; AMCL's `laser_sigma_hit`).
const DIFFER_M: f64 = 0.5;
/// A beam of difference is worth this much driving, metres.
const METRES_PER_BEAM: f64 = 1.0;
/// The leg driven when no place tells the hypotheses apart: on into the open.
const WANDER_LEG_M: f64 = 1.0;
/// Steps (0.1 s each) without moving more than `STILL_M` or `STILL_RAD` before the way
/// ahead counts as refused, and how far the robot must then move on before it may try
/// that way again.
const STALL_STEPS: u32 = 20;
const STILL_M: f64 = 0.01;
const STILL_RAD: f64 = 0.02;
const MOVED_ON_M: f64 = 0.3;
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
    /// The odometry pose when the robot last moved, and the steps since.
    still: Option<(Pose2, u32)>,
    /// A way the robot would not go (odometry heading), and where it was refused.
    refused: Option<(f64, Pose2)>,
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
        self.watch_for_stalls(odom);
        let done = self
            .leg
            .is_none_or(|(_, from, length)| from.position().distance(odom.position()) >= length);
        let blocked = clearance(scan, 0.0) < clear;
        if done || (blocked && self.aimed(odom)) {
            let refused = self.refused.map(|(h, _)| wrap_angle(h - odom.theta));
            self.leg = best_leg(scan, map, hypotheses, clear, refused)
                .map(|(b, length)| (wrap_angle(odom.theta + b), odom, length));
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

    /// Asked to move, the robot has not for `STALL_STEPS` steps: something the lidar's
    /// clearance misses (or the pilot's own safety stop) holds it. The way it was
    /// driving is refused, and another leg chosen, until it has moved on.
    fn watch_for_stalls(&mut self, odom: Pose2) {
        let moved = self.still.is_none_or(|(at, _)| {
            at.position().distance(odom.position()) > STILL_M
                || wrap_angle(odom.theta - at.theta).abs() > STILL_RAD
        });
        let (since, steps) = match self.still {
            Some((at, n)) if !moved => (at, n + 1),
            _ => (odom, 0),
        };
        self.still = Some((since, steps));
        if steps >= STALL_STEPS {
            self.refused = Some((odom.theta, odom));
            self.leg = None;
            self.still = Some((odom, 0));
        }
        if self
            .refused
            .is_some_and(|(_, at)| at.position().distance(odom.position()) > MOVED_ON_M)
        {
            self.refused = None;
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

/// The leg to drive: a bearing (robot frame) and a length, to the place in the open the
/// lidar sees where the hypotheses' views differ in the most beams, less one for every
/// `METRES_PER_BEAM` of driving; when no place tells them apart by a beam, the most open
/// bearing, a short leg. Bearings within twice the clearance sector of `refused` (robot
/// frame) are not taken.
pub fn best_leg(
    scan: &LaserScan,
    map: &KnownMap,
    hypotheses: &[(Pose2, f64)],
    clear: f64,
    refused: Option<f64>,
) -> Option<(f64, f64)> {
    let steps = (360.0 / BEARING_STEP_DEG).round() as usize;
    let top = &hypotheses[..hypotheses.len().min(MOST_HYPOTHESES)];
    // (value, length, bearing) of the best place; (open, bearing) of the most open way.
    let mut best: Option<(f64, f64, f64)> = None;
    let mut widest: Option<(f64, f64)> = None;
    for k in 0..steps {
        let b = wrap_angle((k as f64 * BEARING_STEP_DEG).to_radians());
        let open = clearance(scan, b);
        let barred =
            refused.is_some_and(|r| wrap_angle(b - r).abs() < 2.0 * SECTOR_DEG.to_radians());
        if open < clear + 0.1 || barred {
            continue;
        }
        if widest.is_none_or(|(o, _)| open > o) {
            widest = Some((open, b));
        }
        let reach = (open - clear).min(LONGEST_LEG_M);
        let mut t = LEG_STEP_M.min(reach);
        while t <= reach + 1e-9 {
            let beams = disagreement(map, scan, top, Pose2::new(t * b.cos(), t * b.sin(), b));
            let value = beams - t / METRES_PER_BEAM;
            if beams >= 1.0 && best.is_none_or(|(v, _, _)| value > v + 1e-9) {
                best = Some((value, t, b));
            }
            t += LEG_STEP_M;
        }
    }
    match best {
        Some((_, length, b)) => Some((b, length)),
        None => widest.map(|(open, b)| (b, (open - clear).clamp(0.1, WANDER_LEG_M))),
    }
}

/// How many beams the hypotheses' views differ in at `offset` (a pose in the robot's
/// frame): each pair's count of beams whose ranges differ by more than `DIFFER_M`,
/// weighted by both hypotheses' shares. A hypothesis that would put the place inside a
/// wall differs from the others in every beam: getting there rules it out.
fn disagreement(map: &KnownMap, scan: &LaserScan, top: &[(Pose2, f64)], offset: Pose2) -> f64 {
    let span = (scan.angle_increment * scan.ranges.len() as f64)
        .clamp(-std::f64::consts::TAU, std::f64::consts::TAU);
    let views: Vec<Option<Vec<f64>>> = (top.iter())
        .map(|&(h, _)| {
            let at = h.compose(offset);
            map.is_free(at.position()).then(|| {
                (0..VIEW_BEAMS)
                    .map(|k| {
                        let a = at.theta + scan.angle_min + span * k as f64 / VIEW_BEAMS as f64;
                        map.ray_cast(at.x, at.y, a.cos(), a.sin(), scan.range_max)
                    })
                    .collect()
            })
        })
        .collect();
    let (mut sum, mut total) = (0.0, 0.0);
    for i in 0..top.len() {
        for j in i + 1..top.len() {
            let w = top[i].1 * top[j].1;
            let differ = match (&views[i], &views[j]) {
                (Some(a), Some(b)) => a
                    .iter()
                    .zip(b)
                    .filter(|(x, y)| (*x - *y).abs() > DIFFER_M)
                    .count(),
                (None, None) => 0,
                _ => VIEW_BEAMS,
            };
            sum += w * differ as f64;
            total += w;
        }
    }
    if total > 0.0 { sum / total } else { 0.0 }
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

    /// One hypothesis near each end of the corridor, facing +x, equally heavy.
    fn corridor_ends() -> [(Pose2, f64); 2] {
        [
            (Pose2::new(1.0, 1.0, 0.0), 0.5),
            (Pose2::new(5.0, 1.0, 0.0), 0.5),
        ]
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
        let hyps = corridor_ends();
        let (b, _) = best_leg(&open_scan(), &map, &hyps, 0.3, None).unwrap();
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
    fn a_robot_held_still_while_driving_ahead_turns_to_another_way() {
        // Two hypotheses that differ ahead: the move drives forward, but the robot does
        // not move (held by something the lidar's clearance does not show).
        let map = corridor();
        let hyps = corridor_ends();
        let mut scan = open_scan();
        scan.ranges = vec![3.0; 360];
        let mut seek = Seek::default();
        let odom = Pose2::new(0.0, 0.0, 0.0);
        let first = seek.step(odom, &scan, &map, &hyps, 0.3);
        let aimed = seek.leg.map(|(h, _, _)| h).unwrap();
        let drives: Vec<SeekDrive> = (0..2 * STALL_STEPS)
            .map(|_| seek.step(odom, &scan, &map, &hyps, 0.3))
            .collect();
        // Once the stall is noticed, the way it was taking is refused.
        let now = seek.leg.map(|(h, _, _)| h).unwrap();
        assert!(
            wrap_angle(now - aimed).abs() >= 2.0 * SECTOR_DEG.to_radians() - 1e-9,
            "{first:?} then {drives:?}: still heading {now} (was {aimed})"
        );
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
