//! Composes one frame from the panels; reads the app, never changes it.

use super::theme::Theme;
use super::widgets::{arm_view, camera, help, landmarks, log, map, status, text, title};
use crate::app::App;
use crate::app::screen::{Area, MIN_SIZE, layout};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph};

/// Columns and rows inside the status panel's border.
fn status_inner((_, _, w, h): Area) -> (usize, usize) {
    (
        usize::from(w.saturating_sub(2)),
        usize::from(h.saturating_sub(2)),
    )
}

fn rect((x, y, w, h): Area) -> Rect {
    Rect::new(x, y, w, h)
}

pub fn draw(frame: &mut Frame, app: &App, theme: Theme) {
    draw_in(frame, frame.area(), app, theme);
}

/// The console in `size`, a part of the frame from its top-left corner (a replay keeps
/// the bottom row for its time bar).
pub fn draw_in(frame: &mut Frame, size: Rect, app: &App, theme: Theme) {
    if size.width < MIN_SIZE.0 || size.height < MIN_SIZE.1 {
        let text = format!(
            "terminal too small (need {}x{}, this one is {}x{}): make it larger, or q quits.",
            MIN_SIZE.0, MIN_SIZE.1, size.width, size.height
        );
        frame.render_widget(Paragraph::new(text).wrap(Default::default()), size);
        return;
    }
    let parts = layout((size.width, size.height));
    frame.render_widget(Paragraph::new(title::line(app, theme)), rect(parts.title));

    let map_block = Block::bordered()
        .title(map_title(app))
        .border_style(theme.border());
    let map_rect = rect(parts.map);
    let inner = map_block.inner(map_rect);
    frame.render_widget(map_block, map_rect);
    map::render(app, theme, inner, frame.buffer_mut());
    if let Some(text) = app.prompt()
        && inner.height > 0
    {
        let bar = Rect::new(inner.x, inner.y + inner.height - 1, inner.width, 1);
        frame.render_widget(Clear, bar);
        let line = match text.strip_prefix('/') {
            Some(_) => format!("{text}█  (enter shows the log lines containing it, esc cancels)"),
            None => format!(":{text}█  (enter runs, esc cancels)"),
        };
        frame.render_widget(Paragraph::new(line).style(theme.value()), bar);
    }

    let (status_w, status_h) = status_inner(parts.status);
    let status_block = Block::bordered()
        .title(" Status ")
        .border_style(theme.border());
    frame.render_widget(
        Paragraph::new(status::lines(app, theme, status_w, status_h)).block(status_block),
        rect(parts.status),
    );

    let log_rect = rect(parts.log);
    let log_block = Block::bordered()
        .title(log::title(app))
        .border_style(theme.border());
    let rows = usize::from(log_rect.height.saturating_sub(2));
    let width = usize::from(log_rect.width.saturating_sub(2));
    frame.render_widget(
        Paragraph::new(log::lines(app, theme, rows, width)).block(log_block),
        log_rect,
    );

    // Panels over the map sit inside its border, which stays whole.
    if app.view().landmarks {
        draw_landmarks(frame, app, theme, inner);
    }
    let lane_mode = app.pilot().mode() == crate::app::mode::Mode::Lane;
    if lane_mode && app.view().camera != crate::app::view::CameraPanel::Off {
        draw_lane(frame, app, theme, inner);
    } else if app.view().camera != crate::app::view::CameraPanel::Off {
        draw_camera(frame, app, theme, inner);
    }
    if app.pilot().mode() == crate::app::mode::Mode::Route {
        draw_route(frame, app, theme, inner);
    }
    if app.pilot().mode() == crate::app::mode::Mode::Gripper && app.pilot().arm().is_some() {
        draw_arm(frame, app, theme, inner);
    }
    if let Some((entries, selected)) = app.map_picker() {
        draw_picker(
            frame,
            entries,
            selected,
            app.picker_listing(),
            app.picker_confirming(),
            theme,
            map_rect,
        );
    }
    if app.view().help {
        draw_help(frame, app, theme, size);
    }
}

