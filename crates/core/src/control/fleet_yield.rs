//! Who gives way when two robots of a fleet meet: the rule a robot's autonomy follows so
//! that robots never drive into each other. A robot moving towards another that moves
//! too, within a few footprints, yields unless it has the right of way: a robot in a
//! doorway (a passage narrower than `doorway`) goes first, so that it clears it; between
//! two robots equally placed, the lower number goes. A robot standing still is an
//! obstacle like any other, left to the collision monitor and the planner, except that
//! no robot moves towards another closer than `keep_clear`, however slowly: there the
//! monitor's zones no longer tell a robot from the one it touches.

use crate::geometry::{Point2, Pose2, wrap_angle};

/// Another robot of the fleet as this one knows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peer {
    /// Its number in the fleet, from 1.
    pub number: usize,
    pub pose: Pose2,
    /// Its forward speed, m/s (negative backing).
    pub linear: f64,
}

/// The rule's distances and angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YieldRule {
    /// Robots farther apart than this (centre to centre), metres, pass each other by.
    pub radius: f64,
    /// A robot lies in the way when its bearing from the direction of travel is within
    /// this, radians.
    pub ahead: f64,
    /// A passage narrower than this is a doorway, metres.
    pub doorway: f64,
    /// Slower than this a robot counts as standing, m/s.
    pub standing: f64,
    /// Nearer than this (centre to centre), metres, a robot moves towards no other.
    pub keep_clear: f64,
}

impl Default for YieldRule {
    /// navdeck's figures for TurtleBot3-sized robots (0.08 m footprint radius): 0.6 m is
    /// about two robots' stopping distance at 0.22 m/s plus both footprints; a doorway
    /// under 0.8 m lets one robot through at a time; 0.22 m keeps 6 cm
    /// between two footprints.
    fn default() -> Self {
        Self {
            radius: 0.6,
            ahead: 60f64.to_radians(),
            doorway: 0.8,
            standing: 0.02,
            keep_clear: 0.22,
        }
    }
}

/// Whether a robot goes on or waits, and for whom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Right {
    Go,
    /// Wait for robot `to`, because `why`.
    Yield {
        to: usize,
        why: &'static str,
    },
}

/// Whether `target` lies within `cone` of the way `from` travels (forward when `linear`
/// is positive, backward when negative).
fn within(cone: f64, from: Pose2, linear: f64, target: Point2) -> bool {
    let way = if linear >= 0.0 {
        from.theta
    } else {
        from.theta + std::f64::consts::PI
    };
    let bearing = (target.y - from.y).atan2(target.x - from.x);
    wrap_angle(bearing - way).abs() <= cone
}

/// Whether `target` lies within `rule.ahead` of the way `from` travels.
fn in_the_way(rule: &YieldRule, from: Pose2, linear: f64, target: Point2) -> bool {
    within(rule.ahead, from, linear, target)
}

/// Whether robot `me_number` at `me`, moving at `linear`, goes on or yields to one of
/// `peers`; `narrow(p)` says whether `p` lies in a doorway.
pub fn judge(
    rule: &YieldRule,
    me_number: usize,
    me: Pose2,
    linear: f64,
    peers: &[Peer],
    narrow: &dyn Fn(Point2) -> bool,
) -> Right {
    // Turning on the spot moves no robot towards another.
    if linear.abs() < 1e-3 {
        return Right::Go;
    }
    let here = me.position();
    let crowded = (peers.iter())
        .filter(|p| p.number != me_number)
        .filter(|p| here.distance(p.pose.position()) < rule.keep_clear)
        // Any motion that brings the two nearer: within a right angle of the way.
        .find(|p| within(std::f64::consts::FRAC_PI_2, me, linear, p.pose.position()));
    if let Some(p) = crowded {
        return Right::Yield {
            to: p.number,
            why: "it is too close",
        };
    }
    if linear.abs() < rule.standing {
        return Right::Go;
    }
    let mut first: Option<(f64, Right)> = None;
    for p in peers.iter().filter(|p| p.number != me_number) {
        let there = p.pose.position();
        let gap = here.distance(there);
        let moving = p.linear.abs() >= rule.standing;
        if gap > rule.radius || !moving || !in_the_way(rule, me, linear, there) {
            continue;
        }
        let (mine, theirs) = (narrow(here), narrow(there));
        let right = match (mine, theirs) {
            (false, true) => Right::Yield {
                to: p.number,
                why: "it is in the doorway",
            },
            (true, false) => continue,
            _ if p.number < me_number => Right::Yield {
                to: p.number,
                why: "it has the lower number",
            },
            _ => continue,
        };
        // The nearest robot owed way is the one named.
        if first.as_ref().is_none_or(|(g, _)| gap < *g) {
            first = Some((gap, right));
        }
    }
    first.map_or(Right::Go, |(_, right)| right)
}

/// Whether a passage narrower than `width` runs through `p`: along one of eight
/// directions, `blocked` is true within `width / 2` on both sides, sampled every `step`.
pub fn narrow_at(p: Point2, width: f64, step: f64, blocked: &dyn Fn(Point2) -> bool) -> bool {
    let reach = width / 2.0;
    let hits = |angle: f64| {
        let (c, s) = (angle.cos(), angle.sin());
        let n = (reach / step).ceil() as usize;
        (1..=n).any(|k| {
            let d = (k as f64 * step).min(reach);
            blocked(Point2::new(p.x + c * d, p.y + s * d))
        })
    };
    (0..4).any(|k| {
        let a = k as f64 * std::f64::consts::FRAC_PI_4;
        hits(a) && hits(a + std::f64::consts::PI)
    })
}

#[cfg(test)]
#[path = "fleet_yield_tests.rs"]
mod tests;
