//! A colour camera frame, BGR bytes as OpenCV keeps them, and the small colour thumbnail
//! the console's lane panel draws of it.

use super::frame::FrameError;
use crate::data::ColourThumbnail;

/// An 8-bit BGR image, rows top to bottom, `3 * width * height` bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BgrFrame {
    pub width: usize,
    pub height: usize,
    pub data: Vec<u8>,
}

impl BgrFrame {
    /// A frame of one colour, `bgr`.
    pub fn filled(width: usize, height: usize, bgr: [u8; 3]) -> Self {
        let data = bgr
            .iter()
            .copied()
            .cycle()
            .take(3 * width * height)
            .collect();
        Self {
            width,
            height,
            data,
        }
    }

    /// The BGR colour at (`x`, `y`); black outside the frame.
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        if x < self.width && y < self.height {
            let i = 3 * (y * self.width + x);
            [self.data[i], self.data[i + 1], self.data[i + 2]]
        } else {
            [0; 3]
        }
    }

    /// From sensor_msgs/Image fields: `encoding` rgb8, bgr8 or mono8, `step` bytes per row.
    pub fn from_raw(
        width: usize,
        height: usize,
        encoding: &str,
        step: usize,
        bytes: &[u8],
    ) -> Result<Self, FrameError> {
        let channels = super::frame::check_raw(width, height, encoding, step, bytes.len())?;
        let mut data = Vec::with_capacity(3 * width * height);
        for row in bytes.chunks(step).take(height) {
            let row = &row[..width * channels];
            match encoding {
                "mono8" => data.extend(row.iter().flat_map(|&g| [g, g, g])),
                "bgr8" => data.extend_from_slice(row),
                _ => data.extend(row.chunks_exact(3).flat_map(|p| [p[2], p[1], p[0]])),
            }
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// The frame shrunk to `width` x `height` by averaging boxes of pixels, as RGB.
    pub fn thumbnail(&self, width: usize, height: usize) -> ColourThumbnail {
        let (w, h) = (width.max(1), height.max(1));
        let mut rgb = Vec::with_capacity(3 * w * h);
        for ty in 0..h {
            let y0 = ty * self.height / h;
            let y1 = ((ty + 1) * self.height / h).max(y0 + 1).min(self.height);
            for tx in 0..w {
                let x0 = tx * self.width / w;
                let x1 = ((tx + 1) * self.width / w).max(x0 + 1).min(self.width);
                let mut sum = [0u32; 3];
                for y in y0..y1 {
                    let row = (self.data)
                        .get(3 * (y * self.width + x0)..3 * (y * self.width + x1))
                        .unwrap_or_default();
                    for p in row.chunks_exact(3) {
                        for c in 0..3 {
                            sum[c] += u32::from(p[c]);
                        }
                    }
                }
                let n = ((y1 - y0) * (x1 - x0)).max(1) as u32;
                rgb.extend([sum[2] / n, sum[1] / n, sum[0] / n].map(|v| v as u8));
            }
        }
        ColourThumbnail {
            width: w,
            height: h,
            rgb,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgb_bytes_are_kept_as_bgr_and_thumbnails_are_rgb() {
        let f = BgrFrame::from_raw(2, 1, "rgb8", 8, &[255, 0, 0, 0, 0, 255, 9, 9]).unwrap();
        assert_eq!(f.at(0, 0), [0, 0, 255]);
        assert_eq!(f.at(1, 0), [255, 0, 0]);
        let t = f.thumbnail(1, 1);
        assert_eq!(t.at(0, 0), [127, 0, 127]);
        let e = BgrFrame::from_raw(4, 2, "rgb8", 12, &[0; 7]).unwrap_err();
        assert!(e.to_string().contains("got 7"), "{e}");
    }
}

/// A frame as a camera source hands it over: grey (mono8) or colour.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CameraImage {
    Gray(super::frame::GrayFrame),
    Colour(BgrFrame),
}

impl From<super::frame::GrayFrame> for CameraImage {
    fn from(f: super::frame::GrayFrame) -> Self {
        Self::Gray(f)
    }
}

impl From<BgrFrame> for CameraImage {
    fn from(f: BgrFrame) -> Self {
        Self::Colour(f)
    }
}

impl CameraImage {
    /// The grey frame the marker detector reads (ITU-R BT.601 luma of a colour one).
    pub fn into_gray(self) -> super::frame::GrayFrame {
        match self {
            Self::Gray(g) => g,
            Self::Colour(c) => c.to_gray(),
        }
    }

    /// The colour frame the lane pipeline reads (a grey one has three equal channels).
    pub fn to_colour(&self) -> BgrFrame {
        match self {
            Self::Gray(g) => BgrFrame {
                width: g.width,
                height: g.height,
                data: g.data.iter().flat_map(|&v| [v, v, v]).collect(),
            },
            Self::Colour(c) => c.clone(),
        }
    }
}

impl BgrFrame {
    /// The frame in grey: ITU-R BT.601 luma, as OpenCV's cvtColor.
    pub fn to_gray(&self) -> super::frame::GrayFrame {
        let data = (self.data.chunks_exact(3))
            .map(|p| {
                let y = 114 * u32::from(p[0]) + 587 * u32::from(p[1]) + 299 * u32::from(p[2]);
                ((y + 500) / 1000) as u8
            })
            .collect();
        super::frame::GrayFrame {
            width: self.width,
            height: self.height,
            data,
        }
    }
}
