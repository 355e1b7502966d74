use super::*;
use crate::geometry::Point2;
use std::collections::BTreeMap;

fn frame() -> Frame {
    Frame {
        resolution: 0.05,
        origin: Point2::new(-2.0, -2.0),
        width: 80,
        height: 80,
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Rect {
    Rect { x0, y0, x1, y1 }
}

/// Files in memory: written by `encode`, read back through `read_filter`.
fn files(out: Vec<(PathBuf, Vec<u8>)>) -> BTreeMap<PathBuf, Vec<u8>> {
    out.into_iter().collect()
}

fn read_back(files: &BTreeMap<PathBuf, Vec<u8>>, info: &Path) -> Result<ZoneList, MaskError> {
    read_filter(info, &mut |p| {
        files
            .get(p)
            .cloned()
            .ok_or_else(|| std::io::Error::from(std::io::ErrorKind::NotFound))
    })
}

fn close(a: &Rect, b: &Rect) -> bool {
    [(a.x0, b.x0), (a.y0, b.y0), (a.x1, b.x1), (a.y1, b.y1)]
        .iter()
        .all(|(p, q)| (p - q).abs() < 1e-6)
}

#[test]
fn file_names_follow_the_map() {
    let (yaml, pgm, info) = paths(Path::new("maps/lab.yaml"), MaskKind::Keepout);
    assert_eq!(yaml, Path::new("maps/lab.keepout.yaml"));
    assert_eq!(pgm, Path::new("maps/lab.keepout.pgm"));
    assert_eq!(info, Path::new("maps/lab.keepout_filter_info.yaml"));
}

#[test]
fn keepout_and_speed_zones_round_trip() {
    let zones = ZoneList::new(vec![
        Zone::keepout(rect(-0.5, 0.0, 0.5, 0.25)),
        Zone::speed(SpeedLimit::MetresPerSecond(0.1), rect(1.0, 1.0, 1.5, 1.5)),
        Zone::speed(
            SpeedLimit::MetresPerSecond(0.15),
            rect(-1.5, -1.5, -1.0, -0.5),
        ),
        // Beyond the map: the mask grows to hold it.
        Zone::keepout(rect(3.0, 3.0, 3.5, 3.2)),
    ])
    .unwrap();
    let map = Path::new("m/lab.yaml");
    let mut all = BTreeMap::new();
    for kind in MaskKind::ALL {
        all.extend(files(encode(&zones, kind, map, frame(), 0.22)));
    }
    let keepout = read_back(&all, &paths(map, MaskKind::Keepout).2).unwrap();
    assert_eq!(keepout.len(), 2);
    assert!(keepout.zones().iter().all(|z| z.kind == ZoneKind::Keepout));
    assert!(close(&keepout.zones()[0].rect, &zones.zones()[0].rect));
    assert!(close(&keepout.zones()[1].rect, &zones.zones()[3].rect));
    let speed = read_back(&all, &paths(map, MaskKind::Speed).2).unwrap();
    assert_eq!(speed.len(), 2);
    let limit_at = |p: Point2| speed.speed_limit_near(p, 0.0, 0.22).unwrap();
    assert!((limit_at(Point2::new(1.2, 1.2)) - 0.1).abs() < 1e-9);
    assert!((limit_at(Point2::new(-1.2, -1.0)) - 0.15).abs() < 1e-9);
    // The parameters are Nav2's: type 2 (m/s), base 0, multiplier 0.01.
    let info = String::from_utf8(all[&paths(map, MaskKind::Speed).2].clone()).unwrap();
    assert!(info.contains("costmap_filter_info_server:\n  ros__parameters:\n    type: 2"));
    assert!(info.contains("multiplier: 0.01"), "{info}");
}

#[test]
fn percent_zones_make_a_percent_filter() {
    let zones = ZoneList::new(vec![Zone::speed(
        SpeedLimit::Percent(40.0),
        rect(0.0, 0.0, 0.5, 0.5),
    )])
    .unwrap();
    let map = Path::new("lab.yaml");
    let all = files(encode(&zones, MaskKind::Speed, map, frame(), 0.22));
    let back = read_back(&all, &paths(map, MaskKind::Speed).2).unwrap();
    assert_eq!(back.len(), 1);
    assert_eq!(
        back.zones()[0].kind,
        ZoneKind::Speed(SpeedLimit::Percent(40.0))
    );
}

/// A Nav2 user's speed mask as nav2_bringup ships them (scale, thresholds 1.0 and 0.0,
/// percent with base 100 and multiplier -1), at its own resolution and origin, negated.
#[test]
fn a_nav2_users_negated_percent_mask_reads() {
    // 4 x 2 pixels at 0.1 m from (10, 20); negate: occ = shade. Top row: white (255) is
    // occ 1.0 -> value 100 -> 100 - 100 = 0 % (no limit in Nav2); 51 -> occ 0.2 -> 20 ->
    // 80 %. Bottom row: black -> 0 (free, no limit).
    let pgm = pgm::encode(4, 2, &[255, 51, 51, 255, 0, 0, 0, 0]);
    let yaml = "image: speed.pgm\nmode: scale\nresolution: 0.1\norigin: [10.0, 20.0, 0]\n\
                negate: 1\noccupied_thresh: 1.0\nfree_thresh: 0.0\n";
    let info = "speed_filter_info_server:\n  ros__parameters:\n    type: 1\n    base: 100.0\n    \
                multiplier: -1.0\n    filter_info_topic: x\n    mask_topic: y\n\
                speed_filter_mask_server:\n  ros__parameters:\n    yaml_filename: speed.yaml\n";
    let all: BTreeMap<PathBuf, Vec<u8>> = [
        (PathBuf::from("u/speed.pgm"), pgm),
        (PathBuf::from("u/speed.yaml"), yaml.as_bytes().to_vec()),
        (PathBuf::from("u/info.yaml"), info.as_bytes().to_vec()),
    ]
    .into_iter()
    .collect();
    let back = read_back(&all, Path::new("u/info.yaml")).unwrap();
    assert_eq!(back.len(), 1, "{back:?}");
    let z = back.zones()[0];
    assert_eq!(z.kind, ZoneKind::Speed(SpeedLimit::Percent(80.0)));
    assert!(close(&z.rect, &rect(10.1, 20.1, 10.3, 20.2)), "{z:?}");
}

#[test]
fn nav2_scale_values_follow_map_server() {
    // Every mask value survives the scale pixels: rint((1 - p / 255) * 100).
    let mut grid = frame().grid(0);
    for v in 0..=100i8 {
        grid.set(v as usize % 80, v as usize / 80, v);
    }
    let image = pgm::decode(&pgm::encode(80, 80, &scale_pixels(&grid))).unwrap();
    let raw = RawMap {
        resolution: 0.05,
        origin: frame().origin,
        negate: false,
        occupied_thresh: 1.0,
        free_thresh: 0.0,
        mode: crate::map::raw_map::Mode::Scale,
        image,
        extras: None,
    };
    assert_eq!(mask_values(&raw).cells, grid.cells);
}

#[test]
fn bad_filter_info_names_its_field() {
    let all: BTreeMap<PathBuf, Vec<u8>> = [(
        PathBuf::from("a_filter_info.yaml"),
        b"costmap_filter_info_server:\n  ros__parameters:\n    type: 7\n".to_vec(),
    )]
    .into_iter()
    .collect();
    let e = read_back(&all, Path::new("a_filter_info.yaml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("field `type` = 7"), "{e}");
    let none: BTreeMap<PathBuf, Vec<u8>> = [(
        PathBuf::from("b_filter_info.yaml"),
        b"costmap_filter_info_server:\n  ros__parameters:\n    type: 0\n    base: x\n".to_vec(),
    )]
    .into_iter()
    .collect();
    let e = read_back(&none, Path::new("b_filter_info.yaml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`base`"), "{e}");
    // The mask it points at is missing: named, never a panic.
    let ok: BTreeMap<PathBuf, Vec<u8>> = [(
        PathBuf::from("c_filter_info.yaml"),
        b"costmap_filter_info_server:\n  ros__parameters:\n    type: 0\n".to_vec(),
    )]
    .into_iter()
    .collect();
    let e = read_back(&ok, Path::new("c_filter_info.yaml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("c.yaml"), "{e}");
}
