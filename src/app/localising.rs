//! `:localise`: the console drives the move that tells MCL's hypotheses apart (the same
//! move as `navdeck tour`'s) until MCL says `localised`, at the teleop's speed, in
//! manual mode. Any key or command that moves the robot or changes its mode takes over.

use super::App;
use super::log::Level;
use super::mode::Mode;
use crate::link::runtime::localising::LocalisingMove;
use crate::pilot;

impl App {
    /// Starts the move, or says why there is nothing for it to do.
    pub(super) fn start_localising(&mut self) {
        if self.pilot().mcl().is_none() {
            return self.log(
                Level::Warn,
                "localise needs MCL: start with --estimator mcl and a map (--map or a Nav2 --world)",
            );
        }
        if !LocalisingMove::wanted(self.pilot()) {
            return self.log(
                Level::Info,
                "localise: MCL has localised already (:relocalize looks for the robot everywhere)",
            );
        }
        if self.pilot().mode() != Mode::Manual {
            self.run_intent(pilot::Intent::Mode(Mode::Manual));
        }
        self.localising = Some(LocalisingMove::default());
        self.log(
            Level::Info,
            "localise: driving to tell MCL's hypotheses apart (any drive key takes over)",
        );
    }

    /// Ends the move, if it drives, releasing its key; `why` goes in the log.
    pub(super) fn end_localising(&mut self, why: &str) {
        let Some(mut moving) = self.localising.take() else {
            return;
        };
        if let Some(release) = moving.stop() {
            let stepped = self.runtime.intend(release);
            self.absorb(stepped);
        }
        self.log(Level::Info, format!("localise: stopped, {why}"));
    }

    /// The move's intents for the next control step: none when it is not driving, and
    /// its end once MCL has localised.
    pub(super) fn localising_intents(&mut self) -> Vec<pilot::Intent> {
        let Some(moving) = &mut self.localising else {
            return Vec::new();
        };
        if LocalisingMove::wanted(self.runtime.pilot()) {
            return moving.intents(self.runtime.pilot());
        }
        let release = moving.stop();
        self.localising = None;
        self.log(Level::Info, "localise: MCL has localised, the move stops");
        release.into_iter().collect()
    }
}
