//! `[safety]`'s checks: every number in range, every shape a usable outline, every zone
//! named once. Fields are named as a user writes them: `polygons[1].radius`.

use super::config::{PolygonConfig, SafetyConfig};
use super::outline;
use crate::data::check::{self, Invalid};
use crate::geometry::Point2;

/// The most zones a `[safety]` section may hold (each is checked every control step).
pub const MAX_POLYGONS: usize = 16;
/// The most corners a zone's outline may have.
pub const MAX_CORNERS: usize = 64;
/// Zones reach at most this far from the robot's centre, metres: farther is a typo.
pub const FARTHEST_CORNER: f64 = 10.0;
/// An approach zone's prediction takes at most this many steps per check.
pub const MOST_STEPS: f64 = 10_000.0;

/// A zone's field names (a refusal names its field, and field names are static).
struct Fields {
    name: &'static str,
    points: &'static str,
    radius: &'static str,
    min_points: &'static str,
    slowdown_ratio: &'static str,
    linear_limit: &'static str,
    angular_limit: &'static str,
    time_before_collision: &'static str,
    simulation_time_step: &'static str,
}

macro_rules! fields {
    ($($k:literal)*) => {
        [$(Fields {
            name: concat!("polygons[", $k, "].name"),
            points: concat!("polygons[", $k, "].points"),
            radius: concat!("polygons[", $k, "].radius"),
            min_points: concat!("polygons[", $k, "].min_points"),
            slowdown_ratio: concat!("polygons[", $k, "].slowdown_ratio"),
            linear_limit: concat!("polygons[", $k, "].linear_limit"),
            angular_limit: concat!("polygons[", $k, "].angular_limit"),
            time_before_collision: concat!("polygons[", $k, "].time_before_collision"),
            simulation_time_step: concat!("polygons[", $k, "].simulation_time_step"),
        },)*]
    };
}

const FIELDS: [Fields; MAX_POLYGONS] =
    fields!("0" "1" "2" "3" "4" "5" "6" "7" "8" "9" "10" "11" "12" "13" "14" "15");

