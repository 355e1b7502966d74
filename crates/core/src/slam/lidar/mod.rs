//! Mapping with the lidar alone, in the shape slam_toolbox and Karto gave graph SLAM
//! (Konolige et al., "Efficient Sparse Pose Adjustment for 2D Mapping", 2010): each scan
//! is matched against a local map of the last keyframes, seeded by odometry (correlative
//! matching, `matcher.rs`); every so often the scan becomes a keyframe, a node of the pose
//! graph joined to the one before by what the match measured; near older parts of the map
//! a keyframe is matched against them too, and a match that is good and unambiguous
//! closes the loop: an edge to the old node, and the graph solved by sparse least squares
//! (`graph.rs`). Poses are in the map frame; the odometry frame is carried along by
//! `correction` (the map → odom transform), as slam_toolbox publishes it.

mod closing;
pub mod config;
mod field;
pub mod graph;
mod keyframes;
mod matcher;
mod render;
pub mod saved;

pub use config::LidarSlamConfig;
pub use graph::{Edge, EdgeKind, PoseGraph};
pub use matcher::Match;
pub use saved::SavedGraph;

use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2, wrap_angle};
use field::Field;
use keyframes::Keyframe;
use matcher::Window;
use nalgebra::{Matrix3, Vector3};

/// A loop the latest keyframe closed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Closure {
    /// The old node matched and the new one.
    pub old: usize,
    pub new: usize,
    /// How far the solve moved the newest node, metres.
    pub correction: f64,
    /// The farthest the solve moved any node, metres: past the grid's cell, a map drawn
    /// from the old poses is off.
    pub largest_shift: f64,
    /// The match's response (0 to 1).
    pub response: f64,
}

impl Closure {
    /// The nodes round the loop, from the old one to the new one.
    pub fn nodes(&self) -> usize {
        self.new - self.old + 1
    }
}

/// What one scan changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Update {
    /// The scan matched the local map (false: odometry alone moved the pose).
    pub matched: bool,
    /// The keyframe it became, when it became one.
    pub keyframe: Option<usize>,
    /// The loop it closed, when it closed one.
    pub closure: Option<Closure>,
    /// On a continued map, the first keyframe's join to the saved graph: `Some(true)` when
    /// its scan matched the saved map, `Some(false)` when it joined at the given pose.
    pub joined: Option<bool>,
}

/// A scan is matched once the robot moved this far (m) or turned this much (degrees)
/// since the last match: a robot standing still sees nothing new.
const MATCH_STEP: (f64, f64) = (0.05, 3.0);
/// Less motion than this between two scans is standing still: metres and degrees.
const STILL: (f64, f64) = (0.002, 0.2);
/// Fewer points than this and a scan is not matched.
const MIN_POINTS: usize = 20;
/// A loop closure is tried after the robot travelled this far since the last try, metres:
/// about every other keyframe.
const LOOP_TRY_EVERY: f64 = 0.4;
/// Keyframes either side of the old node that make the map a loop closure matches
/// against, as many as the local map holds in all.
const LOOP_CHAIN_SHARE: usize = 2;
/// A continued map's first keyframe joins the saved graph with this uncertainty when its
/// scan does not match: metres and degrees (the user's "2D Pose Estimate" spread).
const JOIN_STD: (f64, f64) = (0.25, 10.0);
/// The Mahalanobis gate on a loop closure's correction, chi-square with 3 degrees of
/// freedom at 99.9 % (16.27).
const LOOP_GATE_CHI2: f64 = 16.27;
/// Added to the uncertainty a loop's correction is gated with: metres and degrees.
const LOOP_GATE_FLOOR: (f64, f64) = (0.1, 5.0);

