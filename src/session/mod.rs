//! Building a session from the command line's choices: config, keymap, world, link.
//! Everything is loaded and checked here, before the terminal is touched.

mod estimator;
pub mod fleet;
mod lane;
mod tags;

use crate::app::App;
use crate::config::Config;
use crate::keymap::Keymap;
use crate::link::RobotLink;
use crate::link::ros2::{Ros2Link, Ros2Options, domain_from};
use crate::link::serial::SerialLink;
use crate::link::sim::SimLink;
use crate::pilot::localize::{InitialPose, Localizer};
use crate::sim::{Twin, World};
use crate::slam::mcl::config::Estimator;
use anyhow::{Context, Result, bail};
use estimator::localizer_for;
pub use estimator::{continuing, graph_beside, read_graph};
use std::path::PathBuf;
pub use tags::load_tag_map;

/// Why a camera option is refused by a build without OpenCV, and what to do.
#[cfg(not(feature = "vision"))]
pub const NEEDS_VISION: &str = "needs navdeck built with the `vision` feature \
     (cargo build --features vision; needs OpenCV: libopencv-dev libopencv-contrib-dev clang libclang-dev)";

/// Which robot to drive.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkChoice {
    Sim,
    Ros2(Ros2Target),
    Serial(String),
}

/// The command line's say on where the ROS 2 robot is: over the config file, and for the
/// domain over ROS_DOMAIN_ID.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Ros2Target {
    pub namespace: Option<String>,
    pub domain: Option<u16>,
}

impl std::str::FromStr for LinkChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "sim" => Ok(LinkChoice::Sim),
            "ros2" => Ok(LinkChoice::Ros2(Ros2Target::default())),
            _ => match s.strip_prefix("serial:") {
                Some(path) if !path.is_empty() => Ok(LinkChoice::Serial(path.to_string())),
                _ => Err(format!(
                    "unknown link {s:?}: expected sim, ros2 or serial:PATH[@BAUD]"
                )),
            },
        }
    }
}

/// The choices a session is built from.
#[derive(Clone, Debug)]
pub struct SessionSpec {
    /// A world file (TOML), or a Nav2 map (YAML + PGM) whose occupied cells are walls.
    pub world: Option<PathBuf>,
    pub seed: u64,
    /// Where the robot starts instead of the world's own start pose.
    pub start: Option<crate::geometry::Pose2>,
    pub config: Option<PathBuf>,
    pub keymap: Option<PathBuf>,
    pub link: LinkChoice,
    pub localize: LocalizeChoice,
}

impl SessionSpec {
    /// The twin in `world` (the built-in arena when None), seed 1, every file default.
    pub fn twin(world: Option<PathBuf>) -> Self {
        Self {
            world,
            seed: 1,
            start: None,
            config: None,
            keymap: None,
            link: LinkChoice::Sim,
            localize: LocalizeChoice::default(),
        }
    }
}

/// The command line's say on how the robot is localised (over `[localization]`).
#[derive(Clone, Debug, Default)]
pub struct LocalizeChoice {
    /// `--estimator`.
    pub estimator: Option<Estimator>,
    /// `--map`: the map MCL localises on (default: the world, when it is a Nav2 map).
    pub map: Option<PathBuf>,
    /// `--initial-pose` (default: the twin's start, or global localisation on a robot).
    pub initial_pose: Option<InitialPose>,
}

/// Whether `path` names a Nav2 map (map_server YAML) rather than a world file.
pub fn is_nav2_map(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("yaml") || e.eq_ignore_ascii_case("yml"))
}

/// The robot a session drives: the twin stays itself until the console starts, so its
/// sensors can still be changed (`--sim-camera`); any other robot is already a link.
pub(crate) enum Robot {
    Twin(Box<Twin>),
    Link(Box<dyn RobotLink>),
}

impl Robot {
    fn into_link(self) -> Box<dyn RobotLink> {
        match self {
            Robot::Twin(twin) => Box::new(SimLink::new(*twin, 0.0)),
            Robot::Link(link) => link,
        }
    }
}

