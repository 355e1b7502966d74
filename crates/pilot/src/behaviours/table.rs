//! The behaviours and their priorities (seed 000 §5.3.1: emergency_stop 100,
//! collision_avoidance 90, traffic_compliance 80, lane_following 70, pick_and_place 60,
//! exploration 50). The seed's table has no keyboard driving; navdeck places teleop and
//! race at 75, where a user expects them: above every autonomous behaviour, below every
//! safety one. Path following (65) and gripper jogging (55) sit between the seed's tasks;
//! tag-route driving (seed 003) shares path following's 65: both drive a route, never at
//! once.
//! Sensor health (85, seed 000 §7.2.1's graceful degradation) holds or slows the task when
//! a sensor is lost; the collision monitor, above it, still weighs what it lets through.
//! Fleet yield (82, navdeck's) holds an autonomous robot that owes another of its fleet
//! the way (`control::fleet_yield`): a rule of the road, beside traffic compliance.

use std::fmt;

/// One behaviour the arbiter weighs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Behaviour {
    EmergencyStop,
    CollisionMonitor,
    SensorHealth,
    FleetYield,
    TrafficCompliance,
    Teleop,
    Race,
    LaneFollowing,
    PathFollowing,
    TagRoute,
    PickAndPlace,
    GripperJog,
    Exploration,
}

impl Behaviour {
    pub const ALL: [Behaviour; 13] = [
        Behaviour::EmergencyStop,
        Behaviour::CollisionMonitor,
        Behaviour::SensorHealth,
        Behaviour::FleetYield,
        Behaviour::TrafficCompliance,
        Behaviour::Teleop,
        Behaviour::Race,
        Behaviour::LaneFollowing,
        Behaviour::PathFollowing,
        Behaviour::TagRoute,
        Behaviour::PickAndPlace,
        Behaviour::GripperJog,
        Behaviour::Exploration,
    ];

    /// The higher wins.
    pub fn priority(self) -> u8 {
        match self {
            Behaviour::EmergencyStop => 100,
            Behaviour::CollisionMonitor => 90,
            Behaviour::SensorHealth => 85,
            Behaviour::FleetYield => 82,
            Behaviour::TrafficCompliance => 80,
            Behaviour::Teleop | Behaviour::Race => 75,
            Behaviour::LaneFollowing => 70,
            Behaviour::PathFollowing | Behaviour::TagRoute => 65,
            Behaviour::PickAndPlace => 60,
            Behaviour::GripperJog => 55,
            Behaviour::Exploration => 50,
        }
    }

    /// Whether the behaviour keeps the robot safe: it runs in every mode, and the user
    /// may not switch the e-stop off.
    pub fn is_safety(self) -> bool {
        self.priority() >= Behaviour::TrafficCompliance.priority()
    }

    /// The name a user types (`:behaviour collision_monitor off 30`).
    pub fn name(self) -> &'static str {
        match self {
            Behaviour::EmergencyStop => "emergency_stop",
            Behaviour::CollisionMonitor => "collision_monitor",
            Behaviour::SensorHealth => "sensor_health",
            Behaviour::FleetYield => "fleet_yield",
            Behaviour::TrafficCompliance => "traffic_compliance",
            Behaviour::Teleop => "teleop",
            Behaviour::Race => "race",
            Behaviour::LaneFollowing => "lane_following",
            Behaviour::PathFollowing => "path_following",
            Behaviour::TagRoute => "tag_route",
            Behaviour::PickAndPlace => "pick_and_place",
            Behaviour::GripperJog => "gripper_jog",
            Behaviour::Exploration => "exploration",
        }
    }

    /// The behaviour named `name` (as `name()` gives it, or with spaces or dashes).
    pub fn named(name: &str) -> Option<Behaviour> {
        let name = name.replace([' ', '-'], "_").to_lowercase();
        let name = match name.as_str() {
            "estop" | "e_stop" => "emergency_stop",
            "collision" | "collision_avoidance" => "collision_monitor",
            "health" | "degradation" => "sensor_health",
            other => other,
        }
        .to_string();
        Behaviour::ALL.into_iter().find(|b| b.name() == name)
    }
}

impl fmt::Display for Behaviour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let label = match self {
            Behaviour::EmergencyStop => "e-stop",
            Behaviour::CollisionMonitor => "collision monitor",
            Behaviour::SensorHealth => "sensor health",
            Behaviour::FleetYield => "fleet yield",
            Behaviour::TrafficCompliance => "traffic compliance",
            Behaviour::Teleop => "teleop",
            Behaviour::Race => "race",
            Behaviour::LaneFollowing => "lane following",
            Behaviour::PathFollowing => "path following",
            Behaviour::TagRoute => "tag route",
            Behaviour::PickAndPlace => "pick and place",
            Behaviour::GripperJog => "gripper jogging",
            Behaviour::Exploration => "exploration",
        };
        f.write_str(label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_000s_table_and_teleop_between_safety_and_autonomy() {
        use Behaviour::*;
        let seed = [
            (EmergencyStop, 100),
            (CollisionMonitor, 90),
            (TrafficCompliance, 80),
            (LaneFollowing, 70),
            (PickAndPlace, 60),
            (Exploration, 50),
        ];
        for (b, p) in seed {
            assert_eq!(b.priority(), p, "{b}");
        }
        // Sensor health weighs the task; the collision monitor weighs what it lets by.
        assert!(SensorHealth.is_safety());
        assert!(SensorHealth.priority() < CollisionMonitor.priority());
        assert!(SensorHealth.priority() > TrafficCompliance.priority());
        for keys in [Teleop, Race] {
            assert!(keys.priority() < TrafficCompliance.priority());
            for auto in [
                LaneFollowing,
                PathFollowing,
                TagRoute,
                PickAndPlace,
                GripperJog,
                Exploration,
            ] {
                assert!(keys.priority() > auto.priority(), "{keys} over {auto}");
            }
        }
    }

    #[test]
    fn every_behaviour_is_found_by_its_name() {
        for b in Behaviour::ALL {
            assert_eq!(Behaviour::named(b.name()), Some(b));
        }
        assert_eq!(
            Behaviour::named("collision monitor"),
            Some(Behaviour::CollisionMonitor)
        );
        assert_eq!(Behaviour::named("e-stop"), Some(Behaviour::EmergencyStop));
        assert_eq!(Behaviour::named("wander"), None);
    }
}
