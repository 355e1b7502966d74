//! Keepout and speed zones in the console: `:zone …` typed, or drawn in thinking mode
//! with the goal cursor as RViz's tools draw (a key at one corner, the same key at the
//! opposite corner), listed in the log, and read from a Nav2 filter mask.

use super::App;
use super::command::Typed;
use super::log::Level;
use crate::geometry::Point2;
use crate::map::zones::{Rect, SpeedLimit, Zone, mask};
use crate::pilot::{self, zones::ZoneAsk};
use std::path::PathBuf;

/// A drawn speed zone's limit until `:zone speed V …` sets another, m/s.
const DEFAULT_DRAWN_SPEED: f64 = 0.1;

/// What `:zone` asks.
#[derive(Clone, Debug, PartialEq)]
pub enum ZoneTyped {
    Ask(ZoneAsk),
    List,
    /// `zone load FILE`: a Nav2 filter info file (its mask beside it).
    Load(String),
}

/// The zone being drawn: its first corner and whether it is a speed zone, and the limit a
/// drawn speed zone gets.
#[derive(Clone, Debug)]
pub struct Drawing {
    anchor: Option<(Point2, bool)>,
    speed: f64,
}

impl Default for Drawing {
    fn default() -> Self {
        Self {
            anchor: None,
            speed: DEFAULT_DRAWN_SPEED,
        }
    }
}

impl Drawing {
    /// The first corner placed, while a zone is being drawn.
    pub fn anchor(&self) -> Option<(Point2, bool)> {
        self.anchor
    }
}

pub const WANTS: &str = "zone wants keepout X0 Y0 X1 Y1 | speed V X0 Y0 X1 Y1 (V in m/s, or N%) | list | delete N | clear | load FILE";

/// `zone …`.
pub fn parse(words: &[&str]) -> Result<Typed, String> {
    let number = |s: &str| {
        s.trim_end_matches(',')
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && v.abs() <= 1.0e5)
            .ok_or_else(|| format!("zone: `{s}` is not a number"))
    };
    let rect = |c: &[&str]| -> Result<Rect, String> {
        let a = Point2::new(number(c[0])?, number(c[1])?);
        let b = Point2::new(number(c[2])?, number(c[3])?);
        Ok(Rect::from_corners(a, b))
    };
    let zone = |z: Zone| match z.validate() {
        Ok(()) => Ok(Typed::Zone(ZoneTyped::Ask(ZoneAsk::Add(z)))),
        Err(e) => Err(format!("zone: {e}")),
    };
    match words {
        ["keepout", c @ ..] if c.len() == 4 => zone(Zone::keepout(rect(c)?)),
        ["speed", v, c @ ..] if c.len() == 4 => {
            let limit = match v.strip_suffix('%') {
                Some(p) => SpeedLimit::Percent(number(p)?),
                None => SpeedLimit::MetresPerSecond(number(v)?),
            };
            zone(Zone::speed(limit, rect(c)?))
        }
        ["list"] | [] => Ok(Typed::Zone(ZoneTyped::List)),
        ["clear"] => Ok(Typed::Zone(ZoneTyped::Ask(ZoneAsk::Clear))),
        ["delete", n] => n
            .parse::<usize>()
            .ok()
            .filter(|n| *n >= 1)
            .map(|n| Typed::Zone(ZoneTyped::Ask(ZoneAsk::Delete(n))))
            .ok_or_else(|| format!("zone delete: `{n}` is not a zone number (1, 2, …)")),
        ["load", file] => Ok(Typed::Zone(ZoneTyped::Load(file.to_string()))),
        _ => Err(WANTS.to_string()),
    }
}

impl App {
    /// The zone being drawn with the cursor.
    pub fn zone_drawing(&self) -> &Drawing {
        &self.zone_drawing
    }

    pub(super) fn apply_zone(&mut self, typed: ZoneTyped) {
        match typed {
            ZoneTyped::Ask(ask) => {
                if let ZoneAsk::Add(Zone {
                    kind: crate::map::zones::ZoneKind::Speed(SpeedLimit::MetresPerSecond(v)),
                    ..
                }) = ask
                {
                    // The next drawn speed zone keeps the last typed limit.
                    self.zone_drawing.speed = v;
                }
                self.run_intent(pilot::Intent::Zones(ask));
            }
            ZoneTyped::List => self.show_zones(),
            ZoneTyped::Load(file) => self.load_zones(&file),
        }
    }

