//! Camera calibration files (feature `vision`).

use super::Case;
#[cfg(feature = "vision")]
use super::case;

#[cfg(feature = "vision")]
pub fn cases() -> Vec<Case> {
    let calib = |fx: &str, cx: &str, width: &str, dist: &str| {
        format!(
            "%YAML:1.0\n---\nimage_width: {width}\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ {fx}, 0., {cx}, 0., 600., 240., 0., 0., 1. ]\ndistortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n   data: [ {dist}, 0., 0., 0., 0. ]\n"
        )
    };
    let args = [
        "--sim-camera",
        "--config",
        "c.toml",
        "--headless",
        "--keys",
        "w",
    ];
    let config = "[vision]\ncalibration = \"cam.yml\"\n";
    let with = |names: &str, body: String| {
        case("calibration", &args, names)
            .file("c.toml", config)
            .file("cam.yml", body)
    };
    vec![
        with("cx", calib("600.", ".nan", "640", "0.")),
        with("cx", calib("600.", "1e308", "640", "0.")),
        with("fx", calib("-600.", "320.", "640", "0.")),
        with("fx", calib("1e308", "320.", "640", "0.")),
        with("distortion", calib("600.", "320.", "640", ".nan")),
        with("image_width", calib("600.", "320.", "wide", "0.")),
        with("image_width", calib("600.", "320.", "2000000000", "0.")),
        // Found by fuzzing: OpenCV 4.6's FileStorage parser never returns on this file.
        with(
            "did not finish",
            include_str!("../hostile_inputs/calibration_parser_loop.yml").to_string(),
        ),
        case("calibration", &args, "/dev/zero")
            .file("c.toml", "[vision]\ncalibration = \"/dev/zero\"\n"),
    ]
}

#[cfg(not(feature = "vision"))]
pub fn cases() -> Vec<Case> {
    Vec::new()
}
