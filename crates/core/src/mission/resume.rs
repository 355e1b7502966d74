//! Taking the mission up again after the user drove the robot.

use super::machine::Mission;
use super::phase::Phase;
use super::pickup::name;
use super::step::Level;
use crate::data::GripperState;

/// What resuming says, and the markers whose landmarks the filter should drop.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Resumed {
    pub log: Vec<(Level, String)>,
    pub forget: Vec<u32>,
}

impl Mission {
    /// Takes the mission up again at `t` after the user drove the robot: the blocks and
    /// gates found and the deliveries stand; what to do next is chosen afresh from where
    /// the robot now is (a handover's cause and the targets given up are cleared: the user
    /// may have fixed what stopped it). A block held when the user took over goes on to
    /// its gate if the gripper still holds it (or cannot tell); otherwise it was put down
    /// somewhere and is forgotten, to be found again: its markers are returned so the
    /// filter can drop their old places.
    pub fn resume(&mut self, t: f64, gripper: Option<GripperState>) -> Resumed {
        let mut log = Vec::new();
        let mut forget = Vec::new();
        self.handover = None;
        self.relocated = false;
        self.given_up.retry_rounds = 0;
        self.given_up.goals.clear();
        self.given_up.markers.clear();
        self.last_marker = t;
        self.phase = Phase::Choose;
        if let Some(odd) = self.held {
            let block = self.objects.blocks().find(|b| b.markers[0] == odd).copied();
            let holding = matches!(gripper, None | Some(GripperState::Holding));
            match block {
                Some(b) if holding => {
                    log.push((
                        Level::Info,
                        format!("Still holding {} - on to its gate", name(b.colour, odd)),
                    ));
                    self.phase = self.delivering(odd, b.colour, t);
                }
                _ => {
                    let what = block.map_or(format!("block {odd}"), |b| name(b.colour, odd));
                    log.push((
                        Level::Warn,
                        format!("{what} is no longer in the gripper - looking for it again"),
                    ));
                    self.held = None;
                    self.objects.forget(odd);
                    self.demoted.remove(&odd);
                    forget = vec![odd, odd + 1];
                }
            }
        }
        log.push((
            Level::Info,
            format!(
                "Mission resumed: {} delivered, {} more known",
                self.objects.delivered(),
                self.objects.blocks().filter(|b| !b.delivered).count()
            ),
        ));
        Resumed { log, forget }
    }
}
