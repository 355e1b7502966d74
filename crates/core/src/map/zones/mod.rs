//! Keepout and speed zones (Nav2's costmap filters): rectangles in the map frame where the
//! robot may never go, or must keep under a speed. Saved beside a map as Nav2 filter
//! masks (mask.rs), rasterised from them (raster.rs).

pub mod mask;
pub mod raster;

use crate::geometry::Point2;

/// Coordinates beyond this many metres from the origin are refused (a map's own bound).
const MAX_COORD: f64 = 1.0e5;
/// The most zones a list holds: a painted Nav2 mask decomposes into many rectangles.
pub const MAX_ZONES: usize = 20_000;

/// A speed limit, as Nav2's speed filter gives it (`type` 2: m/s, `type` 1: percent).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpeedLimit {
    MetresPerSecond(f64),
    /// Percent of the robot's maximum linear speed.
    Percent(f64),
}

impl SpeedLimit {
    /// The limit in m/s for a robot whose top speed is `max_speed`.
    pub fn metres_per_second(self, max_speed: f64) -> f64 {
        match self {
            SpeedLimit::MetresPerSecond(v) => v,
            // Nav2 SpeedFilter: a percent limit is that share of the maximum speed.
            SpeedLimit::Percent(p) => max_speed * p / 100.0,
        }
    }

    pub fn label(self) -> String {
        match self {
            SpeedLimit::MetresPerSecond(v) => format!("{v:.2} m/s"),
            SpeedLimit::Percent(p) => format!("{p:.0}% of top speed"),
        }
    }
}

/// What a zone asks of the robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ZoneKind {
    /// Never planned through, never driven into (Nav2's keepout filter, lethal cost).
    Keepout,
    /// The robot keeps under this speed while its footprint is in the zone.
    Speed(SpeedLimit),
}

/// An axis-aligned rectangle in the map frame, corners ordered (x0 < x1, y0 < y1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    /// The rectangle with corners `a` and `b`, in either order.
    pub fn from_corners(a: Point2, b: Point2) -> Self {
        Self {
            x0: a.x.min(b.x),
            y0: a.y.min(b.y),
            x1: a.x.max(b.x),
            y1: a.y.max(b.y),
        }
    }

    pub fn contains(&self, p: Point2) -> bool {
        (self.x0..=self.x1).contains(&p.x) && (self.y0..=self.y1).contains(&p.y)
    }

    /// Distance from `p` to the rectangle, 0 inside it.
    pub fn distance(&self, p: Point2) -> f64 {
        // Euclidean distance to an axis-aligned box: the per-axis excess, combined.
        let dx = (self.x0 - p.x).max(0.0).max(p.x - self.x1);
        let dy = (self.y0 - p.y).max(0.0).max(p.y - self.y1);
        dx.hypot(dy)
    }

    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }
}

/// One zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zone {
    pub kind: ZoneKind,
    pub rect: Rect,
}

impl Zone {
    pub fn keepout(rect: Rect) -> Self {
        Self {
            kind: ZoneKind::Keepout,
            rect,
        }
    }

    pub fn speed(limit: SpeedLimit, rect: Rect) -> Self {
        Self {
            kind: ZoneKind::Speed(limit),
            rect,
        }
    }

    /// How the log and `:zone list` name it.
    pub fn label(&self) -> String {
        let r = &self.rect;
        let what = match self.kind {
            ZoneKind::Keepout => "keepout".to_string(),
            ZoneKind::Speed(limit) => format!("speed {}", limit.label()),
        };
        format!(
            "{what} ({:.2}, {:.2})..({:.2}, {:.2})",
            r.x0, r.y0, r.x1, r.y1
        )
    }

