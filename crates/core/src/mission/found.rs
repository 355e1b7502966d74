//! What the mission learns each step: new blocks and gates for the log and the timeline,
//! and demoted blocks that come back into view (seed 001 section 7 "Block Detection").

use super::config::DEMOTED_FOR;
use super::machine::Mission;
use super::objects::{Colour, Found};
use super::pickup::name;
use super::step::{Inputs, Level};

impl Mission {
    /// Updates the objects from the landmarks and tells the log what is new.
    pub(super) fn note_found(&mut self, inputs: &Inputs, log: &mut Vec<(Level, String)>) {
        let robot = inputs.pose.position();
        if inputs.camera_frame {
            self.objects.note_sightings(inputs.seen, robot);
        }
        for found in
            self.objects
                .update(inputs.landmarks, robot, self.config.block_size, inputs.map)
        {
            match found {
                // Re-confirmed by the same landmarks: it stays demoted (below).
                Found::Block(b) if self.demoted.contains_key(&b.markers[0]) => {}
                Found::Block(b) => {
                    log.push((
                        Level::Success,
                        format!("Found {}", name(b.colour, b.markers[0])),
                    ));
                    if !self.timeline.iter().any(|e| e.0 == b.markers[0]) {
                        self.timeline.push((b.markers[0], inputs.t, None, None));
                    }
                }
                Found::PotentialBlock(b) => log.push((
                    Level::Info,
                    format!("Found potential {}", name(b.colour, b.markers[0])),
                )),
                Found::Gate(g) => {
                    log.push((Level::Success, format!("Found {} gate", g.colour.label())))
                }
            }
        }
        // A demoted block is a target again once seen a while after the demotion.
        let t = inputs.t;
        self.demoted.retain(|odd, at| {
            !(t - *at >= DEMOTED_FOR && inputs.seen.iter().any(|m| *m == *odd || *m == odd + 1))
        });
        // Seed 001 "Block Lost During Approach": a potential block until seen again.
        for &odd in self.demoted.keys() {
            self.objects.demote(odd);
        }
        for colour in [Colour::Red, Colour::Blue] {
            let ready = self.objects.gate_for(colour).is_some()
                && self
                    .objects
                    .blocks()
                    .any(|b| b.colour == colour && b.confirmed && !b.delivered);
            if ready && self.announced.insert(colour) {
                // Both a block and its gate known: stop exploring (seed 001 "Operating Modes /
                // Autonomous Operation" and its "Found red gate and blocks" console line).
                // The seed switches to its Thinking mode here; navdeck's mission plans the
                // delivery itself and the mode stays exploration, so the line says that.
                log.push((
                    Level::Info,
                    format!(
                        "Found {} gate and blocks - planning a delivery",
                        colour.label()
                    ),
                ));
            }
        }
    }

    /// Sets a timeline time: 2 picked, 3 delivered.
    pub(super) fn stamp(&mut self, odd: u32, t: f64, field: usize) {
        if let Some(e) = self.timeline.iter_mut().find(|e| e.0 == odd) {
            match field {
                2 => e.2 = Some(t),
                _ => e.3 = Some(t),
            }
        }
    }
}
