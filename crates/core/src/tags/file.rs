//! The tag map file, in the shape of seed 003's `map.yaml` (§1.2.3, §2.2):
//!
//! ```yaml
//! tags:        # id: {x, y, type, zone}; metres in the map frame
//!   508: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
//!   101: {x: 0.5, y: 0.0, type: waypoint, zone: A}
//! edges:       # from: [{to, direction, type}]
//!   508:
//!     - {to: 101, direction: forward, type: straight}
//! tasks:       # name: {waypoints: [...]}
//!   task1: {waypoints: [508, 101, 508]}
//! parameters:  # anything, read by dotted path ("speeds.linear")
//!   speeds: {linear: 0.3}
//! ```
//!
//! The seed names the fields but not their values; navdeck's are: a tag's `type` is
//! `dock`, `waypoint`, `pivot` (where a route turns 90 degrees) or `shelf` (a stop to
//! scan); its `zone` is `A`-`E` or `DOCK`, which fixes the heading a robot faces on it
//! (§2.5: A and DOCK +x, B and D +y, C and E -y). An edge's `direction` is how the robot
//! drives the leg (`forward` or `backward`, §2.3's two gains), its `type` `straight`
//! (along an aisle) or `pivot` (leaving the aisle after a turn). Legs run along the map's
//! axes.

use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;

/// An AprilTag's id (36h11 has 587).
pub type TagId = u32;

/// Where a robot's heading on a tag is fixed (seed 003 §2.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum Zone {
    A,
    B,
    C,
    D,
    E,
    #[serde(rename = "DOCK")]
    Dock,
}

