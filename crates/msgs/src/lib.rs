//! The message vocabulary navdeck shares between its links and its recordings: the
//! ROS 2 messages it speaks (`ros`, `arm_msgs`), how what navdeck believes is drawn in
//! them (`picture`; route mode's tag graph in `tag_graph_markers`), and navdeck's own
//! recorded types (`record`).

pub mod arm_msgs;
pub mod picture;
pub mod record;
pub mod ros;
pub mod tag_graph_markers;
