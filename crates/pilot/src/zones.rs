//! Keepout and speed zones in the pilot: the zones themselves (kept with navigation),
//! the keepout layer they lay over the planning map, the speed cap on every command, and
//! the keepout edges the collision monitor treats as obstacles.

use super::Pilot;
use navdeck_core::data::Level;
use navdeck_core::geometry::{Point2, Twist};
use navdeck_core::map::zones::{Rect, Zone, ZoneList};

/// Keepout edges are handed to the collision monitor this far apart, metres.
const EDGE_STEP: f64 = 0.02;

/// What to do with the zones (`:zone`, the drawing keys, a map load).
#[derive(Clone, Debug, PartialEq)]
pub enum ZoneAsk {
    Add(Zone),
    /// Take out zone N (1-based, as `:zone list` numbers them).
    Delete(usize),
    Clear,
    /// The zones of a loaded map replace these; `source` names it in the log.
    Replace {
        zones: ZoneList,
        source: String,
    },
    /// More zones, from a Nav2 filter mask; `source` names it.
    Extend {
        zones: ZoneList,
        source: String,
    },
}

/// The zones and what the pilot remembers about applying them.
#[derive(Clone, Debug, Default)]
pub(super) struct Zones {
    pub list: ZoneList,
    /// Grows with every change, so the planning map's keepout layer can tell it is stale.
    pub tag: u64,
    /// The speed limit being kept, m/s, for logging once when it starts and stops.
    pub limiting: Option<f64>,
}

impl Pilot {
    /// The keepout and speed zones.
    pub fn zones(&self) -> &ZoneList {
        &self.nav.zones.list
    }

    /// The speed limit the zones impose now, m/s, if any.
    pub fn zone_speed_limit(&self) -> Option<f64> {
        self.nav.zones.limiting
    }

    pub(super) fn ask_zones(&mut self, ask: ZoneAsk) {
        let zones = &mut self.nav.zones;
        match ask {
            ZoneAsk::Add(zone) => match zones.list.push(zone) {
                Ok(()) => {
                    let n = zones.list.len();
                    self.log(Level::Success, format!("zone {n}: {}", zone.label()));
                }
                Err(e) => {
                    self.log(Level::Error, format!("zone refused: {e}"));
                    return;
                }
            },
            ZoneAsk::Delete(n) => match n.checked_sub(1).and_then(|k| zones.list.remove(k)) {
                Some(zone) => self.log(Level::Info, format!("zone {n} deleted: {}", zone.label())),
                None => {
                    let have = zones.list.len();
                    self.log(
                        Level::Error,
                        format!("no zone {n}: there are {have} (:zone list numbers them)"),
                    );
                    return;
                }
            },
            ZoneAsk::Clear => {
                let n = zones.list.len();
                zones.list = ZoneList::default();
                self.log(Level::Info, format!("{n} zones cleared"));
            }
            ZoneAsk::Replace { zones: new, source } => {
                let n = new.len();
                zones.list = new;
                self.log(Level::Info, format!("{n} zones from {source}"));
            }
            ZoneAsk::Extend { zones: new, source } => {
                let n = new.len();
                if let Err(e) = zones.list.extend(new) {
                    self.log(Level::Error, format!("zones of {source} refused: {e}"));
                    return;
                }
                self.log(Level::Success, format!("{n} zones added from {source}"));
            }
        }
        self.nav.zones.tag += 1;
        self.sync_keepout();
    }

    /// Lays the keepout zones over the planning map when it does not show them yet (they
    /// changed, or the map was made anew).
    pub(super) fn sync_keepout(&mut self) {
        let zones = &self.nav.zones;
        if self.belief.keepout_tag() == zones.tag {
            return;
        }
        let rects: Vec<Rect> = zones.list.keepouts().copied().collect();
        self.belief.set_keepout(zones.tag, &rects);
    }

    /// The keepout zone `goal` lies in, 1-based, if any.
    pub(super) fn keepout_holding(&self, goal: Point2) -> Option<usize> {
        let zones = self.nav.zones.list.zones();
        zones
            .iter()
            .position(|z| {
                z.kind == navdeck_core::map::zones::ZoneKind::Keepout && z.rect.contains(goal)
            })
            .map(|k| k + 1)
    }

    /// `twist` kept under the speed limit of any speed zone the robot's footprint is in,
    /// or will be in before it could brake (Nav2's speed filter limits the controller).
    pub(super) fn zone_speed_cap(&mut self, twist: Twist) -> Twist {
        if self.nav.zones.list.is_empty() && self.nav.zones.limiting.is_none() {
            return twist;
        }
        let r = &self.settings.robot;
        let v = self
            .measuring
            .commanded
            .linear
            .abs()
            .max(twist.linear.abs());
        // Braking distance at constant deceleration, v^2 / 2a, and one period's travel.
        let reach = r.footprint_radius + v * v / (2.0 * r.max_linear_accel) + v * r.control_period;
        let limit =
            (self.nav.zones.list).speed_limit_near(self.pose().position(), reach, r.max_linear);
        if limit != self.nav.zones.limiting {
            match limit {
                Some(l) => self.log(Level::Info, format!("speed zone: keeping under {l:.2} m/s")),
                None => self.log(Level::Info, "speed zone left: no zone speed limit"),
            }
            self.nav.zones.limiting = limit;
        }
        match limit {
            Some(l) => cap(twist, l),
            None => twist,
        }
    }

    /// Points along the keepout zones' edges within `radius` of the robot, in its frame:
    /// the collision monitor's obstacles whether a scan shows them or not.
    pub(crate) fn keepout_points(&self, radius: f64) -> Vec<Point2> {
        let pose = self.pose();
        let here = pose.position();
        let mut points = Vec::new();
        for r in self.nav.zones.list.keepouts() {
            if r.distance(here) > radius {
                continue;
            }
            let corners = [
                Point2::new(r.x0, r.y0),
                Point2::new(r.x1, r.y0),
                Point2::new(r.x1, r.y1),
                Point2::new(r.x0, r.y1),
            ];
            for (k, &a) in corners.iter().enumerate() {
                let b = corners[(k + 1) % 4];
                let n = ((a.distance(b) / EDGE_STEP).ceil() as usize).max(1);
                for i in 0..n {
                    let t = i as f64 / n as f64;
                    let p = Point2::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t);
                    if p.distance(here) <= radius {
                        points.push(pose.inverse_transform_point(p));
                    }
                }
            }
        }
        points
    }
}

/// `twist` with its linear speed at most `limit`, the turn rate scaled alike so the robot
/// keeps its curvature (a turn on the spot keeps its rate).
pub fn cap(twist: Twist, limit: f64) -> Twist {
    let v = twist.linear.abs();
    if v <= limit || v == 0.0 {
        return twist;
    }
    // Scaling v and w by one factor keeps the curvature w / v.
    let k = limit / v;
    Twist {
        linear: twist.linear * k,
        angular: twist.angular * k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cap_keeps_curvature_and_spins() {
        let t = cap(
            Twist {
                linear: -0.4,
                angular: 1.0,
            },
            0.1,
        );
        assert!((t.linear + 0.1).abs() < 1e-12);
        assert!((t.angular - 0.25).abs() < 1e-12);
        let spin = Twist {
            linear: 0.0,
            angular: 2.0,
        };
        assert_eq!(cap(spin, 0.1), spin);
        let slow = Twist {
            linear: 0.05,
            angular: 0.3,
        };
        assert_eq!(cap(slow, 0.1), slow);
    }
}
