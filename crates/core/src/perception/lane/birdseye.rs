//! The lane camera's view of the floor: the bird's-eye grid over the floor ahead, the
//! homography from a grid cell to the image pixel that sees it, the horizon's row, and
//! rays from pixels back onto a plane of the robot frame.
//!
//! Grid cells are numbered as an image: column 0 at the view's left edge, row 0 at its
//! far edge. Fits are in millimetres on that grid: x across from the left edge, y down
//! from the far edge.

use super::config::BirdsEyeView;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::lane_camera::LaneCameraConfig;
use crate::perception::mount::Mount;
use nalgebra::{Matrix3, Vector3};

/// The bird's-eye grid and the camera that sees it.
#[derive(Clone, Debug)]
pub struct BirdsEye {
    view: BirdsEyeView,
    cols: usize,
    rows: usize,
    intrinsics: Intrinsics,
    mount: Mount,
    grid_to_image: Matrix3<f64>,
}

impl BirdsEye {
    /// The grid of `view` as `camera` sees it; an error when part of the view lies behind
    /// the camera or wholly outside its image.
    pub fn new(view: &BirdsEyeView, camera: &LaneCameraConfig) -> Result<Self, String> {
        let (intrinsics, mount) = (camera.intrinsics(), camera.mount());
        let cols = (2.0 * view.half_width / view.cell).round() as usize;
        let rows = ((view.far - view.near) / view.cell).round() as usize;
        // Floor (x, y, 1) -> camera point: p_c = R^T (p_r - t) is affine in (x, y) on z = 0.
        let origin = mount.to_camera(Vector3::zeros());
        let along = mount.to_camera(Vector3::x()) - origin;
        let across = mount.to_camera(Vector3::y()) - origin;
        let floor_to_camera = Matrix3::from_columns(&[along, across, origin]);
        // Cell (col, row, 1) -> floor (x, y, 1), cell centres.
        let c = view.cell;
        let cell_to_floor = Matrix3::new(
            0.0,
            -c,
            view.far - 0.5 * c, //
            -c,
            0.0,
            view.half_width - 0.5 * c, //
            0.0,
            0.0,
            1.0,
        );
        // Pinhole: u = fx x / z + cx, v = fy y / z + cy (Hartley & Zisserman eq. 6.4).
        let k = Matrix3::new(
            intrinsics.fx,
            0.0,
            intrinsics.cx, //
            0.0,
            intrinsics.fy,
            intrinsics.cy, //
            0.0,
            0.0,
            1.0,
        );
        let grid_to_image = k * floor_to_camera * cell_to_floor;
        let eye = Self {
            view: view.clone(),
            cols,
            rows,
            intrinsics,
            mount,
            grid_to_image,
        };
        let corners = [
            (0.0, 0.0),
            (cols as f64, 0.0),
            (0.0, rows as f64),
            (cols as f64, rows as f64),
        ];
        let seen: Vec<_> = corners
            .iter()
            .map(|&(c, r)| eye.pixel_of_cell(c, r))
            .collect();
        if seen.iter().any(Option::is_none) {
            return Err("part of the view lies behind the camera".into());
        }
        if !seen
            .iter()
            .flatten()
            .any(|&(_, v)| v >= 0.0 && v < f64::from(eye.intrinsics.height))
        {
            return Err("the view lies wholly above or below the image".into());
        }
        Ok(eye)
    }

    pub fn cols(&self) -> usize {
        self.cols
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        &self.intrinsics
    }

    pub fn mount(&self) -> &Mount {
        &self.mount
    }

    /// Millimetres of floor per grid cell.
    pub fn cell_mm(&self) -> f64 {
        self.view.cell * 1000.0
    }

    /// The grid's width in millimetres; the robot's axis is at half of it.
    pub fn width_mm(&self) -> f64 {
        self.cols as f64 * self.cell_mm()
    }

    /// The fit row (millimetres down from the far edge) of a floor distance ahead.
    pub fn row_mm_of_ahead(&self, ahead: f64) -> f64 {
        (self.view.far - ahead) * 1000.0
    }

    /// The homography taking grid (col, row, 1) to image (u, v, 1), row-major, for
    /// OpenCV's inverse-map warp.
    pub fn grid_to_image(&self) -> [[f64; 3]; 3] {
        let m = &self.grid_to_image;
        [0, 1, 2].map(|r| [m[(r, 0)], m[(r, 1)], m[(r, 2)]])
    }

