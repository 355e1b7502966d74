//! The twin's world: static walls and obstacles, markers, gates and movable blocks,
//! as loaded from a world file (see `maps/arena.toml` for the format).

use super::{WorldError, build, raster, world_file, world_toml};
use crate::geometry::{Point2, Pose2, Segment};
use crate::map::grid::OccupancyGrid;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The built-in arena of seed 001, compiled into the binary.
const ARENA_TOML: &str = include_str!("../../../../maps/arena.toml");
/// The built-in lane course of seed 000, compiled into the binary.
const TRACK_TOML: &str = include_str!("../../../../maps/track.toml");

/// Colour of a block and of the gate it belongs to (seed 001 section 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BlockColor {
    Red,
    Blue,
}

impl BlockColor {
    pub fn label(self) -> &'static str {
        match self {
            Self::Red => "red",
            Self::Blue => "blue",
        }
    }
}

/// A fiducial marker fixed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    pub id: u32,
    pub position: Point2,
    /// Direction the marker faces (its surface normal), radians.
    pub normal: f64,
}

/// A delivery gate: two gate markers of its colour mounted on a wall.
#[derive(Clone, Debug, PartialEq)]
pub struct Gate {
    pub color: BlockColor,
    pub markers: [u32; 2],
}

/// A block as placed in the world file: a square of side `size` carrying the odd marker
/// `markers[0]` on its local +x face and the even `markers[1]` on its local +y face.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub color: BlockColor,
    pub pose: Pose2,
    pub size: f64,
    pub markers: [u32; 2],
}

/// A box obstacle: a `width` x `height` rectangle (along its local x and y) at `pose`.
#[derive(Clone, Debug, PartialEq)]
pub struct Obstacle {
    pub pose: Pose2,
    pub width: f64,
    pub height: f64,
}

/// A world spanning [-width/2, width/2] x [-height/2, height/2] metres.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    pub name: String,
    pub width: f64,
    pub height: f64,
    pub start: Pose2,
    /// Every static solid segment: boundary and inner walls, then obstacle outlines.
    pub walls: Vec<Segment>,
    /// Every fixed marker: generated along walls, on obstacle faces, explicit, and gates'.
    /// Block markers travel with their blocks and are not listed here.
    pub markers: Vec<Marker>,
    pub blocks: Vec<Block>,
    pub gates: Vec<Gate>,
    /// The box obstacles whose outlines are also in `walls`.
    pub obstacles: Vec<Obstacle>,
    /// A lane track on the floor, with its lights and barriers.
    pub track: Option<Box<super::track::TrackScene>>,
}

impl World {
    /// Parses and validates world-file text; `source` only names the file in errors.
    pub fn from_toml(text: &str, source: &Path) -> Result<World, WorldError> {
        let file = world_file::parse(text, source)?;
        build::build(file, text, source)
    }

    /// Reads and validates a world file.
    pub fn load(path: &Path) -> Result<World, WorldError> {
        let text = crate::data::files::read_text_limited(path, crate::data::files::WORLD_LIMIT)
            .map_err(|source| WorldError::Read {
                path: path.to_path_buf(),
                error: source,
            })?;
        Self::from_toml(&text, path)
    }

    /// The world as world-file text, which `from_toml` reads back as the same world.
    pub fn to_toml(&self) -> String {
        world_toml::to_toml(self)
    }

    /// Seed 001's 4 m x 4 m arena (`maps/arena.toml`, embedded at build time).
    pub fn default_arena() -> World {
        Self::from_toml(ARENA_TOML, Path::new("maps/arena.toml"))
            .expect("the embedded maps/arena.toml is valid (checked by a test)")
    }

    /// The AutoRace-style lane course (`maps/track.toml`, embedded at build time).
    pub fn default_track() -> World {
        Self::from_toml(TRACK_TOML, Path::new("maps/track.toml"))
            .expect("the embedded maps/track.toml is valid (checked by a test)")
    }

