//! A PID on an angle error, with anti-windup, for the heading loops of the followers.

use crate::geometry::wrap_angle;

/// PID gains and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PidGains {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    /// The integral of the error never leaves [-limit, limit].
    pub integral_limit: f64,
    /// The output never leaves [-limit, limit]; `f64::INFINITY` for none.
    pub output_limit: f64,
}

/// Proportional-integral-derivative control of a wrapped angle error.
#[derive(Clone, Debug, PartialEq)]
pub struct Pid {
    gains: PidGains,
    integral: f64,
    last_error: Option<f64>,
}

impl Pid {
    pub fn new(gains: PidGains) -> Self {
        Self {
            gains,
            integral: 0.0,
            last_error: None,
        }
    }

    /// Forgets the integral and the previous error.
    pub fn reset(&mut self) {
        self.integral = 0.0;
        self.last_error = None;
    }

    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// The output for `error` (radians, wrapped to [-pi, pi]) after `dt` seconds.
    pub fn update(&mut self, error: f64, dt: f64) -> f64 {
        let g = self.gains;
        let error = wrap_angle(error);
        // The first step has no derivative; later ones difference the wrapped errors, so a
        // crossing of +-pi reads as the small change it is.
        let derivative = match self.last_error {
            Some(last) if dt > 0.0 => wrap_angle(error - last) / dt,
            _ => 0.0,
        };
        self.last_error = Some(error);
        // u = Kp e + Ki int(e) dt + Kd de/dt (seed 001 section 6).
        let output = |integral: f64| g.kp * error + g.ki * integral + g.kd * derivative;
        let candidate =
            (self.integral + error * dt.max(0.0)).clamp(-g.integral_limit, g.integral_limit);
        // Conditional integration (Astrom & Hagglund, "Advanced PID Control", 3.5): no
        // integrating while the output is saturated in the direction the error pushes it.
        let u = output(candidate);
        let saturated = u.abs() > g.output_limit && u.signum() == error.signum();
        if !saturated {
            self.integral = candidate;
        }
        output(self.integral).clamp(-g.output_limit, g.output_limit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gains(kp: f64, ki: f64, kd: f64) -> PidGains {
        PidGains {
            kp,
            ki,
            kd,
            integral_limit: 10.0,
            output_limit: f64::INFINITY,
        }
    }

    #[test]
    fn terms_match_hand_worked_numbers() {
        // Seed 001 gains, errors 0.2 then 0.1 rad at dt 0.1 s.
        let mut pid = Pid::new(gains(0.5, 0.01, 0.3));
        // 0.5*0.2 + 0.01*0.02 + 0 = 0.1002
        assert!((pid.update(0.2, 0.1) - 0.1002).abs() < 1e-12);
        // 0.5*0.1 + 0.01*0.03 + 0.3*(-1.0) = -0.2497
        assert!((pid.update(0.1, 0.1) + 0.2497).abs() < 1e-12);
        assert!((pid.integral() - 0.03).abs() < 1e-12);
    }

    #[test]
    fn each_term_alone() {
        let mut p = Pid::new(gains(2.0, 0.0, 0.0));
        assert!((p.update(0.25, 0.1) - 0.5).abs() < 1e-12);
        let mut i = Pid::new(gains(0.0, 1.0, 0.0));
        for _ in 0..10 {
            i.update(0.5, 0.1);
        }
        // int 0.5 dt over 1 s = 0.5
        assert!((i.update(0.0, 0.1) - 0.5).abs() < 1e-12);
        let mut d = Pid::new(gains(0.0, 0.0, 1.0));
        assert_eq!(
            d.update(0.3, 0.1),
            0.0,
            "no derivative kick on the first step"
        );
        // (0.1 - 0.3) / 0.1 = -2
        assert!((d.update(0.1, 0.1) + 2.0).abs() < 1e-12);
    }

    #[test]
    fn derivative_sees_a_small_step_across_pi() {
        let mut d = Pid::new(gains(0.0, 0.0, 1.0));
        d.update(3.1, 0.1);
        // 3.1 -> 3.2 wraps to -3.083; the error moved by +0.1, not by -6.18.
        assert!((d.update(3.2, 0.1) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn integral_is_clamped_to_its_limit() {
        let mut pid = Pid::new(PidGains {
            integral_limit: 0.5,
            ..gains(0.0, 1.0, 0.0)
        });
        for _ in 0..100 {
            pid.update(1.0, 0.1);
        }
        assert_eq!(pid.integral(), 0.5);
    }

    #[test]
    fn output_leaves_saturation_as_soon_as_the_error_changes_sign() {
        let limits = PidGains {
            kp: 0.5,
            ki: 0.5,
            kd: 0.0,
            integral_limit: 100.0,
            output_limit: 1.0,
        };
        let mut pid = Pid::new(limits);
        // 100 s pushed against the limit.
        for _ in 0..1000 {
            assert_eq!(pid.update(3.0, 0.1), 1.0);
        }
        // A naive integral would hold 300 and keep the output at +1 for minutes.
        let out = pid.update(-0.5, 0.1);
        assert!(out < 0.0, "still wound up: {out}");
    }

    #[test]
    fn reset_forgets_the_past() {
        let mut pid = Pid::new(gains(0.0, 1.0, 1.0));
        pid.update(1.0, 0.1);
        pid.update(0.5, 0.1);
        pid.reset();
        assert_eq!(pid.integral(), 0.0);
        assert_eq!(pid.update(0.0, 0.1), 0.0);
    }
}
