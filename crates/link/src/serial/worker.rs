//! The blocking task that owns the serial port (in the links' runtime's blocking pool).
//! It reads the encoders at the configured rate, turns the latest twist into motor
//! targets, refreshes them inside the firmware's 2 s auto-stop, stops the motors when the
//! console goes quiet, and reopens a port that went away (`open.rs`). It is the edge: it
//! reads the wall clock for its own timing.

use super::arm::ServoQueue;
pub use super::open::{SerialTransport, Settings, open};
use super::protocol::{Reply, Request};
use super::transport::{Counters, TransactError};
use super::wheels::{Dither, Odometer, Reading};
use crate::{GripperCommand, GripperState, WheelTravel};
use navdeck_core::geometry::Twist;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

/// How often a moving command's integer targets are re-derived (see `Dither`), seconds.
const DITHER_PERIOD: f64 = 0.1;
/// At most one summary of the fault counters per this many seconds.
const NOTE_EVERY: f64 = 2.0;
/// A servo within this many degrees of its target has arrived.
const SERVO_TOLERANCE: i64 = 2;

/// The console's wishes, latest first served.
pub enum ToWorker {
    Drive(Twist),
    Gripper(GripperCommand),
    /// Arm servo writes, (index, degrees), base joint first.
    Servos(Vec<(u8, u16)>),
    Stop,
    Shutdown,
}

/// What the worker tells the console.
pub enum FromWorker {
    Travel { wheels: WheelTravel, elapsed: f64 },
    Gripper(GripperState),
    Connected,
    Lost(String),
    Note(String),
}

/// How a connection ended.
enum End {
    Shutdown,
    Lost(String),
}

pub struct Worker {
    pub settings: Settings,
    pub rx: Receiver<ToWorker>,
    pub tx: Sender<FromWorker>,
    pub counters: Arc<Counters>,
    epoch: Instant,
    odometer: Odometer,
    noted: String,
    noted_at: f64,
    gripper_note: bool,
    servo_note: bool,
}

impl Worker {
    pub fn new(
        settings: Settings,
        rx: Receiver<ToWorker>,
        tx: Sender<FromWorker>,
        counters: Arc<Counters>,
    ) -> Self {
        let odometer = Odometer::new(settings.geometry, settings.max_wheel_speed);
        Self {
            settings,
            rx,
            tx,
            counters,
            epoch: Instant::now(),
            odometer,
            noted: String::new(),
            noted_at: f64::NEG_INFINITY,
            gripper_note: false,
            servo_note: false,
        }
    }

    /// Serves connections until the console shuts the link down.
    pub fn run(mut self, mut transport: SerialTransport) {
        loop {
            match self.serve(&mut transport) {
                End::Shutdown => return,
                End::Lost(reason) => {
                    let _ = transport.send_only(Request::Motors(0, 0));
                    self.say(FromWorker::Lost(format!(
                        "serial {}: {reason}; reconnecting every {} s",
                        self.settings.path, self.settings.serial.reconnect_every
                    )));
                }
            }
            drop(transport);
            match self.reconnect() {
                Some(t) => transport = t,
                None => return,
            }
        }
    }

    fn now(&self) -> f64 {
        self.epoch.elapsed().as_secs_f64()
    }

    fn say(&self, message: FromWorker) {
        // Lines for the log wake the console; the wheels' travel waits for its tick.
        let urgent = !matches!(message, FromWorker::Travel { .. });
        // The console may be gone already; then nobody is left to tell.
        if self.tx.send(message).is_ok() && urgent {
            crate::tasks::wake::notify();
        }
    }

    fn note(&mut self, text: String) {
        self.say(FromWorker::Note(format!("serial: {text}")));
    }

    /// Tries to reopen the port every `reconnect_every` seconds; `None` on shutdown.
    fn reconnect(&mut self) -> Option<SerialTransport> {
        let every = self.settings.serial.reconnect_every;
        loop {
            let attempt = self.now() + every;
            // Commands sent while the link is down are dropped: nothing stale survives.
            loop {
                let left = attempt - self.now();
                if left <= 0.0 {
                    break;
                }
                match self.rx.recv_timeout(Duration::from_secs_f64(left)) {
                    Ok(ToWorker::Shutdown) | Err(RecvTimeoutError::Disconnected) => return None,
                    Ok(_) | Err(RecvTimeoutError::Timeout) => {}
                }
            }
            if let Ok(t) = open(&self.settings, &self.counters) {
                Counters::bump(&self.counters.reconnects);
                self.odometer.rebase();
                self.say(FromWorker::Connected);
                return Some(t);
            }
        }
    }

