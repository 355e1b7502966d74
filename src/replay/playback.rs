//! Playing a recording: where in it the console is, how fast it goes, which view, and
//! what the replay's keys do. Time is passed in (wall seconds since the last call).

use crate::keymap::{Key, KeyCode};

/// The speeds `[` and `]` step through, times real time.
pub const SPEEDS: [f64; 9] = [0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0];
/// Seconds a left or right arrow moves, and page up or down.
pub const SEEK_STEP: f64 = 5.0;
pub const SEEK_PAGE: f64 = 60.0;

/// What the console shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// What was believed when it was recorded.
    AsRecorded,
    /// Today's estimator and planner on the recorded data.
    Rerun,
}

impl View {
    pub fn label(self) -> &'static str {
        match self {
            View::AsRecorded => "as recorded",
            View::Rerun => "re-run",
        }
    }
}

/// What a key asked of the replay.
#[derive(Clone, Debug, PartialEq)]
pub enum Asked {
    Nothing,
    Quit,
    /// Go to this session time (backwards re-runs from the start).
    Seek(f64),
    /// A key for the re-run's view (zoom, pan, braille, ...).
    View(Key),
}

/// The replay's clock and controls.
#[derive(Clone, Debug)]
pub struct Playback {
    pub speed: f64,
    pub paused: bool,
    pub view: View,
    position: f64,
    start: f64,
    end: f64,
    /// Seconds of one step (`,` and `.`): the control period.
    step: f64,
    /// The time being typed after `:`.
    pub prompt: Option<String>,
    /// Why the last typed time was refused.
    pub refusal: Option<String>,
    /// The replay's keys are shown over the screen (`?`).
    pub help: bool,
}

impl Playback {
    pub fn new((start, end): (f64, f64), speed: f64, view: View, step: f64) -> Self {
        Self {
            speed: speed.clamp(SPEEDS[0], SPEEDS[SPEEDS.len() - 1]),
            paused: false,
            view,
            position: start,
            start,
            end: end.max(start),
            step,
            prompt: None,
            refusal: None,
            help: false,
        }
    }

    pub fn position(&self) -> f64 {
        self.position
    }

    pub fn span(&self) -> (f64, f64) {
        (self.start, self.end)
    }

    /// Lets `wall` seconds pass; playing stops at the end.
    pub fn advance(&mut self, wall: f64) {
        if self.paused || !(wall.is_finite() && wall > 0.0) {
            return;
        }
        self.position = (self.position + wall * self.speed).min(self.end);
        if self.position >= self.end {
            self.paused = true;
        }
    }

    /// Moves to `t`, within the recording.
    pub fn go_to(&mut self, t: f64) -> f64 {
        self.position = t.clamp(self.start, self.end);
        self.position
    }

    fn speed_step(&mut self, up: bool) {
        let i = SPEEDS
            .iter()
            .position(|&s| s >= self.speed - 1e-9)
            .unwrap_or(SPEEDS.len() - 1);
        let i = if up {
            (i + 1).min(SPEEDS.len() - 1)
        } else {
            i.saturating_sub(1)
        };
        self.speed = SPEEDS[i];
    }

