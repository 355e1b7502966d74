//! The barrier's arm while the robot waits before it closed: whether it is rising, so
//! the way opens even when the arm leaves the picture before the seed's UP (seed 000
//! §3.2.3: UP from 70 degrees).

/// An arm seen rising past this angle, degrees, is opening: from a stop before it, the
/// camera loses a rising arm past about 15-50 degrees, before it is UP.
const RISEN_DEG: f64 = 45.0;
/// Degrees above the lowest angle seen that make an arm rising, past the finder's noise.
const RISE_DEG: f64 = 8.0;
/// Frames (a second at the lane camera's 10 Hz) without the arm that open the way: an arm
/// down across the lane within the stopping range is always in the picture (at 0.1 m up,
/// 0.3-0.55 m ahead it lies 5-8 degrees below the lens, inside the 20-degree-down view),
/// so one gone that long has risen out of it, even when the frames of its rise read its
/// angle too poorly to show a rise (an arm a third of a metre off fills the picture).
const GONE_FRAMES: u32 = 10;

/// The arm's angles while the robot waits before it closed: whether it is rising.
#[derive(Clone, Debug, Default)]
pub(super) struct ArmWatch {
    /// The lowest and the last angle seen, degrees above level.
    lowest: Option<f64>,
    last: Option<f64>,
    rising: bool,
    /// Frames since the arm was last seen.
    unseen: u32,
}

impl ArmWatch {
    /// Takes this frame's arm angle (none: no arm seen) while `watching` (the robot waits
    /// before the arm closed); whether an opening has begun.
    pub(super) fn opening(&mut self, angle: Option<f64>, watching: bool) -> bool {
        if !watching {
            *self = Self::default();
            return false;
        }
        let Some(a) = angle else {
            // Lost from view while rising, or for a second: it rose out of the picture.
            self.unseen += 1;
            return self.rising || self.unseen >= GONE_FRAMES;
        };
        self.unseen = 0;
        let lowest = self.lowest.map_or(a, |l| l.min(a));
        // A repeated angle (the filter holding the arm between sightings) keeps the rise.
        let climbing = self.last.is_none_or(|l| a >= l - 1.0);
        self.rising = climbing && a >= lowest + RISE_DEG;
        self.lowest = Some(lowest);
        self.last = Some(a);
        self.rising && a >= RISEN_DEG
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_arm_gone_from_view_for_a_second_has_opened_and_one_glimpsed_again_has_not() {
        let mut w = ArmWatch::default();
        // Down, then read poorly as it rises close by (16, 7, 7 degrees), then gone.
        for a in [3.0, 3.0, 16.0, 7.0, 7.0] {
            assert!(!w.opening(Some(a), true), "{a}");
        }
        for k in 1..GONE_FRAMES {
            assert!(!w.opening(None, true), "{k}");
        }
        assert!(w.opening(None, true));
        // Missed for a few frames, then seen down again: still closed.
        let mut w = ArmWatch::default();
        for _ in 0..5 {
            w.opening(None, true);
        }
        assert!(!w.opening(Some(2.0), true));
        for _ in 1..GONE_FRAMES {
            assert!(!w.opening(None, true));
        }
    }
}
