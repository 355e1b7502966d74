//! Choosing what to do next (seed 001 "Operating Modes", `t` Thinking): a deliverable
//! block first, else the next exploration target, else potential blocks, else finish.

use super::config::{
    EXPLAINED_WITHIN, FRONTIER_MIN_CELLS, GIVE_UP_ROUNDS, MAX_BLOCK_ATTEMPTS, OBJECT_LOOKS,
    POTENTIAL_LOOKS, POTENTIAL_VIEW, TARGET_TOO_CLOSE, TargetRule, UNSEEN_MIN_CELLS,
};
use super::drive::{Turn, towards};
use super::explored::Unexplained;
use super::fleet_explored::{mapped_by, seen_by};
use super::leg::Leg;
use super::machine::Mission;
use super::objects::Block;
use super::phase::{Cause, Phase, Target};
use super::pickup::{Pickup, name};
use super::step::{Inputs, Level};
use super::targets::{frontiers, furthest_marker, reachable};
use super::unexplained::{GATHER, small_objects};
use crate::geometry::Point2;

impl Mission {
    pub(super) fn choose(&mut self, inputs: &Inputs, log: &mut Vec<(Level, String)>) {
        self.explored.candidates.clear();
        self.shared.claimed_out = false;
        let robot = inputs.pose.position();
        let total = self.config.total_blocks as usize;
        if total > 0 && self.objects.delivered() >= total {
            log.push((
                Level::Success,
                format!("All {total} blocks delivered - mission complete"),
            ));
            self.phase = Phase::Done;
            return;
        }
        // Without an arm that answers, blocks wait and exploring goes on.
        if let Some(block) = self.deliverable(robot).filter(|_| inputs.can_pick) {
            *self.attempts.entry(block.markers[0]).or_default() += 1;
            self.phase = Phase::Pickup(Pickup::new(
                &block,
                self.objects.seen_from(block.markers[0]),
                robot,
                inputs.map,
                &self.config,
                inputs.t,
            ));
            return;
        }
        // One rule to the end: with frontiers, exploration is complete when no reachable
        // frontier is left and the camera has looked at every free place the robot can
        // reach; with markers, when every valid marker was visited.
        // One flood from the robot serves both kinds of frontier target.
        let reach = match self.config.target_rule {
            TargetRule::Frontiers => reachable(inputs.map, inputs.pose.position()),
            TargetRule::Markers => Vec::new(),
        };
        let found = self
            .explore_target(self.config.target_rule, inputs, &reach)
            .or_else(|| self.unseen_target(inputs, &reach));
        if let Some((goal, target, label)) = found {
            (self.shared.waiting, self.shared.boxed_since) = (false, None);
            self.shared.home_reached = false;
            self.phase = Phase::Explore {
                leg: Leg::replaceable(goal, label),
                target,
            };
            return;
        }
        // Nothing left to explore: go and look at blocks seen by one marker only.
        let potential = self
            .objects
            .blocks()
            .filter(|b| !b.confirmed && !b.delivered && !self.shared.blocks.contains(&b.markers[0]))
            .filter(|b| self.looks_at(b.markers[0]) < POTENTIAL_LOOKS)
            .min_by(|a, b| {
                let (da, db) = (a.position.distance(robot), b.position.distance(robot));
                da.total_cmp(&db)
            })
            .copied();
        if let Some(b) = potential {
            // First from the robot's side; then from the four diagonals, each showing two
            // faces at 45°, until both markers have been seen (navdeck's).
            let goal = match self.looks_at(b.markers[0]) {
                0 => towards(b.position, robot, self.config.staging_distance),
                k => {
                    let a = std::f64::consts::FRAC_PI_4
                        + f64::from(k - 1) * std::f64::consts::FRAC_PI_2;
                    let d = POTENTIAL_VIEW * self.config.staging_distance;
                    Point2::new(b.position.x + d * a.cos(), b.position.y + d * a.sin())
                }
            };
            let label = format!("potential {}", name(b.colour, b.markers[0]));
            self.phase = Phase::Explore {
                leg: Leg::replaceable(goal, label),
                target: Target::Potential(b.markers[0]),
            };
            return;
        }
        if let Some((goal, i)) = self.object_look(inputs) {
            let at = self.explored.unexplained[i].at;
            let label = format!("unexplained object ({:.2}, {:.2})", at.x, at.y);
            self.phase = Phase::Explore {
                leg: Leg::replaceable(goal, label),
                target: Target::Object(i),
            };
            return;
        }
        // In a fleet, what is left to explore may all lie in ground another robot claims.
        if self.wait_for_claims(inputs, log) {
            return;
        }
        // Seed 001 "Path Planning Failure": turn a little and try again. navdeck turns once
        // for every target given up, then tries them all again, a few rounds at most.
        if !self.given_up.goals.is_empty() && self.given_up.retry_rounds < GIVE_UP_ROUNDS {
            self.given_up.retry_rounds += 1;
            self.ctx.recoveries += 1;
            log.push((
                Level::Warn,
                format!(
                    "No path to any of {} targets - turning {:.0}° and trying them again ({}/{GIVE_UP_ROUNDS})",
                    self.given_up.goals.len(),
                    self.config.retry_turn_deg,
                    self.given_up.retry_rounds
                ),
            ));
            self.given_up.goals.clear();
            let angle = self.config.retry_turn_deg.to_radians();
            self.phase = Phase::Scan {
                turn: Turn::new(inputs.pose, inputs.t, angle, self.config.scan_speed),
                initial: false,
            };
            return;
        }
        if !inputs.can_pick && self.deliverable(robot).is_some() {
            log.push((
                Level::Warn,
                "Nothing left to explore and the arm does not answer - waiting for it".into(),
            ));
            self.phase = Phase::WaitArm;
            return;
        }
        // In a fleet, another robot may be what keeps the rest out of reach.
        if self.wait_for_the_boxed_in(inputs, &reach, log) || self.go_home(inputs, log) {
            return;
        }
        log.push((Level::Info, "Exploration complete".into()));
        let left = self.objects.blocks().any(|b| b.confirmed && !b.delivered);
        if !left && total == 0 {
            log.push((
                Level::Success,
                format!(
                    "All {} blocks found delivered - mission complete",
                    self.objects.delivered()
                ),
            ));
            self.phase = Phase::Done;
        } else {
            log.push((
                Level::Warn,
                format!(
                    "Exploration complete with {}{} blocks delivered - switching to manual",
                    self.objects.delivered(),
                    if total > 0 {
                        format!("/{total}")
                    } else {
                        String::new()
                    }
                ),
            ));
            self.handover = Some(Cause::BlocksLeft.label());
            self.phase = Phase::Manual;
        }
    }

