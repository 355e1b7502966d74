//! The landmark table: what the filter holds, one row per landmark (ID, category, mean,
//! the larger standard deviation, sightings), gates and blocks first; a chosen row to
//! plan to, scrolled into view.

use crate::app::App;
use crate::perception::markers::MarkerCategory;
use crate::slam::ekf::LandmarkEstimate;
use crate::tui::theme::Theme;
use ratatui::text::Line;

/// The table's title: what it lists (`landmarks`, as `App::listed_landmarks` gives them)
/// and how to use it.
pub fn title(app: &App, landmarks: &[LandmarkEstimate]) -> String {
    let listed = landmarks.len();
    let what = if app.view().table.targets_only {
        "gates+blocks"
    } else {
        "all"
    };
    let at = if listed == 0 {
        0
    } else {
        app.view().table.selected.min(listed - 1) + 1
    };
    format!(" Landmarks {at}/{listed} {what} · ↑↓ enter · tab ")
}

/// Header and `rows` rows of `landmarks` at most, the chosen one highlighted and in view.
pub fn lines(
    app: &App,
    landmarks: &[LandmarkEstimate],
    theme: Theme,
    rows: usize,
) -> Vec<Line<'static>> {
    let mut out = vec![Line::styled(
        "  ID category      x      y     σ  seen",
        theme.title(),
    )];
    if landmarks.is_empty() {
        out.push(Line::styled("  no landmarks yet", theme.label()));
        return out;
    }
    let shown = rows.saturating_sub(1).max(1);
    let selected = app.view().table.selected.min(landmarks.len() - 1);
    // The window of rows that keeps the chosen one in view.
    let first = selected
        .saturating_sub(shown - 1)
        .min(landmarks.len().saturating_sub(shown));
    for (i, l) in landmarks.iter().enumerate().skip(first).take(shown) {
        let style = if i == selected {
            theme.cursor()
        } else {
            theme.value()
        };
        if let Some(at) = app.delivered_at(l.id) {
            // A delivered block's marker is where the block was put down.
            out.push(Line::styled(
                format!(
                    "{:>4} {:<10} {:6.2} {:6.2} delivered",
                    l.id,
                    MarkerCategory::of(l.id).label(),
                    at.x,
                    at.y
                ),
                style,
            ));
            continue;
        }
        out.push(Line::styled(
            format!(
                "{:>4} {:<10} {:6.2} {:6.2} {:5.3} {:>5}",
                l.id,
                MarkerCategory::of(l.id).label(),
                l.mean.x,
                l.mean.y,
                // The larger of the two standard deviations: one column fits 80 columns.
                l.covariance[(0, 0)]
                    .max(l.covariance[(1, 1)])
                    .max(0.0)
                    .sqrt(),
                l.sightings
            ),
            style,
        ));
    }
    out
}