/// The estimator; see the module comment.
#[derive(Clone, Debug)]
pub struct LidarSlam {
    config: LidarSlamConfig,
    graph: PoseGraph,
    frames: Vec<Keyframe>,
    /// Map → odom: the map pose is `correction ∘ odom`.
    correction: Pose2,
    /// The pose's covariance in the map frame.
    covariance: Matrix3<f64>,
    /// The odometry pose of the last scan, and the covariance it gathered since the last
    /// match (robot frame).
    last_odom: Option<Pose2>,
    /// The odometry pose of the last matched scan, and whether the robot was moving then.
    matched_odom: Pose2,
    matched_moving: bool,
    drift: Matrix3<f64>,
    /// The local map and its coarse copy.
    local: Option<(Field, Field)>,
    /// Until the first scan: whether it is still to come.
    first: bool,
    /// Keyframes loaded from a saved graph (they come first).
    loaded: usize,
    /// Path length at the last loop closure try, metres.
    last_loop_try: f64,
    loops: usize,
    last_response: f64,
}

impl LidarSlam {
    /// A new map whose frame has the robot at `start` when odometry reads `odom`.
    pub fn new(config: &LidarSlamConfig, start: Pose2, odom: Pose2) -> LidarSlam {
        LidarSlam {
            config: config.clone(),
            graph: PoseGraph::default(),
            frames: Vec::new(),
            correction: start.compose(odom.inverse()),
            covariance: Matrix3::zeros(),
            last_odom: None,
            matched_odom: odom,
            matched_moving: false,
            drift: Matrix3::zeros(),
            local: None,
            first: true,
            loaded: 0,
            last_loop_try: 0.0,
            loops: 0,
            last_response: 0.0,
        }
    }

    /// Mapping continued on a saved graph, the robot at `start` in its map frame when
    /// odometry reads `odom`: the first scan joins the saved graph by matching it there
    /// (slam_toolbox's "continue mapping").
    pub fn resume(
        config: &LidarSlamConfig,
        saved: SavedGraph,
        start: Pose2,
        odom: Pose2,
    ) -> Result<Self, String> {
        saved.check()?;
        let (graph, scans) = saved.into_parts();
        let mut slam = LidarSlam::new(config, start, odom);
        let mut travelled = 0.0;
        for (k, scan) in scans.into_iter().enumerate() {
            let pose = graph.poses[k];
            if k > 0 {
                travelled += graph.poses[k - 1].position().distance(pose.position());
            }
            slam.frames
                .push(Keyframe::new(pose, scan, config.resolution, travelled));
        }
        // Every new keyframe is "far along the path" from every saved one.
        slam.last_loop_try = travelled + config.loop_minimum_travel;
        slam.loaded = slam.frames.len();
        slam.loops = graph
            .edges
            .iter()
            .filter(|e| e.kind == EdgeKind::Loop)
            .count();
        slam.graph = graph;
        Ok(slam)
    }

    /// The pose in the map frame of a robot at odometry pose `odom`.
    pub fn pose(&self, odom: Pose2) -> Pose2 {
        self.correction.compose(odom)
    }

    pub fn covariance(&self) -> Matrix3<f64> {
        self.covariance
    }

    pub fn graph(&self) -> &PoseGraph {
        &self.graph
    }

    /// Every keyframe's pose and scan, oldest first.
    pub fn keyframes(&self) -> impl Iterator<Item = (Pose2, &LaserScan)> {
        (self.graph.poses.iter().copied()).zip(self.frames.iter().map(|f| &f.scan))
    }

    /// Keyframes loaded from a saved graph.
    pub fn loaded(&self) -> usize {
        self.loaded
    }

    /// Loops closed, including a saved graph's.
    pub fn loops(&self) -> usize {
        self.loops
    }

    /// The last match's response (0 to 1).
    pub fn last_response(&self) -> f64 {
        self.last_response
    }

    /// The graph for saving.
    pub fn save(&self) -> SavedGraph {
        SavedGraph::new(
            &self.graph.poses,
            self.frames.iter().map(|f| &f.scan),
            &self.graph.edges,
        )
    }

