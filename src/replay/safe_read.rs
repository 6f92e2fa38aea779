//! A reader of MCAP files that is safe on any bytes: every length is checked against what the
//! file (or the chunk around it) can hold before anything is allocated or decompressed.
//!
//! Why not the mcap crate's reader: its `ChunkFlattener` sizes a chunk's buffer from the chunk's
//! declared uncompressed size and its records' buffers from their declared lengths (a 137-byte
//! file declaring a 2^40-byte record aborts the process on the failed allocation; 2^64-1 panics
//! it), and none of its options bounds the chunk decompressor by the size of the file. The
//! framing of MCAP is small, so it is parsed here, with every bound explicit:
//!
//! - a record's length (opcode u8, length u64, body) must fit in what is left of the file, or of
//!   the decompressed chunk for a record inside a chunk; every string, byte array and map inside
//!   a record must fit in what is left of the record;
//! - a chunk's declared uncompressed size must fit in [`Limits::max_chunk`] (64 MiB: one chunk
//!   buffer is the largest allocation) and in what is left of the file's decompression budget,
//!   [`Limits::max_ratio`] times the file size over all chunks (64x: our logs' chunks compress
//!   1.1-2.6x, zstd on other MCAP data typically 3-10x, so 64x refuses no real file while it
//!   bounds the bytes decompressed, hence the time, to a fixed multiple of the file);
//! - zstd decompresses in one call into a buffer of exactly the declared size (the bulk API:
//!   no window buffer, output capped at the buffer), which must then be exactly full and match
//!   the chunk's CRC-32; an LZ4 frame (lz4_flex, pure Rust) is read into the same exactly sized
//!   buffer, and a frame that holds more or less than declared is refused;
//! - chunks nest no further: a chunk inside a chunk is skipped, not opened.
//!
//! So memory is the file plus one chunk buffer, and time is linear in the file (each byte is
//! framed once, decompressed output is at most 64x the file). Every problem is one line naming
//! the record (kind and opcode) and its byte offset; see [`ReadError`].

use std::fmt;

/// The eight bytes that open and close every MCAP file.
pub const MAGIC: &[u8; 8] = b"\x89MCAP0\r\n";

/// Opcodes of the MCAP records this reader interprets (the others are framed and skipped).
pub mod op {
    /// Header: profile and library strings.
    pub const HEADER: u8 = 0x01;
    /// Footer: offsets of the summary.
    pub const FOOTER: u8 = 0x02;
    /// Schema.
    pub const SCHEMA: u8 = 0x03;
    /// Channel.
    pub const CHANNEL: u8 = 0x04;
    /// Message.
    pub const MESSAGE: u8 = 0x05;
    /// Chunk of compressed records.
    pub const CHUNK: u8 = 0x06;
    /// Attachment.
    pub const ATTACHMENT: u8 = 0x09;
    /// Metadata (a string map).
    pub const METADATA: u8 = 0x0C;
    /// End of the data section.
    pub const DATA_END: u8 = 0x0F;
}

/// What the record with `opcode` is called in the MCAP specification.
pub fn record_name(opcode: u8) -> &'static str {
    match opcode {
        0x01 => "header",
        0x02 => "footer",
        0x03 => "schema",
        0x04 => "channel",
        0x05 => "message",
        0x06 => "chunk",
        0x07 => "message index",
        0x08 => "chunk index",
        0x09 => "attachment",
        0x0A => "attachment index",
        0x0B => "statistics",
        0x0C => "metadata",
        0x0D => "metadata index",
        0x0E => "summary offset",
        0x0F => "data end",
        0x80..=0xFF => "application",
        _ => "unknown",
    }
}

/// Bounds on the work a file may ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The sum of all chunks' declared uncompressed sizes may be at most this multiple of the
    /// file size (default 64).
    pub max_ratio: u64,
    /// Largest declared uncompressed size of one chunk, bytes (default 64 MiB; our chunks are
    /// at most 256 KiB, other writers' at most a few MiB).
    pub max_chunk: u64,
}

/// Default [`Limits::max_ratio`].
pub const MAX_RATIO: u64 = 64;
/// Default [`Limits::max_chunk`].
pub const MAX_CHUNK: u64 = 64 << 20;

