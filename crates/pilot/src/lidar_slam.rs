//! Lidar SLAM in the pilot: each scan goes to the estimator, whose pose everything else
//! uses; the EKF is kept at that pose so that the markers it maps (blocks, gates) line up
//! with the lidar's map; a closed loop is logged and the planning map is redrawn from the
//! keyframes at their corrected poses, so that walls seen before and after the loop do
//! not stand twice.

use super::Pilot;
use super::localize::ScanEstimator;
use navdeck_core::data::{GripperState, LaserScan, Level};
use navdeck_core::geometry::{Pose2, wrap_angle};
use navdeck_core::map::belief::BeliefMap;
use navdeck_core::map::contact::JAWS;
use navdeck_core::map::grid::OccupancyGrid;
use navdeck_core::slam::lidar::{Closure, LidarSlam, LidarSlamConfig, SavedGraph};

/// A loop closure is false when the relative pose it measured differs from the truth's
/// by more than this: metres and degrees (twice the 0.05 m loop gate, and 5°).
pub const FALSE_CLOSURE: (f64, f64) = (0.1, 5.0);

/// The estimator and what the pilot keeps beside it.
#[derive(Clone, Debug)]
pub struct SlamPilot {
    pub slam: LidarSlam,
    /// Each keyframe's true pose, when a simulator gave one (for scoring only).
    truth: Vec<Option<Pose2>>,
    /// Each keyframe: whether the gripper held a block (its beams end in the jaws).
    holding: Vec<bool>,
    /// Loop closures whose measured relative pose the truth contradicts.
    false_closures: usize,
    /// The loops closed this session, newest last.
    pub closures: Vec<Closure>,
    /// Whether the newest scan became a keyframe.
    pub keyframed: bool,
}

/// The log line of a closed loop, which the console also flashes.
pub fn closure_line(c: &Closure) -> String {
    format!(
        "loop closed: {:.2} m corrected over {} nodes",
        c.correction,
        c.nodes()
    )
}

impl SlamPilot {
    pub fn new(config: &LidarSlamConfig, start: Pose2) -> Self {
        SlamPilot {
            slam: LidarSlam::new(config, start, start),
            truth: Vec::new(),
            holding: Vec::new(),
            false_closures: 0,
            closures: Vec::new(),
            keyframed: false,
        }
    }

    /// Loop closures the truth contradicts (0 without a simulator).
    pub fn false_closures(&self) -> usize {
        self.false_closures
    }

    /// Whether the truth contradicts `c`: the true pose of the new keyframe seen from the
    /// old one against the graph's.
    fn is_false(&self, c: &Closure) -> bool {
        let (Some(Some(a)), Some(Some(b))) = (self.truth.get(c.old), self.truth.get(c.new)) else {
            return false;
        };
        let truth = a.between(*b);
        let poses = &self.slam.graph().poses;
        let measured = poses[c.old].between(poses[c.new]);
        truth.position().distance(measured.position()) > FALSE_CLOSURE.0
            || wrap_angle(truth.theta - measured.theta).abs() > FALSE_CLOSURE.1.to_radians()
    }
}

impl Pilot {
    /// Lidar SLAM, when it runs.
    pub fn lidar_slam(&self) -> Option<&SlamPilot> {
        match &self.scan_estimator {
            ScanEstimator::Slam(s) => Some(s),
            _ => None,
        }
    }

    /// The map a user saves: lidar SLAM's map (every keyframe at its pose in the graph, at
    /// its grid's resolution, as slam_toolbox saves) when it runs, else the planning map.
    pub fn map_to_save(&self) -> navdeck_core::map::grid::OccupancyGrid {
        self.lidar_slam()
            .and_then(|s| s.slam.occupancy_grid())
            .unwrap_or_else(|| self.belief.occupancy_grid())
    }

