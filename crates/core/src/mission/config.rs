//! The `[mission]` parameters: distances, speeds and timeouts of seed 001 sections 7-8 and
//! "Failure Modes & Recovery".

use serde::{Deserialize, Serialize};

/// Rotate to scan after this long without any marker in view, s (navdeck's trigger for
/// seed 001 "Robot Lost", whose only figure is the 30 s hand-over to manual).
pub const LOST_SCAN_AFTER: f64 = 10.0;
/// A lost robot drives back to this far in front of the nearest landmark it knows,
/// metres (navdeck's: within any camera's range, clear of the wall's ring).
pub const RELOCATE_STANDOFF: f64 = 0.5;
/// Heading error accepted when turning to face a block or a gate, radians (3 degrees).
pub const FACE_TOLERANCE: f64 = 3.0 * std::f64::consts::PI / 180.0;
/// Seed 001 "Block Lost During Approach": markers unseen this long while in view, s
/// (navdeck's value; the seed gives no time).
pub const BLOCK_LOST_AFTER: f64 = 3.0;
/// How far ahead the camera is expected to see a block's markers, metres.
pub const CAMERA_RANGE: f64 = 0.6;
/// Half the angle in which the camera is expected to see a block's markers, radians.
pub const CAMERA_HALF_FOV: f64 = 0.5;
/// Smallest frontier cluster worth exploring, cells.
pub const FRONTIER_MIN_CELLS: usize = 20;
/// Rounds of turning and trying every given-up exploration target again before the
/// mission calls exploration complete (navdeck's).
pub const GIVE_UP_ROUNDS: u32 = 3;
/// Unseen free space smaller than this many coverage cells (0.1 m square) is not worth a
/// trip: a sliver along a wall (navdeck's).
pub const UNSEEN_MIN_CELLS: usize = 3;
/// Looks at a block seen by one marker only before leaving it: one from the robot's side
/// and one from each diagonal (navdeck's).
pub const POTENTIAL_LOOKS: u32 = 5;
/// Looks at an unexplained small object, from four sides 90° apart: a block's two
/// markers face two adjacent sides, so one of four looks faces a marker (navdeck's).
pub const OBJECT_LOOKS: u32 = 4;
/// An object the lidar maps this near a block or gate the markers placed is that block
/// or gate (or a block delivered there), metres.
pub const EXPLAINED_WITHIN: f64 = 0.25;
/// The lidar's outline of a block is looked for this far from where its markers put it,
/// metres: a marker placed from a few sightings can be several centimetres off.
pub const FIT_SEARCH: f64 = 0.1;
/// The diagonal looks stand this many staging distances from the block.
pub const POTENTIAL_VIEW: f64 = 1.5;
/// Targets closer to the robot than this are ignored, metres (seed 001
/// `get_furthest_marker`, < 0.3 m).
pub const TARGET_TOO_CLOSE: f64 = 0.3;
/// How far a robot of a fleet turns while what is left to explore is another robot's
/// before it chooses again, radians (navdeck's: a quarter turn looks round meanwhile).
pub const WAIT_TURN: f64 = std::f64::consts::FRAC_PI_2;
/// Seed 001 section 8: backing off after a drop, m/s.
pub const BACK_OFF_SPEED: f64 = 0.1;
/// Progress along the path that counts as not stuck, metres.
pub const STUCK_PROGRESS: f64 = 0.05;
/// Attempts at one block before it is left alone.
pub const MAX_BLOCK_ATTEMPTS: u32 = 3;
/// A demoted block becomes a target again when seen this long after the demotion, s.
pub const DEMOTED_FOR: f64 = 5.0;

/// Where exploration goes next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetRule {
    /// Seed 001 "Marker Selection Heuristic": the furthest valid unvisited marker. The
    /// enum's default, as the seed's rule; `MissionConfig::default()` uses `Frontiers`, so
    /// a config without `target_rule` explores by frontiers. In the 4 m arena the
    /// 360-degree lidar leaves no frontier after the first scans, so both rules drive the
    /// same missions (`navdeck mission --sweep 1..50` with either: 50 of 50 delivered).
    #[default]
    Markers,
    /// The nearest frontier between known and unknown space (falls back to markers).
    Frontiers,
}

