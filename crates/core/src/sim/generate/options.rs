//! What a generated world is asked to be, the checks on that, and why generation fails.

use super::rules::{MAX_BLOCKS, MAX_OBSTACLES, MAX_SIDE, MIN_BLOCK_SPACING, WALL_CLEARANCE};
use std::fmt;
use std::str::FromStr;

/// The shape of a generated world's interior.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Style {
    /// Free-standing boxes in one room.
    #[default]
    Boxes,
    /// Interior walls split the area into 2-4 rooms joined by doorways.
    Rooms,
    /// Long interior walls make corridors joined at alternate ends.
    Corridors,
    /// One corridor all the way round a walled island.
    Loop,
}

impl Style {
    pub const ALL: [Style; 4] = [Style::Boxes, Style::Rooms, Style::Corridors, Style::Loop];

    pub fn label(self) -> &'static str {
        match self {
            Style::Boxes => "boxes",
            Style::Rooms => "rooms",
            Style::Corridors => "corridors",
            Style::Loop => "loop",
        }
    }

    /// Width and height when none is asked for, metres: seed 001's 4 m x 4 m arena for
    /// boxes; rooms and corridors need a little more to leave space for blocks; a loop
    /// needs its corridor on all four sides of an island.
    pub fn default_size(self) -> (f64, f64) {
        match self {
            Style::Boxes => (4.0, 4.0),
            Style::Rooms | Style::Corridors => (5.0, 4.0),
            Style::Loop => (6.0, 4.0),
        }
    }

    /// Smallest (longer side, shorter side) the style can be built in, metres: two rooms
    /// of 1.2 m, two corridors of 1 m beside a wall that leaves a 0.8 m turn, or a loop's
    /// 1 m corridor either side of a 0.5 m island (ring.rs).
    fn min_size(self) -> (f64, f64) {
        match self {
            Style::Boxes => (2.0, 2.0),
            Style::Rooms => (2.5, 2.0),
            Style::Corridors => (3.0, 2.0),
            Style::Loop => (2.5, 2.5),
        }
    }

    /// Whether `loops` changes this style: only rooms and corridors are trees without it.
    fn takes_loops(self) -> bool {
        matches!(self, Style::Rooms | Style::Corridors)
    }
}

impl fmt::Display for Style {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

impl FromStr for Style {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Style::ALL
            .into_iter()
            .find(|style| style.label() == s)
            .ok_or_else(|| format!("unknown style `{s}`: expected rooms, boxes, corridors or loop"))
    }
}

/// The options of one generated world; the same options give the same world.
#[derive(Clone, Debug, PartialEq)]
pub struct GenerateOptions {
    pub seed: u64,
    /// (width, height) in metres; `None`: the style's default.
    pub size: Option<(f64, f64)>,
    pub blocks: usize,
    /// Free-standing boxes, in every style.
    pub obstacles: usize,
    pub style: Style,
    /// Markers on the boundary, the interior walls and the boxes; without them only the
    /// blocks and the gates carry markers. The layout is the same either way.
    pub wall_markers: bool,
    /// Rooms and corridors with ways round: a second doorway in the walls between rooms,
    /// corridor walls free at both ends.
    pub loops: bool,
}

impl Default for GenerateOptions {
    fn default() -> Self {
        Self {
            seed: 1,
            size: None,
            blocks: 3,
            obstacles: 3,
            style: Style::Boxes,
            wall_markers: true,
            loops: false,
        }
    }
}

impl GenerateOptions {
    /// The width and height the world will have.
    pub fn size(&self) -> (f64, f64) {
        self.size.unwrap_or(self.style.default_size())
    }

    /// The world's name, e.g. `generated:boxes:7`, `generated:rooms:7:loops:bare` (with
    /// loops, without wall markers): each variant keeps its own autosaved map.
    pub fn name(&self) -> String {
        let loops = if self.loops { ":loops" } else { "" };
        let bare = if self.wall_markers { "" } else { ":bare" };
        format!("generated:{}:{}{loops}{bare}", self.style, self.seed)
    }

    /// Refuses options no world can satisfy, naming the option.
    pub fn validate(&self) -> Result<(), GenerateError> {
        let (w, h) = self.size();
        let size = || {
            use crate::data::number::short;
            format!("{},{}", short(w), short(h))
        };
        let bad = |option, value: String, reason: String| {
            Err(GenerateError::Option {
                option,
                value,
                reason,
            })
        };
        if !(w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0) {
            return bad(
                "size",
                size(),
                "must be two positive numbers of metres".into(),
            );
        }
        if w.max(h) > MAX_SIDE {
            let reason = format!("a side longer than {MAX_SIDE} m runs out of wall marker ids");
            return bad("size", size(), reason);
        }
        let (long, short) = self.style.min_size();
        if w.max(h) < long || w.min(h) < short {
            let reason = format!("{} need at least {long} m x {short} m", self.style.label());
            return bad("size", size(), reason);
        }
        if self.loops && !self.style.takes_loops() {
            let reason = "only rooms and corridors take loops (boxes and loop worlds have ways round already)";
            let value = format!("with {} worlds", self.style.label());
            return bad("loops", value, reason.into());
        }
        if self.blocks == 0 || self.blocks > MAX_BLOCKS {
            let reason = format!(
                "must lie in 1..={MAX_BLOCKS} (15 marker pairs per colour, seed 001 section 1)"
            );
            return bad("blocks", self.blocks.to_string(), reason);
        }
        if self.obstacles > MAX_OBSTACLES {
            let reason = format!(
                "must be at most {MAX_OBSTACLES} (four faces each in ids 301-400, seed 001 section 1)"
            );
            return bad("obstacles", self.obstacles.to_string(), reason);
        }
        // Blocks keep WALL_CLEARANCE from the walls and MIN_BLOCK_SPACING from each other:
        // at most one block per spacing-sided square of the inner area.
        let per_row = |side: f64| ((side - 2.0 * WALL_CLEARANCE) / MIN_BLOCK_SPACING).floor() + 1.0;
        let room = per_row(w).max(0.0) * per_row(h).max(0.0);
        if (self.blocks as f64) > room / 2.0 {
            let reason = format!(
                "too small for {} blocks, each {WALL_CLEARANCE} m from every wall and {MIN_BLOCK_SPACING} m from the next",
                self.blocks
            );
            return bad("size", size(), reason);
        }
        Ok(())
    }

    /// The command that makes this world, for a file's first line.
    pub fn command(&self) -> String {
        let (w, h) = self.size();
        let loops = if self.loops { " --loops" } else { "" };
        let bare = if self.wall_markers {
            ""
        } else {
            " --no-wall-markers"
        };
        format!(
            "navdeck world generate --seed {} --style {} --size {w},{h} --blocks {} --obstacles {}{loops}{bare}",
            self.seed, self.style, self.blocks, self.obstacles
        )
    }
}

/// Why no world was generated.
#[derive(Debug, thiserror::Error)]
pub enum GenerateError {
    /// An option no world can satisfy.
    #[error("option `{option}` = {value}: {reason}")]
    Option {
        option: &'static str,
        value: String,
        reason: String,
    },
    /// Every candidate drawn from the seed failed a check.
    #[error(
        "no {style} world for seed {seed} after {attempts} candidates; the last failed: {reason}"
    )]
    Exhausted {
        seed: u64,
        style: Style,
        attempts: usize,
        reason: String,
    },
    /// The world file written for a candidate was refused by the loader: a generator bug.
    #[error("the world generated for seed {seed} ({style}) does not load back: {reason}")]
    Unloadable {
        seed: u64,
        style: Style,
        reason: String,
    },
}
