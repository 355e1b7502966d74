//! The camera panel: frame rate, detection latency, the IDs in view, and a thumbnail of
//! the newest frame in half blocks (two pixels a cell) or braille (eight dots a cell).

use super::text::wrap_rows;
use crate::app::App;
use crate::app::view::CameraPanel;
use crate::perception::frame::Thumbnail;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Line;

/// The panel's text in `width` columns: rate and latency, then the IDs in view, wrapped
/// over as many rows as they take (three at most).
pub fn lines(app: &App, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let feed = app.camera();
    let wrapped = |text: String, rows: usize, style| -> Vec<Line<'static>> {
        // A text that fits keeps its own spacing ("10.0 Hz  detect").
        let parts = if text.chars().count() <= width {
            vec![text]
        } else {
            wrap_rows(&text, width, rows)
        };
        parts.into_iter().map(|l| Line::styled(l, style)).collect()
    };
    let Some(status) = &feed.status else {
        // Sightings may come without images: the twin's marker sensor gives them.
        let source = if app.link().ground_truth().is_some() {
            "markers in view come from the twin's marker sensor, not a camera"
        } else {
            "markers in view come from the link, not a camera"
        };
        let mut out = wrapped("no camera images".into(), 1, theme.label());
        out.extend(wrapped(source.into(), 3, theme.label()));
        out.extend(wrapped(
            "(--sim-camera or --camera SRC shows them)".into(),
            2,
            theme.label(),
        ));
        return out;
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
    let mut out = wrapped(first, 2, theme.value());
    out.extend(wrapped(format!("IDs {ids}{refused}"), 3, theme.value()));
    out
}

/// Levels apart the darkest and lightest pixels must be for the picture to have ink.
const MIN_CONTRAST: u8 = 12;

/// The darkest and lightest levels of `pixels`, ignoring the extreme 1 % at each end so a
/// stray pixel does not decide the stretch.
fn levels(pixels: &[u8]) -> (u8, u8) {
    let mut counts = [0usize; 256];
    for &p in pixels {
        counts[usize::from(p)] += 1;
    }
    let cut = pixels.len() / 100;
    let level_at = |from_top: bool| {
        let mut seen = 0;
        let order: Box<dyn Iterator<Item = usize>> = if from_top {
            Box::new((0..256).rev())
        } else {
            Box::new(0..256)
        };
        for level in order {
            seen += counts[level];
            if seen > cut {
                return level as u8;
            }
        }
        0
    };
    (level_at(false), level_at(true))
}

/// The middle grey level of `pixels`: the background a few markers stand on.
fn median(pixels: &[u8]) -> u8 {
    let mut sorted = pixels.to_vec();
    sorted.sort_unstable();
    sorted.get(sorted.len() / 2).copied().unwrap_or(0)
}

/// The pixel of `thumb` under dot (x, y) of a `dots`-sized grid that differs most from
/// `background` (max-deviation pooling, so no detail smaller than a dot is lost).
fn standout(thumb: &Thumbnail, background: u8, (x, y): (usize, usize), dots: (usize, usize)) -> u8 {
    let span = |d: usize, dots: usize, size: usize| {
        let start = d * size / dots.max(1);
        start..((d + 1) * size / dots.max(1)).max(start + 1)
    };
    let mut best = thumb.at(
        span(x, dots.0, thumb.width).start,
        span(y, dots.1, thumb.height).start,
    );
    for ty in span(y, dots.1, thumb.height) {
        for tx in span(x, dots.0, thumb.width) {
            let p = thumb.at(tx, ty);
            if p.abs_diff(background) > best.abs_diff(background) {
                best = p;
            }
        }
    }
    best
}

/// `p` with the levels `lo..=hi` stretched over 0..=255 (a flat picture stays as it is).
fn stretch(p: u8, lo: u8, hi: u8) -> u8 {
    if hi.saturating_sub(lo) < MIN_CONTRAST {
        return p;
    }
    // Linear contrast stretch: (p - lo) * 255 / (hi - lo), clamped.
    let v = (i32::from(p) - i32::from(lo)) * 255 / (i32::from(hi) - i32::from(lo));
    v.clamp(0, 255) as u8
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
    let (lo, hi) = levels(&thumb.pixels);
    let background = median(&thumb.pixels);
    // Each dot shows the thumbnail pixel of its box that stands out most from the
    // background (a marker a pixel wide would fall between nearest-neighbour samples),
    // its levels stretched to the full range (an image viewer's "auto levels"): a marker a
    // few levels darker than the floor shows as black on white.
    let sample = |x: usize, y: usize| {
        let p = standout(thumb, background, (x, y), (px_w, px_h));
        stretch(p, lo, hi)
    };
    // Braille ink is what is clearly darker than the background: the marker's black cells.
    let ink_below = stretch(background, lo, hi) / 2;
    // A picture with (almost) no contrast has no ink: stretching it would draw its noise.
    let flat = hi.saturating_sub(lo) < MIN_CONTRAST;
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
                            if !flat && sample(col * 2 + dx, row * 4 + dy) < ink_below {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_faint_marker_is_stretched_to_black_on_white() {
        let mut pixels = vec![140u8; 400];
        pixels[..40].fill(110);
        let (lo, hi) = levels(&pixels);
        assert_eq!((lo, hi), (110, 140));
        assert_eq!(stretch(110, lo, hi), 0);
        assert_eq!(stretch(140, lo, hi), 255);
    }

    #[test]
    fn a_marker_smaller_than_a_dot_still_shows() {
        // A 96 x 54 floor with one dark pixel, drawn 32 x 18: nearest-neighbour sampling
        // (every third pixel) would skip it.
        let mut pixels = vec![140u8; 96 * 54];
        pixels[20 * 96 + 40] = 30;
        let thumb = Thumbnail {
            width: 96,
            height: 54,
            pixels,
        };
        assert_eq!(standout(&thumb, 140, (13, 6), (32, 18)), 30);
        assert_eq!(standout(&thumb, 140, (12, 6), (32, 18)), 140);
    }

    #[test]
    fn a_flat_picture_is_left_as_it_is() {
        let mut pixels = vec![139u8; 400];
        pixels[..200].fill(140);
        let (lo, hi) = levels(&pixels);
        assert_eq!(stretch(139, lo, hi), 139);
    }
}
