//! ArUco markers found with OpenCV (seed 001 sections 1-2): detection in the original
//! dictionary, pose of each marker by solvePnP (IPPE_SQUARE), camera -> robot transform,
//! and seed 001's (range, bearing) measurement for the EKF.
//!
//! `Detector` is built once from the config and then called on any thread (it is `Send`
//! and `Clone`); camera sources hand it `GrayFrame`s.

use super::bit_check::{self, CELLS};
use super::calibration;
use super::config::{CornerRefinement, DetectorConfig, VisionConfig};
use super::edge_fit::{Refined, shortest_side};
use super::frame::{CameraStatus, GrayFrame, Thumbnail};
use super::intrinsics::Intrinsics;
use super::mount::{Mount, range_bearing};
use super::region::Region;
use super::square_pose::square_pose;
use crate::clock::Clock;
use crate::data::MarkerSighting;
use opencv::core::{Mat, Point2f, Ptr, Vector};
use opencv::prelude::*;
use opencv::{aruco, imgproc};

/// Why detection could not run.
#[derive(Debug, thiserror::Error)]
pub enum VisionError {
    #[error("OpenCV: {0}")]
    OpenCv(#[from] opencv::Error),
    #[error("frame is {got_w}x{got_h} but the calibration is for {want_w}x{want_h}")]
    FrameSize {
        got_w: usize,
        got_h: usize,
        want_w: u32,
        want_h: u32,
    },
    #[error(transparent)]
    Calibration(#[from] super::intrinsics::CalibrationError),
}

/// One marker found in a frame, with the quality of its pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArucoSighting {
    pub id: u32,
    /// Planar range from the robot centre, metres.
    pub range: f64,
    /// Bearing from the robot's heading, radians, CCW positive.
    pub bearing: f64,
    /// RMS distance between the detected corners and the pose's reprojection, pixels.
    pub reprojection_px: f64,
    /// Detected corners, clockwise from the marker's top-left, pixels.
    pub corners: [[f32; 2]; 4],
}

impl ArucoSighting {
    pub fn sighting(&self) -> MarkerSighting {
        MarkerSighting {
            id: self.id,
            range: self.range,
            bearing: self.bearing,
        }
    }
}

/// What one frame showed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Detection {
    /// Markers with a trustworthy pose, for the EKF.
    pub sightings: Vec<ArucoSighting>,
    /// Markers decoded but refused: reprojection error over the limit, or out of range.
    pub rejected: usize,
    /// Every ID decoded in the frame, accepted or not, ascending.
    pub ids: Vec<u32>,
    /// Seconds detection and pose took, when a stopwatch was given.
    pub latency: Option<f64>,
}

impl Detection {
    /// The sightings as the link reports them.
    pub fn marker_sightings(&self) -> Vec<MarkerSighting> {
        self.sightings.iter().map(ArucoSighting::sighting).collect()
    }

    /// What the camera panel shows of it, with a thumbnail of the frame if there is one.
    pub fn status(self, thumbnail: Option<Thumbnail>) -> CameraStatus {
        CameraStatus {
            accepted: self.sightings.len(),
            rejected: self.rejected,
            ids: self.ids,
            latency: self.latency,
            thumbnail,
            error: None,
        }
    }
}

/// Thumbnail size handed to the console, pixels.
pub const THUMBNAIL: (usize, usize) = (96, 54);

/// The ArUco detector and pose solver of one camera.
pub struct Detector {
    config: VisionConfig,
    intrinsics: Intrinsics,
    mount: Mount,
    dictionary: Ptr<aruco::Dictionary>,
    parameters: Ptr<aruco::DetectorParameters>,
    camera_matrix: Mat,
    distortion: Mat,
}

impl std::fmt::Debug for Detector {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Detector")
            .field("intrinsics", &self.intrinsics)
            .field("mount", &self.mount)
            .finish_non_exhaustive()
    }
}

impl Clone for Detector {
    /// A fresh detector from the same settings (OpenCV objects are not shared).
    fn clone(&self) -> Self {
        Self::with_intrinsics(&self.config, self.intrinsics.clone())
            .expect("settings that built a detector build it again")
    }
}

impl Detector {
    /// A detector for the configured camera: calibration file or seed 001's intrinsics.
    pub fn from_config(config: &VisionConfig) -> Result<Self, VisionError> {
        let intrinsics = calibration::load_or_default(config.calibration.as_deref())?;
        Self::with_intrinsics(config, intrinsics)
    }

