//! The traffic light ahead as the robot approaches it: a colour believed only once two
//! frames agree on it and on where the lamp stands, its range carried on by the distance
//! driven while it is out of view, and the stop line passed only on a green seen lately;
//! once the robot can no longer stop before the line, the light no longer stops it until
//! it has driven by.

use crate::data::{LightColour, LightSeen};

/// Most seconds between the two sightings that confirm a light.
const CONFIRM_GAP: f64 = 1.0;
/// How far apart, metres plus a share of the range, two sightings of one lamp may put it
/// once the distance driven between them is taken off: a lamp's range from its row is
/// good to a few per cent, and a red blob whose range jumps (a barrier's stripe cut by the
/// picture's edge) is not a lamp standing still.
const CONFIRM_METRES: f64 = 0.05;
const CONFIRM_SHARE: f64 = 0.05;
/// A green seen longer ago than this, seconds, is stale at the stop point: the light may
/// have turned (a yellow lasts a few seconds), so the robot stops and looks again.
pub const GREEN_FRESH: f64 = 1.0;
/// Metres past the stop line, by the robot's reckoning, after which a light that turns no
/// longer stops the robot: at lane speed it stops within a centimetre, so before the line
/// it can always stop, and a lamp's distance along the lane reads up to a tenth of a metre
/// short (a robot 0.15 m before the line reckoned itself 0.04 m before it and drove
/// through a late yellow as it turned red).
const LINE_MARGIN: f64 = 0.05;
/// Metres past the lamp, measured from the stop point, after which the light is behind.
const PASS_MARGIN: f64 = 0.3;

/// A green the robot went on at: how far along the lane the lamp now is, and how far
/// the robot has still to drive to be past the light.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Commit {
    ahead: f64,
    left: f64,
}

/// One lamp as seen at `seen_at`, its range and how far along the lane it stands since
/// shortened by the distance driven.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sighting {
    colour: LightColour,
    range: f64,
    ahead: f64,
    seen_at: f64,
}

/// What the light ahead asks of the robot now.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum LightCall {
    /// Nothing: no light near, or a green passed on.
    Go,
    /// A red or yellow at the stop point.
    Stop(LightColour),
    /// At the stop point with only a stale green: look again before crossing.
    Look,
}

/// See the module comment.
#[derive(Clone, Debug, Default)]
pub(super) struct LightWatch {
    /// A sighting not yet confirmed by a second one.
    pending: Option<Sighting>,
    /// The confirmed light ahead.
    ahead: Option<Sighting>,
    /// Past the stop point on a fresh green: the light is no longer looked for.
    committed: Option<Commit>,
}

impl LightWatch {
    /// The robot drove `metres` since the last step: every lamp is that much nearer, and
    /// one driven past is forgotten.
    pub(super) fn drive(&mut self, metres: f64) {
        let metres = metres.max(0.0);
        for s in [&mut self.pending, &mut self.ahead] {
            if let Some(seen) = s {
                seen.range -= metres;
                seen.ahead -= metres;
            }
            if s.is_some_and(|seen| seen.range < 0.0) {
                *s = None;
            }
        }
        if let Some(c) = &mut self.committed {
            c.ahead -= metres;
            c.left -= metres;
        }
        if self.committed.is_some_and(|c| c.left < 0.0) {
            self.committed = None;
        }
    }

    /// Takes a lamp seen at `t` beside a lane of `curvature` (1/m, + left); a light
    /// farther off than `reach` may be another stretch's and is not taken.
    pub(super) fn see(&mut self, t: f64, light: &LightSeen, curvature: f64, reach: f64, line: f64) {
        if light.range > reach {
            return;
        }
        let now = Sighting {
            colour: light.colour,
            range: light.range,
            ahead: along_lane(light.ahead, light.left, curvature),
            seen_at: t,
        };
        let agrees = |before: &Sighting| {
            before.colour == now.colour
                && t - before.seen_at <= CONFIRM_GAP
                && (now.range - before.range).abs() <= CONFIRM_METRES + CONFIRM_SHARE * now.range
        };
        // A confirmed light seen again as it was needs no second look.
        if self.pending.as_ref().is_some_and(agrees) || self.ahead.as_ref().is_some_and(agrees) {
            // A light that turns before the robot is well on its way is obeyed afresh.
            let turned = self.ahead.is_some_and(|a| a.colour != now.colour);
            if turned && self.committed.is_some_and(|c| c.ahead > line - LINE_MARGIN) {
                self.committed = None;
            }
            self.ahead = Some(now);
        }
        self.pending = Some(now);
    }

