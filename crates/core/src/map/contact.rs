//! Contact ahead: would the command, kept up for a moment, bring the robot's footprint
//! onto something the lidar mapped? The path keeps its distance from obstacles; the robot
//! drifting off it (a swing at a sharp corner, an estimate that jumped) does not, and this
//! catches it before the bumper does (the idea of Nav2's collision monitor, which projects
//! the command forward and stops short of what the sensors see).

use super::costmap::Costmap;
use crate::geometry::{Point2, Pose2, Twist};

/// Time step of the projection, seconds.
const STEP: f64 = 0.05;

/// What the projection ignores: cells where a held block may have been mapped, a box
/// ahead of the robot's centre (`ahead` metres long, `half_width` either side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldZone {
    pub ahead: f64,
    pub half_width: f64,
}

impl HeldZone {
    /// Whether world point `q` lies in the zone of a robot at `pose`.
    pub fn contains(&self, pose: Pose2, q: Point2) -> bool {
        let (s, c) = pose.theta.sin_cos();
        let (dx, dy) = (q.x - pose.x, q.y - pose.y);
        let (along, across) = (dx * c + dy * s, -dx * s + dy * c);
        (0.0..=self.ahead).contains(&along) && across.abs() <= self.half_width
    }
}

/// The jaws hold a block's far face 0.14 m ahead of the robot centre; a 5 cm block,
/// turned, reaches 3.5 cm either side (navdeck's gripper).
pub const JAWS: HeldZone = HeldZone {
    ahead: 0.16,
    half_width: 0.05,
};

/// The first occupied cell centre the footprint (a disc of `radius`) would come within
/// `radius` of while driving `twist` from `pose` for `horizon` seconds, counted only if the
/// robot is closing on it: a footprint already touching something may still back or turn
/// away. `occupied` is the lidar layer of `map`; `None` when nothing is in the way.
pub fn contact_ahead(
    map: &Costmap,
    occupied: &[bool],
    pose: Pose2,
    twist: Twist,
    radius: f64,
    horizon: f64,
    held: Option<HeldZone>,
) -> Option<Point2> {
    if occupied.len() != map.width * map.height || twist.linear == 0.0 {
        return None;
    }
    let ignored = |q: Point2| held.is_some_and(|z| z.contains(pose, q));
    let steps = (horizon / STEP).ceil().max(1.0) as usize;
    let mut p = pose;
    for _ in 0..steps {
        p = advance(p, twist, STEP);
        let hit = nearest_occupied(map, occupied, p.position(), radius, &ignored);
        if let Some(q) = hit
            && q.distance(p.position()) + 1e-3 < q.distance(pose.position())
        {
            return Some(q);
        }
    }
    None
}

/// The pose after driving `twist` for `dt` (unicycle, exact arc).
fn advance(p: Pose2, twist: Twist, dt: f64) -> Pose2 {
    let (v, w) = (twist.linear, twist.angular);
    let theta = p.theta + w * dt;
    if w.abs() < 1e-9 {
        return Pose2::new(
            p.x + v * dt * p.theta.cos(),
            p.y + v * dt * p.theta.sin(),
            theta,
        );
    }
    // Circular arc of radius v / w (differential-drive kinematics).
    let r = v / w;
    Pose2::new(
        p.x + r * (theta.sin() - p.theta.sin()),
        p.y - r * (theta.cos() - p.theta.cos()),
        theta,
    )
}

/// The nearest occupied, not ignored cell centre within `radius` of `p`.
fn nearest_occupied(
    map: &Costmap,
    occupied: &[bool],
    p: Point2,
    radius: f64,
    ignored: &impl Fn(Point2) -> bool,
) -> Option<Point2> {
    let reach = (radius / map.resolution).ceil() as i64;
    let (cx, cy) = map.cell_of(p).map(|(x, y)| (x as i64, y as i64))?;
    let mut best: Option<(f64, Point2)> = None;
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (x, y) = (cx + dx, cy + dy);
            if x < 0 || y < 0 || x >= map.width as i64 || y >= map.height as i64 {
                continue;
            }
            let (x, y) = (x as usize, y as usize);
            if !occupied[map.index(x, y)] {
                continue;
            }
            let q = map.center_of(x, y);
            let d = q.distance(p);
            if d < radius && best.is_none_or(|(b, _)| d < b) && !ignored(q) {
                best = Some((d, q));
            }
        }
    }
    best.map(|(_, q)| q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::FREE;

    /// A 1 m square map at 1 cm with a wall along x = 0.6 m.
    fn walled() -> (Costmap, Vec<bool>) {
        let map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), FREE);
        let mut occupied = vec![false; 100 * 100];
        for y in 0..100 {
            occupied[y * 100 + 60] = true;
        }
        (map, occupied)
    }

    #[test]
    fn driving_at_a_wall_is_caught_before_the_footprint_touches_it() {
        let (map, occupied) = walled();
        let twist = Twist::new(0.2, 0.0);
        let near = Pose2::new(0.45, 0.5, 0.0);
        let hit = contact_ahead(&map, &occupied, near, twist, 0.08, 0.5, None);
        assert!(hit.is_some_and(|q| (q.x - 0.605).abs() < 0.01), "{hit:?}");
        let far = Pose2::new(0.3, 0.5, 0.0);
        assert_eq!(
            contact_ahead(&map, &occupied, far, twist, 0.08, 0.5, None),
            None,
            "0.1 m in half a second stays 0.2 m short"
        );
    }

    #[test]
    fn driving_along_or_away_from_a_wall_is_not_stopped() {
        let (map, occupied) = walled();
        let beside = Pose2::new(0.5, 0.3, std::f64::consts::FRAC_PI_2);
        let along = contact_ahead(
            &map,
            &occupied,
            beside,
            Twist::new(0.2, 0.0),
            0.08,
            0.5,
            None,
        );
        assert_eq!(along, None, "10 cm off the wall, driving along it");
        let touching = Pose2::new(0.53, 0.5, std::f64::consts::PI);
        let away = contact_ahead(
            &map,
            &occupied,
            touching,
            Twist::new(0.2, 0.0),
            0.08,
            0.5,
            None,
        );
        assert_eq!(away, None, "backing off a wall it touches");
    }

    #[test]
    fn a_turn_towards_a_wall_is_caught_and_a_held_block_is_not_an_obstacle() {
        let (map, mut occupied) = walled();
        // 15 cm off the wall, driving along it; a hard right turn would sweep into it.
        let pose = Pose2::new(0.45, 0.3, std::f64::consts::FRAC_PI_2);
        let turning = Twist::new(0.2, -2.0);
        assert!(contact_ahead(&map, &occupied, pose, turning, 0.08, 1.0, None).is_some());
        let straight = Twist::new(0.2, 0.0);
        assert_eq!(
            contact_ahead(&map, &occupied, pose, straight, 0.08, 1.0, None),
            None
        );
        // A block mapped in the jaws, 0.1 m ahead of the robot centre.
        occupied[40 * 100 + 45] = true;
        assert!(contact_ahead(&map, &occupied, pose, straight, 0.08, 1.0, None).is_some());
        assert_eq!(
            contact_ahead(&map, &occupied, pose, straight, 0.08, 1.0, Some(JAWS)),
            None
        );
    }
}
