//! The localising move as drive keys: while MCL weighs several places the robot could
//! be, hold the key the seek asks for (`navdeck_core::slam::mcl::seek`), releasing the one
//! held before so the teleop's deadman never keeps two. `navdeck tour` and the console's
//! `:localise` drive the same move.

use navdeck_core::slam::mcl::seek::{Seek, SeekDrive};
use navdeck_pilot::teleop::DriveKey;
use navdeck_pilot::{Intent, Pilot};

/// The robot keeps this far from what is ahead while seeking, metres, or its footprint
/// when that is larger: room to turn in place before it would touch.
const SEEK_NEAR: f64 = 0.4;

/// The move's state: the seek and the key it holds.
#[derive(Clone, Debug, Default)]
pub struct LocalisingMove {
    seek: Seek,
    held: Option<DriveKey>,
}

impl LocalisingMove {
    /// Whether MCL runs and still looks for the robot: the move has something to do.
    pub fn wanted(pilot: &Pilot) -> bool {
        pilot.mcl().is_some_and(|m| !m.status().converged)
    }

    /// This step's intents: release the key held before if the move now wants another,
    /// and hold the one it wants (repeated, as a held key is).
    pub fn intents(&mut self, pilot: &Pilot) -> Vec<Intent> {
        let key = self.key(pilot);
        let mut asked = Vec::new();
        if let Some(old) = self.held.replace(key)
            && old != key
        {
            asked.push(Intent::KeyUp(old));
        }
        asked.push(Intent::KeyDown { key, repeat: true });
        asked
    }

    /// Ends the move: the key it holds, released (none if it held nothing).
    pub fn stop(&mut self) -> Option<Intent> {
        self.seek = Seek::default();
        self.held.take().map(Intent::KeyUp)
    }

    fn key(&mut self, pilot: &Pilot) -> DriveKey {
        let (Some(mcl), Some((_, scan))) = (pilot.mcl(), pilot.newest_scan()) else {
            return DriveKey::TurnLeft;
        };
        let footprint = pilot.settings().robot.footprint_radius;
        let drive = (self.seek).step(
            pilot.odometry_pose(),
            scan,
            mcl.map(),
            mcl.hypotheses(),
            SEEK_NEAR.max(footprint),
        );
        match drive {
            SeekDrive::TurnLeft => DriveKey::TurnLeft,
            SeekDrive::TurnRight => DriveKey::TurnRight,
            SeekDrive::Forward => DriveKey::Forward,
        }
    }
}
