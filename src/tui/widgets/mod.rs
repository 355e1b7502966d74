//! The console's panels, each a read-only view of the `App`.

pub mod arm_view;
pub mod beliefs;
pub mod camera;
pub mod explore;
pub mod filter_zones;
pub mod graph;
pub mod help;
pub mod landmarks;
pub mod lane;
pub mod log;
pub mod map;
pub mod particles;
pub mod path;
pub mod rows;
pub mod sensing;
pub mod status;
pub mod tag_graph;
pub mod tag_route;
pub mod text;
pub mod title;
pub mod viewport;
pub mod zones;

use ratatui::layout::Rect;

/// A `width` x `height` rectangle centred on `size` (both no larger than `size`): where
/// an overlay such as the help is drawn.
pub fn centred(size: Rect, width: u16, height: u16) -> Rect {
    let (width, height) = (width.min(size.width), height.min(size.height));
    Rect::new(
        size.x + (size.width - width) / 2,
        size.y + (size.height - height) / 2,
        width,
        height,
    )
}
