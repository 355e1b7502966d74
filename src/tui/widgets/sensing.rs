//! What the robot senses now and where it has been, over the map: the newest lidar scan's
//! hits (`'`, toggled with L), the driven trail (`·`, toggled with T) and, zoomed in far
//! enough that it spans a few columns, the robot's footprint (`%`).

use super::beliefs::set_dot;
use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::Style;

/// The footprint is outlined once its radius spans this many columns.
const FOOTPRINT_COLUMNS: f64 = 2.0;

/// The trail and the scan, under the path and the robot.
pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let braille = app.view().braille;
    if app.view().trail {
        for &p in app.pilot().trail() {
            mark(p, '·', vp, braille, theme.trail(), buf);
        }
    }
    if app.view().scan
        && let Some((pose, scan)) = app.pilot().newest_scan()
    {
        for p in scan.hits(pose) {
            if braille {
                set_dot(p, vp, theme.scan(), buf);
            } else if let Some(cell) = vp.cell(p) {
                // Over the map only: a wall the scan hits keeps its glyph, in the scan's
                // colour; markers and blocks stay as they are.
                let cell = &mut buf[cell];
                match cell.symbol() {
                    "#" => {
                        cell.set_style(theme.scan());
                    }
                    " " | "." | ":" | "·" => {
                        cell.set_char('\'').set_style(theme.scan());
                    }
                    _ => {}
                }
            }
        }
    }
}

/// The robot's footprint, when zoomed in far enough to show it.
pub fn footprint(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let radius = app.pilot().settings().robot.footprint_radius;
    if radius < FOOTPRINT_COLUMNS * vp.scale {
        return;
    }
    let braille = app.view().braille;
    let centre = app.pilot().estimated_pose().position();
    let step = if braille { vp.scale / 2.0 } else { vp.scale };
    // Points under a dot apart round the circle.
    let n = ((std::f64::consts::TAU * radius / (0.5 * step)) as usize).clamp(12, 720);
    for k in 0..n {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        let p = Point2::new(centre.x + radius * a.cos(), centre.y + radius * a.sin());
        if braille {
            set_dot(p, vp, theme.robot(), buf);
        } else if let Some(cell) = vp.cell(p) {
            // Over everything but walls: how close the robot comes to them is the point.
            let cell = &mut buf[cell];
            if cell.symbol() != "#" {
                cell.set_char('%').set_style(theme.robot());
            }
        }
    }
}

/// `glyph` at `p` on a cell that shows nothing but free space, or a braille dot there.
fn mark(p: Point2, glyph: char, vp: &Viewport, braille: bool, style: Style, buf: &mut Buffer) {
    if braille {
        set_dot(p, vp, style, buf);
    } else if let Some(cell) = vp.cell(p) {
        let cell = &mut buf[cell];
        if matches!(cell.symbol(), " " | "." | "·") {
            cell.set_char(glyph).set_style(style);
        }
    }
}