    /// Drives one open connection until it fails or the console shuts down.
    fn serve(&mut self, t: &mut SerialTransport) -> End {
        let cfg = self.settings.serial.clone();
        let geometry = self.settings.geometry;
        let timeout = self.settings.reply_timeout();
        let horizon = DITHER_PERIOD * cfg.pid_rate_hz;
        let poll_period = 1.0 / cfg.poll_hz;
        let mut desired = Twist::ZERO;
        let mut ordered_at = self.now();
        // The targets last acknowledged, the twist they came from, and when.
        let mut sent = (0, 0);
        let mut basis = Twist::ZERO;
        let mut sent_at = self.now();
        let mut derived_at = f64::NEG_INFINITY;
        let mut dither = (Dither::default(), Dither::default());
        let mut next_poll = self.now();
        let mut last_reading: Option<f64> = None;
        let mut gripper_order: Option<GripperCommand> = None;
        let mut actuating: Option<(GripperCommand, f64)> = None;
        let mut servos = ServoQueue::default();
        if let Some(state) = self.initial_gripper(t) {
            self.say(FromWorker::Gripper(state));
        }
        loop {
            // Sleep until something is due or the console says something.
            let now = self.now();
            let moving = desired != Twist::ZERO;
            let mut due = next_poll.min(sent_at + cfg.refresh);
            if moving {
                due = due
                    .min(derived_at + DITHER_PERIOD)
                    .min(ordered_at + cfg.command_timeout);
            }
            if gripper_order.is_some() || !servos.is_empty() {
                due = now;
            }
            let first = if due > now {
                let wait = Duration::try_from_secs_f64(due - now).unwrap_or(Duration::MAX);
                match self.rx.recv_timeout(wait) {
                    Ok(m) => Some(m),
                    Err(RecvTimeoutError::Timeout) => None,
                    Err(RecvTimeoutError::Disconnected) => Some(ToWorker::Shutdown),
                }
            } else {
                None
            };
            for message in first.into_iter().chain(self.rx.try_iter()) {
                match message {
                    ToWorker::Drive(twist) => {
                        desired = twist;
                        ordered_at = self.now();
                    }
                    ToWorker::Stop => desired = Twist::ZERO,
                    ToWorker::Gripper(g) => gripper_order = Some(g),
                    ToWorker::Servos(writes) => servos.push(&writes),
                    ToWorker::Shutdown => {
                        let _ =
                            t.transact(Request::Motors(0, 0), timeout, cfg.retries, &self.counters);
                        return End::Shutdown;
                    }
                }
            }
            let now = self.now();
            if desired != Twist::ZERO && now - ordered_at > cfg.command_timeout {
                desired = Twist::ZERO;
                self.note(format!(
                    "no command from the console for {} s: robot stopped",
                    cfg.command_timeout
                ));
            }

            // Motors: re-derive the integer targets on a change and every DITHER_PERIOD.
            let mut target = sent;
            if desired == Twist::ZERO {
                target = (0, 0);
                dither = (Dither::default(), Dither::default());
            } else if desired != basis || now >= derived_at + DITHER_PERIOD {
                let frame = now * cfg.pid_rate_hz;
                let (vl, vr) = geometry.wheel_speeds(desired);
                target = (
                    dither.0.next(geometry.ticks_per_frame(vl), frame, horizon),
                    dither.1.next(geometry.ticks_per_frame(vr), frame, horizon),
                );
                derived_at = now;
            }
            if target != sent || now >= sent_at + cfg.refresh {
                let request = Request::Motors(target.0, target.1);
                if let Err(e) = t.transact(request, timeout, cfg.retries, &self.counters) {
                    return End::Lost(e.to_string());
                }
                sent = target;
                basis = desired;
                sent_at = self.now();
            }

            if let Some(g) = gripper_order.take()
                && let Err(e) = self.order_gripper(t, g, &mut actuating)
            {
                return End::Lost(e.to_string());
            }

            // One arm servo a turn: the wheels' requests go between them.
            if let Some((index, deg)) = servos.pop()
                && let Err(e) = self.write_servo(t, index, deg)
            {
                return End::Lost(e.to_string());
            }

            if now >= next_poll {
                next_poll = (next_poll + poll_period).max(now);
                match t.transact(Request::Encoders, timeout, cfg.retries, &self.counters) {
                    Ok(Reply::Counts(l, r)) => {
                        let at = self.now();
                        let dt = last_reading.map_or(0.0, |p| at - p);
                        last_reading = Some(at);
                        self.take_reading(l, r, dt);
                    }
                    Ok(_) => {}
                    Err(e) => return End::Lost(e.to_string()),
                }
                if let Err(e) = self.watch_gripper(t, &mut actuating) {
                    return End::Lost(e.to_string());
                }
            }
            self.summarise();
        }
    }

    fn take_reading(&mut self, left: i32, right: i32, dt: f64) {
        Counters::bump(&self.counters.readings);
        match self.odometer.read(left, right, dt) {
            Reading::Baseline => {}
            Reading::Travel(wheels) => self.say(FromWorker::Travel {
                wheels,
                elapsed: dt,
            }),
            Reading::Jump(dl, dr) => {
                Counters::bump(&self.counters.jumps);
                self.note(format!(
                    "encoder jump of {dl} / {dr} counts in {dt:.3} s rejected (faster than the robot can drive)"
                ));
            }
        }
    }

