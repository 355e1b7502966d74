//! The twin itself: a differential-drive robot with encoders, camera, lidar and gripper in a
//! world, advanced only by `step(dt)` and driven by one seeded random generator.

mod arms;
mod grasp;
#[cfg(feature = "vision")]
mod lane;
mod others;
mod sensors;
mod tags;

use super::blocks::BlockState;
use super::collision::{Collider, Disc};
use super::config::{PhysicsConfig, SimConfig};
use super::drive::{integrate, wheel_travel};
use super::encoders::Encoders;
use super::fault::FaultKind;
use super::faults::Faults;
use super::gripper::Gripper;
use super::{Marker, World};
use crate::data::robot::RobotConfig;
use crate::data::{GripperState, SensorFrame};
use crate::geometry::{Pose2, Segment, Twist};
pub use others::Neighbour;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use sensors::Sensors;
use std::sync::Arc;

/// A simulated robot in a simulated world. Cloning copies the whole state, random
/// generator included, so a clone replays exactly what the original would do.
///
/// Simplifications: the footprint is a circle; a held block rides in the jaws without
/// colliding and is invisible to camera and lidar; the camera and lidar sit at the robot
/// centre; a bumped block does not move.
#[derive(Clone, Debug)]
pub struct Twin {
    world: Arc<World>,
    robot: RobotConfig,
    rng: ChaCha8Rng,
    clock: PhysicsClock,
    pose: Pose2,
    command: Twist,
    /// The base's actual (speed- and acceleration-limited) twist.
    drive: Twist,
    /// True path length of the robot centre, metres.
    distance: f64,
    encoders: Encoders,
    sensors: Sensors,
    gripper: Gripper,
    /// An arm, when the robot has one.
    arm: Option<super::arm::TwinArm>,
    blocks: Vec<BlockState>,
    free_blocks: FreeBlocks,
    /// The block the jaws last let go of: it sits between them, so the robot may back
    /// away from it (or stand still) without touching it.
    released: Option<usize>,
    contacts: Contacts,
    /// The faces the lidar sees at the walls' free ends (`World::wall_end_faces`).
    wall_ends: Vec<Segment>,
    /// Faults injected on the twin's time (`--fault`, `:fault`).
    faults: Faults,
    /// A fleet's other robots in the same world (`others.rs`).
    others: others::Others,
}

/// Half the thickness of the twin's walls as the lidar sees their ends, metres: a 5 cm
/// partition (navdeck's figure; world walls are drawn as lines).
const WALL_HALF_THICKNESS: f64 = 0.025;

/// Twin time, counted in whole physics steps.
#[derive(Clone, Debug)]
struct PhysicsClock {
    /// Physics step, seconds.
    h: f64,
    /// Physics steps taken; twin time is `ticks * h`.
    ticks: u64,
    /// Requested time not yet simulated, always under one physics step.
    carry: f64,
    /// `ticks` at the previous `take_frame`.
    taken_at: u64,
}

/// Outlines and markers of the free blocks, rebuilt only when a block moved.
#[derive(Clone, Debug)]
struct FreeBlocks {
    edges: Vec<Segment>,
    markers: Vec<Marker>,
    moved: bool,
}

/// What the robot runs into: the collider, the blocks' discs in the current step,
/// whether it rests against something, and the contacts so far.
#[derive(Clone, Debug)]
struct Contacts {
    collider: Collider,
    discs: Vec<Disc>,
    in_contact: bool,
    collisions: u32,
    /// Contacts with a barrier's arm (`arms.rs`), also counted in `collisions`.
    barrier_hits: u32,
}

