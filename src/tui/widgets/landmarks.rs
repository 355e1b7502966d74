//! The landmark table: what the filter holds, one row per landmark.

use crate::app::App;
use crate::perception::markers::MarkerCategory;
use crate::tui::theme::Theme;
use ratatui::text::Line;

/// Header and rows, sorted by ID; `rows` limits the count (the rest is summarised).
pub fn lines(app: &App, theme: Theme, rows: usize) -> Vec<Line<'static>> {
    let mut landmarks: Vec<_> = app.pilot().slam().landmarks().collect();
    landmarks.sort_by_key(|l| l.id);
    let mut out = vec![Line::styled(
        "  ID category      x      y    σx    σy   seen",
        theme.title(),
    )];
    let shown = rows.saturating_sub(1);
    for l in landmarks.iter().take(if landmarks.len() > shown {
        shown.saturating_sub(1)
    } else {
        shown
    }) {
        out.push(Line::styled(
            format!(
                "{:>4} {:<10} {:6.2} {:6.2} {:5.3} {:5.3} {:6}",
                l.id,
                MarkerCategory::of(l.id).label(),
                l.mean.x,
                l.mean.y,
                l.covariance[(0, 0)].max(0.0).sqrt(),
                l.covariance[(1, 1)].max(0.0).sqrt(),
                l.sightings
            ),
            theme.value(),
        ));
    }
    if landmarks.len() > shown {
        out.push(Line::styled(
            format!("  ... {} more", landmarks.len() - (shown.saturating_sub(1))),
            theme.label(),
        ));
    }
    if landmarks.is_empty() {
        out.push(Line::styled("  no landmarks yet", theme.label()));
    }
    out
}
