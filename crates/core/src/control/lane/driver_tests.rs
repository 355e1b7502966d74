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

#[test]
fn an_arm_seen_opening_and_then_standing_raised_beyond_the_stopping_range_is_passed() {
    let mut d = LaneDriver::new(LaneDriveConfig::default());
    d.reset(0.0);
    rise_from_level(&mut d);
    assert_eq!(d.step(0.5, Some(&arm(50.0)), 0.0).wait, None);
    // Raised, its range reading 0.7 m for two seconds while the robot creeps on, then out
    // of view above the picture: the robot drives under it.
    let mut t = 0.5;
    for _ in 0..20 {
        t += 0.1;
        let raised = barrier_at(BarrierState::Up, 80.0, 0.7);
        assert_eq!(d.step(t, Some(&raised), 0.1).wait, None, "{t}");
    }
    for _ in 0..40 {
        t += 0.1;
        assert_eq!(d.step(t, Some(&seen(0.0)), 0.1).wait, None, "{t}");
    }
}

#[test]
fn one_misread_frame_of_an_arm_at_the_robot_does_not_hold_it() {
    let mut d = LaneDriver::new(LaneDriveConfig::default());
    d.reset(0.0);
    // A raised arm 1.6 m off, one frame read 6 cm off and then lost, the pipeline
    // repeating that reading while its filter still tracks the arm.
    for (k, (range, fresh)) in [(1.66, true), (1.65, true), (1.62, true), (0.06, true)]
        .into_iter()
        .chain([(0.06, false); 20])
        .enumerate()
    {
        let mut s = barrier_at(BarrierState::Up, 80.0, range);
        s.barrier.as_mut().unwrap().fresh = fresh;
        let step = d.step(0.1 * (k + 1) as f64, Some(&s), 0.1);
        assert_eq!(step.wait, None, "{k}: {range}");
    }
}