    /// Continues mapping on a saved pose graph (slam_toolbox's "continue mapping") from
    /// `start`: the SLAM estimator is replaced by one holding the saved keyframes, the
    /// planning map is made to cover `grid` (the Nav2 map saved with the graph) and is
    /// drawn from the keyframes; the first scan joins the saved graph by matching.
    /// Refused, with the reason, when lidar SLAM does not run or the graph is bad.
    pub fn continue_mapping(
        &mut self,
        saved: SavedGraph,
        grid: &OccupancyGrid,
        start: Pose2,
        source: &str,
    ) -> Result<(), String> {
        let ScanEstimator::Slam(sp) = &mut self.scan_estimator else {
            return Err("continuing a saved map needs lidar SLAM (--estimator slam)".into());
        };
        let odom = self.odometry.pose();
        let slam = LidarSlam::resume(&self.settings.lidar_slam, saved, start, odom)
            .map_err(|why| format!("pose graph {source}: {why}"))?;
        let (keyframes, loops) = (slam.loaded(), slam.loops());
        **sp = SlamPilot {
            slam,
            truth: vec![None; keyframes],
            holding: vec![false; keyframes],
            false_closures: 0,
            closures: Vec::new(),
            keyframed: false,
        };
        let cov = sp.slam.covariance();
        self.ekf.relocate(start, &cov);
        self.cover(grid);
        self.redraw_from_keyframes();
        self.log(
            Level::Info,
            format!("lidar SLAM continues {source}: {keyframes} keyframes, {loops} loops"),
        );
        Ok(())
    }

    /// Folds a scan into lidar SLAM.
    pub(super) fn slam_scan(&mut self, scan: &LaserScan) {
        let odom = self.odometry.pose();
        let truth = self.estimating.truth;
        let holding = self.hand.state == Some(GripperState::Holding);
        let ScanEstimator::Slam(sp) = &mut self.scan_estimator else {
            return;
        };
        let update = sp.slam.update(odom, scan);
        sp.keyframed = update.keyframe.is_some();
        if sp.keyframed {
            sp.truth.push(truth);
            sp.holding.push(holding);
        }
        let (pose, cov) = (sp.slam.pose(odom), sp.slam.covariance());
        let mut lines = Vec::new();
        if let Some(joined) = update.joined {
            lines.push(if joined {
                (Level::Success, format!("continuing the saved map: the first scan matched it at ({:.2}, {:.2})", pose.x, pose.y))
            } else {
                (Level::Warn, format!("continuing the saved map from ({:.2}, {:.2}): the first scan did not match it, so a loop closure must tie the two", pose.x, pose.y))
            });
        }
        let mut redraw = false;
        if let Some(c) = update.closure {
            if sp.is_false(&c) {
                sp.false_closures += 1;
            }
            sp.closures.push(c);
            // A map drawn from poses that moved less than the lidar map's cell stands.
            redraw = c.largest_shift > self.settings.lidar_slam.resolution;
            lines.push((Level::Success, closure_line(&c)));
        }
        self.ekf.relocate(pose, &cov);
        for (level, text) in lines {
            self.log(level, text);
        }
        if redraw {
            self.redraw_from_keyframes();
        }
    }

    /// The planning map drawn again from every keyframe at its pose in the graph, and the
    /// robot's path through them: what was drawn before a loop closed moved with it.
    fn redraw_from_keyframes(&mut self) {
        let ScanEstimator::Slam(sp) = &self.scan_estimator else {
            return;
        };
        let c = self.belief.costmap();
        let (origin, extent) = (
            c.origin,
            (
                c.width as f64 * c.resolution,
                c.height as f64 * c.resolution,
            ),
        );
        let mut belief = BeliefMap::covering(&self.settings.map, origin, extent);
        let radius = self.settings.robot.footprint_radius;
        for ((pose, scan), &held) in sp.slam.keyframes().zip(&sp.holding) {
            belief.observe_footprint(pose.position(), radius);
            belief.observe_scan_holding(pose, scan, held.then_some(JAWS));
        }
        let landmarks: Vec<_> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        belief.update_landmarks(landmarks);
        belief.succeed(&self.belief);
        self.belief = belief;
    }
}