    /// The zone's values in their bounds; the error names the field and its value.
    pub fn validate(&self) -> Result<(), ZoneError> {
        let r = &self.rect;
        for (field, value) in [("x0", r.x0), ("y0", r.y0), ("x1", r.x1), ("y1", r.y1)] {
            if !value.is_finite() || value.abs() > MAX_COORD {
                return Err(ZoneError::field(
                    field,
                    value,
                    "must be a number within ±100000 m",
                ));
            }
        }
        if r.x1 <= r.x0 {
            return Err(ZoneError::field(
                "x1",
                r.x1,
                "must lie beyond x0: the zone has no width",
            ));
        }
        if r.y1 <= r.y0 {
            return Err(ZoneError::field(
                "y1",
                r.y1,
                "must lie beyond y0: the zone has no height",
            ));
        }
        match self.kind {
            ZoneKind::Keepout => Ok(()),
            ZoneKind::Speed(SpeedLimit::MetresPerSecond(v)) if !(v > 0.0 && v <= 10.0) => {
                Err(ZoneError::field(
                    "speed",
                    v,
                    "must lie in (0, 10] m/s (0 means no limit in Nav2)",
                ))
            }
            ZoneKind::Speed(SpeedLimit::Percent(p)) if !(p > 0.0 && p <= 100.0) => {
                Err(ZoneError::field("percent", p, "must lie in (0, 100]"))
            }
            ZoneKind::Speed(_) => Ok(()),
        }
    }
}

/// Why a zone was refused: the field and its value.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ZoneError {
    #[error("zone field `{field}` = {value}: {reason}")]
    Field {
        field: &'static str,
        value: String,
        reason: &'static str,
    },
    #[error("too many zones: {0} (at most {MAX_ZONES})")]
    TooMany(usize),
}

impl ZoneError {
    fn field(field: &'static str, value: f64, reason: &'static str) -> Self {
        ZoneError::Field {
            field,
            value: crate::data::number::short(value),
            reason,
        }
    }
}

/// The zones of one map, in the order they were made.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZoneList {
    zones: Vec<Zone>,
}

impl ZoneList {
    /// A list of checked zones; the first bad one is named.
    pub fn new(zones: Vec<Zone>) -> Result<Self, ZoneError> {
        if zones.len() > MAX_ZONES {
            return Err(ZoneError::TooMany(zones.len()));
        }
        for z in &zones {
            z.validate()?;
        }
        Ok(Self { zones })
    }

    pub fn zones(&self) -> &[Zone] {
        &self.zones
    }

    pub fn is_empty(&self) -> bool {
        self.zones.is_empty()
    }

    pub fn len(&self) -> usize {
        self.zones.len()
    }

    /// Adds a zone once it is checked.
    pub fn push(&mut self, zone: Zone) -> Result<(), ZoneError> {
        zone.validate()?;
        if self.zones.len() >= MAX_ZONES {
            return Err(ZoneError::TooMany(self.zones.len() + 1));
        }
        self.zones.push(zone);
        Ok(())
    }

    /// Takes out zone `index` (0-based), if there is one.
    pub fn remove(&mut self, index: usize) -> Option<Zone> {
        (index < self.zones.len()).then(|| self.zones.remove(index))
    }

    /// Appends every zone of `other`.
    pub fn extend(&mut self, other: ZoneList) -> Result<(), ZoneError> {
        if self.zones.len() + other.zones.len() > MAX_ZONES {
            return Err(ZoneError::TooMany(self.zones.len() + other.zones.len()));
        }
        self.zones.extend(other.zones);
        Ok(())
    }

    pub fn keepouts(&self) -> impl Iterator<Item = &Rect> {
        self.zones
            .iter()
            .filter(|z| z.kind == ZoneKind::Keepout)
            .map(|z| &z.rect)
    }

    /// Whether `p` lies in a keepout zone.
    pub fn in_keepout(&self, p: Point2) -> bool {
        self.keepouts().any(|r| r.contains(p))
    }