    pub fn with_intrinsics(
        config: &VisionConfig,
        intrinsics: Intrinsics,
    ) -> Result<Self, VisionError> {
        let dictionary = aruco::get_predefined_dictionary(
            aruco::PREDEFINED_DICTIONARY_NAME::DICT_ARUCO_ORIGINAL,
        )?;
        let parameters = parameters(&config.detector)?;
        Ok(Self {
            config: config.clone(),
            mount: Mount::new(&config.mount),
            camera_matrix: calibration::camera_matrix(&intrinsics)?,
            distortion: calibration::distortion(&intrinsics)?,
            intrinsics,
            dictionary,
            parameters,
        })
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        &self.intrinsics
    }

    pub fn mount(&self) -> &Mount {
        &self.mount
    }

    pub fn config(&self) -> &VisionConfig {
        &self.config
    }

    /// The dictionary markers are drawn from and looked up in.
    pub fn dictionary(&self) -> &Ptr<aruco::Dictionary> {
        &self.dictionary
    }

    /// OpenCV's detector parameters, as the config set them.
    pub fn parameters(&self) -> &Ptr<aruco::DetectorParameters> {
        &self.parameters
    }

    /// Reads `frame` for the console: the sightings for the estimator, and the status
    /// (IDs, counts, latency, thumbnail) for the camera panel. A blank frame (a covered
    /// camera, `blank::blank_reason`) is a failed one.
    pub fn read(
        &self,
        frame: &GrayFrame,
        stopwatch: Option<&dyn Clock>,
    ) -> (Vec<MarkerSighting>, CameraStatus) {
        if let Some(why) = super::blank::blank_reason(frame) {
            return (Vec::new(), CameraStatus::failed(why));
        }
        match self.detect(frame, stopwatch) {
            Ok(d) => (
                d.marker_sightings(),
                d.status(Some(frame.thumbnail(THUMBNAIL.0, THUMBNAIL.1))),
            ),
            Err(e) => (Vec::new(), CameraStatus::failed(e.to_string())),
        }
    }

    /// Finds the markers in `frame` and measures each one's range and bearing from the
    /// robot. With a stopwatch, the time taken is reported as `latency`.
    pub fn detect(
        &self,
        frame: &GrayFrame,
        stopwatch: Option<&dyn Clock>,
    ) -> Result<Detection, VisionError> {
        let started = stopwatch.map(|s| s.now());
        self.check_size(frame)?;
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
        let mut out = self.read_quads(frame, corners.iter().zip(ids.iter()))?;
        out.latency = stopwatch.zip(started).map(|(s, t0)| s.now() - t0);
        Ok(out)
    }

    /// As `detect`, but looking only inside `regions` of the frame: the markers found are
    /// those `detect` finds wholly inside a region, at least half the largest threshold
    /// window and 3 px from its edges (`aruco_regions`).
    pub fn detect_in(
        &self,
        frame: &GrayFrame,
        regions: &[Region],
        stopwatch: Option<&dyn Clock>,
    ) -> Result<Detection, VisionError> {
        let started = stopwatch.map(|s| s.now());
        self.check_size(frame)?;
        let quads = super::aruco_regions::find(self, frame, regions)?;
        let mut out = self.read_quads(frame, quads.into_iter())?;
        out.latency = stopwatch.zip(started).map(|(s, t0)| s.now() - t0);
        Ok(out)
    }

    fn check_size(&self, frame: &GrayFrame) -> Result<(), VisionError> {
        if frame.width != self.intrinsics.width as usize
            || frame.height != self.intrinsics.height as usize
            || frame.data.len() != frame.width * frame.height
        {
            return Err(VisionError::FrameSize {
                got_w: frame.width,
                got_h: frame.height,
                want_w: self.intrinsics.width,
                want_h: self.intrinsics.height,
            });
        }
        Ok(())
    }

