//! The three controllers of seed 003's tag driving, each a pure function of what is
//! measured: pure pursuit towards the next tag (§1.2.4, §2.3), the 90° turn's P control
//! (§1.2.6, §2.4) and the alignment on a tag (§2.5).

use crate::geometry::wrap_angle;

/// Gains and limits of the three controllers, the seed's values by default; a tag map's
/// `parameters` may change them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveGains {
    /// Forward and backward speed along a leg, m/s (seed 003 §2.3: 0.3).
    pub speed: f64,
    /// Pure pursuit's gain forward and backward (§2.3: 1.0 and 0.8).
    pub gain_forward: f64,
    pub gain_backward: f64,
    /// Least look-ahead, metres (§1.2.4: L_eff = max(d, 0.4)).
    pub look_ahead_min: f64,
    /// Lateral offsets under this steer straight, metres (§1.2.4: 0.005).
    pub deadband: f64,
    /// Most turning rate while driving a leg, rad/s (§1.2.4: 0.3).
    pub pursuit_max: f64,
    /// Inside this distance the turning rate is scaled down by d / radius (§1.2.4: 0.3).
    pub slow_radius: f64,
    /// The turn's P gain, and the finer gain within `turn_fine_deg` (§2.4: 1.0, 0.5, 3°).
    pub turn_kp: f64,
    pub turn_kp_fine: f64,
    pub turn_fine_deg: f64,
    /// The turn's least and most rate, rad/s (§2.4: 0.08, 0.3), and when it is done (1°).
    pub turn_min: f64,
    pub turn_max: f64,
    pub turn_done_deg: f64,
    /// Alignment's gain, least rate and when the least applies, most rate (§2.5: 0.8,
    /// 0.08 beyond 0.3°, 0.2) and when it is done (0.5° and 0.05 m).
    pub align_k: f64,
    pub align_min: f64,
    pub align_min_beyond_deg: f64,
    pub align_max: f64,
    pub align_done_deg: f64,
    pub align_done_lateral: f64,
}

impl Default for DriveGains {
    fn default() -> Self {
        Self {
            speed: 0.3,
            gain_forward: 1.0,
            gain_backward: 0.8,
            look_ahead_min: 0.4,
            deadband: 0.005,
            pursuit_max: 0.3,
            slow_radius: 0.3,
            turn_kp: 1.0,
            turn_kp_fine: 0.5,
            turn_fine_deg: 3.0,
            turn_min: 0.08,
            turn_max: 0.3,
            turn_done_deg: 1.0,
            align_k: 0.8,
            align_min: 0.08,
            align_min_beyond_deg: 0.3,
            align_max: 0.2,
            align_done_deg: 0.5,
            align_done_lateral: 0.05,
        }
    }
}

impl DriveGains {
    /// The gains of a tag map's `parameters` (seed 003's names), the seed's where absent.
    pub fn from_map(map: &crate::tags::TagMap) -> Self {
        let d = Self::default();
        let p = |path: &str, default: f64| map.param_f64(path, default);
        Self {
            speed: p("speeds.linear", d.speed),
            gain_forward: p("pure_pursuit.gain_forward", d.gain_forward),
            gain_backward: p("pure_pursuit.gain_backward", d.gain_backward),
            look_ahead_min: p("pure_pursuit.look_ahead", d.look_ahead_min),
            deadband: p("pure_pursuit.deadband", d.deadband),
            pursuit_max: p("pure_pursuit.max_angular", d.pursuit_max),
            slow_radius: p("pure_pursuit.slow_radius", d.slow_radius),
            turn_kp: p("rotation.kp", d.turn_kp),
            turn_kp_fine: p("rotation.kp_near", d.turn_kp_fine),
            turn_fine_deg: p("rotation.near_deg", d.turn_fine_deg),
            turn_min: p("rotation.min_speed", d.turn_min),
            turn_max: p("rotation.max_speed", d.turn_max),
            turn_done_deg: p("rotation.done_deg", d.turn_done_deg),
            align_k: p("align.k", d.align_k),
            align_min: p("align.min_speed", d.align_min),
            align_min_beyond_deg: d.align_min_beyond_deg,
            align_max: p("align.max_speed", d.align_max),
            align_done_deg: p("align.done_deg", d.align_done_deg),
            align_done_lateral: p("align.done_lateral", d.align_done_lateral),
        }
    }
}

