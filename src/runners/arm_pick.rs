//! `navdeck arm pick-test`: seed 000's pick sequence in the twin, many times over, with
//! the block's pose taken from the camera: a block stands 20 to 45 cm ahead of the
//! camera; the robot sights it for a second, turns to face it and drives up to it on
//! odometry, then the arm goes above the block, descends, closes and lifts. A pick
//! succeeds when the twin's jaws hold the block after the lift. The error is how far the
//! estimated block centre was from the true one when the arm went for it.

use crate::arm::{ArmConfig, Joints, Target, inverse};
use crate::config::Config;
use crate::data::{ArmTarget, GripperCommand, GripperState};
use crate::geometry::{Point2, Pose2, Twist, wrap_angle};
use crate::sim::{Twin, World};
use crate::slam::odometry::Odometry;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Distances from the camera's side of the robot, metres (seed 000 section 6.1.2's
/// 20-45 cm), and the bearing the block may stand at either side.
const BANDS: [(f64, f64); 5] = [
    (0.20, 0.25),
    (0.25, 0.30),
    (0.30, 0.35),
    (0.35, 0.40),
    (0.40, 0.45),
];
const BEARING: f64 = 0.3;
/// How long the robot looks at the block, seconds.
const LOOK: f64 = 1.0;
/// The tool goes this far above the block before it descends, metres (the mission's).
const ABOVE: f64 = crate::mission::ARM_ABOVE;
/// The runner's time step, seconds.
const STEP: f64 = 0.05;

/// One pick's outcome.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pick {
    pub distance: f64,
    /// How far the estimated block was from the true one; none when the camera never
    /// saw it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_mm: Option<f64>,
    pub success: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<String>,
}

/// Outcomes per distance band.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Band {
    pub from_m: f64,
    pub to_m: f64,
    pub picks: usize,
    pub successes: usize,
    pub success_rate: f64,
    /// Over the band's picks whose block was seen; none when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_error_mm: Option<f64>,
}

/// `picks` picks from `seed`, with the twin of `config` (its `[arm]`, or the default arm).
pub fn run(config: &Config, picks: usize, seed: u64) -> (Vec<Pick>, Vec<Band>) {
    let arm = config.arm.clone().unwrap_or_default();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let all: Vec<Pick> = (0..picks)
        .map(|k| {
            let (lo, hi) = BANDS[k % BANDS.len()];
            let d = rng.random_range(lo..hi);
            let bearing = rng.random_range(-BEARING..BEARING);
            one(
                config,
                &arm,
                d,
                bearing,
                seed.wrapping_mul(1000).wrapping_add(k as u64),
            )
        })
        .collect();
    let bands = BANDS
        .iter()
        .map(|&(lo, hi)| {
            let these: Vec<&Pick> = all
                .iter()
                .filter(|p| (lo..hi).contains(&p.distance))
                .collect();
            let n = these.len();
            let ok = these.iter().filter(|p| p.success).count();
            Band {
                from_m: lo,
                to_m: hi,
                picks: n,
                successes: ok,
                success_rate: ok as f64 / n.max(1) as f64,
                mean_error_mm: mean(these.iter().filter_map(|p| p.error_mm)),
            }
        })
        .collect();
    (all, bands)
}

