use super::*;

fn open(_: Point2) -> bool {
    false
}

/// A wall along x = 0 with a doorway from y = -0.3 to 0.3.
fn wall_with_door(p: Point2) -> bool {
    p.x.abs() < 0.05 && p.y.abs() > 0.3
}

fn doorway(p: Point2) -> bool {
    narrow_at(p, YieldRule::default().doorway, 0.02, &wall_with_door)
}

fn peer(number: usize, x: f64, y: f64, theta: f64, linear: f64) -> Peer {
    Peer {
        number,
        pose: Pose2::new(x, y, theta),
        linear,
    }
}

#[test]
fn head_on_in_the_open_the_higher_number_yields_and_the_lower_goes() {
    let rule = YieldRule::default();
    let one = peer(1, 0.0, 0.0, 0.0, 0.2);
    let two = peer(2, 0.5, 0.0, std::f64::consts::PI, 0.2);
    let peers = [one, two];
    assert_eq!(judge(&rule, 1, one.pose, 0.2, &peers, &open), Right::Go);
    assert_eq!(
        judge(&rule, 2, two.pose, 0.2, &peers, &open),
        Right::Yield {
            to: 1,
            why: "it has the lower number"
        }
    );
}

#[test]
fn in_a_doorway_the_robot_inside_goes_whatever_its_number() {
    let rule = YieldRule::default();
    // Robot 2 is in the doorway heading out; robot 1 waits in the open room.
    let inside = peer(2, 0.0, 0.0, 0.0, 0.2);
    let outside = peer(1, 0.45, 0.05, std::f64::consts::PI, 0.2);
    assert!(doorway(inside.pose.position()) && !doorway(outside.pose.position()));
    let peers = [inside, outside];
    assert_eq!(
        judge(&rule, 1, outside.pose, 0.2, &peers, &doorway),
        Right::Yield {
            to: 2,
            why: "it is in the doorway"
        }
    );
    assert_eq!(
        judge(&rule, 2, inside.pose, 0.2, &peers, &doorway),
        Right::Go
    );
}

#[test]
fn nobody_yields_to_a_standing_robot_one_behind_or_one_far_off() {
    let rule = YieldRule::default();
    let me = peer(2, 0.0, 0.0, 0.0, 0.2);
    let judged = |other: Peer| judge(&rule, 2, me.pose, 0.2, &[me, other], &open);
    // Standing: an obstacle for the monitor and the planner.
    assert_eq!(judged(peer(1, 0.4, 0.0, 0.0, 0.0)), Right::Go);
    // Behind, moving towards me: it is its turn to give way.
    assert_eq!(judged(peer(1, -0.4, 0.0, 0.0, 0.2)), Right::Go);
    // Ahead but beyond the radius.
    assert_eq!(
        judged(peer(1, 0.7, 0.0, std::f64::consts::PI, 0.2)),
        Right::Go
    );
    // Turning on the spot, I move nowhere.
    let turning = judge(
        &rule,
        2,
        me.pose,
        0.0,
        &[me, peer(1, 0.4, 0.0, 3.1, 0.2)],
        &open,
    );
    assert_eq!(turning, Right::Go);
    // Backing towards it, it is in my way.
    let backing = judge(
        &rule,
        2,
        me.pose,
        -0.1,
        &[me, peer(1, -0.4, 0.0, 0.0, 0.2)],
        &open,
    );
    assert!(matches!(backing, Right::Yield { to: 1, .. }));
}

