//! Traffic lights and barriers: where they stand beside the lane and what they show at
//! twin time `t`.

use super::Track;
use crate::data::{BarrierState, LightColour};
use crate::geometry::Point2;

/// When a light shows which colour.
#[derive(Clone, Debug, PartialEq)]
pub enum LightCycle {
    /// Red, then green, then yellow, for these seconds each, round and round, starting
    /// `offset` seconds into the cycle at time 0.
    Periodic {
        red: f64,
        green: f64,
        yellow: f64,
        offset: f64,
    },
    /// Each colour for its seconds in turn; the last one stays.
    Sequence(Vec<(LightColour, f64)>),
}

impl LightCycle {
    /// The colour shown at twin time `t`.
    pub fn colour_at(&self, t: f64) -> LightColour {
        match self {
            Self::Periodic {
                red,
                green,
                yellow,
                offset,
            } => {
                let period = red + green + yellow;
                let phase = (t + offset).rem_euclid(period);
                if phase < *red {
                    LightColour::Red
                } else if phase < red + green {
                    LightColour::Green
                } else {
                    LightColour::Yellow
                }
            }
            Self::Sequence(steps) => {
                let mut end = 0.0;
                for (colour, seconds) in steps {
                    end += seconds;
                    if t < end {
                        return *colour;
                    }
                }
                steps.last().map_or(LightColour::Green, |s| s.0)
            }
        }
    }
}

/// How far past its stop line a light's post stands, metres: as a road's signal stands
/// across the junction, so a robot waiting at the line still has it in view.
pub const LIGHT_BEYOND: f64 = 0.6;

/// A traffic light on a post beside the lane, `LIGHT_BEYOND` past its stop line, its lamps
/// facing the oncoming robot.
#[derive(Clone, Debug, PartialEq)]
pub struct TrafficLight {
    /// Arc length along the lane of the stop line the robot must stop before, metres.
    pub along: f64,
    /// The post's centre.
    pub position: Point2,
    /// Direction the lamps face (back down the lane), radians.
    pub facing: f64,
    pub cycle: LightCycle,
}

impl TrafficLight {
    /// The light whose stop line is `along` metres along the lane, its post `side` metres
    /// left of the lane (negative: right), `LIGHT_BEYOND` further on.
    pub fn beside(track: &Track, along: f64, side: f64, cycle: LightCycle) -> Self {
        let (p, heading) = track.at(along + LIGHT_BEYOND);
        let (s, c) = heading.sin_cos();
        Self {
            along,
            position: Point2::new(p.x - s * side, p.y + c * side),
            facing: heading + std::f64::consts::PI,
            cycle,
        }
    }
}

/// How a barrier's arm moves: down, rising, up, lowering, for these seconds each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarrierCycle {
    pub down: f64,
    /// Seconds to rise or to lower.
    pub moving: f64,
    pub up: f64,
    /// Seconds into the cycle at time 0.
    pub offset: f64,
}

impl BarrierCycle {
    /// The arm's angle above level at twin time `t`, radians (0 down, pi/2 up).
    pub fn angle_at(&self, t: f64) -> f64 {
        let period = self.down + 2.0 * self.moving + self.up;
        let phase = (t + self.offset).rem_euclid(period);
        let half_pi = std::f64::consts::FRAC_PI_2;
        if phase < self.down {
            0.0
        } else if phase < self.down + self.moving {
            half_pi * (phase - self.down) / self.moving
        } else if phase < self.down + self.moving + self.up {
            half_pi
        } else {
            half_pi * (1.0 - (phase - self.down - self.moving - self.up) / self.moving)
        }
    }
}

/// A barrier: a post beside the lane and an arm of `span` metres that lies across the lane
/// when down and stands upright when up.
#[derive(Clone, Debug, PartialEq)]
pub struct Barrier {
    /// Arc length along the lane where the arm crosses it, metres.
    pub along: f64,
    /// The post's centre, where the arm turns.
    pub pivot: Point2,
    /// Direction the lowered arm points from the pivot, across the lane, radians.
    pub across: f64,
    pub span: f64,
    pub cycle: BarrierCycle,
}