    /// What the light asks of the robot at `t` with the stop point `stop_range` from the
    /// lamp and the stop line `line` before the lamp (along the robot's heading).
    pub(super) fn call(&mut self, t: f64, stop_range: f64, line: f64) -> LightCall {
        if self
            .committed
            .is_some_and(|c| c.ahead <= line - LINE_MARGIN)
        {
            return LightCall::Go;
        }
        let Some(ahead) = self.ahead.filter(|a| a.range <= stop_range) else {
            return LightCall::Go;
        };
        if ahead.colour.stops() {
            return LightCall::Stop(ahead.colour);
        }
        if self.committed.is_some() || t - ahead.seen_at <= GREEN_FRESH {
            self.committed.get_or_insert(Commit {
                ahead: ahead.ahead,
                left: ahead.range + PASS_MARGIN,
            });
            return LightCall::Go;
        }
        LightCall::Look
    }
}

/// How far along a lane of `curvature` (1/m, + left) the robot drives to come abreast of
/// a point `ahead` of it and `left` of it: on a circle of radius 1/k about (0, 1/k) the
/// point lies atan2(k x, 1 - k y) round from the robot, that angle over k along the arc
/// (and simply `ahead` on a straight). In a bend a lamp beside the lane is nearer ahead
/// than along: 0.6 m along and 0.4 m inside a bend of radius 1 m is 0.34 m ahead.
pub(super) fn along_lane(ahead: f64, left: f64, curvature: f64) -> f64 {
    if curvature.abs() < 1e-6 {
        return ahead;
    }
    (curvature * ahead).atan2(1.0 - curvature * left) / curvature
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stop line 0.6 m before the lamp.
    const LINE: f64 = 0.6;

    /// The lamp `range` off, 0.4 m aside.
    fn lamp(colour: LightColour, range: f64) -> LightSeen {
        LightSeen {
            colour,
            range,
            ahead: (range * range - 0.16).max(0.0).sqrt(),
            left: 0.4,
            confidence: 0.9,
        }
    }

    #[test]
    fn one_frame_is_not_believed_and_two_that_agree_are() {
        let mut w = LightWatch::default();
        w.see(0.0, &lamp(LightColour::Red, 0.8), 0.0, 1.7, LINE);
        assert_eq!(w.call(0.0, 0.85, LINE), LightCall::Go);
        w.drive(0.01);
        w.see(0.1, &lamp(LightColour::Red, 0.8), 0.0, 1.7, LINE);
        assert_eq!(w.call(0.1, 0.85, LINE), LightCall::Stop(LightColour::Red));
    }

    #[test]
    fn a_red_blob_whose_range_jumps_is_not_a_lamp() {
        let mut w = LightWatch::default();
        // A barrier's stripe leaving the picture: 1.23 m, 1.39, 1.59, 1.89 while the
        // robot creeps 1 cm a frame.
        for (k, r) in [1.23, 1.39, 1.59, 1.89].into_iter().enumerate() {
            w.drive(0.01);
            w.see(0.1 * k as f64, &lamp(LightColour::Red, r), 0.0, 1.7, LINE);
        }
        w.drive(1.5);
        assert_eq!(w.call(0.5, 0.85, LINE), LightCall::Go);
    }

    #[test]
    fn a_green_seen_far_off_is_looked_at_again_at_the_stop_point_and_then_passed() {
        let mut w = LightWatch::default();
        w.see(0.0, &lamp(LightColour::Green, 1.6), 0.0, 1.7, LINE);
        w.drive(0.01);
        w.see(0.1, &lamp(LightColour::Green, 1.59), 0.0, 1.7, LINE);
        // Out of view for 7.5 s at 0.1 m/s: at the stop point the green is stale.
        let mut t = 0.1;
        while t < 7.7 {
            t += 0.1;
            w.drive(0.01);
        }
        assert_eq!(w.call(t, 0.85, LINE), LightCall::Look);
        // One frame of it is not yet believed; two are.
        w.see(t + 0.1, &lamp(LightColour::Green, 0.83), 0.0, 1.7, LINE);
        assert_eq!(w.call(t + 0.1, 0.85, LINE), LightCall::Look);
        w.see(t + 0.2, &lamp(LightColour::Green, 0.83), 0.0, 1.7, LINE);
        assert_eq!(w.call(t + 0.2, 0.85, LINE), LightCall::Go);
        // Just past the stop point on that green, the light seen turning is still obeyed.
        w.drive(0.05);
        w.see(t + 0.7, &lamp(LightColour::Yellow, 0.78), 0.0, 1.7, LINE);
        w.see(t + 0.8, &lamp(LightColour::Yellow, 0.78), 0.0, 1.7, LINE);
        assert_eq!(
            w.call(t + 0.8, 0.85, LINE),
            LightCall::Stop(LightColour::Yellow)
        );
    }

    #[test]
    fn a_light_that_turns_once_the_robot_is_past_its_line_does_not_stop_it_there() {
        let mut w = LightWatch::default();
        w.see(0.0, &lamp(LightColour::Green, 0.84), 0.0, 1.7, LINE);
        w.see(0.1, &lamp(LightColour::Green, 0.84), 0.0, 1.7, LINE);
        assert_eq!(w.call(0.1, 0.85, LINE), LightCall::Go);
        // 0.25 m on, beside the post: it turns yellow, then red, and leaves the view.
        w.drive(0.25);
        for k in 0..4 {
            let colour = if k < 2 {
                LightColour::Yellow
            } else {
                LightColour::Red
            };
            w.see(2.6 + 0.1 * f64::from(k), &lamp(colour, 0.6), 0.0, 1.7, LINE);
            assert_eq!(
                w.call(2.6 + 0.1 * f64::from(k), 0.85, LINE),
                LightCall::Go,
                "{k}"
            );
        }
        // Driven by it, the next light is obeyed as ever.
        w.drive(1.0);
        w.see(13.0, &lamp(LightColour::Red, 0.8), 0.0, 1.7, LINE);
        w.see(13.1, &lamp(LightColour::Red, 0.8), 0.0, 1.7, LINE);
        assert_eq!(w.call(13.1, 0.85, LINE), LightCall::Stop(LightColour::Red));
    }

    /// A lamp `along` metres along a bend of curvature `k` (+ left), `inside` metres
    /// towards the bend's centre, as the camera reads it.
    fn lamp_in_bend(colour: LightColour, along: f64, inside: f64, k: f64) -> LightSeen {
        let (r, phi) = (1.0 / k.abs() - inside, along * k.abs());
        let (ahead, aside) = (r * phi.sin(), 1.0 / k.abs() - r * phi.cos());
        LightSeen {
            colour,
            range: ahead.hypot(aside),
            ahead,
            left: aside * k.signum(),
            confidence: 0.9,
        }
    }

    #[test]
    fn a_lamp_beside_a_bend_is_as_far_along_the_lane_as_it_stands() {
        for k in [-2.0, -1.0, 1.0, 2.0] {
            for inside in [-0.4, 0.0, 0.4] {
                let seen = lamp_in_bend(LightColour::Red, 0.6, inside, k);
                let along = along_lane(seen.ahead, seen.left, k);
                assert!((along - 0.6).abs() < 1e-9, "{k} {inside}: {along}");
            }
        }
        assert_eq!(along_lane(0.7, 0.4, 0.0), 0.7);
    }

    #[test]
    fn a_light_turning_in_a_bend_before_the_line_stops_the_robot() {
        // 0.15 m before the line of a lamp 0.4 m inside a bend of radius 1 m: 0.41 m
        // ahead, 0.75 m along.
        let mut w = LightWatch::default();
        for (k, colour) in [LightColour::Green, LightColour::Green]
            .into_iter()
            .enumerate()
        {
            let t = 0.1 * k as f64;
            w.see(t, &lamp_in_bend(colour, 0.75, 0.4, 1.0), 1.0, 1.7, LINE);
            assert_eq!(w.call(t, 0.85, LINE), LightCall::Go);
        }
        for t in [0.2, 0.3] {
            w.see(
                t,
                &lamp_in_bend(LightColour::Yellow, 0.75, 0.4, 1.0),
                1.0,
                1.7,
                LINE,
            );
        }
        assert_eq!(
            w.call(0.3, 0.85, LINE),
            LightCall::Stop(LightColour::Yellow)
        );
    }

    #[test]
    fn a_light_driven_past_is_forgotten() {
        let mut w = LightWatch::default();
        w.see(0.0, &lamp(LightColour::Red, 1.0), 0.0, 1.7, LINE);
        w.see(0.1, &lamp(LightColour::Red, 1.0), 0.0, 1.7, LINE);
        w.drive(1.1);
        assert_eq!(w.call(0.2, 0.85, LINE), LightCall::Go);
    }
}
