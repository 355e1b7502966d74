//! The data that crosses a robot link, below every other module: commands out, sensor
//! frames in, the level of a log line, the robot's geometry and limits, and the range
//! checks every config section validates with. The core,
//! the links and the console all speak it; it imports nothing of navdeck but geometry.

pub mod arm;
pub mod camera;
pub mod check;
pub mod command;
pub mod files;
pub mod frame_check;
pub mod lane;
pub mod level;
pub mod number;
pub mod printable;
pub mod replace;
pub mod robot;
pub mod sensors;
pub mod tag_check;
pub mod tags;

pub use arm::{ArmState, ArmTarget};
pub use camera::{CameraStatus, Thumbnail};
pub use command::{Command, GripperCommand};
pub use lane::{BarrierSeen, BarrierState, ColourThumbnail, LaneSighting, LightColour, LightSeen};
pub use level::Level;
pub use sensors::{GripperState, LaserScan, MarkerSighting, SensorFrame, WheelTravel};
pub use tags::TagSighting;
