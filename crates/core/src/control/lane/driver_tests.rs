//! The lane driver's tests: lane following's gains, and the holds for lights and arms.
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
            ahead: (range * range - 0.16).max(0.0).sqrt(),
            left: 0.4,
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
    let barrier = |state| barrier_at(state, 0.0, 0.5);
    // One frame is not yet believed; the second, agreeing on where it stands, is.
    let once = d.step(0.05, Some(&barrier(BarrierState::Moving)), 0.1);
    assert_eq!(once.wait, None);
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
    d.step(0.05, Some(&arm(85.0)), 0.1);
    let up = d.step(0.1, Some(&arm(85.0)), 0.1);
    assert_eq!(up.wait, Some(Wait::Barrier(BarrierState::Up)));
    // Still up a frame later: how long it stays up is still unknown.
    let still = d.step(0.15, Some(&arm(85.0)), 0.0);
    assert_eq!(still.wait, Some(Wait::Barrier(BarrierState::Up)));
    // Read moving and then raised again (what is left in the picture of an arm standing
    // up, merged with one farther on): not an opening.
    d.step(0.2, Some(&arm(67.0)), 0.0);
    let merged = d.step(0.3, Some(&arm(76.0)), 0.0);
    assert_eq!(merged.wait, Some(Wait::Barrier(BarrierState::Up)));
    // Seen lying down, then raised: that is an opening.
    d.step(0.4, Some(&arm(40.0)), 0.0);
    let down = d.step(0.5, Some(&arm(2.0)), 0.0);
    assert_eq!(down.wait, Some(Wait::Barrier(BarrierState::Down)));
    assert_eq!(d.step(0.6, Some(&arm(85.0)), 0.0).wait, None);
}

#[test]
fn an_arm_seen_ahead_and_then_lost_above_the_picture_holds_the_robot_at_the_stopping_range() {
    // Met up, or met down and rising out of view before the robot reached it.
    for first in [85.0, 0.0] {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        let ahead = barrier_at(BarrierState::of_angle(first), first, 0.8);
        d.step(0.05, Some(&ahead), 0.0);
        assert_eq!(d.step(0.1, Some(&ahead), 0.1).wait, None, "{first}");
        // Out of view from here at 0.1 m/s: 0.25 m on it is 0.55 m off.
        let (wait, t) = drive_until_held(&mut d, 0.1).expect("held");
        assert_eq!(wait, Wait::Barrier(BarrierState::Up), "{first}");
        assert!((t - 2.6).abs() < 0.15, "{first}: {t}");
        // It comes down (read 0.6 m off, past the stopping range) and rises again: that
        // opening is the robot's.
        for (k, a) in [40.0, 10.0, 0.0, 0.0, 12.0, 30.0].into_iter().enumerate() {
            let s = barrier_at(BarrierState::of_angle(a), a, 0.6);
            let step = d.step(t + 0.1 * (k + 1) as f64, Some(&s), 0.0);
            assert!(step.wait.is_some(), "{first} then {a}: {step:?}");
        }
        assert_eq!(d.step(t + 0.7, Some(&arm(50.0)), 0.0).wait, None, "{first}");
    }
}

#[test]
fn another_barrier_rising_down_the_track_is_not_the_opening_of_the_one_ahead() {
    // 2.5 m on, past two stopping ranges; 0.9 m on, inside them but more than 0.3 m past
    // the arm waited for (0.5 m off).
    for range in [2.5, 0.9] {
        let mut d = LaneDriver::new(LaneDriveConfig::default());
        d.reset(0.0);
        for k in 1..=3 {
            d.step(0.1 * f64::from(k), Some(&arm(2.0)), 0.0);
        }
        // The arm ahead is out of view; the other one rises from level to 60 degrees.
        for (k, a) in [0.0, 0.0, 20.0, 40.0, 60.0].into_iter().enumerate() {
            let far = barrier_at(BarrierState::of_angle(a), a, range);
            let s = d.step(0.4 + 0.1 * k as f64, Some(&far), 0.0);
            assert_eq!(
                s.wait,
                Some(Wait::Barrier(BarrierState::Down)),
                "{range} {a}"
            );
        }
    }
}

/// A centred lane with an arm in `state` at `angle_deg`, `range` metres ahead.
fn barrier_at(state: BarrierState, angle_deg: f64, range: f64) -> LaneSighting {
    let mut belief = [0.0; 3];
    belief[state as usize] = 1.0;
    LaneSighting {
        barrier: Some(BarrierSeen {
            state,
            angle_deg,
            range,
            belief,
            fresh: true,
        }),
        ..seen(0.0)
    }
}

/// An arm 0.5 m ahead seen level and rising to 46 degrees, a frame every 0.1 s to 0.4 s.
fn rise_from_level(d: &mut LaneDriver) {
    for (i, a) in [0.0, 10.0, 30.0, 46.0].into_iter().enumerate() {
        d.step(0.1 * (i + 1) as f64, Some(&arm(a)), 0.0);
    }
}

/// Steps a centred lane with nothing else in view from `t`, at 0.1 m/s, a frame every
/// 0.1 s up to 5 s: the first wait and when it began.
fn drive_until_held(d: &mut LaneDriver, mut t: f64) -> Option<(Wait, f64)> {
    while t < 5.0 {
        t += 0.1;
        if let Some(wait) = d.step(t, Some(&seen(0.0)), 0.1).wait {
            return Some((wait, t));
        }
    }
    None
}

/// A centred lane with an arm at `angle_deg` 0.5 m ahead, in the state of its angle.
fn arm(angle_deg: f64) -> LaneSighting {
    barrier_at(BarrierState::of_angle(angle_deg), angle_deg, 0.5)
}

#[test]
fn an_arm_seen_rising_out_of_the_picture_is_an_opening_and_one_lowering_is_not() {
    let mut d = LaneDriver::new(LaneDriveConfig::default());
    d.reset(0.0);
    d.step(0.05, Some(&arm(2.0)), 0.0);
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
    rise_from_level(&mut d);
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

#[path = "driver_barrier_tests.rs"]
mod barrier;
