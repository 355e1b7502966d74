//! The mission state machine driven by scripted inputs: a tiny stand-in for the console
//! (straight-line paths, a gripper that catches what lies between its jaws) and hand-made
//! landmark maps. No twin, no clock: every run is the same.

use navdeck::geometry::{Point2, Pose2, wrap_angle};
use navdeck::link::{GripperCommand, GripperState};
use navdeck::map::costmap::{Costmap, FREE, NO_INFORMATION};
use navdeck::mission::step::{Inputs, Motion, Outputs, PathStatus};
use navdeck::mission::{Mission, MissionConfig, TargetRule};
use std::collections::BTreeMap;
use std::f64::consts::PI;

const DT: f64 = 0.1;

/// A scripted console around the mission.
struct Rig {
    mission: Mission,
    t: f64,
    pose: Pose2,
    landmarks: BTreeMap<u32, Point2>,
    seen: Vec<u32>,
    camera_frame: bool,
    gripper: Option<GripperState>,
    path: PathStatus,
    map: Costmap,
    /// Follow planned paths in straight lines at 0.2 m/s and run the gripper.
    auto: bool,
    /// Block centres by odd marker (where they really are), for the gripper.
    blocks: Vec<(u32, Point2)>,
    goal: Option<Point2>,
    /// Gripper command in progress and when it was given.
    pending: Option<(GripperCommand, f64)>,
    log: Vec<String>,
    commands: Vec<GripperCommand>,
    plans: Vec<(f64, Point2, String)>,
}

impl Rig {
    fn new(config: MissionConfig, map: Costmap) -> Self {
        Self {
            mission: Mission::new(config, 0.0),
            t: 0.0,
            pose: Pose2::new(0.0, 0.0, 0.0),
            landmarks: BTreeMap::new(),
            seen: vec![1],
            camera_frame: true,
            gripper: Some(GripperState::Closed),
            path: PathStatus::Idle,
            map,
            auto: true,
            blocks: Vec::new(),
            goal: None,
            pending: None,
            log: Vec::new(),
            commands: Vec::new(),
            plans: Vec::new(),
        }
    }

    /// A 0.05 m block centred at (x, y), turned so both marked faces look towards -x.
    fn add_block(&mut self, odd: u32, x: f64, y: f64) {
        let k = 0.025 * std::f64::consts::FRAC_1_SQRT_2;
        self.landmarks.insert(odd, Point2::new(x - k, y + k));
        self.landmarks.insert(odd + 1, Point2::new(x - k, y - k));
        self.blocks.push((odd, Point2::new(x, y)));
        self.seen.extend([odd, odd + 1]);
    }

    /// The red gate centred at (-1, 1) on a wall along y, facing +x.
    fn add_red_gate(&mut self) {
        self.landmarks.insert(401, Point2::new(-1.0, 1.15));
        self.landmarks.insert(402, Point2::new(-1.0, 0.85));
    }

    fn step(&mut self) -> Outputs {
        let inputs = Inputs {
            t: self.t,
            pose: self.pose,
            landmarks: &self.landmarks,
            seen: if self.camera_frame { &self.seen } else { &[] },
            camera_frame: self.camera_frame,
            gripper: self.gripper,
            path: &self.path,
            map: &self.map,
        };
        let out = self.mission.step(&inputs);
        self.log.extend(out.log.iter().map(|(_, l)| l.clone()));
        if let Some(c) = out.gripper {
            self.commands.push(c);
            if self.auto {
                self.pending = Some((c, self.t));
                self.gripper = Some(match c {
                    GripperCommand::Open => GripperState::Opening,
                    GripperCommand::Close => GripperState::Closing,
                });
            }
        }
        match &out.motion {
            Motion::Drive(tw) => {
                self.pose.theta = wrap_angle(self.pose.theta + tw.angular * DT);
                self.pose.x += tw.linear * DT * self.pose.theta.cos();
                self.pose.y += tw.linear * DT * self.pose.theta.sin();
            }
            Motion::PlanTo { goal, label } => {
                self.plans.push((self.t, *goal, label.clone()));
                if self.auto {
                    self.goal = Some(*goal);
                    let remaining = self.pose.position().distance(*goal);
                    self.path = PathStatus::Following { remaining };
                }
            }
            Motion::Follow if self.auto => self.follow(),
            _ => {}
        }
        if self.auto {
            self.run_gripper();
        }
        self.t += DT;
        out
    }

