//! Value parsers shared by the command line's options.

use navdeck::data::number::short;
use navdeck::geometry::{Point2, Pose2};

/// A number within lo..=hi, or why not, the value and bounds printed short (`1e308`).
pub(crate) fn bounded(s: &str, lo: f64, hi: f64, unit: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(outside(v, lo, hi, unit))
    }
}

/// "1e308 s is outside 0.1..=7200": a value refused for lying outside its bounds.
pub(crate) fn outside(v: f64, lo: f64, hi: f64, unit: &str) -> String {
    format!(
        "{} {unit} is outside {}..={}",
        short(v),
        short(lo),
        short(hi)
    )
}

/// A whole number (a seed, a count), or why not, naming the value: clap's own message
/// for these is the standard library's bare "invalid digit found in string".
pub(crate) fn whole<T: std::str::FromStr<Err = std::num::ParseIntError>>(
    s: &str,
) -> Result<T, String> {
    use std::num::IntErrorKind;
    s.trim()
        .parse()
        .map_err(|e: std::num::ParseIntError| match e.kind() {
            IntErrorKind::Empty => "a whole number is missing".to_string(),
            IntErrorKind::PosOverflow => format!("`{s}` is too large a number"),
            _ => format!("`{s}` is not a whole number (0, 1, 2, …)"),
        })
}

/// A ROS 2 domain ID: 0 to 232 (ROS 2's "ROS_DOMAIN_ID" page).
pub(crate) fn parse_domain(s: &str) -> Result<u16, String> {
    let d: u16 = whole(s).map_err(|_| format!("`{s}` is not a domain ID (0 to 232)"))?;
    if d <= 232 {
        Ok(d)
    } else {
        Err(format!("domain {d} is outside 0..=232"))
    }
}

/// Headless keys per second of simulated time: 0.1 to 1000.
pub(crate) fn parse_key_rate(s: &str) -> Result<f64, String> {
    bounded(s, 0.1, 1000.0, "keys a second")
}

/// A mission's time limit: up to two simulated hours.
pub(crate) fn parse_time_limit(s: &str) -> Result<f64, String> {
    bounded(s, 1.0, 7200.0, "s")
}

/// A pose as X,Y,THETA_DEG: metres and degrees, finite.
pub(crate) fn parse_pose(s: &str) -> Result<Pose2, String> {
    navdeck::geometry::parse_pose_degrees(s)
}

pub(crate) fn parse_point(s: &str) -> Result<Point2, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y] = parts.as_slice() else {
        return Err(format!("`{s}` is not X,Y"));
    };
    let number = |v: &str| {
        v.parse::<f64>()
            .ok()
            .filter(|n| n.is_finite())
            .ok_or_else(|| format!("`{v}` in `{s}` is not a number of metres"))
    };
    Ok(Point2::new(number(x)?, number(y)?))
}

/// `--ns`: a ROS 2 namespace by rcl's rules, refused before any link is opened (not as
/// clap's parser, which would echo a value of any length and with any characters).
pub(crate) fn check_namespace(option: &str, ns: &str) -> anyhow::Result<()> {
    navdeck::link::ros2::config::check_namespace(ns).map_err(|e| anyhow::anyhow!("{option}: {e}"))
}
