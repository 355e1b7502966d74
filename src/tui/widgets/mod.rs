//! The console's panels, each a read-only view of the `App`.

pub mod arm_view;
pub mod beliefs;
pub mod camera;
pub mod explore;
pub mod help;
pub mod landmarks;
pub mod log;
pub mod map;
pub mod particles;
pub mod path;
pub mod rows;
pub mod sensing;
pub mod status;
pub mod text;
pub mod title;
pub mod viewport;