    fn follow(&mut self) {
        let Some(goal) = self.goal else { return };
        let d = self.pose.position().distance(goal);
        if d > 1e-9 {
            self.pose.theta = (goal.y - self.pose.y).atan2(goal.x - self.pose.x);
        }
        let step = d.min(0.2 * DT);
        self.pose.x += step * self.pose.theta.cos();
        self.pose.y += step * self.pose.theta.sin();
        let remaining = d - step;
        self.path = if remaining < 1e-9 {
            self.goal = None;
            PathStatus::Arrived
        } else {
            PathStatus::Following { remaining }
        };
    }

    /// The twin's jaws: a block 0.06-0.14 m ahead within 0.035 m sideways is caught.
    fn run_gripper(&mut self) {
        let Some((command, since)) = self.pending else {
            return;
        };
        if self.t - since < 0.5 {
            return;
        }
        self.pending = None;
        self.gripper = Some(match command {
            GripperCommand::Open => GripperState::Open,
            GripperCommand::Close => {
                let caught = self.blocks.iter().any(|(_, c)| {
                    let local = self.pose.inverse_transform_point(*c);
                    (0.06..=0.14).contains(&local.x) && local.y.abs() <= 0.035
                });
                if caught {
                    GripperState::Holding
                } else {
                    GripperState::Closed
                }
            }
        });
    }

    /// Steps until `done` holds for the outputs; panics after `max` steps.
    fn until(&mut self, max: usize, done: impl Fn(&Outputs, &Rig) -> bool) -> Outputs {
        for _ in 0..max {
            let out = self.step();
            if done(&out, self) {
                return out;
            }
        }
        panic!(
            "not reached by t = {:.1}; state {}; log {:#?}",
            self.t,
            self.mission.state_label(),
            self.log
        );
    }

    fn logged(&self, text: &str) -> bool {
        self.log.iter().any(|l| l.contains(text))
    }
}

fn plan_to(out: &Outputs) -> Option<(Point2, &str)> {
    match &out.motion {
        Motion::PlanTo { goal, label } => Some((*goal, label.as_str())),
        _ => None,
    }
}

/// 4 m x 2 m: known free on the left half, unknown on the right (one long frontier at x = 0.95).
fn half_known() -> Costmap {
    let mut map = Costmap::new(40, 20, 0.1, Point2::new(-2.0, -1.0), NO_INFORMATION);
    for y in 0..20 {
        for x in 0..30 {
            map.set(x, y, FREE);
        }
    }
    map
}

fn all_free() -> Costmap {
    Costmap::new(40, 40, 0.1, Point2::new(-2.0, -2.0), FREE)
}

fn config(total_blocks: u32) -> MissionConfig {
    MissionConfig {
        total_blocks,
        ..MissionConfig::default()
    }
}

#[test]
fn the_initial_scan_turns_a_full_turn_then_plans_to_a_frontier() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    let out = rig.until(200, |out, _| plan_to(out).is_some());
    let turned = rig.t - DT; // time spent turning: the last step planned
    assert!(rig.logged("Initial rotation scan"));
    assert!(
        turned >= 2.0 * PI / 0.6,
        "planned after {turned:.1} s, before a full turn"
    );
    assert!(turned < 2.0 * PI / 0.6 + 0.5);
    let (goal, label) = plan_to(&out).unwrap();
    assert!((goal.x - 0.95).abs() < 1e-9, "{goal:?}");
    assert!(label.starts_with("frontier"), "{label}");
    assert!(rig.logged("Thinking path to frontier"));
    assert!(rig.mission.state_label().starts_with("explore frontier"));
    // While the path is followed: Follow, and no second PlanTo.
    rig.path = PathStatus::Following { remaining: 0.9 };
    for _ in 0..20 {
        assert_eq!(rig.step().motion, Motion::Follow);
    }
}

#[test]
fn a_deliverable_block_beats_exploring_and_interrupts_it() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    for _ in 0..10 {
        rig.step();
    }
    // Block and gate come into view while following the frontier path.
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    let out = rig.step();
    let (goal, label) = plan_to(&out).expect("plans to the block at once");
    assert_eq!(label, "red block 421");
    assert!(goal.distance(Point2::new(0.7, 0.0)) < 1e-6, "{goal:?}");
    assert!(rig.logged("Found red block 421"));
    assert!(rig.logged("Found red gate"));
    assert!(rig.logged("Found red gate and blocks - switching to thinking"));
    assert_eq!(rig.mission.state_label(), "travel to red block 421");
    assert_eq!(rig.mission.known_blocks(), 1);

    // Known from the start: the first plan after the scan goes to the block.
    let mut rig = Rig::new(config(4), half_known());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    let out = rig.until(200, |out, _| plan_to(out).is_some());
    assert_eq!(plan_to(&out).unwrap().1, "red block 421");
}

