//! The recording's writer, in the links' runtime's blocking pool: it owns the file and the MCAP writer, so the control loop
//! only ever hands it a finished message and never waits on the disk.

use super::config::Compression;
use super::schema::schema;
use mcap::records::MessageHeader;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::Receiver;
use std::sync::{Arc, Mutex};

/// A message's CDR bytes, made on the writer's thread: the control loop only builds the
/// message.
pub(super) type Encoder = Box<dyn FnOnce() -> Vec<u8> + Send>;

/// What the control loop hands the writer.
pub(super) enum Packet {
    Message {
        /// The channel's index in the file's channel list (its ID less one).
        channel: usize,
        sequence: u32,
        time_ns: u64,
        data: Encoder,
    },
    Attachment {
        name: String,
        media_type: String,
        time_ns: u64,
        data: Vec<u8>,
    },
    Metadata {
        name: String,
        entries: BTreeMap<String, String>,
    },
    /// Answered once everything before it is written (`Recorder::wait_for_writer`).
    Barrier(std::sync::mpsc::Sender<()>),
}

/// What a finished recording holds.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Summary {
    pub path: String,
    pub bytes: u64,
    /// (topic, ROS 2 type, messages), in channel order.
    pub topics: Vec<(String, String, u64)>,
    /// Messages the writer could not keep up with (none unless the disk stalled).
    pub dropped: u64,
}

pub(super) struct Options {
    pub compression: Compression,
    pub level: u32,
    pub chunk_period_ns: u64,
}

/// The recording's file, keeping its length where the console can read it as it grows.
pub(super) struct CountedFile {
    pub file: File,
    /// The file's length so far, bytes.
    pub written: Arc<AtomicU64>,
    /// Where the next write goes (the MCAP writer seeks back to fill in lengths).
    pub position: u64,
}

impl Write for CountedFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.position += n as u64;
        self.written.fetch_max(self.position, Ordering::Relaxed);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl std::io::Seek for CountedFile {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        self.position = self.file.seek(pos)?;
        Ok(self.position)
    }
}

type McapWriter = mcap::Writer<BufWriter<CountedFile>>;

/// One channel of the file: its topic and ROS 2 type. Channel IDs are the index in the
/// list plus one.
pub(super) type Channel = (String, &'static str);

/// Opens the MCAP file on `file` and registers every channel of `channels`, each type's
/// schema once.
pub(super) fn open(
    file: CountedFile,
    options: &Options,
    channels: &[Channel],
) -> Result<McapWriter, mcap::McapError> {
    let compression = match options.compression {
        Compression::Zstd => Some(mcap::Compression::Zstd),
        Compression::Lz4 => Some(mcap::Compression::Lz4),
        Compression::None => None,
    };
    let write_options = mcap::WriteOptions::new()
        .compression(compression)
        .compression_level(options.level)
        .profile("ros2")
        .library(concat!("navdeck ", env!("CARGO_PKG_VERSION")))
        // Chunks close on time (`chunk_period`); this only bounds a burst.
        .chunk_size(Some(4 << 20));
    let mut writer = mcap::Writer::with_options(BufWriter::new(file), write_options)?;
    let mut schemas = BTreeMap::new();
    for (i, (topic, ty)) in channels.iter().enumerate() {
        let schema_id = match schemas.get(ty) {
            Some(id) => *id,
            None => {
                let text = schema(ty).unwrap_or_default();
                let id = writer.add_schema(ty, "ros2msg", text.as_bytes())?;
                schemas.insert(*ty, id);
                id
            }
        };
        let id = writer.add_channel(schema_id, topic, "cdr", &BTreeMap::new())?;
        debug_assert_eq!(usize::from(id), i + 1);
    }
    writer.flush()?;
    Ok(writer)
}

/// Writes what arrives until the sender goes, then the summary and footer. A failure
/// is put in `problem` and ends the writing (what was written stays readable).
pub(super) fn run(
    mut writer: McapWriter,
    packets: Receiver<Vec<Packet>>,
    options: Options,
    channels: Vec<Channel>,
    problem: Arc<Mutex<Option<String>>>,
) -> Summary {
    let mut counts = vec![0u64; channels.len()];
    let mut chunk_start: Option<u64> = None;
    let mut failed = None;
    for packet in packets.iter().flatten() {
        if failed.is_some() {
            if let Packet::Barrier(done) = packet {
                let _ = done.send(());
            }
            continue;
        }
        let result = match packet {
            Packet::Message {
                channel,
                sequence,
                time_ns,
                data,
            } => {
                if let Some(count) = counts.get_mut(channel) {
                    *count += 1;
                }
                let header = MessageHeader {
                    channel_id: (channel + 1) as u16,
                    sequence,
                    log_time: time_ns,
                    publish_time: time_ns,
                };
                let start = *chunk_start.get_or_insert(time_ns);
                writer
                    .write_to_known_channel(&header, &data())
                    .and_then(|()| {
                        // Closing the chunk on time makes it readable after a crash.
                        if time_ns.saturating_sub(start) >= options.chunk_period_ns {
                            chunk_start = None;
                            writer.flush()
                        } else {
                            Ok(())
                        }
                    })
            }
            Packet::Attachment {
                name,
                media_type,
                time_ns,
                data,
            } => writer.attach(&mcap::Attachment {
                log_time: time_ns,
                create_time: time_ns,
                name,
                media_type,
                data: data.into(),
            }),
            Packet::Metadata { name, entries } => writer.write_metadata(&mcap::records::Metadata {
                name,
                metadata: entries,
            }),
            Packet::Barrier(done) => {
                let _ = done.send(());
                Ok(())
            }
        };
        if let Err(e) = result {
            failed = Some(e.to_string());
        }
    }
    if failed.is_none()
        && let Err(e) = writer.finish()
    {
        failed = Some(e.to_string());
    }
    let bytes = writer
        .into_inner()
        .into_inner()
        .ok()
        .and_then(|f| f.file.metadata().ok())
        .map_or(0, |m| m.len());
    if let Some(why) = failed
        && let Ok(mut slot) = problem.lock()
    {
        *slot = Some(why);
    }
    Summary {
        path: String::new(),
        bytes,
        topics: channels
            .into_iter()
            .zip(counts)
            .map(|((name, ty), n)| (name, ty.to_string(), n))
            .collect(),
        dropped: 0,
    }
}