/// A loaded, validated session, ready for the TUI or the headless runner.
pub struct Session {
    pub config: Config,
    pub keymap: Keymap,
    robot: Robot,
    /// The DDS domain of a ROS 2 link, for a ROS 2 camera beside it.
    pub ros2_domain: Option<u16>,
    /// Whether the config file set `[mission] blind_distance` (else it follows the camera).
    blind_from_user: bool,
    /// MCL's map and start, when the session localises with it.
    pub localizer: Option<Localizer>,
    /// Why lane mode cannot run, until a lane camera is set up (`use_lane_camera`).
    lane_unavailable: Option<String>,
    /// Route mode's tag map and its camera's floor point ahead of the robot, metres,
    /// when a real robot's tag camera reads it (the twin keeps its own).
    tags: Option<(std::sync::Arc<crate::tags::TagMap>, f64)>,
}

impl Session {
    pub fn load(spec: &SessionSpec) -> Result<Session> {
        Self::load_inner(spec, None, None)
    }

    /// As `load`, a ROS 2 robot's node on `shared`, a participant the robots of a fleet
    /// share (one DDS participant per process, as ROS 2's own nodes have).
    pub fn load_on(spec: &SessionSpec, shared: &crate::link::ros2::Participant) -> Result<Session> {
        Self::load_inner(spec, None, Some(shared))
    }

    /// As `load`, with the twin in `world` (one made in memory, e.g. generated) instead
    /// of `spec.world`; refused for a link that is not the twin. The mission is not told
    /// how many blocks the world holds: it delivers what it finds.
    pub fn load_with_world(spec: &SessionSpec, world: World) -> Result<Session> {
        if spec.link != LinkChoice::Sim {
            bail!("world {} needs the twin (--link sim)", world.name);
        }
        Self::load_inner(spec, Some(world), None)
    }

    fn load_inner(
        spec: &SessionSpec,
        given: Option<World>,
        shared: Option<&crate::link::ros2::Participant>,
    ) -> Result<Session> {
        let mut config = match &spec.config {
            Some(path) => Config::load(path)?,
            None => Config::default(),
        };
        let keymap = match &spec.keymap {
            Some(path) => Keymap::load(path)?,
            None => Keymap::default_map(),
        };
        let mut ros2_domain = None;
        let robot = match &spec.link {
            LinkChoice::Sim => {
                let world = match (given, &spec.world) {
                    (Some(world), _) => world,
                    (None, Some(path)) if is_nav2_map(path) => {
                        // One sentence naming the file and what is wrong with it.
                        crate::sim::nav2_world::load(path, spec.start).map_err(|e| {
                            let file = path.display();
                            anyhow::anyhow!("cannot use map {file} as a world: {}", e.reason())
                        })?
                    }
                    (None, Some(path)) => World::load(path).map_err(|e| {
                        anyhow::anyhow!("cannot use world {}: {}", path.display(), e.reason())
                    })?,
                    (None, None) => World::default_arena(),
                };
                let mut world = world;
                if let Some(start) = spec.start {
                    world.start = start;
                }
                crate::world_fit::world_fits(&world, &config).map_err(|why| {
                    let name = spec
                        .world
                        .as_ref()
                        .map_or("the built-in arena".into(), |p| {
                            format!("world {}", p.display())
                        });
                    anyhow::anyhow!("{name}: {why}")
                })?;
                let mut twin = Twin::new(world, &config.robot, &config.sim, spec.seed);
                if let Some(arm) = &config.arm {
                    // The twin's arm starts at home, as the pilot believes it does.
                    twin.add_arm(arm);
                }
                Robot::Twin(Box::new(twin))
            }
            LinkChoice::Ros2(target) => {
                // The command line's namespace holds for everything on ROS 2 (a camera too).
                if let Some(ns) = &target.namespace {
                    config.ros2.namespace = ns.clone();
                }
                let domain = domain_from(target.domain, std::env::var("ROS_DOMAIN_ID").ok())
                    .map_err(anyhow::Error::msg)?;
                ros2_domain = Some(domain);
                let options = Ros2Options {
                    config: config.ros2.clone(),
                    domain,
                    track: config.robot.track,
                    max_wheel_speed: config.robot.max_wheel_speed(),
                };
                let link = match shared {
                    Some(participant) => Ros2Link::connect_on(options, participant.clone()),
                    None => Ros2Link::connect(options),
                }
                .context("cannot open the ROS 2 link")?;
                Robot::Link(Box::new(link))
            }
            LinkChoice::Serial(spec) => Robot::Link(Box::new(SerialLink::open(
                spec,
                &config.serial,
                &config.robot,
            )?)),
        };
        let blind_from_user = config.mission.blind_distance.is_some();
        let localizer = localizer_for(spec, &mut config, &robot)?;
        let mut session = Session {
            config,
            keymap,
            robot,
            ros2_domain,
            blind_from_user,
            localizer,
            lane_unavailable: Some(
                "no lane camera: lane mode drives a world with a [track] in the twin \
                 (--world maps/track.toml), or a real robot's --camera"
                    .into(),
            ),
            tags: None,
        };
        // The twin's ideal sensor sees a block until the marker on its face is at the
        // sensor's least range.
        let ideal = session.config.sim.camera.min_range + session.config.mission.block_size / 2.0;
        session.set_blind_distance(ideal);
        Ok(session)
    }

