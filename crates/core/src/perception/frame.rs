//! A grey camera frame, as every camera source hands it to the detector, and the small
//! thumbnail the console draws of it.

pub use crate::data::{CameraStatus, Thumbnail};

/// An 8-bit grey image, rows top to bottom, `width * height` bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GrayFrame {
    pub width: usize,
    pub height: usize,
    pub data: Vec<u8>,
}

/// Why raw image bytes could not become a frame.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum FrameError {
    #[error("image encoding `{0}` is not supported: expected mono8, rgb8 or bgr8")]
    Encoding(String),
    #[error(
        "image {width}x{height} is not a picture navdeck reads: each side must be 1 to {MAX_SIDE} pixels"
    )]
    Sides { width: usize, height: usize },
    #[error("image {width}x{height} {encoding} with step {step} needs {needed} bytes, got {got}")]
    Size {
        width: usize,
        height: usize,
        encoding: String,
        step: usize,
        needed: usize,
        got: usize,
    },
}

/// The longest side of a camera image navdeck reads, pixels: a calibration's bound.
pub const MAX_SIDE: usize = super::intrinsics::MAX_SIDE as usize;

/// The channels of a sensor_msgs/Image's `encoding` (mono8 1, rgb8 and bgr8 3), once its
/// sides are within `MAX_SIDE` and `len` bytes hold `height` rows `step` apart.
pub fn check_raw(
    width: usize,
    height: usize,
    encoding: &str,
    step: usize,
    len: usize,
) -> Result<usize, FrameError> {
    let channels = match encoding {
        "mono8" => 1,
        "rgb8" | "bgr8" => 3,
        other => return Err(FrameError::Encoding(other.to_string())),
    };
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return Err(FrameError::Sides { width, height });
    }
    // A step past the bytes there are cannot be right: checked so it cannot overflow.
    let needed = step
        .checked_mul(height - 1)
        .and_then(|n| n.checked_add(width * channels))
        .unwrap_or(usize::MAX);
    if step < width * channels || len < needed {
        return Err(FrameError::Size {
            width,
            height,
            encoding: encoding.to_string(),
            step,
            needed,
            got: len,
        });
    }
    Ok(channels)
}

impl GrayFrame {
    /// A frame of one grey level.
    pub fn filled(width: usize, height: usize, level: u8) -> Self {
        Self {
            width,
            height,
            data: vec![level; width * height],
        }
    }

    /// The grey level at (`x`, `y`), pixel centres at whole numbers, interpolated
    /// bilinearly between the four nearest pixels; `None` outside the frame.
    #[inline]
    pub fn sample(&self, x: f64, y: f64) -> Option<f64> {
        // Both non-negative below, so truncation is the floor (and needs no libm call).
        if !(x >= 0.0 && y >= 0.0) {
            return None;
        }
        let (col, row) = (x as usize, y as usize);
        if col + 1 >= self.width || row + 1 >= self.height {
            return None;
        }
        let (fx, fy) = (x - col as f64, y - row as f64);
        let i = row * self.width + col;
        let at = |k: usize| f64::from(self.data[k]);
        let top = at(i) * (1.0 - fx) + at(i + 1) * fx;
        let bottom = at(i + self.width) * (1.0 - fx) + at(i + self.width + 1) * fx;
        Some(top * (1.0 - fy) + bottom * fy)
    }

