//! What the robot perceives: marker ID conventions now, camera detection later.

pub mod markers;
