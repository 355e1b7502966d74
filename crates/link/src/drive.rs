//! One control step over a link: poll what the robot reported, run the pilot on it, send
//! the pilot's command. The console and the headless mission runner both drive through it.

use super::RobotLink;
use navdeck_core::data::SensorFrame;
use navdeck_core::geometry::Pose2;
use navdeck_pilot::config::Settings;
use navdeck_pilot::{Due, Input, LogLine, Pilot, Report};

/// A pilot for the robot behind `link` at session time `now`. With a simulator behind
/// the link it starts at the true pose and its planning map covers the simulated world
/// when that is larger than the config's; otherwise it starts at the origin.
/// The planning map reaches this far beyond a simulated world's walls, metres: a lidar hit
/// on a wall at the map's very edge lands outside half the time, and the beam then clears
/// the edge cells instead of mapping the wall there.
const MAP_MARGIN: f64 = 0.25;

pub fn pilot_for(link: &dyn RobotLink, settings: Settings, now: f64) -> Pilot {
    let truth = link.ground_truth();
    let start = truth.map_or(Pose2::default(), |t| t.pose());
    let m = 2.0 * MAP_MARGIN;
    let extent = truth.map_or((0.0, 0.0), |t| (t.world().width + m, t.world().height + m));
    Pilot::new(settings, start, extent, now)
}

/// What one step brought: the frame the link reported (for the console's own panels) and
/// the pilot's log lines.
#[derive(Debug, Default)]
pub struct Stepped {
    pub frame: Option<SensorFrame>,
    /// Why the poll failed, when it did.
    pub failure: Option<String>,
    /// The command sent, when one was.
    pub command: Option<navdeck_core::data::Command>,
    pub log: Vec<LogLine>,
}

/// Polls `link` at session time `t`, runs `pilot` on the report, and sends the command
/// when `due` asks for one. A failed poll or send puts the pilot's link in doubt.
pub fn step(link: &mut dyn RobotLink, pilot: &mut Pilot, t: f64, due: Due) -> Stepped {
    let polled = link.poll(t);
    let truth = link.ground_truth().map(|g| g.pose());
    let failure = polled.as_ref().err().map(ToString::to_string);
    let report = match (&polled, &failure) {
        (Ok(frame), _) => Report::Frame(frame),
        (Err(_), Some(why)) => Report::Failed(why),
        (Err(_), None) => Report::Failed(""),
    };
    let out = pilot.step(Input::report(t, report, truth, due));
    let mut log = out.log;
    if let Some(command) = &out.command
        && let Err(e) = link.send(command)
    {
        let reason = format!("command not sent: {e}");
        let failed = Input::report(t, Report::Failed(&reason), truth, Due::Nothing);
        log.extend(pilot.step(failed).log);
    }
    Stepped {
        frame: polled.ok(),
        failure,
        command: out.command,
        log,
    }
}