impl Default for Limits {
    fn default() -> Self {
        Limits { max_ratio: MAX_RATIO, max_chunk: MAX_CHUNK }
    }
}

/// Where a record is: its byte offset in the file, or, inside a chunk, its offset in the
/// chunk's decompressed records and the chunk's offset in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Place {
    /// Offset of the record's opcode: in the file, or in the chunk's decompressed records.
    pub offset: u64,
    /// Offset in the file of the chunk record holding this record, if any.
    pub chunk: Option<u64>,
}

impl Place {
    fn file(offset: usize) -> Place {
        Place { offset: offset as u64, chunk: None }
    }
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.chunk {
            None => write!(f, "byte {}", self.offset),
            Some(chunk) => write!(f, "byte {} of the records of the chunk at byte {chunk}", self.offset),
        }
    }
}

/// A record the reader interprets, borrowing from the file or from the current chunk.
#[derive(Clone, Debug, PartialEq)]
pub enum Record<'a> {
    /// The first record.
    Header {
        /// Profile (`beam-impact` for our logs).
        profile: &'a str,
        /// Writing library.
        library: &'a str,
    },
    /// A schema (its data is not interpreted).
    Schema {
        /// Schema id.
        id: u16,
        /// Schema name.
        name: &'a str,
        /// Schema encoding.
        encoding: &'a str,
        /// Schema data.
        data: &'a [u8],
    },
    /// A channel (its metadata map is checked, not returned).
    Channel {
        /// Channel id.
        id: u16,
        /// Schema id.
        schema_id: u16,
        /// Topic.
        topic: &'a str,
        /// Message encoding.
        message_encoding: &'a str,
    },
    /// A message.
    Message {
        /// Channel id.
        channel_id: u16,
        /// Per-channel sequence number.
        sequence: u32,
        /// Log time, ns.
        log_time: u64,
        /// Publish time, ns.
        publish_time: u64,
        /// The encoded message.
        data: &'a [u8],
    },
    /// An attachment (its CRC checked when not 0).
    Attachment {
        /// Log time, ns.
        log_time: u64,
        /// Creation time, ns.
        create_time: u64,
        /// Name.
        name: &'a str,
        /// Media type.
        media_type: &'a str,
        /// Content.
        data: &'a [u8],
    },
    /// A metadata record: a name and a string map, in file order.
    Metadata {
        /// Name.
        name: &'a str,
        /// Key-value pairs.
        entries: Vec<(&'a str, &'a str)>,
    },
    /// The end of the data section.
    DataEnd {
        /// CRC-32 of the data section (0: not computed).
        data_section_crc: u32,
    },
    /// The footer (the last record; the closing magic follows).
    Footer {
        /// Offset of the summary section (0: none).
        summary_start: u64,
        /// Offset of the summary offset section (0: none).
        summary_offset_start: u64,
        /// CRC-32 of the summary (0: not computed).
        summary_crc: u32,
    },
}