impl Twin {
    /// A twin at the world's start pose, its noise drawn from `seed`. Config values are
    /// expected validated; a physics step that is not a positive number falls back to the
    /// default, and a sensor rate that is not positive turns that sensor off.
    pub fn new(world: World, robot: &RobotConfig, sim: &SimConfig, seed: u64) -> Twin {
        let h = if sim.physics.step.is_finite() && sim.physics.step > 0.0 {
            sim.physics.step
        } else {
            PhysicsConfig::default().step
        };
        let wall_ends = world.wall_end_faces(WALL_HALF_THICKNESS);
        Twin {
            pose: world.start,
            blocks: world.blocks.iter().map(BlockState::from_block).collect(),
            world: Arc::new(world),
            robot: robot.clone(),
            clock: PhysicsClock {
                h,
                ticks: 0,
                carry: 0.0,
                taken_at: 0,
            },
            rng: ChaCha8Rng::seed_from_u64(seed),
            command: Twist::ZERO,
            drive: Twist::ZERO,
            encoders: Encoders::new(robot, &sim.encoders),
            sensors: Sensors::new(sim),
            gripper: Gripper::new(&sim.gripper),
            contacts: Contacts {
                collider: Collider::new(robot.footprint_radius),
                discs: Vec::new(),
                in_contact: false,
                collisions: 0,
                barrier_hits: 0,
            },
            distance: 0.0,
            free_blocks: FreeBlocks {
                edges: Vec::new(),
                markers: Vec::new(),
                moved: true,
            },
            arm: None,
            released: None,
            wall_ends,
            faults: Faults::default(),
            others: others::Others::default(),
        }
    }

    pub fn world(&self) -> &World {
        &self.world
    }

    /// Twin time in seconds: whole physics steps taken.
    pub fn time(&self) -> f64 {
        self.clock.ticks as f64 * self.clock.h
    }

    /// True pose (ground truth).
    pub fn pose(&self) -> Pose2 {
        self.pose
    }

    /// Gives the robot the arm of `config`, at rest at home; its gripper is then the
    /// arm's, catching blocks at the tool tip.
    pub fn add_arm(&mut self, config: &crate::arm::ArmConfig) {
        self.arm = Some(super::arm::TwinArm::new(config));
    }

    /// Asks the arm for new joint positions (no arm, or an arm fault: nothing happens).
    pub fn command_arm(&mut self, target: &crate::data::ArmTarget) {
        if self.faults.is_active(FaultKind::Arm) {
            return;
        }
        if let Some(arm) = self.arm.as_mut() {
            arm.command(target);
        }
    }

    /// The arm's joints, when there is an arm.
    pub fn arm_joints(&self) -> Option<[f64; 4]> {
        self.arm.as_ref().map(|a| a.joints())
    }

    /// Carries the robot to `pose` without its wheels turning: the kidnapped robot of
    /// Probabilistic Robotics 8.3, for tests of recovery. The odometry knows nothing of it.
    pub fn teleport(&mut self, pose: Pose2) {
        self.pose = pose;
        self.drive = Twist::ZERO;
    }

    /// The base's actual twist after speed and acceleration limits (zero after a collision).
    pub fn velocity(&self) -> Twist {
        self.drive
    }

    /// The twist asked for; held until the next call.
    pub fn set_command(&mut self, twist: Twist) {
        self.command = twist;
    }

    /// The twist last asked for.
    pub fn command(&self) -> Twist {
        self.command
    }

    /// Advances the twin by `dt` seconds in whole physics steps; the remainder under one
    /// step carries to the next call, so one call of 1.0 s equals ten calls of 0.1 s.
    /// A `dt` that is not a positive finite number does nothing.
    pub fn step(&mut self, dt: f64) {
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        self.clock.carry += dt;
        // Slack of a millionth of a step absorbs sums like 10 x 0.1 != 1.0.
        let n = (self.clock.carry / self.clock.h + 1e-6).floor();
        if n < 1.0 {
            return;
        }
        self.clock.carry = (self.clock.carry - n * self.clock.h).max(0.0);
        for _ in 0..n as u64 {
            self.tick();
        }
    }

