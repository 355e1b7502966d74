//! What the main loop drives: one robot's console, or a fleet of them.

use super::theme::Theme;
use crate::app::{App, KeyKind};
use crate::keymap::Key;
use ratatui::Frame;

/// The console as the main loop sees it: time, keys and the terminal's size in, a
/// frame out when its revision changed, and a stop on every way out.
pub trait Deck {
    fn resize(&mut self, width: u16, height: u16);
    /// Runs every control step due up to `now`.
    fn update(&mut self, now: f64);
    fn handle_key(&mut self, key: Key, kind: KeyKind, now: f64);
    fn should_quit(&self) -> bool;
    /// Changes whenever the screen would look different.
    fn revision(&self) -> u64;
    /// Session time by which the loop must run again.
    fn next_deadline(&self) -> f64;
    /// Stops every robot and says why in the log.
    fn shutdown(&mut self, reason: &str);
    fn draw(&self, frame: &mut Frame, theme: Theme);
}

impl Deck for App {
    fn resize(&mut self, width: u16, height: u16) {
        App::resize(self, width, height);
    }
    fn update(&mut self, now: f64) {
        App::update(self, now);
    }
    fn handle_key(&mut self, key: Key, kind: KeyKind, now: f64) {
        App::handle_key(self, key, kind, now);
        alone(self);
    }
    fn should_quit(&self) -> bool {
        App::should_quit(self)
    }
    fn revision(&self) -> u64 {
        App::revision(self)
    }
    fn next_deadline(&self) -> f64 {
        App::next_deadline(self)
    }
    fn shutdown(&mut self, reason: &str) {
        App::shutdown(self, reason);
    }
    fn draw(&self, frame: &mut Frame, theme: Theme) {
        super::draw::draw(frame, self, theme);
    }
}

/// A console on its own is a fleet of one: stop-all stops its robot, and there is no
/// other robot to select.
fn alone(app: &mut App) {
    match app.take_fleet_ask() {
        Some(crate::app::fleet_view::FleetAsk::StopAll) => {
            app.apply(crate::keymap::Action::Stop);
        }
        Some(_) => app.note(
            crate::app::log::Level::Warn,
            "one robot in this console: --robots N or --ns repeated opens a fleet",
        ),
        None => {}
    }
}
