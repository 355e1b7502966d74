//! Claims on a fleet's exploration goals: a frontier (or unseen space) is explored by one
//! robot at a time, and so is the ground round it. Each robot says the goal it drives
//! to; a robot keeps its claim while it wants the same goal, and a new goal is granted,
//! robots in order, only when it lies at least `reach` from every goal already held.
//! A robot that wants nothing (it reached its goal, gave it up, or stopped exploring)
//! holds nothing.

use crate::geometry::Point2;

/// Two goals nearer than this are the same goal, metres (a map cell or two).
const SAME_GOAL: f64 = 0.05;

/// Who holds which exploration goal, by robot index; see the module comment.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrontierClaims {
    holders: Vec<Option<Point2>>,
    /// The claimed ground's radius round each goal, metres.
    reach: f64,
}

impl FrontierClaims {
    /// Claims whose goals keep `reach` metres of ground each.
    pub fn new(reach: f64) -> Self {
        Self {
            holders: Vec::new(),
            reach,
        }
    }

    /// The claimed ground's radius, metres.
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// Takes the goal each robot wants now (`wants[i]` for robot `i`). A robot keeps the
    /// goal it holds while it wants it still; then, robots in order, a new goal is
    /// granted when no goal held lies within `reach` of it. Returns, for each robot,
    /// whether it holds what it wants (wanting nothing is always granted).
    pub fn settle(&mut self, wants: &[Option<Point2>]) -> Vec<bool> {
        self.holders.resize(wants.len(), None);
        self.holders.truncate(wants.len());
        for (held, want) in self.holders.iter_mut().zip(wants) {
            let same = matches!((*held, *want), (Some(h), Some(w)) if h.distance(w) < SAME_GOAL);
            if !same {
                *held = None;
            }
        }
        for (robot, want) in wants.iter().enumerate() {
            let Some(goal) = *want else { continue };
            if self.holders[robot].is_none() && self.is_free_for(robot, goal) {
                self.holders[robot] = Some(goal);
            }
        }
        (wants.iter().zip(&self.holders))
            .map(|(want, held)| want.is_none() || held.is_some())
            .collect()
    }

    /// The goals the other robots hold: robot `robot` may not go within `reach` of them.
    pub fn taken_for(&self, robot: usize) -> Vec<Point2> {
        (self.holders.iter().enumerate())
            .filter(|(r, _)| *r != robot)
            .filter_map(|(_, held)| *held)
            .collect()
    }

    /// The goal robot `robot` holds, if any.
    pub fn held_by(&self, robot: usize) -> Option<Point2> {
        self.holders.get(robot).copied().flatten()
    }

    /// Whether `goal` lies at least `reach` from every goal the others hold.
    fn is_free_for(&self, robot: usize, goal: Point2) -> bool {
        is_free(goal, &self.taken_for(robot), self.reach)
    }
}

/// Whether `goal` lies at least `reach` from every point of `taken`.
pub fn is_free(goal: Point2, taken: &[Point2], reach: f64) -> bool {
    taken.iter().all(|t| t.distance(goal) >= reach)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn p(x: f64, y: f64) -> Option<Point2> {
        Some(Point2::new(x, y))
    }

    #[test]
    fn the_first_to_want_a_frontier_holds_it_and_its_ground_until_it_lets_go() {
        let mut claims = FrontierClaims::new(1.0);
        assert_eq!(claims.settle(&[p(2.0, 0.0), None]), [true, true]);
        // Robot 1 wants a goal 0.5 m from robot 0's: refused, and told what is taken.
        assert_eq!(claims.settle(&[p(2.0, 0.0), p(2.5, 0.0)]), [true, false]);
        assert_eq!(claims.taken_for(1), [Point2::new(2.0, 0.0)]);
        assert!(claims.taken_for(0).is_empty());
        // A goal outside the claimed ground is granted beside it.
        assert_eq!(claims.settle(&[p(2.0, 0.0), p(3.2, 0.0)]), [true, true]);
        // Robot 0 reached its goal and wants nothing: its ground is free again.
        assert_eq!(claims.settle(&[None, p(2.5, 0.0)]), [true, true]);
        assert_eq!(claims.held_by(1), p(2.5, 0.0));
        assert_eq!(claims.held_by(0), None);
    }

    #[test]
    fn a_robot_picks_among_unclaimed_frontiers_only() {
        let mut claims = FrontierClaims::new(1.0);
        claims.settle(&[p(0.0, 0.0), None]);
        let frontiers = [Point2::new(0.4, 0.0), Point2::new(3.0, 0.0)];
        let taken = claims.taken_for(1);
        let free: Vec<Point2> = (frontiers.iter().copied())
            .filter(|f| is_free(*f, &taken, claims.reach()))
            .collect();
        assert_eq!(free, [Point2::new(3.0, 0.0)]);
        assert_eq!(claims.settle(&[p(0.0, 0.0), Some(free[0])]), [true, true]);
    }

    #[test]
    fn no_frontier_is_ever_held_by_two_robots() {
        // Five robots wanting among six goals on a line 0.6 m apart (each within 1 m of
        // its neighbours), drawn anew each round for 2000 rounds.
        let mut claims = FrontierClaims::new(1.0);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(987654321);
        for _ in 0..2000 {
            let wants: Vec<Option<Point2>> = (0..5)
                .map(|_| match rng.random_range(0..7) {
                    0 => None,
                    k => p(0.6 * f64::from(k), 0.0),
                })
                .collect();
            let held = claims.settle(&wants);
            let holding: Vec<Point2> = (0..5).filter_map(|r| claims.held_by(r)).collect();
            for (i, a) in holding.iter().enumerate() {
                for b in &holding[i + 1..] {
                    assert!(a.distance(*b) >= 1.0, "{a:?} and {b:?} both held");
                }
            }
            for r in 0..5 {
                assert_eq!(held[r], wants[r].is_none() || claims.held_by(r) == wants[r]);
                if claims.held_by(r).is_some() {
                    assert_eq!(claims.held_by(r), wants[r], "robot {r} holds what it wants");
                }
            }
        }
    }
}
