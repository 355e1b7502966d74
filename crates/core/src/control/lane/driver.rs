//! The lane driver: one step per control period from the newest lane sighting.

use super::LaneDriveConfig;
use super::arm_watch::ArmWatch;
use super::light_watch::{LightCall, LightWatch};
use crate::data::{BarrierState, LaneSighting, LightColour};
use crate::geometry::Twist;

/// What holds the robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wait {
    /// A red or yellow light ahead: go at green.
    Light(LightColour),
    /// At the stop line with the light's green seen too long ago: look again.
    LookingForLight,
    /// A barrier down or moving ahead: go when it is up.
    Barrier(BarrierState),
    /// No lane line seen for `lost_after` seconds.
    LaneLost,
}

impl Wait {
    /// What the status line says.
    pub fn text(self) -> String {
        match self {
            Wait::Light(c) => format!("waiting at a {} light", c.label()),
            Wait::LookingForLight => "at the stop line: looking for the light again".into(),
            Wait::Barrier(BarrierState::Up) => "waiting for the barrier's next opening".into(),
            Wait::Barrier(s) => format!("waiting at a barrier ({})", s.label()),
            Wait::LaneLost => "lane lost: stopped".into(),
        }
    }
}

/// One step's decision: lane following's twist, and what traffic compliance holds the
/// robot for (the arbiter lets the hold win).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneStep {
    pub twist: Twist,
    pub wait: Option<Wait>,
}

/// See the module comment.
#[derive(Clone, Debug)]
pub struct LaneDriver {
    cfg: LaneDriveConfig,
    /// The error of the last frame that had one, for the derivative.
    last_error: Option<f64>,
    /// When a lane line was last seen.
    seen_at: Option<f64>,
    /// The hold for a barrier, kept until it clears.
    hold: Option<Wait>,
    /// Whether the robot saw the barrier ahead open while it waited, and may pass.
    opened: bool,
    /// The range of the arm the robot stopped for, when it was seen near (none while no
    /// barrier holds the robot, and for an arm remembered out of view).
    held_range: Option<f64>,
    /// Metres still to drive at the crossing speed, past an arm whose opening the robot saw.
    crossing: Option<f64>,
    /// Frames since an arm was last seen ahead (within `BARRIER_AHEAD` stopping ranges).
    unseen: u32,
    /// The arm's range in the last frame that showed it, and whether that frame agreed
    /// with the one before it (the arm is believed).
    arm_range: Option<(f64, bool)>,
    /// How the arm ahead moved while the robot waited before it.
    arm: ArmWatch,
    /// The arm's angle in the last frame that showed one, degrees above level.
    last_arm: Option<f64>,
    /// The light ahead as last seen, its range since shortened by the distance driven.
    light: LightWatch,
    /// The range of an arm seen ahead and not seen to open, shortened likewise: an arm
    /// that rises leaves the picture's top before the robot reaches its stopping range.
    arm_ahead: Option<f64>,
    /// Whether the hold is for an arm remembered out of view: its range may have read
    /// short (glare ranged an arm 1.9 m off at 0.9 m), so an arm seen anywhere ahead is it.
    remembered: bool,
    /// When a frame last showed an arm, or the remembered arm's hold began.
    arm_seen_at: f64,
    /// When the last step was taken.
    last_t: Option<f64>,
}

/// Frames without an arm seen ahead after which the barrier is behind the robot.
const BARRIER_GONE: u32 = 10;
/// Lights seen within this many stopping ranges are remembered as the light ahead.
const LIGHT_AHEAD: f64 = 2.0;
/// Arms seen within this many stopping ranges are the barrier ahead: remembered when lost
/// from view, and while the robot waits, the only arm that can open its way.
const BARRIER_AHEAD: f64 = 2.0;
/// Metres past the arm, beyond the robot's reckoned distance to it, that the crossing
/// speed lasts: the camera sits 5 cm before the robot's centre, the footprint reaches
/// about 0.1 m behind it, and the arm's range may read a tenth of a metre short.
const CROSS_BEYOND: f64 = 0.3;
/// Metres beyond the range of the arm the robot stopped for past which an arm seen while
/// it waits is another barrier.
const ARM_SEPARATE: f64 = 0.3;
/// Arms placed within this many stopping ranges are remembered when they rise out of
/// view: an arm down 1.7 m ahead reads 1.1-1.2 m, and one seen rising from there stays up
/// too short a time for the robot to reach it at lane speed.
const REMEMBER_AHEAD: f64 = 3.0;
/// How far apart, metres plus a share of the range, two frames may put an arm for the
/// second to confirm the first: a raised arm's range wanders by a tenth, a misread one
/// jumps (1.6 m, then 6 cm, then 1.7 m).
const ARM_AGREE_METRES: f64 = 0.05;
const ARM_AGREE_SHARE: f64 = 0.15;
/// seed 000 §3.2.3: an arm within this of level is DOWN.
const DOWN_DEG: f64 = 20.0;

