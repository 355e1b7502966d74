//! The twin's tag camera (seed 003 §2.1, ideal): with a tag map laid on its floor, every
//! frame taken reports the tags in the camera's view from the true pose at that moment,
//! with the camera's noise drawn from a generator of its own (so laying tags changes no
//! other sensor's noise). Nothing is seen while a camera fault lasts.

use super::Twin;
use crate::data::TagSighting;
use crate::sim::fault::FaultKind;
use crate::sim::tag_camera::TagCamera;
use crate::tags::TagMap;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// Stirred into the twin's seed for the tag camera's own generator.
const TAG_NOISE_STREAM: u64 = 0x7a95;

/// The tags on the floor and the camera that sees them.
#[derive(Clone, Debug)]
pub(super) struct TagRig {
    map: Arc<TagMap>,
    camera: TagCamera,
    rng: ChaCha8Rng,
}

impl Twin {
    /// Lays `map`'s tags on the twin's floor, seen by `camera`, its noise drawn from `seed`.
    pub fn use_tag_camera(&mut self, map: Arc<TagMap>, camera: TagCamera, seed: u64) {
        self.sensors.tag_rig = Some(TagRig {
            map,
            camera,
            rng: ChaCha8Rng::seed_from_u64(seed ^ TAG_NOISE_STREAM),
        });
    }

    /// The tag map on the floor and its camera, when tags are laid.
    pub fn tag_camera(&self) -> Option<(&TagMap, &TagCamera)> {
        (self.sensors.tag_rig.as_ref()).map(|r| (r.map.as_ref(), &r.camera))
    }

    /// The tag map on the floor, shared, when tags are laid.
    pub fn tag_map(&self) -> Option<Arc<TagMap>> {
        self.sensors.tag_rig.as_ref().map(|r| r.map.clone())
    }

    /// The tags in view now, for the frame being taken: None without tags on the floor,
    /// an empty list while the camera is dark.
    pub(super) fn take_tags(&mut self) -> Option<Vec<TagSighting>> {
        let dark = self.faults.is_active(FaultKind::Camera);
        let pose = self.pose;
        let rig = self.sensors.tag_rig.as_mut()?;
        if dark {
            return Some(Vec::new());
        }
        Some(rig.camera.sightings(&rig.map, pose, &mut rig.rng))
    }
}
