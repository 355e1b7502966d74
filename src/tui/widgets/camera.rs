//! The camera panel: frame rate, detection latency, the IDs in view, and a thumbnail of
//! the newest frame in half blocks (two pixels a cell) or braille (eight dots a cell).

use crate::app::App;
use crate::app::view::CameraPanel;
use crate::perception::frame::Thumbnail;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Line;

/// Text rows above the thumbnail.
pub const TEXT_ROWS: u16 = 2;

/// The panel's text, `width` columns at most: rate and latency, then the IDs.
pub fn lines(app: &App, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let feed = app.camera();
    let fitted = |text: String, style| Line::styled(super::text::fit(&text, width), style);
    let Some(status) = &feed.status else {
        return vec![
            fitted("no camera frames".into(), theme.label()),
            fitted("(--sim-camera or --camera SRC)".into(), theme.label()),
        ];
    };
    let latency = status
        .latency
        .map_or("-".to_string(), |s| format!("{:.1} ms", s * 1000.0));
    let ids = if status.ids.is_empty() {
        "none".to_string()
    } else {
        status
            .ids
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(" ")
    };
    let refused = if status.rejected > 0 {
        format!(" ({} refused)", status.rejected)
    } else {
        String::new()
    };
    let first = match &status.error {
        Some(e) => format!("{:.1} Hz  error: {e}", feed.rate),
        None => format!("{:.1} Hz  detect {latency}", feed.rate),
    };
    vec![
        fitted(first, theme.value()),
        fitted(format!("IDs {ids}{refused}"), theme.value()),
    ]
}

/// Draws the thumbnail into `area`, scaled to fill it.
pub fn thumbnail(
    thumb: &Thumbnail,
    style: CameraPanel,
    theme: Theme,
    area: Rect,
    buf: &mut Buffer,
) {
    if thumb.width == 0 || thumb.height == 0 {
        return;
    }
    let (cols, rows) = (usize::from(area.width), usize::from(area.height));
    let (dots_x, dots_y) = match style {
        CameraPanel::Braille => (2, 4),
        _ => (1, 2),
    };
    let (px_w, px_h) = (cols * dots_x, rows * dots_y);
    // Nearest-neighbour sampling of the thumbnail at the panel's resolution.
    let sample = |x: usize, y: usize| {
        thumb.at(
            x * thumb.width / px_w.max(1),
            y * thumb.height / px_h.max(1),
        )
    };
    let mean = thumb.pixels.iter().map(|&p| u32::from(p)).sum::<u32>() / thumb.pixels.len() as u32;
    for row in 0..rows {
        for col in 0..cols {
            let cell = &mut buf[(area.x + col as u16, area.y + row as u16)];
            match style {
                CameraPanel::Braille => {
                    // Braille dot bits by (column, row) in the 2x4 cell (Unicode's layout).
                    const BITS: [[u32; 4]; 2] =
                        [[0x01, 0x02, 0x04, 0x40], [0x08, 0x10, 0x20, 0x80]];
                    let mut bits = 0;
                    for (dx, column) in BITS.iter().enumerate() {
                        for (dy, bit) in column.iter().enumerate() {
                            // Dark pixels are ink: markers are black on white.
                            if u32::from(sample(col * 2 + dx, row * 4 + dy)) < mean {
                                bits |= bit;
                            }
                        }
                    }
                    cell.set_char(char::from_u32(0x2800 + bits).unwrap_or(' '));
                    cell.set_style(theme.value());
                }
                _ => {
                    let (top, bottom) = (sample(col, row * 2), sample(col, row * 2 + 1));
                    if theme.color {
                        cell.set_char('▀');
                        cell.set_style(
                            Style::new()
                                .fg(Color::Rgb(top, top, top))
                                .bg(Color::Rgb(bottom, bottom, bottom)),
                        );
                    } else {
                        const SHADES: [char; 5] = [' ', '░', '▒', '▓', '█'];
                        let level = (u16::from(top) + u16::from(bottom)) / 2;
                        cell.set_char(SHADES[usize::from(level) * 5 / 256]);
                    }
                }
            }
        }
    }
}