impl LaneDriver {
    pub fn new(cfg: LaneDriveConfig) -> Self {
        Self {
            cfg,
            last_error: None,
            seen_at: None,
            hold: None,
            opened: false,
            crossing: None,
            held_range: None,
            unseen: 0,
            arm_range: None,
            arm: ArmWatch::default(),
            last_arm: None,
            light: LightWatch::default(),
            arm_ahead: None,
            remembered: false,
            arm_seen_at: 0.0,
            last_t: None,
        }
    }

    pub fn config(&self) -> &LaneDriveConfig {
        &self.cfg
    }

    /// Forgets the lane and any hold (lane mode entered anew).
    pub fn reset(&mut self, t: f64) {
        self.last_error = None;
        self.seen_at = Some(t);
        self.hold = None;
        self.opened = false;
        self.crossing = None;
        self.held_range = None;
        // What was seen before the pause is not ahead any more: the robot may have moved.
        self.light = LightWatch::default();
        self.arm_ahead = None;
        self.remembered = false;
        self.arm_seen_at = t;
        self.arm_range = None;
        self.arm = ArmWatch::default();
        self.last_arm = None;
        self.last_t = None;
    }

    /// The step at `t` from `fresh`, a sighting taken since the last step (none: no new
    /// frame), with the robot's measured forward speed `speed`.
    pub fn step(&mut self, t: f64, fresh: Option<&LaneSighting>, speed: f64) -> LaneStep {
        let dt = self.last_t.map_or(0.0, |last| (t - last).max(0.0));
        self.last_t = Some(t);
        self.light.drive(speed * dt);
        if let Some(range) = &mut self.arm_ahead {
            *range -= speed.max(0.0) * dt;
        }
        if let Some(range) = &mut self.held_range {
            *range -= speed.max(0.0) * dt;
        }
        if let Some(left) = &mut self.crossing {
            *left -= speed.max(0.0) * dt;
        }
        if self.crossing.is_some_and(|left| left <= 0.0) {
            // Past the arm: the next one is met afresh.
            self.crossing = None;
            self.opened = false;
        }
        if self.hold.is_some() {
            self.crossing = None;
        }
        if let Some(s) = fresh {
            if let Some(light) = &s.light {
                let reach = LIGHT_AHEAD * self.cfg.light_stop_range;
                let curvature = s.curvature.unwrap_or(0.0);
                (self.light).see(t, light, curvature, reach, self.cfg.light_line_ahead);
            }
            self.comply(s);
        }
        // An arm seen ahead and then lost from view above the picture (met up, or rising
        // before the robot reached it) holds the robot at the stopping range all the same:
        // how long it stays up is unknown.
        if let Some(range) = self.arm_ahead
            && range <= self.cfg.barrier_stop_range
        {
            self.arm_ahead = None;
            // Remembered while crossing, it is the next barrier: the crossing is over.
            if self.crossing.take().is_some() {
                self.opened = false;
            }
            if self.hold.is_none() && !self.opened && range >= 0.0 {
                self.hold = Some(Wait::Barrier(BarrierState::Up));
                self.remembered = true;
                self.arm_seen_at = t;
            }
        }
        if fresh.is_some_and(|s| s.barrier.is_some_and(|b| b.fresh)) {
            self.arm_seen_at = t;
        }
        // Waiting for a remembered arm that no frame has shown for the patience: it stands
        // open, or was never where it was remembered.
        if self.remembered
            && self.hold == Some(Wait::Barrier(BarrierState::Up))
            && t - self.arm_seen_at >= self.cfg.unseen_arm_patience
        {
            self.hold = None;
            self.remembered = false;
            self.opened = true;
            self.unseen = 0;
        }
        // A red or yellow seen near, or seen farther off and then lost from view (a lamp
        // seen only now and then, or leaving the picture in a bend), stops the robot where
        // it would have stopped had it stayed in view.
        let (stop, line) = (self.cfg.light_stop_range, self.cfg.light_line_ahead);
        let light_wait = match self.light.call(t, stop, line) {
            LightCall::Go => None,
            LightCall::Stop(colour) => Some(Wait::Light(colour)),
            LightCall::Look => Some(Wait::LookingForLight),
        };
        let twist = match fresh.and_then(|s| s.error_px.map(|e| (e, s.curvature))) {
            Some((e, curvature)) => {
                self.seen_at = Some(t);
                self.follow(e, curvature.unwrap_or(0.0), speed)
            }
            // Between frames, and briefly after losing the lines, keep the last command's
            // shape from the last error; past `lost_after` stop.
            None => match (self.seen_at, self.last_error) {
                (Some(seen), Some(e)) if t - seen < self.cfg.lost_after => {
                    let (v, _) = self.speed_law(e);
                    Twist::new(v, self.turn(e, 0.0, 0.0, speed))
                }
                _ => Twist::ZERO,
            },
        };
        // Passing an opened barrier, the speed law's share of the crossing speed.
        let twist = match self.crossing {
            Some(_) => Twist::new(
                twist.linear * self.cfg.crossing_speed / self.cfg.max_speed,
                twist.angular,
            ),
            None => twist,
        };
        let lost = self.seen_at.is_none_or(|s| t - s >= self.cfg.lost_after);
        let wait = (light_wait.or(self.hold)).or(lost.then_some(Wait::LaneLost));
        LaneStep { twist, wait }
    }

