//! The fault switches of the emulated firmware: garbage on the wire, a dropped or slow
//! reply, an encoder jump, and the cable pulled and plugged back in.

use super::firmware::{Control, Emulator};
use std::time::Duration;

impl Emulator {
    pub fn inject_garbage(&self, bytes: &[u8]) {
        self.state().garbage = Some(bytes.to_vec());
    }

    pub fn drop_next_reply(&self) {
        self.state().drop_next = true;
    }

    pub fn delay_next_reply(&self, delay: Duration) {
        self.state().delay_next = Some(delay);
    }

    /// Adds `counts` to the left encoder at once, as a glitch or a reset would.
    pub fn jump_left(&self, counts: f64) {
        self.state().left += counts;
    }

    /// Pulls the cable: the terminal closes and the device path disappears.
    pub fn unplug(&self) {
        self.control.send(Control::Unplug).unwrap();
        self.wait_for("the unplug", |s| !s.plugged);
    }

    /// Plugs it back in: a new terminal behind the same path, the board freshly reset.
    pub fn replug(&self) {
        self.control.send(Control::Replug).unwrap();
        self.wait_for("the replug", |s| s.plugged);
    }
}