    /// The nearest confirmed, undelivered block whose gate is known and that is not
    /// waiting after a demotion.
    pub(super) fn deliverable(&self, robot: Point2) -> Option<Block> {
        self.objects
            .blocks()
            .filter(|b| b.confirmed && !b.delivered && self.held != Some(b.markers[0]))
            .filter(|b| self.objects.gate_for(b.colour).is_some())
            .filter(|b| !self.demoted.contains_key(&b.markers[0]))
            .filter(|b| !self.shared.blocks.contains(&b.markers[0]))
            .filter(|b| self.attempts.get(&b.markers[0]).copied().unwrap_or(0) < MAX_BLOCK_ATTEMPTS)
            .min_by(|a, b| {
                let (da, db) = (a.position.distance(robot), b.position.distance(robot));
                da.total_cmp(&db)
            })
            .copied()
    }

    fn explore_target(
        &mut self,
        rule: TargetRule,
        inputs: &Inputs,
        reach: &[bool],
    ) -> Option<(Point2, Target, String)> {
        let robot = inputs.pose.position();
        match rule {
            TargetRule::Frontiers => {
                let others = self.explored_elsewhere();
                let mapped_elsewhere = |p| mapped_by(&others, p);
                let found: Vec<Point2> =
                    (frontiers(inputs.map, reach, FRONTIER_MIN_CELLS, mapped_elsewhere)
                        .into_iter())
                    .map(|f| f.target)
                    .filter(|p| p.distance(robot) >= TARGET_TOO_CLOSE)
                    .filter(|p| {
                        (self.explored.visited_goals.iter())
                            .chain(&self.given_up.goals)
                            .all(|v| v.distance(*p) >= TARGET_TOO_CLOSE)
                    })
                    .collect();
                self.explored.candidates.extend(&found);
                let found = self.shared.unclaimed(found);
                (found.into_iter())
                    .min_by(|a, b| a.distance(robot).total_cmp(&b.distance(robot)))
                    .map(|p| {
                        let label = format!("frontier ({:.2}, {:.2})", p.x, p.y);
                        (p, Target::Frontier, label)
                    })
            }
            // Seed 001 "Marker Selection Heuristic"; the goal stops short of the wall.
            TargetRule::Markers => {
                let mut skip = self.explored.visited_markers.clone();
                skip.extend(&self.given_up.markers);
                furthest_marker(inputs.landmarks, robot, &skip).map(|(id, p)| {
                    let goal = towards(p, robot, TARGET_TOO_CLOSE);
                    (goal, Target::Marker(id), format!("marker {id}"))
                })
            }
        }
    }

