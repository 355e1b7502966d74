//! Monte-Carlo localisation in the pilot: when the session gives a known map, the
//! particle filter's pose is the one everything else uses (planning, following, the
//! mission, the map, the status panel, the accuracy report), and the EKF is kept at that
//! pose so that the landmarks it maps line up with the known map.

use super::Pilot;
use nalgebra::Matrix3;
use navdeck_core::data::{LaserScan, Level};
use navdeck_core::geometry::Pose2;
use navdeck_core::map::config::MapConfig;
use navdeck_core::map::grid::OccupancyGrid;
use navdeck_core::slam::lidar::SavedGraph;
use navdeck_core::slam::mcl::config::Estimator;
use navdeck_core::slam::mcl::known_map::DEFAULT_REACH;
use navdeck_core::slam::mcl::{KnownMap, Mcl};
use std::sync::Arc;

/// The estimator that reads the lidar, when one runs: its pose is the one everything
/// else uses.
#[derive(Default)]
pub enum ScanEstimator {
    /// The EKF alone places the robot.
    #[default]
    None,
    /// Monte-Carlo localisation on a known map.
    Mcl(Box<Mcl>),
    /// Lidar SLAM, mapping as it goes.
    Slam(Box<super::lidar_slam::SlamPilot>),
}

impl ScanEstimator {
    /// Lidar SLAM from `start` when the settings ask for it; MCL waits for its map.
    pub fn for_settings(settings: &super::config::Settings, start: Pose2) -> Self {
        match settings.localization.estimator {
            Estimator::Slam => ScanEstimator::Slam(Box::new(super::lidar_slam::SlamPilot::new(
                &settings.lidar_slam,
                start,
            ))),
            Estimator::Ekf | Estimator::Mcl => ScanEstimator::None,
        }
    }
}

/// Where the filter starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InitialPose {
    /// Near a known pose (`--initial-pose X,Y,THETA`, RViz's "2D Pose Estimate").
    At(Pose2),
    /// Anywhere on the map's free space: global localisation.
    Unknown,
}

impl std::str::FromStr for InitialPose {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s.trim() == "unknown" {
            return Ok(InitialPose::Unknown);
        }
        navdeck_core::geometry::parse_pose_degrees(s).map(InitialPose::At)
    }
}

impl Pilot {
    /// Localises with MCL on `grid` from `initial`, the grid also becoming the planning
    /// map's prior; `seed` seeds the filter's random numbers. Refused (with the reason)
    /// for a map MCL cannot use or an initial pose off its free space.
    pub fn use_mcl(
        &mut self,
        grid: &OccupancyGrid,
        initial: InitialPose,
        seed: u64,
    ) -> Result<(), String> {
        self.settings
            .map
            .check_extent(planning_extent(grid))
            .map_err(|why| format!("the map's planning map: {why}"))?;
        // Distances kept as far as the likelihood field reads them.
        let reach = (self.settings.localization.measurement.likelihood_max_dist).max(DEFAULT_REACH);
        let map = Arc::new(KnownMap::with_reach(grid, reach).map_err(|e| e.to_string())?);
        if let InitialPose::At(p) = initial {
            check_on_free_space(&map, p)?;
        }
        self.cover(grid);
        self.belief.absorb_grid(grid);
        let mut mcl = Mcl::new(map, &self.settings.localization, seed);
        self.place(&mut mcl, initial);
        self.scan_estimator = ScanEstimator::Mcl(Box::new(mcl));
        Ok(())
    }

    /// Makes the planning map cover `grid` (it is centred on the origin, as every map
    /// navdeck builds); an empty planning map is simply made larger.
    pub(super) fn cover(&mut self, grid: &OccupancyGrid) {
        let need = planning_extent(grid);
        let c = self.belief.costmap();
        let have = (
            c.width as f64 * c.resolution,
            c.height as f64 * c.resolution,
        );
        if need.0 > have.0 || need.1 > have.1 {
            let extent = (need.0.max(have.0), need.1.max(have.1));
            self.belief = navdeck_core::map::belief::BeliefMap::new(&self.settings.map, extent);
        }
    }

    fn place(&mut self, mcl: &mut Mcl, initial: InitialPose) {
        let c = &self.settings.localization.spread;
        match initial {
            InitialPose::At(p) => mcl.init_at(p, c.initial_std, c.initial_std_deg.to_radians()),
            InitialPose::Unknown => mcl.init_global(),
        }
    }

    /// The localiser, when one runs.
    pub fn mcl(&self) -> Option<&Mcl> {
        match &self.scan_estimator {
            ScanEstimator::Mcl(mcl) => Some(mcl),
            _ => None,
        }
    }

    fn mcl_mut(&mut self) -> Option<&mut Mcl> {
        match &mut self.scan_estimator {
            ScanEstimator::Mcl(mcl) => Some(mcl),
            _ => None,
        }
    }

    /// The pose everything decides with: MCL's or lidar SLAM's when one runs, else the
    /// EKF's.
    pub fn pose(&self) -> Pose2 {
        match &self.scan_estimator {
            ScanEstimator::Mcl(mcl) => mcl.pose(self.odometry.pose()),
            ScanEstimator::Slam(slam) => slam.slam.pose(self.odometry.pose()),
            ScanEstimator::None => self.ekf.pose(),
        }
    }

