//! Route mode's tag map for a session (`--tags FILE`, seed 003): read and checked, laid
//! on the twin's floor (the twin's world round the tags when no `--world` is given) and
//! seen by the twin's ideal tag camera.

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
        if spec.link != super::LinkChoice::Sim {
            bail!(
                "--tags {} needs the twin (--link sim): its tag camera is the twin's",
                path.display()
            );
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

    /// The tag map on the twin's floor, when one is laid.
    pub(super) fn tag_map(&self) -> Option<Arc<TagMap>> {
        match &self.robot {
            Robot::Twin(twin) => twin.tag_map(),
            Robot::Link(_) => None,
        }
    }
}
