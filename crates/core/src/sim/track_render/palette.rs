//! The colours the lane camera sees, given in OpenCV's HSV scale (H 0-179, S and V
//! 0-255) so that each can be checked against the seed's thresholds, and turned into BGR.

/// A colour as OpenCV's `cvtColor(BGR2HSV)` reports it: hue 0-179 (degrees / 2),
/// saturation and value 0-255.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hsv {
    pub h: f64,
    pub s: f64,
    pub v: f64,
}

const fn hsv(h: f64, s: f64, v: f64) -> Hsv {
    Hsv { h, s, v }
}

/// The floor: a matte light-grey linoleum, slightly warm, of low saturation.
pub const FLOOR: Hsv = hsv(15.0, 18.0, 105.0);
/// The room beyond the floor's horizon, where no wall stands.
pub const ROOM: Hsv = hsv(15.0, 25.0, 120.0);
/// Yellow tape: seed 000 §2.1.2's base_hue = 25; V 180 is §2.1.3's lanes (V 180 +- 25).
pub const YELLOW_TAPE: Hsv = hsv(25.0, 200.0, 180.0);
/// White tape: V 183 stays under §2.1.3's glare threshold 230 at bright (x1.2) with noise.
pub const WHITE_TAPE: Hsv = hsv(20.0, 15.0, 183.0);
/// The world's walls: light grey.
pub const WALL: Hsv = hsv(20.0, 12.0, 170.0);
/// Box obstacles: brown cardboard.
pub const BOX: Hsv = hsv(12.0, 150.0, 115.0);
/// A traffic light's post.
pub const LIGHT_POST: Hsv = hsv(0.0, 0.0, 60.0);
/// A traffic light's housing.
pub const HOUSING: Hsv = hsv(0.0, 0.0, 38.0);
/// A barrier's post.
pub const BARRIER_POST: Hsv = hsv(0.0, 0.0, 125.0);
/// The red stripes of a barrier's arm: well saturated.
pub const ARM_RED: Hsv = hsv(178.0, 215.0, 175.0);
/// The white stripes of a barrier's arm, as bright as white tape.
pub const ARM_WHITE: Hsv = hsv(20.0, 12.0, 183.0);

/// Hue of a lit red lamp: seed 000 §3.1.1's red peaks are 10 and 170 (sigma 8).
pub const LAMP_RED_HUE: f64 = 2.0;
/// Hue of a lit yellow (amber) lamp: near the yellow tape's 25.
pub const LAMP_YELLOW_HUE: f64 = 28.0;
/// Hue of a lit green lamp: seed 000 §3.1.1's mu_g = 65 (sigma 12).
pub const LAMP_GREEN_HUE: f64 = 65.0;
/// A lit lamp's rim: bright and saturated.
pub const LAMP_RIM_SV: (f64, f64) = (235.0, 230.0);
/// A lit lamp's centre: brighter, still saturated.
pub const LAMP_CORE_SV: (f64, f64) = (205.0, 255.0);
/// An unlit lamp: dull tinted glass.
pub const LAMP_OFF_SV: (f64, f64) = (50.0, 55.0);

/// The BGR bytes of `c` (the hexcone model, Smith 1978, as OpenCV's `cvtColor` documents
/// it: C = V S, X = C (1 - |H' mod 2 - 1|), m = V - C).
pub fn bgr(c: Hsv) -> [f64; 3] {
    let v = c.v.clamp(0.0, 255.0);
    let chroma = v * (c.s / 255.0).clamp(0.0, 1.0);
    let sector = (c.h * 2.0).rem_euclid(360.0) / 60.0;
    let x = chroma * (1.0 - (sector % 2.0 - 1.0).abs());
    let m = v - chroma;
    let (r, g, b) = match sector as u32 {
        0 => (chroma, x, 0.0),
        1 => (x, chroma, 0.0),
        2 => (0.0, chroma, x),
        3 => (0.0, x, chroma),
        4 => (x, 0.0, chroma),
        _ => (chroma, 0.0, x),
    };
    [b + m, g + m, r + m]
}

/// `bgr` scaled by `factor` and rounded to bytes.
pub fn bytes(c: [f64; 3], factor: f64) -> [u8; 3] {
    c.map(|v| (v * factor).round().clamp(0.0, 255.0) as u8)
}
