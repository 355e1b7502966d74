//! The help overlay: the active mode's bindings, generated from the keymap, and a legend.

use crate::app::App;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

/// Lines of `key(s)  description`, one per bound action.
pub fn entries(app: &App, theme: Theme) -> Vec<Line<'static>> {
    app.keymap()
        .bindings(app.pilot().mode())
        .into_iter()
        .map(|(action, keys)| {
            let names: Vec<String> = keys.iter().map(|k| k.to_string()).collect();
            Line::from(vec![
                Span::styled(format!("{:<9}", names.join(" ")), theme.title()),
                Span::styled(action.description().to_string(), theme.value()),
            ])
        })
        .collect()
}

/// What the map's glyphs mean.
pub const LEGEND: &str =
    "@ robot  o truth  + 95% ellipse  # wall  * boundary  x obstacle  R/B gate  r/b block";
