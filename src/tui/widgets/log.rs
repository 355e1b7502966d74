//! The log pane: newest lines at the bottom, coloured by level; paged back, filtered by
//! level or text, and a line too long for the pane ends in `…`.

use crate::app::App;
use crate::app::log::{Entry, format_time};
use crate::data::Level;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

/// The pane's title: what it shows when that is not simply everything, newest last.
pub fn title(app: &App) -> String {
    let view = &app.view().log;
    let mut parts = vec!["Log".to_string()];
    match view.min_level {
        Some(Level::Error) => parts.push("errors only".into()),
        Some(_) => parts.push("warnings+".into()),
        None => {}
    }
    if let Some(text) = &view.search {
        parts.push(format!("/{text}"));
    }
    if view.back > 0 {
        parts.push(format!("{} newer below (PgDn)", view.back));
    }
    format!(" {} ", parts.join(" · "))
}

/// The `rows` lines the pane shows, each at most `width` columns.
pub fn lines(app: &App, theme: Theme, rows: usize, width: usize) -> Vec<Line<'static>> {
    let view = &app.view().log;
    let shown: Vec<&Entry> = app.log_book().iter().filter(|e| view.shows(e)).collect();
    let end = shown.len().saturating_sub(view.back);
    let start = end.saturating_sub(rows);
    shown[start..end]
        .iter()
        .map(|e| line(e, theme, width))
        .collect()
}

fn line(e: &Entry, theme: Theme, width: usize) -> Line<'static> {
    let style = theme.level(e.level);
    let head = format!("{} {} ", format_time(e.time), e.level.tag());
    let mut text = e.text.clone();
    if e.repeats > 1 {
        text.push_str(&format!("  ×{}", e.repeats));
    }
    let room = width.saturating_sub(head.chars().count());
    Line::from(vec![
        Span::styled(format_time(e.time), theme.label()),
        Span::raw(" "),
        Span::styled(e.level.tag(), style),
        Span::raw(" "),
        Span::styled(fit(&text, room), style),
    ])
}

/// `text` as it fits in `room` columns: cut with `…` as its last column when too long.
pub fn fit(text: &str, room: usize) -> String {
    if text.chars().count() <= room {
        return text.to_string();
    }
    let mut out: String = text.chars().take(room.saturating_sub(1)).collect();
    if room > 0 {
        out.push('…');
    }
    out
}
