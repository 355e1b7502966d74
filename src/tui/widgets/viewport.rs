//! Where the map area sits in the world, shared by the map and what is drawn over it.

use crate::geometry::Point2;
use ratatui::layout::Rect;

/// Where the map area sits in the world: left edge, top edge, metres per column.
#[derive(Clone, Copy, Debug)]
pub struct Viewport {
    pub area: Rect,
    pub left: f64,
    pub top: f64,
    /// Metres per column; a row covers twice as much (terminal cells are about 1:2).
    pub scale: f64,
}

impl Viewport {
    pub fn new(area: Rect, center: Point2, scale: f64) -> Self {
        Self {
            area,
            left: center.x - f64::from(area.width) * scale / 2.0,
            top: center.y + f64::from(area.height) * scale,
            scale,
        }
    }

    /// The cell showing world point `p`, if it is on screen.
    pub fn cell(&self, p: Point2) -> Option<(u16, u16)> {
        let c = ((p.x - self.left) / self.scale).floor();
        let r = ((self.top - p.y) / (2.0 * self.scale)).floor();
        let (w, h) = (f64::from(self.area.width), f64::from(self.area.height));
        if c < 0.0 || r < 0.0 || c >= w || r >= h {
            return None;
        }
        Some((self.area.x + c as u16, self.area.y + r as u16))
    }
}
