//! The rendered tag camera's picture: the floor's grey, a tag's black border and white
//! rim where the pinhole puts them, and frames repeatable from their seed.

use super::*;
use crate::tags::TagMap;

const MAP: &str = "
tags:
  508: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
  101: {x: 0.6, y: 0.0, type: waypoint, zone: A}
edges:
  508: [{to: 101, direction: forward, type: straight}]
  101: [{to: 508, direction: backward, type: straight}]
tasks:
  out: {waypoints: [508, 101, 508]}
";

/// Every cell white but the data cell at marker row 3, column 3.
fn patterns() -> BTreeMap<TagId, TagCells> {
    let mut cells = [true; MARKER_CELLS * MARKER_CELLS];
    for k in 0..MARKER_CELLS {
        for edge in [k, (MARKER_CELLS - 1) * MARKER_CELLS + k] {
            cells[edge] = false;
        }
        cells[k * MARKER_CELLS] = false;
        cells[k * MARKER_CELLS + MARKER_CELLS - 1] = false;
    }
    cells[3 * MARKER_CELLS + 3] = false;
    [(508, cells), (101, cells)].into_iter().collect()
}

fn renderer() -> (TagRenderer, TagCameraConfig) {
    let map = TagMap::parse(MAP).unwrap();
    let camera = TagCameraConfig::default();
    (
        TagRenderer::new(&map, &camera, 0.05, &patterns(), 7),
        camera,
    )
}

#[test]
fn a_tag_under_the_image_centre_shows_its_border_and_rim_on_a_grey_floor() {
    let (r, camera) = renderer();
    let look = camera.look().unwrap();
    // The image centre over the dock tag, facing its way (east).
    let pose = Pose2::new(-look, 0.0, 0.0);
    let frame = r.render(pose, &mut ChaCha8Rng::seed_from_u64(1));
    assert_eq!((frame.width, frame.height), (1280, 720));
    let view = FloorView::new(r.intrinsics(), &camera.mount(), pose);
    let grey = |x: f64, y: f64| {
        let (u, v) = view.pixel_of(x, y).unwrap();
        frame.data[v.round() as usize * frame.width + u.round() as usize]
    };
    // Cells are 6.25 mm: the black border 3.5 cells off the centre, the rim 4.5 off,
    // the floor beyond 5 cells; the black data cell at marker row 3, column 3 lies half
    // a cell above and left of the centre.
    let cell = 0.05 / 8.0;
    assert!(
        grey(0.0, 3.5 * cell) < 60,
        "border {}",
        grey(0.0, 3.5 * cell)
    );
    assert!(grey(4.5 * cell, 0.0) > 180, "rim {}", grey(4.5 * cell, 0.0));
    assert!(grey(0.5 * cell, 0.5 * cell) < 60);
    assert!(grey(-0.5 * cell, -0.5 * cell) > 180);
    let floor = grey(0.0, 0.15);
    assert!((140..200).contains(&floor), "floor {floor}");
    assert_eq!(r.wholly_in_view(pose, 4.0), vec![508]);
}

#[test]
fn frames_repeat_from_the_seed_and_noise_differs_from_frame_to_frame() {
    let (r, _) = renderer();
    let pose = Pose2::new(0.3, 0.01, 0.05);
    let a = r.render(pose, &mut ChaCha8Rng::seed_from_u64(2));
    let b = r.render(pose, &mut ChaCha8Rng::seed_from_u64(2));
    assert_eq!(a, b);
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let first = r.render(pose, &mut rng);
    let second = r.render(pose, &mut rng);
    assert_ne!(first, second);
    // Between the tags only floor is in view.
    assert!(r.wholly_in_view(pose, 0.0).is_empty());
    // A tag reaching past the image's top edge is not whole in view.
    let look = TagCameraConfig::default().look().unwrap();
    let near_top = Pose2::new(0.6 - look - 0.14, 0.0, 0.0);
    assert!(r.wholly_in_view(near_top, 0.0).is_empty());
}

#[test]
fn a_tag_without_a_pattern_is_named_and_left_off_the_floor() {
    let map = TagMap::parse(MAP).unwrap();
    let mut only_dock = patterns();
    only_dock.remove(&101);
    let r = TagRenderer::new(&map, &TagCameraConfig::default(), 0.05, &only_dock, 1);
    assert_eq!(r.unpainted(), &[101]);
    let look = TagCameraConfig::default().look().unwrap();
    assert!(
        r.wholly_in_view(Pose2::new(0.6 - look, 0.0, 0.0), 0.0)
            .is_empty()
    );
}
