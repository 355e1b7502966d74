//! sensor_msgs/CompressedImage (feature `vision`): a JPEG or PNG camera frame, as a
//! TurtleBot3's camera publishes it on `.../compressed`, decoded (and encoded) by OpenCV.

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

/// `frame` as JPEG bytes of `quality` (1-100), as a camera driver compresses its frames.
pub fn encode_jpeg(frame: &BgrFrame, quality: i32) -> Result<Vec<u8>, String> {
    use opencv::prelude::*;
    let fail = |e: opencv::Error| format!("JPEG of a {}x{} frame: {e}", frame.width, frame.height);
    let rows = opencv::core::Mat::from_slice(&frame.data).map_err(fail)?;
    let image = rows.reshape(3, frame.height as i32).map_err(fail)?;
    let mut out = opencv::core::Vector::<u8>::new();
    let params = [
        opencv::imgcodecs::IMWRITE_JPEG_QUALITY,
        quality.clamp(1, 100),
    ];
    let params = opencv::core::Vector::from_slice(&params);
    opencv::imgcodecs::imencode(".jpg", &image, &mut out, &params).map_err(fail)?;
    Ok(out.to_vec())
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

    #[test]
    fn a_frame_survives_jpeg_within_a_few_levels() {
        // A 16x8 frame: left half a yellow, right half a grey.
        let data = (0..16 * 8)
            .flat_map(|i| {
                if i % 16 < 8 {
                    [30, 200, 220]
                } else {
                    [90, 90, 90]
                }
            })
            .collect();
        let frame = BgrFrame {
            width: 16,
            height: 8,
            data,
        };
        let jpeg = encode_jpeg(&frame, 95).unwrap();
        assert_eq!(&jpeg[..2], &[0xFF, 0xD8], "a JPEG's start-of-image marker");
        let CameraImage::Colour(back) = decode_compressed("jpeg", &jpeg).unwrap() else {
            panic!("a colour frame")
        };
        assert_eq!((back.width, back.height), (16, 8));
        for (x, want) in [(2, [30u8, 200, 220]), (13, [90, 90, 90])] {
            let got = back.at(x, 4);
            let off = (0..3).map(|k| got[k].abs_diff(want[k])).max().unwrap();
            assert!(off <= 12, "{got:?} for {want:?}");
        }
    }
}
