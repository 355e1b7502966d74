//! What the filter believes, drawn over the map: landmark estimates with their 95 %
//! ellipses and the robot's position ellipse. ASCII outlines use `+`; braille sets dots.

use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::perception::markers::MarkerCategory;
use crate::slam::ellipse::{CHI2_2DOF_95, axes, outline};
use crate::tui::theme::{Theme, marker_glyph};
use nalgebra::Matrix2;
use ratatui::buffer::Buffer;
use ratatui::style::{Modifier, Style};

/// Unicode braille bit of dot (column 0-1, row 0-3), rows top to bottom.
const BITS: [[u32; 4]; 2] = [[0x01, 0x02, 0x04, 0x40], [0x08, 0x10, 0x20, 0x80]];

pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let braille = app.view().braille;
    let slam = app.pilot().slam();
    // A delivered block's markers are drawn where it was put down, not where the filter
    // last saw them (the mission ignores them once picked up).
    let place = |id: u32| app.delivered_at(id);
    for l in slam.landmarks().filter(|l| place(l.id).is_none()) {
        let style = theme.marker(MarkerCategory::of(l.id));
        draw_ellipse(l.mean, &l.covariance, vp, braille, style, buf);
    }
    for l in slam.landmarks() {
        if let Some(cell) = vp.cell(place(l.id).unwrap_or(l.mean)) {
            let category = MarkerCategory::of(l.id);
            buf[cell]
                .set_char(marker_glyph(category))
                .set_style(theme.marker(category).add_modifier(Modifier::BOLD));
        }
    }
    // The pose the robot decides with (MCL's when it runs) and its covariance.
    let position = app.pilot().estimated_pose().position();
    let cov = app
        .pilot()
        .pose_covariance()
        .fixed_view::<2, 2>(0, 0)
        .into_owned();
    draw_ellipse(position, &cov, vp, braille, theme.robot(), buf);
}

/// The 95 % outline of `cov` around `center`, when it is larger than one cell.
pub fn draw_ellipse(
    center: Point2,
    cov: &Matrix2<f64>,
    vp: &Viewport,
    braille: bool,
    style: Style,
    buf: &mut Buffer,
) {
    let (major, _, _) = axes(cov, CHI2_2DOF_95);
    let step = if braille { vp.scale / 2.0 } else { vp.scale };
    if !(major.is_finite() && major > step) {
        return;
    }
    // Enough points that neighbours are under a dot apart; capped for huge ellipses.
    let n = ((std::f64::consts::TAU * major / (0.5 * step)) as usize).clamp(12, 720);
    for p in outline(center, cov, CHI2_2DOF_95, n) {
        if braille {
            set_dot(p, vp, style, buf);
        } else if let Some(cell) = vp.cell(p) {
            buf[cell].set_char('+').set_style(style);
        }
    }
}

/// Sets the braille dot under `p`, keeping the dots already in its cell.
pub(super) fn set_dot(p: Point2, vp: &Viewport, style: Style, buf: &mut Buffer) {
    let Some(cell) = vp.cell(p) else { return };
    let col = ((p.x - vp.left) / (vp.scale / 2.0)).floor() as i64;
    let row = ((vp.top - p.y) / (vp.scale / 2.0)).floor() as i64;
    let bit = BITS[(col.rem_euclid(2)) as usize][(row.rem_euclid(4)) as usize];
    let existing = buf[cell]
        .symbol()
        .chars()
        .next()
        .map(u32::from)
        .filter(|c| (0x2800..=0x28ff).contains(c))
        .map_or(0, |c| c - 0x2800);
    if let Some(ch) = char::from_u32(0x2800 + (existing | bit)) {
        buf[cell].set_char(ch).set_style(style);
    }
}

/// Keeps the truth glyphs apart from the beliefs: used by the map to dim truth markers.
pub fn truth_style(style: Style) -> Style {
    style
        .remove_modifier(Modifier::BOLD)
        .add_modifier(Modifier::DIM)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;

    #[test]
    fn ascii_outline_surrounds_the_centre() {
        let vp = Viewport::new(Rect::new(0, 0, 40, 20), Point2::new(0.0, 0.0), 0.05);
        let mut buf = Buffer::empty(Rect::new(0, 0, 40, 20));
        let cov = Matrix2::new(0.04, 0.0, 0.0, 0.04);
        draw_ellipse(
            Point2::new(0.0, 0.0),
            &cov,
            &vp,
            false,
            Style::new(),
            &mut buf,
        );
        let centre = vp.cell(Point2::new(0.0, 0.0)).unwrap();
        assert_eq!(buf[centre].symbol(), " ");
        // 95 % radius sqrt(5.991 * 0.04) = 0.49 m: about 9.8 columns to the right.
        let right = vp.cell(Point2::new(0.489, 0.0)).unwrap();
        assert_eq!(buf[right].symbol(), "+");
    }

    #[test]
    fn braille_dots_accumulate_in_a_cell() {
        let vp = Viewport::new(Rect::new(0, 0, 10, 10), Point2::new(0.0, 0.0), 0.1);
        let mut buf = Buffer::empty(Rect::new(0, 0, 10, 10));
        let cell_origin = Point2::new(vp.left + 0.01, vp.top - 0.01);
        set_dot(cell_origin, &vp, Style::new(), &mut buf);
        set_dot(
            Point2::new(cell_origin.x + 0.05, cell_origin.y),
            &vp,
            Style::new(),
            &mut buf,
        );
        assert_eq!(buf[(0, 0)].symbol(), "\u{2809}");
    }
}
