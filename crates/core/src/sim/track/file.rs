//! The `[track]` section of a world file: the lane's shape as the control points of a
//! closed cubic B-spline (seed 004 smooths paths with B-splines), its widths, and the
//! lights and barriers placed by distance along it.
//!
//! ```toml
//! [track]
//! points = [[-1.5, -1.0], [1.5, -1.0], [1.5, 1.0], [-1.5, 1.0]]
//! lane_width = 0.4       # between the centres of the yellow and the white line
//! line_width = 0.025
//! white = "dashed"       # or "solid"
//! [[track.lights]]
//! at = 3.0               # metres along the lane from the first point
//! side = -0.35           # metres left of the centreline (negative: right)
//! cycle = { red = 6, green = 8, yellow = 2, offset = 0 }
//! # or: sequence = [["red", 5], ["green", 1000]]
//! [[track.barriers]]
//! at = 7.0
//! side = -0.35
//! cycle = { down = 5, moving = 2, up = 6, offset = 0 }
//! ```

use super::{Barrier, BarrierCycle, LightCycle, Track, TrackScene, TrafficLight};
use crate::data::LightColour;
use crate::geometry::Point2;
use serde::{Deserialize, Serialize};

/// Samples per B-spline span.
const SPAN_SAMPLES: usize = 24;

#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TrackSpec {
    /// Control points of the closed centreline, `[x, y]` metres.
    pub points: Vec<[f64; 2]>,
    /// `spline` (default: a closed cubic B-spline of the points) or `polyline` (through
    /// them, corners and all).
    #[serde(default = "spline")]
    pub shape: String,
    #[serde(default = "lane_width")]
    pub lane_width: f64,
    #[serde(default = "line_width")]
    pub line_width: f64,
    /// `dashed` or `solid`.
    #[serde(default = "dashed")]
    pub white: String,
    /// Length of a dash and of a gap of a dashed line, metres.
    #[serde(default = "dash")]
    pub dash: f64,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<LightSpec>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub barriers: Vec<BarrierSpec>,
}

#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LightSpec {
    pub at: f64,
    #[serde(default = "side")]
    pub side: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<LightCycleSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sequence: Option<Vec<(LightColour, f64)>>,
}

#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LightCycleSpec {
    pub red: f64,
    pub green: f64,
    pub yellow: f64,
    #[serde(default)]
    pub offset: f64,
}

#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BarrierSpec {
    pub at: f64,
    #[serde(default = "side")]
    pub side: f64,
    /// Length of the arm, metres; by default it reaches past the far line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub span: Option<f64>,
    pub cycle: BarrierCycleSpec,
}

#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BarrierCycleSpec {
    pub down: f64,
    pub moving: f64,
    pub up: f64,
    #[serde(default)]
    pub offset: f64,
}

fn spline() -> String {
    "spline".into()
}
fn lane_width() -> f64 {
    0.4
}
fn line_width() -> f64 {
    0.025
}
fn dashed() -> String {
    "dashed".into()
}
fn dash() -> f64 {
    0.1
}
fn side() -> f64 {
    -0.35
}

/// What is wrong with a `[track]` section: the field and its value.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("track.{field} = {value}: {reason}")]
pub struct TrackError {
    pub field: String,
    pub value: String,
    pub reason: String,
}

fn bad(field: impl Into<String>, value: impl ToString, reason: impl Into<String>) -> TrackError {
    TrackError {
        field: field.into(),
        value: value.to_string(),
        reason: reason.into(),
    }
}

fn positive(field: &str, v: f64, max: f64) -> Result<(), TrackError> {
    if v.is_finite() && v > 0.0 && v <= max {
        Ok(())
    } else {
        Err(bad(field, v, format!("must be above 0 and at most {max}")))
    }
}

/// A closed uniform cubic B-spline through `control`, `SPAN_SAMPLES` points a span
/// (the uniform B-spline basis, Piegl & Tiller, The NURBS Book, 2.2).
pub fn closed_bspline(control: &[Point2]) -> Vec<Point2> {
    let n = control.len();
    let mut out = Vec::with_capacity(n * SPAN_SAMPLES);
    for i in 0..n {
        let p = |k: usize| control[(i + n + k - 1) % n];
        let (p0, p1, p2, p3) = (p(0), p(1), p(2), p(3));
        for j in 0..SPAN_SAMPLES {
            let u = j as f64 / SPAN_SAMPLES as f64;
            let b0 = (1.0 - u).powi(3) / 6.0;
            let b1 = (3.0 * u.powi(3) - 6.0 * u * u + 4.0) / 6.0;
            let b2 = (-3.0 * u.powi(3) + 3.0 * u * u + 3.0 * u + 1.0) / 6.0;
            let b3 = u.powi(3) / 6.0;
            out.push(Point2::new(
                b0 * p0.x + b1 * p1.x + b2 * p2.x + b3 * p3.x,
                b0 * p0.y + b1 * p1.y + b2 * p2.y + b3 * p3.y,
            ));
        }
    }
    out
}