/// The turning rate that steers towards a target `ahead` metres in front of the way the
/// robot travels and `lateral` metres to its right (the camera's sign: + right), at
/// `speed` with `gain`. seed 003 §1.2.4: L_eff = max(d, 0.4), α = atan2(-lateral, L_eff),
/// κ = 2 sin α / L_eff, ω = v κ gain, 0 inside the deadband, clipped, and scaled by
/// d / 0.3 inside 0.3 m. Driving backward the robot travels the other way round: the
/// caller gives the target in that frame (ahead behind it, right to its left), and the
/// rate in that frame is the rate of the robot, a half turn not changing a turn's sense.
pub fn pursuit(g: &DriveGains, ahead: f64, lateral: f64, gain: f64) -> f64 {
    if lateral.abs() < g.deadband {
        return 0.0;
    }
    let distance = ahead.hypot(lateral);
    let look = distance.max(g.look_ahead_min);
    let alpha = (-lateral).atan2(look);
    let curvature = 2.0 * alpha.sin() / look;
    let omega = (g.speed * curvature * gain).clamp(-g.pursuit_max, g.pursuit_max);
    if distance < g.slow_radius {
        omega * distance / g.slow_radius
    } else {
        omega
    }
}

/// The 90° turn's rate for a heading `error` (target less heading, radians): seed 003
/// §2.4's P control, kp 1.0 (0.5 within 3°), at least 0.08 rad/s while the error is over
/// 3°, at most 0.3; 0 once within 1°. The seed also says (§1.2.6) that the least rate
/// applies whatever the error; navdeck follows §2.4, since a floor inside 3° would undo
/// the finer gain there.
pub fn turn_rate(g: &DriveGains, error: f64) -> f64 {
    let error = wrap_angle(error);
    let deg = error.abs().to_degrees();
    if deg < g.turn_done_deg {
        return 0.0;
    }
    let kp = if deg < g.turn_fine_deg {
        g.turn_kp_fine
    } else {
        g.turn_kp
    };
    let mut omega = kp * error;
    if omega.abs() < g.turn_min && deg > g.turn_fine_deg {
        omega = g.turn_min * error.signum();
    }
    omega.clamp(-g.turn_max, g.turn_max)
}

/// Whether a turn with heading `error` is done (seed 003 §2.4: within 1°).
pub fn turn_done(g: &DriveGains, error: f64) -> bool {
    wrap_angle(error).abs().to_degrees() < g.turn_done_deg
}

/// The alignment's rate for the tag's angle in the image `align` (radians, + when the
/// tag is turned anticlockwise, seed 003 §2.5's corner angle): the seed gives the gain
/// 0.8, the limits and the sense (a tag turned anticlockwise turns the robot clockwise)
/// but no law; navdeck's is proportional, ω = -0.8 α, at least 0.08 rad/s beyond 0.3°,
/// at most 0.2, and 0 once within 0.5°.
pub fn align_rate(g: &DriveGains, align: f64) -> f64 {
    let deg = align.abs().to_degrees();
    if deg < g.align_done_deg {
        return 0.0;
    }
    let mut omega = -g.align_k * align;
    if omega.abs() < g.align_min && deg > g.align_min_beyond_deg {
        omega = -g.align_min * align.signum();
    }
    omega.clamp(-g.align_max, g.align_max)
}

