//! The firmware's PID frames: waiting for some to pass, and the encoder counts they
//! integrate set outright.

use super::firmware::Emulator;

impl Emulator {
    /// Blocks until `n` more PID frames have run (real time passing on the robot).
    pub fn wait_frames(&self, n: u64) {
        let until = self.state().frames + n;
        self.wait_for("the frames pass", |s| s.frames >= until);
    }

    pub fn set_counts(&self, left: f64, right: f64) {
        let mut s = self.state();
        s.left = left;
        s.right = right;
    }
}
