//! The `[serial]` config section: a ROSArduinoBridge robot's encoders, PID rate, timing and
//! gripper servo. Wheel radius and track come from `[robot]`.

use crate::data::check::{Invalid, all_non_negative, all_positive};
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
}

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
        }
    }
}

impl SerialConfig {
    /// The first bad field (name within `[serial]`), its value and why.
    pub fn validate(&self) -> Result<(), Invalid> {
        crate::data::check::within(&[
            ("counts_per_rev", self.counts_per_rev, 1.0, 1.0e6),
            ("pid_rate_hz", self.pid_rate_hz, 1.0, 1000.0),
            ("poll_hz", self.poll_hz, 1.0, 1000.0),
        ])?;
        crate::data::check::counts_within(&[("baud", u64::from(self.baud), 300, 4_000_000)])?;
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
        Ok(())
    }
}
