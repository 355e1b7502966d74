//! How the map is looked at: zoom, pan, rendering style, overlays. Changed only by actions.

use crate::geometry::Point2;

/// Zoom steps: metres per character column.
pub const ZOOM_LEVELS: [f64; 9] = [0.01, 0.02, 0.03, 0.05, 0.08, 0.12, 0.2, 0.3, 0.5];

#[derive(Clone, Debug, PartialEq)]
pub struct ViewState {
    /// `None` fits the world into the map area; `Some(i)` picks `ZOOM_LEVELS[i]`.
    pub zoom: Option<usize>,
    /// Map centre; `None` follows the robot's estimate (or the world centre when fitting).
    pub center: Option<Point2>,
    pub braille: bool,
    pub show_truth: bool,
    pub help: bool,
    /// The landmark table over the map.
    pub landmarks: bool,
    /// What the landmark table lists and which row is chosen.
    pub table: LandmarkTable,
    /// The camera panel over the map, and how its thumbnail is drawn.
    pub camera: CameraPanel,
    /// The newest lidar scan over the map.
    pub scan: bool,
    /// Where the robot has driven, over the map.
    pub trail: bool,
    /// Lidar SLAM's pose graph (nodes and edges), over the map.
    pub graph: bool,
    /// What the log pane shows.
    pub log: LogView,
}

/// The landmark table's filter and chosen row (an index into the rows it lists).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LandmarkTable {
    /// Only gates and blocks: what `:goto marker ID` is mostly wanted for.
    pub targets_only: bool,
    pub selected: usize,
}

/// The log pane's scrollback and filters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LogView {
    /// Lines scrolled back from the newest; 0 follows new lines.
    pub back: usize,
    /// Only lines at or above this level.
    pub min_level: Option<crate::data::Level>,
    /// Only lines containing this text or said by a node of this name (any case).
    pub search: Option<String>,
    /// Whose lines: everyone's, navdeck's own, or the robot's nodes' (/rosout).
    pub source: SourceFilter,
}

/// Whose lines the log pane shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SourceFilter {
    #[default]
    All,
    Navdeck,
    Robot,
}

impl LogView {
    /// The next level filter: all, warnings and errors, errors only, all.
    pub fn next_level(&mut self) {
        use crate::data::Level;
        self.min_level = match self.min_level {
            None => Some(Level::Warn),
            Some(Level::Warn) => Some(Level::Error),
            _ => None,
        };
        self.back = 0;
    }

    /// The next source filter: every line, navdeck's own, the robot's nodes', every line.
    pub fn next_source(&mut self) {
        self.source = match self.source {
            SourceFilter::All => SourceFilter::Navdeck,
            SourceFilter::Navdeck => SourceFilter::Robot,
            SourceFilter::Robot => SourceFilter::All,
        };
        self.back = 0;
    }

    /// Whether the pane shows `entry`.
    pub fn shows(&self, entry: &crate::app::log::Entry) -> bool {
        let contains = |text: &str, s: &str| text.to_lowercase().contains(&s.to_lowercase());
        let from = match self.source {
            SourceFilter::All => true,
            SourceFilter::Navdeck => entry.source.is_none(),
            SourceFilter::Robot => entry.source.is_some(),
        };
        from && self.min_level.is_none_or(|l| entry.level >= l)
            && self.search.as_ref().is_none_or(|s| {
                contains(&entry.text, s) || entry.source.as_deref().is_some_and(|n| contains(n, s))
            })
    }
}

/// The camera panel: hidden, or shown with its thumbnail in half blocks or braille.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CameraPanel {
    #[default]
    Off,
    HalfBlock,
    Braille,
}

impl CameraPanel {
    /// The next style the toggle key gives.
    pub fn next(self) -> Self {
        match self {
            Self::Off => Self::HalfBlock,
            Self::HalfBlock => Self::Braille,
            Self::Braille => Self::Off,
        }
    }
}

impl Default for ViewState {
    fn default() -> Self {
        Self {
            zoom: None,
            center: None,
            braille: false,
            show_truth: true,
            help: false,
            landmarks: false,
            table: LandmarkTable::default(),
            camera: CameraPanel::Off,
            scan: true,
            trail: false,
            graph: false,
            log: LogView::default(),
        }
    }
}

impl ViewState {
    /// Metres per column given the fitted scale the renderer computed.
    pub fn scale(&self, fitted: f64) -> f64 {
        self.zoom.map_or(fitted, |i| ZOOM_LEVELS[i])
    }

    /// One step in (`finer`) or out from the current scale.
    pub fn zoom_step(&mut self, fitted: f64, finer: bool) {
        let current = self.scale(fitted);
        let next = if finer {
            ZOOM_LEVELS.iter().rposition(|&z| z < current - 1e-12)
        } else {
            ZOOM_LEVELS.iter().position(|&z| z > current + 1e-12)
        };
        if let Some(i) = next {
            self.zoom = Some(i);
        }
    }

    /// Moves the centre by a quarter of the visible span in the given direction.
    pub fn pan(&mut self, from: Point2, span: (f64, f64), dx: f64, dy: f64) {
        let c = self.center.unwrap_or(from);
        self.center = Some(Point2::new(
            c.x + dx * span.0 / 4.0,
            c.y + dy * span.1 / 4.0,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zoom_steps_from_fitted_scale() {
        let mut v = ViewState::default();
        v.zoom_step(0.07, true);
        assert_eq!(v.scale(0.07), 0.05);
        v.zoom_step(0.07, false);
        assert_eq!(v.scale(0.07), 0.08);
        v.zoom = Some(0);
        v.zoom_step(0.07, true);
        assert_eq!(v.zoom, Some(0), "finest zoom stays");
    }

    #[test]
    fn the_log_shows_everyones_lines_then_navdecks_then_the_robots_and_finds_nodes() {
        use crate::app::log::Entry;
        use crate::data::Level;
        let line = |source: Option<&str>, level, text: &str| Entry {
            time: 0.0,
            level,
            text: text.into(),
            repeats: 1,
            source: source.map(String::from),
        };
        let own = line(None, Level::Info, "mode MANUAL");
        let robot = line(Some("turtlebot3_node"), Level::Warn, "battery low");
        let mut view = LogView::default();
        assert!(view.shows(&own) && view.shows(&robot));
        view.next_source();
        assert_eq!(view.source, SourceFilter::Navdeck);
        assert!(view.shows(&own) && !view.shows(&robot));
        view.next_source();
        assert!(!view.shows(&own) && view.shows(&robot));
        view.next_source();
        assert_eq!(view.source, SourceFilter::All);
        // A search matches a node's name as well as the text.
        view.search = Some("TURTLEBOT3".into());
        assert!(view.shows(&robot) && !view.shows(&own));
        // Level and source filters combine.
        view.search = None;
        view.next_level();
        assert!(view.shows(&robot) && !view.shows(&own));
    }
}
