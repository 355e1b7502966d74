//! The arm's bars. FK(IK(p)) within 0.1 mm for 10,000 random reachable targets (drawn as
//! FK of random in-limit joints from a seeded generator) for each solver; and dense grids
//! in the arm's x-z plane where every target the solver calls reachable is reached
//! within 0.1 mm inside every limit, and every target it refuses is found unreachable by
//! a brute-force sweep of the joints (none refused deeper than `BAND` inside the swept
//! workspace).

use super::config::{ArmConfig, Solver};
use super::kinematics::link_pitches;
use super::{Joints, Target, check_limits, forward, inverse};
use crate::geometry::wrap_angle;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// FK(IK(p)) must land this close to p, metres.
const BAR: f64 = 1e-4;
/// Targets per random bar.
const RANDOM_TARGETS: usize = 10_000;
/// Brute-force cells, metres.
const CELL: f64 = 0.001;
/// Grid targets, metres apart.
const GRID_STEP: f64 = 0.004;
/// The tolerance band at the workspace boundary: a refused target counts as wrongly
/// refused only when the swept workspace covers every cell within this of it.
const BAND: f64 = 0.002;
/// The plane y = 0: x and z bounds of the grid and the cells (beyond the arm's reach,
/// 0.404 m from the shoulder at z = 0.077).
const X0: f64 = -0.44;
const X1: f64 = 0.44;
const Z0: f64 = -0.36;
const Z1: f64 = 0.52;

fn random_joints(cfg: &ArmConfig, rng: &mut ChaCha8Rng) -> Joints {
    Joints(std::array::from_fn(|i| {
        rng.random_range(cfg.limits.min[i]..=cfg.limits.max[i])
    }))
}

fn distance(cfg: &ArmConfig, q: &Joints, t: &Target) -> f64 {
    let p = forward(cfg, q);
    ((p.x - t.x).powi(2) + (p.y - t.y).powi(2) + (p.z - t.z).powi(2)).sqrt()
}

/// Asserts a solver's answer reaches `t` (its pitch too, when asked) within limits.
fn assert_reached(cfg: &ArmConfig, t: &Target, q: &Joints, what: &str) {
    let d = distance(cfg, q, t);
    assert!(d < BAR, "{what}: {t:?} missed by {d} m with {q:?}");
    assert_eq!(check_limits(cfg, q), Ok(()), "{what}: {t:?}");
    if let Some(pitch) = t.pitch {
        let off = wrap_angle(forward(cfg, q).pitch - pitch).abs();
        assert!(off < 1e-6, "{what}: {t:?} pitch off by {off} rad");
    }
}

#[test]
fn four_dof_reaches_10000_random_poses_within_a_tenth_of_a_millimetre() {
    let cfg = ArmConfig::default();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut worst = 0.0f64;
    for _ in 0..RANDOM_TARGETS {
        let t = Target::from(forward(&cfg, &random_joints(&cfg, &mut rng)));
        let current = random_joints(&cfg, &mut rng);
        let s = inverse(&cfg, &t, &current).unwrap_or_else(|e| panic!("{t:?}: {e}"));
        assert_reached(&cfg, &t, &s.joints, "4dof pose");
        worst = worst.max(distance(&cfg, &s.joints, &t));
    }
    eprintln!("4dof poses: worst FK residual {worst:.2e} m");
}

#[test]
fn four_dof_reaches_10000_random_points_within_a_tenth_of_a_millimetre() {
    let cfg = ArmConfig::default();
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let mut worst = 0.0f64;
    for _ in 0..RANDOM_TARGETS {
        let p = forward(&cfg, &random_joints(&cfg, &mut rng));
        let t = Target::point(p.x, p.y, p.z);
        let current = random_joints(&cfg, &mut rng);
        let s = inverse(&cfg, &t, &current).unwrap_or_else(|e| panic!("{t:?}: {e}"));
        assert_reached(&cfg, &t, &s.joints, "4dof point");
        worst = worst.max(distance(&cfg, &s.joints, &t));
    }
    eprintln!("4dof points: worst FK residual {worst:.2e} m");
}

