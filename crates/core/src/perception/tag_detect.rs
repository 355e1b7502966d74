//! AprilTags (36h11) on the floor found with OpenCV (seed 003 §1.2.2, §2.1): the ArUco
//! detector on the 36h11 dictionary, each tag's pose by solvePnP (IPPE_SQUARE) from its
//! four corners, turned through the camera's mount into the robot frame and so into the
//! `TagSighting` the ideal tag camera gives (ahead of and right of the image centre's
//! floor point, the tag's angle), with the seed's outputs beside it: lateral, vertical
//! and distance in the camera frame and the centre pixel.
//!
//! A tag is refused rather than reported with a wrong pose: a corner near the image's
//! edge (its border may be cut off), corners the pose does not reproject onto, or a pose
//! that does not lie flat on the floor. Ids the map does not hold are counted and left.

use super::calibration;
use super::frame::GrayFrame;
use super::intrinsics::Intrinsics;
use super::mount::Mount;
use super::square_pose::square_pose;
use super::tag_camera::{TagCameraConfig, TagCornerRefinement};
use crate::geometry::wrap_angle;
use crate::tags::drive::TagSighting;
use crate::tags::{TagId, TagMap};
use opencv::aruco;
use opencv::core::{Mat, Point2f, Ptr, Vector};
use opencv::prelude::*;
use std::f64::consts::FRAC_PI_2;

/// Candidates nearer each other than this share of their perimeter are one square
/// (OpenCV's minMarkerDistanceRate): under a cell, 1/32 of the perimeter.
const MIN_MARKER_DISTANCE_RATE: f64 = 0.02;

/// Why detection could not run.
#[derive(Debug, thiserror::Error)]
pub enum TagDetectError {
    #[error("OpenCV: {0}")]
    OpenCv(#[from] opencv::Error),
    #[error("frame is {got_w}x{got_h} but the tag camera's is {want_w}x{want_h}")]
    FrameSize {
        got_w: usize,
        got_h: usize,
        want_w: u32,
        want_h: u32,
    },
    #[error("the tag camera does not look down at the floor: check [vision.tag_camera] mount")]
    NoFloor,
}

/// One tag found, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TagDetection {
    /// As the ideal tag camera reports it.
    pub sighting: TagSighting,
    /// Seed 003 §2.1's (x, y, z): the tag's centre in the camera frame, metres (x
    /// lateral, + right; y vertical, + down the image; z distance along the axis).
    pub camera_xyz: [f64; 3],
    /// Seed 003 §2.1's centre_x, centre_y: the tag centre's pixel.
    pub centre_px: [f64; 2],
    /// RMS distance between the corners found and the pose's reprojection, pixels.
    pub reprojection_px: f64,
    /// The corners found, clockwise from the marker's top-left, pixels.
    pub corners: [[f32; 2]; 4],
}

/// What one frame showed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TagFrame {
    pub detections: Vec<TagDetection>,
    /// Tags decoded with ids the map does not hold, left out.
    pub unknown: usize,
    /// Tags of the map decoded but whose pose was refused.
    pub refused: usize,
}

/// The tag camera's detector and pose solver.
pub struct TagDetector {
    config: TagCameraConfig,
    intrinsics: Intrinsics,
    mount: Mount,
    /// The image centre's floor point, metres ahead of the robot's centre.
    look: f64,
    /// Half the black square's side, metres.
    half_side: f64,
    dictionary: Ptr<aruco::Dictionary>,
    parameters: Ptr<aruco::DetectorParameters>,
    camera_matrix: Mat,
    distortion: Mat,
}

impl std::fmt::Debug for TagDetector {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TagDetector")
            .field("intrinsics", &self.intrinsics)
            .field("half_side", &self.half_side)
            .finish_non_exhaustive()
    }
}

impl TagDetector {
    /// A detector for `camera` and tags with black squares `side` metres across.
    pub fn new(camera: &TagCameraConfig, side: f64) -> Result<Self, TagDetectError> {
        Self::with_intrinsics(camera, side, camera.intrinsics())
    }

    /// As `new`, the lens calibrated elsewhere (a ROS 2 camera's camera_info) rather
    /// than the config's image size and field of view.
    pub fn with_intrinsics(
        camera: &TagCameraConfig,
        side: f64,
        intrinsics: Intrinsics,
    ) -> Result<Self, TagDetectError> {
        let mut parameters = aruco::DetectorParameters::create()?;
        parameters.set_corner_refinement_method(match camera.corner_refinement {
            TagCornerRefinement::None => aruco::CORNER_REFINE_NONE,
            TagCornerRefinement::Subpix => aruco::CORNER_REFINE_SUBPIX,
            TagCornerRefinement::Apriltag => aruco::CORNER_REFINE_APRILTAG,
        });
        // Seed 003 §1.2.2: the AprilTag detector's quad decimate 1.0 (OpenCV's own
        // AprilTag refinement takes it too).
        parameters.set_april_tag_quad_decimate(1.0);
        // A printed tag's white border is one cell wide: the square round it (against a
        // darker floor) lies 1/32 of the perimeter outside the black square, nearer than
        // OpenCV's default 0.05, which merges the two and keeps the outer, blank one.
        parameters.set_min_marker_distance_rate(MIN_MARKER_DISTANCE_RATE);
        // One threshold pass, its window odd as OpenCV's adaptiveThreshold needs.
        let window = (camera.threshold_window_px | 1).min(255) as i32;
        parameters.set_adaptive_thresh_win_size_min(window);
        parameters.set_adaptive_thresh_win_size_max(window);
        Ok(Self {
            look: camera.look().ok_or(TagDetectError::NoFloor)?,
            half_side: side / 2.0,
            mount: camera.mount(),
            camera_matrix: calibration::camera_matrix(&intrinsics)?,
            distortion: calibration::distortion(&intrinsics)?,
            intrinsics,
            config: camera.clone(),
            dictionary: super::tag_patterns::dictionary()?,
            parameters,
        })
    }

