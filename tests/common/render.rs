//! The console drawn once, at the usual size.

use super::render_at::render_at;
use navdeck::app::App;

/// The console drawn once on a 100x30 test terminal, as text.
pub fn render(app: &App) -> String {
    render_at(app, 100, 30)
}
