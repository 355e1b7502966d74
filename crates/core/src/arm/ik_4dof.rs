//! Seed 000 section 4.2: the 4-DOF closed form, with the tool's pitch asked or chosen,
//! then section 4.3.2's refinement.
//!
//! Without a pitch, the position leaves one degree of freedom (section 4.2.2). navdeck
//! takes the pitch nearest `preferred_pitch` (the seed's target_orientation, pi/2: tool
//! straight down) at which some solution is within every limit: the seed's objective
//! with its limit penalty made a hard constraint and its singularity term left to the
//! choice among solutions (`planar::choose`). The search: the preferred pitch itself;
//! else pitches 5 degrees apart outward from it (passing over those `PitchArcs` rules
//! out: the wrist beyond shoulder and elbow's reach within joint 3's limits), the first
//! possible one bisected back toward the preferred pitch; else, for a target whose
//! possible pitches all fall between two samples, a golden-section search for the pitch
//! farthest inside every limit around each of the most promising samples.

use super::config::ArmConfig;
use super::planar::{self, InPlane, PitchArcs, Way};
use super::refine::refine;
use super::{Joints, Solution, Target, Unreachable};
use std::f64::consts::PI;

/// Pitches tried around the whole turn when the preferred one fails (5 degrees apart).
const SAMPLES: usize = 72;
/// Bisection steps from a 5 degree gap: 2^-16 of it (under 0.0001 degree).
const BISECTIONS: u32 = 16;
/// Golden-section steps from a 10 degree bracket: 0.618^40 of it.
const GOLDEN_STEPS: u32 = 40;
/// How many of the best samples the golden-section search starts from.
const PEAKS: usize = 4;

pub(super) fn solve(
    cfg: &ArmConfig,
    t: &Target,
    current: &Joints,
) -> Result<Solution, Unreachable> {
    planar::out_of_span(cfg, t.x, t.y, t.z)?;
    let planes = planar::planes(cfg, t.x, t.y, t.z, current);
    match t.pitch {
        Some(pitch) => {
            let ways = planar::all_ways(cfg, &planes, pitch);
            finish(cfg, &ways, pitch, t, current)
        }
        None => free_pitch(cfg, &planes, t, current),
    }
}

/// The chosen way at `pitch`, refined, or why none.
pub(super) fn finish(
    cfg: &ArmConfig,
    ways: &[Way],
    pitch: f64,
    t: &Target,
    current: &Joints,
) -> Result<Solution, Unreachable> {
    match planar::choose(cfg, ways, current) {
        None => Err(planar::refusal(cfg, ways, pitch)),
        Some(Err(manipulability)) => Err(Unreachable::Singular { manipulability }),
        Some(Ok(chosen)) => Ok(chosen.refined(cfg, refine(cfg, chosen.joints, t))),
    }
}

/// The least margin of way `k` (of the four) at `pitch`.
fn margin(cfg: &ArmConfig, planes: &[InPlane; 2], pitch: f64, k: usize) -> f64 {
    planar::ways(cfg, &planes[k / 2], pitch)[k % 2].margin
}