    /// What the robot reported since the previous take: wheel travel (always, but for an
    /// odometry fault), the newest camera frame and scan (if any arrived), the gripper
    /// state (always), the arm's joints (with an arm, but for an arm fault) and the tags
    /// in view (with a tag map on the floor).
    pub fn take_frame(&mut self) -> SensorFrame {
        let h = self.clock.h;
        let taken_at = self.clock.taken_at as f64 * h;
        let mut elapsed = (self.clock.ticks - self.clock.taken_at) as f64 * h;
        self.clock.taken_at = self.clock.ticks;
        let now = self.time();
        let odometry_silent = self.faults.is_active(FaultKind::Odom);
        // The wheel travel covers the time since the previous take, or since an odometry
        // fault ended if that was later: the encoders counted nothing before.
        if let Some(end) = self
            .faults
            .last_ended(FaultKind::Odom)
            .filter(|e| *e > taken_at)
        {
            elapsed = (now - end).max(0.0);
        }
        let arm_silent = self.faults.is_active(FaultKind::Arm);
        // Counts from before a silence began go unreported with it.
        let wheels = self.encoders.take();
        SensorFrame {
            stamp: now,
            elapsed: if odometry_silent { 0.0 } else { elapsed },
            wheels: (!odometry_silent).then_some(wheels),
            sightings: self.sensors.take_sightings(),
            scan: self.sensors.take_scan(),
            gripper: Some(self.gripper.state()),
            camera: self.sensors.take_camera_status(),
            initial_pose: None,
            goal: None,
            arm: (self.arm.as_ref())
                .filter(|_| !arm_silent)
                .map(|a| a.state()),
            lane: self.sensors.take_lane(),
            tags: self.take_tags(),
        }
    }

    /// The faults injected so far and which are in force (simulated time).
    pub fn faults(&self) -> &Faults {
        &self.faults
    }

    /// The fault schedule, to add to or clear (`--fault`, `:fault`); its times are the
    /// twin's.
    pub fn faults_mut(&mut self) -> &mut Faults {
        &mut self.faults
    }

    /// Replaces the ideal marker sensor by a rendered camera read with the ArUco
    /// detector (feature `vision`), which sees no further than the ideal sensor did and
    /// draws `frames`; with a stopwatch, detection latency is reported. Returns the
    /// camera's detector.
    #[cfg(feature = "vision")]
    pub fn use_rendered_camera(
        &mut self,
        vision: &crate::perception::config::VisionConfig,
        stopwatch: Option<Arc<dyn crate::clock::Clock>>,
        frames: super::CameraFrames,
    ) -> Result<&crate::perception::aruco::Detector, crate::perception::aruco::VisionError> {
        self.sensors.use_rendered_camera(vision, stopwatch, frames)
    }

    pub fn blocks(&self) -> &[BlockState] {
        &self.blocks
    }

    pub fn gripper(&self) -> GripperState {
        self.gripper.state()
    }

    /// Contacts so far; a contact lasting many steps counts once.
    pub fn collisions(&self) -> u32 {
        self.contacts.collisions
    }

    /// True while the robot rests against something it ran into.
    pub fn in_contact(&self) -> bool {
        self.contacts.in_contact
    }

    /// True path length of the robot centre, metres.
    pub fn distance_driven(&self) -> f64 {
        self.distance
    }

    /// One physics step: gripper, drive, collision, then any sensor that is due.
    fn tick(&mut self) {
        let h = self.clock.h;
        if let Some(arm) = self.arm.as_mut() {
            arm.step(h);
            self.carry_in_arm();
        }
        if self.gripper.advance(h) {
            self.catch_block();
        }
        let before = self.drive;
        let target = self.robot.clamp_twist(self.command);
        self.drive = self.robot.ramp(before, target, h);
        // Speed changes linearly within the step: the mean twist gives its travel.
        let mean = before.halfway(self.drive);
        if !mean.is_zero() {
            self.move_base(mean);
        }
        self.clock.ticks += 1;
        let now = self.time();
        self.faults.advance(now);
        if self.sensors.camera_due(now) {
            if self.faults.is_active(FaultKind::Camera) {
                self.sensors.capture_dark();
            } else {
                self.capture_camera();
            }
        }
        #[cfg(feature = "vision")]
        self.capture_lane(now, self.faults.is_active(FaultKind::Camera));
        // A silent lidar keeps its clock: scans resume on their own schedule.
        if self.sensors.lidar_due(now) && !self.faults.is_active(FaultKind::Lidar) {
            self.capture_scan();
        }
    }