impl TrackSpec {
    /// The scene this section describes, or the first thing wrong with it.
    pub fn build(&self) -> Result<TrackScene, TrackError> {
        if self.points.len() < 3 {
            return Err(bad("points", self.points.len(), "needs at least 3 points"));
        }
        if let Some((i, p)) =
            (self.points.iter().enumerate()).find(|(_, p)| !p.iter().all(|v| v.is_finite()))
        {
            return Err(bad(
                format!("points[{i}]"),
                format!("{p:?}"),
                "must be finite",
            ));
        }
        positive("lane_width", self.lane_width, 5.0)?;
        positive("line_width", self.line_width, self.lane_width / 2.0)?;
        positive("dash", self.dash, 10.0)?;
        let dashed = match self.white.as_str() {
            "dashed" => true,
            "solid" => false,
            other => {
                return Err(bad(
                    "white",
                    format!("\"{other}\""),
                    "expected \"dashed\" or \"solid\"",
                ));
            }
        };
        let control: Vec<Point2> = self
            .points
            .iter()
            .map(|p| Point2::new(p[0], p[1]))
            .collect();
        let line = match self.shape.as_str() {
            "spline" => closed_bspline(&control),
            "polyline" => control,
            other => {
                return Err(bad(
                    "shape",
                    format!("\"{other}\""),
                    "expected \"spline\" or \"polyline\"",
                ));
            }
        };
        let track = Track::new(&line, self.lane_width, self.line_width, dashed, self.dash)
            .ok_or_else(|| {
                bad(
                    "points",
                    format!("{:?}", self.points),
                    "the lane has no length",
                )
            })?;
        let along = |field: String, at: f64| {
            if at.is_finite() && (0.0..track.length()).contains(&at) {
                Ok(())
            } else {
                Err(bad(
                    field,
                    at,
                    format!(
                        "must be from 0 to under the lane's length, {:.2} m",
                        track.length()
                    ),
                ))
            }
        };
        let mut lights = Vec::new();
        for (i, l) in self.lights.iter().enumerate() {
            along(format!("lights[{i}].at"), l.at)?;
            side_check(&format!("lights[{i}].side"), l.side, self.lane_width)?;
            let cycle = match (&l.cycle, &l.sequence) {
                (Some(c), None) => {
                    for (name, v) in [("red", c.red), ("green", c.green), ("yellow", c.yellow)] {
                        positive(&format!("lights[{i}].cycle.{name}"), v, 3600.0)?;
                    }
                    LightCycle::Periodic {
                        red: c.red,
                        green: c.green,
                        yellow: c.yellow,
                        offset: c.offset,
                    }
                }
                (None, Some(s)) if !s.is_empty() => {
                    for (k, (_, v)) in s.iter().enumerate() {
                        positive(&format!("lights[{i}].sequence[{k}]"), *v, 1e9)?;
                    }
                    LightCycle::Sequence(s.clone())
                }
                _ => {
                    return Err(bad(
                        format!("lights[{i}]"),
                        "…",
                        "give either `cycle` or a non-empty `sequence`",
                    ));
                }
            };
            lights.push(TrafficLight::beside(&track, l.at, l.side, cycle));
        }
        let mut barriers = Vec::new();
        for (i, b) in self.barriers.iter().enumerate() {
            along(format!("barriers[{i}].at"), b.at)?;
            side_check(&format!("barriers[{i}].side"), b.side, self.lane_width)?;
            let c = b.cycle;
            for (name, v) in [("down", c.down), ("moving", c.moving), ("up", c.up)] {
                positive(&format!("barriers[{i}].cycle.{name}"), v, 3600.0)?;
            }
            // By default the arm reaches from its post past the far line by a line's width.
            let span = b
                .span
                .unwrap_or(b.side.abs() + self.lane_width / 2.0 + self.line_width);
            positive(&format!("barriers[{i}].span"), span, 5.0)?;
            let cycle = BarrierCycle {
                down: c.down,
                moving: c.moving,
                up: c.up,
                offset: c.offset,
            };
            barriers.push(Barrier::beside(&track, b.at, b.side, span, cycle));
        }
        Ok(TrackScene {
            spec: self.clone(),
            track,
            lights,
            barriers,
        })
    }
}

/// A post must stand off the lane: beyond its line, at most 2 m away.
fn side_check(field: &str, side: f64, lane_width: f64) -> Result<(), TrackError> {
    let least = lane_width / 2.0 + 0.05;
    if side.is_finite() && (least..=2.0).contains(&side.abs()) {
        Ok(())
    } else {
        Err(bad(
            field,
            side,
            format!("the post must stand off the lane: |side| from {least:.2} to 2 m"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(extra: &str) -> Result<TrackScene, String> {
        let text =
            format!("points = [[-1.5, -1.0], [1.5, -1.0], [1.5, 1.0], [-1.5, 1.0]]\n{extra}");
        let spec: TrackSpec = toml::from_str(&text).map_err(|e| e.to_string())?;
        spec.build().map_err(|e| e.to_string())
    }

    #[test]
    fn a_spline_track_is_smooth_and_inside_its_control_points() {
        let scene = spec("").unwrap();
        assert!(
            scene.track.min_radius(5) > 0.4,
            "{}",
            scene.track.min_radius(5)
        );
        assert!(
            scene
                .track
                .points()
                .iter()
                .all(|p| p.x.abs() < 1.5 && p.y.abs() < 1.0)
        );
    }

    #[test]
    fn bad_fields_are_named_with_their_values() {
        let e = spec("lane_width = -1").unwrap_err();
        assert!(e.contains("track.lane_width = -1"), "{e}");
        let e = spec("white = \"dotted\"").unwrap_err();
        assert!(e.contains("track.white = \"dotted\""), "{e}");
        let e =
            spec("[[lights]]\nat = 99\ncycle = { red = 1, green = 1, yellow = 1 }").unwrap_err();
        assert!(e.contains("track.lights[0].at = 99"), "{e}");
        let e = spec("[[lights]]\nat = 1\nside = 0.1\nsequence = [[\"red\", 1]]").unwrap_err();
        assert!(e.contains("track.lights[0].side = 0.1"), "{e}");
        let e = spec("[[barriers]]\nat = 1\ncycle = { down = 0, moving = 1, up = 1 }").unwrap_err();
        assert!(e.contains("track.barriers[0].cycle.down = 0"), "{e}");
    }
}
