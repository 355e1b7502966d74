//! Opening a ROSArduinoBridge port: the settings the worker runs with, and the first
//! exchange (the firmware answering `b` through an Arduino's reset, then `m 0 0`).

use super::config::SerialConfig;
use super::protocol::Request;
use super::transport::{Counters, TransactError, Transport};
use super::wheels::WheelGeometry;
use std::time::{Duration, Instant};

pub type SerialTransport = Transport<Box<dyn serialport::SerialPort>>;

/// Everything the worker needs to know about the port and the robot.
#[derive(Clone, Debug)]
pub struct Settings {
    pub path: String,
    pub baud: u32,
    pub serial: SerialConfig,
    pub geometry: WheelGeometry,
    /// Fastest believable rim speed, m/s, for rejecting encoder jumps.
    pub max_wheel_speed: f64,
}

impl Settings {
    pub(super) fn reply_timeout(&self) -> Duration {
        Duration::from_secs_f64(self.serial.reply_timeout)
    }
}

/// Opens the port (8N1, no flow control) and waits for the firmware to answer `b`; then
/// stops the motors, which also resets the firmware's PID.
pub fn open(settings: &Settings, counters: &Counters) -> Result<SerialTransport, String> {
    let port = serialport::new(settings.path.as_str(), settings.baud)
        .data_bits(serialport::DataBits::Eight)
        .parity(serialport::Parity::None)
        .stop_bits(serialport::StopBits::One)
        .flow_control(serialport::FlowControl::None)
        .timeout(settings.reply_timeout())
        .open()
        .map_err(|e| e.to_string())?;
    let mut transport = Transport::new(port);
    // An Arduino resets when the port opens: its bootloader's noise is not counted.
    let boot = Counters::default();
    let deadline = Instant::now() + Duration::from_secs_f64(settings.serial.boot_wait);
    loop {
        match transport.transact(Request::Baud, settings.reply_timeout(), 0, &boot) {
            Ok(_) => break,
            Err(TransactError::Io(e)) => return Err(e.to_string()),
            Err(_) if Instant::now() >= deadline => {
                return Err(format!(
                    "no answer to `b` within {} s: is ROSArduinoBridge running at {} baud?",
                    settings.serial.boot_wait, settings.baud
                ));
            }
            Err(_) => {}
        }
    }
    let retries = settings.serial.retries;
    match transport.transact(
        Request::Motors(0, 0),
        settings.reply_timeout(),
        retries,
        counters,
    ) {
        Ok(_) => Ok(transport),
        Err(TransactError::Refused(_)) => {
            Err("the firmware refuses `m`: build ROSArduinoBridge with USE_BASE".into())
        }
        Err(e) => Err(e.to_string()),
    }
}