/// Load mode's list of saved maps over the map panel.
fn draw_picker(
    frame: &mut Frame,
    entries: &[crate::app::loading::MapEntry],
    selected: usize,
    listing: bool,
    confirming: bool,
    theme: Theme,
    map: Rect,
) {
    let area = Rect::new(
        map.x + 2.min(map.width),
        map.y + 1.min(map.height),
        map.width.saturating_sub(4),
        map.height.saturating_sub(2),
    );
    // Columns as wide as the longest name (within reason) and the largest map.
    let name_w =
        (entries.iter().map(|e| e.name.chars().count()).max()).map_or(16, |n| n.clamp(8, 28));
    let mut lines: Vec<Line> = entries
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let name = text::fit(&e.name, name_w);
            let text = match &e.summary {
                Ok((w, h, n, created)) => {
                    format!("{name:<name_w$} {w:>5.1} x {h:>5.1} m  {n:>3} landmarks  {created}")
                }
                Err(why) => format!("{name:<name_w$} unreadable: {why}"),
            };
            let style = if i == selected {
                theme.mode()
            } else {
                theme.value()
            };
            Line::styled(text, style)
        })
        .collect();
    if lines.is_empty() {
        let text = if listing {
            "listing the maps folder…"
        } else {
            "no saved maps here yet (S saves one)"
        };
        lines.push(Line::styled(text, theme.label()));
    }
    let title = if confirming {
        " It does not fit (see the log): enter loads it anyway, esc keeps the map "
    } else {
        " Load a map: up/down, enter loads, u undoes a load, esc leaves "
    };
    let block = Block::bordered().title(title).border_style(theme.border());
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}

/// The landmark table in the lower right of the map.
fn draw_landmarks(frame: &mut Frame, app: &App, theme: Theme, map: Rect) {
    let width = 48.min(map.width);
    let height = (map.height / 2).max(5).min(map.height);
    let area = Rect::new(
        map.x + map.width - width,
        map.y + map.height - height,
        width,
        height,
    );
    let rows = usize::from(height.saturating_sub(2));
    let listed = app.listed_landmarks();
    let title = text::fit(
        &landmarks::title(app, &listed),
        usize::from(width.saturating_sub(2)),
    );
    let block = Block::bordered().title(title).border_style(theme.border());
    frame.render_widget(Clear, area);
    frame.render_widget(
        Paragraph::new(landmarks::lines(app, &listed, theme, rows)).block(block),
        area,
    );
}

/// Gripper mode's side view of the arm in the map's top-right corner.
fn draw_arm(frame: &mut Frame, app: &App, theme: Theme, map: Rect) {
    let width = 36.min(map.width);
    let height = 20.min(map.height);
    let area = Rect::new(map.x + map.width - width, map.y, width, height);
    let block = Block::bordered()
        .title(" Arm (h) ")
        .border_style(theme.border());
    let inner = block.inner(area);
    frame.render_widget(Clear, area);
    let text = arm_view::lines(app, theme, usize::from(inner.width));
    let text_rows = (text.len() as u16).min(inner.height);
    frame.render_widget(Paragraph::new(text).block(block), area);
    let drawing = Rect::new(
        inner.x,
        inner.y + text_rows,
        inner.width,
        inner.height - text_rows,
    );
    arm_view::drawing(app, theme, drawing, frame.buffer_mut());
}

/// The camera panel in the map's top-left corner: 32 columns of thumbnail (16:9).
fn draw_camera(frame: &mut Frame, app: &App, theme: Theme, map: Rect) {
    let width = 34.min(map.width);
    let thumb = app
        .camera()
        .status
        .as_ref()
        .and_then(|s| s.thumbnail.as_ref());
    // No picture, no room kept for one.
    let thumb_rows = if thumb.is_some() { 9 } else { 0 };
    let text = camera::lines(app, theme, usize::from(width.saturating_sub(2)));
    let height = (text.len() as u16 + thumb_rows + 2).min(map.height);
    let area = Rect::new(map.x, map.y, width, height);
    let block = Block::bordered()
        .title(" Camera (v) ")
        .border_style(theme.border());
    let inner = block.inner(area);
    let text_rows = (text.len() as u16).min(inner.height);
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(text).block(block), area);
    let thumb_area = Rect::new(
        inner.x,
        inner.y + text_rows,
        inner.width,
        inner.height - text_rows,
    );
    if let Some(thumb) = thumb {
        camera::thumbnail(
            thumb,
            app.view().camera,
            theme,
            thumb_area,
            frame.buffer_mut(),
        );
    }
}

