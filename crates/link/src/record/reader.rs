//! Reading a recording back, forgiving: every message up to the first damage is kept,
//! and the damage is named with its byte offset. A file cut short by a crash, a foreign
//! MCAP file or one with a bad chunk never panics the reader.

use mcap::records::Record;
use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

/// The 8 bytes an MCAP file starts (and ends) with.
const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";
/// A chunk may unpack to this many bytes at most (a lying header must not exhaust memory).
const MAX_CHUNK: u64 = 256 << 20;
/// All of a recording's chunks together may unpack to this many bytes at most: many small
/// chunks each under `MAX_CHUNK` must not add up to more than a machine holds.
pub const MAX_UNPACKED: u64 = 1 << 30;
/// Message and attachment bytes kept from one recording, at most: a 10 Hz session with a
/// camera thumbnail records about 10 kB/s, so this is some 14 hours.
pub const MAX_KEPT: u64 = 512 << 20;

/// One message as the file holds it. Its channel's names are shared by every message on
/// the channel, never copied per message.
#[derive(Clone, Debug, PartialEq)]
pub struct RawMessage {
    pub topic: Arc<str>,
    /// The channel's schema name, e.g. `nav_msgs/Odometry`.
    pub schema: Arc<str>,
    pub encoding: Arc<str>,
    pub log_time: u64,
    pub data: Vec<u8>,
}

/// Everything readable in a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawRecording {
    pub profile: String,
    pub library: String,
    /// In log-time order.
    pub messages: Vec<RawMessage>,
    pub attachments: Vec<(String, Vec<u8>)>,
    pub metadata: Vec<(String, BTreeMap<String, String>)>,
    /// Where reading stopped early and why: "offset 1234: ...".
    pub damage: Option<String>,
}

#[derive(Default)]
struct State {
    schemas: HashMap<u16, Arc<str>>,
    /// Channel ID -> (topic, schema name, message encoding).
    channels: HashMap<u16, Channel>,
    out: RawRecording,
    /// Bytes unpacked from chunks so far, and message and attachment bytes kept.
    unpacked: u64,
    kept: u64,
}

/// A channel's topic, schema name and message encoding.
type Channel = (Arc<str>, Arc<str>, Arc<str>);

impl State {
    /// Takes one record; an error names what was wrong with it.
    fn take(&mut self, record: Record<'_>) -> Result<bool, String> {
        match record {
            Record::Header(h) => {
                self.out.profile = h.profile;
                self.out.library = h.library;
            }
            Record::Schema { header, .. } => {
                self.schemas.insert(header.id, header.name.into());
            }
            Record::Channel(c) => {
                let schema = self.schemas.get(&c.schema_id).cloned().unwrap_or_default();
                self.channels
                    .insert(c.id, (c.topic.into(), schema, c.message_encoding.into()));
            }
            Record::Message { header, data } => {
                let Some((topic, schema, encoding)) =
                    self.channels.get(&header.channel_id).cloned()
                else {
                    return Err(format!(
                        "a message on channel {} that no channel record announced",
                        header.channel_id
                    ));
                };
                self.keep(data.len())?;
                self.out.messages.push(RawMessage {
                    topic,
                    schema,
                    encoding,
                    log_time: header.log_time,
                    data: data.into_owned(),
                });
            }
            Record::Attachment { header, data, .. } => {
                self.keep(data.len())?;
                self.out.attachments.push((header.name, data.into_owned()));
            }
            Record::Metadata(m) => self.out.metadata.push((m.name, m.metadata)),
            // The data section ends here; the summary repeats what was read.
            Record::DataEnd(_) | Record::Footer(_) => return Ok(false),
            _ => {}
        }
        Ok(true)
    }

    /// Counts `bytes` more kept, refusing past `MAX_KEPT`.
    fn keep(&mut self, bytes: usize) -> Result<(), String> {
        self.kept += bytes as u64;
        if self.kept > MAX_KEPT {
            return Err(format!(
                "its messages come to over {} MiB, the most navdeck reads of one recording",
                MAX_KEPT >> 20
            ));
        }
        Ok(())
    }
}

/// Reads every message, attachment and metadata record `bytes` holds up to the first damage.
pub fn read(bytes: &[u8]) -> RawRecording {
    let mut state = State::default();
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        state.out.damage =
            Some("offset 0: not an MCAP file (it does not start with MCAP's magic bytes)".into());
        return state.out;
    }
    let damage = match records(&mut state, bytes, MAGIC.len(), true) {
        Ok(_) => None,
        Err(Damage { at, why }) => Some(format!("offset {at}: {why}")),
    };
    state.out.damage = damage;
    state.out.messages.sort_by_key(|m| m.log_time);
    state.out
}

/// What is wrong, and where (a byte offset in the file).
struct Damage {
    at: usize,
    why: String,
}