/// Runs from the start to the delivery plan; returns the rig.
fn picked_up(total: u32) -> Rig {
    let mut rig = Rig::new(config(total), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |out, _| {
        plan_to(out).is_some_and(|p| p.1 == "red gate")
    });
    rig
}

#[test]
fn the_pick_up_sequence_opens_faces_approaches_closes_and_heads_for_the_gate() {
    let mut rig = Rig::new(config(4), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.until(100, |_, r| {
        r.mission.state_label() == "open gripper for red block 421"
    });
    assert!(rig.pose.position().distance(Point2::new(0.7, 0.0)) < 1e-6);
    assert!(rig.logged("Path found") && rig.logged("Following path to red block 421"));
    assert_eq!(rig.commands, [GripperCommand::Open]);
    // Turn the robot away: it must face the block again before approaching.
    rig.pose.theta = 0.5;
    rig.until(50, |_, r| r.mission.state_label() == "face red block 421");
    rig.until(100, |_, r| {
        r.mission.state_label() == "approach red block 421"
    });
    assert!(rig.pose.theta.abs() < 3f64.to_radians(), "{:?}", rig.pose);
    let out = rig.until(200, |out, _| out.gripper == Some(GripperCommand::Close));
    assert!(out.ignore_markers.is_empty(), "not held yet");
    let ahead = rig.pose.inverse_transform_point(Point2::new(1.0, 0.0));
    assert!(
        (ahead.x - 0.10).abs() < 0.01 && ahead.y.abs() < 0.01,
        "{ahead:?}"
    );
    let out = rig.until(50, |out, _| plan_to(out).is_some());
    let (goal, _) = plan_to(&out).unwrap();
    assert!(goal.distance(Point2::new(-0.6, 1.0)) < 1e-9, "{goal:?}");
    assert!(rig.logged("Picked up red block 421"));
    assert_eq!(out.ignore_markers, [421, 422]);
    assert_eq!(rig.commands, [GripperCommand::Open, GripperCommand::Close]);
    let entry = rig.mission.timeline()[0];
    assert_eq!(entry.0, 421);
    assert!(entry.2.is_some() && entry.3.is_none());
}

#[test]
fn the_delivery_sequence_drops_backs_off_and_counts() {
    let mut rig = picked_up(4);
    rig.until(300, |_, r| {
        r.mission.state_label().starts_with("face red gate")
    });
    rig.until(100, |_, r| r.mission.state_label().starts_with("drive"));
    assert!(wrap_angle(rig.pose.theta - PI).abs() < 3f64.to_radians());
    rig.until(200, |out, _| out.gripper == Some(GripperCommand::Open));
    let gate = Point2::new(-1.0, 1.0);
    assert!((rig.pose.position().distance(gate) - 0.18).abs() < 0.01);
    let at_drop = rig.pose.position();
    let out = rig.until(100, |out, _| !out.log.is_empty());
    assert!(rig.logged("Delivered red block 421 (1/4)"), "{:?}", rig.log);
    assert!(
        (rig.pose.position().distance(at_drop) - 0.2).abs() < 0.011,
        "backs off 2 s at 0.1 m/s"
    );
    assert_eq!(rig.mission.delivered(), 1);
    assert_eq!(
        out.ignore_markers,
        [421, 422],
        "delivered markers stay ignored"
    );
    assert_eq!(
        rig.commands,
        [
            GripperCommand::Open,
            GripperCommand::Close,
            GripperCommand::Open
        ]
    );
    assert!(rig.mission.timeline()[0].3.is_some());
    // Nothing else to do in an explored arena with 1 of 4 blocks: manual.
    let out = rig.step();
    assert!(out.to_manual, "{:?}", rig.log);
    assert!(rig.logged("Exploration complete"));
    assert!(!rig.mission.is_done());
}

#[test]
fn the_mission_is_done_after_total_blocks_deliveries() {
    let mut rig = Rig::new(config(2), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_block(423, 1.0, -0.6);
    rig.add_red_gate();
    rig.until(3000, |_, r| r.mission.is_done());
    assert_eq!(rig.mission.delivered(), 2);
    assert!(rig.logged("Delivered red block 423 (2/2)"), "{:?}", rig.log);
    assert!(rig.logged("All 2 blocks delivered - mission complete"));
    let timeline = rig.mission.timeline();
    assert_eq!(timeline.len(), 2);
    assert!(timeline.iter().all(|e| e.2.is_some() && e.3.is_some()));
    let out = rig.step();
    assert_eq!(out.motion, Motion::Stop);
    assert!(!out.to_manual);
    let mut ignored = out.ignore_markers.clone();
    ignored.sort();
    assert_eq!(ignored, [421, 422, 423, 424]);
    assert_eq!(rig.mission.state_label(), "done");
}

#[test]
fn an_empty_gripper_reopens_and_retries_once_then_demotes_the_block() {
    let mut rig = Rig::new(config(4), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    // The block is really 5 cm to the side of where the map has it: the jaws miss.
    rig.blocks[0].1 = Point2::new(1.0, 0.05);
    rig.until(800, |_, r| r.logged("Gripper closed on nothing"));
    assert!(rig.mission.state_label().starts_with("reopen"));
    rig.until(300, |_, r| r.logged("back to a potential block"));
    assert_eq!(
        rig.commands,
        [
            GripperCommand::Open,
            GripperCommand::Close,
            GripperCommand::Open,
            GripperCommand::Close
        ]
    );
    assert!(rig.mission.recoveries() >= 2);
    assert!(rig.mission.timeline()[0].2.is_none(), "never picked");
    // Not straight back to the same block: it waits as a potential one.
    let out = rig.step();
    assert!(
        !rig.mission
            .state_label()
            .contains("travel to red block 421"),
        "{}",
        rig.mission.state_label()
    );
    assert!(out.ignore_markers.is_empty());
}

#[test]
fn a_block_unseen_in_view_for_3_s_during_the_approach_is_demoted() {
    let mut rig = Rig::new(config(4), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |_, r| r.mission.state_label() == "face red block 421");
    rig.seen = vec![1];
    let start = rig.t;
    rig.until(100, |_, r| {
        r.logged("Lost red block 421 during the approach")
    });
    let took = rig.t - start;
    assert!((3.0..3.3).contains(&took), "{took}");
    assert!(!rig.mission.state_label().contains("approach red block"));
    assert_eq!(
        rig.mission.known_blocks(),
        0,
        "demoted to a potential block"
    );
}

#[test]
fn a_lost_robot_scans_after_10_s_and_hands_over_after_30_s() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    let dark = rig.t;
    let out = rig.until(200, |out, _| matches!(out.motion, Motion::Drive(_)));
    assert!(rig.logged("No landmarks for 10 s - rotating to scan"));
    assert!(rig.t - dark >= 10.0 - 1.0 && rig.t - dark <= 10.2);
    let Motion::Drive(tw) = out.motion else {
        unreachable!()
    };
    assert!(tw.linear == 0.0 && tw.angular > 0.0);
    let out = rig.until(300, |out, _| out.to_manual);
    assert!(rig.logged("Robot lost: no landmarks for 30 s - switching to manual"));
    assert!((rig.t - dark - 30.0).abs() < 1.5, "{}", rig.t - dark);
    assert_eq!(out.motion, Motion::Stop);
    assert!(rig.mission.recoveries() >= 1);
}

#[test]
fn a_lost_robot_that_sees_a_marker_again_goes_back_to_choosing() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    rig.until(200, |_, r| r.mission.state_label().starts_with("lost"));
    rig.seen = vec![1];
    let out = rig.until(20, |out, _| plan_to(out).is_some());
    assert!(!out.to_manual);
    assert!(rig.logged("Landmarks back in view"));
}

#[test]
fn no_path_turns_10_degrees_and_retries_then_hands_over_after_36() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    let first = rig.plans.len();
    rig.path = PathStatus::NoPath("goal in an obstacle".into());
    let mut headings = vec![rig.pose.theta];
    let out = rig.until(2000, |out, r| {
        out.to_manual || (plan_to(out).is_some() && r.plans.len() == first + 1)
    });
    assert!(!out.to_manual);
    headings.push(rig.pose.theta);
    assert!(
        rig.logged("turning 10° and retrying (1/36)"),
        "{:?}",
        rig.log
    );
    let turned = wrap_angle(headings[1] - headings[0]);
    assert!(
        turned >= 10f64.to_radians() - 1e-9 && turned < 16f64.to_radians(),
        "{turned}"
    );
    let out = rig.until(2000, |out, _| out.to_manual);
    assert_eq!(rig.plans.len() - first, 36, "36 retries");
    assert!(rig.logged("(36/36)"));
    assert!(rig.logged("after 36 retries - switching to manual"));
    assert_eq!(rig.mission.replans(), 36);
    assert_eq!(out.motion, Motion::Stop);
    let gaps = rig.plans.windows(2).map(|w| w[1].0 - w[0].0);
    assert!(gaps.clone().all(|g| g >= 0.5 - 1e-9), "cooldown");
}

