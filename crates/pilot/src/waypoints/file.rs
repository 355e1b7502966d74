//! Route files: the waypoints as a YAML list of poses in the map frame, the way a Nav2
//! waypoint list reads (x and y in metres, yaw in radians per REP-103, optional).
//!
//! ```yaml
//! frame_id: map
//! loops: 2
//! waypoints:
//!   - {x: 1.0, y: 0.5, yaw: 1.5708}
//!   - {x: 2.0, y: -0.5}
//! ```

use super::Waypoint;
use navdeck_core::geometry::Point2;
use serde::{Deserialize, Serialize};

/// Coordinates beyond this many metres are refused as typing slips.
const FARTHEST: f64 = 1.0e5;

/// A route as its file holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteFile {
    pub waypoints: Vec<Waypoint>,
    pub loops: usize,
}

/// Why a route file was refused: the file, and the field and value at fault.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum RouteFileError {
    #[error("{file}: {reason}")]
    Yaml { file: String, reason: String },
    #[error("{file}: {field}: `{value}` {why}")]
    Field {
        file: String,
        field: String,
        value: String,
        why: &'static str,
    },
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Yaml {
    #[serde(default = "map_frame")]
    frame_id: String,
    #[serde(default = "one")]
    loops: i64,
    waypoints: Vec<YamlPose>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct YamlPose {
    x: f64,
    y: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    yaw: Option<f64>,
}

fn map_frame() -> String {
    "map".to_string()
}
fn one() -> i64 {
    1
}

/// Reads a route file's text; `file` names it in errors.
pub fn parse(text: &str, file: &str) -> Result<RouteFile, RouteFileError> {
    let yaml: Yaml = serde_norway::from_str(text).map_err(|e| RouteFileError::Yaml {
        file: file.to_string(),
        reason: e.to_string(),
    })?;
    let bad = |field: String, value: String, why| RouteFileError::Field {
        file: file.to_string(),
        field,
        value,
        why,
    };
    if yaml.frame_id != "map" {
        return Err(bad(
            "frame_id".into(),
            yaml.frame_id,
            "is not `map`: waypoints are poses in the map frame",
        ));
    }
    let loops = usize::try_from(yaml.loops)
        .ok()
        .filter(|n| (1..=1000).contains(n))
        .ok_or_else(|| {
            bad(
                "loops".into(),
                yaml.loops.to_string(),
                "is not a count from 1 to 1000",
            )
        })?;
    if yaml.waypoints.is_empty() {
        return Err(bad(
            "waypoints".into(),
            "[]".into(),
            "is empty: a route needs a waypoint",
        ));
    }
    let mut waypoints = Vec::new();
    for (i, p) in yaml.waypoints.iter().enumerate() {
        let metres = |name: &str, v: f64| {
            if v.is_finite() && v.abs() <= FARTHEST {
                Ok(v)
            } else {
                Err(bad(
                    format!("waypoints[{i}].{name}"),
                    v.to_string(),
                    "is not a number of metres within 100000",
                ))
            }
        };
        let (x, y) = (metres("x", p.x)?, metres("y", p.y)?);
        let yaw = match p.yaw {
            Some(v) if !v.is_finite() => {
                return Err(bad(
                    format!("waypoints[{i}].yaw"),
                    v.to_string(),
                    "is not a number of radians",
                ));
            }
            yaw => yaw,
        };
        waypoints.push(Waypoint {
            position: Point2::new(x, y),
            yaw,
        });
    }
    Ok(RouteFile { waypoints, loops })
}

/// The route as a file's text.
pub fn to_yaml(route: &RouteFile) -> String {
    let yaml = Yaml {
        frame_id: map_frame(),
        loops: route.loops as i64,
        waypoints: route
            .waypoints
            .iter()
            .map(|w| YamlPose {
                x: w.position.x,
                y: w.position.y,
                yaw: w.yaw,
            })
            .collect(),
    };
    let body = serde_norway::to_string(&yaml).unwrap_or_default();
    format!("# navdeck route: poses in the map frame (x, y in metres, yaw in radians)\n{body}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_route_reads_back_as_written() {
        let route = RouteFile {
            waypoints: vec![
                Waypoint {
                    position: Point2::new(1.0, 0.5),
                    yaw: Some(1.5),
                },
                Waypoint {
                    position: Point2::new(-2.25, 3.0),
                    yaw: None,
                },
            ],
            loops: 2,
        };
        assert_eq!(parse(&to_yaml(&route), "r.yaml"), Ok(route));
    }

    #[test]
    fn errors_name_the_file_the_field_and_the_value() {
        let e = parse("waypoints:\n  - {x: 1, y: .nan}\n", "r.yaml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("r.yaml") && e.contains("waypoints[0].y") && e.contains("NaN"),
            "{e}"
        );
        let e = parse("loops: 0\nwaypoints:\n  - {x: 1, y: 2}\n", "r.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("loops") && e.contains("`0`"), "{e}");
        let e = parse("waypoints:\n  - {x: one, y: 2}\n", "r.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("r.yaml") && e.contains("waypoints"), "{e}");
        let e = parse("frame_id: odom\nwaypoints:\n  - {x: 1, y: 2}\n", "r.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("frame_id") && e.contains("odom"), "{e}");
    }
}
