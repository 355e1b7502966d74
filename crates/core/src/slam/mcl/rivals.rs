//! Before the filter says "localised": is there another place on the map where the scan
//! fits as well? A particle filter can lose the right hypothesis by the luck of where its
//! particles first fell, and then settle, confidently, on a look-alike. So the scan is
//! matched against the whole map (a coarse lattice of poses scored with a few beams, the
//! best refined by hill climbing with all of them, as a correlative scan matcher searches;
//! Olson, "Real-Time Correlative Scan Matching", 2009), and a pose elsewhere that fits
//! nearly as well as the estimate is a rival: the filter takes it back as a hypothesis
//! and stays "localising" until the scans tell them apart. A rival is judged on the
//! recent scans too, not only the last one: a place the robot's own motion has already
//! ruled out (its recent scans, taken together, fit far worse there) is not taken back,
//! so that evidence gathered over metres of driving is not thrown away.

use super::config::MeasurementModel;
use super::known_map::KnownMap;
use super::sensor::{Beams, Weigher};
use crate::geometry::{Pose2, wrap_angle};
use std::collections::VecDeque;

/// The lattice the map is searched on: positions every 0.2 m, headings every 5° (half
/// the KLD bins' angle), scored with about 20 beams.
const STEP_M: f64 = 0.2;
const STEP_DEG: f64 = 5.0;
const SCREEN_BEAMS: usize = 20;
/// How many of the best lattice poses are refined.
const REFINED: usize = 96;
/// A pose this far from the estimate (or turned this much) is another place.
const ELSEWHERE_M: f64 = 1.0;
const ELSEWHERE_DEG: f64 = 30.0;

/// The poses elsewhere on `map` where `beams` fit within `margin` nats of how well they
/// fit at (the refined) `estimate`, best first.
pub fn rivals(
    map: &KnownMap,
    weigher: &mut Weigher,
    beams: &Beams,
    estimate: Pose2,
    margin: f64,
) -> Vec<Pose2> {
    let screen = every_kth(beams, beams.len().div_ceil(SCREEN_BEAMS).max(1));
    let stride = ((STEP_M / map.resolution).round() as usize).max(1);
    let turns = (360.0 / STEP_DEG).round() as usize;
    let mut scored: Vec<(f64, Pose2)> = Vec::new();
    for &cell in map.free_cells() {
        let cell = cell as usize;
        if !(cell % map.width).is_multiple_of(stride) || !(cell / map.width).is_multiple_of(stride)
        {
            continue;
        }
        let c = map.center(cell);
        for k in 0..turns {
            let theta = wrap_angle((k as f64 * STEP_DEG).to_radians());
            let pose = Pose2::new(c.x, c.y, theta);
            if near(pose, estimate) {
                continue;
            }
            scored.push((weigher.log_likelihood(map, pose, &screen), pose));
        }
    }
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    // The best of each place: none within the lattice's reach of a better one kept.
    let mut seeds: Vec<Pose2> = Vec::new();
    for (_, pose) in scored {
        if seeds.len() >= REFINED {
            break;
        }
        let taken = seeds.iter().any(|s| {
            s.position().distance(pose.position()) < 2.0 * STEP_M
                && wrap_angle(s.theta - pose.theta).abs() < (2.0 * STEP_DEG).to_radians()
        });
        if !taken {
            seeds.push(pose);
        }
    }
    let (best, _) = refine(map, weigher, beams, estimate);
    let mut found: Vec<(f64, Pose2)> = (seeds.into_iter())
        .map(|s| refine(map, weigher, beams, s))
        .filter(|(fit, pose)| *fit >= best - margin && !near(*pose, estimate))
        .collect();
    found.sort_by(|a, b| b.0.total_cmp(&a.0));
    // Seeds that climbed to the same place are one rival.
    let mut places: Vec<Pose2> = Vec::new();
    for (_, pose) in found {
        if !places.iter().any(|p| near(*p, pose)) {
            places.push(pose);
        }
    }
    places
}

/// Scans kept to judge rivals by: the last 20 updates, 2 m of driving at the default
/// 0.1 m per update, short enough for the odometry between them to stay within a few
/// centimetres (the motion model's alpha3 of 0.2 gives 0.2 m per metre at 1σ only for
/// the worst of robots; the twin and a TurtleBot3 drift far less).
const RECENT_SCANS: usize = 20;

