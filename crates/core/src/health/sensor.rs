//! The sensors whose health is watched.

use serde::Serialize;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sensor {
    Odometry,
    Lidar,
    Camera,
    Arm,
}

impl Sensor {
    pub const ALL: [Sensor; 4] = [Sensor::Odometry, Sensor::Lidar, Sensor::Camera, Sensor::Arm];

    pub fn name(self) -> &'static str {
        match self {
            Sensor::Odometry => "odometry",
            Sensor::Lidar => "lidar",
            Sensor::Camera => "camera",
            Sensor::Arm => "arm",
        }
    }

    pub(super) fn index(self) -> usize {
        self as usize
    }
}

impl fmt::Display for Sensor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