/// Why reading stopped before the footer. Each is one line naming the record and where it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ReadError {
    /// The file does not start with the MCAP magic bytes.
    NotMcap {
        /// Size of the file, bytes.
        length: u64,
    },
    /// The first record is not a header.
    NoHeader {
        /// Opcode of the first record.
        opcode: u8,
    },
    /// A record's declared length runs past the end of the file (a log cut short) or, inside a
    /// chunk, past the end of the chunk's records.
    Truncated {
        /// Where the record starts.
        at: Place,
        /// Its opcode (0 when the file ends inside the opcode and length themselves).
        opcode: u8,
        /// Bytes it declares (opcode and length included).
        declared: u64,
        /// Bytes that follow its start.
        available: u64,
    },
    /// A field inside a record declares more bytes than the record has left.
    Field {
        /// Where the record starts.
        at: Place,
        /// Its opcode.
        opcode: u8,
        /// The field.
        field: &'static str,
        /// Bytes the field needs.
        declared: u64,
        /// Bytes left in the record.
        available: u64,
    },
    /// A string field is not UTF-8.
    Utf8 {
        /// Where the record starts.
        at: Place,
        /// Its opcode.
        opcode: u8,
        /// The field.
        field: &'static str,
    },
    /// A chunk declares more uncompressed bytes than the limits allow.
    ChunkTooLarge {
        /// Where the chunk starts.
        at: Place,
        /// Declared uncompressed size.
        declared: u64,
        /// The most it could have been.
        limit: u64,
        /// Why that is the limit.
        reason: String,
    },
    /// A chunk's compression is not one this reader has.
    Compression {
        /// Where the chunk starts.
        at: Place,
        /// The chunk's compression name.
        name: String,
    },
    /// The decompressor refused the chunk's data (including output beyond the declared size).
    Decompress {
        /// Where the chunk starts.
        at: Place,
        /// The decompressor's message.
        detail: String,
    },
    /// A chunk's data decompresses to another size than it declares.
    SizeMismatch {
        /// Where the chunk starts.
        at: Place,
        /// Declared uncompressed size.
        declared: u64,
        /// Bytes the data holds.
        found: u64,
    },
    /// A stored CRC-32 does not match the bytes.
    Crc {
        /// Where the record starts.
        at: Place,
        /// Its opcode.
        opcode: u8,
        /// The CRC in the file.
        saved: u32,
        /// The CRC of the bytes.
        calculated: u32,
    },
    /// The file ends after a complete record but before its footer: a writer that never
    /// finished.
    NoFooter {
        /// Size of the file, bytes.
        at: u64,
    },
    /// The file ends inside the closing magic, after the footer.
    EndMagicCut {
        /// Where the closing magic starts.
        at: u64,
        /// Bytes of it in the file.
        available: u64,
    },
    /// Something other than the closing magic follows the footer.
    EndMagic {
        /// Where the footer starts.
        at: u64,
        /// Bytes after the footer.
        trailing: u64,
    },
    /// The data end record's CRC of the data section (non-zero: written) does not match it: a
    /// byte changed outside the chunks (whose own CRCs hold), for example in a top-level
    /// metadata record, which has no CRC of its own.
    DataSectionCrc {
        /// Where the data end record starts.
        at: u64,
        /// The stored CRC.
        saved: u32,
        /// The CRC of the bytes before the data end record.
        calculated: u32,
    },
}

/// A file-supplied string for a one-line message: escaped, at most 40 characters.
pub(crate) fn quoted(text: &str) -> String {
    let short: String = text.chars().take(40).collect();
    let more = if short.len() < text.len() { "..." } else { "" };
    format!("{short:?}{more}")
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let record = |opcode: u8| format!("{} record (opcode 0x{opcode:02x})", record_name(opcode));
        match self {
            ReadError::NotMcap { length } => {
                write!(f, "not an MCAP file: its {length} bytes do not start with the MCAP magic bytes")
            }
            ReadError::NoHeader { opcode } => {
                write!(f, "not an MCAP log: the first record, at byte 8, is a {} and not the header", record(*opcode))
            }
            ReadError::Truncated { at, opcode: 0, declared, available } if *declared == 9 => write!(
                f,
                "the record at {at} is cut short: {available} bytes follow, fewer than its opcode and length (9)"
            ),
            ReadError::Truncated { at, opcode, declared, available } if at.chunk.is_some() => write!(
                f,
                "{} at {at} declares {declared} bytes but only {available} are left in the chunk",
                record(*opcode)
            ),
            ReadError::Truncated { at, opcode, declared, available } => write!(
                f,
                "{} at {at} declares {declared} bytes but the file ends {available} bytes after its start",
                record(*opcode)
            ),
            ReadError::Field { at, opcode, field, declared, available } => write!(
                f,
                "{} at {at}: {field} needs {declared} bytes but the record has {available} left",
                record(*opcode)
            ),
            ReadError::Utf8 { at, opcode, field } => write!(f, "{} at {at}: {field} is not UTF-8", record(*opcode)),
            ReadError::ChunkTooLarge { at, declared, limit, reason } => write!(
                f,
                "{} at {at} declares {declared} uncompressed bytes, more than the {limit} allowed ({reason})",
                record(op::CHUNK)
            ),
            ReadError::Compression { at, name } => {
                write!(
                    f,
                    "{} at {at} uses compression {}, which this reader does not have",
                    record(op::CHUNK),
                    quoted(name)
                )
            }
            ReadError::Decompress { at, detail } => {
                write!(f, "{} at {at} does not decompress: {}", record(op::CHUNK), detail.trim())
            }
            ReadError::SizeMismatch { at, declared, found } => write!(
                f,
                "{} at {at} declares {declared} uncompressed bytes but its data holds {found}",
                record(op::CHUNK)
            ),
            ReadError::Crc { at, opcode, saved, calculated } => write!(
                f,
                "{} at {at} fails its CRC check (stored 0x{saved:08x}, computed 0x{calculated:08x})",
                record(*opcode)
            ),
            ReadError::NoFooter { at } => {
                write!(f, "the file ends at byte {at} before its summary and footer (the writer never finished)")
            }
            ReadError::EndMagicCut { at, available } => write!(
                f,
                "the file ends inside its closing magic bytes at byte {at} ({available} of 8), after the footer"
            ),
            ReadError::EndMagic { at, trailing } => {
                write!(f, "the footer at byte {at} is followed by {trailing} bytes that are not the closing MCAP magic")
            }
            ReadError::DataSectionCrc { at, saved, calculated } => write!(
                f,
                "data end record (opcode 0x0f) at byte {at}: the data section fails its CRC check (stored \
                 0x{saved:08x}, computed 0x{calculated:08x}): a byte before it changed outside the chunks"
            ),
        }
    }
}