#[test]
fn an_arm_seen_only_while_moving_is_not_remembered_where_its_range_reads() {
    let mut d = LaneDriver::new(LaneDriveConfig::default());
    d.reset(0.0);
    // Rising at 30-58 degrees, read about 1 m off (truly 2.3 m), then out of view.
    for (k, (a, r)) in [(30.0, 1.1), (44.0, 0.97), (58.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let s = barrier_at(BarrierState::Moving, a, r);
        assert_eq!(
            d.step(0.1 * (k + 1) as f64, Some(&s), 0.1).wait,
            None,
            "{a}"
        );
    }
    let mut t = 0.3;
    while t < 10.0 {
        t += 0.1;
        assert_eq!(d.step(t, Some(&seen(0.0)), 0.1).wait, None, "{t}");
    }
}

#[test]
fn an_arm_remembered_short_of_where_it_stands_is_waited_for_wherever_it_is_seen_next() {
    let mut d = LaneDriver::new(LaneDriveConfig::default());
    d.reset(0.0);
    // Read lying down 0.8 m off twice (it stands 1.5 m off), then out of view.
    let misread = barrier_at(BarrierState::Down, 5.0, 0.8);
    d.step(0.05, Some(&misread), 0.1);
    d.step(0.1, Some(&misread), 0.1);
    let (held, t) = drive_until_held(&mut d, 0.1).expect("held");
    assert_eq!(held, Wait::Barrier(BarrierState::Up));
    // The arm itself, 1.2 m off, past the reach of a robot waiting at a barrier it ranged:
    // seen lying down, then rising. That opening is the robot's.
    for (k, a) in [0.0, 0.0, 15.0, 30.0].into_iter().enumerate() {
        let s = barrier_at(BarrierState::of_angle(a), a, 1.2);
        let step = d.step(t + 0.1 * (k + 1) as f64, Some(&s), 0.0);
        assert!(step.wait.is_some(), "{a}: {step:?}");
    }
    let far = barrier_at(BarrierState::Moving, 50.0, 1.2);
    assert_eq!(d.step(t + 0.5, Some(&far), 0.0).wait, None);
}

#[test]
fn an_arm_remembered_ahead_and_never_seen_again_is_waited_for_only_the_patience() {
    let cfg = LaneDriveConfig::default();
    let patience = cfg.unseen_arm_patience;
    let mut d = LaneDriver::new(cfg);
    d.reset(0.0);
    let ahead = barrier_at(BarrierState::Down, 5.0, 0.8);
    d.step(0.05, Some(&ahead), 0.1);
    d.step(0.1, Some(&ahead), 0.1);
    let (_, held_at) = drive_until_held(&mut d, 0.1).expect("held");
    let mut t = held_at;
    // Nothing in view: held until the patience runs out, then on its way for good.
    let mut freed = None;
    while t < held_at + 2.0 * patience && freed.is_none() {
        t += 0.1;
        freed = d.step(t, Some(&seen(0.0)), 0.0).wait.is_none().then_some(t);
    }
    let freed = freed.expect("freed");
    assert!(
        (freed - held_at - patience).abs() < 0.15,
        "{held_at} {freed}"
    );
    assert_eq!(d.step(t + 0.1, Some(&seen(0.0)), 0.1).wait, None);
    // An arm then met closed near still holds it.
    let near = barrier_at(BarrierState::Down, 2.0, 0.5);
    d.step(t + 0.2, Some(&near), 0.1);
    let s = d.step(t + 0.3, Some(&near), 0.1);
    assert_eq!(s.wait, Some(Wait::Barrier(BarrierState::Down)));
}

/// Drives on from `t` at the speed commanded, a centred lane and a frame every 0.1 s,
/// until `far` metres are behind: the speeds commanded (none of them a wait).
fn speeds_over(d: &mut LaneDriver, mut t: f64, far: f64) -> Vec<f64> {
    let mut driven = 0.0;
    let mut speeds: Vec<f64> = Vec::new();
    while driven < far {
        t += 0.1;
        let v = speeds.last().copied().unwrap_or(0.0);
        let s = d.step(t, Some(&seen(0.0)), v);
        assert_eq!(s.wait, None, "{t}");
        driven += 0.1 * v;
        speeds.push(s.twist.linear);
    }
    speeds
}

#[test]
fn an_opened_barrier_is_crossed_at_the_crossing_speed_and_lane_speed_follows() {
    let cfg = LaneDriveConfig::default();
    let (lane, crossing) = (cfg.max_speed, cfg.crossing_speed);
    let mut d = LaneDriver::new(cfg);
    d.reset(0.0);
    rise_from_level(&mut d);
    let speeds = speeds_over(&mut d, 0.4, 1.5);
    // Fast until past the arm (0.5 m ahead, and 0.3 m more: 40 steps of 2 cm), then lane
    // speed again.
    let fast = speeds
        .iter()
        .filter(|&&v| (v - crossing).abs() < 1e-9)
        .count();
    assert!((40..=41).contains(&fast), "{fast}: {speeds:?}");
    assert!((speeds.last().unwrap() - lane).abs() < 1e-9, "{speeds:?}");
}

#[test]
fn a_remembered_arm_is_crossed_fast_as_far_as_it_may_stand() {
    let cfg = LaneDriveConfig::default();
    let (stop, crossing) = (cfg.barrier_stop_range, cfg.crossing_speed);
    let mut d = LaneDriver::new(cfg);
    d.reset(0.0);
    // Read lying down 0.8 m off, then out of view: held where the reckoning puts it at the
    // stopping range, though an arm read so may stand three stopping ranges off.
    let misread = barrier_at(BarrierState::Down, 5.0, 0.8);
    d.step(0.05, Some(&misread), 0.1);
    d.step(0.1, Some(&misread), 0.1);
    let (_, t) = drive_until_held(&mut d, 0.1).expect("held");
    for (k, a) in [0.0, 0.0, 15.0, 30.0, 50.0].into_iter().enumerate() {
        let s = barrier_at(BarrierState::of_angle(a), a, 1.2);
        d.step(t + 0.1 * (k + 1) as f64, Some(&s), 0.0);
    }
    // Fast for 3 x 0.55 m and 0.3 m more: 97-98 steps of 2 cm.
    let speeds = speeds_over(&mut d, t + 0.5, 2.5);
    let fast = speeds
        .iter()
        .filter(|&&v| (v - crossing).abs() < 1e-9)
        .count();
    let expected = ((3.0 * stop + 0.3) / (0.1 * crossing)) as usize;
    assert!(fast.abs_diff(expected) <= 1, "{fast}: {speeds:?}");
}

#[test]
fn an_arm_down_beyond_the_one_being_crossed_stops_the_robot_at_its_own_stopping_range() {
    let cfg = LaneDriveConfig::default();
    let stop = cfg.barrier_stop_range;
    let mut d = LaneDriver::new(cfg);
    d.reset(0.0);
    rise_from_level(&mut d);
    // Crossing: the next arm, 1.4 m on, lies down in two frames, then rises out of view.
    let next = barrier_at(BarrierState::Down, 2.0, 1.4);
    d.step(0.5, Some(&next), 0.0);
    assert_eq!(d.step(0.6, Some(&next), 0.0).wait, None);
    let (mut t, mut driven) = (0.6, 0.0);
    let held = loop {
        t += 0.1;
        let s = d.step(t, Some(&seen(0.0)), 0.2);
        driven += 0.02;
        if let Some(wait) = s.wait {
            break wait;
        }
        assert!(driven < 2.0, "never held");
    };
    assert_eq!(held, Wait::Barrier(BarrierState::Up));
    assert!((driven - (1.4 - stop)).abs() < 0.03, "{driven}");
}