    /// The gripper's angle read at connection, as open or closed if it is at either.
    fn initial_gripper(&mut self, t: &mut SerialTransport) -> Option<GripperState> {
        let cfg = &self.settings.serial;
        let index = cfg.gripper_servo?;
        let reply = t
            .transact(
                Request::ServoAngle(index),
                self.settings.reply_timeout(),
                cfg.retries,
                &self.counters,
            )
            .ok()?;
        let Reply::Number(angle) = reply else {
            return None;
        };
        let near = |deg: f64| (angle as f64 - deg).abs() <= SERVO_TOLERANCE as f64;
        if near(cfg.gripper_open_deg) {
            Some(GripperState::Open)
        } else if near(cfg.gripper_close_deg) {
            Some(GripperState::Closed)
        } else {
            None
        }
    }

    /// `s IDX DEG` for an open or close order; the gripper is then reported moving.
    fn order_gripper(
        &mut self,
        t: &mut SerialTransport,
        order: GripperCommand,
        actuating: &mut Option<(GripperCommand, f64)>,
    ) -> Result<(), TransactError> {
        let cfg = self.settings.serial.clone();
        let Some(index) = cfg.gripper_servo else {
            if !std::mem::replace(&mut self.gripper_note, true) {
                self.note("gripper order ignored: no [serial] gripper_servo configured".into());
            }
            return Ok(());
        };
        let degrees = self.gripper_degrees(order);
        let request = Request::Servo(index, degrees.round() as u16);
        match t.transact(
            request,
            self.settings.reply_timeout(),
            cfg.retries,
            &self.counters,
        ) {
            Ok(_) => {
                self.say(FromWorker::Gripper(match order {
                    GripperCommand::Open => GripperState::Opening,
                    GripperCommand::Close => GripperState::Closing,
                }));
                *actuating = Some((order, self.now()));
                Ok(())
            }
            Err(TransactError::Refused(r)) => {
                self.note(format!(
                    "the firmware refuses `{r}`: build ROSArduinoBridge with USE_SERVOS"
                ));
                Ok(())
            }
            Err(e) => Err(e),
        }
    }

    /// `s IDX DEG` for an arm joint; a firmware without servos is named once.
    fn write_servo(
        &mut self,
        t: &mut SerialTransport,
        index: u8,
        deg: u16,
    ) -> Result<(), TransactError> {
        let request = Request::Servo(index, deg);
        let retries = self.settings.serial.retries;
        match t.transact(
            request,
            self.settings.reply_timeout(),
            retries,
            &self.counters,
        ) {
            Ok(_) => Ok(()),
            Err(TransactError::Refused(r)) => {
                if !std::mem::replace(&mut self.servo_note, true) {
                    self.note(format!(
                        "the firmware refuses `{r}`: build ROSArduinoBridge with USE_SERVOS (and enough N_SERVOS for the arm)"
                    ));
                }
                Ok(())
            }
            Err(e) => Err(e),
        }
    }

    fn gripper_degrees(&self, order: GripperCommand) -> f64 {
        match order {
            GripperCommand::Open => self.settings.serial.gripper_open_deg,
            GripperCommand::Close => self.settings.serial.gripper_close_deg,
        }
    }

    /// While the servo moves, `t IDX` tells when it has arrived; after `gripper_timeout`
    /// it is reported where it was sent.
    fn watch_gripper(
        &mut self,
        t: &mut SerialTransport,
        actuating: &mut Option<(GripperCommand, f64)>,
    ) -> Result<(), TransactError> {
        let (Some((order, started)), Some(index)) =
            (*actuating, self.settings.serial.gripper_servo)
        else {
            return Ok(());
        };
        let target = self.gripper_degrees(order).round() as i64;
        let request = Request::ServoAngle(index);
        let arrived = match t.transact(request, self.settings.reply_timeout(), 0, &self.counters) {
            Ok(Reply::Number(angle)) => (angle - target).abs() <= SERVO_TOLERANCE,
            Ok(_) | Err(TransactError::Refused(_)) | Err(TransactError::Silent(..)) => false,
            Err(e) => return Err(e),
        };
        let late = self.now() - started > self.settings.serial.gripper_timeout;
        if arrived || late {
            if late && !arrived {
                self.note(format!(
                    "gripper servo {index} did not report reaching {target} degrees within {} s",
                    self.settings.serial.gripper_timeout
                ));
            }
            *actuating = None;
            self.say(FromWorker::Gripper(match order {
                GripperCommand::Open => GripperState::Open,
                GripperCommand::Close => GripperState::Closed,
            }));
        }
        Ok(())
    }

    /// Tells the console the fault totals when they changed, at most every NOTE_EVERY s.
    fn summarise(&mut self) {
        let now = self.now();
        if now - self.noted_at < NOTE_EVERY {
            return;
        }
        let faults = self.counters.snapshot().faults();
        if !faults.is_empty() && faults != self.noted {
            self.noted_at = now;
            self.note(format!("{faults} so far"));
            self.noted = faults;
        }
    }
}
