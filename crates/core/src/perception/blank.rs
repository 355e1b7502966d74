//! A blank frame: a covered or dark camera still sends frames, evenly black (or, blinded,
//! evenly white). Read as a camera frame, it would say "no marker in view" where the truth
//! is "nothing seen"; the pipeline reports it as a failed frame instead, and sensor health
//! counts the camera lost while it lasts (seed 000 §6.4.2, "Camera temporary blockage").
//! An evenly lit plain wall is a frame: it shows that no marker is there.

use super::frame::GrayFrame;

/// A frame whose grey levels spread less than this (standard deviation, of 255) is even.
pub const BLANK_SPREAD: f64 = 3.0;
/// An even frame this dark (mean grey, of 255) is a covered or unlit camera...
pub const DARK_MEAN: f64 = 16.0;
/// ...and one this bright a blinded or saturated one.
pub const GLARE_MEAN: f64 = 250.0;
/// Pixels sampled across the frame, at most.
const SAMPLES: usize = 4096;

/// Why `frame` shows nothing, when it is blank: its mean and spread.
pub fn blank_reason(frame: &GrayFrame) -> Option<String> {
    let n = frame.data.len();
    if n == 0 {
        return Some("frame empty".into());
    }
    let step = (n / SAMPLES).max(1);
    let (mut count, mut sum, mut squares) = (0.0, 0.0, 0.0);
    for &v in frame.data.iter().step_by(step) {
        let v = f64::from(v);
        count += 1.0;
        sum += v;
        squares += v * v;
    }
    let mean = sum / count;
    // Variance as E[v²] - E[v]², clamped against rounding below zero.
    let spread = (squares / count - mean * mean).max(0.0).sqrt();
    let even_extreme = !(DARK_MEAN..=GLARE_MEAN).contains(&mean);
    (spread < BLANK_SPREAD && even_extreme).then(|| {
        format!(
            "frame blank (mean grey {mean:.0}, spread {spread:.1}): camera covered, dark or blinded"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_even_frame_is_blank_and_a_scene_is_not() {
        for level in [0, 12, 255] {
            let dark = GrayFrame::filled(640, 480, level);
            assert!(blank_reason(&dark).is_some_and(|r| r.contains("camera covered")));
        }
        // A plain wall, evenly lit, shows that no marker is there.
        assert_eq!(blank_reason(&GrayFrame::filled(640, 480, 128)), None);
        // A lit wall with a marker: half the pixels dark, half light.
        let mut scene = GrayFrame::filled(640, 480, 200);
        for (i, v) in scene.data.iter_mut().enumerate() {
            if (i / 640) % 40 < 20 {
                *v = 30;
            }
        }
        assert_eq!(blank_reason(&scene), None);
        // A dim but textured frame is a frame.
        let mut dim = GrayFrame::filled(64, 48, 4);
        for (i, v) in dim.data.iter_mut().enumerate() {
            *v = 4 + (i * 7 % 13) as u8;
        }
        assert_eq!(blank_reason(&dim), None);
    }
}
