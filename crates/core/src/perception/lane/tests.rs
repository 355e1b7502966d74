//! The lane pipeline on synthetic frames: what a driver would notice of it.

use super::test_frames::*;
use super::{LanePipeline, LaneVisionConfig};
use crate::clock::Clock;
use crate::data::{BarrierState, LightColour, LightSeen};
use crate::perception::colour::BgrFrame;
use crate::perception::lane_camera::LaneCameraConfig;
use crate::sim::track::lamp_height;
use nalgebra::Vector3;
use opencv::imgproc;
use std::sync::Mutex;

fn pipeline() -> LanePipeline {
    LanePipeline::new(&LaneVisionConfig::default(), &LaneCameraConfig::default()).unwrap()
}

/// The sighting after `n` frames of the same picture.
fn settled(p: &mut LanePipeline, frame: &BgrFrame, n: usize) -> crate::data::LaneSighting {
    for _ in 1..n {
        p.read(frame, None);
    }
    p.read(frame, None)
}

#[test]
fn a_lane_five_centimetres_left_or_right_reads_as_fifty_millimetres_of_error() {
    for (offset, want) in [(0.05, -50.0), (-0.05, 50.0), (0.0, 0.0)] {
        let mut p = pipeline();
        let s = settled(&mut p, &straight_lane(offset), 3);
        let e = s.error_px.unwrap();
        assert!(
            (e - want).abs() < 4.0,
            "lane {offset} m left: error {e} mm, {s:?}"
        );
        assert!(s.yellow.is_some() && s.white.is_some());
        assert!(s.curvature.unwrap().abs() < 0.2, "{:?}", s.curvature);
    }
}

#[test]
fn a_bend_to_the_left_has_positive_curvature_and_to_the_right_negative() {
    for radius in [1.5, -1.5] {
        let mut p = pipeline();
        let s = settled(&mut p, &curved_lane(radius), 3);
        let k = s.curvature.unwrap();
        // 1 / 1.5 m within a quarter: a parabola through arcs of 1.3 and 1.7 m, 0.7 m
        // long, bends more than their mean.
        assert!(
            (k * radius - 1.0).abs() < 0.25,
            "radius {radius}: curvature {k}"
        );
        // The robot sits on the lane's centre, tangent to it: 0.35 m ahead the centre has
        // bent R - sqrt(R^2 - 0.35^2) = 41 mm towards the bend.
        let e = s.error_px.unwrap();
        assert!(
            (e + 41.0 * radius.signum()).abs() < 10.0,
            "radius {radius}: error {e}"
        );
    }
}

#[test]
fn with_one_line_missing_the_other_gives_the_centre() {
    for (yellow, white) in [(true, false), (false, true)] {
        let frame = floor(|_, y| lines(yellow.then_some(0.25), white.then_some(-0.15), y));
        let mut p = pipeline();
        let s = settled(&mut p, &frame, 3);
        // Lines 0.25 left and 0.15 right: the centre is 5 cm left, an error of -50 mm.
        let e = s.error_px.unwrap();
        assert!((e + 50.0).abs() < 5.0, "yellow {yellow} white {white}: {e}");
        assert_eq!((s.yellow.is_some(), s.white.is_some()), (yellow, white));
    }
}

/// A floor with a glare spot on it: V 250 unsaturated, a soft rim of 5 px to the floor.
fn glare(frame: &BgrFrame, at: (f64, f64), radius: f64) -> BgrFrame {
    let mut out = frame.clone();
    for v in 0..frame.height {
        for u in 0..frame.width {
            let d = (u as f64 - at.0).hypot(v as f64 - at.1) - radius;
            if d < 5.0 {
                let t = (d / 5.0).clamp(0.0, 1.0);
                let level = (250.0 * (1.0 - t) + 40.0 * t) as u8;
                let i = 3 * (v * frame.width + u);
                out.data[i..i + 3].copy_from_slice(&[level, level, level.saturating_sub(4)]);
            }
        }
    }
    out
}

#[test]
fn a_glare_spot_is_not_taken_for_a_lane_line() {
    // On a bare floor: nothing.
    let bare = glare(&floor(|_, _| FLOOR), (420.0, 330.0), 50.0);
    let mut p = pipeline();
    let s = settled(&mut p, &bare, 10);
    assert_eq!((s.white, s.error_px), (None, None), "{s:?}");
    // Without growing the glare mask its rim passes for white paint.
    let cfg = LaneVisionConfig {
        glare_grow_cells: 0,
        ..LaneVisionConfig::default()
    };
    let mut unguarded = LanePipeline::new(&cfg, &LaneCameraConfig::default()).unwrap();
    assert!(settled(&mut unguarded, &bare, 10).white.is_some());
    // Beside the lines: the centre stays where it is.
    let lane = glare(&straight_lane(0.0), (400.0, 330.0), 40.0);
    let s = settled(&mut pipeline(), &lane, 5);
    assert!(s.error_px.unwrap().abs() < 5.0, "{s:?}");
}