#[test]
fn two_robots_meeting_never_both_wait_nor_both_go() {
    // Every meeting within the radius, in the open and at a doorway: exactly one goes.
    let rule = YieldRule::default();
    let mut meetings = 0;
    for k in 0..200 {
        let a = k as f64 * 0.7;
        let (x, y) = (0.22 + 0.3 * (a * 1.3).cos().abs(), 0.2 * a.sin());
        let one = peer(1, -x / 2.0, -y / 2.0, (y).atan2(x), 0.2);
        let two = peer(2, x / 2.0, y / 2.0, (-y).atan2(-x), 0.15);
        let peers = [one, two];
        for narrow in [&open as &dyn Fn(Point2) -> bool, &doorway] {
            let first = judge(&rule, 1, one.pose, one.linear, &peers, narrow);
            let second = judge(&rule, 2, two.pose, two.linear, &peers, narrow);
            meetings += 1;
            assert!(
                (first == Right::Go) != (second == Right::Go),
                "{one:?} {two:?}: {first:?} {second:?}"
            );
        }
    }
    assert_eq!(meetings, 400);
}

#[test]
fn a_doorway_is_a_passage_narrower_than_the_rule_says() {
    assert!(doorway(Point2::new(0.0, 0.0)));
    assert!(!doorway(Point2::new(0.6, 0.0)), "the open room");
    // A wide opening is no doorway.
    let wide = |p: Point2| p.x.abs() < 0.05 && p.y.abs() > 0.6;
    assert!(!narrow_at(Point2::new(0.0, 0.0), 0.8, 0.02, &wide));
}

#[test]
fn nobody_moves_towards_a_robot_closer_than_keep_clear_even_slowly_or_standing() {
    let rule = YieldRule::default();
    let me = peer(1, 0.0, 0.0, 0.0, 0.01);
    let near = peer(2, 0.2, 0.0, 0.0, 0.0);
    let peers = [me, near];
    let too_close = Right::Yield {
        to: 2,
        why: "it is too close",
    };
    // Robot 1 has the lower number, and robot 2 stands: still it may not creep on.
    assert_eq!(judge(&rule, 1, me.pose, 0.01, &peers, &open), too_close);
    // Off to the side but drawing nearer: still too close.
    let beside = peer(2, 0.1, 0.18, 0.0, 0.0);
    let side = judge(&rule, 1, me.pose, 0.1, &[me, beside], &open);
    assert!(matches!(side, Right::Yield { to: 2, .. }), "{side:?}");
    // Away from it, or turning on the spot, it may.
    assert_eq!(judge(&rule, 1, me.pose, -0.1, &peers, &open), Right::Go);
    assert_eq!(judge(&rule, 1, me.pose, 0.0, &peers, &open), Right::Go);
}

#[test]
fn the_robot_owing_the_way_keeps_its_stopping_distance_when_closing_fast() {
    let rule = YieldRule::for_robot(0.1, 1.0);
    // Robot 3 drives at 62° off the line to robot 2, which drives at it: outside the
    // way cone, but the two close at 0.3 m/s. v·t + v²/2a = 0.06 + 0.045 m.
    let two = peer(2, 0.0, 0.0, 0.0, 0.2);
    let theta = std::f64::consts::PI - 62f64.to_radians();
    let three = peer(3, 0.3, 0.0, theta, 0.2);
    let closing = 0.2 + 0.2 * 62f64.to_radians().cos();
    let expected = 0.22 + closing * 0.2 + closing * closing / 2.0;
    assert!((rule.clearance(three.pose, 0.2, &two) - expected).abs() < 1e-9);
    let peers = [two, three];
    assert_eq!(
        judge(&rule, 3, three.pose, 0.2, &peers, &open),
        Right::Yield {
            to: 2,
            why: "it is too close"
        }
    );
    // Robot 2 has the right of way: it goes, and only one of the two waits.
    assert_eq!(judge(&rule, 2, two.pose, 0.2, &peers, &open), Right::Go);
    // The same gap with robot 2 standing and robot 3 creeping: only keep_clear holds.
    let standing = peer(2, 0.0, 0.0, 0.0, 0.0);
    assert_eq!(
        judge(&rule, 3, three.pose, 0.03, &[standing, three], &open),
        Right::Go
    );
    // Moving apart needs no room at all beyond keep_clear.
    let away = peer(2, 0.0, 0.0, std::f64::consts::PI, 0.2);
    assert!((rule.clearance(three.pose, 0.0, &away) - 0.22).abs() < 1e-9);
}