fn free_pitch(
    cfg: &ArmConfig,
    planes: &[InPlane; 2],
    t: &Target,
    current: &Joints,
) -> Result<Solution, Unreachable> {
    let preferred = cfg.preferred_pitch;
    let solve_at = |pitch: f64| {
        let ways = planar::all_ways(cfg, planes, pitch);
        let target = Target { pitch: None, ..*t };
        finish(cfg, &ways, pitch, &target, current)
    };
    let first = planar::all_ways(cfg, planes, preferred);
    if first.iter().any(Way::possible) {
        return solve_at(preferred);
    }
    // A plane whose yaw joint 1 cannot take is out at every pitch.
    let live = [0, 1].map(|p| {
        first[2 * p].joints[0] >= cfg.limits.min[0] - planar::LIMIT_SLACK
            && first[2 * p].joints[0] <= cfg.limits.max[0] + planar::LIMIT_SLACK
    });
    if !live.iter().any(|&l| l) {
        return Err(Unreachable::JointLimit {
            joint: 1,
            value: first[0].joints[0],
            min: cfg.limits.min[0],
            max: cfg.limits.max[0],
        });
    }
    let arcs = planes.map(|p| PitchArcs::new(cfg, &p));
    // Margins at `pitch`, or (`quick`) only where the arcs admit it, NEG_INFINITY elsewhere.
    let margins_at = |pitch: f64, quick: bool| -> [f64; 4] {
        let mut m = [f64::NEG_INFINITY; 4];
        for p in (0..2).filter(|&p| live[p] && (!quick || arcs[p].admit(pitch))) {
            let [a, b] = planar::ways(cfg, &planes[p], pitch);
            (m[2 * p], m[2 * p + 1]) = (a.margin, b.margin);
        }
        m
    };
    // Sample j at preferred + (j - HALF) steps, around the whole turn, taken outward from
    // the preferred pitch until one has a possible way; then bisect back toward its
    // neighbour on the preferred side (impossible, or it would have been found first).
    const HALF: usize = SAMPLES / 2;
    let step = 2.0 * PI / SAMPLES as f64;
    let angle = |j: usize| preferred + (j as f64 - HALF as f64) * step;
    let mut margins = [[f64::NEG_INFINITY; 4]; SAMPLES];
    margins[HALF] = first.map(|w| w.margin);
    let outward = (1..=HALF)
        .flat_map(|d| [HALF + d, HALF - d])
        .filter(|&j| j < SAMPLES);
    for j in outward {
        margins[j] = margins_at(angle(j), true);
        let Some(k) = (0..4)
            .filter(|&k| margins[j][k] >= 0.0)
            .max_by(|&a, &b| margins[j][a].total_cmp(&margins[j][b]))
        else {
            continue;
        };
        let inward = if j > HALF { j - 1 } else { j + 1 };
        let (mut good, mut bad) = (angle(j), angle(inward));
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (good + bad);
            if margin(cfg, planes, mid, k) >= 0.0 {
                good = mid;
            } else {
                bad = mid;
            }
        }
        return solve_at(good);
    }
    // No sample possible: search between samples around the local best of them (every
    // sample's margins now, the arcs' too: a narrow window may lie where they end).
    for (j, row) in margins.iter_mut().enumerate() {
        if j != HALF {
            *row = margins_at(angle(j), false);
        }
    }
    let mut peaks: Vec<(f64, usize, usize)> = Vec::new();
    for j in 0..SAMPLES {
        let (lo, hi) = ((j + SAMPLES - 1) % SAMPLES, (j + 1) % SAMPLES);
        for (k, &m) in margins[j].iter().enumerate() {
            if live[k / 2] && m >= margins[lo][k] && m >= margins[hi][k] {
                peaks.push((m, j, k));
            }
        }
    }
    peaks.sort_by(|a, b| b.0.total_cmp(&a.0));
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    let mut best = (f64::NEG_INFINITY, preferred, 0);
    for &(_, j, k) in peaks.iter().take(PEAKS) {
        let (mut a, mut b) = (angle(j) - step, angle(j) + step);
        let mut c = b - golden * (b - a);
        let mut d = a + golden * (b - a);
        let (mut fc, mut fd) = (margin(cfg, planes, c, k), margin(cfg, planes, d, k));
        for _ in 0..GOLDEN_STEPS {
            if fc.max(fd) >= 0.0 {
                break;
            }
            if fc >= fd {
                (b, d, fd) = (d, c, fc);
                c = b - golden * (b - a);
                fc = margin(cfg, planes, c, k);
            } else {
                (a, c, fc) = (c, d, fd);
                d = a + golden * (b - a);
                fd = margin(cfg, planes, d, k);
            }
        }
        let (f, at) = if fc >= fd { (fc, c) } else { (fd, d) };
        if f >= 0.0 {
            return solve_at(at);
        }
        if f > best.0 {
            best = (f, at, k);
        }
    }
    // Nothing possible: the way nearest possible names what stops it.
    let (_, pitch, k) = best;
    let way = planar::ways(cfg, &planes[k / 2], pitch)[k % 2];
    Err(if way.wrist_reached {
        let i = way.worst_joint;
        Unreachable::JointLimit {
            joint: i + 1,
            value: way.joints[i],
            min: cfg.limits.min[i],
            max: cfg.limits.max[i],
        }
    } else {
        let (distance, least, reach) = planar::tool_reach(cfg, t.x, t.y, t.z);
        if distance > reach {
            Unreachable::TooFar { distance, reach }
        } else if distance < least {
            Unreachable::TooClose { distance, least }
        } else {
            Unreachable::NoPitch {
                distance,
                least,
                reach,
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arm::{Branch, forward};
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn right_angle_elbow_by_hand() {
        let c = ArmConfig::default();
        let lean = 0.024f64.atan2(0.128);
        let t = Target {
            pitch: Some(FRAC_PI_2),
            ..Target::point(0.124, 0.0, 0.057)
        };
        let s = solve(&c, &t, &Joints::default()).unwrap();
        let want = [0.0, -lean, lean, FRAC_PI_2];
        for (i, w) in want.iter().enumerate() {
            assert!((s.joints.0[i] - w).abs() < 1e-12, "{s:?}");
        }
        assert_eq!(s.branch, Branch::ElbowUp);
        assert_eq!(s.iterations, 0);
        assert!(s.residual < 1e-12);
        // Without a pitch the preferred one, straight down, reaches it: the same joints.
        let s = solve(&c, &Target::point(0.124, 0.0, 0.057), &Joints::default()).unwrap();
        assert!((s.joints.0[1] + lean).abs() < 1e-12, "{s:?}");
    }

    #[test]
    fn too_far_and_pitch_out_of_reach_say_why() {
        let c = ArmConfig::default();
        let e = solve(&c, &Target::point(0.5, 0.0, 0.077), &Joints::default()).unwrap_err();
        assert!(matches!(e, Unreachable::TooFar { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            "target 0.500 m from the shoulder, the arm reaches 0.404 m"
        );
        // 0.35 m ahead at shoulder height is within reach, but not with the tool down.
        let t = Target {
            pitch: Some(FRAC_PI_2),
            ..Target::point(0.35, 0.0, 0.077)
        };
        let e = solve(&c, &t, &Joints::default()).unwrap_err();
        assert!(matches!(e, Unreachable::PitchOutOfReach { .. }), "{e}");
        // Leaving the pitch free reaches it, tilted as little from straight down as the
        // limits allow.
        let s = solve(&c, &Target::point(0.35, 0.0, 0.077), &Joints::default()).unwrap();
        assert!(s.residual < 1e-6, "{s:?}");
        let p = forward(&c, &s.joints);
        assert!(p.pitch < FRAC_PI_2 && p.pitch > -FRAC_PI_2, "{p:?}");
    }

    #[test]
    fn both_elbow_branches_where_the_limits_allow_the_nearest_chosen() {
        // Joints 2 to 4 free to turn half a turn either way: elbow down is possible too.
        let mut c = ArmConfig::default();
        for i in 1..4 {
            (c.limits.min[i], c.limits.max[i]) = (-PI, PI);
        }
        let t = Target {
            pitch: Some(FRAC_PI_2),
            ..Target::point(0.124, 0.0, 0.057)
        };
        let up = solve(&c, &t, &Joints(c.poses.home)).unwrap();
        assert_eq!(up.branch, Branch::ElbowUp);
        // Elbow down for the same target, by hand: the upper arm pitched
        // atan2(-0.130, 0.124) + acos(0.0338 / (2 x 0.130 x 0.179655)) = -0.809016 +
        // 0.761781 = -0.047235 rad, the forearm a right angle below it;
        // joint 2 = -0.047235 + 1.385448, joint 3 = -pi/2 - 1.385448.
        let near_down = Joints([0.0, 1.3, -2.9, -3.0]);
        let down = solve(&c, &t, &near_down).unwrap();
        assert_eq!(down.branch, Branch::ElbowDown, "{down:?}");
        assert!((down.joints.0[1] - 1.338213).abs() < 1e-6, "{down:?}");
        assert!((down.joints.0[2] + 2.956245).abs() < 1e-6, "{down:?}");
        assert!(down.residual < 1e-9);
    }

    #[test]
    fn a_target_only_reached_near_a_singularity_is_refused_when_asked() {
        // Straight above the base the tool is on joint 1's axis: manipulability 0.
        let t = Target::point(0.0, 0.0, 0.30);
        let s = solve(&ArmConfig::default(), &t, &Joints::default()).unwrap();
        assert!(s.manipulability < 1e-9 && s.residual < 1e-6, "{s:?}");
        let c = ArmConfig {
            min_manipulability: 1e-4,
            ..ArmConfig::default()
        };
        let e = solve(&c, &t, &Joints::default()).unwrap_err();
        assert!(matches!(e, Unreachable::Singular { .. }), "{e}");
    }

    #[test]
    fn a_target_within_the_span_but_at_no_pitch_says_so() {
        // 0.2 m behind the base, low: within the stretched arm's span, but joint 1 cannot
        // face it and reaching back over the shoulder breaks joint 2's or 3's limits.
        let c = ArmConfig::default();
        let e = solve(&c, &Target::point(-0.2, 0.0, 0.05), &Joints::default()).unwrap_err();
        assert!(matches!(e, Unreachable::NoPitch { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            "target 0.202 m from the shoulder is within the arm's span (0.000 to 0.404 m), but no tool pitch reaches it within the joint limits"
        );
    }

    #[test]
    fn just_beyond_reach_prints_the_two_distances_apart() {
        let c = ArmConfig::default();
        let reach: f64 = c.links.iter().sum();
        let t = Target::point(reach + 2e-7, 0.0, c.base_height);
        let e = solve(&c, &t, &Joints::default()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "target 0.4040002 m from the shoulder, the arm reaches 0.4040000 m"
        );
    }

    #[test]
    fn behind_the_arm_it_reaches_back_over_the_shoulder() {
        // Joint 1 cannot turn to face x < 0 (its limit is 162 degrees); the arm leans back.
        let c = ArmConfig::default();
        let s = solve(&c, &Target::point(-0.05, 0.0, 0.30), &Joints::default()).unwrap();
        assert!(s.residual < 1e-6 && s.joints.0[0].abs() < 1e-9, "{s:?}");
    }
}
