//! The safety gate: the robot is commanded nothing while the e-stop is on, the link is in
//! doubt, or the console is ending; after a loss, control resumes only on the user's word.

use super::Pilot;
use navdeck_core::data::Level;
use navdeck_core::geometry::Twist;

/// Whether the robot link is answering.
#[derive(Clone, Debug, PartialEq)]
pub enum LinkStatus {
    Ok,
    Lost(String),
    /// Data flows again, but the robot stays still until the user presses a key.
    Back,
}

/// What keeps the robot still.
#[derive(Clone, Debug)]
pub(super) struct Gate {
    pub estop: bool,
    /// The console is ending: nothing more is commanded.
    pub halted: bool,
    pub link: LinkStatus,
    /// Whether the link has ever answered: only a loss after that needs a key to resume.
    pub link_was_up: bool,
}

impl Default for Gate {
    fn default() -> Self {
        Self {
            estop: false,
            halted: false,
            link: LinkStatus::Ok,
            link_was_up: false,
        }
    }
}

impl Gate {
    /// Whether control is in doubt: the command is forced to zero.
    pub fn in_doubt(&self) -> bool {
        self.why_in_doubt().is_some()
    }

    /// Why control is in doubt, if it is: the reason the e-stop behaviour gives.
    pub fn why_in_doubt(&self) -> Option<String> {
        if self.halted {
            Some("the console is ending".into())
        } else if self.estop {
            Some("pressed".into())
        } else {
            match &self.link {
                LinkStatus::Ok => None,
                LinkStatus::Lost(_) if !self.link_was_up => Some("waiting for the robot".into()),
                LinkStatus::Lost(why) => Some(format!("link lost ({why})")),
                LinkStatus::Back => Some("link back: waiting for a key".into()),
            }
        }
    }
}

impl Pilot {
    /// The link answered at `t`.
    pub(super) fn link_answered(&mut self, t: f64) {
        if let LinkStatus::Lost(_) = self.behaviours.gate.link {
            if self.behaviours.gate.link_was_up {
                self.behaviours.gate.link = LinkStatus::Back;
                self.log_at(
                    t,
                    Level::Success,
                    "link back: press any key to resume control",
                );
            } else {
                // Control was never established, so there is nothing to resume.
                self.behaviours.gate.link = LinkStatus::Ok;
                self.log_at(t, Level::Success, "link up");
            }
        }
        self.behaviours.gate.link_was_up = true;
    }

    /// Control is lost: drop held keys, command nothing further, say so once.
    pub(super) fn lose_link(&mut self, t: f64, reason: String) {
        if !matches!(self.behaviours.gate.link, LinkStatus::Lost(_)) {
            // Before the robot first answers, waiting is expected rather than an error.
            let level = if self.behaviours.gate.link_was_up {
                Level::Error
            } else {
                Level::Info
            };
            self.log_at(t, level, reason.clone());
        }
        self.behaviours.gate.link = LinkStatus::Lost(reason);
        self.restart_sensor_health();
        self.teleop.clear();
        self.measuring.commanded = Twist::ZERO;
    }

    /// The user's word after the link came back.
    pub(super) fn resume(&mut self) {
        if self.behaviours.gate.link == LinkStatus::Back {
            self.behaviours.gate.link = LinkStatus::Ok;
            self.log(Level::Success, "control resumed");
        }
    }
}
