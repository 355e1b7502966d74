//! The log pane: newest lines at the bottom, coloured by level.

use crate::app::App;
use crate::app::log::format_time;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

/// The newest `rows` log lines as text.
pub fn lines(app: &App, theme: Theme, rows: usize) -> Vec<Line<'static>> {
    app.log_book()
        .tail(rows)
        .map(|e| {
            let style = theme.level(e.level);
            Line::from(vec![
                Span::styled(format_time(e.time), theme.label()),
                Span::raw(" "),
                Span::styled(e.level.tag(), style),
                Span::raw(" "),
                Span::styled(e.text.clone(), style),
            ])
        })
        .collect()
}
