//! The arena as the rendered camera sees it (wall, obstacle, gate and block markers; walls
//! and block faces hide what is behind), and a camera rendering and detecting it.

use navdeck::geometry::{Pose2, Segment};
use navdeck::perception::aruco::Detector;
use navdeck::perception::config::VisionConfig;
use navdeck::perception::frame::GrayFrame;
use navdeck::sim::rendered_camera::Renderer;
use navdeck::sim::{BlockState, Marker, World};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

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

/// The detector of one camera configuration and the twin's renderer of what it sees,
/// with noise from a seeded generator.
pub struct ArenaCamera {
    pub det: Detector,
    renderer: Renderer,
    rng: ChaCha8Rng,
}

impl ArenaCamera {
    pub fn new(cfg: &VisionConfig, seed: u64) -> Self {
        Self {
            det: Detector::from_config(cfg).unwrap(),
            renderer: Renderer::new(&cfg.markers, &cfg.render),
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    /// The frame seen from `pose` of `markers`, `occluders` hiding what is behind them.
    pub fn frame<'a>(
        &mut self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
    ) -> GrayFrame {
        self.renderer
            .render(&self.det, pose, markers, occluders, &mut self.rng)
            .unwrap()
    }
}