/// The straight lane on a floor of faint pale stripes 2 cm wide every 6 cm, 30 levels above
/// the floor.
fn hatched() -> BgrFrame {
    floor(|x, y| match lines(Some(0.2), Some(-0.2), y) {
        FLOOR if (x / 0.06).fract() < 0.33 => [70, 70, 70],
        c => c,
    })
}

#[test]
fn the_brightness_floor_rises_through_faint_stripes_until_only_the_lines_pass() {
    // The stripes are narrow enough to stand out, and far over the band's 5 % at the
    // starting floor of 50.
    let hatched = hatched();
    let mut p = pipeline();
    let before = p.read(&hatched, None).pixel_ratio;
    assert!(before > 0.1, "{before}");
    let s = settled(&mut p, &hatched, 15);
    assert!(p.value_floor() > 70.0, "{}", p.value_floor());
    assert!(s.pixel_ratio <= 0.06, "{before} -> {}", s.pixel_ratio);
    assert!(s.error_px.unwrap().abs() < 5.0, "{s:?}");
}

#[test]
fn a_lane_gone_dark_under_a_shadow_is_found_again_by_a_robot_standing_before_it() {
    // The floor learnt over faint stripes in the light is above the tape once a shadow
    // falls over the whole view at 0.3 of the light: the paint vanishes, then a line comes
    // back as the floor sinks, with nothing moving.
    let hatched = hatched();
    let mut p = pipeline();
    settled(&mut p, &hatched, 15);
    let learnt = p.value_floor();
    let dark = floor(|_, y| lines(Some(0.2), Some(-0.2), y).map(|v| (f64::from(v) * 0.3) as u8));
    let first = p.read(&dark, None);
    assert_eq!(first.pixel_ratio, 0.0, "{learnt}");
    let s = settled(&mut p, &dark, 40);
    assert!(s.pixel_ratio > 0.01, "{}", s.pixel_ratio);
    assert!(p.value_floor() < learnt, "{} vs {learnt}", p.value_floor());
    // One line is enough to drive on; the floor sinks no further once one is found.
    assert!(s.yellow.is_some() || s.white.is_some(), "{s:?}");
    assert!(s.error_px.unwrap().abs() < 8.0, "{s:?}");
}

#[test]
fn bright_floor_wider_than_paint_is_never_a_line_however_bright() {
    // Pale yellow and pale grey floor beyond the lines, brightening from 100 to 200 away
    // from them: brighter than the lines, but no stripe.
    let loud = floor(|_, y| match lines(Some(0.2), Some(-0.2), y) {
        FLOOR if y.abs() > 0.25 => {
            let v = (100.0 + 200.0 * (y.abs() - 0.25)).min(200.0);
            if y > 0.0 {
                [(0.4 * v) as u8, (0.9 * v) as u8, v as u8]
            } else {
                [v as u8; 3]
            }
        }
        c => c,
    });
    let mut p = pipeline();
    let s = settled(&mut p, &loud, 10);
    assert!(s.error_px.unwrap().abs() < 5.0, "{s:?}");
    // No more paint than the two lines alone show.
    let plain = settled(&mut pipeline(), &straight_lane(0.0), 10).pixel_ratio;
    assert!(
        (s.pixel_ratio - plain).abs() < 0.002,
        "{} vs {plain}",
        s.pixel_ratio
    );
}

#[test]
fn a_hard_shadow_over_most_of_the_floor_leaves_the_lines_readable() {
    // Everything nearer than 0.6 m and left of 0.1 m at under half the light, tape too.
    let shade = |c: [u8; 3]| c.map(|v| (f64::from(v) * 0.45) as u8);
    let shadowed = floor(|x, y| {
        let c = lines(Some(0.2), Some(-0.2), y);
        if x < 0.6 || y > 0.1 { shade(c) } else { c }
    });
    let s = settled(&mut pipeline(), &shadowed, 10);
    assert!(s.yellow.is_some() && s.white.is_some(), "{s:?}");
    assert!(s.error_px.unwrap().abs() < 8.0, "{s:?}");
}

/// A lamp 0.8 m ahead, 0.3 m right, at the lamp height.
const LAMP: Vector3<f64> = Vector3::new(0.8, -0.3, 0.22);