impl std::error::Error for ReadError {}

impl ReadError {
    /// Whether the file simply ends early (a killed writer), as opposed to holding bytes that
    /// are not a valid MCAP log.
    pub fn is_cut_short(&self) -> bool {
        matches!(
            self,
            ReadError::NoFooter { .. }
                | ReadError::EndMagicCut { .. }
                | ReadError::Truncated { at: Place { chunk: None, .. }, .. }
        )
    }
}

/// How reading a file ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Ending {
    /// The footer and the closing magic were read.
    Complete,
    /// Reading stopped at this problem; every record before it was visited.
    Stopped(ReadError),
}

/// Decodes the fields of one record body, each length checked against what the body has left.
struct Fields<'a> {
    body: &'a [u8],
    pos: usize,
    at: Place,
    opcode: u8,
}

impl<'a> Fields<'a> {
    fn new(body: &'a [u8], at: Place, opcode: u8) -> Self {
        Fields { body, pos: 0, at, opcode }
    }

    fn left(&self) -> usize {
        self.body.len() - self.pos
    }

    fn take(&mut self, n: u64, field: &'static str) -> Result<&'a [u8], ReadError> {
        let left = self.left();
        if n > left as u64 {
            return Err(ReadError::Field {
                at: self.at,
                opcode: self.opcode,
                field,
                declared: n,
                available: left as u64,
            });
        }
        let n = n as usize;
        let out = &self.body[self.pos..self.pos + n];
        self.pos += n;
        Ok(out)
    }

    fn array<const N: usize>(&mut self, field: &'static str) -> Result<[u8; N], ReadError> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.take(N as u64, field)?);
        Ok(out)
    }

    fn u16(&mut self, field: &'static str) -> Result<u16, ReadError> {
        Ok(u16::from_le_bytes(self.array(field)?))
    }

    fn u32(&mut self, field: &'static str) -> Result<u32, ReadError> {
        Ok(u32::from_le_bytes(self.array(field)?))
    }

    fn u64(&mut self, field: &'static str) -> Result<u64, ReadError> {
        Ok(u64::from_le_bytes(self.array(field)?))
    }

    /// A u32-length-prefixed byte array.
    fn bytes32(&mut self, field: &'static str) -> Result<&'a [u8], ReadError> {
        let n = self.u32(field)?;
        self.take(u64::from(n), field)
    }

    /// A u64-length-prefixed byte array.
    fn bytes64(&mut self, field: &'static str) -> Result<&'a [u8], ReadError> {
        let n = self.u64(field)?;
        self.take(n, field)
    }

    /// A u32-length-prefixed UTF-8 string.
    fn string(&mut self, field: &'static str) -> Result<&'a str, ReadError> {
        let bytes = self.bytes32(field)?;
        std::str::from_utf8(bytes).map_err(|_| ReadError::Utf8 { at: self.at, opcode: self.opcode, field })
    }

    /// A string map: its byte length (u32), then key and value strings. The pairs need at least
    /// 8 bytes each, so the list is bounded by the record.
    fn string_map(&mut self, field: &'static str) -> Result<Vec<(&'a str, &'a str)>, ReadError> {
        let bytes = self.bytes32(field)?;
        let mut inner = Fields { body: bytes, pos: 0, at: self.at, opcode: self.opcode };
        let mut out = Vec::new();
        while inner.left() > 0 {
            let key = inner.string(field)?;
            let value = inner.string(field)?;
            out.push((key, value));
        }
        Ok(out)
    }

    fn rest(&mut self) -> &'a [u8] {
        let out = &self.body[self.pos..];
        self.pos = self.body.len();
        out
    }
}

/// CRC-32 (IEEE 802.3), the one MCAP uses.
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

/// One record's frame: opcode, body, and the offset just past it.
struct Frame<'a> {
    opcode: u8,
    body: &'a [u8],
    next: usize,
}

/// Frames the record at `pos` of `bytes`: its length must fit in what follows.
fn frame(bytes: &[u8], pos: usize, at: Place) -> Result<Frame<'_>, ReadError> {
    let available = (bytes.len() - pos) as u64;
    if available < 9 {
        return Err(ReadError::Truncated { at, opcode: 0, declared: 9, available });
    }
    let opcode = bytes[pos];
    let mut length = [0u8; 8];
    length.copy_from_slice(&bytes[pos + 1..pos + 9]);
    let length = u64::from_le_bytes(length);
    if length > available - 9 {
        return Err(ReadError::Truncated { at, opcode, declared: length.saturating_add(9), available });
    }
    let end = pos + 9 + length as usize;
    Ok(Frame { opcode, body: &bytes[pos + 9..end], next: end })
}

/// Parses the records that may appear both inside and outside chunks.
fn parse_common<'a>(opcode: u8, body: &'a [u8], at: Place) -> Result<Option<Record<'a>>, ReadError> {
    let mut f = Fields::new(body, at, opcode);
    Ok(Some(match opcode {
        op::SCHEMA => {
            let id = f.u16("schema id")?;
            let name = f.string("schema name")?;
            let encoding = f.string("schema encoding")?;
            let data = f.bytes32("schema data")?;
            Record::Schema { id, name, encoding, data }
        }
        op::CHANNEL => {
            let id = f.u16("channel id")?;
            let schema_id = f.u16("schema id")?;
            let topic = f.string("topic")?;
            let message_encoding = f.string("message encoding")?;
            f.string_map("channel metadata")?;
            Record::Channel { id, schema_id, topic, message_encoding }
        }
        op::MESSAGE => {
            let channel_id = f.u16("channel id")?;
            let sequence = f.u32("sequence")?;
            let log_time = f.u64("log time")?;
            let publish_time = f.u64("publish time")?;
            Record::Message { channel_id, sequence, log_time, publish_time, data: f.rest() }
        }
        _ => return Ok(None),
    }))
}

