//! Route mode's tag map for a session (`--tags FILE`, seed 003): read and checked, laid
//! on the twin's floor (the twin's world round the tags when no `--world` is given) and
//! seen by the twin's ideal tag camera; or, over ROS 2, read by the robot's own tag
//! camera (`[ros2.tags]`: its image and camera_info topics, seed 003 §1.2.2).

use super::{Robot, Session, SessionSpec};
use crate::sim::tag_camera::TagCamera;
use crate::tags::TagMap;
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::sync::Arc;

/// The tag map in `path`, read bounded and checked; errors name the file and the line.
pub fn load_tag_map(path: &Path) -> Result<TagMap> {
    let limit = crate::data::files::TEXT_LIMIT;
    let text = crate::data::files::read_text_limited(path, limit)
        .with_context(|| format!("reading tag map {}", path.display()))?;
    TagMap::parse(&text).with_context(|| format!("tag map {}", path.display()))
}

impl Session {
    /// The session of `spec` with the tag map in `tags` laid on the twin's floor: in
    /// `spec.world` when given, else in a world built round the tags with the robot on
    /// the dock (`tags::floor::world_for`). Without `tags`, `Session::load`.
    pub fn load_with_tags(spec: &SessionSpec, tags: Option<&Path>) -> Result<Session> {
        let Some(path) = tags else {
            return Session::load(spec);
        };
        match spec.link {
            super::LinkChoice::Sim => {}
            super::LinkChoice::Ros2(_) => {
                let map = load_tag_map(path)?;
                return Session::load(spec)?.read_tags_over_ros2(Arc::new(map));
            }
            super::LinkChoice::Serial(_) => bail!(
                "--tags {} needs a tag camera: the twin's (--link sim) or a ROS 2 robot's                  (--link ros2, its topics in [ros2.tags])",
                path.display()
            ),
        }
        let map = load_tag_map(path)?;
        let camera = TagCamera::default();
        let mut session = match &spec.world {
            Some(_) => Session::load(spec)?,
            None => {
                let world = crate::tags::floor::world_for(&map, camera.look, &[])
                    .map_err(anyhow::Error::msg)
                    .with_context(|| format!("the twin's world for tag map {}", path.display()))?;
                Session::load_with_world(spec, world)?
            }
        };
        session.lay_tags(Arc::new(map), camera, spec.seed)?;
        Ok(session)
    }

    /// Lays `map`'s tags on the twin's floor, seen by `camera` with noise from `seed`.
    pub fn lay_tags(&mut self, map: Arc<TagMap>, camera: TagCamera, seed: u64) -> Result<()> {
        let Robot::Twin(twin) = &mut self.robot else {
            bail!("a tag map needs the twin (--link sim): its tag camera is the twin's");
        };
        twin.use_tag_camera(map, camera, seed);
        Ok(())
    }

    /// Reads `map`'s tags in the ROS 2 robot's camera frames (`[ros2.tags]` image and
    /// camera_info topics) through `[vision.tag_camera]`'s mount, on the tag pipeline's
    /// threads; the sightings ride in the link's frames.
    fn read_tags_over_ros2(self, map: Arc<TagMap>) -> Result<Session> {
        #[cfg(feature = "vision")]
        {
            let camera = self.config.vision.tag_camera.clone();
            let look = camera
                .look()
                .context("[vision.tag_camera] mount: the tag camera must look down at the floor")?;
            let side = map.param_f64("vision.tag_size", camera.tag_side);
            if !(0.005..=1.0).contains(&side) {
                bail!("the tag map's vision.tag_size = {side}: must lie in 0.005..=1 m");
            }
            let domain = self
                .ros2_domain
                .context("the tag camera needs the ROS 2 link's domain")?;
            let topics = self.config.ros2.tags.clone();
            let source = crate::link::ros2::image::Ros2ImageSource::connect_with_info(
                &self.config.ros2,
                domain,
                &topics.image_topic,
                Some(&topics.camera_info_topic),
            )
            .with_context(|| {
                format!(
                    "cannot subscribe to tag camera topic {}",
                    topics.image_topic
                )
            })?;
            let pipeline = crate::perception::tag_pipeline::TagPipeline::start(
                Box::new(source),
                camera,
                side,
                map.clone(),
            );
            let link = crate::link::tag_camera::WithTagCamera::new(
                self.robot.into_link(),
                pipeline,
                topics.image_topic,
            );
            Ok(Session {
                robot: Robot::Link(Box::new(link)),
                tags: Some((map, look)),
                ..self
            })
        }
        #[cfg(not(feature = "vision"))]
        {
            let _ = map;
            bail!("--tags over ROS 2 {}", super::NEEDS_VISION)
        }
    }

    /// The tag map route mode drives on and its camera's floor point ahead of the robot,
    /// when one is laid.
    pub(super) fn tag_map(&self) -> Option<(Arc<TagMap>, f64)> {
        match &self.robot {
            Robot::Twin(twin) => twin.tag_map().map(|m| (m, TagCamera::default().look)),
            Robot::Link(_) => self.tags.clone(),
        }
    }
}