    /// Folds in a scan taken at odometry pose `odom`.
    pub fn update(&mut self, odom: Pose2, scan: &LaserScan) -> Update {
        let points = keyframes::thin(scan, self.config.resolution);
        if std::mem::take(&mut self.first) {
            let start = self.correction.compose(odom);
            self.last_odom = Some(odom);
            self.matched_odom = odom;
            if self.loaded > 0 {
                return self.join(start, odom, scan, &points);
            }
            self.add_keyframe(start, odom, scan, None);
            return Update {
                keyframe: Some(0),
                ..Update::default()
            };
        }
        let last = self.last_odom.replace(odom).unwrap_or(odom);
        let step = last.between(odom);
        self.drift += keyframes::odometry_noise(step, self.config.odometry_noise);
        let predicted = self.correction.compose(odom);
        let mut update = Update::default();
        let mut pose = predicted;
        let mut matched_cov = None;
        let Some(kf) = self.graph.poses.len().checked_sub(1) else {
            return update;
        };
        let since_match = self.matched_odom.between(odom);
        // A scan is paired with the odometry of the poll that brought it, a little after it
        // was taken: a match made while the robot moved carries that lag, so the first
        // scan after it stops is matched too.
        let settled = self.matched_moving && !moved(step, STILL);
        let due = self.keyframe_due(self.graph.poses[kf].between(predicted))
            || moved(since_match, MATCH_STEP)
            || settled;
        if due && let Some(m) = self.match_local(&points, predicted, since_match) {
            pose = fuse(predicted, &rotate(&self.drift, predicted.theta), &m);
            self.correction = pose.compose(odom.inverse());
            self.drift = Matrix3::zeros();
            self.matched_odom = odom;
            self.matched_moving = moved(step, STILL);
            update.matched = true;
            matched_cov = Some(m.covariance);
        }
        let kf_pose = self.graph.poses[kf];
        let since = kf_pose.between(pose);
        // What is known of the pose relative to the keyframe, in the keyframe's frame: the
        // match's spread, or odometry's since the keyframe.
        let relative_cov = match matched_cov {
            Some(cov) => rotate(&cov, -kf_pose.theta),
            None => keyframes::odometry_noise(since, self.config.odometry_noise),
        };
        self.covariance = self.frames[kf].covariance + rotate(&relative_cov, kf_pose.theta);
        if !self.keyframe_due(since) {
            return update;
        }
        let new = self.add_keyframe(pose, odom, scan, Some((kf, since, relative_cov)));
        update.keyframe = Some(new);
        update.closure = self.close_loop(new);
        update
    }

    /// Whether a pose `since` the last keyframe (in its frame) makes a new one.
    fn keyframe_due(&self, since: Pose2) -> bool {
        let c = &self.config;
        moved(
            since,
            (c.minimum_travel_distance, c.minimum_travel_heading_deg),
        )
    }

    /// The match of `points` against the local map round `guess`, when it is good enough.
    /// The window grows by the odometry `step` since the last scan: a scan is taken up to
    /// a poll before the odometry it is paired with, so while the robot turns fast the
    /// guess may be off by as much as the turn.
    fn match_local(&mut self, points: &[Point2], guess: Pose2, step: Pose2) -> Option<Match> {
        let (fine, coarse) = self.local.as_ref()?;
        if points.len() < MIN_POINTS {
            return None;
        }
        let c = &self.config;
        let window = Window {
            half_width: (c.search_half_width + step.x.hypot(step.y)).min(c.loop_search_half_width),
            half_angle: (c.search_half_angle_deg.to_radians() + step.theta.abs()).min(
                c.loop_search_half_angle_deg
                    .to_radians()
                    .max(c.search_half_angle_deg.to_radians()),
            ),
        };
        let m = matcher::correlate(fine, coarse, points, guess, window)?;
        self.last_response = m.response;
        (m.response >= self.config.minimum_response).then_some(m)
    }

