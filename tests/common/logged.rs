//! What the console's log says.

use navdeck::app::App;

/// Whether the console's log has a line containing `text`.
pub fn logged(app: &App, text: &str) -> bool {
    app.log_book().iter().any(|e| e.text.contains(text))
}
