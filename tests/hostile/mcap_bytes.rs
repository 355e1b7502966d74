//! MCAP records written byte by byte (the MCAP spec's layouts), so a case can say what
//! no writer would: chunks that unpack to gigabytes, names of 64 kB, wrong CRCs.

/// A record: opcode, body length (u64, little-endian), body.
pub fn record(op: u8, body: &[u8]) -> Vec<u8> {
    [&[op][..], &(body.len() as u64).to_le_bytes(), body].concat()
}

/// A string field: u32 length, then the bytes.
pub fn string(s: &[u8]) -> Vec<u8> {
    [&(s.len() as u32).to_le_bytes()[..], s].concat()
}

/// The magic bytes and a Header record (profile `ros2`).
pub fn start() -> Vec<u8> {
    let header = record(0x01, &[string(b"ros2"), string(b"hostile")].concat());
    [&b"\x89MCAP0\r\n"[..], &header].concat()
}

/// A DataEnd and a Footer record, and the closing magic bytes.
pub fn end() -> Vec<u8> {
    let data_end = record(0x0f, &0u32.to_le_bytes());
    let footer = record(0x02, &[0u8; 20]);
    [data_end, footer, b"\x89MCAP0\r\n".to_vec()].concat()
}

/// A Schema record with no schema text.
pub fn schema(id: u16, name: &[u8]) -> Vec<u8> {
    let body = [
        &id.to_le_bytes()[..],
        &string(name),
        &string(b"ros2msg"),
        &0u32.to_le_bytes(),
    ]
    .concat();
    record(0x03, &body)
}

/// A Channel record with no metadata.
pub fn channel(id: u16, schema: u16, topic: &[u8]) -> Vec<u8> {
    let body = [
        &id.to_le_bytes()[..],
        &schema.to_le_bytes(),
        &string(topic),
        &string(b"cdr"),
        &0u32.to_le_bytes(),
    ]
    .concat();
    record(0x04, &body)
}

/// A Message record on `channel` at `ns`.
pub fn message(channel: u16, ns: u64, data: &[u8]) -> Vec<u8> {
    let body = [
        &channel.to_le_bytes()[..],
        &0u32.to_le_bytes(),
        &ns.to_le_bytes(),
        &ns.to_le_bytes(),
        data,
    ]
    .concat();
    record(0x05, &body)
}

/// A Chunk record holding `packed` (already compressed with `compression`), whose header
/// claims it unpacks to `claimed` bytes; CRC 0 (not checked).
pub fn chunk(packed: &[u8], claimed: u64, compression: &[u8]) -> Vec<u8> {
    let body = [
        &0u64.to_le_bytes()[..],
        &0u64.to_le_bytes(),
        &claimed.to_le_bytes(),
        &0u32.to_le_bytes(),
        &string(compression),
        &(packed.len() as u64).to_le_bytes(),
        packed,
    ]
    .concat();
    record(0x06, &body)
}

/// A zstd chunk of `records`, its header truthful.
pub fn zstd_chunk(records: &[u8]) -> Vec<u8> {
    chunk(
        &zstd::encode_all(records, 3).unwrap(),
        records.len() as u64,
        b"zstd",
    )
}

/// An Attachment record whose CRC is `crc` (0: not checked).
pub fn attachment(name: &[u8], data: &[u8], crc: u32) -> Vec<u8> {
    let body = [
        &0u64.to_le_bytes()[..],
        &0u64.to_le_bytes(),
        &string(name),
        &string(b"application/octet-stream"),
        &(data.len() as u64).to_le_bytes(),
        data,
        &crc.to_le_bytes(),
    ]
    .concat();
    record(0x09, &body)
}
