//! sensor_msgs/CompressedImage (feature `vision`): a JPEG or PNG camera frame, as a
//! TurtleBot3's camera publishes it on `.../compressed`, decoded by OpenCV.

use super::colour::{BgrFrame, CameraImage};

/// A sensor_msgs/CompressedImage's bytes decoded as colour (OpenCV's imdecode reads JPEG
/// and PNG); `format` names the encoding in errors ("jpeg", "rgb8; jpeg compressed bgr8").
pub fn decode_compressed(format: &str, bytes: &[u8]) -> Result<CameraImage, String> {
    use opencv::prelude::*;
    let fail = |e: opencv::Error| format!("compressed image ({format}): {e}");
    if bytes.is_empty() {
        return Err(format!("compressed image ({format}): no bytes"));
    }
    let buffer = opencv::core::Vector::<u8>::from_slice(bytes);
    let mat =
        opencv::imgcodecs::imdecode(&buffer, opencv::imgcodecs::IMREAD_COLOR).map_err(fail)?;
    if mat.empty() || mat.channels() != 3 {
        return Err(format!(
            "compressed image ({format}): not a picture OpenCV reads"
        ));
    }
    let (w, h) = (mat.cols() as usize, mat.rows() as usize);
    let max = super::frame::MAX_SIDE;
    if w > max || h > max {
        return Err(format!(
            "compressed image ({format}): {w}x{h} is over {max} pixels a side"
        ));
    }
    let data = mat.data_bytes().map_err(fail)?.to_vec();
    Ok(CameraImage::Colour(BgrFrame {
        width: w,
        height: h,
        data,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_png_decodes_to_its_colours_and_garbage_is_named() {
        use opencv::prelude::*;
        // A 2x1 picture: a red pixel then a green one, written as PNG by OpenCV.
        let bgr = [0u8, 0, 255, 0, 255, 0];
        let mat = opencv::core::Mat::new_rows_cols_with_data(1, 6, &bgr).unwrap();
        let mat = mat.reshape(3, 1).unwrap();
        let mut png = opencv::core::Vector::<u8>::new();
        opencv::imgcodecs::imencode_def(".png", &mat, &mut png).unwrap();
        let CameraImage::Colour(f) = decode_compressed("png", png.as_slice()).unwrap() else {
            panic!("a colour frame")
        };
        assert_eq!((f.width, f.height), (2, 1));
        assert_eq!((f.at(0, 0), f.at(1, 0)), ([0, 0, 255], [0, 255, 0]));
        let e = decode_compressed("jpeg", &[1, 2, 3]).unwrap_err();
        assert!(e.contains("jpeg"), "{e}");
    }
}
