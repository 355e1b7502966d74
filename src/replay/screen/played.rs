//! What the replay's console plays: one robot's re-run or a fleet's. Either shows one
//! robot's console and stream (a fleet's: the selected one as recorded, or the one
//! `ctrl-n` and `ctrl-p` chose) and moves to a time when asked.

use crate::app::App;
use crate::record::recorded::Recorded;
use crate::replay::Replay;
use crate::replay::fleet::FleetReplay;
use crate::tui::theme::Theme;
use ratatui::Frame;
use ratatui::layout::Rect;

/// A re-run as the replay's console drives and draws it.
pub trait Played {
    /// The console shown (a fleet's selected robot's).
    fn app(&self) -> &App;
    fn app_mut(&mut self) -> &mut App;
    /// The stream shown as recorded (a fleet's selected robot's).
    fn recorded(&self) -> &Recorded;
    /// Session time of the first and the last thing recorded.
    fn span(&self) -> (f64, f64);
    fn run_to(&mut self, t: f64);
    /// Session time the re-run has reached.
    fn position(&self) -> f64;
    /// Back to the start.
    fn restart(&mut self) -> anyhow::Result<()>;
    /// Goes to session time `t`, forwards or (re-running from the start) backwards.
    fn seek(&mut self, t: f64) -> anyhow::Result<()> {
        if t + 1e-9 < self.position() {
            self.restart()?;
        }
        self.run_to(t);
        Ok(())
    }
    /// The terminal's size: from now on the recorded sizes are not applied.
    fn show_on_screen(&mut self, width: u16, height: u16);
    /// The re-run's screen in `area`.
    fn draw_rerun(&self, frame: &mut Frame, area: Rect, theme: Theme);
    /// Shows another robot of a fleet, `by` places on; one robot has no other.
    fn show_next(&mut self, _by: i8) {}
}

impl Played for Replay {
    fn app(&self) -> &App {
        Replay::app(self)
    }
    fn app_mut(&mut self) -> &mut App {
        Replay::app_mut(self)
    }
    fn recorded(&self) -> &Recorded {
        Replay::recorded(self)
    }
    fn span(&self) -> (f64, f64) {
        Replay::span(self)
    }
    fn run_to(&mut self, t: f64) {
        Replay::run_to(self, t);
    }
    fn position(&self) -> f64 {
        Replay::position(self)
    }
    fn restart(&mut self) -> anyhow::Result<()> {
        Replay::restart(self)
    }
    fn show_on_screen(&mut self, width: u16, height: u16) {
        Replay::show_on_screen(self, width, height);
    }
    fn draw_rerun(&self, frame: &mut Frame, area: Rect, theme: Theme) {
        crate::tui::draw::draw_in(frame, area, self.app(), theme);
    }
}

impl Played for FleetReplay {
    fn app(&self) -> &App {
        FleetReplay::app(self)
    }
    fn app_mut(&mut self) -> &mut App {
        FleetReplay::app_mut(self)
    }
    fn recorded(&self) -> &Recorded {
        self.shown_recorded()
    }
    fn span(&self) -> (f64, f64) {
        FleetReplay::span(self)
    }
    fn run_to(&mut self, t: f64) {
        FleetReplay::run_to(self, t);
    }
    fn position(&self) -> f64 {
        FleetReplay::position(self)
    }
    fn restart(&mut self) -> anyhow::Result<()> {
        FleetReplay::restart(self)
    }
    fn show_on_screen(&mut self, width: u16, height: u16) {
        FleetReplay::show_on_screen(self, width, height);
    }
    /// The fleet's screen: the shown robot's console above the fleet panel.
    fn draw_rerun(&self, frame: &mut Frame, area: Rect, theme: Theme) {
        self.fleet().draw_showing(frame, area, theme, self.shown());
    }
    fn show_next(&mut self, by: i8) {
        FleetReplay::show_next(self, by);
    }
}
