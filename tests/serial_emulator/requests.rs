//! The requests the emulated firmware received, read back.

use super::firmware::State;

impl State {
    /// The `m L R` requests received, as (L, R), from request number `from` on.
    pub fn motor_targets(&self, from: usize) -> Vec<(i32, i32)> {
        self.requests[from.min(self.requests.len())..]
            .iter()
            .filter_map(|r| {
                let mut it = r.strip_prefix("m ")?.split(' ');
                Some((it.next()?.parse().ok()?, it.next()?.parse().ok()?))
            })
            .collect()
    }
}