/// Lane mode's panel over the map's top left, in the camera panel's place (`v`).
fn draw_lane(frame: &mut Frame, app: &App, theme: Theme, map: Rect) {
    let width = 36.min(map.width);
    let thumb = app.pilot().lane().last().and_then(|s| s.thumbnail.as_ref());
    let thumb_rows = if thumb.is_some() { 9 } else { 0 };
    let text = super::widgets::lane::lines(app, theme);
    let height = (text.len() as u16 + thumb_rows + 2).min(map.height);
    let area = Rect::new(map.x, map.y, width, height);
    let block = Block::bordered()
        .title(" Lane (v) ")
        .border_style(theme.border());
    let inner = block.inner(area);
    let text_rows = (text.len() as u16).min(inner.height);
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(text).block(block), area);
    if let Some(thumb) = thumb {
        let thumb_area = Rect::new(
            inner.x,
            inner.y + text_rows,
            inner.width,
            inner.height - text_rows,
        );
        super::widgets::lane::thumbnail(thumb, theme, thumb_area, frame.buffer_mut());
    }
}

/// Route mode's panel in the map's top-right corner: the run, then the list to choose
/// from.
fn draw_route(frame: &mut Frame, app: &App, theme: Theme, map: Rect) {
    let width = (map.width / 2).clamp(30, 44).min(map.width);
    let height = (map.height * 2 / 5).max(7).min(map.height);
    let area = Rect::new(map.x + map.width - width, map.y, width, height);
    let inner_w = usize::from(width.saturating_sub(2));
    let rows = usize::from(height.saturating_sub(2));
    let title = text::fit(super::widgets::tag_route::TITLE, inner_w);
    let block = Block::bordered().title(title).border_style(theme.border());
    let lines = super::widgets::tag_route::lines(app, theme, inner_w, rows);
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}

fn map_title(app: &App) -> String {
    let style = if app.view().braille {
        "braille"
    } else {
        "ascii"
    };
    let scale = app.view().scale(app.fitted_scale());
    format!(" Map {:.0} cm/col {style} ", scale * 100.0)
}

/// The help popup over the whole screen: bindings in as many columns as fit, how driving
/// works and the map's legend underneath.
fn draw_help(frame: &mut Frame, app: &App, theme: Theme, size: Rect) {
    let entries = help::entries(app, theme);
    let width = size.width.min(100);
    let inner_w = usize::from(width.saturating_sub(2));
    let mut notes = text::wrap(&help::driving(app), inner_w);
    notes.extend(text::wrap(help::LEGEND, inner_w));
    let col_w = help::ENTRY_WIDTH + 1;
    let columns = (inner_w / col_w).max(1);
    // The keys take what the borders, a blank line and the notes leave.
    let room = usize::from(size.height.saturating_sub(3))
        .saturating_sub(notes.len())
        .max(4);
    let rows = entries.len().div_ceil(columns).clamp(1, room);
    let mut lines: Vec<Line> = Vec::new();
    for r in 0..rows {
        let mut spans = Vec::new();
        for c in 0..columns {
            if let Some(entry) = entries.get(c * rows + r) {
                let text_len: usize = entry.spans.iter().map(|s| s.content.chars().count()).sum();
                spans.extend(entry.spans.iter().cloned());
                if c + 1 < columns {
                    spans.push(" ".repeat(col_w.saturating_sub(text_len)).into());
                }
            }
        }
        lines.push(Line::from(spans));
    }
    if entries.len() > rows * columns {
        lines.push(Line::from(format!(
            "... {} more: widen the terminal",
            entries.len() - rows * columns
        )));
    } else {
        lines.push(Line::default());
    }
    lines.extend(notes.into_iter().map(|n| Line::styled(n, theme.label())));
    // As tall as what it holds, centred; the whole screen when that is more.
    let height = (lines.len() as u16 + 2).min(size.height);
    let area = super::widgets::centred(size, width, height);
    let block = Block::bordered()
        .title(format!(
            " Keys in {} mode ({}): any key closes ",
            app.pilot().mode().label().to_lowercase(),
            app.keymap().source()
        ))
        .border_style(theme.border());
    frame.render_widget(Clear, area);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
