//! The planning map's keepout layer: the keepout zones laid over it as obstacles.

use super::BeliefMap;

impl BeliefMap {
    /// Lays the keepout zones `rects` over the map as obstacles (lethal within the lethal
    /// radius, inflated within the inflation), remembered as `tag`.
    pub fn set_keepout(&mut self, tag: u64, rects: &[crate::map::zones::Rect]) {
        let cost = crate::map::zones::raster::keepout_costs(
            &self.costmap,
            rects,
            self.config.lethal_radius,
            self.config.obstacle_inflation,
        );
        let old = std::mem::replace(&mut self.keepout_cost, cost);
        self.keepout_tag = tag;
        let changed: Vec<usize> = (old.iter().zip(&self.keepout_cost).enumerate())
            .filter(|(_, (a, b))| a != b)
            .map(|(i, _)| i)
            .collect();
        for i in changed {
            self.refresh(i);
        }
    }

    /// Which zones the keepout layer shows (0: none were ever laid).
    pub fn keepout_tag(&self) -> u64 {
        self.keepout_tag
    }
}
