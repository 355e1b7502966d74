//! A lane track on the twin's floor (seed 000 §2-§3, an AutoRace-style course): the
//! lane's centreline with a yellow line on its left and a white one on its right, the
//! traffic lights beside it and the barriers across it, each on its own cycle of the
//! twin's time; and the lighting the colour camera renders it under.
//!
//! `line` is the lane's geometry (where a point lies along and across it), `signals` the
//! lights and barriers, `file` the `[track]` section of a world file, `lighting` the
//! lighting variants of seed 000 §6.4.2.

mod file;
pub mod lighting;
mod line;
mod score;
mod signals;

pub use file::{
    BarrierCycleSpec, BarrierSpec, LightCycleSpec, LightSpec, TrackError, TrackSpec, closed_bspline,
};
pub use lighting::{Lighting, LightingLevel};
pub use line::{Track, TrackPoint};
pub use score::{LaneFigures, LaneScore};
pub use signals::{Barrier, BarrierCycle, LIGHT_BEYOND, LightCycle, TrafficLight};

use crate::geometry::Point2;

/// Height of a traffic light's lamps' centre above the floor, metres.
pub const LAMP_HEIGHT: f64 = 0.22;
/// Metres between a light's lamps, red above yellow above green.
pub const LAMP_PITCH: f64 = 0.05;

/// Height of the lamp of `colour` above the floor, metres.
pub fn lamp_height(colour: crate::data::LightColour) -> f64 {
    use crate::data::LightColour;
    match colour {
        LightColour::Red => LAMP_HEIGHT + LAMP_PITCH,
        LightColour::Yellow => LAMP_HEIGHT,
        LightColour::Green => LAMP_HEIGHT - LAMP_PITCH,
    }
}

/// Radius of a lit lamp, metres.
pub const LAMP_RADIUS: f64 = 0.025;
/// Height of a barrier's arm above the floor at its pivot, metres.
pub const ARM_HEIGHT: f64 = 0.1;
/// Thickness of a barrier's arm, metres.
pub const ARM_THICKNESS: f64 = 0.03;

/// The track and what stands on it.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackScene {
    /// The section it was built from, written back as it was read.
    pub spec: TrackSpec,
    pub track: Track,
    pub lights: Vec<TrafficLight>,
    pub barriers: Vec<Barrier>,
}

impl TrackScene {
    /// The poles the lidar and the footprint meet: one per light and per barrier, as the
    /// centre of a square post `POST` metres across.
    pub fn posts(&self) -> Vec<Point2> {
        let lights = self.lights.iter().map(|l| l.position);
        let barriers = self.barriers.iter().map(|b| b.pivot);
        lights.chain(barriers).collect()
    }
}

impl TrackScene {
    /// The posts' outlines, as walls: the lidar sees them and the robot cannot drive
    /// through them.
    pub fn post_outlines(&self) -> Vec<crate::geometry::Segment> {
        use crate::geometry::Pose2;
        (self.posts().into_iter())
            .flat_map(|p| super::shapes::rect_edges(Pose2::new(p.x, p.y, 0.0), POST, POST))
            .collect()
    }
}

/// Side of a light's or barrier's post, metres.
pub const POST: f64 = 0.04;
