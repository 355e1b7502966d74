//! Shared by the vision tests: a level camera, and the arena as the rendered camera sees
//! it (wall, obstacle, gate and block markers; walls and block faces hide what is behind).
#![allow(dead_code)]

use navdeck::geometry::Segment;
use navdeck::perception::config::VisionConfig;
use navdeck::sim::{BlockState, Marker, World};

/// A camera looking level ahead (x -90 degrees) 10 cm up, so markers up to 4 m away are
/// in frame.
pub fn level() -> VisionConfig {
    let mut v = VisionConfig::default();
    v.mount.rotation_deg = [-90.0, 0.0, -90.0];
    v.mount.translation = [0.03, 0.0, 0.10];
    v
}

/// The default arena with its blocks where the world file puts them.
pub struct ArenaScene {
    pub world: World,
    pub block_markers: Vec<Marker>,
    pub block_edges: Vec<Segment>,
}

impl ArenaScene {
    pub fn new() -> Self {
        let world = World::default_arena();
        let blocks: Vec<BlockState> = world.blocks.iter().map(BlockState::from_block).collect();
        Self {
            block_markers: blocks.iter().flat_map(|b| b.current_markers()).collect(),
            block_edges: blocks.iter().flat_map(|b| b.edges()).collect(),
            world,
        }
    }

    /// Every marker: the world's, then the blocks'.
    pub fn markers(&self) -> Vec<&Marker> {
        self.world
            .markers
            .iter()
            .chain(&self.block_markers)
            .collect()
    }

    /// What blocks the camera's view: walls and block faces.
    pub fn occluders(&self) -> [&[Segment]; 2] {
        [&self.world.walls, &self.block_edges]
    }
}
