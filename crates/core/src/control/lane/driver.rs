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
    /// Frames since a barrier was last seen in range.
    unseen: u32,
    /// How the arm ahead moved while the robot waited before it.
    arm: ArmWatch,
    /// The arm's angle in the last frame that showed one, degrees above level.
    last_arm: Option<f64>,
    /// The light ahead as last seen, its range since shortened by the distance driven.
    light: LightWatch,
    /// When the last step was taken.
    last_t: Option<f64>,
}

/// Frames without a barrier in range after which it is behind the robot.
const BARRIER_GONE: u32 = 10;
/// Lights seen within this many stopping ranges are remembered as the light ahead.
const LIGHT_AHEAD: f64 = 2.0;
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
            unseen: 0,
            arm: ArmWatch::default(),
            last_arm: None,
            light: LightWatch::default(),
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
        // What was seen before the pause is not ahead any more: the robot may have moved.
        self.light = LightWatch::default();
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
        if let Some(s) = fresh {
            if let Some(light) = &s.light {
                let reach = LIGHT_AHEAD * self.cfg.light_stop_range;
                self.light.see(t, light, reach);
            }
            self.comply(s);
        }
        // A red or yellow seen near, or seen farther off and then lost from view (a lamp
        // seen only now and then, or leaving the picture in a bend), stops the robot where
        // it would have stopped had it stayed in view.
        let light_wait = match self.light.call(t, self.cfg.light_stop_range) {
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
        let lost = self.seen_at.is_none_or(|s| t - s >= self.cfg.lost_after);
        let wait = (light_wait.or(self.hold)).or(lost.then_some(Wait::LaneLost));
        LaneStep { twist, wait }
    }

    /// Holds for a closed barrier in range; clears the hold when it opens (seed 000 §3's
    /// traffic compliance).
    fn comply(&mut self, s: &LaneSighting) {
        let angle = s.barrier.map(|b| b.angle_deg.abs());
        let last_arm = std::mem::replace(&mut self.last_arm, angle);
        let waiting = matches!(self.hold, Some(Wait::Barrier(_)));
        let closed_ahead = waiting && self.hold != Some(Wait::Barrier(BarrierState::Up));
        if self.arm.opening(angle, closed_ahead) {
            // Seen rising from where it lay while the robot waited, and now past RISEN_DEG
            // or gone from the view above it: the opening has begun, and the arm clears the
            // robot's height before the robot reaches it.
            self.hold = None;
            self.opened = true;
            self.unseen = 0;
            return;
        }
        match s.barrier {
            // Seen rising while waiting (not the arm met already up, whose next opening
            // begins with it down), wherever the raised arm now seems to be: this opening
            // is the robot's to pass.
            Some(b)
                if waiting
                    && b.state == BarrierState::Up
                    && self.hold != Some(Wait::Barrier(BarrierState::Up)) =>
            {
                self.hold = None;
                self.opened = true;
                self.unseen = 0;
            }
            Some(b) if b.range <= self.cfg.barrier_stop_range => {
                self.unseen = 0;
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
                    self.hold = None;
                    self.opened = true;
                } else if !self.opened {
                    // Up when first met near: how long it stays up is unknown, so the
                    // robot waits for an opening it sees begin.
                    self.hold = Some(Wait::Barrier(BarrierState::Up));
                }
            }
            _ => {
                // Past the barrier (or out of its range) for a second: the next one is met
                // afresh.
                self.unseen += 1;
                if self.unseen >= BARRIER_GONE {
                    self.opened = false;
                }
            }
        }
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
mod tests {
    use super::*;
    use crate::data::{BarrierSeen, LightSeen};

    fn seen(e: f64) -> LaneSighting {
        LaneSighting {
            error_px: Some(e),
            curvature: Some(0.0),
            ..LaneSighting::default()
        }
    }