    /// That pose's covariance (x, y, θ).
    pub fn pose_covariance(&self) -> Matrix3<f64> {
        match &self.scan_estimator {
            ScanEstimator::Mcl(mcl) => mcl.covariance(),
            ScanEstimator::Slam(slam) => slam.slam.covariance(),
            ScanEstimator::None => self.ekf.pose_covariance(),
        }
    }

    /// Whether the pose can be trusted to map with: always for the EKF and lidar SLAM,
    /// for MCL once one cluster holds the weight.
    pub(super) fn localized(&self) -> bool {
        self.mcl().is_none_or(|m| m.status().converged)
    }

    /// Folds a scan into the lidar estimator.
    pub(super) fn localize_scan(&mut self, scan: &LaserScan) {
        if matches!(self.scan_estimator, ScanEstimator::Slam(_)) {
            return self.slam_scan(scan);
        }
        let odom = self.odometry.pose();
        let Some(mcl) = self.mcl_mut() else {
            return;
        };
        let was = mcl.status().converged;
        if !mcl.update(odom, scan) {
            return;
        }
        let status = mcl.status();
        let (pose, cov) = (mcl.pose(odom), mcl.covariance());
        if status.converged {
            self.ekf.relocate(pose, &cov);
        }
        if status.converged != was {
            let (level, text) = if status.converged {
                let text = format!(
                    "localised at ({:.2}, {:.2}) {:.0}° ({} particles)",
                    pose.x,
                    pose.y,
                    degrees(pose.theta),
                    status.particles
                );
                (Level::Success, text)
            } else if status.clusters > 1 {
                let text = format!(
                    "localisation uncertain: {} hypotheses, the best holds {:.0} % of the weight",
                    status.clusters,
                    100.0 * status.cluster_weight
                );
                (Level::Warn, text)
            } else {
                let text = format!(
                    "localisation uncertain: the particles spread {:.2} m",
                    self.mcl().map_or(0.0, |m| m.position_std())
                );
                (Level::Warn, text)
            };
            self.log(level, text);
        }
    }

    /// Places the estimate at `pose` (RViz's "2D Pose Estimate", `:pose`): MCL's particles
    /// spread round it, or the EKF moved there.
    pub(super) fn set_pose(&mut self, pose: Pose2) {
        if matches!(self.scan_estimator, ScanEstimator::Slam(_)) {
            // slam_toolbox's mapping mode takes no initial pose either: the map is built
            // in the frame the robot started in, and moving the robot would tear it.
            self.log(
                Level::Error,
                "pose not set: lidar SLAM is mapping, and a map being built takes no initial pose \
                 (to place the robot on a saved map, localise on it: --estimator mcl --map FILE.yaml)",
            );
            return;
        }
        let c = &self.settings.localization.spread;
        let (sd, sa) = (c.initial_std, c.initial_std_deg.to_radians());
        // The check `--initial-pose` makes: on MCL's free space, or with the EKF at least
        // on the planning map.
        let checked = match self.mcl() {
            Some(mcl) => check_on_free_space(mcl.map(), pose),
            None => check_finite(pose).and_then(|()| {
                let on_map = self.belief.costmap().cell_of(pose.position()).is_some();
                on_map.then_some(()).ok_or_else(|| off_the_map(pose))
            }),
        };
        if let Err(why) = checked {
            self.log(Level::Error, format!("pose not set: {why}"));
            return;
        }
        if let ScanEstimator::Mcl(mut mcl) = std::mem::take(&mut self.scan_estimator) {
            self.place(&mut mcl, InitialPose::At(pose));
            self.scan_estimator = ScanEstimator::Mcl(mcl);
        }
        let cov = Matrix3::from_diagonal(&nalgebra::Vector3::new(sd * sd, sd * sd, sa * sa));
        self.ekf.relocate(pose, &cov);
        self.log(
            Level::Info,
            format!(
                "pose set to ({:.2}, {:.2}) {:.0}°",
                pose.x,
                pose.y,
                degrees(pose.theta)
            ),
        );
    }

    /// Starts global localisation afresh (`:relocalize`).
    pub(super) fn relocalize(&mut self) {
        let ScanEstimator::Mcl(mut mcl) = std::mem::take(&mut self.scan_estimator) else {
            self.log(
                Level::Warn,
                "relocalize needs MCL: start with --estimator mcl and a map (--map or a Nav2 --world)",
            );
            return;
        };
        self.place(&mut mcl, InitialPose::Unknown);
        let n = mcl.status().particles;
        self.scan_estimator = ScanEstimator::Mcl(mcl);
        self.log(
            Level::Info,
            format!("global localisation: {n} particles over the free space; drive to localise"),
        );
    }
}

/// The extent of a planning map centred on the origin (as every map navdeck builds) that
/// covers `grid`.
pub fn planning_extent(grid: &OccupancyGrid) -> (f64, f64) {
    let (w, h) = grid.extent();
    let o = grid.origin;
    (
        2.0 * o.x.abs().max((o.x + w).abs()),
        2.0 * o.y.abs().max((o.y + h).abs()),
    )
}