    /// The nearest place, not given up, from which free space the camera has not looked
    /// at can be seen (frontier rule only: the marker rule is the seed's, kept as it is).
    fn unseen_target(
        &mut self,
        inputs: &Inputs,
        reach: &[bool],
    ) -> Option<(Point2, Target, String)> {
        if self.config.target_rule != TargetRule::Frontiers {
            return None;
        }
        let robot = inputs.pose.position();
        let tried: Vec<Point2> = (self.explored.visited_goals.iter())
            .chain(&self.given_up.goals)
            .copied()
            .collect();
        let others = self.explored_elsewhere();
        let unseen = self.explored.coverage.unseen(
            inputs.map,
            reach,
            UNSEEN_MIN_CELLS,
            (&tried, TARGET_TOO_CLOSE),
            |p| seen_by(&others, p),
        );
        let unseen: Vec<Point2> = unseen.into_iter().map(|u| u.target).collect();
        self.explored.candidates.extend(&unseen);
        (self.shared.unclaimed(unseen).into_iter())
            .min_by(|a, b| a.distance(robot).total_cmp(&b.distance(robot)))
            .map(|p| {
                let label = format!("unseen space ({:.2}, {:.2})", p.x, p.y);
                (p, Target::Unseen, label)
            })
    }

    /// Where to look next at the nearest small object the lidar mapped that neither a
    /// landmark nor a block explains, and which one (index into `unexplained`); each is
    /// looked at from four sides, the first from the robot's side.
    fn object_look(&mut self, inputs: &Inputs) -> Option<(Point2, usize)> {
        let robot = inputs.pose.position();
        // A fleet's other robots are small objects to the lidar too.
        let explainers: Vec<Point2> = (inputs.landmarks.values().copied())
            .chain(self.objects.blocks().map(|b| b.position))
            .chain(self.shared.fleet.peers.iter().copied())
            .collect();
        let present = small_objects(inputs.map, inputs.occupied, self.config.object_size);
        let mut open = Vec::new();
        for p in present {
            if explainers.iter().any(|e| e.distance(p) < EXPLAINED_WITHIN) {
                continue;
            }
            let known =
                (self.explored.unexplained.iter()).position(|u| u.at.distance(p) < 2.0 * GATHER);
            let i = known.unwrap_or_else(|| {
                (self.explored.unexplained).push(Unexplained::new(p, robot, None));
                self.explored.unexplained.len() - 1
            });
            if self.explored.unexplained[i].looks < OBJECT_LOOKS {
                open.push(i);
            }
        }
        // Blocks let go where they did not count, until found again.
        let lost = |u: &Unexplained| {
            u.let_go
                .is_some_and(|odd| self.objects.blocks().all(|b| b.markers[0] != odd))
        };
        for (i, u) in self.explored.unexplained.iter().enumerate() {
            if lost(u) && u.looks < OBJECT_LOOKS && !open.contains(&i) {
                open.push(i);
            }
        }
        let i = open.into_iter().min_by(|&a, &b| {
            let d = |i: usize| self.explored.unexplained[i].at.distance(robot);
            d(a).total_cmp(&d(b))
        })?;
        let u = self.explored.unexplained[i];
        let a = u.first + f64::from(u.looks) * std::f64::consts::FRAC_PI_2;
        let d = POTENTIAL_VIEW * self.config.staging_distance;
        Some((Point2::new(u.at.x + d * a.cos(), u.at.y + d * a.sin()), i))
    }

    /// Looks taken so far at the potential block with odd marker `odd`.
    fn looks_at(&self, odd: u32) -> u32 {
        self.explored
            .potential_looks
            .get(&odd)
            .copied()
            .unwrap_or(0)
    }

    /// Gives up an exploration goal the planner cannot reach, until the next retry round.
    pub(super) fn give_up(&mut self, goal: Point2, target: &Target) {
        match *target {
            Target::Frontier | Target::Unseen => self.given_up.goals.push(goal),
            Target::Marker(id) => self.given_up.markers.push(id),
            // A side that cannot be reached counts as a look: the next side is tried.
            Target::Potential(odd) => *self.explored.potential_looks.entry(odd).or_default() += 1,
            Target::Object(i) => self.explored.unexplained[i].looks += 1,
            Target::Home => self.shared.home_reached = true,
        }
    }

    /// Remembers an exploration goal reached so it is not chosen again.
    pub(super) fn arrived(&mut self, goal: Point2, target: Target) {
        self.explored.visited_goals.push(goal);
        // Progress: targets given up may be reachable from here.
        self.given_up.retry_rounds = 0;
        match target {
            Target::Marker(id) => self.explored.visited_markers.push(id),
            Target::Potential(odd) => *self.explored.potential_looks.entry(odd).or_default() += 1,
            Target::Object(i) => self.explored.unexplained[i].looks += 1,
            Target::Home => self.shared.home_reached = true,
            Target::Frontier | Target::Unseen => {}
        }
    }
}
