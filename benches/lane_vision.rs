//! One lane camera frame through the lane pipeline: 640x480 with both lines, a lit red lamp
//! and a lowered barrier arm in view, read whole (`read`: masks, bird's-eye windows and
//! fits, lamp, arm and filters) and for the light and barrier alone (`detect_objects`).
//! Seed 000 §6.3.1 measures lane detection 18.7 ms, object recognition 23.4 ms and the whole
//! cycle 50.7 ms. Needs `--features vision`.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use navdeck::perception::colour::BgrFrame;
use navdeck::perception::lane::{LanePipeline, LaneVisionConfig};
use navdeck::perception::lane_camera::LaneCameraConfig;
use std::hint::black_box;

/// The colour a pixel's ray meets: a 0.4 m lane with 25 mm lines, a red lamp 2.5 cm across
/// 0.9 m ahead and 0.3 m right at 0.22 m, an arm of red and white 6 cm stripes 0.7 m ahead at
/// 0.1 m across the lane.
fn scene(camera: &LaneCameraConfig) -> BgrFrame {
    let (k, mount) = (camera.intrinsics(), camera.mount());
    let lens = mount.to_robot(Vector3::zeros());
    let lamp = Vector3::new(0.9, -0.3, 0.22);
    let (w, h) = (k.width as usize, k.height as usize);
    let mut data = Vec::with_capacity(3 * w * h);
    for v in 0..h {
        for u in 0..w {
            // Inverse pinhole (Hartley & Zisserman 6.1): the ray of unit depth, robot frame.
            let d = mount.rotate_to_robot(Vector3::new(
                (u as f64 - k.cx) / k.fx,
                (v as f64 - k.cy) / k.fy,
                1.0,
            ));
            let at = |s: f64| lens + s * d;
            let mut colour = [70, 60, 60];
            if d.z < 0.0 {
                let p = at(-lens.z / d.z);
                colour = match p.y {
                    y if (y - 0.2).abs() < 0.0125 => [20, 190, 220],
                    y if (y + 0.2).abs() < 0.0125 => [200, 200, 200],
                    _ => [40, 40, 40],
                };
            }
            let arm = at((0.7 - lens.x) / d.x);
            if (arm.z - 0.1).abs() < 0.015 && (-0.35..0.25).contains(&arm.y) {
                let stripe = ((arm.y + 0.35) / 0.06) as usize;
                colour = if stripe.is_multiple_of(2) {
                    [0, 0, 210]
                } else {
                    [215, 215, 215]
                };
            }
            let q = at((lamp.x - lens.x) / d.x);
            if (q.y - lamp.y).hypot(q.z - lamp.z) < 0.025 {
                colour = [40, 40, 235];
            }
            data.extend_from_slice(&colour);
        }
    }
    BgrFrame {
        width: w,
        height: h,
        data,
    }
}

fn bench(c: &mut Criterion) {
    let camera = LaneCameraConfig::default();
    let frame = scene(&camera);
    let mut pipeline = LanePipeline::new(&LaneVisionConfig::default(), &camera).unwrap();
    let s = pipeline.read(&frame, None);
    assert!(
        s.error_px.is_some() && s.light.is_some() && s.barrier.is_some(),
        "{s:?}"
    );
    c.bench_function("lane read 640x480 (lines, lamp, arm)", |b| {
        b.iter(|| pipeline.read(black_box(&frame), None))
    });
    c.bench_function("lane detect_objects 640x480 (lamp, arm)", |b| {
        b.iter(|| pipeline.detect_objects(black_box(&frame)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
