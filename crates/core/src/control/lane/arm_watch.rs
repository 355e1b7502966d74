//! The barrier's arm while the robot waits before it closed: whether it is rising, so
//! the way opens even when the arm leaves the picture before the seed's UP (seed 000
//! §3.2.3: UP from 70 degrees).

/// An arm seen rising past this angle, degrees, is opening: from a stop before it, the
/// camera loses a rising arm past about 15-50 degrees, before it is UP.
const RISEN_DEG: f64 = 45.0;
/// Degrees above the lowest angle seen that make an arm rising, past the finder's noise.
const RISE_DEG: f64 = 8.0;

/// The arm's angles while the robot waits before it closed: whether it is rising.
#[derive(Clone, Debug, Default)]
pub(super) struct ArmWatch {
    /// The lowest and the last angle seen, degrees above level.
    lowest: Option<f64>,
    last: Option<f64>,
    rising: bool,
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
            // Lost from view while rising: it rose out of the picture.
            return self.rising;
        };
        let lowest = self.lowest.map_or(a, |l| l.min(a));
        // A repeated angle (the filter holding the arm between sightings) keeps the rise.
        let climbing = self.last.is_none_or(|l| a >= l - 1.0);
        self.rising = climbing && a >= lowest + RISE_DEG;
        self.lowest = Some(lowest);
        self.last = Some(a);
        self.rising && a >= RISEN_DEG
    }
}
