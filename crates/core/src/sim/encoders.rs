//! Wheel encoders: integer counts per wheel with multiplicative noise and occasional slip.
//!
//! Slip is modelled on the ground, not in the count: in a slipping physics step the wheel
//! turns by its full amount (and the encoder counts all of it) while that wheel's contact
//! point advances only `1 - slip_fraction` of it, so the robot really moves less than the
//! odometry says. That is the drift an estimator has to correct with landmarks.

use super::config::EncoderConfig;
use crate::data::WheelTravel;
use crate::data::robot::RobotConfig;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use std::f64::consts::PI;

/// What one physics step does to the two wheels (left, right), metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelStep {
    /// How far each wheel's contact point really moved over the floor.
    pub ground: [f64; 2],
    /// What each encoder will add when the step is taken, before quantisation.
    pub measured: [f64; 2],
}

#[derive(Clone, Debug)]
pub struct Encoders {
    /// Wheel circumference over counts per turn: 2 pi r / ticks.
    metres_per_tick: f64,
    noise_std: f64,
    slip_probability: f64,
    slip_fraction: f64,
    /// Continuous encoder position in ticks; the count is its floor.
    position: [f64; 2],
    /// Counts at the previous `take`.
    reported: [i64; 2],
}

impl Encoders {
    pub fn new(robot: &RobotConfig, cfg: &EncoderConfig) -> Self {
        Self {
            metres_per_tick: 2.0 * PI * robot.wheel_radius / f64::from(cfg.ticks_per_rev.max(1)),
            noise_std: cfg.noise_std.max(0.0),
            slip_probability: cfg.slip_probability.clamp(0.0, 1.0),
            slip_fraction: cfg.slip_fraction.clamp(0.0, 1.0),
            position: [0.0; 2],
            reported: [0; 2],
        }
    }

    /// Draws slip and noise for one step in which the wheels turn by `turned` metres of rim.
    /// A wheel that does not turn draws nothing.
    pub fn sample(&self, rng: &mut ChaCha8Rng, turned: [f64; 2]) -> WheelStep {
        let mut step = WheelStep {
            ground: turned,
            measured: turned,
        };
        for (k, &turn) in turned.iter().enumerate() {
            if turn == 0.0 {
                continue;
            }
            if self.slip_probability > 0.0 && rng.random::<f64>() < self.slip_probability {
                step.ground[k] = turn * (1.0 - self.slip_fraction);
            }
            if self.noise_std > 0.0 {
                let n: f64 = rng.sample(StandardNormal);
                // Multiplicative odometry noise: navdeck reads seed 001's motor_std as
                // growing with travel.
                step.measured[k] = turn * (1.0 + self.noise_std * n);
            }
        }
        step
    }

    /// Adds a taken step's measured travel to the encoder positions.
    pub fn commit(&mut self, step: &WheelStep) {
        for (pos, m) in self.position.iter_mut().zip(step.measured) {
            *pos += m / self.metres_per_tick;
        }
    }

    /// Travel since the previous take, from whole counts; fractions of a tick carry over.
    pub fn take(&mut self) -> WheelTravel {
        let mut travel = [0.0; 2];
        for (k, out) in travel.iter_mut().enumerate() {
            let count = self.position[k].floor() as i64;
            *out = (count - self.reported[k]) as f64 * self.metres_per_tick;
            self.reported[k] = count;
        }
        WheelTravel {
            left: travel[0],
            right: travel[1],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn quiet() -> Encoders {
        let cfg = EncoderConfig {
            noise_std: 0.0,
            slip_probability: 0.0,
            ..EncoderConfig::default()
        };
        Encoders::new(&RobotConfig::default(), &cfg)
    }

    #[test]
    fn counts_are_whole_ticks_and_fractions_carry() {
        let mut e = quiet();
        let tick = e.metres_per_tick;
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        // Left turns half a tick per step, right a quarter tick backwards.
        let s = e.sample(&mut rng, [0.5 * tick, -0.25 * tick]);
        let mut steps_then_take = |n: usize| {
            for _ in 0..n {
                e.commit(&s);
            }
            let t = e.take();
            (t.left / tick, t.right / tick)
        };
        assert_eq!(
            steps_then_take(1),
            (0.0, -1.0),
            "0.5 reads 0; -0.25 reads count -1"
        );
        assert_eq!(
            steps_then_take(2),
            (1.0, 0.0),
            "1.5 reads 1; -0.75 still count -1"
        );
        assert_eq!(
            steps_then_take(3),
            (2.0, -1.0),
            "3.0 reads 3; -1.5 reads count -2"
        );
    }

    #[test]
    fn slip_shortens_the_ground_travel_not_the_count() {
        let cfg = EncoderConfig {
            noise_std: 0.0,
            slip_probability: 1.0,
            slip_fraction: 0.5,
            ..EncoderConfig::default()
        };
        let e = Encoders::new(&RobotConfig::default(), &cfg);
        let s = e.sample(&mut ChaCha8Rng::seed_from_u64(2), [0.01, 0.02]);
        assert_eq!(s.ground, [0.005, 0.01]);
        assert_eq!(s.measured, [0.01, 0.02]);
    }
}