/// How many single scans' "nearly as well" margins the recent scans must fall short by
/// in all to rule a rival out: more than one scan's worth, as the beams of nearby scans
/// are not independent of each other (Probabilistic Robotics 6.3.4).
const RULED_OUT_SCANS: f64 = 3.0;

/// The recent scans, each with the odometry pose it was taken at.
#[derive(Clone, Debug, Default)]
pub struct RecentScans {
    scans: VecDeque<(Pose2, Beams)>,
}

impl RecentScans {
    pub fn push(&mut self, odom: Pose2, beams: Beams) {
        if self.scans.len() == RECENT_SCANS {
            self.scans.pop_front();
        }
        self.scans.push_back((odom, beams));
    }

    pub fn clear(&mut self) {
        self.scans.clear();
    }

    /// Whether the recent scans rule `rival` out beside `estimate`, both poses now, at the
    /// odometry pose `odom`: carried back along the odometry, the rival's scans fit worse
    /// than the estimate's by more than `RULED_OUT_SCANS` times `margin` nats in all (the
    /// log-likelihood ratio of the two paths, Bayes over the scans kept; a path through a
    /// wall fits badly too). Summed, not averaged: a few scans from where the two places
    /// differ decide, however many were taken where they look alike.
    pub fn rule_out(
        &self,
        map: &KnownMap,
        weigher: &mut Weigher,
        odom: Pose2,
        estimate: Pose2,
        rival: Pose2,
        margin: f64,
    ) -> bool {
        if self.scans.is_empty() {
            return false;
        }
        let mut shortfall = 0.0;
        for (then, beams) in &self.scans {
            // Where the robot was then, seen from where it is now (odometry's frame).
            let back = odom.between(*then);
            let (e, r) = (estimate.compose(back), rival.compose(back));
            // Each fitted near where the odometry puts it, as the filter's particles spread
            // by the motion model are: the odometry drifts over the scans kept.
            let (le, lr) = (
                refine(map, weigher, beams, e).0,
                refine(map, weigher, beams, r).0,
            );
            shortfall += le - lr;
        }
        shortfall > RULED_OUT_SCANS * margin
    }
}

/// "Nearly as well", in nats, for `beams`: what it costs every beam that hit something
/// to end half a σ_hit farther from the walls (the likelihood field's own scale,
/// Probabilistic Robotics table 6.3).
pub fn margin(c: &MeasurementModel, beams: &Beams) -> f64 {
    let q = |d: f64| {
        let g = (-(d * d) / (2.0 * c.sigma_hit * c.sigma_hit)).exp();
        c.z_hit * g / ((2.0 * std::f64::consts::PI).sqrt() * c.sigma_hit)
            + c.z_rand / beams.max_range
    };
    let hits = (beams.ranges.iter())
        .filter(|&&r| r < beams.max_range)
        .count();
    hits as f64 * (q(0.0) / q(0.5 * c.sigma_hit)).ln()
}

/// Whether `a` is at the same place as `b`.
pub(super) fn near(a: Pose2, b: Pose2) -> bool {
    a.position().distance(b.position()) < ELSEWHERE_M
        && wrap_angle(a.theta - b.theta).abs() < ELSEWHERE_DEG.to_radians()
}

/// Every k-th beam of `beams`.
fn every_kth(beams: &Beams, k: usize) -> Beams {
    let pick = |v: &[f64]| v.iter().step_by(k).copied().collect::<Vec<f64>>();
    Beams {
        directions: beams.directions.iter().step_by(k).copied().collect(),
        angles: pick(&beams.angles),
        ranges: pick(&beams.ranges),
        max_range: beams.max_range,
    }
}