impl TargetRule {
    pub fn other(self) -> Self {
        match self {
            Self::Markers => Self::Frontiers,
            Self::Frontiers => Self::Markers,
        }
    }
}

/// Mission parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MissionConfig {
    pub target_rule: TargetRule,
    /// A block's side, metres.
    pub block_size: f64,
    /// Turn rate of scans and retry turns, rad/s.
    pub scan_speed: f64,
    /// Where the path to a block ends: this far from it, on the robot's side, metres.
    pub staging_distance: f64,
    /// Block centre ahead of the robot centre when the gripper closes, metres. The twin's
    /// jaws catch 0.06-0.14 m ahead; 0.115 leans to the far end because the block's estimate
    /// can be 4 cm off, and a block behind the zone is run into while one beyond it is only
    /// a missed grip, which is retried (seeds 51-150 found the difference).
    pub grip_distance: f64,
    /// Final approach speed to a block or gate, m/s.
    pub approach_speed: f64,
    /// A block nearer than this (robot centre to block centre, metres) is below or beside
    /// the camera's view, so its markers are not expected in view: the last of the approach
    /// drives on the filter's estimate. Unset: worked out from the camera in use (the
    /// twin's ideal sensor, its rendered camera or `[vision]`'s mount and intrinsics).
    pub blind_distance: Option<f64>,
    /// Time the gripper takes to open or close, s (seed 001).
    pub gripper_wait: f64,
    /// Where the path to a gate ends: this far in front of it, metres.
    pub drop_staging: f64,
    /// Robot centre to gate centre when the gripper opens, metres.
    pub drop_distance: f64,
    /// Backing off at 0.1 m/s after a drop, and out of a spot where the robot is stuck, s.
    pub back_off_time: f64,
    /// No landmarks this long: drive back towards the nearest landmark known, and hand
    /// over to manual if none is in view there (or none is known), s.
    pub lost_timeout: f64,
    /// The robot counts as lost (after 10 s without a marker) only once the filter's
    /// position standard deviation passes this, metres (navdeck's: the planning map's
    /// lethal ring leaves 7 cm round the footprint). 0: lost whenever no marker was seen
    /// for 10 s.
    pub lost_position_std: f64,
    /// Failed plans (each followed by a turn) before handing over to manual.
    pub no_path_retries: u32,
    /// Turn before retrying a failed plan, degrees.
    pub retry_turn_deg: f64,
    /// No progress along a path this long: replan, s.
    pub stuck_timeout: f64,
    /// Least time between two plan requests, s.
    pub replan_cooldown: f64,
    /// Blocks to deliver; 0 delivers every block found and ends when exploration is
    /// complete (seed 001's arena has 4).
    pub total_blocks: u32,
    /// How far and how wide the camera is taken to see markers for sure when exploration
    /// judges what it has looked at, metres and degrees (navdeck's: half the twin's 3 m
    /// range, and inside its 68° field of view).
    pub view_range: f64,
    pub view_fov_deg: f64,
    /// Something the lidar maps that fits in a square this size, metres, and that no
    /// marker explains, is looked at from four sides before exploration ends: a block
    /// whose markers were never turned towards the camera (navdeck's: more than a block's
    /// diagonal, less than an obstacle). 0 turns the looks off.
    pub object_size: f64,
    /// With an `[arm]`: the robot stops with the block this far ahead of the arm's base
    /// joint, metres (navdeck's: 0.25 m, which the default arm reaches on the floor with
    /// the tool pointing down, and which leaves the default body 5 cm clear of the block's
    /// corners when the block's estimate is a few centimetres off).
    pub arm_standoff: f64,
}

