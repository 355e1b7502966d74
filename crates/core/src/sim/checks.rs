//! The rules a world file's content must keep, each failing with file, line, field and value.

use super::WorldError;
use crate::data::number::short;
use crate::geometry::Point2;
use crate::perception::markers::MarkerCategory;
use std::collections::HashMap;
use std::fmt::Display;
use std::ops::Range;
use std::path::Path;

/// Largest world side accepted, metres: beyond this a file is surely a typo (mm for m).
pub const MAX_WORLD_SIDE: f64 = 100.0;
/// Slack when testing points against the world bounds, metres.
const BOUNDS_SLACK: f64 = 1e-9;

/// Validation context: where errors point and which marker ids are taken.
pub struct Checker<'a> {
    path: &'a Path,
    text: &'a str,
    half: (f64, f64),
    /// id -> (field that placed it, its line)
    taken: HashMap<u32, (String, Option<usize>)>,
}

impl<'a> Checker<'a> {
    pub fn new(text: &'a str, path: &'a Path) -> Self {
        Self {
            path,
            text,
            half: (f64::INFINITY, f64::INFINITY),
            taken: HashMap::new(),
        }
    }

    /// 1-based line of a byte span in the file text.
    pub fn line(&self, span: Range<usize>) -> Option<usize> {
        let start = span.start.min(self.text.len());
        self.text
            .get(..start)
            .map(|before| before.matches('\n').count() + 1)
    }

    pub fn set_bounds(&mut self, width: f64, height: f64) {
        self.half = (width / 2.0, height / 2.0);
    }

    pub fn err(
        &self,
        line: Option<usize>,
        field: &str,
        value: impl Display,
        reason: impl Into<String>,
    ) -> WorldError {
        WorldError::Invalid {
            path: self.path.to_path_buf(),
            line,
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Refuses NaN and infinities (TOML allows `nan` and `inf`).
    pub fn finite(
        &self,
        line: Option<usize>,
        field: &str,
        values: &[f64],
    ) -> Result<(), WorldError> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(&v) if values.len() == 1 => {
                Err(self.err(line, field, short(v), "must be a finite number"))
            }
            Some(_) => Err(self.err(line, field, fmt_numbers(values), "must be a finite number")),
            None => Ok(()),
        }
    }

    pub fn positive(&self, line: Option<usize>, field: &str, value: f64) -> Result<(), WorldError> {
        self.finite(line, field, &[value])?;
        if value > 0.0 {
            Ok(())
        } else {
            Err(self.err(line, field, short(value), "must be greater than zero"))
        }
    }

    /// Refuses a point outside [-w/2, w/2] x [-h/2, h/2].
    pub fn inside(&self, line: Option<usize>, field: &str, p: Point2) -> Result<(), WorldError> {
        self.finite(line, field, &[p.x, p.y])?;
        if p.x.abs() <= self.half.0 + BOUNDS_SLACK && p.y.abs() <= self.half.1 + BOUNDS_SLACK {
            return Ok(());
        }
        let reason = format!(
            "lies outside the world, which spans [{}, {}] x [{}, {}]",
            short(-self.half.0),
            short(self.half.0),
            short(-self.half.1),
            short(self.half.1)
        );
        Err(self.err(line, field, fmt_point(p), reason))
    }

    /// Takes a marker id for `field`, refusing one already used anywhere in the file.
    pub fn claim(&mut self, line: Option<usize>, field: &str, id: u32) -> Result<(), WorldError> {
        if let Some((first, first_line)) = self.taken.get(&id) {
            let at = first_line.map_or_else(String::new, |l| format!(" (line {l})"));
            return Err(self.err(
                line,
                field,
                id,
                format!("duplicate marker id, already used by `{first}`{at}"),
            ));
        }
        self.taken.insert(id, (field.to_string(), line));
        Ok(())
    }

    /// Refuses an id whose seed 001 category is not one of `allowed`.
    pub fn category(
        &self,
        line: Option<usize>,
        field: &str,
        id: u32,
        allowed: &[MarkerCategory],
    ) -> Result<MarkerCategory, WorldError> {
        let cat = MarkerCategory::of(id);
        if allowed.contains(&cat) {
            return Ok(cat);
        }
        let want: Vec<String> = allowed.iter().map(|c| describe(*c)).collect();
        let reason = format!("id is {}; expected {}", describe(cat), want.join(" or "));
        Err(self.err(line, field, id, reason))
    }
}

/// A category with its id range (seed 001 section 1).
pub fn describe(cat: MarkerCategory) -> String {
    let range = match cat {
        MarkerCategory::Boundary => "1-300",
        MarkerCategory::Obstacle => "301-400",
        MarkerCategory::RedGate => "401-420",
        MarkerCategory::RedBlock => "421-450",
        MarkerCategory::BlueGate => "501-520",
        MarkerCategory::BlueBlock => "521-550",
        MarkerCategory::Unknown => return "outside every marker range of seed 001".to_string(),
    };
    let article = if cat == MarkerCategory::Obstacle {
        "an"
    } else {
        "a"
    };
    format!("{article} {} marker ({range})", cat.label())
}

/// A point as `[x, y]`, each printed short.
pub fn fmt_point(p: Point2) -> String {
    format!("[{}, {}]", short(p.x), short(p.y))
}

/// Numbers as `[a, b, c]`, each printed short.
pub fn fmt_numbers(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|&v| short(v)).collect();
    format!("[{}]", items.join(", "))
}

pub fn fmt_list<T: Display>(values: &[T]) -> String {
    let items: Vec<String> = values.iter().map(ToString::to_string).collect();
    format!("[{}]", items.join(", "))
}