/// A zone name refused: the field (`polygons[1].name`), the name and why.
pub type NameProblem = (&'static str, String, String);

impl SafetyConfig {
    /// Checks what the parser cannot: (field, value, reason) for the first bad number or
    /// shape. Names are checked by `name_problem`, as a name is not a number.
    pub fn validate(&self) -> Result<(), Invalid> {
        check::within(&[("source_timeout", self.source_timeout, 0.01, 60.0)])?;
        self.health.validate()?;
        let count = self.polygons.len() as u64;
        check::counts_within(&[("polygons", count, 0, MAX_POLYGONS as u64)])?;
        for (polygon, fields) in self.polygons.iter().zip(&FIELDS) {
            check_polygon(polygon, fields)?;
        }
        Ok(())
    }

    /// The first zone whose name is empty or taken by an earlier zone, if any.
    pub fn name_problem(&self) -> Option<NameProblem> {
        for (k, (polygon, fields)) in self.polygons.iter().zip(&FIELDS).enumerate() {
            let name = &polygon.name;
            if name.trim().is_empty() {
                return Some((fields.name, name.clone(), "a zone needs a name".into()));
            }
            if let Some(first) = self.polygons[..k].iter().position(|p| &p.name == name) {
                let reason = format!("polygons[{first}] has that name already");
                return Some((fields.name, name.clone(), reason));
            }
        }
        None
    }
}

/// One zone's numbers and shape.
fn check_polygon(p: &PolygonConfig, f: &Fields) -> Result<(), Invalid> {
    check::counts_within(&[(f.min_points, u64::from(p.min_points), 1, 100_000)])?;
    check::all_probabilities(&[(f.slowdown_ratio, p.slowdown_ratio)])?;
    check::within(&[
        (f.linear_limit, p.linear_limit, 0.0, 10.0),
        (f.angular_limit, p.angular_limit, 0.0, 50.0),
        (f.time_before_collision, p.time_before_collision, 0.01, 60.0),
        (f.simulation_time_step, p.simulation_time_step, 0.001, 60.0),
    ])?;
    let (step, horizon) = (p.simulation_time_step, p.time_before_collision);
    if step > horizon {
        let reason = format!("must not exceed time_before_collision ({horizon})");
        return Err((f.simulation_time_step, step, reason.into()));
    }
    if horizon / step > MOST_STEPS {
        let reason = format!(
            "makes over {MOST_STEPS} steps of time_before_collision ({horizon}): take a longer step"
        );
        return Err((f.simulation_time_step, step, reason.into()));
    }
    match (&p.points, p.radius) {
        (Some(_), Some(radius)) => Err((
            f.radius,
            radius,
            "a zone is either points or a radius: set one of them".into(),
        )),
        (None, Some(radius)) => check::within(&[(f.radius, radius, 0.01, FARTHEST_CORNER)]),
        (Some(points), None) => check_outline(points, f),
        (None, None) => Ok(()),
    }
}

/// A zone's corners: enough of them, near the robot, and a simple polygon.
fn check_outline(points: &[[f64; 2]], f: &Fields) -> Result<(), Invalid> {
    let count = points.len() as u64;
    check::counts_within(&[(f.points, count, 3, MAX_CORNERS as u64)])?;
    for &[x, y] in points {
        check::within(&[
            (f.points, x, -FARTHEST_CORNER, FARTHEST_CORNER),
            (f.points, y, -FARTHEST_CORNER, FARTHEST_CORNER),
        ])?;
    }
    let corners: Vec<Point2> = points.iter().map(|&[x, y]| Point2::new(x, y)).collect();
    match outline::problem(&corners) {
        Some(reason) => Err((f.points, count as f64, reason.into())),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::collision_monitor::config::ActionType;

    fn with(polygon: PolygonConfig) -> SafetyConfig {
        let mut config = SafetyConfig::default();
        config.polygons.push(polygon);
        config
    }

    fn refusal(config: &SafetyConfig) -> (&'static str, f64) {
        let (field, value, _) = config.validate().unwrap_err();
        (field, value)
    }

    #[test]
    fn the_defaults_pass() {
        let config = SafetyConfig::default();
        assert_eq!(config.validate(), Ok(()));
        assert_eq!(config.name_problem(), None);
    }

    #[test]
    fn a_bad_number_is_named_with_its_zone() {
        let ratio = PolygonConfig {
            slowdown_ratio: 1.5,
            ..PolygonConfig::new("slow", ActionType::Slowdown).circle(0.3)
        };
        assert_eq!(refusal(&with(ratio)), ("polygons[3].slowdown_ratio", 1.5));
        let radius = PolygonConfig::new("stop2", ActionType::Stop).circle(-0.2);
        assert_eq!(refusal(&with(radius)), ("polygons[3].radius", -0.2));
        let time = PolygonConfig {
            time_before_collision: 0.0,
            ..PolygonConfig::new("near", ActionType::Approach)
        };
        assert_eq!(
            refusal(&with(time)),
            ("polygons[3].time_before_collision", 0.0)
        );
        let step = PolygonConfig {
            simulation_time_step: 3.0,
            ..PolygonConfig::new("near", ActionType::Approach)
        };
        assert_eq!(
            refusal(&with(step)),
            ("polygons[3].simulation_time_step", 3.0)
        );
        let never = PolygonConfig {
            min_points: 0,
            ..PolygonConfig::new("stop2", ActionType::Stop).circle(0.2)
        };
        assert_eq!(refusal(&with(never)), ("polygons[3].min_points", 0.0));
        let stale = SafetyConfig {
            source_timeout: f64::NAN,
            ..SafetyConfig::default()
        };
        assert_eq!(refusal(&stale).0, "source_timeout");
    }

    #[test]
    fn a_shape_must_be_one_simple_outline() {
        let both = PolygonConfig::new("x", ActionType::Stop).polygon(&[
            [0.3, 0.2],
            [0.3, -0.2],
            [0.0, 0.0],
        ]);
        let both = PolygonConfig {
            radius: Some(0.2),
            ..both
        };
        assert_eq!(refusal(&with(both)), ("polygons[3].radius", 0.2));
        let two = PolygonConfig::new("x", ActionType::Stop).polygon(&[[0.3, 0.2], [0.3, -0.2]]);
        assert_eq!(refusal(&with(two)), ("polygons[3].points", 2.0));
        let far = PolygonConfig::new("x", ActionType::Stop).polygon(&[
            [300.0, 0.2],
            [0.3, -0.2],
            [0.0, 0.0],
        ]);
        assert_eq!(refusal(&with(far)), ("polygons[3].points", 300.0));
        let bow_tie = PolygonConfig::new("x", ActionType::Stop).polygon(&[
            [0.0, 0.0],
            [0.4, 0.4],
            [0.4, 0.0],
            [0.0, 0.4],
        ]);
        let (field, value, reason) = with(bow_tie).validate().unwrap_err();
        assert_eq!((field, value), ("polygons[3].points", 4.0));
        assert!(reason.contains("cross"), "{reason}");
    }

    #[test]
    fn names_are_needed_and_told_apart() {
        let twice = with(PolygonConfig::new("stop", ActionType::Stop).circle(0.2));
        let (field, name, reason) = twice.name_problem().unwrap();
        assert_eq!((field, name.as_str()), ("polygons[3].name", "stop"));
        assert!(reason.contains("polygons[0]"), "{reason}");
        let blank = with(PolygonConfig::new(" ", ActionType::Stop).circle(0.2));
        assert_eq!(blank.name_problem().unwrap().0, "polygons[3].name");
    }

    #[test]
    fn too_many_zones_are_refused() {
        let mut config = SafetyConfig::default();
        for k in config.polygons.len()..=MAX_POLYGONS {
            let name = format!("zone {k}");
            config
                .polygons
                .push(PolygonConfig::new(&name, ActionType::Stop).circle(0.2));
        }
        assert_eq!(refusal(&config), ("polygons", (MAX_POLYGONS + 1) as f64));
    }
}