impl Default for MissionConfig {
    fn default() -> Self {
        Self {
            target_rule: TargetRule::Frontiers,
            block_size: 0.05,
            scan_speed: 0.6,
            staging_distance: 0.30,
            grip_distance: 0.115,
            approach_speed: 0.05,
            blind_distance: None,
            gripper_wait: 1.0,
            drop_staging: 0.40,
            drop_distance: 0.18,
            back_off_time: 2.0,
            lost_timeout: 30.0,
            lost_position_std: 0.07,
            no_path_retries: 36,
            retry_turn_deg: 10.0,
            stuck_timeout: 30.0,
            replan_cooldown: 0.5,
            total_blocks: 0,
            view_range: 1.5,
            view_fov_deg: 60.0,
            object_size: 0.15,
            arm_standoff: 0.25,
        }
    }
}

impl MissionConfig {
    /// Checks values a parser cannot: (field, value, reason) for the first bad one.
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        crate::data::check::within(&[
            ("block_size", self.block_size, 0.01, 1.0),
            ("scan_speed", self.scan_speed, 0.01, 20.0),
            ("staging_distance", self.staging_distance, 0.01, 5.0),
            ("grip_distance", self.grip_distance, 0.01, 5.0),
            ("approach_speed", self.approach_speed, 0.001, 5.0),
            ("gripper_wait", self.gripper_wait, 0.0, 60.0),
            ("drop_staging", self.drop_staging, 0.01, 5.0),
            ("drop_distance", self.drop_distance, 0.01, 5.0),
            ("arm_standoff", self.arm_standoff, 0.01, 2.0),
            ("back_off_time", self.back_off_time, 0.0, 60.0),
            ("lost_timeout", self.lost_timeout, 0.0, 3600.0),
            ("lost_position_std", self.lost_position_std, 0.0, 10.0),
            ("retry_turn_deg", self.retry_turn_deg, 0.1, 360.0),
            ("stuck_timeout", self.stuck_timeout, 0.1, 3600.0),
            ("replan_cooldown", self.replan_cooldown, 0.0, 60.0),
            ("view_range", self.view_range, 0.01, 100.0),
            ("object_size", self.object_size, 0.0, 10.0),
        ])?;
        crate::data::check::counts_within(&[
            ("no_path_retries", u64::from(self.no_path_retries), 0, 1000),
            ("total_blocks", u64::from(self.total_blocks), 0, 1000),
        ])?;
        if !(self.view_fov_deg > 0.0 && self.view_fov_deg <= 360.0) {
            return Err((
                "view_fov_deg",
                self.view_fov_deg,
                "must lie in (0, 360]".into(),
            ));
        }
        if let Some(blind) = self.blind_distance {
            crate::data::check::within(&[("blind_distance", blind, 0.0, 5.0)])?;
        }
        let non_negative = [
            ("gripper_wait", self.gripper_wait),
            ("back_off_time", self.back_off_time),
            ("replan_cooldown", self.replan_cooldown),
            ("object_size", self.object_size),
            ("lost_position_std", self.lost_position_std),
        ];
        crate::data::check::all_non_negative(&non_negative)?;
        if !(self.lost_timeout.is_finite() && self.lost_timeout > LOST_SCAN_AFTER) {
            return Err((
                "lost_timeout",
                self.lost_timeout,
                "must be more than the 10 s after which a lost robot scans".into(),
            ));
        }
        if self.grip_distance >= self.staging_distance {
            return Err((
                "grip_distance",
                self.grip_distance,
                "must be less than staging_distance".into(),
            ));
        }
        if self.drop_distance >= self.drop_staging {
            return Err((
                "drop_distance",
                self.drop_distance,
                "must be less than drop_staging".into(),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_a_bad_value_is_named() {
        assert_eq!(MissionConfig::default().validate(), Ok(()));
        let bad = MissionConfig {
            grip_distance: 0.5,
            ..MissionConfig::default()
        };
        assert_eq!(bad.validate().unwrap_err().0, "grip_distance");
        let parsed: MissionConfig = toml::from_str("target_rule = \"markers\"").unwrap();
        assert_eq!(parsed.target_rule, TargetRule::Markers);
        assert!(toml::from_str::<MissionConfig>("speed = 1.0").is_err());
    }
}