    /// The zone key at the cursor: the first press places a corner, the second (the same
    /// key) the opposite one and makes the zone; the other zone key starts afresh.
    pub(super) fn zone_corner(&mut self, speed: bool) {
        let at = self
            .cursor
            .unwrap_or_else(|| self.pilot().estimated_pose().position());
        let what = if speed { "speed" } else { "keepout" };
        match self.zone_drawing.anchor.take() {
            Some((first, kind)) if kind == speed => {
                let rect = Rect::from_corners(first, at);
                let zone = if speed {
                    Zone::speed(SpeedLimit::MetresPerSecond(self.zone_drawing.speed), rect)
                } else {
                    Zone::keepout(rect)
                };
                self.run_intent(pilot::Intent::Zones(ZoneAsk::Add(zone)));
            }
            _ => {
                self.zone_drawing.anchor = Some((at, speed));
                self.log(
                    Level::Info,
                    format!(
                        "{what} zone: corner at ({:.2}, {:.2}); move the cursor to the opposite corner and press the key again",
                        at.x, at.y
                    ),
                );
            }
        }
    }

    /// The zones saved beside the map `map_yaml` (its Nav2 filter masks) replace the
    /// pilot's; a map without masks leaves none.
    pub fn load_zones_beside(&mut self, map_yaml: &std::path::Path) {
        match mask::load_beside(map_yaml) {
            Ok(zones) if zones.is_empty() && self.pilot().zones().is_empty() => {}
            Ok(zones) => self.run_intent(pilot::Intent::Zones(ZoneAsk::Replace {
                zones,
                source: format!("the masks beside {}", map_yaml.display()),
            })),
            Err(e) => self.log(Level::Error, format!("zones not loaded: {e}")),
        }
    }

    /// `:zone list`: every zone, numbered for `:zone delete N`.
    fn show_zones(&mut self) {
        let zones = self.pilot().zones().clone();
        if zones.is_empty() {
            return self.log(
                Level::Info,
                "no zones: :zone keepout X0 Y0 X1 Y1, :zone speed V X0 Y0 X1 Y1, or z / Z in thinking mode",
            );
        }
        for (k, z) in zones.zones().iter().enumerate() {
            self.log(Level::Info, format!("zone {}: {}", k + 1, z.label()));
        }
    }

    /// `:zone load FILE`: a Nav2 filter info file (in the maps folder unless a path).
    fn load_zones(&mut self, file: &str) {
        let path = if file.contains('/') {
            PathBuf::from(file)
        } else {
            match &self.files.maps_dir {
                Some(dir) => dir.join(file),
                None => PathBuf::from(file),
            }
        };
        let read = mask::read_filter(&path, &mut |p| {
            crate::data::files::read_limited(p, crate::data::files::MAP_IMAGE_LIMIT)
        });
        match read {
            Ok(zones) => self.run_intent(pilot::Intent::Zones(ZoneAsk::Extend {
                zones,
                source: path.display().to_string(),
            })),
            Err(e) => self.log(Level::Error, format!("zones not loaded: {e}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_zone_commands() {
        let keepout = parse(&["keepout", "1", "2", "0", "0.5"]).unwrap();
        let want = Zone::keepout(Rect::from_corners(
            Point2::new(0.0, 0.5),
            Point2::new(1.0, 2.0),
        ));
        assert_eq!(keepout, Typed::Zone(ZoneTyped::Ask(ZoneAsk::Add(want))));
        let pct = parse(&["speed", "40%", "0", "0", "1", "1"]).unwrap();
        assert!(matches!(
            pct,
            Typed::Zone(ZoneTyped::Ask(ZoneAsk::Add(Zone {
                kind: crate::map::zones::ZoneKind::Speed(SpeedLimit::Percent(p)),
                ..
            }))) if p == 40.0
        ));
        assert!(
            parse(&["speed", "0", "0", "0", "1", "1"])
                .unwrap_err()
                .contains("`speed` = 0")
        );
        assert!(
            parse(&["keepout", "0", "0", "0", "1"])
                .unwrap_err()
                .contains("`x1`")
        );
        assert!(
            parse(&["keepout", "a", "0", "1", "1"])
                .unwrap_err()
                .contains("`a`")
        );
        assert!(parse(&["delete", "0"]).is_err());
        assert_eq!(
            parse(&["delete", "2"]),
            Ok(Typed::Zone(ZoneTyped::Ask(ZoneAsk::Delete(2))))
        );
        assert_eq!(parse(&["list"]), Ok(Typed::Zone(ZoneTyped::List)));
    }
}