impl Zone {
    /// The heading a robot faces on the zone's tags, radians (seed 003 §2.5: A and DOCK
    /// 0, B and D +pi/2, C and E -pi/2).
    pub fn heading(self) -> f64 {
        match self {
            Zone::A | Zone::Dock => 0.0,
            Zone::B | Zone::D => std::f64::consts::FRAC_PI_2,
            Zone::C | Zone::E => -std::f64::consts::FRAC_PI_2,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Zone::A => "A",
            Zone::B => "B",
            Zone::C => "C",
            Zone::D => "D",
            Zone::E => "E",
            Zone::Dock => "DOCK",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TagKind {
    Dock,
    Waypoint,
    Pivot,
    Shelf,
}

#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tag {
    pub x: f64,
    pub y: f64,
    #[serde(rename = "type")]
    pub kind: TagKind,
    pub zone: Zone,
}

/// How a leg is driven (seed 003 §2.3: forward at gain 1.0, backward at 0.8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    Forward,
    Backward,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EdgeKind {
    Straight,
    Pivot,
}

/// One edge out of a tag.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TagEdge {
    pub to: TagId,
    pub direction: Direction,
    #[serde(rename = "type")]
    pub kind: EdgeKind,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct TaskEntry {
    waypoints: Vec<TagId>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TagMapFile {
    tags: BTreeMap<TagId, Tag>,
    #[serde(default)]
    edges: BTreeMap<TagId, Vec<TagEdge>>,
    #[serde(default)]
    tasks: BTreeMap<String, TaskEntry>,
    #[serde(default)]
    parameters: Option<serde_norway::Value>,
}

/// A checked tag map.
#[derive(Clone, Debug)]
pub struct TagMap {
    pub tags: BTreeMap<TagId, Tag>,
    /// Edges out of each tag, in the file's order (BFS tries them in it).
    pub edges: BTreeMap<TagId, Vec<TagEdge>>,
    /// Each task's waypoints, in order.
    pub tasks: BTreeMap<String, Vec<TagId>>,
    pub dock: TagId,
    parameters: Option<serde_norway::Value>,
}

/// A tag map refused: where, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct TagMapError {
    /// 1-based line of the file, where one is known.
    pub line: Option<usize>,
    pub message: String,
}

impl fmt::Display for TagMapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

impl std::error::Error for TagMapError {}

/// How far a leg's end may stand off the axis it runs along, metres.
const AXIS_SLACK: f64 = 0.02;

impl TagMap {
    /// Reads and checks a tag map from its YAML `text`.
    pub fn parse(text: &str) -> Result<Self, TagMapError> {
        let file: TagMapFile = serde_norway::from_str(text).map_err(|e| {
            let line = e.location().map(|l| l.line());
            let message = e.to_string();
            // The line goes before the message, as for every other error.
            let message = match message.rfind(" at line ") {
                Some(at) if line.is_some() => message[..at].to_string(),
                _ => message,
            };
            TagMapError { line, message }
        })?;
        let lines = Lines(text);
        let fail = |line: Option<usize>, message: String| Err(TagMapError { line, message });
        for (&id, tag) in &file.tags {
            if !(tag.x.is_finite() && tag.y.is_finite()) {
                let line = lines.find("tags:", &[&format!("{id}:")]);
                return fail(line, format!("tag {id}: x and y must be finite numbers"));
            }
        }
        let docks: Vec<TagId> = (file.tags.iter())
            .filter(|(_, t)| t.kind == TagKind::Dock)
            .map(|(&id, _)| id)
            .collect();
        let dock = match docks[..] {
            [dock] => dock,
            [] => {
                return fail(
                    None,
                    "no tag has type dock: routes start and end at one".into(),
                );
            }
            _ => return fail(None, format!("tags {docks:?} are all docks: give one")),
        };
        for (&from, out) in &file.edges {
            let at = |to: Option<TagId>| {
                let from_key = format!("{from}:");
                match to {
                    Some(to) => {
                        let to_key = format!("to: {to}");
                        lines.find("edges:", &[&from_key, &to_key])
                    }
                    None => lines.find("edges:", &[&from_key]),
                }
            };
            let Some(a) = file.tags.get(&from) else {
                return fail(
                    at(None),
                    format!("edges from tag {from}: no tag {from} in tags"),
                );
            };
            for (i, edge) in out.iter().enumerate() {
                let to = edge.to;
                let Some(b) = file.tags.get(&to) else {
                    return fail(
                        at(Some(to)),
                        format!("edge {from} -> {to}: no tag {to} in tags"),
                    );
                };
                if to == from {
                    return fail(at(Some(to)), format!("edge {from} -> {to} leads to itself"));
                }
                if out[..i].iter().any(|e| e.to == to) {
                    return fail(at(Some(to)), format!("edge {from} -> {to} is given twice"));
                }
                let (dx, dy) = (b.x - a.x, b.y - a.y);
                if dx.hypot(dy) < AXIS_SLACK {
                    let message = format!("edge {from} -> {to}: the two tags stand together");
                    return fail(at(Some(to)), message);
                }
                if dx.abs().min(dy.abs()) > AXIS_SLACK {
                    let off = dy.atan2(dx).to_degrees();
                    let message = format!(
                        "edge {from} -> {to} runs at {off:.0} degrees: legs run along x or y"
                    );
                    return fail(at(Some(to)), message);
                }
            }
        }
        let mut map = TagMap {
            tags: file.tags,
            edges: file.edges,
            tasks: BTreeMap::new(),
            dock,
            parameters: file.parameters,
        };
        for (name, task) in file.tasks {
            let line = || lines.find("tasks:", &[&format!("{name}:")]);
            if task.waypoints.is_empty() {
                return fail(line(), format!("task {name} has no waypoints"));
            }
            if let Some(bad) = task.waypoints.iter().find(|w| !map.tags.contains_key(w)) {
                return fail(line(), format!("task {name}: waypoint {bad} is no tag"));
            }
            if let Err(e) = map.route(&task.waypoints, &Default::default()) {
                return fail(line(), format!("task {name}: {e}"));
            }
            map.tasks.insert(name, task.waypoints);
        }
        Ok(map)
    }

    /// A parameter by dotted path (seed 003 §1.2.3's `get_param`: "speeds.linear").
    pub fn param(&self, path: &str) -> Option<&serde_norway::Value> {
        let mut at = self.parameters.as_ref()?;
        for key in path.split('.') {
            at = at.get(key)?;
        }
        Some(at)
    }

    /// A number parameter, or `default` when it is absent.
    pub fn param_f64(&self, path: &str, default: f64) -> f64 {
        self.param(path).and_then(|v| v.as_f64()).unwrap_or(default)
    }

    /// The edge `from` -> `to`, if the map has one.
    pub fn edge(&self, from: TagId, to: TagId) -> Option<&TagEdge> {
        self.edges.get(&from)?.iter().find(|e| e.to == to)
    }
}

/// The file's text, for the line an error names.
struct Lines<'a>(&'a str);

impl Lines<'_> {
    /// The 1-based line of the last of `keys`, each looked for after the line of the one
    /// before it, within the top-level block that begins `section` ("edges:").
    fn find(&self, section: &str, keys: &[&str]) -> Option<usize> {
        let lines: Vec<&str> = self.0.lines().collect();
        let top = |l: &str| !l.trim().is_empty() && !l.starts_with([' ', '\t', '#']);
        let start = lines
            .iter()
            .position(|l| top(l) && l.starts_with(section))?;
        let end = (start + 1..lines.len())
            .find(|&i| top(lines[i]))
            .unwrap_or(lines.len());
        let mut at = start;
        for key in keys {
            at = (at..end).find(|&i| has_token(lines[i], key))?;
        }
        Some(at + 1)
    }
}

/// Whether `key` stands in `line` as a whole token: "101:" in "  101: {..}", not in
/// "1101: {..}"; "to: 10" in "{to: 10, ..}", not in "{to: 101, ..}".
fn has_token(line: &str, key: &str) -> bool {
    line.match_indices(key).any(|(i, _)| {
        let before = line[..i].chars().next_back();
        let after = line[i + key.len()..].chars().next();
        !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
            && !after.is_some_and(|c| c.is_ascii_digit())
    })
}

#[cfg(test)]
#[path = "file_tests.rs"]
mod tests;