/// Reads the MCAP file `bytes`, calling `visit` with every record it interprets, in file order,
/// chunks opened in place. Reading stops at the first problem in the file, returned as
/// [`Ending::Stopped`] after every record before it was visited; an error from `visit` stops
/// it at once and is returned as is.
pub fn read_records<E>(
    bytes: &[u8],
    limits: Limits,
    visit: &mut dyn FnMut(Place, Record<'_>) -> Result<(), E>,
) -> Result<Ending, E> {
    let mut reader = Reader {
        bytes,
        budget: limits.max_ratio.saturating_mul(bytes.len() as u64),
        limits,
        buffer: Vec::new(),
        decompressor: None,
    };
    match reader.run(visit) {
        Ok(ending) => Ok(ending),
        Err(Stop::File(e)) => Ok(Ending::Stopped(e)),
        Err(Stop::Visitor(e)) => Err(e),
    }
}

enum Stop<E> {
    File(ReadError),
    Visitor(E),
}

impl<E> From<ReadError> for Stop<E> {
    fn from(e: ReadError) -> Self {
        Stop::File(e)
    }
}

struct Reader<'f> {
    bytes: &'f [u8],
    limits: Limits,
    /// Uncompressed bytes the remaining chunks may still declare.
    budget: u64,
    /// The current chunk's records (reused).
    buffer: Vec<u8>,
    decompressor: Option<zstd::bulk::Decompressor<'static>>,
}

