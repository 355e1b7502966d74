//! Blocks and the jaws: the gripper's commands, catching the free block between the jaws
//! (or at an arm's tool tip), carrying it, and the free blocks' outlines and markers the
//! sensors see.

use super::Twin;
use crate::data::GripperCommand;
use crate::geometry::Pose2;

impl Twin {
    /// Starts the jaws moving; opening lets a held block go where it is.
    pub fn command_gripper(&mut self, cmd: GripperCommand) {
        let held = self.gripper.held();
        if self.gripper.command(cmd) {
            self.catch_block();
        }
        if let (Some(i), None) = (held, self.gripper.held()) {
            self.blocks[i].held = false;
            self.free_blocks.moved = true;
            self.released = Some(i);
        }
    }

    /// Carries free block `index` to `pose`, as a hand moving it would (for tests of a
    /// pick whose block moved after it was seen); a held or unknown block stays put.
    pub fn move_block(&mut self, index: usize, pose: Pose2) {
        if let Some(block) = self.blocks.get_mut(index).filter(|b| !b.held) {
            block.pose = pose;
            self.free_blocks.moved = true;
        }
    }

    /// A block in an arm's jaws rides at the tool tip.
    pub(super) fn carry_in_arm(&mut self) {
        let (Some(arm), Some(i)) = (&self.arm, self.gripper.held()) else {
            return;
        };
        let [x, y, _] = arm.tool_in_robot();
        let p = self
            .pose
            .transform_point(crate::geometry::Point2::new(x, y));
        let theta = self.blocks[i].pose.theta;
        self.blocks[i].pose = Pose2::new(p.x, p.y, theta);
        self.free_blocks.moved = true;
    }

    /// At the end of closing: catch the free block nearest the middle of the jaw zone.
    pub(super) fn catch_block(&mut self) {
        let pose = self.pose;
        if let Some(arm) = &self.arm {
            // An arm's jaws close round a block only when the tool tip is at it.
            let [x, y, z] = arm.tool_in_robot();
            let tip = pose.transform_point(crate::geometry::Point2::new(x, y));
            let tol = crate::sim::arm::GRASP_TOLERANCE;
            let caught = (self.blocks.iter().enumerate())
                .filter(|(_, b)| !b.held)
                .map(|(i, b)| (i, b.pose.position().distance(tip), b.size))
                .filter(|&(_, d, size)| d <= size / 2.0 + tol && (-tol..=size + tol).contains(&z))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((i, _, _)) = caught {
                self.gripper.grab(i, pose, self.blocks[i].pose);
                self.blocks[i].held = true;
                self.free_blocks.moved = true;
            }
            return;
        }
        let best = self
            .blocks
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.held)
            .filter_map(|(i, b)| {
                self.gripper
                    .jaw_offset(pose, b.pose.position())
                    .map(|d| (i, d))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((i, _)) = best {
            self.gripper.grab(i, pose, self.blocks[i].pose);
            self.blocks[i].held = true;
            self.free_blocks.moved = true;
        }
    }

    /// Outlines and markers of the blocks not in the gripper (a held block is carried out
    /// of sight of both sensors).
    pub(super) fn refresh_blocks(&mut self) {
        if !self.free_blocks.moved {
            return;
        }
        self.free_blocks.edges.clear();
        self.free_blocks.markers.clear();
        for b in self.blocks.iter().filter(|b| !b.held) {
            self.free_blocks.edges.extend(b.edges());
            self.free_blocks.markers.extend(b.current_markers());
        }
        self.free_blocks.moved = false;
    }
}
