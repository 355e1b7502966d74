//! Reading a recording back, forgiving: every message up to the first damage is kept,
//! and the damage is named with its byte offset. A file cut short by a crash, a foreign
//! MCAP file or one with a bad chunk never panics the reader.

use mcap::records::Record;
use std::collections::{BTreeMap, HashMap};

/// The 8 bytes an MCAP file starts (and ends) with.
const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";
/// A chunk may unpack to this many bytes at most (a lying header must not exhaust memory).
const MAX_CHUNK: u64 = 256 << 20;

/// One message as the file holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct RawMessage {
    pub topic: String,
    /// The channel's schema name, e.g. `nav_msgs/Odometry`.
    pub schema: String,
    pub encoding: String,
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
    schemas: HashMap<u16, String>,
    /// Channel ID -> (topic, schema ID, message encoding).
    channels: HashMap<u16, (String, u16, String)>,
    out: RawRecording,
}

impl State {
    /// Takes one record; an error names what was wrong with it.
    fn take(&mut self, record: Record<'_>) -> Result<bool, String> {
        match record {
            Record::Header(h) => {
                self.out.profile = h.profile;
                self.out.library = h.library;
            }
            Record::Schema { header, .. } => {
                self.schemas.insert(header.id, header.name);
            }
            Record::Channel(c) => {
                self.channels
                    .insert(c.id, (c.topic, c.schema_id, c.message_encoding));
            }
            Record::Message { header, data } => {
                let Some((topic, schema_id, encoding)) = self.channels.get(&header.channel_id)
                else {
                    return Err(format!(
                        "a message on channel {} that no channel record announced",
                        header.channel_id
                    ));
                };
                self.out.messages.push(RawMessage {
                    topic: topic.clone(),
                    schema: self.schemas.get(schema_id).cloned().unwrap_or_default(),
                    encoding: encoding.clone(),
                    log_time: header.log_time,
                    data: data.into_owned(),
                });
            }
            Record::Attachment { header, data, .. } => {
                self.out.attachments.push((header.name, data.into_owned()));
            }
            Record::Metadata(m) => self.out.metadata.push((m.name, m.metadata)),
            // The data section ends here; the summary repeats what was read.
            Record::DataEnd(_) | Record::Footer(_) => return Ok(false),
            _ => {}
        }
        Ok(true)
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
            Err(e) => return fail(at, format!("a bad record (opcode 0x{op:02x}): {e}")),
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

/// Unpacks one chunk (never past the size its header gives, at most `MAX_CHUNK`), checks
/// its CRC and takes its records.
fn read_chunk(
    state: &mut State,
    header: mcap::records::ChunkHeader,
    data: &[u8],
) -> Result<bool, String> {
    let size = header.uncompressed_size;
    if size > MAX_CHUNK {
        return Err(format!(
            "a chunk claims {size} bytes unpacked, over the {MAX_CHUNK} read"
        ));
    }
    let unpacked = unpack(&header.compression, data, size)?;
    if unpacked.len() as u64 != size {
        return Err(format!(
            "a chunk unpacks to {} bytes, not the {size} its header gives",
            unpacked.len()
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
