//! What a generated world is asked to be, the checks on that, and why generation fails.

use super::rules::{
    DOORWAYS, MARKER_SPACING, MARKER_SPACINGS, MAX_BLOCKS, MAX_OBSTACLES, MAX_PER_COLOUR, MAX_SIDE,
    MIN_BLOCK_SPACING, MIN_ROOM, WALL_CLEARANCE,
};
use crate::data::number::short;
use crate::sim::BlockColor;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::fmt;
use std::str::FromStr;

/// How the blocks' colours are chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Colours {
    /// Red, blue, red, ...
    #[default]
    Alternating,
    /// Each block red or blue at random (seeded), a gate's drop places at most of one.
    Random,
    /// Every block red: one gate takes them all.
    One,
}

impl Colours {
    pub const ALL: [Colours; 3] = [Colours::Alternating, Colours::Random, Colours::One];

    pub fn label(self) -> &'static str {
        match self {
            Colours::Alternating => "alternating",
            Colours::Random => "random",
            Colours::One => "one",
        }
    }

    /// The colour of each of `count` blocks, in turn (drawn from `rng` when random, at
    /// most `MAX_PER_COLOUR` of either: a colour that is full gives way to the other).
    pub fn draw(self, count: usize, rng: &mut ChaCha8Rng) -> Vec<BlockColor> {
        let mut colours = Vec::with_capacity(count);
        for i in 0..count {
            let red = match self {
                Colours::Alternating => i % 2 == 0,
                Colours::One => true,
                Colours::Random => {
                    let reds = colours.iter().filter(|&&c| c == BlockColor::Red).count();
                    let blues = i - reds;
                    let drawn = rng.random_bool(0.5);
                    (drawn && reds < MAX_PER_COLOUR) || blues >= MAX_PER_COLOUR
                }
            };
            colours.push(if red {
                BlockColor::Red
            } else {
                BlockColor::Blue
            });
        }
        colours
    }

    /// The most blocks a world of these colours holds.
    fn max_blocks(self) -> usize {
        match self {
            Colours::One => MAX_PER_COLOUR,
            Colours::Alternating | Colours::Random => MAX_BLOCKS,
        }
    }
}

impl fmt::Display for Colours {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

impl FromStr for Colours {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Colours::ALL
            .into_iter()
            .find(|c| c.label() == s)
            .ok_or_else(|| format!("unknown colours `{s}`: expected alternating, random or one"))
    }
}

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
    /// A closed lane with traffic lights and barriers in a walled room, for lane
    /// following (seed 000): no blocks, gates, boxes or markers.
    Track,
}

impl Style {
    /// The styles of mission worlds, with blocks and gates.
    pub const ALL: [Style; 4] = [Style::Boxes, Style::Rooms, Style::Corridors, Style::Loop];
    /// Every style a user can name: the mission worlds' and the lane track.
    pub const NAMED: [Style; 5] = [
        Style::Boxes,
        Style::Rooms,
        Style::Corridors,
        Style::Loop,
        Style::Track,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Style::Boxes => "boxes",
            Style::Rooms => "rooms",
            Style::Corridors => "corridors",
            Style::Loop => "loop",
            Style::Track => "track",
        }
    }

    /// Width and height when none is asked for, metres: seed 001's 4 m x 4 m arena for
    /// boxes; rooms and corridors need a little more to leave space for blocks; a loop
    /// needs its corridor on all four sides of an island; a track is drawn from 4-8 m a
    /// side when none is asked for, about seed 000's 6 m x 4 m course.
    pub fn default_size(self) -> (f64, f64) {
        match self {
            Style::Boxes => (4.0, 4.0),
            Style::Rooms | Style::Corridors => (5.0, 4.0),
            Style::Loop | Style::Track => (6.0, 4.0),
        }
    }

    /// Smallest (longer side, shorter side) the style can be built in, metres: two rooms
    /// of 1.2 m, two corridors of 1 m beside a wall that leaves a 0.8 m turn, or a loop's
    /// 1 m corridor either side of a 0.5 m island (ring.rs), or a lane whose bends, start
    /// straight and spaced lights and barriers fit 0.3 m inside the walls (track.rs).
    fn min_size(self) -> (f64, f64) {
        match self {
            Style::Boxes => (2.0, 2.0),
            Style::Rooms => (2.5, 2.0),
            Style::Corridors => (3.0, 2.0),
            Style::Loop => (2.5, 2.5),
            Style::Track => (4.0, 3.5),
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
        Style::NAMED
            .into_iter()
            .find(|style| style.label() == s)
            .ok_or_else(|| {
                format!("unknown style `{s}`: expected rooms, boxes, corridors, loop or track")
            })
    }
}

/// The options of one generated world; the same options give the same world.
#[derive(Clone, Debug, PartialEq)]
pub struct GenerateOptions {
    pub seed: u64,
    /// (width, height) in metres; `None`: the style's default (a track's is drawn).
    pub size: Option<(f64, f64)>,
    /// Blocks, in every style but the track, which has none.
    pub blocks: usize,
    /// Free-standing boxes, in every style but the track, which has none.
    pub obstacles: usize,
    pub style: Style,
    /// Markers on the boundary, the interior walls and the boxes; without them only the
    /// blocks and the gates carry markers. The layout is the same either way.
    pub wall_markers: bool,
    /// Rooms and corridors with ways round: a second doorway in the walls between rooms,
    /// corridor walls free at both ends.
    pub loops: bool,
    /// Wall markers every this many metres.
    pub marker_spacing: f64,
    pub colours: Colours,
    /// Every doorway (rooms) and corridor turn this wide, metres; `None`: drawn.
    pub doorway: Option<f64>,
    /// How many rooms a rooms world has; `None`: 2-4 drawn.
    pub rooms: Option<usize>,
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
            marker_spacing: MARKER_SPACING,
            colours: Colours::Alternating,
            doorway: None,
            rooms: None,
        }
    }
}