    /// Static geometry as an occupancy grid: walls and obstacles occupied, the rest free.
    /// Cell (0, 0) sits at the world's lower-left corner. A resolution that is not a
    /// positive number gives an empty grid.
    pub fn rasterize(&self, resolution: f64) -> OccupancyGrid {
        raster::rasterize(self, resolution)
    }

    /// The fixed marker with this id, if any.
    pub fn marker(&self, id: u32) -> Option<&Marker> {
        self.markers.iter().find(|m| m.id == id)
    }

    /// Midpoint of a gate's two markers and the direction it faces, radians.
    pub fn gate_pose(&self, gate: &Gate) -> Option<Pose2> {
        let (a, b) = (self.marker(gate.markers[0])?, self.marker(gate.markers[1])?);
        let mid = Point2::new(
            (a.position.x + b.position.x) / 2.0,
            (a.position.y + b.position.y) / 2.0,
        );
        Some(Pose2::new(mid.x, mid.y, a.normal))
    }

    /// What a robot of footprint `radius` at the start pose runs into: its centre inside
    /// an obstacle or a block, or within `radius` of a wall or a block's side; `None`
    /// when it stands clear.
    pub fn start_conflict(&self, radius: f64) -> Option<String> {
        self.pose_conflict(self.start.position(), radius)
    }

    /// What a robot of footprint `radius` at `start` runs into (see `start_conflict`).
    pub fn pose_conflict(&self, start: Point2, radius: f64) -> Option<String> {
        use super::shapes::{rect_contains, rect_edges};
        if let Some(i) = self
            .obstacles
            .iter()
            .position(|o| rect_contains(o.pose, o.width, o.height, start))
        {
            return Some(format!("lies inside obstacles[{i}]"));
        }
        for (i, b) in self.blocks.iter().enumerate() {
            if rect_contains(b.pose, b.size, b.size, start) {
                return Some(format!("lies inside blocks[{i}]"));
            }
            let edges = rect_edges(b.pose, b.size, b.size);
            if let Some(d) = edges
                .iter()
                .map(|e| e.distance_to(start))
                .find(|&d| d < radius)
            {
                return Some(format!("is {d:.3} m from blocks[{i}], under {radius} m"));
            }
        }
        self.walls
            .iter()
            .map(|w| w.distance_to(start))
            .find(|&d| d < radius)
            .map(|d| format!("is {d:.3} m from a wall, under {radius} m"))
    }

    /// The faces a lidar sees at the free ends of walls (a door jamb, a wall's end in a
    /// room): world walls are lines, real ones have a thickness, and a line seen end-on
    /// is invisible to a beam. Each free end gets a face across the wall, `half_thickness`
    /// either side of it. Corners joined to another wall have none.
    pub fn wall_end_faces(&self, half_thickness: f64) -> Vec<Segment> {
        let ends = self.walls.iter().flat_map(|w| [(w.a, w.b), (w.b, w.a)]);
        let shared = |p: Point2| {
            self.walls
                .iter()
                .filter(|w| w.a.distance(p) < 1e-6 || w.b.distance(p) < 1e-6)
                .count()
                > 1
        };
        ends.filter(|&(end, _)| !shared(end))
            .filter_map(|(end, other)| {
                let length = end.distance(other);
                (length > 1e-9).then(|| {
                    // The unit normal of the wall, scaled to the half thickness.
                    let k = half_thickness / length;
                    let (nx, ny) = (-(other.y - end.y) * k, (other.x - end.x) * k);
                    Segment {
                        a: Point2::new(end.x + nx, end.y + ny),
                        b: Point2::new(end.x - nx, end.y - ny),
                    }
                })
            })
            .collect()
    }

    /// True when `p` lies within the world's bounds.
    pub fn contains(&self, p: Point2) -> bool {
        p.x.abs() <= self.width / 2.0 && p.y.abs() <= self.height / 2.0
    }
}
