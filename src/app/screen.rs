//! The screen's layout as plain arithmetic, shared by the renderer and the map scale.
//! Rectangles are (x, y, width, height) in terminal cells.

pub type Area = (u16, u16, u16, u16);

/// Smallest terminal the console draws into; smaller ones get a notice. At 60 x 16 the
/// map keeps 10 rows and the status panel its first rows under it.
pub const MIN_SIZE: (u16, u16) = (60, 16);
/// Below this width the status panel moves under the map.
pub const WIDE: u16 = 70;
/// Width of the status panel beside the map: 32 columns, growing with the terminal to
/// three tenths of it (56 at most), so long states and targets fit on wide screens.
pub fn status_width(width: u16) -> u16 {
    (width * 3 / 10).clamp(32, 56).min(width / 2)
}

/// Where each part of the screen goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    pub title: Area,
    pub map: Area,
    pub status: Area,
    pub log: Area,
}

/// Splits a `width` x `height` terminal: title line, map with the status panel at its
/// right (or below it when narrow), log at the bottom.
pub fn layout((width, height): (u16, u16)) -> Layout {
    let log_h = if height >= 36 {
        10
    } else {
        (height / 4).max(4)
    };
    let body_y = 1;
    let body_h = height.saturating_sub(1 + log_h);
    let log = (0, body_y + body_h, width, log_h);
    let title = (0, 0, width, 1);
    if width >= WIDE {
        let status_w = status_width(width);
        Layout {
            title,
            map: (0, body_y, width - status_w, body_h),
            status: (width - status_w, body_y, status_w, body_h),
            log,
        }
    } else {
        let status_h = 6.min(body_h / 2);
        Layout {
            title,
            map: (0, body_y, width, body_h - status_h),
            status: (0, body_y + body_h - status_h, width, status_h),
            log,
        }
    }
}

/// The map's area inside its border.
pub fn map_area(screen: (u16, u16)) -> Area {
    let (x, y, w, h) = layout(screen).map;
    (x + 1, y + 1, w.saturating_sub(2), h.saturating_sub(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_tile_the_screen_at_80x24() {
        let l = layout((80, 24));
        assert_eq!(l.title, (0, 0, 80, 1));
        assert_eq!(l.map.2 + l.status.2, 80);
        assert_eq!(l.map.1 + l.map.3, l.log.1);
        assert_eq!(l.log.1 + l.log.3, 24);
    }

    #[test]
    fn the_status_panel_grows_with_the_terminal() {
        assert_eq!(layout((80, 24)).status.2, 32);
        assert_eq!(layout((120, 40)).status.2, 36);
        assert_eq!(layout((200, 60)).status.2, 56);
    }

    #[test]
    fn narrow_screen_stacks_status_under_map() {
        let l = layout((50, 24));
        assert_eq!(l.map.2, 50);
        assert_eq!(l.status.1, l.map.1 + l.map.3);
    }
}