impl Barrier {
    /// The barrier whose post stands `side` metres left of the lane (negative: right) at
    /// `along`, its arm reaching across the lane.
    pub fn beside(track: &Track, along: f64, side: f64, span: f64, cycle: BarrierCycle) -> Self {
        let (p, heading) = track.at(along);
        let (s, c) = heading.sin_cos();
        let half_pi = std::f64::consts::FRAC_PI_2;
        Self {
            along,
            pivot: Point2::new(p.x - s * side, p.y + c * side),
            across: if side < 0.0 {
                heading + half_pi
            } else {
                heading - half_pi
            },
            span,
            cycle,
        }
    }

    /// The arm's angle above level at `t`, radians.
    pub fn angle_at(&self, t: f64) -> f64 {
        self.cycle.angle_at(t)
    }

    /// The state the arm is in at `t` (seed 000 §3.2.3's bands).
    pub fn state_at(&self, t: f64) -> BarrierState {
        BarrierState::of_angle(self.angle_at(t).to_degrees())
    }

    /// The part of the arm's floor shadow lower than `height` at `t`: from the pivot to
    /// the point where the arm rises past `height`, as the footprint meets it.
    pub fn low_reach(&self, t: f64, height: f64) -> (Point2, Point2) {
        let a = self.angle_at(t);
        // Along the arm, the height is ARM_HEIGHT + r sin(a); it is under `height` for
        // r < (height - ARM_HEIGHT) / sin(a).
        let rise = height - super::ARM_HEIGHT;
        let r = if a.sin() < 1e-9 {
            self.span
        } else {
            (rise / a.sin()).clamp(0.0, self.span)
        };
        let reach = r * a.cos();
        let (s, c) = self.across.sin_cos();
        let end = Point2::new(self.pivot.x + c * reach, self.pivot.y + s * reach);
        (self.pivot, end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_periodic_light_goes_red_green_yellow() {
        let c = LightCycle::Periodic {
            red: 5.0,
            green: 4.0,
            yellow: 1.0,
            offset: 0.0,
        };
        let at = |t| c.colour_at(t);
        assert_eq!(
            [at(0.0), at(5.5), at(9.5), at(10.1)],
            [
                LightColour::Red,
                LightColour::Green,
                LightColour::Yellow,
                LightColour::Red
            ]
        );
        let s = LightCycle::Sequence(vec![(LightColour::Red, 3.0), (LightColour::Green, 1.0)]);
        assert_eq!(s.colour_at(2.0), LightColour::Red);
        assert_eq!(s.colour_at(99.0), LightColour::Green);
    }

    #[test]
    fn a_barrier_rises_and_falls() {
        let c = BarrierCycle {
            down: 4.0,
            moving: 2.0,
            up: 4.0,
            offset: 0.0,
        };
        let deg = |t: f64| c.angle_at(t).to_degrees();
        assert!(deg(1.0).abs() < 1e-9);
        assert!((deg(5.0) - 45.0).abs() < 1e-9);
        assert!((deg(8.0) - 90.0).abs() < 1e-9);
        assert!((deg(11.0) - 45.0).abs() < 1e-9);
    }

    #[test]
    fn a_raised_arm_leaves_the_lane_free() {
        let c = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)].map(|(x, y)| Point2::new(x, y));
        let track = Track::new(&c, 0.4, 0.02, false, 0.1).unwrap();
        let cycle = BarrierCycle {
            down: 4.0,
            moving: 2.0,
            up: 4.0,
            offset: 0.0,
        };
        let b = Barrier::beside(&track, 1.0, -0.3, 0.6, cycle);
        assert!((b.pivot.x - 1.0).abs() < 1e-9 && (b.pivot.y + 0.3).abs() < 1e-9);
        let (_, end) = b.low_reach(0.0, 0.2);
        assert!((end.y - 0.3).abs() < 1e-9, "down: across the lane, {end:?}");
        let (_, end) = b.low_reach(8.0, 0.2);
        assert!((end.y + 0.3).abs() < 1e-9, "up: at the post, {end:?}");
    }
}
