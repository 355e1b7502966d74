//! The collision monitor as a behaviour (priority 90): each control step it weighs the
//! task's command against the newest lidar scan, its points moved to where the robot now
//! stands (Nav2's `base_shift_correction`, by odometry since the scan), or, on a robot that
//! never sent a scan or whose lidar is lost, against the planning map's occupied cells
//! round it; when a zone
//! changes the command, the monitor proposes the changed one and so wins.

use super::{Behaviour, Proposal};
use crate::Pilot;
use navdeck_core::control::collision_monitor::{
    ActionType, CollisionMonitor, Obstacles, SafetyConfig, SourceKind, points_from_grid,
    points_from_scan,
};
use navdeck_core::data::GripperState;
use navdeck_core::geometry::{Point2, Pose2, Twist};
use navdeck_core::map::contact::{HeldZone, JAWS};
use navdeck_core::map::grid::{OCCUPIED, OccupancyGrid, UNKNOWN};

/// Map cells are read this far round a robot without a lidar, metres.
const MAP_RADIUS_M: f64 = 1.0;
/// A lidar does not see closer than its least range (an LDS-01's 0.12 m is beyond a
/// Burger's footprint): hits this near are remembered, by odometry, for this long, so that
/// an obstacle the robot stopped short of still holds it once it is too near to see.
const REMEMBER_WITHIN_M: f64 = 0.35;
const REMEMBER_FOR_S: f64 = 2.0;
/// While a block is picked up and the lidar does not outline it, the hits this near its
/// marker's estimate are the block (a 5 cm block seen from any side, and the estimate's
/// error), metres.
const PICKED_BLOCK_M: f64 = 0.1;
/// While a block is picked up and the lidar outlines it, the hits within its corners'
/// circle widened by `OUTLINE_MARGIN_M`, or in that circle's width between it and the
/// robot, are the block, and only while it lies in the gripper's open mouth (this far
/// either side of the robot's axis: a TurtleBot3 gripper's jaws are 7 cm apart, less the
/// outline's error): the creep takes it between the jaws. A block whose near face sinks
/// under the lidar's least range is outlined by its sides and far face, centimetres too
/// far; its near face, remembered from earlier scans, is still the block. Off the axis
/// its face would meet a jaw, and it stops the creep like any obstacle.
const MOUTH_HALF_WIDTH_M: f64 = 0.025;
const OUTLINE_MARGIN_M: f64 = 0.02;
/// While a block is held, hits in the gripper's jaws (`map::contact::JAWS`) widened by this
/// are the block, metres.
const HELD_MARGIN_M: f64 = 0.03;

/// The monitor and what it remembers between steps.
#[derive(Clone, Debug)]
pub(crate) struct CollisionWatch {
    pub monitor: CollisionMonitor,
    /// The same zones' stop zones alone, while a block is handled: its final approaches
    /// are slow and guarded already, and an approach zone would slow them further.
    handling_monitor: CollisionMonitor,
    /// When the newest scan arrived and the odometry pose then.
    pub scan_at: Option<(f64, Pose2)>,
    /// The planning map as a grid, the map revision it was made at, and whether its
    /// unknown cells were made occupied (the lidar lost).
    map_grid: Option<((u64, bool), OccupancyGrid)>,
    /// Near hits of recent scans (odometry frame), and when each scan arrived.
    remembered: Vec<(f64, Vec<Point2>)>,
}

impl CollisionWatch {
    pub fn new(config: &SafetyConfig, footprint_radius: f64) -> Self {
        let mut stops = config.clone();
        stops.polygons.retain(|p| p.action_type == ActionType::Stop);
        Self {
            monitor: CollisionMonitor::new(config, footprint_radius),
            handling_monitor: CollisionMonitor::new(&stops, footprint_radius),
            scan_at: None,
            map_grid: None,
            remembered: Vec::new(),
        }
    }
}

impl Pilot {
    /// A scan arrived at `t`: the monitor reads its points from where the robot was.
    pub(crate) fn note_scan_for_monitor(&mut self, t: f64) {
        self.behaviours.collision.scan_at = Some((t, self.odometry.pose()));
    }

    /// The newest scan: when it arrived, the odometry pose then, and its hits in the
    /// robot's frame then; `None` without a scan, or with the lidar lost (its last scan
    /// grows stale).
    fn newest_hits(&self) -> Option<(f64, Pose2, Vec<Point2>)> {
        let (at, then) = (self.behaviours.collision.scan_at)
            .filter(|_| !self.sensor_lost(navdeck_core::health::Sensor::Lidar))?;
        let (_, scan) = self.newest_scan()?;
        Some((at, then, points_from_scan(scan, Pose2::default())))
    }

    /// The newest scan's hits in the robot's frame now (moved by odometry since it was
    /// taken); empty without a scan, or with the lidar lost.
    pub(crate) fn scan_here(&self) -> Vec<Point2> {
        self.newest_hits()
            .map(|(_, then, hits)| shifted(&hits, self.odometry.pose(), then))
            .unwrap_or_default()
    }