    /// Sets how near a block can come before it leaves the camera's view, unless the
    /// config file said.
    fn set_blind_distance(&mut self, distance: f64) {
        if !self.blind_from_user {
            self.config.mission.blind_distance = Some(distance);
        }
    }

    /// Makes the twin see through a rendered camera and the ArUco detector instead of
    /// its ideal marker sensor (`--sim-camera`), drawing `frames`. Refused with a clear
    /// message when navdeck was built without the `vision` feature or the link has no twin.
    pub fn use_sim_camera(
        &mut self,
        stopwatch: Option<std::sync::Arc<dyn crate::clock::Clock>>,
        frames: crate::sim::CameraFrames,
    ) -> Result<()> {
        #[cfg(feature = "vision")]
        {
            let Robot::Twin(twin) = &mut self.robot else {
                bail!("--sim-camera needs the twin (--link sim)");
            };
            let detector = twin
                .use_rendered_camera(&self.config.vision, stopwatch, frames)
                .context("cannot start the rendered camera")?;
            let blind = camera_blind_distance(detector, &self.config);
            self.set_blind_distance(blind);
            Ok(())
        }
        #[cfg(not(feature = "vision"))]
        {
            let _ = (stopwatch, frames);
            bail!("--sim-camera {NEEDS_VISION}")
        }
    }

    /// Schedules `faults` in the twin (`--fault`), their times from the start of the run;
    /// refused when the session's robot is not the twin. A start window (`@A..B`) is
    /// drawn from `seed`.
    pub fn inject_faults(&mut self, faults: &[crate::sim::FaultSpec], seed: u64) -> Result<()> {
        if faults.is_empty() {
            return Ok(());
        }
        let Robot::Twin(twin) = &mut self.robot else {
            bail!("--fault {} needs the twin (--link sim)", faults[0]);
        };
        for spec in faults {
            // A start window (`@A..B`) is drawn from the run's seed.
            twin.faults_mut().schedule(spec.drawn(seed));
        }
        Ok(())
    }

