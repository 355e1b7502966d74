//! The digital twin: a simulated differential-drive robot in a simulated arena.
//! (Interface stub; the implementation lands with the twin.)

use crate::config::Config;
use crate::geometry::{Point2, Pose2, Segment, Twist};
use crate::link::{GripperCommand, GripperState, SensorFrame};
use crate::map::grid::OccupancyGrid;
use std::path::Path;

#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct WorldError(pub String);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockColor {
    Red,
    Blue,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    pub id: u32,
    pub position: Point2,
    pub normal: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Gate {
    pub color: BlockColor,
    pub markers: [u32; 2],
}

#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub color: BlockColor,
    pub pose: Pose2,
    pub size: f64,
    pub markers: [u32; 2],
}

#[derive(Clone, Debug, PartialEq)]
pub struct World {
    pub name: String,
    pub width: f64,
    pub height: f64,
    pub start: Pose2,
    pub walls: Vec<Segment>,
    pub markers: Vec<Marker>,
    pub blocks: Vec<Block>,
    pub gates: Vec<Gate>,
}

impl World {
    pub fn from_toml(_text: &str, _source: &Path) -> Result<World, WorldError> {
        todo!()
    }
    pub fn load(_path: &Path) -> Result<World, WorldError> {
        todo!()
    }
    pub fn default_arena() -> World {
        todo!()
    }
    pub fn rasterize(&self, _resolution: f64) -> OccupancyGrid {
        todo!()
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct BlockState {
    pub color: BlockColor,
    pub markers: [u32; 2],
    pub pose: Pose2,
    pub held: bool,
}

#[derive(Clone, Debug)]
pub struct Twin {}

impl Twin {
    pub fn new(_world: World, _config: &Config, _seed: u64) -> Twin {
        todo!()
    }
    pub fn world(&self) -> &World {
        todo!()
    }
    pub fn time(&self) -> f64 {
        todo!()
    }
    pub fn pose(&self) -> Pose2 {
        todo!()
    }
    pub fn velocity(&self) -> Twist {
        todo!()
    }
    pub fn set_command(&mut self, _twist: Twist) {
        todo!()
    }
    pub fn command_gripper(&mut self, _cmd: GripperCommand) {
        todo!()
    }
    pub fn step(&mut self, _dt: f64) {
        todo!()
    }
    pub fn take_frame(&mut self) -> SensorFrame {
        todo!()
    }
    pub fn blocks(&self) -> &[BlockState] {
        todo!()
    }
    pub fn gripper(&self) -> GripperState {
        todo!()
    }
    pub fn collisions(&self) -> u32 {
        todo!()
    }
    pub fn distance_driven(&self) -> f64 {
        todo!()
    }
}