    /// The monitor's proposal at `t` against the task's `twist`, when it changes it. With
    /// `handling` (pick-and-place: a block is being picked up or carried), the block itself
    /// is touched by design: the hits of the picked block (its live outline in the jaws'
    /// mouth, else near its marker) or in the jaws that hold it are not obstacles, and
    /// only the stop zones act.
    pub(crate) fn collision_proposal(
        &mut self,
        t: f64,
        twist: Twist,
        handling: bool,
    ) -> Option<Proposal> {
        if !self.behaviours.arbiter.is_on(Behaviour::CollisionMonitor) {
            return None;
        }
        let odom = self.odometry.pose();
        // Without a fresh scan (the lidar lost), the map is the source.
        let (mut points, age, source) = match self.newest_hits() {
            Some((at, then, hits)) => {
                // From the robot's frame then to its frame now.
                let mut points = shifted(&hits, odom, then);
                let watch = &mut self.behaviours.collision;
                watch
                    .remembered
                    .retain(|(seen, _)| t - seen <= REMEMBER_FOR_S);
                if watch.remembered.last().is_none_or(|(seen, _)| *seen < at) {
                    let near = (hits.iter())
                        .filter(|p| p.x.hypot(p.y) <= REMEMBER_WITHIN_M)
                        .map(|&p| then.transform_point(p))
                        .collect();
                    watch.remembered.push((at, near));
                }
                let older = watch
                    .remembered
                    .iter()
                    .rev()
                    .skip(1)
                    .flat_map(|(_, near)| near);
                points.extend(older.map(|&p| odom.inverse_transform_point(p)));
                (points, Some(t - at), SourceKind::Scan)
            }
            None => (self.map_points(), Some(0.0), SourceKind::Map),
        };
        // Keepout zones' edges are obstacles too (zones.rs).
        points.extend(self.keepout_points(MAP_RADIUS_M));
        if handling {
            let block = self.picked_block_here();
            let outline = self.picked_outline_here();
            let held = self.hand.state == Some(GripperState::Holding);
            let jaws = HeldZone {
                ahead: JAWS.ahead + HELD_MARGIN_M,
                half_width: JAWS.half_width + HELD_MARGIN_M,
            };
            points.retain(|&p| {
                let is_block = match outline {
                    Some((c, r)) => in_mouth(c) && outlined(c, r + OUTLINE_MARGIN_M, p),
                    None => block.is_some_and(|b| b.distance(p) <= PICKED_BLOCK_M),
                };
                let in_jaws = held && jaws.contains(Pose2::default(), p);
                !(is_block || in_jaws)
            });
        }
        let obstacles = Obstacles {
            points: &points,
            age,
            source,
        };
        let watch = &self.behaviours.collision;
        let monitor = if handling {
            &watch.handling_monitor
        } else {
            &watch.monitor
        };
        let verdict = monitor.check(twist, &obstacles);
        let reason = verdict.reason?;
        let reason = reason
            .strip_prefix("collision monitor: ")
            .unwrap_or(&reason);
        Some(Proposal::new(
            Behaviour::CollisionMonitor,
            verdict.command,
            reason,
        ))
    }

    /// Where the marker of the block being picked up is, in the robot's frame.
    fn picked_block_here(&self) -> Option<Point2> {
        let id = self.exploring.mission.as_ref()?.block_being_picked()?;
        let (_, at) = self
            .ekf
            .landmarks()
            .map(|l| (l.id, l.mean))
            .find(|(i, _)| *i == id)?;
        Some(self.pose().inverse_transform_point(at))
    }

    /// The centre of the block being picked up as the lidar's live outline places it, in
    /// the robot's frame, and its corners' radius.
    fn picked_outline_here(&self) -> Option<(Point2, f64)> {
        let (centre, radius) = self.exploring.mission.as_ref()?.picked_block_outline()?;
        Some((self.pose().inverse_transform_point(centre), radius))
    }

    /// The planning map's occupied cells round the robot, in its frame. With the lidar
    /// lost, cells the map does not know count as occupied too: blind, the robot drives
    /// only where the map has seen free space.
    fn map_points(&mut self) -> Vec<Point2> {
        let key = (
            self.belief.revision(),
            self.sensor_lost(navdeck_core::health::Sensor::Lidar),
        );
        let pose = self.pose();
        let watch = &mut self.behaviours.collision;
        if watch.map_grid.as_ref().is_none_or(|(k, _)| *k != key) {
            let mut grid = self.belief.occupancy_grid();
            if key.1 {
                for c in grid.cells.iter_mut().filter(|c| **c == UNKNOWN) {
                    *c = OCCUPIED;
                }
            }
            watch.map_grid = Some((key, grid));
        }
        let grid = &watch.map_grid.as_ref().expect("just made").1;
        points_from_grid(grid, pose, MAP_RADIUS_M)
    }
}

/// Points seen in the robot's frame when odometry read `then`, in its frame at `now`.
fn shifted(points: &[Point2], now: Pose2, then: Pose2) -> Vec<Point2> {
    let shift = now.inverse().compose(then);
    points.iter().map(|&p| shift.transform_point(p)).collect()
}

/// Whether a block centred at `at` (robot frame) lies ahead in the gripper's open mouth.
fn in_mouth(at: Point2) -> bool {
    at.x > 0.0 && at.y.abs() <= MOUTH_HALF_WIDTH_M
}

/// Whether `p` (robot frame) lies within `radius` of a block outlined at `at`, or between
/// it and the robot in the circle's width.
fn outlined(at: Point2, radius: f64, p: Point2) -> bool {
    let nearer = p.x > 0.0 && p.x <= at.x && (p.y - at.y).abs() <= radius;
    nearer || at.distance(p) <= radius
}
