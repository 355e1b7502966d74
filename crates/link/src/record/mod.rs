//! Recording a session as MCAP with the ROS 2 profile (`ros2msg` schemas, CDR messages),
//! so `ros2 bag`, Foxglove and any MCAP reader open it, and `navdeck replay` plays it.
//!
//! The links layer: the writer runs in the links' runtime's blocking pool (`writer.rs`,
//! `tasks`), on a thread of its own while the file is open. The control
//! loop encodes a message (microseconds) and hands it over without waiting; should the
//! disk stall until the hand-over queue is full, messages are dropped and counted.

pub mod config;
pub mod fleet;
pub mod landmarks;

pub mod reader;
pub mod recorded;
mod recorded_check;
pub mod schema;
pub mod topics;
mod writer;

pub use config::RecordConfig;
use navdeck_msgs::ros::Time;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{SyncSender, TrySendError};
use std::sync::{Arc, Mutex};
pub use topics::Topic;
use writer::Packet;
pub use writer::Summary;

/// Batches (one per call into the console) waiting for the writer at most: about two
/// minutes of a session at ten calls a second.
const QUEUE: usize = 1024;

/// Session seconds, and messages, between hand-overs to the writer at most.
const HAND_OVER_EVERY: f64 = 0.5;
const HAND_OVER_COUNT: usize = 512;

/// The CDR encapsulation header of a little-endian plain CDR message (OMG DDS-XTypes
/// 7.6.3.1.2: representation identifier CDR_LE, options 0).
pub const CDR_LE: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Why a recording could not be started.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    #[error("cannot record to {path}: {why}")]
    Open { path: PathBuf, why: String },
}

/// A recording in progress: one robot's, or one of a fleet's streams in a file it
/// shares with the others (`fleet.rs`).
pub struct Recorder {
    path: PathBuf,
    sender: Option<SyncSender<Vec<Packet>>>,
    /// What was recorded since the last hand-over: one wake-up of the writer per batch.
    pending: Vec<Packet>,
    /// Session time of the last hand-over.
    handed_at: f64,
    /// The writer's task, shared by every stream of the file: the last to close joins it.
    writer: Arc<Mutex<SharedWriter>>,
    /// Where this stream's topics are: each topic's channel in the file, if it has one.
    channels: Vec<Option<usize>>,
    /// Put before this stream's attachment and metadata names (a fleet robot's name).
    prefix: String,
    sequences: Vec<u32>,
    /// Wall time of session time 0, nanoseconds since the Unix epoch: log times and
    /// header stamps are wall time, as a robot's own bag would have them.
    epoch_ns: u64,
    dropped: u64,
    problem: Arc<Mutex<Option<String>>>,
    reported: bool,
    /// Wait for the writer when its queue is full instead of dropping: for sessions on
    /// simulated time, where nothing real waits.
    waits: bool,
    /// Bytes in the file so far, counted by the writer's thread.
    written: Arc<std::sync::atomic::AtomicU64>,
}

/// The writer's task and how many of the file's streams are still open.
struct SharedWriter {
    thread: Option<tokio::task::JoinHandle<Summary>>,
    open: usize,
}

/// A file being written: what every stream of it shares.
struct Started {
    sender: SyncSender<Vec<Packet>>,
    writer: Arc<Mutex<SharedWriter>>,
    problem: Arc<Mutex<Option<String>>>,
    written: Arc<std::sync::atomic::AtomicU64>,
}

/// A CDR message as ROS 2 carries it: the encapsulation header, then the body.
pub fn encode<T: Serialize>(msg: &T) -> Vec<u8> {
    let mut data = CDR_LE.to_vec();
    // Encoding into memory fails only on types CDR cannot carry, none of which are here.
    let _ = cdr_encoding::to_writer::<_, byteorder::LittleEndian, _>(&mut data, msg);
    data
}

/// Decodes a CDR message written by `encode` (or any little-endian ROS 2 publisher).
pub fn decode<T: serde::de::DeserializeOwned>(data: &[u8]) -> Result<T, String> {
    match data {
        [0x00, 0x01, _, _, body @ ..] => {
            cdr_encoding::from_bytes::<T, byteorder::LittleEndian>(body)
                .map(|(msg, _)| msg)
                .map_err(|e| e.to_string())
        }
        [0x00, 0x00, _, _, body @ ..] => cdr_encoding::from_bytes::<T, byteorder::BigEndian>(body)
            .map(|(msg, _)| msg)
            .map_err(|e| e.to_string()),
        _ => Err("not a CDR message (no CDR encapsulation header)".to_string()),
    }
}

