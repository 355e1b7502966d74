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

    /// The frame shrunk to `width` x `height` as RGB, each thumbnail pixel the mean of
    /// its box of pixels, sampled on a grid of at most `SAMPLES` x `SAMPLES`.
    pub fn thumbnail(&self, width: usize, height: usize) -> ColourThumbnail {
        /// Pixels sampled along each side of a box.
        const SAMPLES: usize = 6;
        let (w, h) = (width.max(1), height.max(1));
        let mut rgb = Vec::with_capacity(3 * w * h);
        let span = |t: usize, n: usize, size: usize| {
            let a = t * size / n;
            let b = ((t + 1) * size / n).max(a + 1).min(size);
            (a..b).step_by((b - a).div_ceil(SAMPLES).max(1))
        };
        // The columns sampled, each with its thumbnail column.
        let columns: Vec<(usize, usize)> = (0..w)
            .flat_map(|tx| span(tx, w, self.width).map(move |x| (tx, x)))
            .collect();
        let mut sums = vec![[0u32; 4]; w];
        for ty in 0..h {
            sums.fill([0; 4]);
            for y in span(ty, h, self.height) {
                let Some(row) = self.data.get(3 * y * self.width..3 * (y + 1) * self.width) else {
                    continue;
                };
                for &(tx, x) in &columns {
                    let sum = &mut sums[tx];
                    for c in 0..3 {
                        sum[c] += u32::from(row[3 * x + c]);
                    }
                    sum[3] += 1;
                }
            }
            for [b, g, r, n] in &sums {
                let n = (*n).max(1);
                rgb.extend([r / n, g / n, b / n].map(|v| v as u8));
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