#[test]
fn with_wide_limits_both_branches_reach_random_targets_within_a_tenth_of_a_millimetre() {
    // Every joint free to turn half a turn either way: both elbow branches and both yaws
    // are possible, and the choice among them is exercised.
    let mut cfg = ArmConfig::default();
    for i in 0..4 {
        (cfg.limits.min[i], cfg.limits.max[i]) = (-PI, PI);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mut downs = 0;
    for n in 0..RANDOM_TARGETS {
        let p = forward(&cfg, &random_joints(&cfg, &mut rng));
        let t = Target {
            pitch: (n % 2 == 0).then_some(p.pitch),
            ..Target::point(p.x, p.y, p.z)
        };
        let current = random_joints(&cfg, &mut rng);
        let s = inverse(&cfg, &t, &current).unwrap_or_else(|e| panic!("{t:?}: {e}"));
        assert_reached(&cfg, &t, &s.joints, "wide limits");
        downs += usize::from(s.branch == super::Branch::ElbowDown);
    }
    assert!(downs > RANDOM_TARGETS / 5, "{downs} elbow-down solutions");
}

#[test]
fn two_dof_reaches_10000_random_points_within_a_tenth_of_a_millimetre() {
    let cfg = ArmConfig {
        solver: Solver::TwoDof,
        ..ArmConfig::default()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (mut done, mut worst) = (0, 0.0f64);
    while done < RANDOM_TARGETS {
        // Random base, shoulder and elbow; the wrist keeps the fixed pitch, if it can.
        let mut q = random_joints(&cfg, &mut rng);
        let [_, p3, _] = link_pitches(&cfg, &q.0);
        let wrist = cfg.fixed_pitch - p3 - cfg.joint_offsets[3];
        let Some(wrist) = [wrist, wrist - TAU, wrist + TAU]
            .into_iter()
            .find(|w| (cfg.limits.min[3]..=cfg.limits.max[3]).contains(w))
        else {
            continue;
        };
        q.0[3] = wrist;
        let p = forward(&cfg, &q);
        // Half with the pitch asked (the fixed one), half without.
        let t = Target {
            pitch: (done % 2 == 0).then_some(p.pitch),
            ..Target::point(p.x, p.y, p.z)
        };
        let current = random_joints(&cfg, &mut rng);
        let s = inverse(&cfg, &t, &current).unwrap_or_else(|e| panic!("{t:?}: {e}"));
        assert_reached(&cfg, &t, &s.joints, "2dof");
        let off = wrap_angle(forward(&cfg, &s.joints).pitch - cfg.fixed_pitch).abs();
        assert!(off < 1e-6, "2dof left its pitch by {off} rad");
        worst = worst.max(distance(&cfg, &s.joints, &t));
        done += 1;
    }
    eprintln!("2dof: worst FK residual {worst:.2e} m");
}

/// Which 1 mm cells of the plane y = 0 some swept configuration puts the tool in.
struct Cells {
    columns: usize,
    rows: usize,
    hit: Vec<bool>,
}

impl Cells {
    fn new() -> Self {
        let columns = ((X1 - X0) / CELL).ceil() as usize + 1;
        let rows = ((Z1 - Z0) / CELL).ceil() as usize + 1;
        Self {
            columns,
            rows,
            hit: vec![false; columns * rows],
        }
    }

    fn index(&self, x: f64, z: f64) -> Option<usize> {
        let (c, r) = (((x - X0) / CELL).floor(), ((z - Z0) / CELL).floor());
        (c >= 0.0 && r >= 0.0 && (c as usize) < self.columns && (r as usize) < self.rows)
            .then(|| r as usize * self.columns + c as usize)
    }

    fn mark(&mut self, x: f64, z: f64) {
        if let Some(i) = self.index(x, z) {
            self.hit[i] = true;
        }
    }

    fn covered(&self, x: f64, z: f64) -> bool {
        self.index(x, z).is_some_and(|i| self.hit[i])
    }

    /// Every cell within `BAND` of (x, z) covered (the point and 16 around it).
    fn deep_inside(&self, x: f64, z: f64) -> bool {
        self.covered(x, z)
            && (0..16).all(|k| {
                let a = k as f64 * TAU / 16.0;
                self.covered(x + BAND * a.cos(), z + BAND * a.sin())
                    && self.covered(x + 0.5 * BAND * a.cos(), z + 0.5 * BAND * a.sin())
            })
    }

    /// Some cell within two cells of (x, z) covered.
    fn near(&self, x: f64, z: f64) -> bool {
        (-2..=2).any(|i| (-2..=2).any(|j| self.covered(x + i as f64 * CELL, z + j as f64 * CELL)))
    }
}

/// Joint 1 at 0 only: the plane y = 0 is reached facing +x (reaching back for x < 0);
/// the default limits keep joint 1 from facing -x.
fn assert_joint_1_cannot_face_back(cfg: &ArmConfig) {
    assert!(cfg.limits.max[0] < PI && cfg.limits.min[0] > -PI);
}

/// `n` steps from min to max of joint i, inclusive.
fn sweep(cfg: &ArmConfig, i: usize, step: f64) -> impl Iterator<Item = f64> + use<> {
    let (lo, hi) = (cfg.limits.min[i], cfg.limits.max[i]);
    let n = ((hi - lo) / step).ceil() as usize;
    (0..=n).map(move |k| lo + (hi - lo) * k as f64 / n as f64)
}

/// The tool's cells with the pitch free: shoulder, elbow and wrist swept.
fn sweep_free(cfg: &ArmConfig, step: f64) -> Cells {
    let mut cells = Cells::new();
    let [l2, l3, l4] = cfg.links;
    let o = cfg.joint_offsets;
    let wrist: Vec<(f64, f64)> = sweep(cfg, 3, step).map(|t| (t + o[3]).sin_cos()).collect();
    let elbow: Vec<(f64, f64)> = sweep(cfg, 2, step).map(|t| (t + o[2]).sin_cos()).collect();
    for t2 in sweep(cfg, 1, step) {
        let (s2, c2) = (t2 + o[1]).sin_cos();
        let (ex, ez) = (l2 * c2, cfg.base_height - l2 * s2);
        for &(sb, cb) in &elbow {
            // p3 = p2 + (theta3 + offset): angle addition.
            let (s3, c3) = (s2 * cb + c2 * sb, c2 * cb - s2 * sb);
            let (wx, wz) = (ex + l3 * c3, ez - l3 * s3);
            for &(sw, cw) in &wrist {
                let (s4, c4) = (s3 * cw + c3 * sw, c3 * cw - s3 * sw);
                cells.mark(wx + l4 * c4, wz - l4 * s4);
            }
        }
    }
    cells
}

/// The tool's cells with the tool at `pitch`: shoulder and elbow swept, the wrist set to
/// the pitch where its limits allow.
fn sweep_at_pitch(cfg: &ArmConfig, pitch: f64, step: f64) -> Cells {
    let mut cells = Cells::new();
    let [l2, l3, l4] = cfg.links;
    let (sp, cp) = pitch.sin_cos();
    let (lo, hi) = (cfg.limits.min[3], cfg.limits.max[3]);
    for t2 in sweep(cfg, 1, step) {
        for t3 in sweep(cfg, 2, step) {
            let [p2, p3, _] = link_pitches(cfg, &[0.0, t2, t3, 0.0]);
            let wrist = pitch - p3 - cfg.joint_offsets[3];
            let wrist = wrist + ((0.5 * (lo + hi) - wrist) / TAU).round() * TAU;
            if !(lo..=hi).contains(&wrist) {
                continue;
            }
            let x = l2 * p2.cos() + l3 * p3.cos() + l4 * cp;
            let z = cfg.base_height - l2 * p2.sin() - l3 * p3.sin() - l4 * sp;
            cells.mark(x, z);
        }
    }
    cells
}

/// Tallies of one grid.
#[derive(Debug, Default)]
struct Tally {
    reached: usize,
    refused: usize,
    /// Refused with the whole band around them inside the swept workspace.
    wrongly_refused: Vec<(f64, f64, String)>,
    /// Reached, but with no swept cell within two cells: the sweep too coarse.
    unswept: usize,
}

fn grid(cfg: &ArmConfig, cells: &Cells, pitch: Option<f64>) -> Tally {
    let mut tally = Tally::default();
    let current = Joints(cfg.poses.home);
    let columns = ((X1 - X0) / GRID_STEP).round() as usize;
    let rows = ((Z1 - Z0) / GRID_STEP).round() as usize;
    for c in 0..=columns {
        for r in 0..=rows {
            let (x, z) = (X0 + c as f64 * GRID_STEP, Z0 + r as f64 * GRID_STEP);
            let t = Target {
                pitch,
                ..Target::point(x, 0.0, z)
            };
            match inverse(cfg, &t, &current) {
                Ok(s) => {
                    assert_reached(cfg, &t, &s.joints, "grid");
                    tally.reached += 1;
                    if !cells.near(x, z) {
                        tally.unswept += 1;
                    }
                }
                Err(e) => {
                    tally.refused += 1;
                    if cells.deep_inside(x, z) {
                        tally.wrongly_refused.push((x, z, e.to_string()));
                    }
                }
            }
        }
    }
    tally
}

fn assert_grid(tally: &Tally, what: &str) {
    eprintln!(
        "{what}: {} reached, {} refused, {} wrongly refused, {} reached but unswept",
        tally.reached,
        tally.refused,
        tally.wrongly_refused.len(),
        tally.unswept
    );
    assert!(
        tally.reached > 1000 && tally.refused > 1000,
        "{what}: {tally:?}"
    );
    assert!(
        tally.wrongly_refused.is_empty(),
        "{what}: refused deep inside the workspace: {:?}",
        &tally.wrongly_refused[..tally.wrongly_refused.len().min(10)]
    );
    // The sweep agrees with every reached target (it is fine enough to judge refusals).
    assert!(
        tally.unswept * 1000 <= tally.reached,
        "{what}: {} reached targets unswept",
        tally.unswept
    );
}

#[test]
fn four_dof_grid_with_the_pitch_free_refuses_only_the_unreachable() {
    let cfg = ArmConfig::default();
    assert_joint_1_cannot_face_back(&cfg);
    let cells = sweep_free(&cfg, 0.006);
    assert_grid(&grid(&cfg, &cells, None), "4dof, pitch free");
}

#[test]
fn four_dof_grid_at_four_pitches_refuses_only_the_unreachable() {
    let cfg = ArmConfig::default();
    assert_joint_1_cannot_face_back(&cfg);
    for pitch in [0.0, FRAC_PI_4, FRAC_PI_2, -FRAC_PI_4] {
        let cells = sweep_at_pitch(&cfg, pitch, 0.001);
        let what = format!("4dof, pitch {:.0} deg", pitch.to_degrees());
        assert_grid(&grid(&cfg, &cells, Some(pitch)), &what);
    }
}

#[test]
fn two_dof_grid_refuses_only_the_unreachable() {
    let cfg = ArmConfig {
        solver: Solver::TwoDof,
        ..ArmConfig::default()
    };
    assert_joint_1_cannot_face_back(&cfg);
    let cells = sweep_at_pitch(&cfg, cfg.fixed_pitch, 0.001);
    assert_grid(&grid(&cfg, &cells, None), "2dof");
}