impl GenerateOptions {
    /// The width and height the world will have.
    pub fn size(&self) -> (f64, f64) {
        self.size.unwrap_or(self.style.default_size())
    }

    /// The world's name, e.g. `generated:boxes:7`, `generated:rooms:7:loops:bare` (with
    /// loops, without wall markers), `generated:rooms:7:rooms6:door0.9:markers1:random`:
    /// each variant keeps its own autosaved map.
    pub fn name(&self) -> String {
        format!(
            "generated:{}:{}{}",
            self.style,
            self.seed,
            self.variant(":", "", "")
        )
    }

    /// The options that differ from the defaults, each as `sep` + name + value, with `flag`
    /// before names and `space` between a name and its value.
    fn variant(&self, sep: &str, flag: &str, space: &str) -> String {
        let mut parts = Vec::new();
        if self.loops {
            parts.push(format!("{flag}loops"));
        }
        if !self.wall_markers {
            parts.push(if flag.is_empty() {
                "bare".into()
            } else {
                format!("{flag}no-wall-markers")
            });
        }
        if let Some(n) = self.rooms {
            parts.push(format!("{flag}rooms{space}{n}"));
        }
        if let Some(w) = self.doorway {
            let name = if flag.is_empty() { "door" } else { "doorway" };
            parts.push(format!("{flag}{name}{space}{}", short(w)));
        }
        if self.marker_spacing != MARKER_SPACING {
            let name = if flag.is_empty() {
                "markers"
            } else {
                "marker-spacing"
            };
            parts.push(format!("{flag}{name}{space}{}", short(self.marker_spacing)));
        }
        if self.colours != Colours::Alternating {
            let colours = self.colours.label();
            parts.push(if flag.is_empty() {
                colours.into()
            } else {
                format!("{flag}colours {colours}")
            });
        }
        parts.iter().map(|p| format!("{sep}{p}")).collect()
    }

    /// Refuses options no world can satisfy, naming the option.
    pub fn validate(&self) -> Result<(), GenerateError> {
        let (w, h) = self.size();
        let size = || format!("{},{}", short(w), short(h));
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
        let (long, narrow) = self.style.min_size();
        if w.max(h) < long || w.min(h) < narrow {
            let reason = format!("{} need at least {long} m x {narrow} m", self.style.label());
            return bad("size", size(), reason);
        }
        if self.loops && !self.style.takes_loops() {
            let reason = "only rooms and corridors take loops (boxes and loop worlds have ways round already)";
            let value = format!("with {} worlds", self.style.label());
            return bad("loops", value, reason.into());
        }
        if self.style == Style::Track {
            return self.validate_track();
        }
        let max_blocks = self.colours.max_blocks();
        if self.blocks == 0 || self.blocks > max_blocks {
            let reason = format!(
                "must lie in 1..={max_blocks} with {} colours (a gate has {MAX_PER_COLOUR} drop places, mission/drop_places.rs)",
                self.colours
            );
            return bad("blocks", self.blocks.to_string(), reason);
        }
        let (lo, hi) = MARKER_SPACINGS;
        if !(lo..=hi).contains(&self.marker_spacing) {
            let reason = format!(
                "must lie in {lo}..={hi} m (a gate's markers need 0.4 m between wall markers)"
            );
            return bad("marker-spacing", short(self.marker_spacing), reason);
        }
        if let Some(width) = self.doorway {
            let (lo, hi) = DOORWAYS;
            if !matches!(self.style, Style::Rooms | Style::Corridors) {
                let value = format!("{} with {} worlds", short(width), self.style);
                return bad(
                    "doorway",
                    value,
                    "only rooms and corridors have doorways".into(),
                );
            }
            if !(lo..=hi).contains(&width) {
                let reason = format!(
                    "must lie in {lo}..={hi} m (the planner's 0.15 m lethal radius each side and 0.2 m between)"
                );
                return bad("doorway", short(width), reason);
            }
        }
        if let Some(n) = self.rooms {
            if self.style != Style::Rooms {
                let value = format!("{n} with {} worlds", self.style);
                return bad("rooms", value, "only rooms worlds take a room count".into());
            }
            // Rooms are split across their longer side and are at least MIN_ROOM wide.
            let across = |side: f64| (side / MIN_ROOM).floor().max(1.0) as usize;
            let most = across(w) * across(h);
            if n < 2 || n > most {
                let reason = format!(
                    "must lie in 2..={most} for a {} m world (rooms at least {MIN_ROOM} m wide)",
                    size()
                );
                return bad("rooms", n.to_string(), reason);
            }
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
        if self.style == Style::Track {
            // A track's size is drawn from the seed unless one is asked for.
            let size = self.size.map_or(String::new(), |(w, h)| {
                format!(" --size {},{}", short(w), short(h))
            });
            return format!(
                "navdeck world generate --seed {} --style track{size}",
                self.seed
            );
        }
        let (w, h) = self.size();
        format!(
            "navdeck world generate --seed {} --style {} --size {w},{h} --blocks {} --obstacles {}{}",
            self.seed,
            self.style,
            self.blocks,
            self.obstacles,
            self.variant(" ", "--", " ")
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