    /// From sensor_msgs/Image fields: `encoding` mono8, rgb8 or bgr8, `step` bytes per row.
    pub fn from_raw(
        width: usize,
        height: usize,
        encoding: &str,
        step: usize,
        bytes: &[u8],
    ) -> Result<Self, FrameError> {
        let channels = check_raw(width, height, encoding, step, bytes.len())?;
        let (r, b) = if encoding == "rgb8" { (0, 2) } else { (2, 0) };
        let mut data = Vec::with_capacity(width * height);
        for row in bytes.chunks(step).take(height) {
            let row = &row[..width * channels];
            if channels == 1 {
                data.extend_from_slice(row);
            } else {
                // ITU-R BT.601 luma, as OpenCV's cvtColor: Y = 0.299 R + 0.587 G + 0.114 B.
                data.extend(row.chunks_exact(3).map(|p| {
                    let y = 299 * u32::from(p[r]) + 587 * u32::from(p[1]) + 114 * u32::from(p[b]);
                    ((y + 500) / 1000) as u8
                }));
            }
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// Grey level at (x, y); 0 outside the frame.
    pub fn at(&self, x: usize, y: usize) -> u8 {
        if x < self.width && y < self.height {
            self.data[y * self.width + x]
        } else {
            0
        }
    }

    /// The frame shrunk to `width` x `height` by averaging boxes of pixels.
    pub fn thumbnail(&self, width: usize, height: usize) -> Thumbnail {
        let (w, h) = (width.max(1), height.max(1));
        let mut pixels = Vec::with_capacity(w * h);
        for ty in 0..h {
            let (y0, y1) = (
                ty * self.height / h,
                ((ty + 1) * self.height / h).max(ty * self.height / h + 1),
            );
            for tx in 0..w {
                let (x0, x1) = (
                    tx * self.width / w,
                    ((tx + 1) * self.width / w).max(tx * self.width / w + 1),
                );
                let (mut sum, mut n) = (0u32, 0u32);
                for y in y0..y1.min(self.height) {
                    for x in x0..x1.min(self.width) {
                        sum += u32::from(self.data[y * self.width + x]);
                        n += 1;
                    }
                }
                pixels.push(sum.checked_div(n).unwrap_or(0) as u8);
            }
        }
        Thumbnail {
            width: w,
            height: h,
            pixels,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_bytes_become_grey_with_bt601_weights() {
        // One row of two pixels, padded to a step of 8 bytes.
        let rgb = [255, 0, 0, 0, 0, 255, 9, 9];
        let f = GrayFrame::from_raw(2, 1, "rgb8", 8, &rgb).unwrap();
        assert_eq!(f.data, vec![76, 29]);
        let f = GrayFrame::from_raw(2, 1, "bgr8", 8, &rgb).unwrap();
        assert_eq!(f.data, vec![29, 76]);
        let f = GrayFrame::from_raw(2, 2, "mono8", 3, &[1, 2, 0, 3, 4]).unwrap();
        assert_eq!(f.data, vec![1, 2, 3, 4]);
    }

    #[test]
    fn short_buffers_and_unknown_encodings_are_named() {
        let e = GrayFrame::from_raw(4, 2, "mono8", 4, &[0; 7]).unwrap_err();
        assert!(e.to_string().contains("needs 8 bytes, got 7"), "{e}");
        let e = GrayFrame::from_raw(1, 1, "yuv422", 2, &[0; 2]).unwrap_err();
        assert!(e.to_string().contains("yuv422"), "{e}");
    }

    #[test]
    fn empty_huge_and_overflowing_images_are_refused_not_a_panic() {
        for (w, h, step) in [
            (0, 1, 0),
            (1, 0, 1),
            (20_000, 1, 20_000),
            (1, 2, usize::MAX),
        ] {
            let e = GrayFrame::from_raw(w, h, "mono8", step, &[0; 4]).unwrap_err();
            assert!(e.to_string().contains(&format!("{w}x{h}")), "{e}");
        }
        let e = GrayFrame::from_raw(4_000_000_000, 4_000_000_000, "rgb8", 12_000_000_000, &[])
            .unwrap_err();
        assert!(e.to_string().contains("16384"), "{e}");
    }

    #[test]
    fn thumbnail_averages_boxes() {
        let mut f = GrayFrame::filled(4, 2, 0);
        f.data[0..2].copy_from_slice(&[200, 100]);
        let t = f.thumbnail(2, 1);
        assert_eq!(t.pixels, vec![75, 0]);
    }
}
