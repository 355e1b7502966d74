//! The control loop: sense, decide, act at the robot's control period (seed 001: 0.1 s).

use super::log::Level;
use super::mode::Mode;
use super::{App, LinkStatus};
use crate::data::{Command, WheelTravel};
use crate::geometry::Twist;
use crate::slam::odometry::twist_from_wheels;

/// A stall longer than this is skipped rather than caught up, seconds.
const MAX_CATCH_UP: f64 = 1.0;
/// Seconds within which a control step counts as due.
const TICK_SLACK: f64 = 1e-9;
/// At most one overrun warning per this many seconds.
const WARN_EVERY: f64 = 5.0;

/// When the next control step is due, and how regularly steps have run.
#[derive(Clone, Debug)]
pub(super) struct ControlClock {
    period: f64,
    next_tick: f64,
    last_update: f64,
    rate: f64,
    last_warning: f64,
    /// Wheel travel and time since the last periodic tick, for the measured twist.
    travel: WheelTravel,
    travel_time: f64,
}

impl ControlClock {
    pub(super) fn new(now: f64, period: f64) -> Self {
        Self {
            period,
            next_tick: now,
            last_update: now,
            rate: 1.0 / period,
            last_warning: f64::NEG_INFINITY,
            travel: WheelTravel::default(),
            travel_time: 0.0,
        }
    }

    /// Control steps completed per second, smoothed.
    pub(super) fn rate(&self) -> f64 {
        self.rate
    }
}

impl App {
    /// Runs every control step due up to `now` (periodic ticks and deadman expiries).
    pub fn update(&mut self, now: f64) {
        self.advance_to(now);
        // Between control steps, still bring what the robot reports up to date.
        self.sense(now);
        self.refresh_revision();
    }

    /// Seconds of session time until the console next needs to run, for the event wait.
    pub fn next_deadline(&self) -> f64 {
        let tick = self.clock.next_tick;
        self.teleop_cutoff().map_or(tick, |c| c.min(tick))
    }

    pub(super) fn advance_to(&mut self, now: f64) {
        if now < self.now {
            return;
        }
        let gap = now - self.clock.last_update;
        if gap > 1.5 * self.clock.period && self.clock.next_tick <= now {
            if now - self.clock.last_warning >= WARN_EVERY {
                self.clock.last_warning = now;
                self.log.push(
                    now,
                    Level::Warn,
                    format!(
                        "Warning! dt = {gap:.2} s: control loop overran its {:.2} s period",
                        self.clock.period
                    ),
                );
            }
            if now - self.clock.next_tick > MAX_CATCH_UP {
                self.clock.next_tick = now;
            }
        }
        loop {
            let tick = self.clock.next_tick;
            let due = self.teleop_cutoff().map_or(tick, |c| c.min(tick));
            // A tick due a rounding error after `now` is due now: sums of 0.1 s drift apart.
            if due > now + TICK_SLACK {
                break;
            }
            self.control_step(due);
            if due >= tick {
                self.clock.next_tick = tick + self.clock.period;
                let dt = due - self.clock.last_update;
                if dt > 0.0 {
                    // Exponential smoothing over about ten ticks.
                    self.clock.rate += 0.1 * (1.0 / dt - self.clock.rate);
                }
                self.clock.last_update = due;
                self.measure();
                self.map_footprint();
                self.show_picture(due);
                self.sample_accuracy();
                self.check_race_uncertainty();
            }
        }
        self.now = now;
    }

    /// When the held keys' deadman cuts the drive command: early enough that the robot,
    /// braking at its acceleration limits, is at rest `deadman_timeout` after the last key.
    fn teleop_cutoff(&self) -> Option<f64> {
        let expiry = self.teleop.next_expiry(self.brake_margin())?;
        Some(expiry.max(self.now))
    }

    /// One sense-decide-act cycle at session time `t`.
    pub(super) fn control_step(&mut self, t: f64) {
        self.sense(t);
        self.act(t);
    }