    /// The image centre's floor point, metres ahead of the robot's centre.
    pub fn look(&self) -> f64 {
        self.look
    }

    /// Finds the tags of `map` in `frame` and measures each one's pose.
    pub fn detect(&self, frame: &GrayFrame, map: &TagMap) -> Result<TagFrame, TagDetectError> {
        let k = &self.intrinsics;
        if frame.width != k.width as usize
            || frame.height != k.height as usize
            || frame.data.len() != frame.width * frame.height
        {
            return Err(TagDetectError::FrameSize {
                got_w: frame.width,
                got_h: frame.height,
                want_w: k.width,
                want_h: k.height,
            });
        }
        let image =
            Mat::new_rows_cols_with_data(frame.height as i32, frame.width as i32, &frame.data)?;
        let mut corners: Vector<Vector<Point2f>> = Vector::new();
        let mut ids: Vector<i32> = Vector::new();
        let mut refused: Vector<Vector<Point2f>> = Vector::new();
        aruco::detect_markers(
            &image,
            &self.dictionary,
            &mut corners,
            &mut ids,
            &self.parameters,
            &mut refused,
        )?;
        let mut out = TagFrame::default();
        for (quad, id) in corners.iter().zip(ids.iter()) {
            let id = TagId::try_from(id).unwrap_or(TagId::MAX);
            if !map.tags.contains_key(&id) {
                out.unknown += 1;
                continue;
            }
            match self.measure(id, &quad)? {
                Some(d) => out.detections.push(d),
                None => out.refused += 1,
            }
        }
        out.detections.sort_by_key(|d| d.sighting.id);
        Ok(out)
    }

    /// The pose of tag `id` from its corners `quad`; None when it is refused.
    fn measure(
        &self,
        id: TagId,
        quad: &Vector<Point2f>,
    ) -> Result<Option<TagDetection>, TagDetectError> {
        let corners: [[f32; 2]; 4] = std::array::from_fn(|k| {
            let p = quad.get(k).unwrap_or_default();
            [p.x, p.y]
        });
        if quad.len() != 4 || !self.clear_of_edges(&corners) {
            return Ok(None);
        }
        let Some(pose) = square_pose(self.half_side, quad, &self.camera_matrix, &self.distortion)?
        else {
            return Ok(None);
        };
        let (centre, turn, reprojection_px) = (pose.centre, pose.rotation, pose.reprojection_px);
        if !(centre.iter().all(|v| v.is_finite()) && centre.z > 0.0)
            || reprojection_px > self.config.max_reprojection_error_px
        {
            return Ok(None);
        }
        // Seed 001 §2's camera -> robot transform (p_r = R p_c + t) for the centre, the
        // marker's top (object y) and its normal (object z, out of the marker).
        let on_robot = self.mount.to_robot(centre);
        let top = self.mount.rotate_to_robot(turn.column(1).into_owned());
        let normal = self.mount.rotate_to_robot(turn.column(2).into_owned());
        let flat = normal.z >= self.config.max_tilt_deg.to_radians().cos();
        if !flat || on_robot.z.abs() > self.config.max_height {
            return Ok(None);
        }
        // The robot turned anticlockwise from the tag's way sees the tag's top turned
        // clockwise by as much: align = -(the top's yaw in the robot frame), folded into
        // ±45° as a square looks alike a quarter turned (the ideal camera's convention).
        let turned = wrap_angle(-top.y.atan2(top.x));
        let align = turned - (turned / FRAC_PI_2).round() * FRAC_PI_2;
        let k = &self.intrinsics;
        let (cu, cv) = k.project(centre.x, centre.y, centre.z);
        Ok(Some(TagDetection {
            sighting: TagSighting {
                id,
                ahead: on_robot.x - self.look,
                lateral: -on_robot.y,
                align,
            },
            camera_xyz: [centre.x, centre.y, centre.z],
            centre_px: [cu, cv],
            reprojection_px,
            corners,
        }))
    }

    /// Whether every corner lies at least the edge margin inside the image.
    fn clear_of_edges(&self, corners: &[[f32; 2]; 4]) -> bool {
        let m = self.config.edge_margin_px;
        let (w, h) = (
            f64::from(self.intrinsics.width) - 1.0,
            f64::from(self.intrinsics.height) - 1.0,
        );
        corners.iter().all(|&[u, v]| {
            let (u, v) = (f64::from(u), f64::from(v));
            u >= m && v >= m && u <= w - m && v <= h - m
        })
    }
}

#[cfg(test)]
#[path = "tag_detect_tests.rs"]
mod tests;
