//! Colours by role, or none at all when NO_COLOR is set (no-color.org).

use crate::app::log::Level;
use crate::perception::markers::MarkerCategory;
use ratatui::style::{Color, Modifier, Style};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Theme {
    pub color: bool,
}

impl Theme {
    /// Colour unless the NO_COLOR variable is set to anything non-empty.
    pub fn from_env(no_color: Option<std::ffi::OsString>) -> Self {
        Self {
            color: no_color.is_none_or(|v| v.is_empty()),
        }
    }

    fn fg(self, color: Color) -> Style {
        if self.color {
            Style::new().fg(color)
        } else {
            Style::new()
        }
    }

    pub fn border(self) -> Style {
        self.fg(Color::DarkGray)
    }
    pub fn title(self) -> Style {
        Style::new().add_modifier(Modifier::BOLD)
    }
    pub fn label(self) -> Style {
        self.fg(Color::Gray)
    }
    pub fn value(self) -> Style {
        self.fg(Color::White)
    }
    pub fn occupied(self) -> Style {
        self.fg(Color::White)
    }
    pub fn free(self) -> Style {
        self.fg(Color::DarkGray)
    }
    /// Seed 001's 0.7 ring around obstacles.
    pub fn inflated(self) -> Style {
        self.fg(Color::DarkGray).add_modifier(Modifier::BOLD)
    }
    /// The planned path (green, as in seed 001's saved map image, "Saving Maps").
    pub fn path(self) -> Style {
        self.fg(Color::LightGreen)
    }
    /// The goal cursor of thinking mode.
    pub fn cursor(self) -> Style {
        if self.color {
            self.fg(Color::LightGreen)
                .add_modifier(Modifier::BOLD | Modifier::REVERSED)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED)
        }
    }
    /// The newest lidar scan's hits (red, as laser scans are commonly drawn).
    pub fn scan(self) -> Style {
        self.fg(Color::LightRed)
    }
    /// MCL's particles.
    pub fn particles(self) -> Style {
        self.fg(Color::Magenta)
    }
    /// Where the robot has driven.
    pub fn trail(self) -> Style {
        self.fg(Color::Blue)
    }
    pub fn robot(self) -> Style {
        self.fg(Color::Cyan).add_modifier(Modifier::BOLD)
    }
    pub fn truth(self) -> Style {
        self.fg(Color::Magenta)
    }
    pub fn alert(self) -> Style {
        if self.color {
            Style::new()
                .fg(Color::White)
                .bg(Color::Red)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        }
    }
    /// A notable event's line, flashed in the status panel (a success, reversed).
    pub fn flash(self) -> Style {
        if self.color {
            Style::new()
                .fg(Color::Black)
                .bg(Color::Green)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        }
    }
    /// Lidar SLAM's pose graph: its nodes and odometry/scan-match edges.
    pub fn graph(self) -> Style {
        self.fg(Color::LightBlue)
    }
    /// The pose graph's loop-closure edges (yellow, apart from the sequential chain).
    pub fn loop_edge(self) -> Style {
        self.fg(Color::Yellow).add_modifier(Modifier::BOLD)
    }
    pub fn mode(self) -> Style {
        if self.color {
            Style::new()
                .fg(Color::Black)
                .bg(Color::Cyan)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED)
        }
    }

    pub fn level(self, level: Level) -> Style {
        match level {
            Level::Info => self.fg(Color::Gray),
            Level::Success => self.fg(Color::Green),
            Level::Warn => self.fg(Color::Yellow),
            Level::Error => self.fg(Color::Red).add_modifier(Modifier::BOLD),
        }
    }

    /// Seed 001's saved-map colours ("Saving Maps"): boundary green, obstacle orange, gates
    /// and blocks by colour.
    pub fn marker(self, category: MarkerCategory) -> Style {
        match category {
            MarkerCategory::Boundary => self.fg(Color::Green),
            MarkerCategory::Obstacle => self.fg(Color::Yellow),
            MarkerCategory::RedGate | MarkerCategory::RedBlock => {
                self.fg(Color::LightRed).add_modifier(Modifier::BOLD)
            }
            MarkerCategory::BlueGate | MarkerCategory::BlueBlock => {
                self.fg(Color::LightBlue).add_modifier(Modifier::BOLD)
            }
            MarkerCategory::Unknown => self.fg(Color::Gray),
        }
    }
}

/// The map glyph of each marker category; distinct without colour too.
pub fn marker_glyph(category: MarkerCategory) -> char {
    match category {
        MarkerCategory::Boundary => '*',
        MarkerCategory::Obstacle => 'x',
        MarkerCategory::RedGate => 'R',
        MarkerCategory::BlueGate => 'B',
        MarkerCategory::RedBlock => 'r',
        MarkerCategory::BlueBlock => 'b',
        MarkerCategory::Unknown => '?',
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_color_follows_the_convention() {
        assert!(Theme::from_env(None).color);
        assert!(Theme::from_env(Some("".into())).color);
        assert!(!Theme::from_env(Some("1".into())).color);
    }
}
