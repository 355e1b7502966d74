//! The one check for everything a link hands the pilot, live or replayed: a frame's
//! stamps, wheel travel, scan, sightings, floor tags (`tag_check.rs`), camera report,
//! poses and arm joints must be finite and within physical bounds. What fails is taken
//! out (the part, or the whole frame when its stamp is bad) and named with its time,
//! field and value; the rest goes on.

use super::sensors::{LaserScan, SensorFrame};
use crate::geometry::{Pose2, wrap_angle};
use std::collections::BTreeMap;

/// Largest scan accepted, beams (a 0.1° lidar has 3600).
pub const MAX_BEAMS: usize = 20_000;
/// Largest `range_max` a scan may claim, metres: the longest-reaching lidars made
/// (automotive units) see about 300 m.
pub const MAX_SCAN_RANGE: f64 = 300.0;
/// Sightings and camera ids in one frame at most: the ArUco dictionary navdeck decodes
/// (DICT_ARUCO_ORIGINAL) holds 1024 markers, each seen once per frame at most.
pub const MAX_MARKERS: usize = 1024;
/// A marker seen nearer than this is a bad reading, metres: a printed marker fills the
/// camera's view long before (1 cm).
pub const MIN_SIGHTING_RANGE: f64 = 0.01;
/// A marker seen farther than this is a bad reading, metres: the most the detector's and
/// the twin camera's `max_range` may be set to.
pub const MAX_SIGHTING_RANGE: f64 = 100.0;
/// Largest coordinate of a pose handed in (initial pose, goal), metres: 10 km, beyond
/// any map navdeck holds (its 16 M-cell cap is 4,000 cells a side).
pub const MAX_COORDINATE: f64 = 1e4;
/// Most seconds one frame's wheel travel may cover: a link silent this long is lost
/// (and a frame claiming more would excuse any travel).
pub const MAX_ELAPSED: f64 = 60.0;
/// Wheel travel allowed beyond top speed × elapsed, metres: a reading's jitter (the
/// ROS 2 link's joint and odometry checks allow the same).
pub const WHEEL_ALLOWANCE: f64 = 0.05;
/// A revolute arm joint reported beyond one turn either way is a bad reading, radians.
pub const MAX_JOINT: f64 = std::f64::consts::TAU;

/// One part of a frame taken out: the field, its value and the bound it broke.
#[derive(Clone, Debug, PartialEq)]
pub struct Refused {
    pub field: &'static str,
    pub value: f64,
    pub bound: String,
}

impl Refused {
    pub(super) fn new(field: &'static str, value: f64, bound: impl Into<String>) -> Self {
        Self {
            field,
            value,
            bound: bound.into(),
        }
    }
}

/// `v` printed short (`number::short`: `1e308`, `0.25`), and in words when it is no
/// number ("not a number", "infinite"): these lines reach reports that must not say NaN.
pub fn short(v: f64) -> String {
    if v.is_nan() {
        "not a number".into()
    } else if v.is_infinite() {
        if v > 0.0 { "infinite" } else { "-infinite" }.into()
    } else {
        super::number::short(v)
    }
}

/// The scan with ranges beyond `range_max` (and NaN ones) made "no return" (+inf, REP
/// 117), or why the whole scan is refused (its geometry or size is bad).
pub fn check_scan(scan: &mut LaserScan) -> Result<Vec<Refused>, Refused> {
    let n = scan.ranges.len();
    if n == 0 || n > MAX_BEAMS {
        return Err(Refused::new(
            "scan.ranges",
            n as f64,
            format!("beams must number 1..={MAX_BEAMS}"),
        ));
    }
    let finite = [
        ("scan.angle_min", scan.angle_min),
        ("scan.angle_increment", scan.angle_increment),
    ];
    if let Some(&(field, v)) = finite.iter().find(|(_, v)| !v.is_finite()) {
        return Err(Refused::new(field, v, "must be finite"));
    }
    // Beams covering more than two turns are not a planar scan.
    let sweep = scan.angle_increment.abs() * n as f64;
    if scan.angle_increment == 0.0 || sweep > 2.0 * std::f64::consts::TAU {
        let bound = "must be non-zero, sweeping at most two turns";
        return Err(Refused::new(
            "scan.angle_increment",
            scan.angle_increment,
            bound,
        ));
    }
    if !(0.0..MAX_SCAN_RANGE).contains(&scan.range_min) {
        let bound = format!("must lie in 0..{}", short(MAX_SCAN_RANGE));
        return Err(Refused::new("scan.range_min", scan.range_min, bound));
    }
    if !(scan.range_max > scan.range_min && scan.range_max <= MAX_SCAN_RANGE) {
        let bound = format!(
            "must lie in {}..={} (above range_min)",
            short(scan.range_min),
            short(MAX_SCAN_RANGE)
        );
        return Err(Refused::new("scan.range_max", scan.range_max, bound));
    }
    let mut refused = Vec::new();
    for r in &mut scan.ranges {
        if r.is_nan() {
            refused.push(Refused::new("scan.ranges", f64::NAN, "read as no return"));
            *r = f32::INFINITY;
        } else if f64::from(*r) > scan.range_max {
            // Beyond range_max is no return (REP 117); the belief reads it the same.
            *r = f32::INFINITY;
        }
    }
    refused.truncate(1);
    Ok(refused)
}

