//! The ROS 2 environment a user has sourced: which distribution (`ROS_DISTRO`) and how
//! far discovery reaches (`ROS_LOCALHOST_ONLY`, `ROS_AUTOMATIC_DISCOVERY_RANGE`,
//! `ROS_STATIC_PEERS`), turned into what navdeck's DDS participant does and what the log
//! says about it. The values are passed in: nothing here reads the environment.

use crate::Notice;

/// The distribution navdeck's ROS 2 layer was built for (cargo feature `humble` or
/// `jazzy`): Humble's participant GIDs are 24 bytes, Iron's and later 16.
pub fn built_distro() -> &'static str {
    ros2_client::distributions::COMPILED_ROS_DISTRO.as_str()
}

/// What the environment asks of discovery.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DiscoveryScope {
    /// Announce and listen on the loopback interface only.
    pub localhost_only: bool,
    /// What the log should say at start: a mismatch, or a setting navdeck cannot honour.
    pub notes: Vec<Notice>,
}

/// The ROS 2 variables, as read at the edge (None when unset).
#[derive(Clone, Debug, Default)]
pub struct RosEnvironment {
    pub distro: Option<String>,
    pub localhost_only: Option<String>,
    pub discovery_range: Option<String>,
    pub static_peers: Option<String>,
}

impl RosEnvironment {
    /// The variables of this process.
    pub fn from_process() -> Self {
        let var = |name: &str| std::env::var(name).ok();
        Self {
            distro: var("ROS_DISTRO"),
            localhost_only: var("ROS_LOCALHOST_ONLY"),
            discovery_range: var("ROS_AUTOMATIC_DISCOVERY_RANGE"),
            static_peers: var("ROS_STATIC_PEERS"),
        }
    }

    /// What discovery does, and the notes for the log, for a build made for `built`.
    pub fn scope(&self, built: &str) -> DiscoveryScope {
        let mut notes = Vec::new();
        if let Some(distro) = self.distro.as_deref().map(str::trim)
            && !distro.is_empty()
            && distro != built
        {
            let other = if built == "humble" { "jazzy" } else { "humble" };
            notes.push(Notice::warn(format!(
                "ROS 2: ROS_DISTRO is {distro:?} but navdeck was built for {built}: ros2 node list and services may not see it (build with --no-default-features --features {other} for a {other} robot)"
            )));
        }
        let set = |v: &Option<String>| {
            v.as_deref()
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(str::to_string)
        };
        // ROS_LOCALHOST_ONLY: Humble's switch (deprecated in Jazzy, still honoured there).
        let mut localhost_only = match set(&self.localhost_only).as_deref() {
            None | Some("0") => false,
            Some("1") => true,
            Some(other) => {
                notes.push(Notice::warn(format!(
                    "ROS 2: ROS_LOCALHOST_ONLY = {other:?} is neither 0 nor 1: ignored"
                )));
                false
            }
        };
        // Jazzy's range, which takes precedence over ROS_LOCALHOST_ONLY when set.
        match set(&self.discovery_range).as_deref() {
            None | Some("SYSTEM_DEFAULT") | Some("SUBNET") => {}
            Some("LOCALHOST") => localhost_only = true,
            Some("OFF") => {
                localhost_only = true;
                notes.push(Notice::warn(
                    "ROS 2: ROS_AUTOMATIC_DISCOVERY_RANGE = OFF is not supported: navdeck discovers on this host only (use ROS_DOMAIN_ID to keep it apart)",
                ));
            }
            Some(other) => notes.push(Notice::warn(format!(
                "ROS 2: ROS_AUTOMATIC_DISCOVERY_RANGE = {other:?} is not one of SUBNET, LOCALHOST, OFF, SYSTEM_DEFAULT: discovering on the subnet"
            ))),
        }
        if let Some(peers) = set(&self.static_peers) {
            notes.push(Notice::warn(format!(
                "ROS 2: ROS_STATIC_PEERS = {peers:?} is not supported (navdeck's DDS has no unicast peer list): run navdeck on the robot over SSH, or see README \"ROS 2 over Wi-Fi\""
            )));
        }
        if localhost_only {
            notes.push(Notice::info(
                "ROS 2: discovery on this host only (loopback), as the environment asks",
            ));
        }
        DiscoveryScope {
            localhost_only,
            notes,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env(pairs: &[(&str, &str)]) -> RosEnvironment {
        let get = |k: &str| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        };
        RosEnvironment {
            distro: get("ROS_DISTRO"),
            localhost_only: get("ROS_LOCALHOST_ONLY"),
            discovery_range: get("ROS_AUTOMATIC_DISCOVERY_RANGE"),
            static_peers: get("ROS_STATIC_PEERS"),
        }
    }

    #[test]
    fn nothing_set_means_the_subnet_and_no_notes() {
        assert_eq!(env(&[]).scope("jazzy"), DiscoveryScope::default());
    }

    #[test]
    fn a_distribution_other_than_the_build_is_a_warning_naming_both() {
        let scope = env(&[("ROS_DISTRO", "humble")]).scope("jazzy");
        assert_eq!(scope.notes.len(), 1);
        let text = &scope.notes[0].text;
        assert!(text.contains("\"humble\"") && text.contains("built for jazzy"));
        assert!(text.contains("--features humble"), "{text}");
        assert!(
            env(&[("ROS_DISTRO", "jazzy")])
                .scope("jazzy")
                .notes
                .is_empty()
        );
    }

    #[test]
    fn localhost_only_and_the_range_narrow_discovery() {
        assert!(
            env(&[("ROS_LOCALHOST_ONLY", "1")])
                .scope("humble")
                .localhost_only
        );
        assert!(
            !env(&[("ROS_LOCALHOST_ONLY", "0")])
                .scope("humble")
                .localhost_only
        );
        let range = |v| env(&[("ROS_AUTOMATIC_DISCOVERY_RANGE", v)]).scope("jazzy");
        assert!(range("LOCALHOST").localhost_only);
        assert!(!range("SUBNET").localhost_only);
        assert!(!range("SYSTEM_DEFAULT").localhost_only);
        let off = range("OFF");
        assert!(off.localhost_only);
        assert!(
            off.notes
                .iter()
                .any(|n| n.text.contains("OFF is not supported"))
        );
        let bad = range("EVERYWHERE");
        assert!(!bad.localhost_only);
        assert!(bad.notes[0].text.contains("EVERYWHERE"));
        let odd = env(&[("ROS_LOCALHOST_ONLY", "yes")]).scope("humble");
        assert!(!odd.localhost_only && odd.notes[0].text.contains("\"yes\""));
    }

    #[test]
    fn static_peers_are_named_as_unsupported_with_what_to_do() {
        let scope = env(&[("ROS_STATIC_PEERS", "192.168.1.20;robot.local")]).scope("jazzy");
        let text = &scope.notes[0].text;
        assert!(text.contains("192.168.1.20;robot.local") && text.contains("SSH"));
        assert!(!scope.localhost_only);
    }
}
