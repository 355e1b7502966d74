//! The console on a recording (`navdeck replay`): the re-run's screen or the view as
//! recorded, with a time bar along the bottom; the loop that plays it.

pub mod bar;
pub mod help;
pub mod played;
pub mod recorded;
pub mod run;

use crate::app::screen::{Area, MIN_SIZE, layout};
use crate::replay::playback::{Playback, View};
use crate::tui::theme::Theme;
use played::Played;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Rows the time bar takes at the bottom.
pub const BAR_ROWS: u16 = 1;

fn rect((x, y, w, h): Area) -> Rect {
    Rect::new(x, y, w, h)
}

/// One frame of the replay.
pub fn draw(frame: &mut Frame, replay: &impl Played, playback: &Playback, theme: Theme) {
    let size = frame.area();
    let body = Rect::new(0, 0, size.width, size.height.saturating_sub(BAR_ROWS));
    if size.width < MIN_SIZE.0 || body.height < MIN_SIZE.1 {
        let text = format!(
            "terminal too small for a replay (need {}x{}): make it larger, or q quits.",
            MIN_SIZE.0,
            MIN_SIZE.1 + BAR_ROWS
        );
        frame.render_widget(Paragraph::new(text).wrap(Default::default()), size);
        return;
    }
    match playback.view {
        View::Rerun => {
            replay.draw_rerun(frame, body, theme);
            // The re-run's header says it is a replay too, as the recorded view's does.
            let mut title = crate::tui::widgets::title::line(replay.app(), theme);
            title
                .spans
                .insert(1, Span::styled(" REPLAY · re-run ", theme.mode()));
            frame.render_widget(ratatui::widgets::Clear, Rect::new(0, 0, body.width, 1));
            frame.render_widget(Paragraph::new(title), Rect::new(0, 0, body.width, 1));
        }
        View::AsRecorded => draw_as_recorded(frame, body, replay, playback.position(), theme),
    }
    let bar_area = Rect::new(0, body.height, size.width, BAR_ROWS);
    frame.render_widget(
        Paragraph::new(bar::line(playback, theme, usize::from(size.width))),
        bar_area,
    );
    if playback.help {
        help::draw(frame, body, theme);
    }
}

fn draw_as_recorded(frame: &mut Frame, body: Rect, replay: &impl Played, t: f64, theme: Theme) {
    let parts = layout((body.width, body.height));
    let recorded = replay.recorded();
    let app = replay.app();
    let title = Line::from(vec![
        Span::styled(" navdeck ", theme.title()),
        Span::styled(" REPLAY · as recorded ", theme.mode()),
        Span::raw(" "),
        Span::styled(app.link().label(), theme.value()),
        Span::styled("  r re-run view  q quit", theme.label()),
    ]);
    frame.render_widget(Paragraph::new(title), rect(parts.title));
    let map_block = Block::bordered()
        .title(" Map (recorded) ")
        .border_style(theme.border());
    let map_rect = rect(parts.map);
    let inner = map_block.inner(map_rect);
    frame.render_widget(map_block, map_rect);
    recorded::map(app, recorded, t, theme, inner, frame.buffer_mut());
    let status_rect = rect(parts.status);
    let width = usize::from(status_rect.width.saturating_sub(2));
    frame.render_widget(
        Paragraph::new(recorded::status(recorded, t, theme, width)).block(
            Block::bordered()
                .title(" Status (recorded) ")
                .border_style(theme.border()),
        ),
        status_rect,
    );
    let log_rect = rect(parts.log);
    let rows = usize::from(log_rect.height.saturating_sub(2));
    let width = usize::from(log_rect.width.saturating_sub(2));
    frame.render_widget(
        Paragraph::new(recorded::log(recorded, t, theme, rows, width)).block(
            Block::bordered()
                .title(" Log (recorded /rosout) ")
                .border_style(theme.border()),
        ),
        log_rect,
    );
}