    /// Collects what the robot reported up to `t`.
    pub(super) fn sense(&mut self, t: f64) {
        self.now = self.now.max(t);
        match self.link.poll(t) {
            Ok(frame) => {
                if let LinkStatus::Lost(_) = self.link_status {
                    if self.link_was_up {
                        self.link_status = LinkStatus::Back;
                        self.log.push(
                            t,
                            Level::Success,
                            "link back: press any key to resume control",
                        );
                    } else {
                        // Control was never established, so there is nothing to resume.
                        self.link_status = LinkStatus::Ok;
                        self.log.push(t, Level::Success, "link up");
                    }
                }
                self.link_was_up = true;
                if let Some(wheels) = frame.wheels {
                    self.estimate_motion(wheels);
                    self.clock.travel.left += wheels.left;
                    self.clock.travel.right += wheels.right;
                    self.clock.travel_time += frame.elapsed;
                }
                if let Some(s) = frame.sightings {
                    self.estimate_sightings(&s);
                    self.note_sightings(t, &s);
                    self.map_sightings(&s);
                    self.note_frame(s.iter().map(|m| m.id).collect());
                }
                if let Some(status) = frame.camera {
                    self.note_camera(t, status);
                }
                if let Some(scan) = &frame.scan {
                    self.map_scan(t, scan);
                }
                self.note_collisions(t);
                if let Some(g) = frame.gripper {
                    if self.gripper.is_some() && self.gripper != Some(g) {
                        self.log
                            .push(t, Level::Info, format!("gripper {}", g.label()));
                    }
                    self.gripper = Some(g);
                }
            }
            Err(e) => self.lose_link(t, e.to_string()),
        }
        for note in self.link.take_notes() {
            self.log.push(t, note.level, note.text);
        }
    }

    /// The twin counts contacts; each new one is worth a line in the log.
    fn note_collisions(&mut self, t: f64) {
        let count = self.link.ground_truth().map_or(0, |twin| twin.collisions());
        if count > self.collisions_logged {
            self.collisions_logged = count;
            let p = self
                .link
                .ground_truth()
                .map(|twin| twin.pose())
                .unwrap_or_default();
            self.log.push(
                t,
                Level::Warn,
                format!(
                    "collision at ({:.2}, {:.2}): robot stopped against an obstacle ({count} so far)",
                    p.x, p.y
                ),
            );
        }
    }

    /// Decides and sends the command for `t`.
    fn act(&mut self, t: f64) {
        let twist = self.decide(t);
        let command = Command {
            twist,
            gripper: self.pending_gripper.take(),
        };
        self.commanded = twist;
        if let Err(e) = self.link.send(&command) {
            self.lose_link(t, format!("command not sent: {e}"));
        }
    }

    /// Control is lost: drop held keys, command nothing further, say so once.
    fn lose_link(&mut self, t: f64, reason: String) {
        if !matches!(self.link_status, LinkStatus::Lost(_)) {
            // Before the robot first answers, waiting is expected rather than an error.
            let level = if self.link_was_up {
                Level::Error
            } else {
                Level::Info
            };
            self.log.push(t, level, reason.clone());
        }
        self.link_status = LinkStatus::Lost(reason);
        self.teleop.clear();
        self.commanded = Twist::ZERO;
    }

    /// The measured twist over the last control period: whole periods, so that encoder
    /// quantisation does not make it flicker.
    fn measure(&mut self) {
        let c = &mut self.clock;
        if c.travel_time >= 0.5 * c.period {
            self.measured = twist_from_wheels(c.travel, self.config.robot.track, c.travel_time);
            c.travel = WheelTravel::default();
            c.travel_time = 0.0;
        }
    }

    /// The twist the active mode asks for at `t`; zero whenever control is in doubt.
    fn decide(&mut self, t: f64) -> Twist {
        // The deadman always drops expired keys, even while the command is forced to zero,
        // so its deadline moves on and the loop in `advance_to` always progresses.
        let keys = self.teleop.twist(t, self.brake_margin());
        let in_doubt = self.estop || self.quit || self.link_status != LinkStatus::Ok;
        if in_doubt {
            return Twist::ZERO;
        }
        match self.mode {
            Mode::PathFollowing => self.follow(t),
            Mode::Exploration => self.explore(t),
            m if m.drives_by_keys() => keys,
            _ => Twist::ZERO,
        }
    }

    /// For an autonomous mode's step at `t` after its last one (`last`: when, and the twist
    /// it gave): `Err(twist)` when that step was under half a period ago and its command
    /// stands (decide also runs on key events between ticks), else `Ok(dt)`.
    pub(super) fn step_due(&self, last: Option<(f64, Twist)>, t: f64) -> Result<f64, Twist> {
        let period = self.config.robot.control_period;
        match last {
            Some((at, twist)) if t - at < 0.5 * period => Err(twist),
            Some((at, _)) => Ok(t - at),
            None => Ok(period),
        }
    }

    /// Seconds the robot needs to brake from the current command at its acceleration limits.
    pub(super) fn brake_margin(&self) -> f64 {
        let r = &self.config.robot;
        (self.commanded.linear.abs() / r.max_linear_accel)
            .max(self.commanded.angular.abs() / r.max_angular_accel)
    }
}
