//! The top line: name, mode, link and the way to help.

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
    let quit = super::help::quit_keys(app);
    spans.push(Span::styled(
        format!("  ? help  {quit} quit"),
        theme.label(),
    ));
    Line::from(spans)
}
