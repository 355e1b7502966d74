//! What the filter says of itself: its figures and its phase (localised, localising,
//! lost), as the status panel, the log and the JSON show them.

/// What the status panel shows of the filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Status {
    /// Particles now (KLD-sampling sets the count at each resampling).
    pub particles: usize,
    /// The effective sample size 1 / Σ w² of the last scan's normalised weights, before
    /// resampling (Probabilistic Robotics 4.3.4; AMCL resamples on it): how many
    /// particles carry the belief. Equal to `particles` until a scan has weighed them.
    pub effective: f64,
    /// The share of the weight behind the estimate.
    pub cluster_weight: f64,
    pub clusters: usize,
    pub converged: bool,
    /// Localised, still localising, or lost after having been localised.
    pub phase: Phase,
    /// The heaviest cluster's position spread (standard deviation, worst direction), m.
    pub spread: f64,
    /// The chance each resampled particle was replaced by a random one, last time.
    pub random_share: f64,
    pub updates: u64,
}

/// Where the filter stands, as the console, the log and the JSON say it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// One cluster holds the weight, is tight, and the map explains the scan there.
    Localised,
    /// Looking for the robot (global localisation, or the cluster not yet tight).
    Localising,
    /// Was localised, then the scans stopped fitting (augmented MCL's w_fast fell well
    /// under w_slow): the robot was moved, or the map no longer holds. Looking again.
    Lost,
}

impl Status {
    /// "localised", "localising: 3 hypotheses", "localising: 1 hypothesis, spread
    /// 0.40 m", or "lost: 3 hypotheses".
    pub fn summary(&self) -> String {
        let what = match self.phase {
            Phase::Localised => return "localised".into(),
            Phase::Localising => "localising",
            Phase::Lost => "lost",
        };
        match self.clusters {
            0 | 1 => format!("{what}: 1 hypothesis, spread {:.2} m", self.spread),
            n => format!("{what}: {n} hypotheses"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_says_what_the_filter_weighs() {
        let mut s = Status {
            particles: 800,
            effective: 400.0,
            cluster_weight: 0.5,
            clusters: 3,
            converged: false,
            phase: Phase::Localising,
            spread: 0.4,
            random_share: 0.0,
            updates: 9,
        };
        assert_eq!(s.summary(), "localising: 3 hypotheses");
        s.clusters = 1;
        assert_eq!(s.summary(), "localising: 1 hypothesis, spread 0.40 m");
        s.phase = Phase::Lost;
        assert_eq!(s.summary(), "lost: 1 hypothesis, spread 0.40 m");
        s.phase = Phase::Localised;
        assert_eq!(s.summary(), "localised");
    }
}
