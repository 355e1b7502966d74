//! What a lane camera's pipeline made of one colour frame (seed 000 §2-§3): the lane's
//! lines and the robot's offset from their centre, the traffic light and the barrier.
//! Filled by the twin's lane camera or a real camera's, read by the pilot's lane mode and
//! shown by the console's lane panel.

use serde::{Deserialize, Serialize};

/// A traffic light's colour (seed 000 §3.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LightColour {
    Red,
    Yellow,
    Green,
}

impl LightColour {
    pub const ALL: [LightColour; 3] = [Self::Red, Self::Yellow, Self::Green];

    pub fn label(self) -> &'static str {
        match self {
            Self::Red => "red",
            Self::Yellow => "yellow",
            Self::Green => "green",
        }
    }

    /// Whether a robot must stop before the light (red and yellow).
    pub fn stops(self) -> bool {
        self != Self::Green
    }
}

/// A barrier's arm (seed 000 §3.2.3: DOWN within 20 degrees of level, UP from 70).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BarrierState {
    Down,
    Moving,
    Up,
}

impl BarrierState {
    pub const ALL: [BarrierState; 3] = [Self::Down, Self::Moving, Self::Up];

    pub fn label(self) -> &'static str {
        match self {
            Self::Down => "down",
            Self::Moving => "moving",
            Self::Up => "up",
        }
    }

    /// The state an arm at `angle_deg` above level shows (seed 000 §3.2.3's observation
    /// model: |angle| <= 20 DOWN, >= 70 UP, MOVING between).
    pub fn of_angle(angle_deg: f64) -> Self {
        match angle_deg.abs() {
            a if a <= 20.0 => Self::Down,
            a if a >= 70.0 => Self::Up,
            _ => Self::Moving,
        }
    }
}

/// A lit traffic light found in a frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LightSeen {
    pub colour: LightColour,
    /// Distance from the camera, metres.
    pub range: f64,
    /// How far ahead of the camera along the robot's heading, metres: the lamp stands
    /// `range` off, this much of it ahead and the rest aside.
    pub ahead: f64,
    /// How far left of the camera, metres (negative: right).
    pub left: f64,
    /// Posterior probability of `colour` (seed 000 §3.1.2's classifier).
    pub confidence: f64,
}

/// A barrier found in a frame, after the state filter.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BarrierSeen {
    /// The filtered state: the most probable one.
    pub state: BarrierState,
    /// The arm's angle above level in the image, degrees.
    pub angle_deg: f64,
    /// Distance from the camera to the arm, metres.
    pub range: f64,
    /// The filter's probabilities of down, moving and up.
    pub belief: [f64; 3],
    /// Whether this frame showed the arm; if not, its angle and range are as last seen.
    pub fresh: bool,
}

/// A small colour picture of the newest frame, RGB bytes, rows top to bottom.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ColourThumbnail {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
}

impl ColourThumbnail {
    /// The colour at (`x`, `y`), black outside.
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        if x < self.width && y < self.height {
            let i = 3 * (y * self.width + x);
            [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
        } else {
            [0; 3]
        }
    }
}

/// A lane line fitted in the bird's-eye view: x = a y^2 + b y + c (seed 000 §2.2.1), with x
/// across and y along the floor ahead, in bird's-eye pixels of `LaneSighting::MM_PER_PX`.
pub type LaneFit = [f64; 3];

/// What the lane pipeline made of one frame.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LaneSighting {
    /// The lane centre's offset from the image centre in bird's-eye pixels at the look-ahead
    /// row, positive when the centre lies to the robot's right (seed 000 §2.4's error,
    /// after the 5-frame filter); none when no line was found.
    pub error_px: Option<f64>,
    /// The lane's curvature at the look-ahead row, 1/m, positive turning left.
    pub curvature: Option<f64>,
    /// The yellow (left) and white (right) lines' fits, filtered.
    pub yellow: Option<LaneFit>,
    pub white: Option<LaneFit>,
    /// Lane pixels as a fraction of the image (the PI loop holds it near 2-3 %).
    pub pixel_ratio: f64,
    pub light: Option<LightSeen>,
    pub barrier: Option<BarrierSeen>,
    /// Seconds the pipeline took, when a stopwatch was at hand.
    pub latency: Option<f64>,
    pub thumbnail: Option<ColourThumbnail>,
    /// Why the frame could not be used, if it could not.
    pub error: Option<String>,
}

impl LaneSighting {
    /// Millimetres of floor per bird's-eye pixel: seed 000's gains (Kp 0.0025, Kd 0.007)
    /// act on an error in pixels of a bird's-eye view about a metre across, so a pixel is
    /// taken as a millimetre.
    pub const MM_PER_PX: f64 = 1.0;

    /// A frame that could not be used, and why.
    pub fn failed(why: impl Into<String>) -> Self {
        Self {
            error: Some(why.into()),
            ..Self::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_barrier_angle_bands_are_the_seeds() {
        assert_eq!(BarrierState::of_angle(0.0), BarrierState::Down);
        assert_eq!(BarrierState::of_angle(-20.0), BarrierState::Down);
        assert_eq!(BarrierState::of_angle(45.0), BarrierState::Moving);
        assert_eq!(BarrierState::of_angle(70.0), BarrierState::Up);
        assert!(LightColour::Yellow.stops() && !LightColour::Green.stops());
    }
}
