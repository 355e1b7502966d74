//! Labelled rows fitted to a panel: a value too long for one line wraps between words
//! over as many lines as its row may take, and when the panel is too short the rows a
//! user needs least go first, so the ones they need most (mode, link, pose, mission)
//! stay at any size.

use super::text::{fit, wrap_rows};
use crate::tui::theme::Theme;
use ratatui::style::Style;
use ratatui::text::{Line, Span};

/// Columns a row's label takes.
pub const LABEL: usize = 8;

/// How much a user needs a row: the least needed go first when the panel is short.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Need {
    /// Kept at every size: what mode, whether linked, where the robot is, what it does.
    Must,
    High,
    Some,
    Low,
}

/// One labelled row: its value wraps over at most `lines` lines.
pub struct Row {
    pub label: &'static str,
    pub value: String,
    pub lines: usize,
    pub need: Need,
    /// Shown highlighted: a notable event, flashed.
    pub flash: bool,
}

impl Row {
    pub fn new(label: &'static str, value: impl Into<String>, need: Need) -> Self {
        Self {
            label,
            value: value.into(),
            lines: 1,
            need,
            flash: false,
        }
    }

    /// The row, its value highlighted.
    pub fn flashing(mut self) -> Self {
        self.flash = true;
        self
    }

    /// The row, its value wrapped over up to `lines` lines.
    pub fn wrapping(mut self, lines: usize) -> Self {
        self.lines = lines.max(1);
        self
    }

    /// The value's lines in `room` columns, at most `limit`: as it is when it fits (its
    /// own spacing kept), else broken between words, the last line cut with `…`.
    fn parts(&self, room: usize, limit: usize) -> Vec<String> {
        if self.value.chars().count() <= room {
            if self.value.is_empty() {
                return Vec::new();
            }
            return vec![self.value.clone()];
        }
        if limit <= 1 {
            return vec![fit(&self.value, room)];
        }
        wrap_rows(&self.value, room, limit)
    }
}

/// `rows` as lines of at most `width` columns, at most `height` of them: rows dropped
/// least needed first (the lowest of equals first), then the kept rows' wrapping undone
/// from the bottom up, until they fit.
pub fn fit_rows(rows: Vec<Row>, theme: Theme, width: usize, height: usize) -> Vec<Line<'static>> {
    let room = width.saturating_sub(LABEL);
    let mut limits: Vec<usize> = rows.iter().map(|r| r.lines).collect();
    let mut kept = vec![true; rows.len()];
    let total = |kept: &[bool], limits: &[usize]| -> usize {
        rows.iter()
            .enumerate()
            .filter(|(i, _)| kept[*i])
            .map(|(i, r)| r.parts(room, limits[i]).len())
            .sum()
    };
    for need in [Need::Low, Need::Some, Need::High] {
        for i in (0..rows.len()).rev() {
            if total(&kept, &limits) <= height {
                break;
            }
            if rows[i].need == need {
                kept[i] = false;
            }
        }
    }
    for i in (0..rows.len()).rev() {
        if total(&kept, &limits) <= height {
            break;
        }
        limits[i] = 1;
    }
    let mut lines = Vec::new();
    for (i, r) in rows.iter().enumerate().filter(|(i, _)| kept[*i]) {
        for (k, part) in r.parts(room, limits[i]).into_iter().enumerate() {
            let label = if k == 0 { r.label } else { "" };
            let style = if r.flash {
                theme.flash()
            } else {
                theme.value()
            };
            lines.push(line(theme, label, part, style, width));
        }
    }
    lines.truncate(height);
    lines
}

/// A label and its value, cut to `width` columns (a label wider than its column).
fn line(theme: Theme, label: &str, value: String, style: Style, width: usize) -> Line<'static> {
    let label = fit(&format!("{label:<LABEL$}"), width);
    let value = fit(&value, width.saturating_sub(label.chars().count()));
    Line::from(vec![
        Span::styled(label, theme.label()),
        Span::styled(value, style),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(lines: &[Line]) -> Vec<String> {
        lines
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect()
    }

    #[test]
    fn a_long_value_wraps_between_words_under_its_label() {
        let theme = Theme::from_env(None);
        let rows =
            vec![Row::new("Path", "1.40 m arrived at unseen boundary", Need::High).wrapping(2)];
        assert_eq!(
            text(&fit_rows(rows, theme, 30, 10)),
            vec!["Path    1.40 m arrived at", "        unseen boundary"]
        );
    }

    #[test]
    fn a_short_panel_keeps_the_rows_most_needed() {
        let theme = Theme::from_env(None);
        let rows = vec![
            Row::new("Mode", "MANUAL", Need::Must),
            Row::new("Loop", "10 Hz", Need::Low),
            Row::new("Link", "sim ok", Need::Must),
            Row::new("Speed", "v 0.15", Need::High),
            Row::new("Pose", "0 0 0", Need::Must),
        ];
        let shown = text(&fit_rows(rows, theme, 30, 4));
        let labels: Vec<&str> = shown.iter().map(|l| l.split(' ').next().unwrap()).collect();
        assert_eq!(labels, vec!["Mode", "Link", "Speed", "Pose"]);
    }

    #[test]
    fn wrapping_is_undone_before_a_needed_row_is_lost() {
        let theme = Theme::from_env(None);
        let rows = vec![
            Row::new("Mission", "drive blue block 523 into blue gate", Need::Must).wrapping(2),
            Row::new("Pose", "0 0 0", Need::Must),
        ];
        let shown = text(&fit_rows(rows, theme, 24, 2));
        assert_eq!(shown.len(), 2);
        assert!(shown[0].ends_with('…'), "{shown:?}");
        assert!(shown[1].starts_with("Pose"), "{shown:?}");
    }
}