    /// Adds a keyframe at `pose`, joined to `previous` (node, measured relative pose, its
    /// covariance), and rebuilds the local map. Returns its node.
    fn add_keyframe(
        &mut self,
        pose: Pose2,
        odom: Pose2,
        scan: &LaserScan,
        previous: Option<(usize, Pose2, Matrix3<f64>)>,
    ) -> usize {
        let node = self.graph.poses.len();
        let travelled = previous.map_or(0.0, |(p, rel, _)| {
            self.frames[p].travelled + rel.position().distance(Point2::default())
        });
        let mut frame = Keyframe::new(pose, scan.clone(), self.config.resolution, travelled);
        frame.odom = odom;
        if let Some((p, rel, cov)) = previous {
            frame.covariance = self.frames[p].covariance + rotate(&cov, self.graph.poses[p].theta);
            self.graph.edges.push(Edge {
                from: p,
                to: node,
                relative: rel,
                information: information(&cov),
                kind: EdgeKind::Sequential,
            });
        }
        self.covariance = frame.covariance;
        self.graph.poses.push(pose);
        self.frames.push(frame);
        self.rebuild_local();
        node
    }

    /// The local map: the last `scan_buffer_size` keyframes of this session.
    fn rebuild_local(&mut self) {
        let n = self.frames.len();
        let from = n
            .saturating_sub(self.config.scan_buffer_size as usize)
            .max(self.loaded.min(n.saturating_sub(1)));
        self.local = self.field_of(from..n, self.config.search_half_width);
    }

    /// The matching field of keyframes `nodes`, padded by `pad` metres.
    fn field_of(&self, nodes: std::ops::Range<usize>, pad: f64) -> Option<(Field, Field)> {
        let hits: Vec<Point2> = nodes
            .flat_map(|k| {
                let pose = self.graph.poses[k];
                self.frames[k]
                    .points
                    .iter()
                    .map(move |p| pose.transform_point(*p))
            })
            .collect();
        let c = &self.config;
        let fine = Field::from_hits(&hits, c.resolution, c.smear_deviation, pad)?;
        let coarse = fine.coarser();
        Some((fine, coarse))
    }
}

/// Whether `step` goes at least `far` (metres, degrees).
fn moved(step: Pose2, far: (f64, f64)) -> bool {
    step.x.hypot(step.y) >= far.0 || step.theta.abs().to_degrees() >= far.1
}

/// A pose from the prediction and a match, each weighed by its information (the
/// information-form fusion of two Gaussian estimates; Thrun et al., Probabilistic
/// Robotics 3.4.3), so that a corridor's match corrects across it and odometry carries
/// the pose along it.
fn fuse(predicted: Pose2, p_cov: &Matrix3<f64>, m: &Match) -> Pose2 {
    let floor = Matrix3::from_diagonal(&Vector3::new(1e-8, 1e-8, 1e-10));
    let (Some(ip), Some(im)) = (
        (p_cov + floor).try_inverse(),
        (m.covariance + floor).try_inverse(),
    ) else {
        return m.pose;
    };
    let Some(total) = (ip + im).try_inverse() else {
        return m.pose;
    };
    let d = Vector3::new(
        m.pose.x - predicted.x,
        m.pose.y - predicted.y,
        wrap_angle(m.pose.theta - predicted.theta),
    );
    let step = total * im * d;
    Pose2::new(
        predicted.x + step[0],
        predicted.y + step[1],
        wrap_angle(predicted.theta + step[2]),
    )
}

/// A covariance given in a frame turned `theta`, in the parent frame: R Σ Rᵀ.
fn rotate(cov: &Matrix3<f64>, theta: f64) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    let r = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
    r * cov * r.transpose()
}

/// The information matrix of a covariance, or a weak one when it cannot be inverted.
fn information(cov: &Matrix3<f64>) -> Matrix3<f64> {
    let sym = (cov + cov.transpose()) / 2.0;
    sym.try_inverse()
        .filter(|i| i.iter().all(|v| v.is_finite()))
        .unwrap_or_else(|| Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 1.0)))
}
