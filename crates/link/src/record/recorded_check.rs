//! A decoded recording's times and truths checked before a replay uses them: every
//! input, frame, truth and estimate must have a finite time, in order, that a control
//! period can still be added to; a truth or estimate must hold finite poses within
//! bounds. What fails is skipped and named once per kind, with how many and the first
//! time; the rest plays.

use super::recorded::Recorded;
// The latest session time a replay runs to is the latest the runtime runs to.
use crate::runtime::MAX_SESSION_TIME as MAX_TIME;
use navdeck_core::data::frame_check::{MAX_COORDINATE, short};
use navdeck_msgs::record::TruthMsg;

/// Seconds the inputs may go on past the last recorded frame: as long as a headless run
/// carries on after its last key (its follow timeout); beyond, an input is not part of
/// the session the frames recorded.
pub const INPUTS_PAST_FRAMES: f64 = 600.0;

/// Times may step back this little, seconds: sums of 0.1 s drift apart by rounding.
const ROUNDING: f64 = 1e-6;

/// Why an entry at `time` is skipped, given the time of the last one kept.
fn time_fault(time: f64, last: f64, limit: f64) -> Option<String> {
    if !time.is_finite() {
        Some(format!("its time is {}, and must be finite", short(time)))
    } else if time < last - ROUNDING {
        Some(format!(
            "its time must not go back (after {} s)",
            short(last)
        ))
    } else if time > limit {
        Some(format!("its time must be at most {} s", short(limit)))
    } else {
        None
    }
}

/// Keeps the entries of `list` whose times pass `time_fault` and `fault`; names what
/// was skipped (the first of each reason, and how many in all) in `problems`.
fn keep_sane<T>(
    list: &mut Vec<T>,
    what: &str,
    limit: f64,
    time: impl Fn(&T) -> f64,
    fault: impl Fn(&T) -> Option<String>,
    problems: &mut Vec<String>,
) {
    let mut last = f64::NEG_INFINITY;
    // Per kind of fault: the first one's words and time, and how many.
    let mut skipped: Vec<(String, String, f64, usize)> = Vec::new();
    list.retain(|e| {
        let t = time(e);
        let Some(why) = time_fault(t, last, limit).or_else(|| fault(e)) else {
            last = last.max(t);
            return true;
        };
        // A kind is the words before any value: "must not go back (after 3 s)" is one.
        let kind: String = why
            .chars()
            .take_while(|c| !c.is_ascii_digit() && *c != '(' && *c != ',')
            .collect();
        match skipped.iter_mut().find(|s| s.0 == kind) {
            Some(entry) => entry.3 += 1,
            None => skipped.push((kind, why, t, 1)),
        }
        false
    });
    for (_, why, first, n) in skipped {
        let times = if n > 1 {
            format!(" (×{n} in all)")
        } else {
            String::new()
        };
        let at = if first.is_finite() {
            format!(" at {} s", short(first))
        } else {
            String::new()
        };
        problems.push(format!("recorded {what}{at} skipped: {why}{times}"));
    }
}

/// No fault beyond the time's.
fn no_fault<T>(_: &T) -> Option<String> {
    None
}

/// The first field of a pose that is not finite or lies beyond `MAX_COORDINATE`.
fn pose_fault(x: f64, y: f64, theta: f64) -> Option<String> {
    let far = |v: f64| !(0.0..=MAX_COORDINATE).contains(&v.abs());
    let bound = format!("must be finite, within ±{}", short(MAX_COORDINATE));
    if far(x) {
        Some(format!("x is {}: {bound}", short(x)))
    } else if far(y) {
        Some(format!("y is {}: {bound}", short(y)))
    } else if far(theta) {
        // Headings are wrapped when recorded; one beyond this loses all precision.
        Some(format!("theta is {}: {bound}", short(theta)))
    } else {
        None
    }
}

/// What is wrong with a recorded truth, if anything.
fn truth_fault(t: &TruthMsg) -> Option<String> {
    pose_fault(t.x, t.y, t.theta).or_else(|| {
        let rest = [
            ("linear", t.linear),
            ("angular", t.angular),
            ("command_linear", t.command_linear),
            ("command_angular", t.command_angular),
            ("distance_driven", t.distance_driven),
        ];
        let block = t
            .blocks
            .iter()
            .find_map(|b| pose_fault(b.x, b.y, b.theta).map(|w| format!("a block's {w}")));
        rest.iter()
            .find(|(_, v)| !(0.0..=1e9).contains(&v.abs()))
            .map(|(field, v)| format!("{field} is {}: must be finite, within ±1e9", short(*v)))
            .or(block)
    })
}

/// Checks `recorded` in place; see the module comment.
pub fn check(recorded: &mut Recorded) {
    let problems = &mut recorded.problems;
    keep_sane(
        &mut recorded.frames,
        "frame",
        MAX_TIME,
        |f| f.time,
        no_fault,
        problems,
    );
    let last_frame = recorded.frames.last().map(|f| f.time);
    let input_limit = last_frame.map_or(MAX_TIME, |t| (t + INPUTS_PAST_FRAMES).min(MAX_TIME));
    keep_sane(
        &mut recorded.inputs,
        "input",
        input_limit,
        |i| i.time,
        no_fault,
        problems,
    );
    keep_sane(
        &mut recorded.truths,
        "truth",
        MAX_TIME,
        |t| t.time,
        truth_fault,
        problems,
    );
    keep_sane(
        &mut recorded.estimates,
        "estimate",
        MAX_TIME,
        |e| e.time,
        |e| {
            let finite = e.covariance.iter().all(|c| c.is_finite());
            let p = e.pose;
            pose_fault(p.x, p.y, p.theta)
                .or_else(|| (!finite).then(|| "its covariance must be finite".to_string()))
        },
        problems,
    );
    if let (Some(frame), Some(input)) = (last_frame, recorded.inputs.last())
        && input.time > frame + 1e-6
    {
        problems.push(format!(
            "the recorded inputs go on to {} s, past the last recorded frame at {} s: the robot reports nothing after it",
            short(input.time),
            short(frame)
        ));
    }
}