#[test]
fn a_stuck_path_is_replanned_after_30_s_and_dropped_paths_respect_the_cooldown() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    let asked = rig.t - DT;
    // Creeping: 4 cm in 30 s is no progress.
    for i in 0..400 {
        rig.path = PathStatus::Following {
            remaining: 0.9 - 0.0001 * i as f64,
        };
        let out = rig.step();
        if plan_to(&out).is_some() {
            break;
        }
    }
    let replanned = rig.plans.last().unwrap().0;
    assert!(
        (replanned - asked - 30.0).abs() < 0.15,
        "{}",
        replanned - asked
    );
    assert!(rig.logged("Stuck: no progress for 30 s"));
    assert_eq!(rig.mission.replans(), 1);
    // Progress resets the clock: steady progress never replans.
    let n = rig.plans.len();
    for i in 0..400 {
        rig.path = PathStatus::Following {
            remaining: 0.9 - 0.002 * i as f64,
        };
        rig.step();
    }
    assert_eq!(rig.plans.len(), n);
    // The console drops the path each time: plan requests at most every 0.5 s.
    rig.path = PathStatus::Idle;
    for _ in 0..30 {
        rig.step();
    }
    let times: Vec<f64> = rig.plans[n..].iter().map(|p| p.0).collect();
    assert!(times.len() >= 4, "{times:?}");
    assert!(
        times.windows(2).all(|w| w[1] - w[0] >= 0.5 - 1e-9),
        "{times:?}"
    );
}

