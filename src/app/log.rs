//! The status log: timestamped, levelled lines in the spirit of seed 001's console.

pub use crate::data::Level;
use std::collections::VecDeque;

#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Session time, seconds.
    pub time: f64,
    pub level: Level,
    pub text: String,
}

/// A bounded log; the oldest lines fall off.
#[derive(Clone, Debug)]
pub struct LogBook {
    entries: VecDeque<Entry>,
    capacity: usize,
    /// Lines ever written, so a view can tell something new arrived.
    written: u64,
}

impl LogBook {
    pub fn new(capacity: usize) -> Self {
        Self {
            entries: VecDeque::with_capacity(capacity),
            capacity,
            written: 0,
        }
    }

    pub fn push(&mut self, time: f64, level: Level, text: impl Into<String>) {
        if self.entries.len() == self.capacity {
            self.entries.pop_front();
        }
        self.entries.push_back(Entry {
            time,
            level,
            text: text.into(),
        });
        self.written += 1;
    }

    /// The newest `n` entries, oldest first.
    pub fn tail(&self, n: usize) -> impl Iterator<Item = &Entry> {
        self.entries
            .iter()
            .skip(self.entries.len().saturating_sub(n))
    }

    pub fn written(&self) -> u64 {
        self.written
    }

    pub fn last(&self) -> Option<&Entry> {
        self.entries.back()
    }

    pub fn iter(&self) -> impl Iterator<Item = &Entry> {
        self.entries.iter()
    }

    /// Warnings and errors, oldest first: what the run reports list.
    pub fn problems(&self) -> impl Iterator<Item = &Entry> {
        self.entries.iter().filter(|e| e.level >= Level::Warn)
    }
}

/// Session time as `mm:ss.d`, the log's timestamp.
pub fn format_time(t: f64) -> String {
    let tenths = (t.max(0.0) * 10.0).floor() as u64;
    format!(
        "{:02}:{:02}.{}",
        tenths / 600,
        (tenths / 10) % 60,
        tenths % 10
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oldest_lines_fall_off() {
        let mut log = LogBook::new(2);
        log.push(0.0, Level::Info, "a");
        log.push(1.0, Level::Warn, "b");
        log.push(2.0, Level::Error, "c");
        let texts: Vec<_> = log.tail(5).map(|e| e.text.as_str()).collect();
        assert_eq!(texts, ["b", "c"]);
        assert_eq!(log.written(), 3);
    }

    #[test]
    fn time_format_is_minutes_seconds_tenths() {
        assert_eq!(format_time(0.0), "00:00.0");
        assert_eq!(format_time(75.34), "01:15.3");
    }
}