/// Takes the records of `bytes` from `start` on: the file's (`top`, where the footer is
/// due and chunks are opened) or one chunk's unpacked records. Ok(false): the data ended.
/// Every length is checked against what is there before anything is read or allocated.
fn records(state: &mut State, bytes: &[u8], start: usize, top: bool) -> Result<bool, Damage> {
    let mut at = start;
    let fail = |at: usize, why: String| Err(Damage { at, why });
    while at < bytes.len() || top {
        if at == bytes.len() {
            return fail(at, "the file ends without its footer (cut short?)".into());
        }
        let Some(head) = bytes.get(at..at + 9) else {
            return fail(at, "the data ends inside a record's header".into());
        };
        let op = head[0];
        let mut len = [0u8; 8];
        len.copy_from_slice(&head[1..9]);
        let len = u64::from_le_bytes(len);
        let body_start = at + 9;
        let Some(body) = usize::try_from(len)
            .ok()
            .and_then(|n| body_start.checked_add(n))
            .and_then(|end| bytes.get(body_start..end))
        else {
            let left = bytes.len() - body_start;
            return fail(
                at,
                format!("a record of {len} bytes, but only {left} follow (cut short?)"),
            );
        };
        let record = match mcap::read::parse_record(op, body) {
            Ok(r) => r,
            Err(e) => {
                return fail(
                    at,
                    format!("a bad record (opcode 0x{op:02x}): {}", said(&e)),
                );
            }
        };
        let go_on = match record {
            Record::Chunk { header, data } if top => read_chunk(state, header, &data),
            Record::Chunk { .. } => Err("a chunk inside a chunk".to_string()),
            other => state.take(other),
        };
        match go_on {
            Ok(true) => at = body_start + body.len(),
            Ok(false) => return Ok(false),
            Err(why) => return fail(at, why),
        }
    }
    Ok(true)
}

/// What MCAP's reader found wrong, in navdeck's words where its own are unclear.
fn said(e: &mcap::McapError) -> String {
    use mcap::McapError as E;
    let crc = |what: &str, saved: u32, calculated: u32| {
        format!(
            "{what} whose CRC does not match its contents (stored {saved:08X}, computed {calculated:08X})"
        )
    };
    match e {
        E::BadAttachmentCrc { saved, calculated } => crc("an attachment", *saved, *calculated),
        E::BadChunkCrc { saved, calculated } => crc("a chunk", *saved, *calculated),
        E::BadDataCrc { saved, calculated } => crc("a data section", *saved, *calculated),
        E::BadSummaryCrc { saved, calculated } => crc("a summary section", *saved, *calculated),
        E::ConflictingChannels(name) => format!("two different channels named {name:?}"),
        E::ConflictingSchemas(name) => format!("two different schemas named {name:?}"),
        other => other.to_string(),
    }
}

/// Unpacks one chunk (never past the size its header gives, at most `MAX_CHUNK`, nor past
/// `MAX_UNPACKED` for the whole file), checks its CRC and takes its records.
fn read_chunk(
    state: &mut State,
    header: mcap::records::ChunkHeader,
    data: &[u8],
) -> Result<bool, String> {
    let size = header.uncompressed_size;
    if size > MAX_CHUNK {
        return Err(format!(
            "a chunk claims {size} bytes unpacked, over the {} MiB navdeck unpacks of one chunk",
            MAX_CHUNK >> 20
        ));
    }
    state.unpacked += size;
    if state.unpacked > MAX_UNPACKED {
        return Err(format!(
            "its chunks claim over {} MiB unpacked in all, the most navdeck unpacks of one recording",
            MAX_UNPACKED >> 20
        ));
    }
    let unpacked = unpack(&header.compression, data, size)?;
    let got = unpacked.len() as u64;
    if got > size {
        return Err(format!(
            "a chunk unpacks to more than the {size} bytes its header gives"
        ));
    }
    if got < size {
        return Err(format!(
            "a chunk unpacks to {got} bytes, not the {size} its header gives"
        ));
    }
    if header.uncompressed_crc != 0 && crc32fast::hash(&unpacked) != header.uncompressed_crc {
        return Err("a chunk whose CRC does not match its contents".into());
    }
    match records(state, &unpacked, 0, false) {
        Ok(go_on) => Ok(go_on),
        Err(Damage { at, why }) => Err(format!("in a chunk, at {at} of its records: {why}")),
    }
}

/// `data` unpacked with `compression`, reading at most `size` + 1 bytes.
fn unpack(compression: &str, data: &[u8], size: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let mut out = Vec::new();
    let result = match compression {
        "" => return Ok(data.to_vec()),
        "zstd" => zstd::stream::read::Decoder::new(data)
            .and_then(|d| d.take(size + 1).read_to_end(&mut out)),
        "lz4" => lz4::Decoder::new(data).and_then(|d| d.take(size + 1).read_to_end(&mut out)),
        other => {
            return Err(format!(
                "a chunk compressed with {other:?}, which navdeck does not read"
            ));
        }
    };
    result.map_err(|e| format!("a chunk that does not unpack ({compression}): {e}"))?;
    Ok(out)
}