    #[test]
    fn a_lane_to_the_right_turns_right_and_slows_by_the_speed_law() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        let s = d.step(0.1, Some(&seen(100.0)), 0.1);
        // Kp e = 0.0025 * 100 = 0.25 rad/s, speed factor 1; v = 0.1 * 0.8^2.2 = 0.0612.
        assert!((s.twist.angular + 0.25).abs() < 1e-9, "{:?}", s.twist);
        assert!((s.twist.linear - 0.1 * 0.8f64.powf(2.2)).abs() < 1e-9);
        // The error grows by 10 px: Kd adds 0.007 * 10 = 0.07 rad/s.
        let s = d.step(0.2, Some(&seen(110.0)), 0.1);
        assert!(
            (s.twist.angular + 0.275 + 0.07).abs() < 1e-9,
            "{:?}",
            s.twist
        );
        assert_eq!(s.wait, None);
    }

    #[test]
    fn slow_driving_doubles_the_gain_at_most() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        let s = d.step(0.1, Some(&seen(-40.0)), 0.0);
        // Speed factor clamps at 0.5: 0.0025 * 40 / 0.5 = 0.2 rad/s, to the left.
        assert!((s.twist.angular - 0.2).abs() < 1e-9, "{:?}", s.twist);
    }

    /// A centred lane with a lamp of `colour` `range` metres off.
    fn lamp(colour: LightColour, range: f64) -> LaneSighting {
        LaneSighting {
            light: Some(LightSeen {
                colour,
                range,
                confidence: 0.9,
            }),
            ..seen(0.0)
        }
    }

    #[test]
    fn a_red_light_near_holds_until_a_green_seen_twice() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        assert_eq!(
            d.step(0.1, Some(&lamp(LightColour::Red, 0.8)), 0.1).wait,
            None
        );
        // The second frame that agrees on the lamp (1 cm nearer): held.
        let near = d.step(0.2, Some(&lamp(LightColour::Red, 0.79)), 0.1);
        assert_eq!(near.wait, Some(Wait::Light(LightColour::Red)));
        // Nothing seen in a frame does not lift the hold, nor does one green frame.
        assert!(d.step(0.3, Some(&seen(0.0)), 0.0).wait.is_some());
        let once = d.step(0.4, Some(&lamp(LightColour::Green, 0.78)), 0.0);
        assert!(once.wait.is_some());
        let twice = d.step(0.5, Some(&lamp(LightColour::Green, 0.78)), 0.0);
        assert_eq!(twice.wait, None);
    }

    #[test]
    fn a_barrier_down_or_moving_holds_until_up() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        let barrier = |state| LaneSighting {
            barrier: Some(BarrierSeen {
                state,
                angle_deg: 0.0,
                range: 0.5,
                belief: [1.0, 0.0, 0.0],
            }),
            ..seen(0.0)
        };
        let s = d.step(0.1, Some(&barrier(BarrierState::Moving)), 0.1);
        assert_eq!(s.wait, Some(Wait::Barrier(BarrierState::Moving)));
        assert_eq!(
            d.step(0.2, Some(&barrier(BarrierState::Up)), 0.0).wait,
            None
        );
        assert_eq!(
            d.step(0.3, Some(&barrier(BarrierState::Up)), 0.1).wait,
            None
        );
    }

    #[test]
    fn a_barrier_already_up_when_met_is_passed_only_on_an_opening_seen_to_begin() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        let barrier = |state| LaneSighting {
            barrier: Some(BarrierSeen {
                state,
                angle_deg: 90.0,
                range: 0.5,
                belief: [0.0, 0.0, 1.0],
            }),
            ..seen(0.0)
        };
        let up = d.step(0.1, Some(&barrier(BarrierState::Up)), 0.1);
        assert_eq!(up.wait, Some(Wait::Barrier(BarrierState::Up)));
        // Still up a frame later: how long it stays up is still unknown.
        let still = d.step(0.15, Some(&barrier(BarrierState::Up)), 0.0);
        assert_eq!(still.wait, Some(Wait::Barrier(BarrierState::Up)));
        d.step(0.2, Some(&barrier(BarrierState::Moving)), 0.0);
        d.step(0.3, Some(&barrier(BarrierState::Down)), 0.0);
        assert_eq!(
            d.step(0.4, Some(&barrier(BarrierState::Up)), 0.0).wait,
            None
        );
    }

    /// A centred lane with an arm at `angle_deg` 0.5 m ahead, in the state of its angle.
    fn arm(angle_deg: f64) -> LaneSighting {
        LaneSighting {
            barrier: Some(BarrierSeen {
                state: BarrierState::of_angle(angle_deg),
                angle_deg,
                range: 0.5,
                belief: [1.0, 0.0, 0.0],
            }),
            ..seen(0.0)
        }
    }

    #[test]
    fn an_arm_seen_rising_out_of_the_picture_is_an_opening_and_one_lowering_is_not() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        for (i, a) in [2.0, 3.0, 7.0, 12.0, 14.0].into_iter().enumerate() {
            let s = d.step(0.1 * (i + 1) as f64, Some(&arm(a)), 0.0);
            assert!(matches!(s.wait, Some(Wait::Barrier(_))), "{a}: {s:?}");
        }
        // Gone from view above the picture's top while rising.
        assert_eq!(d.step(0.6, Some(&seen(0.0)), 0.0).wait, None);
        // Lowering from 30 degrees to level, then gone: still closed.
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        for (i, a) in [30.0, 25.0, 18.0, 10.0, 2.0].into_iter().enumerate() {
            d.step(0.1 * (i + 1) as f64, Some(&arm(a)), 0.0);
        }
        let s = d.step(0.6, Some(&seen(0.0)), 0.0);
        assert_eq!(s.wait, Some(Wait::Barrier(BarrierState::Down)));
    }

    #[test]
    fn once_an_opening_is_seen_the_rising_arm_does_not_stop_the_robot_but_a_lowering_one_does() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        for (i, a) in [0.0, 10.0, 30.0, 46.0].into_iter().enumerate() {
            d.step(0.1 * (i + 1) as f64, Some(&arm(a)), 0.0);
        }
        // Open at 46 degrees and rising; still moving at 50 and 50 again (a held frame).
        assert_eq!(d.step(0.5, Some(&arm(50.0)), 0.0).wait, None);
        assert_eq!(d.step(0.6, Some(&arm(50.0)), 0.0).wait, None);
        // Coming down again: held.
        let s = d.step(0.7, Some(&arm(40.0)), 0.1);
        assert_eq!(s.wait, Some(Wait::Barrier(BarrierState::Moving)));
    }

    #[test]
    fn a_red_light_seen_far_off_and_then_lost_stops_the_robot_where_it_would_have() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        assert_eq!(
            d.step(0.1, Some(&lamp(LightColour::Red, 1.2)), 0.1).wait,
            None
        );
        assert_eq!(
            d.step(0.2, Some(&lamp(LightColour::Red, 1.19)), 0.1).wait,
            None
        );
        // Driving on at 0.1 m/s without seeing it: 0.34 m on, it would be 0.85 m off.
        let mut t = 0.2;
        let mut held_at = None;
        while t < 5.0 && held_at.is_none() {
            t += 0.1;
            if d.step(t, Some(&seen(0.0)), 0.1).wait.is_some() {
                held_at = Some(t);
            }
        }
        let held_at = held_at.expect("held");
        assert!((held_at - 3.6).abs() < 0.15, "{held_at}");
        for k in 1..=2 {
            let green = lamp(LightColour::Green, 0.85);
            let s = d.step(t + 0.1 * f64::from(k), Some(&green), 0.0);
            assert_eq!(s.wait.is_none(), k == 2, "{k}: {s:?}");
        }
    }

    #[test]
    fn a_green_seen_far_off_is_looked_at_again_before_the_stop_line() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        d.step(0.1, Some(&lamp(LightColour::Green, 1.6)), 0.1);
        d.step(0.2, Some(&lamp(LightColour::Green, 1.59)), 0.1);
        // Out of view from there on: at the stop point the green is 7 s old.
        let mut t = 0.2;
        let mut looked = None;
        while t < 10.0 && looked.is_none() {
            t += 0.1;
            looked = d.step(t, Some(&seen(0.0)), 0.1).wait;
        }
        assert_eq!(looked, Some(Wait::LookingForLight));
        // Seen red now: held; the light's colour decides.
        d.step(t + 0.1, Some(&lamp(LightColour::Red, 0.84)), 0.0);
        let s = d.step(t + 0.2, Some(&lamp(LightColour::Red, 0.84)), 0.0);
        assert_eq!(s.wait, Some(Wait::Light(LightColour::Red)));
    }

    #[test]
    fn a_light_remembered_before_lane_mode_is_left_does_not_stop_the_robot_after() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        d.step(0.1, Some(&lamp(LightColour::Red, 1.2)), 0.1);
        d.step(0.2, Some(&lamp(LightColour::Red, 1.19)), 0.1);
        // Lane mode entered anew, elsewhere: driving on 0.5 m sees no light to stop for.
        d.reset(10.0);
        for k in 1..=50 {
            let s = d.step(10.0 + 0.1 * f64::from(k), Some(&seen(0.0)), 0.1);
            assert_eq!(s.wait, None, "{k}");
        }
    }

    #[test]
    fn losing_the_lane_stops_after_the_timeout() {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        d.step(0.1, Some(&seen(0.0)), 0.1);
        assert!(d.step(0.5, None, 0.1).twist.linear > 0.0);
        let s = d.step(1.2, Some(&LaneSighting::default()), 0.1);
        assert_eq!((s.twist, s.wait), (Twist::ZERO, Some(Wait::LaneLost)));
    }
}