    /// Holds for a closed barrier in range; clears the hold when it opens (seed 000 §3's
    /// traffic compliance).
    fn comply(&mut self, s: &LaneSighting) {
        self.see_barrier(s);
        if self.hold.is_none() {
            self.held_range = None;
        }
        if !matches!(self.hold, Some(Wait::Barrier(_))) {
            self.remembered = false;
        }
    }

    /// What the frame's arm does to the hold; `comply` then forgets the remembered arm
    /// once no barrier holds the robot (this returns early from several branches).
    fn see_barrier(&mut self, s: &LaneSighting) {
        let waiting = matches!(self.hold, Some(Wait::Barrier(_)));
        // While the robot waits before an arm, one seen farther off is another barrier
        // down the track (this one has risen out of the picture), not this one.
        let reach = BARRIER_AHEAD * self.cfg.barrier_stop_range;
        // Before it holds the robot, an arm is believed once two frames in a row agree on
        // where it stands: one misread frame would otherwise hold the robot for an
        // opening it never sees.
        self.arm_range = match s.barrier {
            Some(b) if b.fresh => {
                let agrees = |(r, _): (f64, bool)| {
                    (b.range - r).abs() <= ARM_AGREE_METRES + ARM_AGREE_SHARE * b.range
                };
                Some((b.range, self.arm_range.is_some_and(agrees)))
            }
            Some(_) => self.arm_range,
            None => None,
        };
        let believed = self.arm_range.is_some_and(|(_, believed)| believed);
        // An arm ranged when the robot stopped for it is told from one farther down the
        // track by range (barriers stand at least 1.2 m apart; a far one's range reads
        // short while it moves, 0.8 m for 1.8 m).
        let barrier = (s.barrier).filter(|b| match (waiting, self.held_range) {
            (true, Some(held)) if !self.remembered => b.range <= held + ARM_SEPARATE,
            (true, _) => b.range <= reach || (self.remembered && b.fresh),
            (false, _) => believed,
        });
        let angle = barrier.map(|b| b.angle_deg.abs());
        let last_arm = std::mem::replace(&mut self.last_arm, angle);
        let closed_ahead = waiting && self.hold != Some(Wait::Barrier(BarrierState::Up));
        if self.arm.opening(angle, closed_ahead) {
            // Seen rising from where it lay while the robot waited, and now past RISEN_DEG
            // or gone from the view above it: the opening has begun, and the arm clears the
            // robot's height before the robot reaches it.
            self.open_way();
            return;
        }
        if let Some(b) = barrier {
            let near = b.range <= REMEMBER_AHEAD * self.cfg.barrier_stop_range;
            // A moving arm's range reads short (an arm 2.3 m off, rising, reads 1 m): only
            // one lying down or standing up places the barrier; a moving one keeps the
            // place last read.
            let placed = b.angle_deg.abs() <= DOWN_DEG || b.state == BarrierState::Up;
            // While crossing, an arm seen lying down beyond the one being passed is the next
            // barrier (a raised one may be the one being passed: its range reads long).
            let next = b.angle_deg.abs() <= DOWN_DEG
                && (self.crossing).is_some_and(|left| b.range > left - CROSS_BEYOND + ARM_SEPARATE);
            if !(near && (!self.opened || next) && self.hold.is_none()) {
                self.arm_ahead = None;
            } else if placed && b.fresh {
                self.arm_ahead = Some(b.range);
            }
        }
        match barrier {
            // Seen rising while waiting (not the arm met already up, whose next opening
            // begins with it down), wherever the raised arm now seems to be: this opening
            // is the robot's to pass.
            Some(b)
                if waiting
                    && b.state == BarrierState::Up
                    && self.hold != Some(Wait::Barrier(BarrierState::Up)) =>
            {
                self.open_way();
            }
            // Waiting for the next opening of an arm met up: seen lying down, wherever its
            // range reads (an arm's range reads short while it is raised), it is that arm
            // closed, and its rise will be the robot's opening. Only down: a raised arm
            // stands mostly above the picture, and the finder merges what is left of it with
            // an arm farther down the track into a moving or raised arm that is neither.
            Some(b) if self.hold == Some(Wait::Barrier(BarrierState::Up)) => {
                if b.angle_deg.abs() <= DOWN_DEG {
                    self.hold = Some(Wait::Barrier(BarrierState::Down));
                }
                self.unseen = 0;
            }
            Some(b) if b.range <= self.cfg.barrier_stop_range => {
                self.unseen = 0;
                self.held_range.get_or_insert(b.range);
                // Seen near, the arm is ranged afresh.
                self.remembered = false;
                // After an opening seen to begin, only an arm seen down or coming down
                // closes the way again (the filter's state lags a rising arm).
                let closing = b.angle_deg.abs() <= DOWN_DEG
                    || last_arm.is_some_and(|a| b.angle_deg.abs() < a - 1.0);
                if b.state != BarrierState::Up {
                    // Otherwise the rise it saw begin: carry on.
                    if !self.opened || closing {
                        self.hold = Some(Wait::Barrier(b.state));
                        self.opened = false;
                    }
                } else if closed_ahead {
                    // Seen rising while waiting: this opening is the robot's to pass.
                    self.open_way();
                } else if !self.opened {
                    // Up when first met near: how long it stays up is unknown, so the
                    // robot waits for an opening it sees begin.
                    self.hold = Some(Wait::Barrier(BarrierState::Up));
                }
            }
            // Seen still ahead, short of the stopping range (a raised arm's range reads
            // long): the arm whose opening the robot saw.
            Some(b) if b.range <= reach => self.unseen = 0,
            _ => {
                // No arm ahead for a second: past the barrier, and the next one is met
                // afresh.
                self.unseen += 1;
                if self.unseen >= BARRIER_GONE {
                    self.opened = false;
                }
            }
        }
    }