/// Hill climbing on the fit from `start`: steps in x, y and heading, halved when none
/// improves, from half the lattice down to a cell (a scan matcher's local search).
/// The fit there (nats) and the pose.
fn refine(map: &KnownMap, weigher: &mut Weigher, beams: &Beams, start: Pose2) -> (f64, Pose2) {
    let mut pose = start;
    let mut fit = weigher.log_likelihood(map, pose, beams);
    let (mut step, mut turn) = (STEP_M / 2.0, (STEP_DEG / 2.0).to_radians());
    while step >= map.resolution / 2.0 {
        let mut better = false;
        for (dx, dy, dt) in [
            (step, 0.0, 0.0),
            (-step, 0.0, 0.0),
            (0.0, step, 0.0),
            (0.0, -step, 0.0),
            (0.0, 0.0, turn),
            (0.0, 0.0, -turn),
        ] {
            let p = Pose2::new(pose.x + dx, pose.y + dy, wrap_angle(pose.theta + dt));
            if !map.is_free(p.position()) {
                continue;
            }
            let f = weigher.log_likelihood(map, p, beams);
            if f > fit {
                (fit, pose, better) = (f, p, true);
            }
        }
        if !better {
            step /= 2.0;
            turn /= 2.0;
        }
    }
    (fit, pose)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use crate::map::grid::OccupancyGrid;
    use crate::slam::mcl::config::MeasurementModel;

    /// A 4 m x 2 m room with a wall all round, and optionally a 0.6 m box in one corner.
    fn room(post: bool) -> KnownMap {
        let mut g = OccupancyGrid::new(80, 40, 0.05, Point2::new(0.0, 0.0), 0);
        for x in 0..80 {
            g.set(x, 0, 100);
            g.set(x, 39, 100);
        }
        for y in 0..40 {
            g.set(0, y, 100);
            g.set(79, y, 100);
        }
        if post {
            for x in 60..72 {
                for y in 22..34 {
                    g.set(x, y, 100);
                }
            }
        }
        KnownMap::new(&g).unwrap()
    }

    /// The ranges a perfect 360° lidar of 3.5 m reads at `pose`, 60 beams.
    fn scan_at(map: &KnownMap, pose: Pose2) -> Beams {
        let mut b = Beams {
            max_range: 3.5,
            ..Beams::default()
        };
        for k in 0..60 {
            let a = k as f64 * std::f64::consts::TAU / 60.0;
            let (c, s) = ((pose.theta + a).cos(), (pose.theta + a).sin());
            b.directions.push((a.cos(), a.sin()));
            b.angles.push(a);
            b.ranges.push(map.ray_cast(pose.x, pose.y, c, s, 3.5));
        }
        b
    }

    #[test]
    fn a_bare_room_has_its_half_turn_as_a_rival_and_a_box_removes_it() {
        let c = MeasurementModel::default();
        let at = Pose2::new(1.0, 0.7, 0.3);
        let bare = room(false);
        let mut w = Weigher::new(&bare, &c, 3.5);
        let found = rivals(&bare, &mut w, &scan_at(&bare, at), at, 6.0);
        // The room turned by a half-turn about its centre (2, 1): (3, 1.3) facing 0.3 - π.
        let mirror = Pose2::new(3.0, 1.3, wrap_angle(0.3 - std::f64::consts::PI));
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].position().distance(mirror.position()) < 0.1,
            "{found:?}"
        );
        assert!(wrap_angle(found[0].theta - mirror.theta).abs() < 0.05);
        let boxed = room(true);
        let mut w = Weigher::new(&boxed, &c, 3.5);
        let found = rivals(&boxed, &mut w, &scan_at(&boxed, at), at, 6.0);
        assert!(found.is_empty(), "{found:?}");
    }

    #[test]
    fn the_recent_scans_rule_out_a_look_alike_but_never_the_truth() {
        let c = MeasurementModel::default();
        let boxed = room(true);
        let mut w = Weigher::new(&boxed, &c, 3.5);
        let mut recent = RecentScans::default();
        // Driving east along the room; the odometry frame is the map's here.
        let path: Vec<Pose2> = (0..10)
            .map(|k| Pose2::new(1.0 + 0.1 * k as f64, 0.7, 0.3))
            .collect();
        for &p in &path {
            recent.push(p, scan_at(&boxed, p));
        }
        let now = *path.last().unwrap();
        // The room's half-turn copy of the pose: the box is where it sees none.
        let mirror = Pose2::new(
            4.0 - now.x,
            2.0 - now.y,
            wrap_angle(now.theta - std::f64::consts::PI),
        );
        assert!(recent.rule_out(&boxed, &mut w, now, now, mirror, 6.0));
        assert!(!recent.rule_out(&boxed, &mut w, now, mirror, now, 6.0));
        // In the bare room the copy fits every scan as well: it stays a rival.
        let bare = room(false);
        let mut w = Weigher::new(&bare, &c, 3.5);
        let mut recent = RecentScans::default();
        for &p in &path {
            recent.push(p, scan_at(&bare, p));
        }
        assert!(!recent.rule_out(&bare, &mut w, now, now, mirror, 6.0));
    }
}
