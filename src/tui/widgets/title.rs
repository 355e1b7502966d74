//! The top line: name, mode, link, the recording mark and the way to help.

use crate::app::{App, LinkStatus};
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

pub fn line(app: &App, theme: Theme) -> Line<'static> {
    let mut spans = vec![
        Span::styled(" navdeck ", theme.title()),
        Span::styled(format!(" {} ", app.pilot().mode().label()), theme.mode()),
        Span::raw(" "),
        Span::styled(app.link().label(), theme.value()),
    ];
    match app.pilot().link_status() {
        // Nothing was ever linked: nothing is lost yet, the robot is awaited.
        LinkStatus::Lost(_) if !app.pilot().link_ever_up() => {
            spans.push(Span::raw(" "));
            spans.push(Span::styled(" NO LINK: waiting for robot ", theme.alert()));
        }
        LinkStatus::Lost(_) => {
            spans.push(Span::raw(" "));
            spans.push(Span::styled(" LINK LOST ", theme.alert()));
        }
        LinkStatus::Back => {
            spans.push(Span::raw(" "));
            spans.push(Span::styled(" LINK BACK: press a key ", theme.alert()));
        }
        LinkStatus::Ok => {}
    }
    if app.pilot().estop() {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(" E-STOP ", theme.alert()));
    }
    if let Some((bytes, elapsed)) = app.recording_progress() {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(
            format!("● REC {} {}", size_text(bytes), elapsed_text(elapsed)),
            theme.alert(),
        ));
    }
    let quit = super::help::quit_keys(app);
    spans.push(Span::styled(
        format!("  ? help  {quit} quit"),
        theme.label(),
    ));
    Line::from(spans)
}

/// A file's size as `ls -h` and Foxglove show it: bytes, kB or MB (powers of 1000).
pub fn size_text(bytes: u64) -> String {
    let b = bytes as f64;
    if b < 1e3 {
        format!("{bytes} B")
    } else if b < 1e6 {
        format!("{:.1} kB", b / 1e3)
    } else if b < 1e9 {
        format!("{:.1} MB", b / 1e6)
    } else {
        format!("{:.1} GB", b / 1e9)
    }
}

/// How long something has run, as m:ss (h:mm:ss past an hour).
pub fn elapsed_text(seconds: f64) -> String {
    let s = seconds.max(0.0).floor() as u64;
    if s >= 3600 {
        format!("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60)
    } else {
        format!("{}:{:02}", s / 60, s % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_in_decimal_units() {
        assert_eq!(size_text(512), "512 B");
        assert_eq!(size_text(1_234_567), "1.2 MB");
        assert_eq!(size_text(45_600), "45.6 kB");
    }

    #[test]
    fn elapsed_reads_minutes_and_seconds_then_hours() {
        assert_eq!(elapsed_text(42.9), "0:42");
        assert_eq!(elapsed_text(3725.0), "1:02:05");
    }
}