    /// The opening of the arm the robot waited before has begun: it drives on at the
    /// crossing speed until past the arm (ranged when it stopped; a remembered arm may
    /// stand as far as `REMEMBER_AHEAD` stopping ranges ahead, as it was placed from there).
    fn open_way(&mut self) {
        self.hold = None;
        self.opened = true;
        self.unseen = 0;
        let far = REMEMBER_AHEAD * self.cfg.barrier_stop_range;
        let arm = self.held_range.filter(|_| !self.remembered).unwrap_or(far);
        self.crossing = Some(arm.max(0.0) + CROSS_BEYOND);
    }

    /// Lane following's twist for error `e` (bird's-eye pixels, + when the lane centre is
    /// to the right) on a lane of `curvature` (1/m, + left).
    fn follow(&mut self, e: f64, curvature: f64, speed: f64) -> Twist {
        let de = self.last_error.map_or(0.0, |last| e - last);
        self.last_error = Some(e);
        let (v, _) = self.speed_law(e);
        let feed = self.cfg.curvature_feedforward * curvature * v;
        Twist::new(v, self.turn(e, de, feed, speed))
    }

    /// Seed 000 §2.4.2: v(e) = v_max (max(0, 1 - |e| / e_max))^alpha.
    fn speed_law(&self, e: f64) -> (f64, f64) {
        let f = (1.0 - e.abs() / self.cfg.max_error)
            .max(0.0)
            .powf(self.cfg.alpha);
        (self.cfg.max_speed * f, f)
    }

    /// Seed 000 §2.4.1: (Kp e + Kd de) / speed_factor, speed_factor = clamp(v / v_nom,
    /// 0.5, 1.5), saturated; the error turns the robot towards the lane centre (AutoRace's
    /// sign: angular = -output). `feed`: the curvature feed-forward, v kappa (a unicycle on
    /// a curve of curvature kappa turns at v kappa; the seed's Kf has no value).
    fn turn(&self, e: f64, de: f64, feed: f64, speed: f64) -> f64 {
        let factor = (speed.abs() / self.cfg.nominal_speed).clamp(0.5, 1.5);
        let output = (self.cfg.kp * e + self.cfg.kd * de) / factor;
        (feed - output).clamp(-self.cfg.max_angular, self.cfg.max_angular)
    }
}

#[cfg(test)]
#[path = "driver_tests.rs"]
mod tests;