    /// Turns the wheels for one step, unless that would run the footprint into something.
    fn move_base(&mut self, twist: Twist) {
        let track = self.robot.track;
        let (l, r) = wheel_travel(twist, track, self.clock.h);
        let mut wheels = self.encoders.sample(&mut self.rng, [l, r]);
        if let Some(ratio) = self.faults.slip_ratio() {
            // A slip fault: the contact points cover only `ratio` of the turned rims,
            // which the encoders still count in full.
            wheels.ground = wheels.ground.map(|g| g * ratio);
        }
        let next = integrate(self.pose, wheels.ground[0], wheels.ground[1], track);
        self.contacts.discs.clear();
        let reach = self.gripper.reach_far();
        if let Some(i) = self.released
            && (!self.gripper.jaws_open()
                || self.blocks[i]
                    .pose
                    .position()
                    .distance(self.pose.position())
                    > reach + self.blocks[i].radius())
        {
            // Clear of the jaws, or they shut: the block is an ordinary obstacle again.
            self.released = None;
        }
        for (i, b) in self.blocks.iter().enumerate().filter(|(_, b)| !b.held) {
            if self.released == Some(i) {
                continue;
            }
            // A block may slide into open jaws (seed 001 approaches blocks with the gripper
            // open); an arm's jaws are up on the arm, and the base runs into blocks.
            if self.arm.is_none()
                && self.gripper.jaws_open()
                && self.gripper.jaw_offset(next, b.pose.position()).is_some()
            {
                continue;
            }
            self.contacts.discs.push(Disc {
                center: b.pose.position(),
                radius: b.radius(),
            });
        }
        self.contacts.discs.extend_from_slice(&self.others.discs);
        let verdict = self.contacts.collider.check(
            &self.world.walls,
            &self.contacts.discs,
            self.pose.position(),
            next.position(),
            self.contacts.in_contact,
        );
        let under_arm = self.arm_in_the_way(self.pose.position(), next.position());
        if under_arm && !self.contacts.in_contact {
            self.contacts.barrier_hits += 1;
        }
        if verdict.blocked || under_arm {
            self.drive = Twist::ZERO;
            let r = self.robot.footprint_radius;
            if !self.contacts.in_contact && self.others.touches(next.position(), r) {
                self.others.hits += 1;
            }
            if !self.contacts.in_contact {
                self.contacts.collisions += 1;
                self.contacts.in_contact = true;
            }
            return;
        }
        if verdict.moves_away {
            self.contacts.in_contact = false;
        }
        // Silent odometry: what the wheels turn now is never reported.
        if !self.faults.is_active(FaultKind::Odom) {
            self.encoders.commit(&wheels);
        }
        self.distance += ((wheels.ground[0] + wheels.ground[1]) / 2.0).abs();
        self.pose = next;
        if let Some((i, pose)) = self.gripper.held_pose(self.pose) {
            self.blocks[i].pose = pose;
            self.free_blocks.moved = true;
        }
        self.carry_in_arm();
    }

    fn capture_camera(&mut self) {
        self.refresh_blocks();
        let occluders: [&[Segment]; 3] = [
            &self.world.walls,
            &self.free_blocks.edges,
            &self.others.outlines,
        ];
        let markers = self.world.markers.iter().chain(&self.free_blocks.markers);
        self.sensors
            .capture_camera(self.pose, markers, &occluders, &mut self.rng);
    }

    fn capture_scan(&mut self) {
        self.refresh_blocks();
        let solids: [&[Segment]; 4] = [
            &self.world.walls,
            &self.wall_ends,
            &self.free_blocks.edges,
            &self.others.outlines,
        ];
        self.sensors.capture_scan(self.pose, &solids, &mut self.rng);
    }
}