#[test]
fn the_marker_rule_visits_the_furthest_markers_and_either_rule_falls_back_to_the_other() {
    for rule in [TargetRule::Markers, TargetRule::Frontiers] {
        let config = MissionConfig {
            target_rule: rule,
            ..MissionConfig::default()
        };
        // No frontiers in a fully known map: the frontier rule falls back to markers.
        let mut rig = Rig::new(config, all_free());
        rig.landmarks.insert(1, Point2::new(1.5, 0.0));
        rig.landmarks.insert(2, Point2::new(2.0, 0.5));
        let out = rig.until(200, |out, _| plan_to(out).is_some());
        let (goal, label) = plan_to(&out).unwrap();
        assert_eq!(label, "marker 2", "{rule:?}");
        let stop = Point2::new(2.0, 0.5);
        assert!(
            (goal.distance(stop) - 0.3).abs() < 1e-9,
            "short of the wall"
        );
        rig.until(400, |out, _| plan_to(out).is_some());
        assert_eq!(rig.plans.last().unwrap().2, "marker 1");
        let out = rig.until(400, |out, _| out.to_manual);
        assert!(rig.logged("Exploration complete"));
        assert!(rig.logged("with 0/4 blocks delivered - switching to manual"));
        assert!(out.to_manual && !rig.mission.is_done());
    }
}

#[test]
fn with_total_blocks_0_every_found_block_is_delivered_then_the_mission_ends() {
    let mut rig = Rig::new(config(0), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(1500, |_, r| r.mission.is_done());
    assert_eq!(rig.mission.delivered(), 1);
    assert!(rig.logged("Delivered red block 421 (1)"), "{:?}", rig.log);
    assert!(rig.logged("Exploration complete"));
}

#[test]
fn a_gripper_without_feedback_is_trusted_after_the_seed_wait() {
    let mut rig = Rig::new(config(1), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |out, _| out.gripper == Some(GripperCommand::Close));
    rig.auto = false;
    rig.gripper = None;
    let start = rig.t;
    rig.until(30, |out, _| plan_to(out).is_some());
    assert!((rig.t - start - 1.0).abs() < 0.15, "{}", rig.t - start);
    assert!(rig.logged("Picked up red block 421"));
}
