//! Choosing what to do next (seed 001 "Operating Modes", `t` Thinking): a deliverable
//! block first, else the next exploration target, else potential blocks, else finish.

use super::config::{FRONTIER_MIN_CELLS, MAX_BLOCK_ATTEMPTS, TARGET_TOO_CLOSE, TargetRule};
use super::drive::towards;
use super::leg::Leg;
use super::machine::{Mission, Phase, Target};
use super::objects::Block;
use super::pickup::{Pickup, name};
use super::step::{Inputs, Level};
use super::targets::{frontiers, furthest_marker};
use crate::geometry::Point2;

impl Mission {
    pub(super) fn choose(&mut self, inputs: &Inputs, log: &mut Vec<(Level, String)>) {
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
        if let Some(block) = self.deliverable(robot) {
            *self.attempts.entry(block.markers[0]).or_default() += 1;
            self.phase = Phase::Pickup(Pickup::new(
                &block,
                robot,
                inputs.map,
                &self.config,
                inputs.t,
            ));
            return;
        }
        let rule = self.config.target_rule;
        for rule in [rule, rule.other()] {
            if let Some((goal, target, label)) = self.explore_target(rule, inputs) {
                self.phase = Phase::Explore {
                    leg: Leg::new(goal, label),
                    target,
                };
                return;
            }
        }
        // Nothing left to explore: go and look at blocks seen by one marker only.
        let potential = self
            .objects
            .blocks()
            .filter(|b| !b.confirmed && !b.delivered)
            .filter(|b| !self.visited_potential.contains(&b.markers[0]))
            .min_by(|a, b| {
                let (da, db) = (a.position.distance(robot), b.position.distance(robot));
                da.total_cmp(&db)
            })
            .copied();
        if let Some(b) = potential {
            let goal = towards(b.position, robot, self.config.staging_distance);
            let label = format!("potential {}", name(b.colour, b.markers[0]));
            self.phase = Phase::Explore {
                leg: Leg::new(goal, label),
                target: Target::Potential(b.markers[0]),
            };
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
            self.phase = Phase::Manual;
        }
    }

    /// The nearest confirmed, undelivered block whose gate is known and that is not
    /// waiting after a demotion.
    pub(super) fn deliverable(&self, robot: Point2) -> Option<Block> {
        self.objects
            .blocks()
            .filter(|b| b.confirmed && !b.delivered)
            .filter(|b| self.objects.gate_for(b.colour).is_some())
            .filter(|b| !self.demoted.contains_key(&b.markers[0]))
            .filter(|b| self.attempts.get(&b.markers[0]).copied().unwrap_or(0) < MAX_BLOCK_ATTEMPTS)
            .min_by(|a, b| {
                let (da, db) = (a.position.distance(robot), b.position.distance(robot));
                da.total_cmp(&db)
            })
            .copied()
    }

    fn explore_target(
        &self,
        rule: TargetRule,
        inputs: &Inputs,
    ) -> Option<(Point2, Target, String)> {
        let robot = inputs.pose.position();
        match rule {
            TargetRule::Frontiers => frontiers(inputs.map, FRONTIER_MIN_CELLS)
                .into_iter()
                .map(|f| f.target)
                .filter(|p| p.distance(robot) >= TARGET_TOO_CLOSE)
                .filter(|p| {
                    self.visited_goals
                        .iter()
                        .all(|v| v.distance(*p) >= TARGET_TOO_CLOSE)
                })
                .min_by(|a, b| a.distance(robot).total_cmp(&b.distance(robot)))
                .map(|p| {
                    let label = format!("frontier ({:.2}, {:.2})", p.x, p.y);
                    (p, Target::Frontier, label)
                }),
            // Seed 001 "Marker Selection Heuristic"; the goal stops short of the wall.
            TargetRule::Markers => furthest_marker(inputs.landmarks, robot, &self.visited_markers)
                .map(|(id, p)| {
                    let goal = towards(p, robot, TARGET_TOO_CLOSE);
                    (goal, Target::Marker(id), format!("marker {id}"))
                }),
        }
    }

    /// Remembers an exploration goal reached so it is not chosen again.
    pub(super) fn arrived(&mut self, goal: Point2, target: Target) {
        self.visited_goals.push(goal);
        match target {
            Target::Marker(id) => self.visited_markers.push(id),
            Target::Potential(odd) => {
                self.visited_potential.insert(odd);
            }
            Target::Frontier => {}
        }
    }
}
