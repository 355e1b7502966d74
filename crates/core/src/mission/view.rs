//! Read-only views of the mission for the status panel.

use super::config::{LOST_SCAN_AFTER, OBJECT_LOOKS, POTENTIAL_LOOKS};
use super::machine::{Mission, TimelineEntry};
use super::phase::{Phase, Target};
use crate::geometry::Point2;

impl Mission {
    /// The sub-state and its target, e.g. "approach red block 421".
    pub fn state_label(&self) -> String {
        match &self.phase {
            Phase::Start => "starting".into(),
            Phase::Scan { turn, initial } => {
                let what = if *initial { "initial scan" } else { "scan" };
                format!("{what} {:.0}%", 100.0 * turn.progress())
            }
            Phase::Choose => "thinking".into(),
            Phase::Explore { leg, target } => {
                let what = match target {
                    Target::Potential(_) | Target::Object(_) => "look at",
                    Target::Home => "back to",
                    _ => "explore",
                };
                match leg.retrying() {
                    Some(n) => format!("no path ({n}): retry {what} {}", leg.label),
                    None => format!("{what} {}", leg.label),
                }
            }
            Phase::Lost(_, None) => "lost: scanning for landmarks".into(),
            Phase::Lost(_, Some(leg)) => format!("lost: going back to {}", leg.label),
            Phase::BackOff(_) => "backing away from a lost block".into(),
            Phase::Pickup(p) => p.label(),
            Phase::Deliver(d) => d.label(),
            Phase::WaitArm => "waiting for the arm".into(),
            Phase::Done => "done".into(),
            Phase::Manual => "handed to manual".into(),
        }
    }

    /// Whether the mission is picking up a block or delivering one (pick-and-place), not
    /// looking for one (exploration).
    pub fn is_handling_a_block(&self) -> bool {
        matches!(self.phase, Phase::Pickup(_) | Phase::Deliver(_))
    }

    /// Whether the arm is at work on a block (picking it up or putting it down): without
    /// the arm, the mission cannot go on from there.
    pub fn arm_engaged(&self) -> bool {
        match &self.phase {
            Phase::Pickup(p) => p.arm_engaged(),
            Phase::Deliver(d) => d.arm_engaged(),
            _ => false,
        }
    }

    /// The marker of the block being picked up, while one is.
    pub fn block_being_picked(&self) -> Option<u32> {
        match &self.phase {
            Phase::Pickup(p) => Some(p.block),
            _ => None,
        }
    }

    /// The centre of the block being picked up as its lidar outline places it, while the
    /// robot is near it (the point its final approach aims at), and the radius of the
    /// circle round its corners.
    pub fn picked_block_outline(&self) -> Option<(crate::geometry::Point2, f64)> {
        match &self.phase {
            Phase::Pickup(p) => p
                .outline()
                .map(|c| (c, self.config.block_size * std::f64::consts::FRAC_1_SQRT_2)),
            _ => None,
        }
    }

    /// Why the mission is doing what `state_label` says, in two status rows at most,
    /// e.g. "camera has not looked there (4 left)".
    pub fn reason(&self) -> String {
        let left = self.explored.candidates.len();
        match &self.phase {
            Phase::Start | Phase::Choose => String::new(),
            Phase::Scan { initial: true, .. } => "a look round before choosing".into(),
            Phase::Scan { .. } => "a look round from here".into(),
            Phase::Explore { target, .. } => match target {
                Target::Frontier => format!("reachable unknown space ({left} left)"),
                Target::Unseen => format!("camera has not looked there ({left} left)"),
                Target::Marker(_) => "furthest marker not yet visited".into(),
                Target::Potential(odd) => format!(
                    "1 marker seen; look {}/{POTENTIAL_LOOKS} for the other",
                    self.explored.potential_looks.get(odd).copied().unwrap_or(0) + 1
                ),
                Target::Object(i) => format!(
                    "lidar sees it, no marker; look {}/{OBJECT_LOOKS}",
                    self.explored.unexplained.get(*i).map_or(0, |u| u.looks) + 1
                ),
                Target::Home => "nothing left: out of the other robots' way".into(),
            },
            Phase::Lost(..) if self.config.lost_position_std > 0.0 => {
                format!(
                    "no landmark for {LOST_SCAN_AFTER:.0} s, position unsure (σ > {:.0} cm)",
                    self.config.lost_position_std * 100.0
                )
            }
            Phase::Lost(..) => format!("no landmark in view for {LOST_SCAN_AFTER:.0} s"),
            Phase::BackOff(_) => "block lost from view in the approach".into(),
            Phase::Pickup(_) => "block seen whole, its gate known".into(),
            Phase::Deliver(_) => "holding the block, its gate known".into(),
            Phase::WaitArm => "a block to pick up, the arm not answering".into(),
            Phase::Done => "all explored, every block delivered".into(),
            Phase::Manual => self.handover.unwrap_or("taken over").to_string(),
        }
    }

    /// Blocks delivered so far.
    pub fn delivered(&self) -> usize {
        self.objects.delivered()
    }

    /// Blocks delivered so far, each where it was put down.
    pub fn delivered_blocks(&self) -> impl Iterator<Item = &super::objects::Block> {
        self.objects.blocks().filter(|b| b.delivered)
    }

    /// Blocks confirmed by both markers, delivered ones included.
    pub fn known_blocks(&self) -> usize {
        self.objects
            .blocks()
            .filter(|b| b.confirmed || b.delivered)
            .count()
    }

    /// Plan requests repeated for the same goal (stuck, no path, dropped path).
    pub fn replans(&self) -> usize {
        self.ctx.replans
    }

    /// Recovery actions started: lost scans, no-path turns, stuck replans, gripper
    /// retries, demoted blocks.
    pub fn recoveries(&self) -> usize {
        self.ctx.recoveries
    }

    /// Each confirmed block: odd marker, found, picked up and delivered times.
    pub fn timeline(&self) -> &[TimelineEntry] {
        &self.timeline
    }

    /// The mission finished with every block it had to deliver delivered.
    pub fn is_done(&self) -> bool {
        matches!(self.phase, Phase::Done)
    }

    /// The exploration targets the last choice weighed, and the one it is heading for.
    pub fn exploration_targets(&self) -> (&[Point2], Option<Point2>) {
        let heading = match &self.phase {
            Phase::Explore { leg, .. } => Some(leg.goal),
            _ => None,
        };
        (&self.explored.candidates, heading)
    }

    /// Why the mission handed the robot to manual control, if it has.
    pub fn handover_cause(&self) -> Option<&'static str> {
        self.handover
    }

    /// Whether the mission is working the gripper now (picking up or delivering): the
    /// gripper keys leave it alone then.
    pub fn holds_gripper(&self) -> bool {
        matches!(self.phase, Phase::Pickup(_) | Phase::Deliver(_))
    }
}
