//! Marker ID ranges of seed 001 section 1 ("Marker Categories").

use serde::{Deserialize, Serialize};

/// What a marker ID stands for in the arena.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MarkerCategory {
    /// IDs 1-300: markers along the arena walls.
    Boundary,
    /// IDs 301-400: markers on obstacles.
    Obstacle,
    /// IDs 401-420.
    RedGate,
    /// IDs 421-450, odd/even pairs on one block.
    RedBlock,
    /// IDs 501-520.
    BlueGate,
    /// IDs 521-550, odd/even pairs on one block.
    BlueBlock,
    /// Any other ID: seen, but meaningless to the mission.
    Unknown,
}

impl MarkerCategory {
    /// Seed 001 section 1: ID 1-300 boundary, 301-400 obstacle, 401-420 red gate,
    /// 421-450 red block, 501-520 blue gate, 521-550 blue block.
    pub fn of(id: u32) -> Self {
        match id {
            1..=300 => Self::Boundary,
            301..=400 => Self::Obstacle,
            401..=420 => Self::RedGate,
            421..=450 => Self::RedBlock,
            501..=520 => Self::BlueGate,
            521..=550 => Self::BlueBlock,
            _ => Self::Unknown,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Self::Boundary => "boundary",
            Self::Obstacle => "obstacle",
            Self::RedGate => "red gate",
            Self::RedBlock => "red block",
            Self::BlueGate => "blue gate",
            Self::BlueBlock => "blue block",
            Self::Unknown => "unknown",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_edges_follow_seed_001() {
        assert_eq!(MarkerCategory::of(1), MarkerCategory::Boundary);
        assert_eq!(MarkerCategory::of(300), MarkerCategory::Boundary);
        assert_eq!(MarkerCategory::of(301), MarkerCategory::Obstacle);
        assert_eq!(MarkerCategory::of(420), MarkerCategory::RedGate);
        assert_eq!(MarkerCategory::of(421), MarkerCategory::RedBlock);
        assert_eq!(MarkerCategory::of(451), MarkerCategory::Unknown);
        assert_eq!(MarkerCategory::of(501), MarkerCategory::BlueGate);
        assert_eq!(MarkerCategory::of(550), MarkerCategory::BlueBlock);
        assert_eq!(MarkerCategory::of(0), MarkerCategory::Unknown);
    }
}