/// The mean of `values`, none of none.
fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(sum, n), v| (sum + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// One pick of a block `distance` ahead of the camera at `bearing` from the robot's heading.
fn one(config: &Config, arm: &ArmConfig, distance: f64, bearing: f64, seed: u64) -> Pick {
    // The arena, emptied but for its walls and the one block, the robot at its centre.
    let mut world = World::default_arena();
    world.start = Pose2::default();
    world.obstacles.clear();
    world.gates.clear();
    let mut block = world.blocks[0].clone();
    let camera_x = config.vision.mount.translation[0];
    let at = Point2::new(
        camera_x + distance * bearing.cos(),
        distance * bearing.sin(),
    );
    // A marked face towards the camera.
    block.pose = Pose2::new(at.x, at.y, wrap_angle(bearing + std::f64::consts::PI));
    world.blocks = vec![block.clone()];
    let mut twin = Twin::new(world, &config.robot, &config.sim, seed);
    twin.add_arm(arm);
    let mut odometry = Odometry::new(Pose2::default(), config.robot.track);
    let run = |twin: &mut Twin, odometry: &mut Odometry, seconds: f64| {
        let mut seen = Vec::new();
        for _ in 0..(seconds / STEP).round() as usize {
            twin.step(STEP);
            let frame = twin.take_frame();
            odometry.update(frame.wheels.unwrap_or_default());
            seen.extend(frame.sightings.unwrap_or_default());
        }
        seen
    };
    // Look: every sighting of the block's markers, placed from where the robot stands,
    // and pushed half the block's side further on (the marker is on its near face).
    let seen = run(&mut twin, &mut odometry, LOOK);
    let points: Vec<Point2> = (seen.iter())
        .filter(|s| block.markers.contains(&s.id))
        .map(|s| {
            let r = s.range + block.size / 2.0;
            Point2::new(r * s.bearing.cos(), r * s.bearing.sin())
        })
        .collect();
    if points.is_empty() {
        return failed(distance, None, "the camera never saw the block");
    }
    let n = points.len() as f64;
    let estimate = Point2::new(
        points.iter().map(|p| p.x).sum::<f64>() / n,
        points.iter().map(|p| p.y).sum::<f64>() / n,
    );
    // Approach: turn to face the estimate, drive until it stands `[mission] arm_standoff`
    // ahead of the arm, as the mission does.
    let heading = estimate.y.atan2(estimate.x);
    drive_until(
        &mut twin,
        &mut odometry,
        Twist::new(0.0, heading.signum() * 0.5),
        |o| wrap_angle(heading - o.pose().theta).abs() < 0.01,
    );
    let ahead = estimate.distance(odometry.pose().position())
        - crate::mission::arm_reach(arm, config.mission.arm_standoff, block.size / 2.0);
    let start = odometry.pose().position();
    drive_until(
        &mut twin,
        &mut odometry,
        Twist::new(0.05_f64.copysign(ahead), 0.0),
        |o| o.pose().position().distance(start) >= ahead.abs(),
    );
    // The block in the arm's frame, as the robot believes it, and the error against the truth.
    let believed = odometry.pose().inverse_transform_point(estimate);
    let truth = twin.pose().inverse_transform_point(block.pose.position());
    let error_mm = Some(believed.distance(truth) * 1000.0);
    let in_arm = |z: f64| {
        let p = arm.mount.from_robot([believed.x, believed.y, z]);
        Target::point(p[0], p[1], p[2])
    };
    let mid = block.size / 2.0;
    let mut joints = arm.pose("home").unwrap_or_default();
    twin.command_gripper(GripperCommand::Open);
    for z in [mid + ABOVE, mid] {
        match inverse(arm, &in_arm(z), &joints) {
            Ok(s) => joints = s.joints,
            Err(e) => return failed(distance, error_mm, &format!("out of reach: {e}")),
        }
        if let Err(e) = move_arm(&mut twin, arm, joints) {
            return failed(distance, error_mm, &e);
        }
    }
    twin.command_gripper(GripperCommand::Close);
    run(&mut twin, &mut odometry, 1.0);
    if let Ok(s) = inverse(arm, &in_arm(mid + ABOVE), &joints)
        && let Err(e) = move_arm(&mut twin, arm, s.joints)
    {
        return failed(distance, error_mm, &e);
    }
    let success = twin.gripper() == GripperState::Holding;
    Pick {
        distance,
        error_mm,
        success,
        why: (!success).then(|| "the jaws closed on nothing".to_string()),
    }
}

fn failed(distance: f64, error_mm: Option<f64>, why: &str) -> Pick {
    Pick {
        distance,
        error_mm,
        success: false,
        why: Some(why.to_string()),
    }
}

/// Drives at `twist` until `done` says so by the odometry (at most 20 s).
fn drive_until(
    twin: &mut Twin,
    odometry: &mut Odometry,
    twist: Twist,
    done: impl Fn(&Odometry) -> bool,
) {
    for _ in 0..(20.0 / STEP) as usize {
        if done(odometry) {
            break;
        }
        twin.set_command(twist);
        twin.step(STEP);
        let frame = twin.take_frame();
        odometry.update(frame.wheels.unwrap_or_default());
    }
    twin.set_command(Twist::ZERO);
    twin.step(0.5);
    let frame = twin.take_frame();
    odometry.update(frame.wheels.unwrap_or_default());
}

/// Moves the arm to `joints` and waits until it is there, a step at a time: as many steps
/// as the move's time at the joints' speed limits takes, refused when that is longer than
/// any valid arm's longest move (`arm::config::LONGEST_MOVE`, a turn at the slowest speed).
fn move_arm(twin: &mut Twin, arm: &ArmConfig, joints: Joints) -> Result<(), String> {
    let from = Joints(twin.arm_joints().unwrap_or_default());
    let within = crate::arm::move_time(arm, &from, &joints);
    let longest = crate::arm::config::LONGEST_MOVE;
    if within.is_nan() || within > longest {
        return Err(format!(
            "the arm's move would take {} s, more than the longest a valid arm makes ({} s)",
            crate::data::number::short(within),
            crate::data::number::short(longest)
        ));
    }
    twin.command_arm(&ArmTarget {
        joints: joints.0,
        within,
    });
    // 0.2 s more for the twin's arm to settle.
    let steps = ((within + 0.2) / STEP).ceil() as usize;
    for _ in 0..steps {
        twin.step(STEP);
    }
    Ok(())
}
