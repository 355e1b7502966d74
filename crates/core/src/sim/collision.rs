//! Collisions of the robot's circular footprint with walls, obstacle outlines and blocks.
//!
//! A move from one centre position to the next sweeps the footprint along the chord (a
//! capsule), so even a long physics step cannot tunnel through a thin wall. Only segments
//! near the robot are tested: a cached list, rebuilt when the robot has moved far enough.

use super::shapes::{dist, dist2_to_segment, segment_distance2};
use crate::geometry::{Point2, Segment};

/// How much farther than the footprint the cached neighbourhood reaches, metres.
const MARGIN: f64 = 0.25;

/// A round solid the robot may not enter (a free block).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disc {
    pub center: Point2,
    pub radius: f64,
}

/// The outcome of a proposed move.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Verdict {
    /// The move would bring the footprint into a solid: do not take it.
    pub blocked: bool,
    /// The move increases the clearance to the nearest solid (only computed on request).
    pub moves_away: bool,
}

#[derive(Clone, Debug)]
pub struct Collider {
    radius: f64,
    center: Point2,
    near: Vec<usize>,
    built: bool,
}

impl Collider {
    pub fn new(footprint_radius: f64) -> Self {
        Self {
            radius: footprint_radius,
            center: Point2::default(),
            near: Vec::new(),
            built: false,
        }
    }

    /// Judges moving the footprint's centre from `from` to `to` among `walls` and `discs`.
    /// A footprint already overlapping something may still move if it gets clearer.
    pub fn check(
        &mut self,
        walls: &[Segment],
        discs: &[Disc],
        from: Point2,
        to: Point2,
        want_away: bool,
    ) -> Verdict {
        let travel = dist(from, to);
        let all: Vec<usize>;
        let near: &[usize] = if travel > MARGIN {
            all = (0..walls.len()).collect();
            &all
        } else {
            // Any segment within `radius` of the swept chord lies within radius + MARGIN of
            // the cache centre while |from - centre| + travel <= MARGIN (triangle inequality).
            if !self.built || dist(self.center, from) + travel > MARGIN {
                self.rebuild(walls, from);
            }
            &self.near
        };
        let r = self.radius;
        let touches = near
            .iter()
            .any(|&k| segment_distance2(from, to, walls[k]) < r * r)
            || discs
                .iter()
                .any(|d| dist2_to_segment(d.center, from, to) < (r + d.radius).powi(2));
        if !touches && !want_away {
            return Verdict::default();
        }
        let clearance = |p: Point2| {
            let walls_min = near
                .iter()
                .map(|&k| dist2_to_segment(p, walls[k].a, walls[k].b))
                .fold(f64::INFINITY, f64::min)
                .sqrt()
                - r;
            discs
                .iter()
                .map(|d| dist(p, d.center) - d.radius - r)
                .fold(walls_min, f64::min)
        };
        let (start, end) = (clearance(from), clearance(to));
        Verdict {
            // Entering a solid is refused; one already inside may only work its way out.
            blocked: touches && (start >= 0.0 || end <= start),
            moves_away: end > start + 1e-9,
        }
    }

    fn rebuild(&mut self, walls: &[Segment], at: Point2) {
        let reach = self.radius + MARGIN;
        self.near.clear();
        self.near.extend(
            (0..walls.len())
                .filter(|&k| dist2_to_segment(at, walls[k].a, walls[k].b) <= reach * reach),
        );
        self.center = at;
        self.built = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall() -> Vec<Segment> {
        vec![Segment::new(Point2::new(1.0, -1.0), Point2::new(1.0, 1.0))]
    }

    #[test]
    fn moving_into_a_wall_is_blocked_and_backing_off_is_not() {
        let mut c = Collider::new(0.1);
        let w = wall();
        let ok = c.check(
            &w,
            &[],
            Point2::new(0.85, 0.0),
            Point2::new(0.89, 0.0),
            true,
        );
        assert!(!ok.blocked && !ok.moves_away);
        assert!(
            c.check(
                &w,
                &[],
                Point2::new(0.89, 0.0),
                Point2::new(0.91, 0.0),
                false
            )
            .blocked
        );
        let back = c.check(
            &w,
            &[],
            Point2::new(0.89, 0.0),
            Point2::new(0.88, 0.0),
            true,
        );
        assert!(!back.blocked && back.moves_away);
    }

    #[test]
    fn a_long_step_cannot_tunnel_through_a_wall() {
        let mut c = Collider::new(0.1);
        assert!(
            c.check(
                &wall(),
                &[],
                Point2::new(0.0, 0.0),
                Point2::new(2.0, 0.0),
                false
            )
            .blocked
        );
    }

    #[test]
    fn discs_block_and_a_stuck_robot_may_escape() {
        let mut c = Collider::new(0.1);
        let disc = [Disc {
            center: Point2::new(0.0, 0.0),
            radius: 0.05,
        }];
        assert!(
            c.check(
                &[],
                &disc,
                Point2::new(-0.3, 0.0),
                Point2::new(-0.14, 0.0),
                false
            )
            .blocked
        );
        // Overlapping already: going deeper is refused, getting out is allowed.
        assert!(
            c.check(
                &[],
                &disc,
                Point2::new(-0.12, 0.0),
                Point2::new(-0.11, 0.0),
                false
            )
            .blocked
        );
        assert!(
            !c.check(
                &[],
                &disc,
                Point2::new(-0.12, 0.0),
                Point2::new(-0.13, 0.0),
                false
            )
            .blocked
        );
    }
}
