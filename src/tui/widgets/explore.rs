//! Exploration over the map: every place the mission weighed going to next (frontiers of
//! unknown space, free space the camera has not looked at) as `?`, and the one it is
//! heading for as `!`.

use super::viewport::Viewport;
use crate::app::App;
use crate::pilot::mode::Mode;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;

pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let pilot = app.pilot();
    if pilot.mode() != Mode::Exploration {
        return;
    }
    let Some(mission) = pilot.mission() else {
        return;
    };
    let (candidates, heading) = mission.exploration_targets();
    for &p in candidates {
        if let Some(cell) = vp.cell(p) {
            buf[cell].set_char('?').set_style(theme.path());
        }
    }
    if let Some(cell) = heading.and_then(|p| vp.cell(p)) {
        buf[cell].set_char('!').set_style(theme.cursor());
    }
}
