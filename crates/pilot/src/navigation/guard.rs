//! The contact guard: a command whose forward (or backward) motion, kept up until the
//! robot could brake, would put the footprint onto something the lidar mapped loses that
//! motion; turning stays allowed, since the footprint is round. It watches the follower
//! and every motion the mission drives itself (facing, creeping up to a block, pushing
//! one into its gate, backing away).

use super::super::Pilot;
use super::REPLAN_EVERY;
use navdeck_core::data::{GripperState, Level};
use navdeck_core::geometry::{Point2, Twist};
use navdeck_core::map::contact::{HeldZone, JAWS, contact_ahead};

impl Pilot {
    /// What the jaws may have in them without it counting as an obstacle: a held block,
    /// or with a gripper alone (no arm) and its jaws not shut, the block they are about to
    /// close on (a gripper that reports no state may be open).
    fn jaw_zone(&self, approaching: bool) -> Option<HeldZone> {
        let shut = matches!(
            self.hand.state,
            Some(GripperState::Closed | GripperState::Closing)
        );
        let holding = self.hand.state == Some(GripperState::Holding);
        (holding || (approaching && !shut && self.hand.arm.is_none())).then_some(JAWS)
    }

    /// The first mapped obstacle `twist` would bring the footprint onto, if any.
    fn contact(&self, twist: Twist, jaws: Option<HeldZone>) -> Option<Point2> {
        let robot = &self.settings.robot;
        let margin = self.settings.follow.stop_margin;
        if margin == 0.0 {
            return None;
        }
        let horizon = robot.control_period + twist.linear.abs() / robot.max_linear_accel;
        contact_ahead(
            self.belief.costmap(),
            self.belief.sensed_occupied(),
            self.pose(),
            twist,
            robot.footprint_radius + margin,
            horizon,
            jaws,
        )
    }

    /// The follower's command, guarded; the path is then planned again from where the
    /// robot stands.
    pub(super) fn guarded(&mut self, t: f64, twist: Twist) -> Twist {
        let Some(q) = self.contact(twist, self.jaw_zone(false)) else {
            self.nav.in_contact = false;
            return twist;
        };
        if !self.nav.in_contact {
            self.nav.in_contact = true;
            let reason = format!("obstacle ahead at ({:.2}, {:.2}), stopped", q.x, q.y);
            self.replan(t, reason);
        } else if t - self.nav.last_replan >= REPLAN_EVERY {
            self.replan(t, "obstacle still ahead".to_string());
        }
        Twist::new(0.0, twist.angular)
    }

    /// A motion the mission drives itself, guarded; said once per stop. The mission's
    /// stages end on their own timers, so a stopped creep turns into a retry.
    pub(crate) fn guarded_drive(&mut self, twist: Twist) -> Twist {
        let approaching = twist.linear > 0.0;
        let Some(q) = self.contact(twist, self.jaw_zone(approaching)) else {
            self.nav.drive_in_contact = false;
            return twist;
        };
        if !self.nav.drive_in_contact {
            self.nav.drive_in_contact = true;
            let way = if twist.linear < 0.0 {
                "behind"
            } else {
                "ahead"
            };
            self.log(
                Level::Warn,
                format!("obstacle {way} at ({:.2}, {:.2}): stopped short", q.x, q.y),
            );
        }
        Twist::new(0.0, twist.angular)
    }
}
