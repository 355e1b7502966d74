//! The landmark table's contents and keys: gates and blocks first, a chosen row to plan to.

use super::App;
use crate::keymap::{Key, KeyCode};
use crate::perception::markers::MarkerCategory;
use crate::pilot;
use crate::pilot::navigation::Target;
use crate::slam::ekf::LandmarkEstimate;

/// Gates, then blocks, then obstacles, then walls: what a user looks up first.
fn rank(id: u32) -> u8 {
    match MarkerCategory::of(id) {
        MarkerCategory::RedGate | MarkerCategory::BlueGate => 0,
        MarkerCategory::RedBlock | MarkerCategory::BlueBlock => 1,
        MarkerCategory::Obstacle => 2,
        MarkerCategory::Boundary => 3,
        MarkerCategory::Unknown => 4,
    }
}

impl App {
    /// The landmarks the table lists, in its order: all, or gates and blocks only.
    pub fn listed_landmarks(&self) -> Vec<LandmarkEstimate> {
        let targets_only = self.view.table.targets_only;
        let mut landmarks: Vec<_> = (self.pilot().slam().landmarks())
            .filter(|l| !targets_only || rank(l.id) <= 1)
            .collect();
        landmarks.sort_by_key(|l| (rank(l.id), l.id));
        landmarks
    }

    /// Where the block carrying marker `id` was put down, when the mission delivered it:
    /// the filter still holds the marker where it was picked up.
    pub fn delivered_at(&self, id: u32) -> Option<crate::geometry::Point2> {
        let mission = self.pilot().mission()?;
        mission
            .delivered_blocks()
            .find(|b| b.markers.contains(&id))
            .map(|b| b.position)
    }

    /// While the landmark table is open it takes the arrows (and j, k, page keys) to
    /// choose a row, and enter to plan to it (as `:goto marker ID`); true when the key
    /// was its.
    pub(super) fn table_key(&mut self, key: Key) -> bool {
        let listed = self.listed_landmarks();
        let last = listed.len().saturating_sub(1);
        let chosen = listed.get(self.view.table.selected).map(|l| l.id);
        let table = &mut self.view.table;
        match key.code {
            KeyCode::Up | KeyCode::Char('k') => table.selected = table.selected.saturating_sub(1),
            KeyCode::Down | KeyCode::Char('j') => table.selected = (table.selected + 1).min(last),
            KeyCode::PageUp => table.selected = table.selected.saturating_sub(10),
            KeyCode::PageDown => table.selected = (table.selected + 10).min(last),
            KeyCode::Enter => {
                if let Some(id) = chosen {
                    self.run_intent(pilot::Intent::Goto(Target::Marker(id)));
                }
            }
            _ => return false,
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gates_and_blocks_come_first() {
        let mut ids = vec![3, 521, 301, 401, 422, 1];
        ids.sort_by_key(|&id| (rank(id), id));
        assert_eq!(ids, [401, 422, 521, 301, 1, 3]);
    }
}
