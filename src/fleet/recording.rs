//! Recording a fleet (`--record`, `[record] folder`): one file, each robot's stream under
//! its own namespace as its console records it alone, and the fleet's own calls (ticks,
//! keys, terminal sizes) so that a replay selects and stops as the session did.

use super::Fleet;
use crate::app::log::Level;
use crate::msgs::record::InputMsg;
use crate::record::fleet::{FLEET_METADATA, fleet_entries};
use crate::record::{RecordConfig, Recorder, Summary, Topic};
use std::collections::BTreeMap;
use std::path::Path;

impl Fleet {
    /// Records the fleet from now on into `path` (which must not exist). `epoch` is the
    /// wall time of session time 0; `session` says how it was started, and each robot's
    /// stream adds its name and (for a twin) its own seed. `simulated`: the session runs
    /// on simulated time, so the loop may wait for the writer rather than drop.
    pub fn record_to(
        &mut self,
        path: &Path,
        config: &RecordConfig,
        epoch: f64,
        session: BTreeMap<String, String>,
        simulated: bool,
    ) -> anyhow::Result<()> {
        let names: Vec<String> = self.members.iter().map(|m| m.name.clone()).collect();
        let recorders = Recorder::create_fleet(path, config, epoch, &names)?;
        let now = self.app().now();
        let seed: Option<u64> = session.get("seed").and_then(|s| s.parse().ok());
        let mut twins = 0u64;
        for (member, mut recorder) in self.members.iter_mut().zip(recorders.robots) {
            recorder.wait_when_full(simulated);
            let mut own = session.clone();
            own.insert("fleet_robot".into(), member.name.clone());
            if member.app.link().ground_truth().is_some() {
                // Each twin of a fleet has its own noise seed: the fleet's plus its index.
                if let Some(seed) = seed {
                    own.insert("seed".into(), seed.wrapping_add(twins).to_string());
                }
                twins += 1;
            }
            member.app.record_to(recorder, own);
        }
        let mut fleet = recorders.fleet;
        fleet.wait_when_full(simulated);
        let mut entries = fleet_entries(&names, now);
        entries.insert("selected".into(), names[self.selected].clone());
        fleet.metadata(FLEET_METADATA, entries);
        let (width, height) = self.screen;
        fleet.publish(Topic::Input, now, InputMsg::resize(now, width, height));
        self.recorder = Some(fleet);
        Ok(())
    }

    /// Where the fleet is being recorded, if it is.
    pub fn recording_path(&self) -> Option<&Path> {
        self.recorder.as_ref().map(Recorder::path)
    }

    /// One call into the fleet, so a replay can make it again.
    pub(super) fn record_input(&mut self, msg: InputMsg) {
        if let Some(r) = self.recorder.as_mut() {
            let t = msg.time;
            r.publish(Topic::Input, t, msg);
            r.hand_over_due(t);
        }
    }

    /// Says in the selected robot's log that a robot which joined is not in the
    /// recording (the file's streams are set when it starts).
    pub(super) fn note_unrecorded(&mut self, name: &str) {
        if self.recorder.is_some() {
            let text = format!("robot {name} is not recorded: it joined after the recording began");
            self.app_mut().note(Level::Warn, text);
        }
    }

    /// Closes the recording: every robot's stream, then the fleet's, which finishes the
    /// file and says what it holds. A robot's stream that failed is named.
    pub fn finish_recording(&mut self) -> Option<Result<Summary, String>> {
        let mut fleet = self.recorder.take()?;
        let mut failed = None;
        for m in &mut self.members {
            if let Some(Err(why)) = m.app.finish_recording() {
                failed.get_or_insert(format!("robot {}: {why}", m.name));
            }
        }
        fleet.hand_over();
        let summary = fleet.finish();
        match (summary, failed) {
            (Ok(_), Some(why)) => Some(Err(why)),
            (summary, _) => Some(summary),
        }
    }
}