impl Recorder {
    /// Starts recording to `path`, which must not exist yet (a recording is never
    /// overwritten). `epoch` is the wall time of session time 0, seconds since the epoch.
    pub fn create(path: &Path, config: &RecordConfig, epoch: f64) -> Result<Self, RecordError> {
        let channels: Vec<writer::Channel> = (topics::TOPICS.iter())
            .map(|(_, name, ty)| (name.to_string(), *ty))
            .collect();
        let started = Self::start(path, config, channels, 1)?;
        let every = (0..topics::TOPICS.len()).map(Some).collect();
        Ok(Self::stream(path, &started, every, String::new(), epoch))
    }

    /// Opens `path` with `channels` and starts the writer's thread, which `streams`
    /// recorders will share.
    fn start(
        path: &Path,
        config: &RecordConfig,
        channels: Vec<writer::Channel>,
        streams: usize,
    ) -> Result<Started, RecordError> {
        let fail = |why: String| RecordError::Open {
            path: path.to_path_buf(),
            why,
        };
        use navdeck_core::data::replace;
        replace::check_name(path, "recording").map_err(|e| fail(e.to_string()))?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            replace::create_folder(dir).map_err(|e| fail(e.to_string()))?;
        }
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(|e| match e.kind() {
                std::io::ErrorKind::AlreadyExists => {
                    fail("the file exists (a recording is never overwritten)".to_string())
                }
                _ => fail(e.to_string()),
            })?;
        let options = writer::Options {
            compression: config.compression,
            level: config.level,
            chunk_period_ns: (config.chunk_period * 1e9) as u64,
        };
        let written = Arc::new(std::sync::atomic::AtomicU64::new(0));
        let file = writer::CountedFile {
            file,
            written: written.clone(),
            position: 0,
        };
        let mcap = writer::open(file, &options, &channels).map_err(|e| fail(e.to_string()))?;
        let (sender, packets) = std::sync::mpsc::sync_channel(QUEUE);
        let problem = Arc::new(Mutex::new(None));
        let shared = problem.clone();
        let thread = crate::tasks::spawn_blocking(move || {
            writer::run(mcap, packets, options, channels, shared)
        })
        .map_err(|e| fail(e.to_string()))?;
        Ok(Started {
            sender,
            writer: Arc::new(Mutex::new(SharedWriter {
                thread: Some(thread),
                open: streams,
            })),
            problem,
            written,
        })
    }

    /// One stream into the file `started` writes: its topics on `channels`.
    fn stream(
        path: &Path,
        started: &Started,
        channels: Vec<Option<usize>>,
        prefix: String,
        epoch: f64,
    ) -> Self {
        Self {
            path: path.to_path_buf(),
            sender: Some(started.sender.clone()),
            pending: Vec::new(),
            handed_at: f64::NEG_INFINITY,
            writer: started.writer.clone(),
            channels,
            prefix,
            sequences: vec![0; topics::TOPICS.len()],
            epoch_ns: (epoch.max(0.0) * 1e9) as u64,
            dropped: 0,
            problem: started.problem.clone(),
            reported: false,
            waits: false,
            written: started.written.clone(),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Bytes the writer has put in the file so far (it writes a chunk at a time).
    pub fn bytes_written(&self) -> u64 {
        self.written.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Nanoseconds since the epoch of session time `t`.
    pub fn time_ns(&self, t: f64) -> u64 {
        self.epoch_ns
            .saturating_add((t.max(0.0) * 1e9).round() as u64)
    }

    /// Session time `t` as a ROS 2 header stamp.
    pub fn stamp(&self, t: f64) -> Time {
        let ns = self.time_ns(t);
        Time {
            sec: (ns / 1_000_000_000).min(i32::MAX as u64) as i32,
            nanosec: (ns % 1_000_000_000) as u32,
        }
    }

    /// Whether a full queue makes the caller wait (simulated time) or drops (real time).
    pub fn wait_when_full(&mut self, waits: bool) {
        self.waits = waits;
    }

    fn send(&mut self, packet: Packet) {
        if self.sender.is_some() {
            self.pending.push(packet);
        }
    }

    /// Hands what was recorded to the writer when half a second of session time (`t`)
    /// has passed since the last hand-over or much is waiting: few wake-ups of its thread.
    pub fn hand_over_due(&mut self, t: f64) {
        if t - self.handed_at >= HAND_OVER_EVERY || self.pending.len() >= HAND_OVER_COUNT {
            self.handed_at = t;
            self.hand_over();
        }
    }

    /// Hands everything over and waits until the writer has written it: for benchmarks
    /// that pace the control loop as real time does, the writer idle between ticks.
    pub fn wait_for_writer(&mut self) {
        let (done, written) = std::sync::mpsc::channel();
        self.pending.push(Packet::Barrier(done));
        let waits = std::mem::replace(&mut self.waits, true);
        self.hand_over();
        self.waits = waits;
        let _ = written.recv();
    }

    /// Hands what was recorded since the last call to the writer, in one batch.
    pub fn hand_over(&mut self) {
        if self.pending.is_empty() {
            return;
        }
        let batch = std::mem::take(&mut self.pending);
        let Some(sender) = &self.sender else {
            return;
        };
        if self.waits {
            if sender.send(batch).is_err() {
                self.sender = None;
            }
            return;
        }
        match sender.try_send(batch) {
            Ok(()) => {}
            Err(TrySendError::Full(batch)) => self.dropped += batch.len() as u64,
            Err(TrySendError::Disconnected(_)) => self.sender = None,
        }
    }

    /// Records `msg` on `topic` at session time `t` (encoded on the writer's thread).
    pub fn publish<T: Serialize + Send + 'static>(&mut self, topic: Topic, t: f64, msg: T) {
        self.publish_with(topic, t, move || msg);
    }

    /// Records on `topic` at session time `t` the message `make` builds, on the writer's
    /// thread: the control loop only captures what it needs.
    pub fn publish_with<T: Serialize>(
        &mut self,
        topic: Topic,
        t: f64,
        make: impl FnOnce() -> T + Send + 'static,
    ) {
        let i = topic.index();
        // A stream without this topic (a fleet's own) records none of it.
        let Some(channel) = self.channels.get(i).copied().flatten() else {
            return;
        };
        let sequence = self.sequences[i];
        self.sequences[i] = sequence.wrapping_add(1);
        let time_ns = self.time_ns(t);
        self.send(Packet::Message {
            channel,
            sequence,
            time_ns,
            data: Box::new(move || encode(&make())),
        });
    }

    /// What this stream's attachment and metadata names start with: a fleet robot's name
    /// and a slash, or nothing for one robot.
    pub fn name_prefix(&self) -> &str {
        &self.prefix
    }

    /// Attaches a file (the session's config, the twin's world).
    pub fn attach(&mut self, name: &str, media_type: &str, data: Vec<u8>) {
        let time_ns = self.time_ns(0.0);
        self.send(Packet::Attachment {
            name: format!("{}{name}", self.prefix),
            media_type: media_type.to_string(),
            time_ns,
            data,
        });
    }

    /// A metadata record (how the session was started).
    pub fn metadata(&mut self, name: &str, entries: BTreeMap<String, String>) {
        self.send(Packet::Metadata {
            name: format!("{}{name}", self.prefix),
            entries,
        });
    }

    /// What went wrong with the recording, once: the writer's failure or dropped messages.
    pub fn take_problem(&mut self) -> Option<String> {
        if self.reported {
            return None;
        }
        let failed = self.problem.lock().ok().and_then(|p| p.clone());
        let why = failed.or_else(|| {
            (self.dropped > 0)
                .then(|| format!("{} messages dropped: the disk is too slow", self.dropped))
        })?;
        self.reported = true;
        Some(format!("recording {}: {why}", self.path.display()))
    }

    /// Closes the recording (summary and footer) and says what it holds.
    pub fn finish(mut self) -> Result<Summary, String> {
        self.close()
    }

    /// Closes this stream; the file's last stream to close waits for the writer to
    /// finish the file, and says what it holds. The others say only how far it has got.
    fn close(&mut self) -> Result<Summary, String> {
        self.hand_over();
        if self.sender.take().is_none() && self.channels.is_empty() {
            return Err("already closed".into());
        }
        // Marks this stream closed for good (a second close finds no channels).
        self.channels.clear();
        let thread = match self.writer.lock() {
            Ok(mut shared) => {
                shared.open = shared.open.saturating_sub(1);
                if shared.open == 0 {
                    shared.thread.take()
                } else {
                    None
                }
            }
            Err(_) => None,
        };
        let Some(thread) = thread else {
            return Ok(Summary {
                path: self.path.display().to_string(),
                bytes: self.bytes_written(),
                dropped: self.dropped,
                ..Summary::default()
            });
        };
        let mut summary = crate::tasks::join(thread)
            .ok_or_else(|| "the recording's writer panicked".to_string())?;
        summary.dropped = self.dropped;
        summary.path = self.path.display().to_string();
        match self.problem.lock().ok().and_then(|p| p.clone()) {
            Some(why) => Err(format!("recording {}: {why}", self.path.display())),
            None => Ok(summary),
        }
    }
}

impl Drop for Recorder {
    /// However the session ends, the file gets its summary and footer.
    fn drop(&mut self) {
        let _ = self.close();
    }
}