impl Reader<'_> {
    fn run<E>(&mut self, visit: &mut dyn FnMut(Place, Record<'_>) -> Result<(), E>) -> Result<Ending, Stop<E>> {
        let bytes = self.bytes;
        if !bytes.starts_with(MAGIC) {
            return Err(ReadError::NotMcap { length: bytes.len() as u64 }.into());
        }
        let mut pos = MAGIC.len();
        let mut first = true;
        while pos < bytes.len() {
            let at = Place::file(pos);
            let frame = frame(bytes, pos, at)?;
            if first && frame.opcode != op::HEADER {
                return Err(ReadError::NoHeader { opcode: frame.opcode }.into());
            }
            first = false;
            let mut f = Fields::new(frame.body, at, frame.opcode);
            let record = match frame.opcode {
                op::HEADER => Some(Record::Header { profile: f.string("profile")?, library: f.string("library")? }),
                op::FOOTER => {
                    let record = Record::Footer {
                        summary_start: f.u64("summary start")?,
                        summary_offset_start: f.u64("summary offset start")?,
                        summary_crc: f.u32("summary CRC")?,
                    };
                    visit(at, record).map_err(Stop::Visitor)?;
                    let tail = &bytes[frame.next..];
                    if tail.len() < MAGIC.len() && MAGIC.starts_with(tail) {
                        let (at, available) = (frame.next as u64, tail.len() as u64);
                        return Err(ReadError::EndMagicCut { at, available }.into());
                    }
                    if tail != MAGIC {
                        return Err(ReadError::EndMagic { at: pos as u64, trailing: tail.len() as u64 }.into());
                    }
                    return Ok(Ending::Complete);
                }
                op::CHUNK => {
                    self.chunk(frame.body, pos, visit)?;
                    None
                }
                op::ATTACHMENT => Some(attachment(&mut f)?),
                op::METADATA => {
                    Some(Record::Metadata { name: f.string("metadata name")?, entries: f.string_map("metadata")? })
                }
                op::DATA_END => {
                    let saved = f.u32("data section CRC")?;
                    // 0: not written (format 1 and earlier format 2 logs). The data section is
                    // every byte before the data end record, the leading magic included.
                    if saved != 0 {
                        let calculated = crc32(&bytes[..pos]);
                        if calculated != saved {
                            return Err(ReadError::DataSectionCrc { at: pos as u64, saved, calculated }.into());
                        }
                    }
                    Some(Record::DataEnd { data_section_crc: saved })
                }
                other => parse_common(other, frame.body, at)?,
            };
            if let Some(record) = record {
                visit(at, record).map_err(Stop::Visitor)?;
            }
            pos = frame.next;
        }
        Err(ReadError::NoFooter { at: bytes.len() as u64 }.into())
    }

    /// Checks, decompresses and visits the records of the chunk whose body is `body`.
    fn chunk<E>(
        &mut self,
        body: &[u8],
        offset: usize,
        visit: &mut dyn FnMut(Place, Record<'_>) -> Result<(), E>,
    ) -> Result<(), Stop<E>> {
        let at = Place::file(offset);
        let mut f = Fields::new(body, at, op::CHUNK);
        let _start = f.u64("message start time")?;
        let _end = f.u64("message end time")?;
        let declared = f.u64("uncompressed size")?;
        let crc = f.u32("uncompressed CRC")?;
        let compression = f.string("compression")?;
        let data = f.bytes64("records")?;
        let file = self.bytes.len() as u64;
        let (limit, reason) = if self.limits.max_chunk <= self.budget {
            (self.limits.max_chunk, format!("the largest chunk this reader opens, {} MiB", self.limits.max_chunk >> 20))
        } else {
            (
                self.budget,
                format!(
                    "{}x the file's {file} bytes, less {} already declared by earlier chunks",
                    self.limits.max_ratio,
                    self.limits.max_ratio.saturating_mul(file) - self.budget
                ),
            )
        };
        if declared > limit {
            return Err(ReadError::ChunkTooLarge { at, declared, limit, reason }.into());
        }
        self.budget -= declared;
        let records: &[u8] = match compression {
            "" => {
                if data.len() as u64 != declared {
                    return Err(ReadError::SizeMismatch { at, declared, found: data.len() as u64 }.into());
                }
                data
            }
            "zstd" => {
                let size = declared as usize;
                self.buffer.clear();
                self.buffer.resize(size, 0);
                let decompressor = match &mut self.decompressor {
                    Some(d) => d,
                    None => {
                        let d = zstd::bulk::Decompressor::new()
                            .map_err(|e| ReadError::Decompress { at, detail: e.to_string() })?;
                        self.decompressor.insert(d)
                    }
                };
                let found = decompressor
                    .decompress_to_buffer(data, &mut self.buffer[..])
                    .map_err(|e| ReadError::Decompress { at, detail: e.to_string() })?;
                if found != size {
                    return Err(ReadError::SizeMismatch { at, declared, found: found as u64 }.into());
                }
                &self.buffer[..]
            }
            "lz4" => {
                // An LZ4 frame decoded into exactly the declared size: one byte more is an error.
                let size = declared as usize;
                self.buffer.clear();
                self.buffer.resize(size, 0);
                let mut decoder = lz4_flex::frame::FrameDecoder::new(data);
                let decompress = |e: std::io::Error| ReadError::Decompress { at, detail: e.to_string() };
                let mut found = 0;
                while found < size {
                    match std::io::Read::read(&mut decoder, &mut self.buffer[found..]).map_err(decompress)? {
                        0 => break,
                        n => found += n,
                    }
                }
                let mut extra = [0u8; 1];
                if found == size && std::io::Read::read(&mut decoder, &mut extra).map_err(decompress)? > 0 {
                    found += 1;
                }
                if found != size {
                    return Err(ReadError::SizeMismatch { at, declared, found: found as u64 }.into());
                }
                &self.buffer[..]
            }
            other => return Err(ReadError::Compression { at, name: other.to_string() }.into()),
        };
        if crc != 0 {
            let calculated = crc32(records);
            if calculated != crc {
                return Err(ReadError::Crc { at, opcode: op::CHUNK, saved: crc, calculated }.into());
            }
        }
        let mut pos = 0;
        while pos < records.len() {
            let inner = Place { offset: pos as u64, chunk: Some(offset as u64) };
            let frame = frame(records, pos, inner)?;
            if let Some(record) = parse_common(frame.opcode, frame.body, inner)? {
                visit(inner, record).map_err(Stop::Visitor)?;
            }
            pos = frame.next;
        }
        Ok(())
    }
}

fn attachment<'a>(f: &mut Fields<'a>) -> Result<Record<'a>, ReadError> {
    let log_time = f.u64("log time")?;
    let create_time = f.u64("create time")?;
    let name = f.string("attachment name")?;
    let media_type = f.string("media type")?;
    let data = f.bytes64("attachment data")?;
    let covered = f.pos;
    let saved = f.u32("attachment CRC")?;
    if saved != 0 {
        let calculated = crc32(&f.body[..covered]);
        if calculated != saved {
            return Err(ReadError::Crc { at: f.at, opcode: op::ATTACHMENT, saved, calculated });
        }
    }
    Ok(Record::Attachment { log_time, create_time, name, media_type, data })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        // The CRC-32/ISO-HDLC check value of "123456789".
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b""), 0);
    }

    fn visit_all(bytes: &[u8]) -> (Vec<String>, Ending) {
        let mut seen = Vec::new();
        let ending = read_records::<()>(bytes, Limits::default(), &mut |at, r| {
            seen.push(format!("{at}: {r:?}"));
            Ok(())
        })
        .unwrap();
        (seen, ending)
    }

    fn record(opcode: u8, body: &[u8]) -> Vec<u8> {
        let mut out = vec![opcode];
        out.extend_from_slice(&(body.len() as u64).to_le_bytes());
        out.extend_from_slice(body);
        out
    }

    fn header() -> Vec<u8> {
        let mut b = MAGIC.to_vec();
        b.extend(record(op::HEADER, &[0, 0, 0, 0, 0, 0, 0, 0]));
        b
    }

    #[test]
    fn lengths_beyond_the_file_stop_reading_before_any_allocation() {
        let mut b = header();
        let mut chunk = Vec::new();
        chunk.extend_from_slice(&0u64.to_le_bytes());
        chunk.extend_from_slice(&0u64.to_le_bytes());
        chunk.extend_from_slice(&(1u64 << 40).to_le_bytes());
        chunk.extend_from_slice(&0u32.to_le_bytes());
        chunk.extend_from_slice(&4u32.to_le_bytes());
        chunk.extend_from_slice(b"zstd");
        chunk.extend_from_slice(&4u64.to_le_bytes());
        chunk.extend_from_slice(&[1, 2, 3, 4]);
        b.extend(record(op::CHUNK, &chunk));
        let (_, ending) = visit_all(&b);
        let Ending::Stopped(e @ ReadError::ChunkTooLarge { declared, .. }) = ending else { panic!("{ending:?}") };
        assert_eq!(declared, 1 << 40);
        assert!(!e.is_cut_short());
        let text = e.to_string();
        assert!(text.starts_with("chunk record (opcode 0x06) at byte 25 declares 1099511627776"), "{text}");
        assert!(!text.contains('\n'));

        // A record longer than the file: cut short.
        let mut b = header();
        b.push(op::MESSAGE);
        b.extend_from_slice(&u64::MAX.to_le_bytes());
        let (_, ending) = visit_all(&b);
        assert!(matches!(&ending, Ending::Stopped(e) if e.is_cut_short()), "{ending:?}");
    }

    #[test]
    fn strings_and_maps_are_bounded_by_their_record() {
        let mut body = Vec::new();
        body.extend_from_slice(&u32::MAX.to_le_bytes());
        let mut b = header();
        b.extend(record(op::METADATA, &body));
        let (_, ending) = visit_all(&b);
        assert!(
            matches!(ending, Ending::Stopped(ReadError::Field { field: "metadata name", declared: 4294967295, .. })),
            "{ending:?}"
        );
    }

    #[test]
    fn an_uncompressed_chunk_and_the_footer_are_read() {
        let mut b = header();
        let mut message = Vec::new();
        message.extend_from_slice(&1u16.to_le_bytes());
        message.extend_from_slice(&0u32.to_le_bytes());
        message.extend_from_slice(&5u64.to_le_bytes());
        message.extend_from_slice(&5u64.to_le_bytes());
        message.extend_from_slice(b"hi");
        let records = record(op::MESSAGE, &message);
        let mut chunk = Vec::new();
        chunk.extend_from_slice(&[0; 16]);
        chunk.extend_from_slice(&(records.len() as u64).to_le_bytes());
        chunk.extend_from_slice(&crc32(&records).to_le_bytes());
        chunk.extend_from_slice(&0u32.to_le_bytes());
        chunk.extend_from_slice(&(records.len() as u64).to_le_bytes());
        chunk.extend_from_slice(&records);
        b.extend(record(op::CHUNK, &chunk));
        b.extend(record(op::FOOTER, &[0; 20]));
        b.extend_from_slice(MAGIC);
        let (seen, ending) = visit_all(&b);
        assert_eq!(ending, Ending::Complete);
        assert_eq!(seen.len(), 3, "{seen:?}");
        assert!(seen[1].starts_with("byte 0 of the records of the chunk at byte 25: Message"), "{seen:?}");
        // One flipped bit in the chunk's records: its CRC catches it.
        let n = b.len();
        b[n - 8 - 29 - 1] ^= 1;
        let (_, ending) = visit_all(&b);
        assert!(matches!(ending, Ending::Stopped(ReadError::Crc { opcode: op::CHUNK, .. })), "{ending:?}");
    }
}
