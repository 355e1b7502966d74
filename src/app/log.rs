//! The status log: timestamped, levelled lines in the spirit of seed 001's console.

pub use crate::data::Level;
use std::collections::VecDeque;

#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Session time, seconds.
    pub time: f64,
    pub level: Level,
    pub text: String,
    /// How many lines of the same shape in a row this one stands for (routine lines such
    /// as "new landmark 25 (boundary)", and a held key's refusals such as "emergency stop
    /// is on: …", collapse into the last of them); 1 for most.
    pub repeats: u32,
    /// The robot's node that said it (its /rosout), or None for navdeck's own line.
    pub source: Option<String>,
}

/// How long a flashed line stays in the status panel, seconds of session time (Material
/// Design's snackbar shows for 4 to 10 s).
pub const FLASH_SECONDS: f64 = 5.0;

/// Where every line also goes as it is written: the session's log file.
pub type Sink = Box<dyn std::io::Write + Send>;

/// A bounded log. When full, the oldest routine (info) line falls off first, so mission
/// events and warnings outlive the chatter around them.
pub struct LogBook {
    entries: VecDeque<Entry>,
    capacity: usize,
    /// Lines ever written, so a view can tell something new arrived.
    written: u64,
    sink: Option<Sink>,
    /// Lines written since the last `take_fresh`, when something takes them (a recording,
    /// a link that passes the log on to /rosout).
    fresh: Option<Vec<Entry>>,
    /// A notable line (a loop closed) shown highlighted for `FLASH_SECONDS` after it.
    flashed: Option<Entry>,
}

impl std::fmt::Debug for LogBook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LogBook")
            .field("entries", &self.entries.len())
            .field("written", &self.written)
            .field("sink", &self.sink.is_some())
            .field("flashed", &self.flashed)
            .finish()
    }
}

/// A line's shape: its text with every run of digits (and a sign or decimal point in
/// it) replaced by `#`, so "new landmark 25" and "new landmark 26" are alike.
fn shape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_number = false;
    for c in text.chars() {
        let numeric = c.is_ascii_digit() || (in_number && c == '.');
        if numeric {
            if !in_number {
                out.push('#');
            }
        } else {
            out.push(c);
        }
        in_number = numeric;
    }
    out
}

impl Entry {
    /// The text as the log shows it: a robot node's line names the node.
    pub fn sourced_text(&self) -> String {
        sourced(self.source.as_deref(), &self.text)
    }
}

impl LogBook {
    pub fn new(capacity: usize) -> Self {
        Self {
            entries: VecDeque::with_capacity(capacity),
            capacity: capacity.max(1),
            written: 0,
            sink: None,
            fresh: None,
            flashed: None,
        }
    }

    /// Every line from now on is also written to `sink`, one `mm:ss.d TAG text` a line;
    /// the lines already in the book go first.
    pub fn set_sink(&mut self, mut sink: Sink) -> std::io::Result<()> {
        for e in &self.entries {
            for _ in 0..e.repeats {
                writeln!(sink, "{}", file_line(e))?;
            }
        }
        sink.flush()?;
        self.sink = Some(sink);
        Ok(())
    }

    pub fn push(&mut self, time: f64, level: Level, text: impl Into<String>) {
        self.push_from(time, level, None, text);
    }

    /// A line said by `source` (a robot node's /rosout), or navdeck's own when None.
    pub fn push_from(
        &mut self,
        time: f64,
        level: Level,
        source: Option<String>,
        text: impl Into<String>,
    ) {
        let text: String = text.into();
        let source = source.map(|s| crate::data::printable::printable(&s, None));
        // Lines may quote what a file or a peer sent: only printable text reaches the screen.
        let text = if text.chars().any(char::is_control) {
            crate::data::printable::printable(&text.replace('\n', " "), None)
        } else {
            text
        };
        let entry = Entry {
            time,
            level,
            text,
            repeats: 1,
            source,
        };
        self.written += 1;
        if let Some(fresh) = self.fresh.as_mut() {
            fresh.push(entry.clone());
        }
        if let Some(sink) = self.sink.as_mut() {
            let written = writeln!(sink, "{}", file_line(&entry)).and_then(|()| sink.flush());
            if written.is_err() {
                // A full disk or a closed file must not stop the console: the file ends.
                self.sink = None;
            }
        }
        // Lines of one shape in a row collapse, whatever their level, except events
        // (successes: "Found red block 421", "…423" are two finds).
        if let Some(last) = self.entries.back_mut()
            && level != Level::Success
            && last.level == level
            && last.source == entry.source
            && shape(&last.text) == shape(&entry.text)
        {
            let repeats = last.repeats + 1;
            *last = Entry { repeats, ..entry };
            return;
        }
        if self.entries.len() == self.capacity {
            let routine = self.entries.iter().position(|e| e.level == Level::Info);
            self.entries.remove(routine.unwrap_or(0));
        }
        self.entries.push_back(entry);
    }

    /// From now on every line is also kept until `take_fresh` takes it.
    pub fn keep_fresh(&mut self) {
        self.fresh.get_or_insert_with(Vec::new);
    }

    /// Every line in the book, oldest first, a collapsed run as its lines again.
    pub fn expanded(&self) -> Vec<Entry> {
        let lines = self.entries.iter().flat_map(|e| {
            std::iter::repeat_n(
                Entry {
                    repeats: 1,
                    ..e.clone()
                },
                e.repeats as usize,
            )
        });
        lines.collect()
    }