/// The light read from a lamp of `bgr` at `(x, y)` ahead, at the height of `colour`'s lamp
/// (red on top), checked to be `colour` at its range within `share` of it.
fn lamp_read((x, y): (f64, f64), bgr: [u8; 3], colour: LightColour, share: f64) -> LightSeen {
    let at = Vector3::new(x, y, lamp_height(colour));
    let range = eye().mount().to_camera(at).norm();
    let frame = lamp(&straight_lane(0.0), at, 0.025, bgr, false);
    let seen = pipeline().detect_objects(&frame).light.unwrap();
    assert_eq!(seen.colour, colour);
    assert!(
        (seen.range - range).abs() < share * range,
        "{} vs {range}",
        seen.range
    );
    let lens = eye().mount().to_robot(Vector3::zeros());
    let (ahead, left) = (x - lens.x, y - lens.y);
    assert!(
        (seen.ahead - ahead).abs() < share * range && (seen.left - left).abs() < share * range,
        "{seen:?} vs {ahead} ahead, {left} left"
    );
    seen
}

#[test]
fn lit_lamps_are_read_as_red_yellow_and_green_at_their_range() {
    for (bgr, colour) in [
        ([40, 40, 235], LightColour::Red),
        ([0, 200, 240], LightColour::Yellow),
        ([90, 230, 40], LightColour::Green),
    ] {
        let seen = lamp_read((LAMP.x, LAMP.y), bgr, colour, 0.1);
        // The winning class of four, yellow's prior the smallest (colour_bayes::PRIORS).
        assert!(seen.confidence > 0.5, "{seen:?}");
    }
}

#[test]
fn a_lamp_cut_by_the_pictures_edge_is_still_read_and_ranged() {
    let eye = eye();
    // Beside the lane in a bend: the lamp's centre a few pixels inside the right edge.
    let right = |y: f64| Vector3::new(0.8, y, LAMP.z);
    let beside = (300..800)
        .map(|mm| right(-f64::from(mm) / 1000.0))
        .find(|&p| eye.pixel_of(p).unwrap().0 >= 632.0)
        .unwrap();
    for (bgr, colour) in [
        ([40, 40, 235], LightColour::Red),
        ([90, 230, 40], LightColour::Green),
    ] {
        lamp_read((beside.x, beside.y), bgr, colour, 0.15);
    }
    // A square cut by the edge is still no lamp.
    let frame = lamp(&straight_lane(0.0), beside, 0.025, [40, 40, 235], true);
    assert_eq!(pipeline().detect_objects(&frame).light, None);
}

#[test]
fn a_lamp_seen_45_degrees_off_its_axis_is_still_a_lamp() {
    use opencv::core::{Point, Size};
    // From the side of a bend: the disc drawn out to an upright ellipse, 1 : 0.7, with the
    // pixel a polygon's vertex leaves on top of it.
    let eye = eye();
    let at = Vector3::new(0.8, -0.3, lamp_height(LightColour::Green));
    let (u, v) = eye.pixel_of(at).unwrap();
    let r = eye.intrinsics().fx * 0.025 / eye.mount().to_camera(at).z;
    let frame = drawn(&straight_lane(0.0), |m| {
        let centre = Point::new(u.round() as i32, v.round() as i32);
        let axes = Size::new((0.7 * r).round() as i32, r.round() as i32);
        let green = opencv::core::Scalar::new(90.0, 230.0, 40.0, 0.0);
        imgproc::ellipse(
            m,
            centre,
            axes,
            0.0,
            0.0,
            360.0,
            green,
            -1,
            imgproc::LINE_8,
            0,
        )
        .unwrap();
        let top = Point::new(centre.x, centre.y - axes.height);
        let tip = Point::new(centre.x, top.y - 2);
        imgproc::line(m, top, tip, green, 1, imgproc::LINE_8, 0).unwrap();
    });
    let seen = pipeline().detect_objects(&frame).light;
    assert_eq!(seen.map(|l| l.colour), Some(LightColour::Green), "{seen:?}");
}

#[test]
fn a_round_red_end_between_white_stripes_is_no_lamp() {
    use opencv::core::{Point, Rect, Scalar};
    // Where a lamp would hang, against the room's pale wall, a raised arm's rounded red end
    // under a white stripe.
    let eye = eye();
    let (u, v) = eye.pixel_of(LAMP).unwrap();
    let r = (eye.intrinsics().fx * 0.025 / eye.mount().to_camera(LAMP).z).round() as i32;
    let (u, v) = (u.round() as i32, v.round() as i32);
    let frame = drawn(&straight_lane(0.0), |m| {
        let wall = Rect::new(u - 5 * r, v - 8 * r, 10 * r, 10 * r);
        let pale = Scalar::new(190.0, 195.0, 200.0, 0.0);
        imgproc::rectangle(m, wall, pale, imgproc::FILLED, imgproc::LINE_8, 0).unwrap();
        let white = Scalar::new(215.0, 215.0, 215.0, 0.0);
        let stripe = Rect::new(u - r, v - 6 * r, 2 * r, 6 * r);
        imgproc::rectangle(m, stripe, white, imgproc::FILLED, imgproc::LINE_8, 0).unwrap();
        let red = Scalar::new(40.0, 40.0, 235.0, 0.0);
        imgproc::circle(
            m,
            Point::new(u, v),
            r,
            red,
            imgproc::FILLED,
            imgproc::LINE_8,
            0,
        )
        .unwrap();
    });
    assert_eq!(pipeline().detect_objects(&frame).light, None);
}

