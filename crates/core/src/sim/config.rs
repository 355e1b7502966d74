//! `[sim]`: the digital twin's physics and sensors.

use serde::{Deserialize, Serialize};

/// The digital twin's sensors and physics.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimConfig {
    pub physics: PhysicsConfig,
    pub encoders: EncoderConfig,
    pub camera: CameraConfig,
    pub lidar: LidarConfig,
    pub gripper: GripperConfig,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhysicsConfig {
    /// Integration step of the twin, seconds.
    pub step: f64,
}

impl Default for PhysicsConfig {
    fn default() -> Self {
        Self { step: 0.01 }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EncoderConfig {
    /// Counts per wheel revolution (an EV3 motor reports degrees: 360).
    pub ticks_per_rev: u32,
    /// Multiplicative noise on each wheel's travel, as a standard deviation (0.02 = 2 %).
    pub noise_std: f64,
    /// Probability per physics step that a wheel slips and loses `slip_fraction` of its travel.
    pub slip_probability: f64,
    pub slip_fraction: f64,
}

impl Default for EncoderConfig {
    fn default() -> Self {
        Self {
            ticks_per_rev: 360,
            noise_std: 0.02,
            slip_probability: 0.001,
            slip_fraction: 0.5,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraConfig {
    /// Horizontal field of view in degrees: 2 atan(432 / 635.93) from seed 001's intrinsics at 864 px.
    pub fov_deg: f64,
    pub min_range: f64,
    pub max_range: f64,
    /// A marker seen further than this from face-on is not detected, degrees.
    pub max_view_angle_deg: f64,
    pub rate_hz: f64,
    /// Range noise, metres (seed 001 `dist_std`: 0.1).
    pub dist_std: f64,
    /// Bearing noise, degrees (seed 001 `angle_std`: 4).
    pub angle_std_deg: f64,
    /// Probability that a visible marker is missed in a frame.
    pub miss_probability: f64,
}

impl Default for CameraConfig {
    fn default() -> Self {
        Self {
            fov_deg: 68.4,
            min_range: 0.1,
            max_range: 3.0,
            max_view_angle_deg: 75.0,
            rate_hz: 10.0,
            dist_std: 0.1,
            angle_std_deg: 4.0,
            miss_probability: 0.05,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LidarConfig {
    pub enabled: bool,
    /// Beams over a full turn (TurtleBot3's LDS-01: 360).
    pub beams: u32,
    pub min_range: f64,
    pub max_range: f64,
    pub rate_hz: f64,
    pub range_std: f64,
}

impl Default for LidarConfig {
    fn default() -> Self {
        Self {
            enabled: true,
            beams: 360,
            min_range: 0.12,
            max_range: 3.5,
            rate_hz: 5.0,
            range_std: 0.01,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GripperConfig {
    /// Time the jaws take to open or close, seconds (seed 001 waits 1 s).
    pub actuation_time: f64,
    /// The jaws' reach in front of the robot centre: a block whose centre lies within
    /// [near, far] ahead and `half_width` sideways is caught when they close.
    pub reach_near: f64,
    pub reach_far: f64,
    pub half_width: f64,
}

impl Default for GripperConfig {
    fn default() -> Self {
        Self {
            actuation_time: 1.0,
            reach_near: 0.06,
            reach_far: 0.14,
            half_width: 0.035,
        }
    }
}

impl SimConfig {
    /// Checks what the parser cannot; fields are named within `[sim]`.
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        use crate::data::check;
        let (camera, lidar, encoders) = (&self.camera, &self.lidar, &self.encoders);
        let gripper = &self.gripper;
        check::within(&[
            ("physics.step", self.physics.step, 0.0001, 0.1),
            ("camera.min_range", camera.min_range, 0.0, 100.0),
            ("camera.max_range", camera.max_range, 0.01, 100.0),
            (
                "camera.max_view_angle_deg",
                camera.max_view_angle_deg,
                0.0,
                90.0,
            ),
            ("camera.rate_hz", camera.rate_hz, 0.1, 60.0),
            ("camera.dist_std", camera.dist_std, 0.0, 10.0),
            ("camera.angle_std_deg", camera.angle_std_deg, 0.0, 90.0),
            ("encoders.noise_std", encoders.noise_std, 0.0, 1.0),
            ("lidar.min_range", lidar.min_range, 0.0, 100.0),
            ("lidar.max_range", lidar.max_range, 0.01, 100.0),
            ("lidar.rate_hz", lidar.rate_hz, 0.1, 30.0),
            ("lidar.range_std", lidar.range_std, 0.0, 1.0),
            ("gripper.actuation_time", gripper.actuation_time, 0.0, 60.0),
            ("gripper.reach_near", gripper.reach_near, 0.0, 1.0),
            ("gripper.reach_far", gripper.reach_far, 0.001, 1.0),
            ("gripper.half_width", gripper.half_width, 0.001, 0.5),
        ])?;
        for (near, far, a, b) in [
            (
                "camera.min_range",
                "camera.max_range",
                camera.min_range,
                camera.max_range,
            ),
            (
                "lidar.min_range",
                "lidar.max_range",
                lidar.min_range,
                lidar.max_range,
            ),
            (
                "gripper.reach_near",
                "gripper.reach_far",
                gripper.reach_near,
                gripper.reach_far,
            ),
        ] {
            if a >= b {
                return Err((near, a, format!("must be less than {far} ({b})").into()));
            }
        }
        check::counts_within(&[
            ("lidar.beams", u64::from(lidar.beams), 1, 2048),
            (
                "encoders.ticks_per_rev",
                u64::from(encoders.ticks_per_rev),
                1,
                1_000_000,
            ),
        ])?;
        check::all_probabilities(&[
            ("encoders.slip_probability", encoders.slip_probability),
            ("encoders.slip_fraction", encoders.slip_fraction),
            ("camera.miss_probability", camera.miss_probability),
        ])?;
        if !(camera.fov_deg > 0.0 && camera.fov_deg < 360.0) {
            return Err((
                "camera.fov_deg",
                camera.fov_deg,
                "must lie in (0, 360)".into(),
            ));
        }
        Ok(())
    }
}