/// A pose for the filter must stand on a known free cell of its map.
fn check_on_free_space(map: &KnownMap, p: Pose2) -> Result<(), String> {
    check_finite(p)?;
    if map.is_free(p.position()) {
        Ok(())
    } else if map.index_of(p.x, p.y).is_none() {
        Err(off_the_map(p))
    } else {
        Err(format!(
            "({:.2}, {:.2}) is not on the map's known free space",
            p.x, p.y
        ))
    }
}

fn check_finite(p: Pose2) -> Result<(), String> {
    if p.x.is_finite() && p.y.is_finite() && p.theta.is_finite() {
        return Ok(());
    }
    Err(format!(
        "pose ({:?}, {:?}, {:?}) is not a number",
        p.x, p.y, p.theta
    ))
}

fn off_the_map(p: Pose2) -> String {
    format!("({}, {}) is off the map", short(p.x), short(p.y))
}

/// A coordinate to two decimals, or as `1e308` when too large for that to be short.
fn short(v: f64) -> String {
    if v.abs() < 1e6 {
        format!("{v:.2}")
    } else {
        format!("{v:e}")
    }
}

/// A session's choice of a map to start on: MCL localises on it, or lidar SLAM continues
/// the pose graph saved with it; the map, where to start and the seed, checked before the
/// console starts and applied to each pilot the session makes.
#[derive(Clone, Debug)]
pub struct Localizer {
    pub grid: OccupancyGrid,
    pub initial: InitialPose,
    pub seed: u64,
    /// The map's file, for the log.
    pub source: String,
    /// The pose graph lidar SLAM continues (`NAME.posegraph.json`) and its file; None
    /// for MCL.
    pub continued: Option<(Arc<SavedGraph>, String)>,
}

impl Localizer {
    /// Checks that MCL can run on `grid` from `initial`, and that the planning map that
    /// covers it fits `map_config`'s cell limit (checked before MCL's own tables are made).
    pub fn new(
        grid: OccupancyGrid,
        initial: InitialPose,
        seed: u64,
        source: String,
        map_config: &MapConfig,
    ) -> Result<Self, String> {
        map_config
            .check_extent(planning_extent(&grid))
            .map_err(|why| format!("map {source}: a planning map covering it, {why}"))?;
        let map = KnownMap::new(&grid).map_err(|e| format!("map {source}: {e}"))?;
        if let InitialPose::At(p) = initial {
            check_on_free_space(&map, p).map_err(|e| format!("--initial-pose: {e} of {source}"))?;
        }
        Ok(Self {
            grid,
            initial,
            seed,
            source,
            continued: None,
        })
    }

    /// Lidar SLAM continuing `saved` (read from the file `graph_source`), saved with the
    /// Nav2 map `grid` (from `source`), from `initial` (the origin when unknown: a
    /// continued map has no free space to search). Checks that a planning map covering
    /// the map fits `map_config`'s cell limit.
    pub fn continuing(
        grid: OccupancyGrid,
        initial: InitialPose,
        source: String,
        saved: (SavedGraph, String),
        map_config: &MapConfig,
    ) -> Result<Self, String> {
        map_config
            .check_extent(planning_extent(&grid))
            .map_err(|why| format!("map {source}: a planning map covering it, {why}"))?;
        if let InitialPose::At(p) = initial {
            check_finite(p).map_err(|e| format!("--initial-pose: {e}"))?;
        }
        Ok(Self {
            grid,
            initial,
            seed: 0,
            source,
            continued: Some((Arc::new(saved.0), saved.1)),
        })
    }

    /// What it starts, for the log: "MCL" or "lidar SLAM".
    pub fn label(&self) -> &'static str {
        match self.continued {
            Some(_) => "lidar SLAM",
            None => "MCL",
        }
    }

    /// Starts MCL, or lidar SLAM continuing its saved graph, in `pilot`.
    pub fn apply(&self, pilot: &mut Pilot) -> Result<(), String> {
        if let Some((saved, graph_source)) = &self.continued {
            let start = match self.initial {
                InitialPose::At(p) => p,
                InitialPose::Unknown => Pose2::default(),
            };
            let saved = SavedGraph::clone(saved);
            return pilot.continue_mapping(saved, &self.grid, start, graph_source);
        }
        pilot.use_mcl(&self.grid, self.initial, self.seed)?;
        let from = match self.initial {
            InitialPose::At(p) => format!("from ({:.2}, {:.2}) {:.0}°", p.x, p.y, degrees(p.theta)),
            InitialPose::Unknown => "anywhere: global localisation, drive to localise".into(),
        };
        let n = pilot.mcl().map_or(0, |m| m.status().particles);
        pilot.log(
            Level::Info,
            format!("MCL on {}: {n} particles {from}", self.source),
        );
        Ok(())
    }
}

/// A heading in whole degrees for the log, without a sign on zero.
fn degrees(theta: f64) -> f64 {
    theta.to_degrees().round() + 0.0
}
