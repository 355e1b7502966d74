//! The frames a recorded stream's messages are in (REP-105: `map`, `odom`, `base_link`).
//! A fleet robot's are under its name (`robot2/odom`), as multi-robot ROS 2 setups
//! prefix each robot's tf tree, so that RViz and Foxglove keep the robots apart; its
//! `map` stays the fleet's one frame when the robots share a world (the twins).

/// The frame names of one stream.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frames {
    pub map: String,
    pub odom: String,
    pub base: String,
    pub scan: String,
}

impl Frames {
    /// Frames under `prefix` (`""` for one robot, `robot2/` for a fleet's); `map` is
    /// left unprefixed when `shared_map`.
    pub fn under(prefix: &str, shared_map: bool) -> Self {
        let own = |frame: &str| format!("{prefix}{frame}");
        Self {
            map: if shared_map { "map".into() } else { own("map") },
            odom: own("odom"),
            base: own("base_link"),
            scan: own("base_scan"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_robot_keeps_the_standard_names_and_a_fleet_robot_gets_its_own() {
        let one = Frames::under("", false);
        assert_eq!((one.map.as_str(), one.odom.as_str()), ("map", "odom"));
        assert_eq!(
            (one.base.as_str(), one.scan.as_str()),
            ("base_link", "base_scan")
        );
        let twin = Frames::under("robot2/", true);
        assert_eq!(
            (twin.map.as_str(), twin.odom.as_str()),
            ("map", "robot2/odom")
        );
        assert_eq!(twin.base, "robot2/base_link");
        assert_eq!(Frames::under("tb3_0/", false).map, "tb3_0/map");
    }
}
