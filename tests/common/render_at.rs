//! The console drawn once, at a size.

use super::screen::screen;
use navdeck::app::App;
use ratatui::Terminal;
use ratatui::backend::TestBackend;

/// The console drawn once on a `width` x `height` test terminal, as text.
pub fn render_at(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|frame| {
            navdeck::tui::draw::draw(frame, app, navdeck::tui::theme::Theme::from_env(None))
        })
        .unwrap();
    screen(&terminal)
}
