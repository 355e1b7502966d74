//! The digital twin: a simulated differential-drive robot in a simulated arena.
//!
//! * `World` — walls, obstacles, markers, gates and blocks from a TOML world file
//!   (`maps/arena.toml` documents the format), checked on load, rasterisable, and written
//!   back with `World::to_toml`.
//! * `generate` — worlds made from a seed (rooms, boxes, corridors or a loop), checked for reach.
//! * `Twin` — the robot: speed/acceleration-limited diff drive, encoders with noise and
//!   slip, a marker camera, a lidar, a gripper that carries blocks, and collisions.
//! * `fault`, `faults` — faults injected into the twin on simulated time (`--fault`,
//!   `:fault`): a dark camera, a silent lidar or odometry, an arm not answering, slip.
//!
//! Nothing here reads a clock or touches a terminal: time passes only through
//! `Twin::step(dt)`, and all randomness comes from one generator seeded in `Twin::new`,
//! so the same seed and the same calls give bit-identical results.

pub mod arm;
mod blocks;
mod build;
mod camera;
mod camera_frames;
mod checks;
mod clock;
mod collision;
pub mod config;
mod drive;
mod encoders;
mod error;
pub mod fault;
pub mod faults;
pub mod fleet;
#[cfg(feature = "vision")]
mod frame_noise;
pub mod generate;
mod gripper;
#[cfg(feature = "vision")]
pub mod lane_camera;
mod lidar;
pub mod nav2_world;
pub mod noise_bank;
mod raster;
#[cfg(feature = "vision")]
mod readable;
#[cfg(feature = "vision")]
mod render;
#[cfg(feature = "vision")]
pub mod rendered_camera;
#[cfg(feature = "vision")]
pub mod rendered_tag_camera;
pub mod shapes;
#[cfg(feature = "vision")]
mod sheet_paint;
pub mod tag_camera;
pub mod tag_render;
pub mod track;
pub mod track_render;
mod truth;
mod twin;
mod world;
mod world_file;
mod world_toml;

pub use blocks::BlockState;
pub use camera::clear_line as line_of_sight;
pub use camera_frames::CameraFrames;
pub use error::WorldError;
pub use fault::{FaultKind, FaultSpec, FaultSpecError};
pub use faults::{FaultNote, FaultRecord, Faults, Scheduled};
pub use truth::{GroundTruth, collision_note};
pub use twin::{Neighbour, Twin};
pub use world::{Block, BlockColor, Gate, Marker, Obstacle, World};
pub use world_file::{DEFAULT_BLOCK_SIZE, DEFAULT_GATE_WIDTH};