/// A pose finite and within `MAX_COORDINATE`, its heading wrapped; or the bad field.
fn check_pose(pose: Pose2, names: [&'static str; 3]) -> Result<Pose2, Refused> {
    let bound = format!("must be finite, within ±{}", short(MAX_COORDINATE));
    for (field, v) in names.into_iter().zip([pose.x, pose.y]) {
        if !(0.0..=MAX_COORDINATE).contains(&v.abs()) {
            return Err(Refused::new(field, v, bound));
        }
    }
    if !pose.theta.is_finite() {
        return Err(Refused::new(names[2], pose.theta, "must be finite"));
    }
    Ok(Pose2::new(pose.x, pose.y, wrap_angle(pose.theta)))
}

/// Checks `frame` in place, taking out what breaks a bound: `Err` when the whole frame
/// must go (its stamp is not a time), else the parts taken out.
/// `max_wheel_speed` is the robot's (`RobotConfig::max_wheel_speed`), m/s.
pub fn check_frame(frame: &mut SensorFrame, max_wheel_speed: f64) -> Result<Vec<Refused>, Refused> {
    if !frame.stamp.is_finite() {
        return Err(Refused::new("stamp", frame.stamp, "must be finite"));
    }
    let mut refused = Vec::new();
    if !(0.0..=MAX_ELAPSED).contains(&frame.elapsed) {
        let bound = format!("must lie in 0..={}", short(MAX_ELAPSED));
        refused.push(Refused::new("elapsed", frame.elapsed, bound));
        frame.elapsed = 0.0;
        frame.wheels = None;
    }
    if let Some(w) = frame.wheels {
        let limit = max_wheel_speed * frame.elapsed + WHEEL_ALLOWANCE;
        let bound = format!(
            "must be within ±{} m (top wheel speed {} m/s × {} s + {} m)",
            short(limit),
            short(max_wheel_speed),
            short(frame.elapsed),
            short(WHEEL_ALLOWANCE)
        );
        for (field, v) in [("wheels.left", w.left), ("wheels.right", w.right)] {
            if !(0.0..=limit).contains(&v.abs()) {
                refused.push(Refused::new(field, v, bound.clone()));
                frame.wheels = None;
                break;
            }
        }
    }
    if let Some(scan) = frame.scan.as_mut() {
        match check_scan(scan) {
            Ok(mut parts) => refused.append(&mut parts),
            Err(why) => {
                refused.push(why);
                frame.scan = None;
            }
        }
    }
    check_sightings(frame, &mut refused);
    super::tag_check::check_tags(frame, &mut refused);
    if let Some(camera) = frame.camera.as_mut() {
        if camera.ids.len() > MAX_MARKERS {
            let bound = format!("ids must number at most {MAX_MARKERS}");
            refused.push(Refused::new("camera.ids", camera.ids.len() as f64, bound));
            camera.ids.clear();
        }
        if camera
            .latency
            .is_some_and(|l| !(0.0..=MAX_ELAPSED).contains(&l))
        {
            let bound = format!("must lie in 0..={}", short(MAX_ELAPSED));
            refused.push(Refused::new(
                "camera.latency",
                camera.latency.unwrap_or(0.0),
                bound,
            ));
            camera.latency = None;
        }
    }
    for (pose, names) in [
        (
            &mut frame.initial_pose,
            ["initial_pose.x", "initial_pose.y", "initial_pose.theta"],
        ),
        (&mut frame.goal, ["goal.x", "goal.y", "goal.theta"]),
    ] {
        if let Some(p) = *pose {
            match check_pose(p, names) {
                Ok(p) => *pose = Some(p),
                Err(why) => {
                    refused.push(why);
                    *pose = None;
                }
            }
        }
    }
    if let Some(arm) = frame.arm
        && let Some(&j) = arm
            .joints
            .iter()
            .find(|j| !(0.0..=MAX_JOINT).contains(&j.abs()))
    {
        let bound = format!("must be finite, within ±{:.3} rad", MAX_JOINT);
        refused.push(Refused::new("arm.joints", j, bound));
        frame.arm = None;
    }
    Ok(refused)
}

/// Sightings: at most `MAX_MARKERS`, each range within its bounds and bearing finite
/// (then wrapped); a bad one is taken out, the rest kept.
fn check_sightings(frame: &mut SensorFrame, refused: &mut Vec<Refused>) {
    let range_bound = format!(
        "must lie in {}..={} m",
        short(MIN_SIGHTING_RANGE),
        short(MAX_SIGHTING_RANGE)
    );
    let list = &mut frame.sightings;
    check_list(list, "sightings", MAX_MARKERS, refused, |s| {
        if !(MIN_SIGHTING_RANGE..=MAX_SIGHTING_RANGE).contains(&s.range) {
            Some(Refused::new(
                "sightings.range",
                s.range,
                range_bound.clone(),
            ))
        } else if !s.bearing.is_finite() {
            Some(Refused::new(
                "sightings.bearing",
                s.bearing,
                "must be finite",
            ))
        } else {
            s.bearing = wrap_angle(s.bearing);
            None
        }
    });
}

/// Checks a frame's list `field` in place: more than `max` items and the whole list is
/// taken out; else each item `check` refuses (it may mend the rest) is taken out, the
/// first of them named.
pub(super) fn check_list<T>(
    list: &mut Option<Vec<T>>,
    field: &'static str,
    max: usize,
    refused: &mut Vec<Refused>,
    mut check: impl FnMut(&mut T) -> Option<Refused>,
) {
    let Some(items) = list.as_mut() else {
        return;
    };
    if items.len() > max {
        let bound = format!("must number at most {max}");
        refused.push(Refused::new(field, items.len() as f64, bound));
        *list = None;
        return;
    }
    let mut first = None;
    items.retain_mut(|item| {
        let why = check(item);
        let keep = why.is_none();
        if first.is_none() {
            first = why;
        }
        keep
    });
    refused.extend(first);
}

/// The check with its tally: each field's first refusal is named in full and then again
/// at its 10th, 100th, 1000th..., so a stream of bad frames gives a few lines, not one a
/// frame.
#[derive(Clone, Debug, Default)]
pub struct FrameChecker {
    max_wheel_speed: f64,
    tally: BTreeMap<&'static str, u64>,
}

impl FrameChecker {
    pub fn new(max_wheel_speed: f64) -> Self {
        Self {
            max_wheel_speed,
            tally: BTreeMap::new(),
        }
    }

    /// Checks `frame`, polled at session time `t`: the frame without what was taken out
    /// (None when nothing of it is usable), and the log lines saying what was.
    pub fn check(&mut self, t: f64, mut frame: SensorFrame) -> (Option<SensorFrame>, Vec<String>) {
        let (kept, refused) = match check_frame(&mut frame, self.max_wheel_speed) {
            Ok(refused) => (Some(frame), refused),
            Err(why) => (None, vec![why]),
        };
        let mut lines = Vec::new();
        for r in refused {
            let n = self.tally.entry(r.field).or_insert(0);
            *n += 1;
            let count = *n;
            if is_power_of_ten(count) {
                let whole = if kept.is_none() {
                    " (the frame skipped)"
                } else {
                    ""
                };
                let times = if count > 1 {
                    format!(" (×{count} so far)")
                } else {
                    String::new()
                };
                lines.push(format!(
                    "frame at {t:.3} s: {} is {}, refused{whole}: {}{times}",
                    r.field,
                    short(r.value),
                    r.bound
                ));
            }
        }
        (kept, lines)
    }
}

fn is_power_of_ten(mut n: u64) -> bool {
    while n >= 10 && n.is_multiple_of(10) {
        n /= 10;
    }
    n == 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{MarkerSighting, WheelTravel};

    fn scan(range_max: f64, ranges: Vec<f32>) -> LaserScan {
        LaserScan {
            angle_min: 0.0,
            angle_increment: 0.01,
            range_min: 0.1,
            range_max,
            ranges,
        }
    }

    #[test]
    fn huge_or_non_finite_values_are_taken_out_and_named_the_rest_kept() {
        let mut frame = SensorFrame {
            stamp: 1.0,
            elapsed: 0.1,
            wheels: Some(WheelTravel {
                left: 1e6,
                right: 0.0,
            }),
            sightings: Some(vec![
                MarkerSighting {
                    id: 1,
                    range: 1e-300,
                    bearing: 0.0,
                },
                MarkerSighting {
                    id: 2,
                    range: 1.0,
                    bearing: 7.0,
                },
            ]),
            scan: Some(scan(1e308, vec![1e8])),
            initial_pose: Some(Pose2::new(f64::NAN, 0.0, 0.0)),
            goal: Some(Pose2::new(1.0, 2.0, 4.0)),
            ..SensorFrame::default()
        };
        let refused = check_frame(&mut frame, 1.0).unwrap();
        let fields: Vec<_> = refused.iter().map(|r| r.field).collect();
        assert_eq!(
            fields,
            [
                "wheels.left",
                "scan.range_max",
                "sightings.range",
                "initial_pose.x"
            ]
        );
        assert_eq!(frame.wheels, None);
        assert_eq!(frame.scan, None);
        assert_eq!(frame.initial_pose, None);
        let kept = frame.sightings.unwrap();
        assert_eq!(kept.len(), 1);
        assert!((kept[0].bearing - (7.0 - std::f64::consts::TAU)).abs() < 1e-12);
        assert!((frame.goal.unwrap().theta - (4.0 - std::f64::consts::TAU)).abs() < 1e-12);
        // Wheel travel of top speed × elapsed passes, a little more does not.
        let mut ok = SensorFrame {
            elapsed: 0.1,
            wheels: Some(WheelTravel {
                left: 0.14,
                right: -0.14,
            }),
            ..SensorFrame::default()
        };
        assert_eq!(check_frame(&mut ok, 0.93), Ok(vec![]));
        ok.wheels = Some(WheelTravel {
            left: 0.15,
            right: 0.0,
        });
        assert_eq!(check_frame(&mut ok, 0.93).unwrap().len(), 1);
    }

    #[test]
    fn scans_are_bounded_and_out_of_range_beams_are_no_returns() {
        let mut s = scan(3.5, vec![1.0, f32::NAN, 1e8, f32::NEG_INFINITY]);
        let refused = check_scan(&mut s).unwrap();
        assert_eq!(refused.len(), 1);
        assert_eq!(s.ranges[..3], [1.0, f32::INFINITY, f32::INFINITY]);
        assert_eq!(s.ranges[3], f32::NEG_INFINITY);
        for bad in [f64::INFINITY, f64::NAN, 1e9, 0.05] {
            let err = check_scan(&mut scan(bad, vec![1.0])).unwrap_err();
            assert_eq!(err.field, "scan.range_max");
        }
        let huge = check_scan(&mut scan(3.5, vec![1.0; MAX_BEAMS + 1])).unwrap_err();
        assert_eq!(huge.field, "scan.ranges");
    }

    #[test]
    fn each_field_is_named_once_then_at_each_power_of_ten() {
        let mut checker = FrameChecker::new(1.0);
        let bad = SensorFrame {
            elapsed: 0.1,
            wheels: Some(WheelTravel {
                left: f64::NAN,
                right: 0.0,
            }),
            ..SensorFrame::default()
        };
        let lines: Vec<String> = (0..120)
            .flat_map(|k| checker.check(f64::from(k) * 0.1, bad.clone()).1)
            .collect();
        assert_eq!(lines.len(), 3, "{lines:?}");
        assert!(lines[0].contains("frame at 0.000 s: wheels.left is not a number, refused"));
        assert!(lines[2].contains("×100 so far"), "{lines:?}");
        let (kept, lines) = checker.check(
            2.0,
            SensorFrame {
                stamp: f64::INFINITY,
                ..SensorFrame::default()
            },
        );
        assert!(kept.is_none());
        assert!(lines[0].contains("stamp is infinite, refused (the frame skipped)"));
        assert_eq!(short(1e308), "1e308");
        assert_eq!(short(1e-300), "1e-300");
        assert_eq!(short(0.05), "0.05");
    }
}
