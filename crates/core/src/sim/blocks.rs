//! Blocks as the twin moves them: where they are, their markers and their outline.

use super::shapes::{rect_edges, rect_faces};
use super::{Block, BlockColor, Marker};
use crate::geometry::{Pose2, Segment, wrap_angle};

/// A block in the running twin.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockState {
    pub color: BlockColor,
    pub markers: [u32; 2],
    pub pose: Pose2,
    /// True while the gripper holds it.
    pub held: bool,
    /// Side of the square, metres.
    pub size: f64,
}

impl BlockState {
    pub fn from_block(b: &Block) -> Self {
        Self {
            color: b.color,
            markers: b.markers,
            pose: b.pose,
            held: false,
            size: b.size,
        }
    }

    /// The odd marker on the local +x face and the even one on the local +y face, as placed now.
    pub fn current_markers(&self) -> [Marker; 2] {
        let faces = rect_faces(self.pose, self.size, self.size);
        [0, 1].map(|k| Marker {
            id: self.markers[k],
            position: faces[k].0,
            normal: wrap_angle(faces[k].1),
        })
    }

    /// The square's outline, for the lidar and for hiding markers behind it.
    pub fn edges(&self) -> [Segment; 4] {
        rect_edges(self.pose, self.size, self.size)
    }

    /// Radius of the circle the robot may not enter: the square's half-diagonal.
    pub fn radius(&self) -> f64 {
        self.size / std::f64::consts::SQRT_2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;

    #[test]
    fn markers_sit_on_adjacent_faces_and_turn_with_the_block() {
        let b = Block {
            color: BlockColor::Red,
            pose: Pose2::new(1.0, 1.0, 0.0),
            size: 0.05,
            markers: [421, 422],
        };
        let mut s = BlockState::from_block(&b);
        let [odd, even] = s.current_markers();
        assert_eq!((odd.id, even.id), (421, 422));
        assert!(odd.position.distance(Point2::new(1.025, 1.0)) < 1e-12 && odd.normal.abs() < 1e-12);
        assert!(even.position.distance(Point2::new(1.0, 1.025)) < 1e-12);
        s.pose.theta = std::f64::consts::FRAC_PI_2;
        let [odd, _] = s.current_markers();
        assert!(odd.position.distance(Point2::new(1.0, 1.025)) < 1e-12);
        assert!((s.radius() - 0.05 / 2f64.sqrt()).abs() < 1e-15);
    }
}
