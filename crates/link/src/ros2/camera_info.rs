//! A camera's sensor_msgs/CameraInfo as navdeck's pinhole intrinsics (seed 003 §1.2.2:
//! the tag camera's K gives fx, fy, cx and cy). K is row-major [fx 0 cx; 0 fy cy; 0 0 1]
//! (sensor_msgs/CameraInfo's definition); D is taken for the models OpenCV's own
//! distortion covers (plumb_bob, rational_polynomial), in OpenCV's order.

use navdeck_core::perception::intrinsics::Intrinsics;
use navdeck_msgs::ros::CameraInfo;
use std::path::Path;

/// The intrinsics `m` (from `topic`) gives, checked; the error names the topic, the
/// field and the value.
pub fn intrinsics(m: &CameraInfo, topic: &str) -> Result<Intrinsics, String> {
    let refuse = |field: &str, why: String| format!("camera_info {topic}: {field} {why}");
    if m.binning_x > 1 || m.binning_y > 1 {
        let why = format!(
            "= {}x{}: binned images are not read",
            m.binning_x, m.binning_y
        );
        return Err(refuse("binning_x/binning_y", why));
    }
    let roi = &m.roi;
    let whole = roi.width == 0 || (roi.width == m.width && roi.height == m.height);
    if !whole {
        let why = format!(
            "= {}x{}: cropped images are not read",
            roi.width, roi.height
        );
        return Err(refuse("roi", why));
    }
    let distortion = if m.d.is_empty() || m.d.iter().all(|v| *v == 0.0) {
        vec![0.0; 5]
    } else if matches!(
        m.distortion_model.as_str(),
        "plumb_bob" | "rational_polynomial"
    ) {
        m.d.clone()
    } else {
        let why = format!(
            "{:?} is not one navdeck reads (plumb_bob, rational_polynomial)",
            m.distortion_model
        );
        return Err(refuse("distortion_model", why));
    };
    let k = &m.k;
    Intrinsics {
        width: m.width,
        height: m.height,
        fx: k[0],
        fy: k[4],
        cx: k[2],
        cy: k[5],
        distortion,
    }
    .check(Path::new(topic))
    .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1280x720 camera's calibration as a driver publishes it.
    fn info() -> CameraInfo {
        CameraInfo {
            width: 1280,
            height: 720,
            distortion_model: "plumb_bob".into(),
            d: vec![0.1, -0.2, 0.001, 0.002, 0.05],
            k: [900.0, 0.0, 640.5, 0.0, 905.0, 360.5, 0.0, 0.0, 1.0],
            ..CameraInfo::default()
        }
    }

    #[test]
    fn k_gives_the_focal_lengths_and_principal_point_and_d_the_distortion() {
        let k = intrinsics(&info(), "/camera_info").unwrap();
        assert_eq!((k.width, k.height), (1280, 720));
        assert_eq!((k.fx, k.fy, k.cx, k.cy), (900.0, 905.0, 640.5, 360.5));
        assert_eq!(k.distortion, [0.1, -0.2, 0.001, 0.002, 0.05]);
        // No distortion given is none.
        let plain = CameraInfo {
            d: vec![],
            distortion_model: String::new(),
            ..info()
        };
        assert_eq!(
            intrinsics(&plain, "/camera_info").unwrap().distortion,
            [0.0; 5]
        );
    }

    #[test]
    fn a_calibration_navdeck_cannot_use_is_refused_by_topic_and_field() {
        let cases = [
            (
                CameraInfo {
                    k: [0.0; 9],
                    ..info()
                },
                "fx",
            ),
            (CameraInfo { width: 0, ..info() }, "image_width"),
            (
                CameraInfo {
                    distortion_model: "equidistant".into(),
                    ..info()
                },
                "distortion_model",
            ),
            (
                CameraInfo {
                    binning_x: 2,
                    ..info()
                },
                "binning",
            ),
            (
                CameraInfo {
                    d: vec![f64::NAN; 5],
                    ..info()
                },
                "distortion_coefficients",
            ),
        ];
        for (m, field) in cases {
            let e = intrinsics(&m, "/tb3/camera_info").unwrap_err();
            assert!(
                e.contains("/tb3/camera_info") && e.contains(field),
                "{field}: {e}"
            );
        }
    }
}
