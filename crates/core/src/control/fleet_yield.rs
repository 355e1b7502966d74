//! Who gives way when two robots of a fleet meet: the rule a robot's autonomy follows so
//! that robots never drive into each other. A robot moving towards another that moves
//! too, within a few footprints, yields unless it has the right of way: a robot in a
//! doorway (a passage narrower than `doorway`) goes first, so that it clears it; between
//! two robots equally placed, the lower number goes. A robot standing still is an
//! obstacle like any other, left to the collision monitor and the planner, except that
//! no robot moves towards another closer than `keep_clear`, however slowly (there the
//! monitor's zones no longer tell a robot from the one it touches); and while two close
//! on each other, the one that owes the way holds once nearer than `keep_clear` plus the
//! ground they cover before they can stop.

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
    /// How long a robot takes to act on where another is, seconds: the peer's pose is a
    /// control period old and a hold takes effect at the next.
    pub reaction: f64,
    /// How hard a robot brakes, m/s² (`[robot] max_linear_accel`).
    pub braking: f64,
}

impl YieldRule {
    /// The rule for robots that act every `control_period` and brake at `braking`.
    pub fn for_robot(control_period: f64, braking: f64) -> Self {
        Self {
            reaction: 2.0 * control_period,
            braking,
            ..Self::default()
        }
    }

    /// How near robot `me`, moving at `linear`, may come to `p` (centre to centre): at
    /// the speed v at which the two close, `keep_clear` plus v·t + v²/2a, the distance
    /// covered in the reaction time t and then braking at a (uniform deceleration).
    pub fn clearance(&self, me: Pose2, linear: f64, p: &Peer) -> f64 {
        let (dx, dy) = (p.pose.x - me.x, p.pose.y - me.y);
        let gap = dx.hypot(dy).max(1e-9);
        let (ux, uy) = (dx / gap, dy / gap);
        let mine = linear * (me.theta.cos() * ux + me.theta.sin() * uy);
        let theirs = -p.linear * (p.pose.theta.cos() * ux + p.pose.theta.sin() * uy);
        let v = (mine + theirs).max(0.0);
        self.keep_clear + v * self.reaction + v * v / (2.0 * self.braking.max(1e-3))
    }
}

impl Default for YieldRule {
    /// navdeck's figures for TurtleBot3-sized robots (0.08 m footprint radius): 0.6 m is
    /// about two robots' stopping distance at 0.22 m/s plus both footprints; a doorway
    /// under 0.8 m lets one robot through at a time; 0.22 m keeps 6 cm
    /// between two footprints; a reaction of two 0.1 s control periods; braking at
    /// `[robot] max_linear_accel`'s default, 1 m/s².
    fn default() -> Self {
        Self {
            radius: 0.6,
            ahead: 60f64.to_radians(),
            doorway: 0.8,
            standing: 0.02,
            keep_clear: 0.22,
            reaction: 0.2,
            braking: 1.0,
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

/// Why robot `me_number` owes robot `them` the way, if it does: the robot in a doorway
/// (`theirs`, against `mine` for this one) goes first, then the lower number.
fn owes(mine: bool, theirs: bool, them: usize, me_number: usize) -> Option<&'static str> {
    match (mine, theirs) {
        (false, true) => Some("it is in the doorway"),
        (true, false) => None,
        _ if them < me_number => Some("it has the lower number"),
        _ => None,
    }
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
    // Any motion that brings the two nearer: within a right angle of the way.
    let nearing = |p: &&Peer| {
        p.number != me_number && within(std::f64::consts::FRAC_PI_2, me, linear, p.pose.position())
    };
    let crowded = (peers.iter().filter(nearing))
        .find(|p| here.distance(p.pose.position()) < rule.keep_clear)
        .or_else(|| {
            (peers.iter().filter(nearing))
                .filter(|p| here.distance(p.pose.position()) < rule.clearance(me, linear, p))
                .find(|p| {
                    owes(narrow(here), narrow(p.pose.position()), p.number, me_number).is_some()
                })
        });
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
        let Some(why) = owes(narrow(here), narrow(there), p.number, me_number) else {
            continue;
        };
        let right = Right::Yield { to: p.number, why };
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
