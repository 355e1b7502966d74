//! `:fault`: faults injected into the twin from the console, on its simulated time.
//! `:fault camera+20` darkens the camera from now for 20 s, `:fault camera@60+20` from
//! 60 s, `:fault clear` ends them all, `:fault` alone lists them. The twin's own lines
//! say when each begins and ends ("fault injected: camera dark for 20 s").

use super::App;
use super::log::Level;
use crate::sim::{FaultSpec, Faults, Scheduled};

/// Said where no twin stands behind the link.
const TWIN_ONLY: &str = "fault: faults are injected into the twin only (--link sim)";

impl App {
    /// The faults injected into the twin and which are in force, for the status and the
    /// runners; None where there is no twin.
    pub fn faults(&self) -> Option<&Faults> {
        self.link().faults()
    }

    /// Schedules `text` (a spec `parse` has read once already); one without `@START`
    /// begins now.
    pub(super) fn inject_fault(&mut self, text: &str) {
        let Some(faults) = self.runtime.link_mut().faults_mut() else {
            return self.log(Level::Warn, TWIN_ONLY);
        };
        // Now to the millisecond, not after it: a fault from now is in force at once.
        let now = (faults.now() * 1000.0).floor() / 1000.0;
        let spec = match FaultSpec::parse_at(text, now) {
            // A start window is drawn from the present's bits: any moment within it.
            Ok(spec) => spec.drawn(now.to_bits()),
            Err(e) => return self.log(Level::Error, format!(":fault {text}: {e}")),
        };
        match faults.schedule(spec) {
            // The twin says so as the fault begins, at the next poll.
            Scheduled::Now => {}
            Scheduled::Later(at) => self.log(
                Level::Info,
                format!("fault {spec} scheduled: begins in {:.1} s", at - now),
            ),
            Scheduled::Past => self.log(
                Level::Warn,
                format!("fault {spec} not injected: its time is over (simulated time {now:.1} s)"),
            ),
        }
    }

    /// Ends every fault in force (the twin says which) and forgets those to come.
    pub(super) fn clear_faults(&mut self) {
        let Some(faults) = self.runtime.link_mut().faults_mut() else {
            return self.log(Level::Warn, TWIN_ONLY);
        };
        match faults.clear() {
            (0, 0) => self.log(Level::Info, "fault clear: no fault to clear"),
            (_, 0) => {}
            (_, forgotten) => self.log(
                Level::Info,
                format!("fault clear: {forgotten} still to come forgotten"),
            ),
        }
    }

    /// Lists the faults in force and those to come.
    pub(super) fn show_faults(&mut self) {
        let Some(faults) = self.faults() else {
            return self.log(Level::Warn, TWIN_ONLY);
        };
        let listed = |in_force: bool| -> Vec<String> {
            (faults.records().iter())
                .filter(|r| r.ended.is_none() && r.began.is_some() == in_force)
                .map(|r| r.spec.to_string())
                .collect()
        };
        let (now, later) = (listed(true), listed(false));
        let text = if now.is_empty() && later.is_empty() {
            "faults: none in force or to come (:fault camera+20 darkens the camera for 20 s)"
                .to_string()
        } else {
            let or_none = |v: Vec<String>| {
                if v.is_empty() {
                    "none".to_string()
                } else {
                    v.join(", ")
                }
            };
            format!(
                "faults in force: {}; to come: {}",
                or_none(now),
                or_none(later)
            )
        };
        self.log(Level::Info, text);
    }
}
