//! The replay's help (`?`): its own keys and the view keys the re-run takes, over the
//! screen; any key closes it.

use crate::tui::theme::Theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

/// The replay's keys, as (keys, what they do).
pub const KEYS: [(&str, &str); 12] = [
    ("space", "play or pause"),
    (", .", "step one control period back / forward"),
    ("← →", "5 s back / forward"),
    ("PgUp PgDn", "60 s back / forward"),
    ("[ ]", "slower / faster (0.1x to 50x)"),
    ("1 … 9", "jump to 10 … 90 %"),
    ("Home End", "the start, the end"),
    (":", "go to a time (seconds or m:ss)"),
    ("r", "as recorded or re-run view"),
    ("+ - 0 b g", "zoom, fit, braille, truth (re-run)"),
    ("L T f F", "scan, trail, log filter, source"),
    ("^N ^P", "a fleet: show the next / previous robot"),
];

/// Draws the help centred over `size`.
pub fn draw(frame: &mut Frame, size: Rect, theme: Theme) {
    let mut lines: Vec<Line> = KEYS
        .iter()
        .map(|(keys, what)| {
            Line::from(vec![
                Span::styled(format!("{keys:<10} "), theme.title()),
                Span::styled(*what, theme.value()),
            ])
        })
        .collect();
    lines.push(Line::styled("q or ctrl-c quits the replay", theme.label()));
    let width = size.width.min(52);
    let height = (lines.len() as u16 + 2).min(size.height);
    let area = crate::tui::widgets::centred(size, width, height);
    let block = Block::bordered()
        .title(" Replay keys: any key closes ")
        .border_style(theme.border());
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
