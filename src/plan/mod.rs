//! Planning on the costmap: A*, path post-processing and the velocity profile.

pub mod trajectory;