#[test]
fn of_two_lights_in_view_the_nearer_is_read() {
    // This stretch's light turned yellow 0.9 m off; the next one shows red 2.1 m off.
    let near = Vector3::new(0.8, -0.35, lamp_height(LightColour::Yellow));
    let far = Vector3::new(2.0, 0.4, lamp_height(LightColour::Red));
    let frame = lamp(&straight_lane(0.0), far, 0.025, [40, 40, 235], false);
    let frame = lamp(&frame, near, 0.025, [0, 200, 240], false);
    let seen = pipeline().detect_objects(&frame).light.unwrap();
    assert_eq!(seen.colour, LightColour::Yellow, "{seen:?}");
    assert!(
        (seen.range - eye().mount().to_camera(near).norm()).abs() < 0.1,
        "{seen:?}"
    );
}

#[test]
fn a_red_disc_lower_than_the_lamps_hang_is_no_lamp() {
    // Round and red, but at a barrier arm's height: below the horizon, where no lamp is.
    let low = Vector3::new(LAMP.x, LAMP.y, 0.1);
    let frame = lamp(&straight_lane(0.0), low, 0.025, [40, 40, 235], false);
    assert_eq!(pipeline().detect_objects(&frame).light, None);
}

#[test]
fn a_red_square_is_not_a_lamp() {
    let frame = lamp(&straight_lane(0.0), LAMP, 0.025, [40, 40, 235], true);
    assert_eq!(pipeline().detect_objects(&frame).light, None);
}

#[test]
fn a_red_box_on_the_floor_is_no_barrier_arm() {
    let box_face = Vector3::new(0.6, 0.0, 0.07);
    let frame = lamp(&straight_lane(0.0), box_face, 0.07, [30, 40, 160], true);
    assert_eq!(pipeline().detect_objects(&frame).barrier, None);
}

/// The barrier's pivot: 0.7 m ahead, 0.35 m right, at the arm's height.
const PIVOT: Vector3<f64> = Vector3::new(0.7, -0.35, 0.1);

#[test]
fn the_arm_is_read_down_up_or_moving_from_its_angle() {
    for (angle, state) in [
        (0.0, BarrierState::Down),
        (90.0, BarrierState::Up),
        (45.0, BarrierState::Moving),
    ] {
        let frame = arm(&straight_lane(0.0), PIVOT, angle, 0.6);
        let seen = pipeline().detect_objects(&frame).barrier.unwrap();
        assert_eq!(seen.state, state, "{angle}: {seen:?}");
        assert!((seen.angle_deg - angle).abs() < 8.0, "{angle}: {seen:?}");
        assert!((seen.range - 0.65).abs() < 0.07, "{angle}: {seen:?}");
    }
}

#[test]
fn the_filtered_barrier_follows_the_arm_up_and_forgets_it() {
    let mut p = pipeline();
    let up = arm(&straight_lane(0.0), PIVOT, 90.0, 0.6);
    let s = settled(&mut p, &up, 3);
    let b = s.barrier.unwrap();
    assert_eq!(b.state, BarrierState::Up);
    assert!(b.belief[2] > 0.8, "{b:?}");
    let lane = straight_lane(0.0);
    assert!(settled(&mut p, &lane, 9).barrier.is_some());
    assert_eq!(p.read(&lane, None).barrier, None);
}

struct Ticking(Mutex<f64>);

impl Clock for Ticking {
    fn now(&self) -> f64 {
        let mut t = self.0.lock().unwrap();
        *t += 0.01;
        *t
    }
}

#[test]
fn every_frame_brings_a_thumbnail_and_a_latency_and_a_wrong_frame_an_error() {
    let mut p = pipeline();
    let s = p.read(&straight_lane(0.0), Some(&Ticking(Mutex::new(0.0))));
    assert_eq!(s.latency, Some(0.01));
    let t = s.thumbnail.unwrap();
    assert_eq!((t.width, t.height), (48, 24));
    let wrong = p.read(&BgrFrame::filled(320, 240, [0; 3]), None);
    assert!(wrong.error.unwrap().contains("320x240"));
    let short = BgrFrame {
        width: 640,
        height: 480,
        data: vec![0; 10],
    };
    assert!(p.read(&short, None).error.is_some());
    assert_eq!(p.detect_objects(&short), Default::default());
}
