//! MCL's particle cloud over the map: a density shade per cell in ASCII (`░ ▒ ▓`, more
//! particles darker, scaled to the densest cell), a dot per particle in braille. Drawn
//! only over free or unknown space, so walls and markers stay readable.

use super::beliefs::set_dot;
use super::viewport::Viewport;
use crate::app::App;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use std::collections::HashMap;

/// Braille draws at most this many particles: beyond it the dots only fill the cloud in.
const MOST_DOTS: usize = 4000;

pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let Some(mcl) = app.pilot().mcl() else {
        return;
    };
    let particles = mcl.particles();
    let style = theme.particles();
    if app.view().braille {
        let stride = particles.len().div_ceil(MOST_DOTS).max(1);
        for p in particles.iter().step_by(stride) {
            set_dot(p.pose.position(), vp, style, buf);
        }
        return;
    }
    let mut counts: HashMap<(u16, u16), u32> = HashMap::new();
    for p in particles {
        if let Some(cell) = vp.cell(p.pose.position()) {
            *counts.entry(cell).or_default() += 1;
        }
    }
    let densest = counts.values().copied().max().unwrap_or(1);
    for (cell, n) in counts {
        let glyph = shade(n, densest);
        let cell = &mut buf[cell];
        if matches!(cell.symbol(), " " | "." | ":" | "·" | "'") {
            cell.set_char(glyph).set_style(style);
        }
    }
}

/// The shade for `n` particles in a cell when the densest holds `densest`.
pub fn shade(n: u32, densest: u32) -> char {
    let share = f64::from(n) / f64::from(densest.max(1));
    if share > 2.0 / 3.0 {
        '▓'
    } else if share > 1.0 / 3.0 {
        '▒'
    } else {
        '░'
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn denser_cells_are_darker() {
        assert_eq!(shade(1, 30), '░');
        assert_eq!(shade(15, 30), '▒');
        assert_eq!(shade(30, 30), '▓');
    }
}