    /// The lines written since the last call (with `keep_fresh` on).
    pub fn take_fresh(&mut self) -> Vec<Entry> {
        self.fresh.as_mut().map(std::mem::take).unwrap_or_default()
    }

    /// The newest `n` entries, oldest first.
    pub fn tail(&self, n: usize) -> impl Iterator<Item = &Entry> {
        self.entries
            .iter()
            .skip(self.entries.len().saturating_sub(n))
    }

    /// Flashes the newest line: the status panel shows it highlighted for a while.
    pub fn flash_newest(&mut self) {
        self.flashed = self.entries.back().map(|e| Entry {
            repeats: 1,
            ..e.clone()
        });
    }

    /// The flashed line, while it is fresh at session time `now`.
    pub fn flashing(&self, now: f64) -> Option<&Entry> {
        self.flashed
            .as_ref()
            .filter(|e| (0.0..FLASH_SECONDS).contains(&(now - e.time)))
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

/// One line of the log file.
fn file_line(e: &Entry) -> String {
    format!(
        "{} {} {}",
        format_time(e.time),
        e.level.tag(),
        e.sourced_text()
    )
}

/// `text` as the log shows it: `[node] text` for a robot node's line.
pub fn sourced(source: Option<&str>, text: &str) -> String {
    match source {
        Some(node) => format!("[{node}] {text}"),
        None => text.to_string(),
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
    fn a_robot_nodes_lines_keep_its_name_and_do_not_collapse_into_navdecks() {
        let mut log = LogBook::new(10);
        log.push(0.0, Level::Info, "new landmark 1 (boundary)");
        log.push_from(
            0.1,
            Level::Info,
            Some("lidar".into()),
            "new landmark 2 (boundary)",
        );
        log.push_from(
            0.2,
            Level::Info,
            Some("lidar".into()),
            "new landmark 3 (boundary)",
        );
        let lines: Vec<_> = log
            .iter()
            .map(|e| (e.source.as_deref(), e.repeats))
            .collect();
        assert_eq!(lines, [(None, 1), (Some("lidar"), 2)]);
        assert_eq!(
            file_line(log.last().unwrap()),
            "00:00.2 INFO [lidar] new landmark 3 (boundary)"
        );
    }

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
    fn lines_of_one_shape_collapse_and_events_do_not() {
        let mut log = LogBook::new(10);
        for id in 25..37 {
            log.push(1.0, Level::Info, format!("new landmark {id} (boundary)"));
        }
        log.push(2.0, Level::Success, "Found red block 421");
        log.push(2.1, Level::Success, "Found red block 423");
        for t in 0..50 {
            let at = 3.0 + f64::from(t) / 30.0;
            log.push(at, Level::Warn, "emergency stop is on: press it again");
        }
        let lines: Vec<_> = log.iter().map(|e| (e.text.as_str(), e.repeats)).collect();
        assert_eq!(
            lines,
            [
                ("new landmark 36 (boundary)", 12),
                ("Found red block 421", 1),
                ("Found red block 423", 1),
                ("emergency stop is on: press it again", 50)
            ]
        );
        assert_eq!(log.written(), 64);
    }

    #[test]
    fn when_full_routine_lines_go_before_events() {
        let mut log = LogBook::new(3);
        log.push(0.0, Level::Success, "Picked up red block 421");
        log.push(1.0, Level::Info, "following path");
        log.push(2.0, Level::Warn, "path blocked");
        log.push(3.0, Level::Info, "mode MANUAL");
        let texts: Vec<_> = log.iter().map(|e| e.text.as_str()).collect();
        assert_eq!(
            texts,
            ["Picked up red block 421", "path blocked", "mode MANUAL"]
        );
    }

    /// A sink that keeps what it was given.
    #[derive(Clone, Default)]
    struct Shared(std::sync::Arc<std::sync::Mutex<Vec<u8>>>);

    impl std::io::Write for Shared {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn the_file_gets_every_line_uncollapsed_earlier_ones_first() {
        let mut log = LogBook::new(10);
        log.push(0.0, Level::Info, "new landmark 1 (boundary)");
        let file = Shared::default();
        log.set_sink(Box::new(file.clone())).unwrap();
        log.push(0.5, Level::Info, "new landmark 2 (boundary)");
        log.push(75.34, Level::Warn, "gripper opened by the user");
        let text = String::from_utf8(file.0.lock().unwrap().clone()).unwrap();
        assert_eq!(
            text,
            "00:00.0 INFO new landmark 1 (boundary)\n\
             00:00.5 INFO new landmark 2 (boundary)\n\
             01:15.3 WARN gripper opened by the user\n"
        );
    }

    #[test]
    fn a_flashed_line_shows_for_a_few_seconds_of_session_time() {
        let mut log = LogBook::new(10);
        log.push(
            10.0,
            Level::Success,
            "loop closed: 0.31 m corrected over 42 nodes",
        );
        assert!(log.flashing(10.0).is_none(), "nothing flashed yet");
        log.flash_newest();
        log.push(10.5, Level::Info, "mode MANUAL");
        let shown = |t| log.flashing(t).map(|e| e.text.clone());
        assert_eq!(
            shown(10.0 + FLASH_SECONDS - 0.1).as_deref(),
            Some("loop closed: 0.31 m corrected over 42 nodes")
        );
        assert_eq!(shown(10.0 + FLASH_SECONDS), None);
    }

    #[test]
    fn time_format_is_minutes_seconds_tenths() {
        assert_eq!(format_time(0.0), "00:00.0");
        assert_eq!(format_time(75.34), "01:15.3");
    }
}