    /// Adds a camera beside the link (`--camera`): a V4L2 device, or `ros2:TOPIC` for a
    /// sensor_msgs/Image topic, detected on the pipeline's own threads.
    pub fn with_camera(
        #[cfg_attr(not(feature = "vision"), allow(unused_mut))] mut self,
        source: &str,
        stopwatch: std::sync::Arc<dyn crate::clock::Clock>,
    ) -> Result<Session> {
        #[cfg(feature = "vision")]
        {
            use crate::perception::pipeline::{CameraPipeline, FrameSource, V4l2Source};
            let detector = crate::perception::aruco::Detector::from_config(&self.config.vision)
                .context("cannot set up the ArUco detector")?;
            let frames: Box<dyn FrameSource> = match source.strip_prefix("ros2:") {
                Some(topic) => {
                    let domain = match self.ros2_domain {
                        Some(d) => d,
                        None => domain_from(None, std::env::var("ROS_DOMAIN_ID").ok())
                            .map_err(anyhow::Error::msg)?,
                    };
                    Box::new(
                        crate::link::ros2::image::Ros2ImageSource::connect(
                            &self.config.ros2,
                            domain,
                            topic,
                        )
                        .with_context(|| format!("cannot subscribe to camera topic {topic}"))?,
                    )
                }
                None => {
                    let k = detector.intrinsics();
                    Box::new(
                        V4l2Source::open(source, k.width, k.height).map_err(anyhow::Error::msg)?,
                    )
                }
            };
            let blind = camera_blind_distance(&detector, &self.config);
            self.set_blind_distance(blind);
            // Lane mode reads the same camera: its calibration's image and field of view,
            // on the lane camera's mount ([lane.camera].mount).
            let lane_camera = crate::perception::lane_camera::LaneCameraConfig::matching(
                detector.intrinsics(),
                &self.config.lane.camera,
            );
            let lane =
                crate::perception::lane::LanePipeline::new(&self.config.lane.vision, &lane_camera)
                    .context("cannot set up lane mode's pipeline for this camera")?;
            self.lane_unavailable = None;
            let pipeline = CameraPipeline::start(frames, detector, Some(lane), Some(stopwatch));
            Ok(Session {
                robot: Robot::Link(Box::new(crate::link::camera::WithCamera::new(
                    self.robot.into_link(),
                    pipeline,
                    source.to_string(),
                ))),
                ..self
            })
        }
        #[cfg(not(feature = "vision"))]
        {
            let _ = (stopwatch, self);
            bail!("--camera {source} {NEEDS_VISION}")
        }
    }

    /// Joins ROS 2 beside a robot that is not on it (`--ros2`): RViz's topics, goals and
    /// pose estimates from RViz, /rosout both ways and the console's state. A ROS 2 link
    /// does all this already and is left as it is.
    pub fn with_ros2(mut self, target: &Ros2Target) -> Result<Session> {
        if matches!(self.robot, Robot::Link(_)) && self.ros2_domain.is_some() {
            return Ok(self);
        }
        if let Some(ns) = &target.namespace {
            self.config.ros2.namespace = ns.clone();
        }
        let domain = domain_from(target.domain, std::env::var("ROS_DOMAIN_ID").ok())
            .map_err(anyhow::Error::msg)?;
        let link = crate::link::ros2::beside::Ros2Beside::join(
            self.robot.into_link(),
            self.config.ros2.clone(),
            domain,
        )
        .context("cannot join ROS 2")?;
        Ok(Session {
            robot: Robot::Link(Box::new(link)),
            ros2_domain: Some(domain),
            ..self
        })
    }

    /// The session's config and its robot as a link, for runners that need no console.
    pub fn into_link(self) -> (Config, Box<dyn RobotLink>) {
        (self.config, self.robot.into_link())
    }

    /// The console on this session, starting at session time `now`.
    pub fn into_app(self, now: f64) -> App {
        let tags = self.tag_map();
        let mut app = App::new(self.config, self.keymap, self.robot.into_link(), now);
        app.set_lane_unavailable(self.lane_unavailable);
        app.set_tag_map(tags);
        if let Some(localizer) = &self.localizer {
            app.localize(localizer);
            // The map's keepout and speed zones, when Nav2 filter masks lie beside it.
            app.load_zones_beside(std::path::Path::new(&localizer.source));
        }
        app
    }
}

/// How near a block can come before it leaves the view of `detector`'s camera (its
/// mount and intrinsics), for `config`'s block and marker sizes.
#[cfg(feature = "vision")]
fn camera_blind_distance(detector: &crate::perception::aruco::Detector, config: &Config) -> f64 {
    crate::perception::mount::block_blind_distance(
        detector.mount(),
        detector.intrinsics(),
        &config.vision.markers,
        config.mission.block_size,
    )
}

#[cfg(test)]
mod tests;