    /// What `key` does: the replay's own keys, else a view key for the re-run.
    pub fn key(&mut self, key: Key) -> Asked {
        if self.help {
            // Any key closes the help and does nothing else, as in the console.
            self.help = false;
            return Asked::Nothing;
        }
        if let Some(text) = self.prompt.as_mut() {
            match key.code {
                KeyCode::Enter => {
                    let text = self.prompt.take().unwrap_or_default();
                    return match parse_time(&text) {
                        Ok(t) => {
                            self.refusal = None;
                            Asked::Seek(self.go_to(self.start + t))
                        }
                        Err(why) => {
                            self.refusal = Some(why);
                            Asked::Nothing
                        }
                    };
                }
                KeyCode::Esc => self.prompt = None,
                KeyCode::Backspace => {
                    // Backspace on an empty line closes the prompt.
                    let emptied = text.pop().is_none();
                    self.prompt = self.prompt.take().filter(|_| !emptied);
                }
                KeyCode::Char(c) if !key.ctrl && text.len() < 16 => text.push(c),
                _ => {}
            }
            return Asked::Nothing;
        }
        let seek = |p: &mut Self, dt: f64| Asked::Seek(p.go_to(p.position + dt));
        match key.code {
            KeyCode::Char('q') => Asked::Quit,
            KeyCode::Char('c') if key.ctrl => Asked::Quit,
            KeyCode::Char('?') => {
                self.help = true;
                Asked::Nothing
            }
            KeyCode::Char(' ') => {
                if self.paused && self.position >= self.end {
                    self.position = self.start;
                    self.paused = false;
                    return Asked::Seek(self.start);
                }
                self.paused = !self.paused;
                Asked::Nothing
            }
            KeyCode::Char('.') => {
                self.paused = true;
                seek(self, self.step)
            }
            KeyCode::Char(',') => {
                self.paused = true;
                seek(self, -self.step)
            }
            KeyCode::Right => seek(self, SEEK_STEP),
            KeyCode::Left => seek(self, -SEEK_STEP),
            KeyCode::PageDown => seek(self, SEEK_PAGE),
            KeyCode::PageUp => seek(self, -SEEK_PAGE),
            KeyCode::Home => Asked::Seek(self.go_to(self.start)),
            KeyCode::End => Asked::Seek(self.go_to(self.end)),
            KeyCode::Char(']') => {
                self.speed_step(true);
                Asked::Nothing
            }
            KeyCode::Char('[') => {
                self.speed_step(false);
                Asked::Nothing
            }
            KeyCode::Char(d @ '1'..='9') => {
                let fraction = f64::from(d as u8 - b'0') / 10.0;
                Asked::Seek(self.go_to(self.start + fraction * (self.end - self.start)))
            }
            KeyCode::Char(':') => {
                self.prompt = Some(String::new());
                Asked::Nothing
            }
            KeyCode::Char('r') => {
                self.view = match self.view {
                    View::AsRecorded => View::Rerun,
                    View::Rerun => View::AsRecorded,
                };
                Asked::Nothing
            }
            _ => Asked::View(key),
        }
    }
}

/// A time typed after `:`: seconds (`90`, `12.5`) or minutes and seconds (`1:30`).
pub fn parse_time(text: &str) -> Result<f64, String> {
    let text = text.trim();
    let value = match text.split_once(':') {
        Some((m, s)) => {
            let m: f64 = m
                .parse()
                .map_err(|_| format!("{text:?}: minutes {m:?} is not a number"))?;
            let s: f64 = s
                .parse()
                .map_err(|_| format!("{text:?}: seconds {s:?} is not a number"))?;
            m * 60.0 + s
        }
        None => text
            .parse()
            .map_err(|_| format!("{text:?} is not a time (seconds, or minutes:seconds)"))?,
    };
    if !(value.is_finite() && value >= 0.0) {
        return Err(format!("{text:?} is not a time from the start"));
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(s: &str) -> Key {
        s.parse().unwrap()
    }

    #[test]
    fn playing_moves_at_its_speed_and_stops_at_the_end() {
        let mut p = Playback::new((0.0, 10.0), 2.0, View::AsRecorded, 0.1);
        p.advance(1.5);
        assert!((p.position() - 3.0).abs() < 1e-12);
        p.key(key("]"));
        assert_eq!(p.speed, 5.0);
        p.advance(10.0);
        assert_eq!(p.position(), 10.0);
        assert!(p.paused);
        for _ in 0..20 {
            p.key(key("["));
        }
        assert_eq!(p.speed, 0.1);
    }

    #[test]
    fn keys_seek_step_and_type_a_time() {
        let mut p = Playback::new((0.0, 600.0), 1.0, View::AsRecorded, 0.1);
        assert_eq!(p.key(key("5")), Asked::Seek(300.0));
        assert_eq!(p.key(key("left")), Asked::Seek(295.0));
        let Asked::Seek(t) = p.key(key(".")) else {
            panic!()
        };
        assert!((t - 295.1).abs() < 1e-9 && p.paused);
        p.key(key(":"));
        for c in "1:30".chars() {
            p.key(Key::char(c));
        }
        assert_eq!(p.key(key("enter")), Asked::Seek(90.0));
        p.key(key(":"));
        p.key(Key::char('x'));
        assert_eq!(p.key(key("enter")), Asked::Nothing);
        assert!(p.refusal.as_deref().unwrap().contains("not a time"));
        assert_eq!(p.key(key("r")), Asked::Nothing);
        assert_eq!(p.view, View::Rerun);
        assert_eq!(p.key(key("+")), Asked::View(key("+")));
    }

    #[test]
    fn question_mark_shows_the_keys_and_any_key_closes_them_doing_nothing_else() {
        let mut p = Playback::new((0.0, 600.0), 1.0, View::AsRecorded, 0.1);
        assert_eq!(p.key(key("?")), Asked::Nothing);
        assert!(p.help);
        assert_eq!(p.key(key("q")), Asked::Nothing, "q closes the help only");
        assert!(!p.help);
        p.key(key("?"));
        assert_eq!(p.key(key("5")), Asked::Nothing);
        assert_eq!(p.position(), 0.0);
    }
}