/// Whether the robot is aligned on a tag (seed 003 §2.5: |angle| < 0.5° and
/// |lateral| < 0.05 m).
pub fn aligned(g: &DriveGains, align: f64, lateral: f64) -> bool {
    align.abs().to_degrees() < g.align_done_deg && lateral.abs() < g.align_done_lateral
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn pursuit_matches_the_seeds_formula_worked_by_hand() {
        let g = DriveGains::default();
        // 1 m ahead, 0.1 m right: L = hypot(1, 0.1) = 1.004988, α = atan2(-0.1, L) =
        // -0.099177, κ = 2 sin α / L = -0.197047, ω = 0.3 κ = -0.059114.
        let w = pursuit(&g, 1.0, 0.1, 1.0);
        assert!((w - -0.059114).abs() < 1e-6, "{w}");
        // Backward gain 0.8 scales it.
        assert!(close(pursuit(&g, 1.0, 0.1, 0.8), 0.8 * w));
        // A target to the left turns left.
        assert!(pursuit(&g, 1.0, -0.1, 1.0) > 0.0);
    }

    #[test]
    fn pursuit_keeps_the_least_look_ahead_the_deadband_the_clip_and_slows_near() {
        let g = DriveGains::default();
        assert_eq!(pursuit(&g, 1.0, 0.004, 1.0), 0.0);
        // 0.1 m ahead and 0.2 m right: d = 0.2236 < 0.4, so L = 0.4: α = atan2(-0.2, 0.4)
        // = -0.463648, κ = 2 sin α / 0.4 = -2.236068, ω = 0.3 κ = -0.670820, clipped to
        // -0.3, then scaled by d / 0.3 = 0.745356: -0.223607.
        let w = pursuit(&g, 0.1, 0.2, 1.0);
        assert!((w - -0.223607).abs() < 1e-6, "{w}");
        // 0.3 m ahead and 0.5 m left: L = 0.583095, α = 0.708626, κ = 2.233 and
        // ω = 0.67, clipped to 0.3 (and not slowed: d > 0.3).
        assert!(close(pursuit(&g, 0.3, -0.5, 1.0), 0.3));
    }

    #[test]
    fn the_turn_uses_its_gains_its_floor_outside_three_degrees_and_stops_within_one() {
        let g = DriveGains::default();
        let deg = f64::to_radians;
        // 90° out: 1.0 x 1.571 clipped to 0.3.
        assert!(close(turn_rate(&g, deg(90.0)), 0.3));
        assert!(close(turn_rate(&g, deg(-90.0)), -0.3));
        // 10°: 1.0 x 0.174533.
        assert!(close(turn_rate(&g, deg(10.0)), deg(10.0)));
        // 4°: 0.069813 is under the floor, raised to 0.08.
        assert!(close(turn_rate(&g, deg(4.0)), 0.08));
        // 2°: the fine gain, 0.5 x 0.034907 = 0.017453, no floor.
        assert!(close(turn_rate(&g, deg(2.0)), 0.5 * deg(2.0)));
        assert_eq!(turn_rate(&g, deg(0.9)), 0.0);
        assert!(turn_done(&g, deg(0.9)) && !turn_done(&g, deg(1.1)));
        // Errors are taken the short way round.
        assert!(turn_rate(&g, deg(350.0)) < 0.0);
    }

    #[test]
    fn alignment_turns_against_the_tags_angle_with_its_floor_and_ceiling() {
        let g = DriveGains::default();
        let deg = f64::to_radians;
        // 10°: -0.8 x 0.174533 = -0.139626.
        assert!(close(align_rate(&g, deg(10.0)), -0.8 * deg(10.0)));
        // 20°: -0.279253 clipped to -0.2.
        assert!(close(align_rate(&g, deg(-20.0)), 0.2));
        // 2°: -0.027925 raised to -0.08.
        assert!(close(align_rate(&g, deg(2.0)), -0.08));
        assert_eq!(align_rate(&g, deg(0.4)), 0.0);
        assert!(aligned(&g, deg(0.4), 0.04));
        assert!(!aligned(&g, deg(0.4), 0.06));
        assert!(!aligned(&g, deg(0.6), 0.0));
    }
}
