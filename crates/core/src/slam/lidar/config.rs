//! `[lidar_slam]`: mapping with the lidar alone. Names follow slam_toolbox's parameters
//! where it has the same one, so a user's `slam_toolbox:` block reads across; the
//! defaults are sized for a TurtleBot3's 3.5 m LDS-01 in rooms of a few metres.

use crate::data::check::{self, Invalid};
use serde::{Deserialize, Serialize};

/// Lidar SLAM settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LidarSlamConfig {
    /// Cell size of the grids scans are matched against, metres (slam_toolbox
    /// `resolution` 0.05).
    pub resolution: f64,
    /// How far a hit's likelihood spreads in the matching grid, metres (slam_toolbox
    /// `correlation_search_space_smear_deviation` 0.1; half that suits a 1 cm-noise lidar).
    pub smear_deviation: f64,
    /// A keyframe joins the graph after the robot moved this far (m) or turned this much
    /// (degrees) since the last one (slam_toolbox `minimum_travel_distance` 0.5 and
    /// `minimum_travel_heading` 0.5 rad, shortened for rooms of a few metres).
    pub minimum_travel_distance: f64,
    pub minimum_travel_heading_deg: f64,
    /// Keyframes in the local map each scan is matched against (slam_toolbox
    /// `scan_buffer_size` 10).
    pub scan_buffer_size: u32,
    /// Half the width of the search around the odometry's guess: metres and degrees
    /// (slam_toolbox `correlation_search_space_dimension` 0.5 is the whole width, and
    /// `coarse_search_angle_offset` 0.349 rad).
    pub search_half_width: f64,
    pub search_half_angle_deg: f64,
    /// A match whose response (the mean of its beams' likelihoods, 0 to 1) falls below
    /// this is not trusted: odometry alone carries the pose.
    pub minimum_response: f64,
    /// Older keyframes within this distance of the robot are tried for a loop closure,
    /// metres (slam_toolbox `loop_search_maximum_distance` 3.0).
    pub loop_search_maximum_distance: f64,
    /// A loop closes only to keyframes at least this far back along the path, metres
    /// (slam_toolbox counts `loop_match_minimum_chain_size` 10 scans instead).
    pub loop_minimum_travel: f64,
    /// Half the width of a loop closure's search: metres and degrees (slam_toolbox
    /// `loop_search_space_dimension` 8.0 is the whole width).
    pub loop_search_half_width: f64,
    pub loop_search_half_angle_deg: f64,
    /// A loop closure must match at least this well (slam_toolbox
    /// `loop_match_minimum_response_fine` 0.45 of its own measure)...
    pub loop_minimum_response: f64,
    /// ...and pin the pose this tightly: the match's position standard deviation, metres,
    /// the covariance gate that turns away matches a corridor leaves ambiguous
    /// (slam_toolbox `loop_match_maximum_variance_coarse` 3.0 of its own measure).
    pub loop_maximum_std: f64,
    /// Odometry's noise between keyframes: a share of the distance driven and of the
    /// angle turned (the odometry motion model's alpha3 and alpha1, Probabilistic
    /// Robotics table 5.6), used where a scan cannot be matched.
    pub odometry_noise: f64,
}

impl Default for LidarSlamConfig {
    fn default() -> Self {
        Self {
            resolution: 0.05,
            smear_deviation: 0.05,
            minimum_travel_distance: 0.2,
            minimum_travel_heading_deg: 20.0,
            scan_buffer_size: 15,
            search_half_width: 0.2,
            search_half_angle_deg: 12.0,
            minimum_response: 0.35,
            loop_search_maximum_distance: 3.0,
            loop_minimum_travel: 5.0,
            loop_search_half_width: 1.0,
            loop_search_half_angle_deg: 20.0,
            loop_minimum_response: 0.6,
            loop_maximum_std: 0.05,
            odometry_noise: 0.1,
        }
    }
}

impl LidarSlamConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        check::within(&[
            ("resolution", self.resolution, 0.01, 0.5),
            ("smear_deviation", self.smear_deviation, 0.005, 1.0),
            (
                "minimum_travel_distance",
                self.minimum_travel_distance,
                0.01,
                10.0,
            ),
            (
                "minimum_travel_heading_deg",
                self.minimum_travel_heading_deg,
                1.0,
                180.0,
            ),
            ("search_half_width", self.search_half_width, 0.0, 2.0),
            (
                "search_half_angle_deg",
                self.search_half_angle_deg,
                0.0,
                90.0,
            ),
            ("minimum_response", self.minimum_response, 0.0, 1.0),
            (
                "loop_search_maximum_distance",
                self.loop_search_maximum_distance,
                0.0,
                50.0,
            ),
            ("loop_minimum_travel", self.loop_minimum_travel, 0.0, 1000.0),
            (
                "loop_search_half_width",
                self.loop_search_half_width,
                0.0,
                5.0,
            ),
            (
                "loop_search_half_angle_deg",
                self.loop_search_half_angle_deg,
                0.0,
                180.0,
            ),
            (
                "loop_minimum_response",
                self.loop_minimum_response,
                0.0,
                1.0,
            ),
            ("loop_maximum_std", self.loop_maximum_std, 0.001, 1.0),
            ("odometry_noise", self.odometry_noise, 0.001, 1.0),
        ])?;
        check::counts_within(&[("scan_buffer_size", u64::from(self.scan_buffer_size), 1, 200)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_pass_and_a_bad_field_is_named() {
        assert_eq!(LidarSlamConfig::default().validate(), Ok(()));
        let bad = LidarSlamConfig {
            resolution: f64::NAN,
            ..Default::default()
        };
        assert_eq!(bad.validate().unwrap_err().0, "resolution");
        let bad = LidarSlamConfig {
            scan_buffer_size: 0,
            ..Default::default()
        };
        assert_eq!(bad.validate().unwrap_err().0, "scan_buffer_size");
    }
}