    /// Refines, checks and measures the decoded squares `quads` (corners and ID) of `frame`.
    fn read_quads(
        &self,
        frame: &GrayFrame,
        quads: impl Iterator<Item = (Vector<Point2f>, i32)>,
    ) -> Result<Detection, VisionError> {
        let mut out = Detection::default();
        for (mut quad, id) in quads {
            let id = id as u32;
            if self.config.detector.corner_refinement == CornerRefinement::Edges {
                let start: [[f32; 2]; 4] = std::array::from_fn(|k| {
                    let p = quad.get(k).unwrap_or_default();
                    [p.x, p.y]
                });
                match super::edge_fit::refine(frame, start) {
                    Refined::Corners(refined) => {
                        quad = refined.iter().map(|&[x, y]| Point2f::new(x, y)).collect();
                    }
                    // Part of the marker is hidden: its square, and so its pose, is wrong.
                    Refined::Hidden => {
                        out.ids.push(id);
                        out.rejected += 1;
                        continue;
                    }
                    Refined::Unmeasured => {}
                }
            }
            if self.config.detector.check_cells && !self.cells_match(frame, id, &quad)? {
                // Not clearly this ID's pattern: a misread is likelier than a marker.
                out.rejected += 1;
                continue;
            }
            out.ids.push(id);
            let limits = &self.config.detector;
            match self.measure(id, &quad)? {
                Some(s)
                    if s.reprojection_px <= limits.max_reprojection_error_px
                        && s.range <= limits.max_range
                        && shortest_side(&s.corners) >= limits.min_side_px =>
                {
                    out.sightings.push(s)
                }
                _ => out.rejected += 1,
            }
        }
        out.ids.sort_unstable();
        out.sightings.sort_by_key(|s| s.id);
        Ok(out)
    }

    /// Whether the cells under `quad` are clearly the pattern of marker `id`.
    fn cells_match(
        &self,
        frame: &GrayFrame,
        id: u32,
        quad: &Vector<Point2f>,
    ) -> Result<bool, VisionError> {
        let unit = [
            Point2f::new(0.0, 0.0),
            Point2f::new(1.0, 0.0),
            Point2f::new(1.0, 1.0),
            Point2f::new(0.0, 1.0),
        ];
        let corners: [Point2f; 4] = std::array::from_fn(|k| quad.get(k).unwrap_or_default());
        let h = imgproc::get_perspective_transform_slice_def(&unit, &corners)?;
        let mut homography = [[0.0; 3]; 3];
        for (r, row) in homography.iter_mut().enumerate() {
            for (c, value) in row.iter_mut().enumerate() {
                *value = *h.at_2d::<f64>(r as i32, c as i32)?;
            }
        }
        let mut drawn = Mat::default();
        aruco::draw_marker(&self.dictionary, id as i32, CELLS as i32, &mut drawn, 1)?;
        let expected: Vec<bool> = drawn.data_bytes()?.iter().map(|&g| g > 127).collect();
        Ok(bit_check::cells_match(frame, &homography, &expected))
    }

    /// Pose of one marker from its four corners; `None` when solvePnP finds none.
    fn measure(
        &self,
        id: u32,
        quad: &Vector<Point2f>,
    ) -> Result<Option<ArucoSighting>, VisionError> {
        let half = self.config.markers.side(id) / 2.0;
        let Some(pose) = square_pose(half, quad, &self.camera_matrix, &self.distortion)? else {
            return Ok(None);
        };
        let corners: [[f32; 2]; 4] = std::array::from_fn(|k| {
            let p = quad.get(k).unwrap_or_default();
            [p.x, p.y]
        });
        let centre = pose.centre;
        if centre.z.is_nan() || centre.z <= 0.0 {
            return Ok(None);
        }
        // Seed 001 section 2: marker in camera frame -> robot frame, then (r, alpha).
        let (range, bearing) = range_bearing(self.mount.to_robot(centre));
        Ok(Some(ArucoSighting {
            id,
            range,
            bearing,
            reprojection_px: pose.reprojection_px,
            corners,
        }))
    }
}

/// OpenCV's detector parameters for `d`.
pub(super) fn parameters(d: &DetectorConfig) -> opencv::Result<Ptr<aruco::DetectorParameters>> {
    let mut parameters = aruco::DetectorParameters::create()?;
    parameters.set_adaptive_thresh_win_size_min(d.adaptive_thresh_win_size_min);
    parameters.set_adaptive_thresh_win_size_max(d.adaptive_thresh_win_size_max);
    parameters.set_adaptive_thresh_win_size_step(d.adaptive_thresh_win_size_step);
    parameters.set_min_marker_perimeter_rate(d.min_marker_perimeter_rate);
    parameters.set_corner_refinement_win_size(d.corner_refinement_win_size);
    parameters.set_corner_refinement_method(match d.corner_refinement {
        CornerRefinement::None => aruco::CORNER_REFINE_NONE,
        // Edge lines start from cornerSubPix's corners.
        CornerRefinement::Subpix | CornerRefinement::Edges => aruco::CORNER_REFINE_SUBPIX,
        CornerRefinement::Contour => aruco::CORNER_REFINE_CONTOUR,
    });
    parameters.set_perspective_remove_pixel_per_cell(d.perspective_remove_pixel_per_cell);
    parameters.set_perspective_remove_ignored_margin_per_cell(
        d.perspective_remove_ignored_margin_per_cell,
    );
    Ok(parameters)
}
