//! The `[serial]` config section: a ROSArduinoBridge robot's encoders, PID rate, timing,
//! gripper servo and arm servos. Wheel radius and track come from `[robot]`.

use navdeck_core::data::check::{Invalid, all_non_negative, all_positive};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SerialConfig {
    /// Baud rate when the link is given as `serial:PATH` without `@BAUD` (the firmware's 57600).
    pub baud: u32,
    /// Encoder counts per wheel revolution, as the firmware counts them (both edges of both
    /// channels for ARDUINO_ENC_COUNTER): motor counts x gear ratio.
    pub counts_per_rev: f64,
    /// The firmware's PID loop rate, frames per second (ROSArduinoBridge PID_RATE: 30).
    pub pid_rate_hz: f64,
    /// How often the encoders are read (`e`), per second.
    pub poll_hz: f64,
    /// An unchanged motor command is sent again after this many seconds (the firmware stops
    /// the motors 2 s after the last one).
    pub refresh: f64,
    /// The robot is stopped when the console sent no command for this many seconds.
    pub command_timeout: f64,
    /// Seconds to wait for a reply before asking again.
    pub reply_timeout: f64,
    /// How many times an unanswered or refused request is asked again.
    pub retries: u32,
    /// Seconds after opening the port within which the firmware must answer (an Arduino
    /// resets when the port opens and its bootloader waits about a second).
    pub boot_wait: f64,
    /// Seconds between attempts to reopen a port that went away.
    pub reconnect_every: f64,
    /// Servo index of the gripper (`s IDX DEG`); none: the robot has no gripper.
    pub gripper_servo: Option<u8>,
    /// Servo angles of the open and the closed gripper, degrees.
    pub gripper_open_deg: f64,
    pub gripper_close_deg: f64,
    /// Seconds the gripper servo may take to reach its angle before it is reported as
    /// commanded anyway.
    pub gripper_timeout: f64,
    /// The servos of a four-joint arm, base first; empty: the robot has no arm.
    pub arm_servos: Vec<ArmServo>,
}

/// One arm joint's hobby servo: `s index DEG` with DEG = zero_deg + direction x the
/// joint's angle in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmServo {
    /// The servo's index in the firmware (0..=15).
    pub index: i64,
    /// The servo angle at which the joint is at zero, degrees (0..=180).
    pub zero_deg: f64,
    /// 1 if the servo's angle grows with the joint's, -1 if it is mounted the other way.
    pub direction: i64,
}

/// `arm_servos[k].index`, `.zero_deg` and `.direction`, for refusals (a field name is static).
const SERVO_FIELDS: [[&str; 3]; 4] = [
    [
        "arm_servos[0].index",
        "arm_servos[0].zero_deg",
        "arm_servos[0].direction",
    ],
    [
        "arm_servos[1].index",
        "arm_servos[1].zero_deg",
        "arm_servos[1].direction",
    ],
    [
        "arm_servos[2].index",
        "arm_servos[2].zero_deg",
        "arm_servos[2].direction",
    ],
    [
        "arm_servos[3].index",
        "arm_servos[3].zero_deg",
        "arm_servos[3].direction",
    ],
];

impl Default for SerialConfig {
    fn default() -> Self {
        Self {
            baud: 57600,
            counts_per_rev: 3436.0,
            pid_rate_hz: 30.0,
            poll_hz: 20.0,
            refresh: 0.5,
            command_timeout: 0.5,
            reply_timeout: 0.25,
            retries: 3,
            boot_wait: 3.0,
            reconnect_every: 1.0,
            gripper_servo: None,
            gripper_open_deg: 90.0,
            gripper_close_deg: 20.0,
            gripper_timeout: 3.0,
            arm_servos: Vec::new(),
        }
    }
}

impl SerialConfig {
    /// The first bad field (name within `[serial]`), its value and why.
    pub fn validate(&self) -> Result<(), Invalid> {
        navdeck_core::data::check::within(&[
            ("counts_per_rev", self.counts_per_rev, 1.0, 1.0e6),
            ("pid_rate_hz", self.pid_rate_hz, 1.0, 1000.0),
            ("poll_hz", self.poll_hz, 1.0, 1000.0),
        ])?;
        navdeck_core::data::check::counts_within(&[(
            "baud",
            u64::from(self.baud),
            300,
            4_000_000,
        )])?;
        all_positive(&[
            ("refresh", self.refresh),
            ("command_timeout", self.command_timeout),
            ("reply_timeout", self.reply_timeout),
            ("boot_wait", self.boot_wait),
            ("reconnect_every", self.reconnect_every),
            ("gripper_timeout", self.gripper_timeout),
        ])?;
        all_non_negative(&[
            ("gripper_open_deg", self.gripper_open_deg),
            ("gripper_close_deg", self.gripper_close_deg),
        ])?;
        for (field, seconds) in [
            ("command_timeout", self.command_timeout),
            ("reply_timeout", self.reply_timeout),
            ("boot_wait", self.boot_wait),
            ("reconnect_every", self.reconnect_every),
            ("gripper_timeout", self.gripper_timeout),
        ] {
            if seconds > 60.0 {
                return Err((field, seconds, "must be at most 60 s".into()));
            }
        }
        if self.poll_hz < 1.0 {
            return Err((
                "poll_hz",
                self.poll_hz,
                "must be at least 1 per second".into(),
            ));
        }
        // The firmware stops the motors 2 s after the last command: refresh well inside that.
        if self.refresh > 1.5 {
            return Err(("refresh", self.refresh, "must be at most 1.5 s".into()));
        }
        for (field, deg) in [
            ("gripper_open_deg", self.gripper_open_deg),
            ("gripper_close_deg", self.gripper_close_deg),
        ] {
            if deg > 180.0 {
                return Err((field, deg, "must lie in 0..=180 degrees".into()));
            }
        }
        if self.retries > 20 {
            return Err((
                "retries",
                f64::from(self.retries),
                "must be at most 20".into(),
            ));
        }
        self.check_arm_servos()
    }

    /// None, or four servos: each index 0..=15 and used once (not by the gripper either),
    /// zero within the servo's 0..=180 degrees, direction 1 or -1.
    fn check_arm_servos(&self) -> Result<(), Invalid> {
        let servos = &self.arm_servos;
        if !servos.is_empty() && servos.len() != 4 {
            return Err((
                "arm_servos",
                servos.len() as f64,
                "must list 4 servos, base first, or none (the value is how many it lists)".into(),
            ));
        }
        for (k, s) in servos.iter().enumerate() {
            let [index, zero, direction] = SERVO_FIELDS[k];
            if !(0..=15).contains(&s.index) {
                return Err((index, s.index as f64, "must lie in 0..=15".into()));
            }
            let taken = servos[..k].iter().any(|o| o.index == s.index)
                || self.gripper_servo.map(i64::from) == Some(s.index);
            if taken {
                return Err((
                    index,
                    s.index as f64,
                    "is already used by another arm joint or the gripper".into(),
                ));
            }
            if !(0.0..=180.0).contains(&s.zero_deg) {
                return Err((zero, s.zero_deg, "must lie in 0..=180 degrees".into()));
            }
            if s.direction != 1 && s.direction != -1 {
                return Err((direction, s.direction as f64, "must be 1 or -1".into()));
            }
        }
        Ok(())
    }
}
