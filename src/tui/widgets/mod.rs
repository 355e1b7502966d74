//! The console's panels, each a read-only view of the `App`.

pub mod help;
pub mod log;
pub mod map;
pub mod status;
pub mod title;
