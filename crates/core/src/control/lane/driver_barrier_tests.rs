//! The lane driver's tests of barriers seen opening, remembered and crossed.
use super::*;

/// Lane mode entered at 0 s with an arm read lying down 0.8 m off in two frames and then
/// out of view: driven at 0.1 m/s until it holds the robot for that arm, when it returns.
fn held_for_an_arm_read_short(d: &mut LaneDriver) -> f64 {
    d.reset(0.0);
    let misread = barrier_at(BarrierState::Down, 5.0, 0.8);
    d.step(0.05, Some(&misread), 0.1);
    d.step(0.1, Some(&misread), 0.1);
    let (held, t) = drive_until_held(d, 0.1).expect("held");
    assert_eq!(held, Wait::Barrier(BarrierState::Up));
    t
}

/// How many of `speeds` are `v`.
fn steps_at(speeds: &[f64], v: f64) -> usize {
    speeds.iter().filter(|&&s| (s - v).abs() < 1e-9).count()
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
    // Read 0.8 m off, it stands 1.5 m off.
    let t = held_for_an_arm_read_short(&mut d);
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
    let held_at = held_for_an_arm_read_short(&mut d);
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
    let fast = steps_at(&speeds, crossing);
    assert!((40..=41).contains(&fast), "{fast}: {speeds:?}");
    assert!((speeds.last().unwrap() - lane).abs() < 1e-9, "{speeds:?}");
}

#[test]
fn a_remembered_arm_is_crossed_fast_as_far_as_it_may_stand() {
    let cfg = LaneDriveConfig::default();
    let (stop, crossing) = (cfg.barrier_stop_range, cfg.crossing_speed);
    let mut d = LaneDriver::new(cfg);
    // Held where the reckoning puts the arm at the stopping range, though an arm read so
    // may stand three stopping ranges off.
    let t = held_for_an_arm_read_short(&mut d);
    for (k, a) in [0.0, 0.0, 15.0, 30.0, 50.0].into_iter().enumerate() {
        let s = barrier_at(BarrierState::of_angle(a), a, 1.2);
        d.step(t + 0.1 * (k + 1) as f64, Some(&s), 0.0);
    }
    // Fast for 3 x 0.55 m and 0.3 m more: 97-98 steps of 2 cm.
    let speeds = speeds_over(&mut d, t + 0.5, 2.5);
    let fast = steps_at(&speeds, crossing);
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