    /// The image pixel seeing grid point (col, row), none behind the camera.
    pub fn pixel_of_cell(&self, col: f64, row: f64) -> Option<(f64, f64)> {
        let p = self.grid_to_image * Vector3::new(col, row, 1.0);
        (p.z > 1e-9).then(|| (p.x / p.z, p.y / p.z))
    }

    /// The image pixel of a robot-frame point, none behind the camera.
    pub fn pixel_of(&self, p: Vector3<f64>) -> Option<(f64, f64)> {
        let c = self.mount.to_camera(p);
        (c.z > 1e-9).then(|| self.intrinsics.project(c.x, c.y, c.z))
    }

    /// The first image row below the horizon (the floor's vanishing line), clamped into
    /// the image: rows above it cannot see the floor.
    pub fn horizon_row(&self) -> f64 {
        let d = self.mount.to_camera(Vector3::x()) - self.mount.to_camera(Vector3::zeros());
        let h = f64::from(self.intrinsics.height);
        if d.z <= 1e-9 {
            // Looking away from level ahead: the horizon is above the image.
            return if d.y > 0.0 { h } else { 0.0 };
        }
        // Vanishing point of the direction ahead (Hartley & Zisserman 8.6.1).
        (self.intrinsics.fy * d.y / d.z + self.intrinsics.cy).clamp(0.0, h)
    }

    /// The topmost image row the grid's far edge reaches, clamped into the image.
    pub fn floor_top_row(&self) -> usize {
        let far = [0.0, self.cols as f64]
            .iter()
            .filter_map(|&c| self.pixel_of_cell(c, 0.0))
            .map(|(_, v)| v)
            .fold(f64::INFINITY, f64::min);
        far.floor()
            .clamp(0.0, f64::from(self.intrinsics.height - 1)) as usize
    }

    /// The ray through pixel (u, v): its origin (the lens) and direction, robot frame.
    pub fn ray(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        let k = &self.intrinsics;
        // Inverse pinhole: the camera-frame direction ((u - cx)/fx, (v - cy)/fy, 1).
        let dir = Vector3::new((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
        let origin = self.mount.to_robot(Vector3::zeros());
        (origin, self.mount.rotate_to_robot(dir))
    }

    /// Where the ray through (u, v) meets the level plane `z = height`, ahead of the lens.
    pub fn meet_height(&self, u: f64, v: f64, height: f64) -> Option<Vector3<f64>> {
        let (o, d) = self.ray(u, v);
        let s = (height - o.z) / d.z;
        (d.z.abs() > 1e-9 && s > 0.0).then(|| o + s * d)
    }

    /// Where the ray through (u, v) meets the upright plane `x = ahead` across the robot.
    pub fn meet_ahead(&self, u: f64, v: f64, ahead: f64) -> Option<Vector3<f64>> {
        let (o, d) = self.ray(u, v);
        let s = (ahead - o.x) / d.x;
        (d.x.abs() > 1e-9 && s > 0.0).then(|| o + s * d)
    }

    /// The floor point (robot frame) of fit coordinates (x, y) in millimetres.
    pub fn floor_of_mm(&self, x_mm: f64, y_mm: f64) -> (f64, f64) {
        (
            self.view.far - y_mm / 1000.0,
            self.view.half_width - x_mm / 1000.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_cell_and_its_floor_point_land_on_the_same_pixel() {
        let eye = BirdsEye::new(&BirdsEyeView::default(), &LaneCameraConfig::default()).unwrap();
        assert_eq!((eye.cols(), eye.rows()), (250, 175));
        // Cell (50, 100): 0.5 - 0.202 = 0.298 m left, 0.9 - 0.402 = 0.498 m ahead.
        let (x, y) = eye.floor_of_mm(50.5 * 4.0, 100.5 * 4.0);
        assert!(
            (x - 0.498).abs() < 1e-9 && (y - 0.298).abs() < 1e-9,
            "{x} {y}"
        );
        let a = eye.pixel_of_cell(50.0, 100.0).unwrap();
        let b = eye.pixel_of(Vector3::new(x, y, 0.0)).unwrap();
        assert!(
            (a.0 - b.0).abs() < 1e-6 && (a.1 - b.1).abs() < 1e-6,
            "{a:?} {b:?}"
        );
        // And the ray back through that pixel meets the floor there.
        let p = eye.meet_height(a.0, a.1, 0.0).unwrap();
        assert!((p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9, "{p:?}");
        // 20 degrees down: the horizon is f tan 20 = 139 rows above the centre.
        assert!((eye.horizon_row() - (239.5 - 381.36 * 20f64.to_radians().tan())).abs() < 0.1);
        assert!(eye.floor_top_row() > eye.horizon_row() as usize);
    }
}
