//! The log pane: newest lines at the bottom, coloured by level; paged back, filtered by
//! level or text; a line too long for the pane wraps under its text.

use super::text::wrap_rows;
use crate::app::App;
use crate::app::log::{Entry, format_time};
use crate::app::view::SourceFilter;
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
    match view.source {
        SourceFilter::Navdeck => parts.push("navdeck".into()),
        SourceFilter::Robot => parts.push("robot".into()),
        SourceFilter::All => {}
    }
    if let Some(text) = &view.search {
        parts.push(format!("/{text}"));
    }
    if view.back > 0 {
        parts.push(format!("{} newer below (PgDn)", view.back));
    }
    format!(" {} ", parts.join(" · "))
}

/// Rows one entry may take; the rest of a longer one is cut with `…` (the session's log
/// file has it whole).
const MAX_ROWS: usize = 3;

/// The `rows` lines the pane shows, each at most `width` columns: the newest entries,
/// each wrapped under its text, and the end of the one before when only part fits.
pub fn lines(app: &App, theme: Theme, rows: usize, width: usize) -> Vec<Line<'static>> {
    let view = &app.view().log;
    let shown: Vec<&Entry> = app.log_book().iter().filter(|e| view.shows(e)).collect();
    let end = shown.len().saturating_sub(view.back);
    let mut out: Vec<Line<'static>> = Vec::new();
    for e in shown[..end].iter().rev() {
        let mut entry = entry_lines(e, theme, width);
        let room = rows - out.len();
        if entry.len() > room {
            entry.drain(..entry.len() - room);
        }
        out.splice(0..0, entry);
        if out.len() == rows {
            break;
        }
    }
    out
}

/// One entry: time and level, then its text wrapped in the columns left, at most
/// `MAX_ROWS` rows.
fn entry_lines(e: &Entry, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let style = theme.level(e.level);
    let time = format_time(e.time);
    let head = time.chars().count() + e.level.tag().chars().count() + 2;
    let mut text = e.sourced_text();
    if e.repeats > 1 {
        text.push_str(&format!("  ×{}", e.repeats));
    }
    let room = width.saturating_sub(head).max(1);
    let parts = wrap_rows(&text, room, MAX_ROWS);
    let mut lines = Vec::new();
    for (k, part) in parts.into_iter().enumerate() {
        lines.push(if k == 0 {
            Line::from(vec![
                Span::styled(time.clone(), theme.label()),
                Span::raw(" "),
                Span::styled(e.level.tag(), style),
                Span::raw(" "),
                Span::styled(part, style),
            ])
        } else {
            Line::from(vec![Span::raw(" ".repeat(head)), Span::styled(part, style)])
        });
    }
    lines
}