    /// The strictest speed limit (m/s) of the speed zones within `reach` of `p` (the
    /// footprint's radius and any margin), for a robot whose top speed is `max_speed`.
    pub fn speed_limit_near(&self, p: Point2, reach: f64, max_speed: f64) -> Option<f64> {
        self.zones
            .iter()
            .filter_map(|z| match z.kind {
                ZoneKind::Speed(limit) if z.rect.distance(p) <= reach => {
                    Some(limit.metres_per_second(max_speed))
                }
                _ => None,
            })
            .reduce(f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Rect {
        Rect { x0, y0, x1, y1 }
    }

    #[test]
    fn corners_in_any_order_make_one_rectangle() {
        let r = Rect::from_corners(Point2::new(1.0, -1.0), Point2::new(-1.0, 2.0));
        assert_eq!(r, rect(-1.0, -1.0, 1.0, 2.0));
        assert!(r.contains(Point2::new(0.0, 0.0)));
        assert_eq!(r.distance(Point2::new(0.0, 0.0)), 0.0);
        // 3-4-5 from the corner (1, 2).
        assert!((r.distance(Point2::new(4.0, 6.0)) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_bad_zone_names_its_field() {
        let flat = Zone::keepout(rect(0.0, 1.0, 2.0, 1.0));
        let e = flat.validate().unwrap_err().to_string();
        assert!(e.contains("`y1` = 1"), "{e}");
        let nan = Zone::keepout(rect(f64::NAN, 0.0, 1.0, 1.0));
        assert!(nan.validate().unwrap_err().to_string().contains("`x0`"));
        let stopped = Zone::speed(SpeedLimit::MetresPerSecond(0.0), rect(0.0, 0.0, 1.0, 1.0));
        let e = stopped.validate().unwrap_err().to_string();
        assert!(e.contains("`speed` = 0"), "{e}");
        let over = Zone::speed(SpeedLimit::Percent(150.0), rect(0.0, 0.0, 1.0, 1.0));
        assert!(
            over.validate()
                .unwrap_err()
                .to_string()
                .contains("`percent` = 150")
        );
    }

    #[test]
    fn the_strictest_near_limit_applies() {
        let zones = ZoneList::new(vec![
            Zone::speed(SpeedLimit::MetresPerSecond(0.2), rect(0.0, 0.0, 1.0, 1.0)),
            Zone::speed(SpeedLimit::Percent(50.0), rect(0.5, 0.0, 2.0, 1.0)),
            Zone::keepout(rect(5.0, 5.0, 6.0, 6.0)),
        ])
        .unwrap();
        // Inside both: 50 % of 0.3 m/s = 0.15 m/s is the stricter.
        let v = zones
            .speed_limit_near(Point2::new(0.7, 0.5), 0.0, 0.3)
            .unwrap();
        assert!((v - 0.15).abs() < 1e-12);
        // 0.1 m left of the first: only within reach 0.105.
        assert_eq!(
            zones.speed_limit_near(Point2::new(-0.1, 0.5), 0.05, 0.3),
            None
        );
        assert_eq!(
            zones.speed_limit_near(Point2::new(-0.1, 0.5), 0.105, 0.3),
            Some(0.2)
        );
        assert!(zones.in_keepout(Point2::new(5.5, 5.5)));
        assert!(!zones.in_keepout(Point2::new(4.9, 5.5)));
    }

    #[test]
    fn the_planner_goes_round_a_keepout_zone_and_never_into_one() {
        use crate::map::belief::BeliefMap;
        use crate::map::config::MapConfig;
        use crate::plan::config::PlanConfig;
        use crate::plan::pipeline::Planner;
        let mut belief = BeliefMap::new(&MapConfig::default(), (4.0, 4.0));
        let keepout = rect(-0.3, -1.0, 0.3, 1.0);
        belief.set_keepout(1, &[keepout]);
        assert_eq!(belief.keepout_tag(), 1);
        let (start, goal) = (Point2::new(-1.5, 0.0), Point2::new(1.5, 0.0));
        let config = PlanConfig::default();
        let plan = Planner::default()
            .plan(belief.costmap(), start, goal, &config)
            .expect("a way round the zone");
        // Every pose clears the zone by the lethal radius (0.15 m), less a cell.
        for p in &plan.trajectory.points {
            assert!(keepout.distance(p.position) >= 0.14, "{:?}", p.position);
        }
        assert!(
            plan.length > 3.0 + 0.5,
            "it went round: {:.2} m",
            plan.length
        );
        // A goal inside the zone has no path; the zone cleared, the straight line is back.
        let inside =
            Planner::default().plan(belief.costmap(), start, Point2::new(0.0, 0.5), &config);
        assert!(inside.is_err());
        belief.set_keepout(2, &[]);
        let straight = Planner::default()
            .plan(belief.costmap(), start, goal, &config)
            .unwrap();
        assert!(straight.length < 3.05, "{:.2} m", straight.length);
    }
}
