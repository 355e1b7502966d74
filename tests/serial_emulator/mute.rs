//! The emulated firmware hangs.

use super::firmware::Emulator;

impl Emulator {
    /// The firmware hangs: it goes on reading requests but never answers again.
    pub fn mute(&self) {
        self.state().muted = true;
    }
}
