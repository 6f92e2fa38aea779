//! Shared by the hostile-input tests (`tests/hostile_logs.rs`, `tests/fuzz_*.rs`): a seeded
//! mutator, an MCAP record builder, the crafted logs of issue 9 and real logs recorded on the
//! spot. Each test binary uses part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use beam_impact::model::TimeStep;
use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::{Recorder, RunInfo};
use beam_impact::replay::safe_read::{crc32, op, MAGIC};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{Scenario, Simulation};

/// The committed regression corpora.
pub fn corpus_dir(kind: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests").join("corpus").join(kind)
}

/// Every file of a corpus directory, sorted by name (README files left out).
pub fn corpus_files(kind: &str) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(corpus_dir(kind))
        .unwrap_or_else(|e| panic!("corpus {kind}: {e}"))
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.is_file() && p.file_name().is_some_and(|n| n != "README.md"))
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap()))
        .collect();
    files.sort();
    files
}

/// Iterations of the mutation loops: `BEAM_IMPACT_FUZZ_ITERATIONS` or `default`.
pub fn iterations(default: usize) -> usize {
    std::env::var("BEAM_IMPACT_FUZZ_ITERATIONS").ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// SplitMix64: small, seeded, reproducible.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Lengths an attacker writes into length fields.
pub const NASTY_LENGTHS: &[u64] = &[
    0,
    1,
    7,
    8,
    9,
    0x7F,
    0x80,
    0xFF,
    0xFFFF,
    0x7FFF_FFFF,
    0xFFFF_FFFF,
    1 << 32,
    1 << 40,
    1 << 62,
    i64::MAX as u64,
    u64::MAX - 8,
    u64::MAX,
];

/// One random byte-level mutation of `input` (never empty input: at least the magic survives
/// half the time): bit flips, interesting bytes, 4- and 8-byte length fields, truncation,
/// deletion, duplication and insertion of ranges.
pub fn mutate(input: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = input.to_vec();
    let rounds = 1 + rng.below(4);
    for _ in 0..rounds {
        if b.is_empty() {
            b.push(rng.next_u64() as u8);
            continue;
        }
        let at = rng.below(b.len());
        match rng.below(9) {
            0 => b[at] ^= 1 << rng.below(8),
            1 => b[at] = *rng.pick(&[0u8, 1, 0x7F, 0x80, 0xFF, 0x05, 0x06]),
            2 if b.len() >= at + 8 => {
                let v = *rng.pick(NASTY_LENGTHS);
                b[at..at + 8].copy_from_slice(&v.to_le_bytes());
            }
            3 if b.len() >= at + 4 => {
                let v = *rng.pick(NASTY_LENGTHS) as u32;
                b[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
            4 => b.truncate(at),
            5 => {
                let end = (at + 1 + rng.below(64)).min(b.len());
                b.drain(at..end);
            }
            6 => {
                let end = (at + 1 + rng.below(256)).min(b.len());
                let piece = b[at..end].to_vec();
                let to = rng.below(b.len());
                b.splice(to..to, piece);
            }
            7 => {
                let n = 1 + rng.below(16);
                let piece: Vec<u8> = (0..n).map(|_| rng.next_u64() as u8).collect();
                b.splice(at..at, piece);
            }
            _ => {
                // A record-length field (right after an opcode) set to a nasty value.
                let opcodes: Vec<usize> = b
                    .iter()
                    .enumerate()
                    .filter(|(i, &x)| (1..=0x0F).contains(&x) && i + 9 <= b.len())
                    .map(|(i, _)| i)
                    .collect();
                if !opcodes.is_empty() {
                    let i = *rng.pick(&opcodes);
                    let v = *rng.pick(NASTY_LENGTHS);
                    b[i + 1..i + 9].copy_from_slice(&v.to_le_bytes());
                }
            }
        }
    }
    b
}

/// A record: opcode, u64 length, body.
pub fn record(opcode: u8, body: &[u8]) -> Vec<u8> {
    let mut out = vec![opcode];
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(body);
    out
}

pub fn string(s: &str) -> Vec<u8> {
    let mut out = (s.len() as u32).to_le_bytes().to_vec();
    out.extend_from_slice(s.as_bytes());
    out
}

/// Magic and a header record (profile `beam-impact`).
pub fn start() -> Vec<u8> {
    let mut b = MAGIC.to_vec();
    let mut header = string("beam-impact");
    header.extend(string("crafted"));
    b.extend(record(op::HEADER, &header));
    b
}

/// Data end, footer and the closing magic.
pub fn end(b: &mut Vec<u8>) {
    b.extend(record(op::DATA_END, &0u32.to_le_bytes()));
    b.extend(record(op::FOOTER, &[0; 20]));
    b.extend_from_slice(MAGIC);
}

/// A chunk record holding `records`: zstd-compressed (`zstd`) or not, declaring
/// `declared` uncompressed bytes (None: the true size), with the records' CRC.
pub fn chunk(records: &[u8], zstd: bool, declared: Option<u64>) -> Vec<u8> {
    let data = if zstd { zstd::bulk::compress(records, 1).unwrap() } else { records.to_vec() };
    let mut body = Vec::new();
    body.extend_from_slice(&0u64.to_le_bytes());
    body.extend_from_slice(&0u64.to_le_bytes());
    body.extend_from_slice(&declared.unwrap_or(records.len() as u64).to_le_bytes());
    body.extend_from_slice(&crc32(records).to_le_bytes());
    body.extend(string(if zstd { "zstd" } else { "" }));
    body.extend_from_slice(&(data.len() as u64).to_le_bytes());
    body.extend_from_slice(&data);
    record(op::CHUNK, &body)
}

/// A message record's body on `channel` at `time`.
pub fn message(channel: u16, time: u64, data: &[u8]) -> Vec<u8> {
    let mut body = channel.to_le_bytes().to_vec();
    body.extend_from_slice(&0u32.to_le_bytes());
    body.extend_from_slice(&time.to_le_bytes());
    body.extend_from_slice(&time.to_le_bytes());
    body.extend_from_slice(data);
    record(op::MESSAGE, &body)
}

/// A file whose one zstd chunk holds a record declaring `inner` bytes: issue 9's 137-byte file
/// (2^40 aborted the mcap crate's reader on a failed allocation, 2^64-1 panicked it).
pub fn inner_record_log(inner: u64) -> Vec<u8> {
    let mut records = vec![op::MESSAGE];
    records.extend_from_slice(&inner.to_le_bytes());
    records.extend_from_slice(&[0; 22]);
    let mut b = start();
    b.extend(chunk(&records, true, None));
    end(&mut b);
    b
}

/// The crafted logs of issue 9 and their relatives, each small: (file name, bytes).
pub fn crafted_logs() -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<(String, Vec<u8>)> = Vec::new();
    let mut add = |name: &str, bytes: Vec<u8>| out.push((name.to_string(), bytes));
    add("inner-record-2p40.mcap", inner_record_log(1 << 40));
    add("inner-record-u64max.mcap", inner_record_log(u64::MAX));
    add("inner-record-u64max-minus-8.mcap", inner_record_log(u64::MAX - 8));
    for (name, declared) in [("2p40", 1u64 << 40), ("u64max", u64::MAX), ("64x-file", 64 * 200)] {
        let mut b = start();
        b.extend(chunk(&message(1, 0, b"x"), true, Some(declared)));
        end(&mut b);
        add(&format!("chunk-declares-{name}.mcap"), b);
    }
    // A zstd bomb: 8 MiB of zeros in a few hundred bytes, declared as such.
    {
        let zeros = vec![0u8; 8 << 20];
        let mut b = start();
        b.extend(chunk(&zeros, true, None));
        end(&mut b);
        add("zstd-bomb-8mib.mcap", b);
    }
    // Declared smaller than what the data decompresses to.
    {
        let records = message(1, 0, &[7; 4000]);
        let mut b = start();
        b.extend(chunk(&records, true, Some(100)));
        end(&mut b);
        add("chunk-declares-less-than-its-data.mcap", b);
    }
    {
        let mut b = start();
        let mut c = chunk(&message(1, 0, b"x"), false, None);
        // The compressed-size field (after 8+8+8+4 + 4-byte empty compression string) to u64::MAX.
        let at = 9 + 8 + 8 + 8 + 4 + 4;
        c[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
        b.extend(c);
        end(&mut b);
        add("chunk-compressed-size-u64max.mcap", b);
    }
    {
        let mut b = start();
        let mut body = 0u64.to_le_bytes().to_vec();
        body.extend_from_slice(&0u64.to_le_bytes());
        body.extend_from_slice(&10u64.to_le_bytes());
        body.extend_from_slice(&0u32.to_le_bytes());
        body.extend(string("lz4"));
        body.extend_from_slice(&10u64.to_le_bytes());
        body.extend_from_slice(&[0; 10]);
        b.extend(record(op::CHUNK, &body));
        end(&mut b);
        add("chunk-unknown-compression.mcap", b);
    }
    {
        let mut b = start();
        b.push(op::MESSAGE);
        b.extend_from_slice(&u64::MAX.to_le_bytes());
        add("record-length-u64max.mcap", b);
    }
    // String lengths beyond their record: schema name, channel topic, metadata map, chunk index
    // compression, attachment data.
    {
        let mut schema = 1u16.to_le_bytes().to_vec();
        schema.extend_from_slice(&u32::MAX.to_le_bytes());
        let mut b = start();
        b.extend(chunk(&record(op::SCHEMA, &schema), true, None));
        end(&mut b);
        add("schema-name-u32max.mcap", b);
    }
    {
        let mut channel = 1u16.to_le_bytes().to_vec();
        channel.extend_from_slice(&1u16.to_le_bytes());
        channel.extend_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
        let mut b = start();
        b.extend(chunk(&record(op::CHANNEL, &channel), true, None));
        end(&mut b);
        add("channel-topic-u32max.mcap", b);
    }
    {
        let mut metadata = string("scenario");
        metadata.extend_from_slice(&u32::MAX.to_le_bytes());
        let mut b = start();
        b.extend(record(op::METADATA, &metadata));
        end(&mut b);
        add("metadata-map-u32max.mcap", b);
        let mut metadata = string("scenario");
        let mut map = string("key");
        map.extend_from_slice(&u32::MAX.to_le_bytes());
        metadata.extend_from_slice(&(map.len() as u32).to_le_bytes());
        metadata.extend(map);
        let mut b = start();
        b.extend(record(op::METADATA, &metadata));
        end(&mut b);
        add("metadata-value-u32max.mcap", b);
    }
    {
        let mut index = vec![0u8; 8 + 8 + 8 + 4];
        index.extend_from_slice(&u32::MAX.to_le_bytes());
        let mut b = start();
        b.extend(record(op::DATA_END, &0u32.to_le_bytes()));
        b.extend(record(0x08, &index));
        b.extend(record(op::FOOTER, &[0; 20]));
        b.extend_from_slice(MAGIC);
        add("chunk-index-compression-u32max.mcap", b);
    }
    {
        let mut attachment = vec![0u8; 16];
        attachment.extend(string("scenario.toml"));
        attachment.extend(string("application/toml"));
        attachment.extend_from_slice(&u64::MAX.to_le_bytes());
        let mut b = start();
        b.extend(record(op::ATTACHMENT, &attachment));
        end(&mut b);
        add("attachment-data-u64max.mcap", b);
    }
    add("empty.mcap", Vec::new());
    add("magic-only.mcap", MAGIC.to_vec());
    add("not-mcap.mcap", b"PK\x03\x04 this is a zip file, not a log".to_vec());
    {
        let mut b = start();
        end(&mut b);
        add("header-and-footer-only.mcap", b);
    }
    {
        let mut b = start();
        end(&mut b);
        b.extend_from_slice(b"trailing garbage");
        add("garbage-after-footer.mcap", b);
    }
    out
}

/// Scene-less recorder options with small chunks, for small logs with several chunks.
/// (The stations at every row, so that mutations reach many of their messages.)
pub fn small_chunks() -> RecorderOptions {
    RecorderOptions {
        chunk_size: 4096,
        flush_every: 20,
        scene_interval_ns: 0,
        stations_interval_ns: 0,
        ..RecorderOptions::default()
    }
}

/// A short real run of the default scenario (automatic steps), recorded to `path`: `duration`
/// seconds, with `options`.
pub fn record_real_run(path: &Path, duration: f64, options: RecorderOptions) {
    let scenario = Scenario { duration, ..Scenario::paper_mesh() };
    let mut recorder = McapRecorder::with_options(path, options).unwrap();
    Simulation::new(&scenario).unwrap().run(&mut recorder).unwrap();
}

/// The bytes of a short real log (5 ms after impact, several small chunks, ~80 KB: its first
/// quarter already holds step messages after the model, metadata and attachment).
pub fn real_log_bytes() -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("real.mcap");
    record_real_run(&path, 0.005, small_chunks());
    std::fs::read(&path).unwrap()
}

/// Records `steps` synthetic steps under `scenario`'s header (no model is built: the log only
/// claims the scenario), with a contact event every 1000 steps. With `rollbacks`, every step
/// after the first is recorded, rolled back and recorded again (2 step messages, 1 rollback).
pub fn synthetic_log(path: &Path, scenario: &Scenario, steps: u64, rollbacks: bool, options: RecorderOptions) {
    let mut recorder = McapRecorder::with_options(path, options).unwrap();
    let shapes = nalgebra::DMatrix::<f64>::zeros(2, 2);
    recorder
        .start(&RunInfo {
            scenario,
            lower_nodes: &[0.0, 12.0],
            upper_nodes: &[0.0, 29.0],
            nodal_shapes: &shapes,
            stations: None,
        })
        .unwrap();
    let step_ns = 25_000u64;
    let result = |k: u64| {
        let t = k * step_ns;
        let x = (k as f64 * 1e-3).sin();
        let mut r = StepResult {
            step: k,
            time_ns: t,
            time: t as f64 * 1e-9,
            step_size: step_ns as f64 * 1e-9,
            contact: (k / 1000) % 2 == 1,
            lower_tip_deflection: -0.5 * x.abs(),
            upper_contact_deflection: -0.5 * x.abs(),
            lower_clamp_bending_stress: 4e8 * x,
            lower_clamp_shear_stress: 5e7 * x,
            upper_contact_bending_stress: 2e8 * x,
            contact_force: -1e6 * x.abs(),
            contact_stress: -2.5e7 * x.abs(),
            ..StepResult::default()
        };
        r.peaks.lower_tip_deflection = 0.5 * (k.min(5000) as f64 * 1e-3).sin().abs();
        r
    };
    let q = [0.01, -0.02];
    let mut previous = result(0);
    recorder.step(&previous, &q).unwrap();
    for k in 1..steps {
        let r = result(k);
        if k % 1000 == 0 {
            let event =
                ContactEvent { start: (k / 1000) % 2 == 1, time_ns: r.time_ns, step: k, relative_velocity: -1.0 };
            recorder.contact_event(&event).unwrap();
        }
        recorder.step(&r, &q).unwrap();
        if rollbacks {
            recorder.rollback(&previous).unwrap();
            recorder.step(&r, &q).unwrap();
        }
        previous = r;
    }
    recorder.finish().unwrap();
}

/// A log that claims a scenario of `upper`/`beyond`/`lower` elements (only its TOML is stored:
/// building that model is what a reader must not do before validating it).
pub fn scenario_log(upper: u32, beyond: u32, lower: u32) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("claims.mcap");
    let mut scenario = Scenario::default();
    scenario.upper.elements_to_contact = upper;
    scenario.upper.elements_beyond_contact = beyond;
    scenario.lower.elements = lower;
    scenario.step_free = TimeStep::Auto;
    synthetic_log(&path, &scenario, 3, false, small_chunks());
    std::fs::read(&path).unwrap()
}

/// Rewrites every chunk of `log` (our own writer's: zstd) through `edit` on its decompressed
/// records, recompressed with a correct size and CRC: mutations that reach the messages
/// behind the CRC.
pub fn edit_chunks(log: &[u8], edit: &mut dyn FnMut(usize, Vec<u8>) -> Vec<u8>) -> Vec<u8> {
    let mut out = log[..8.min(log.len())].to_vec();
    let mut pos = 8;
    let mut index = 0;
    while pos + 9 <= log.len() {
        let opcode = log[pos];
        let len = u64::from_le_bytes(log[pos + 1..pos + 9].try_into().unwrap()) as usize;
        let end = pos + 9 + len;
        if end > log.len() {
            break;
        }
        let body = &log[pos + 9..end];
        let rewritten = (|| {
            if opcode != op::CHUNK {
                return None;
            }
            let clen = u32::from_le_bytes(body[28..32].try_into().ok()?) as usize;
            let compression = std::str::from_utf8(body.get(32..32 + clen)?).ok()?;
            let at = 32 + clen;
            let dlen = u64::from_le_bytes(body.get(at..at + 8)?.try_into().ok()?) as usize;
            let data = body.get(at + 8..at + 8 + dlen)?;
            let records = match compression {
                "zstd" => zstd::bulk::decompress(data, 1 << 24).ok()?,
                "" => data.to_vec(),
                _ => return None,
            };
            let records = edit(index, records);
            index += 1;
            Some(chunk(&records, compression == "zstd", None))
        })();
        match rewritten {
            Some(c) => out.extend(c),
            None => out.extend_from_slice(&log[pos..end]),
        }
        pos = end;
    }
    out.extend_from_slice(&log[pos..]);
    out
}

/// A mutation of a real log: half the time at the byte level, half inside one chunk behind a
/// correct CRC.
pub fn mutate_log(log: &[u8], rng: &mut Rng) -> Vec<u8> {
    if rng.below(2) == 0 {
        return mutate(log, rng);
    }
    let target = rng.below(chunk_count(log).max(1));
    let mut seed = Rng(rng.next_u64());
    edit_chunks(log, &mut |i, records| if i == target { mutate(&records, &mut seed) } else { records })
}

/// How many chunk records the top level of `log` frames.
pub fn chunk_count(log: &[u8]) -> usize {
    let (mut pos, mut count) = (8, 0);
    while pos + 9 <= log.len() {
        let len = u64::from_le_bytes(log[pos + 1..pos + 9].try_into().unwrap());
        if len > (log.len() - pos - 9) as u64 {
            break;
        }
        count += usize::from(log[pos] == op::CHUNK);
        pos += 9 + len as usize;
    }
    count
}

/// A log of 50 steps whose values are all `value` (NaN, infinities, 1e308, subnormals...), and
/// their times too with `odd_time`: what a damaged or forged log may hold; the report and its
/// figures must cope.
pub fn odd_values_log(value: f64, odd_time: bool) -> Vec<u8> {
    odd_series_log(&|k| if k % 2 == 0 { value } else { -value }, odd_time)
}

/// A log of 50 steps whose values are `value(step)` (and their times too with `odd_time`).
pub fn odd_series_log(value: &dyn Fn(u64) -> f64, odd_time: bool) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("odd.mcap");
    let scenario = Scenario::default();
    let mut recorder = McapRecorder::with_options(&path, small_chunks()).unwrap();
    let v0 = value(0);
    let shapes = nalgebra::DMatrix::<f64>::from_element(2, 2, v0);
    recorder
        .start(&RunInfo {
            scenario: &scenario,
            lower_nodes: &[v0; 2],
            upper_nodes: &[v0; 2],
            nodal_shapes: &shapes,
            stations: None,
        })
        .unwrap();
    for k in 0..50u64 {
        let v = value(k);
        let mut r = StepResult {
            step: k,
            time_ns: k * 1000,
            time: if odd_time { v } else { k as f64 * 1e-6 },
            step_size: v,
            lower_tip_deflection: v,
            upper_contact_deflection: v,
            upper_tip_deflection: v,
            lower_clamp_bending_stress: v,
            lower_clamp_shear_stress: v,
            upper_contact_bending_stress: v,
            contact_force: v,
            contact_stress: v,
            ..StepResult::default()
        };
        r.energy.residual = v;
        r.energy.strain = v;
        r.energy.external_work = v;
        r.peaks.lower_tip_deflection = v;
        r.peaks.contact_force = v;
        if k % 10 == 5 {
            let event = ContactEvent { start: k % 20 == 5, time_ns: k * 1000, step: k, relative_velocity: v };
            recorder.contact_event(&event).unwrap();
        }
        recorder.step(&r, &[v, v]).unwrap();
    }
    recorder.finish().unwrap();
    std::fs::read(&path).unwrap()
}

/// A log holding `records` as its one uncompressed chunk, between a header and a footer: how the
/// cargo-fuzz target `log_chunk` wraps its input.
pub fn wrap_chunk_records(records: &[u8]) -> Vec<u8> {
    let mut log = MAGIC.to_vec();
    log.extend(record(op::HEADER, &[0; 8]));
    log.extend(chunk(records, false, None));
    log.extend(record(op::DATA_END, &[0; 4]));
    log.extend(record(op::FOOTER, &[0; 20]));
    log.extend_from_slice(MAGIC);
    log
}

/// `records` (a chunk's) with every schema's data emptied: our schemas are protobuf descriptor
/// sets of ~10 KB that no reader of ours interprets, so fuzz inputs without them are small.
pub fn strip_schema_data(records: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(records.len());
    let mut pos = 0;
    while pos + 9 <= records.len() {
        let len = u64::from_le_bytes(records[pos + 1..pos + 9].try_into().unwrap()) as usize;
        let Some(body) = records.get(pos + 9..pos + 9 + len) else { break };
        let stripped = (|| {
            if records[pos] != op::SCHEMA {
                return None;
            }
            let name = 2 + 4 + u32::from_le_bytes(body.get(2..6)?.try_into().ok()?) as usize;
            let encoding = name + 4 + u32::from_le_bytes(body.get(name..name + 4)?.try_into().ok()?) as usize;
            let mut b = body.get(..encoding)?.to_vec();
            b.extend_from_slice(&0u32.to_le_bytes());
            Some(record(op::SCHEMA, &b))
        })();
        match stripped {
            Some(r) => out.extend(r),
            None => out.extend_from_slice(&records[pos..pos + 9 + len]),
        }
        pos += 9 + len;
    }
    out.extend_from_slice(&records[pos..]);
    out
}

/// A ~1 MiB log whose one zstd chunk declares 60 MiB of empty contact messages (each decodes to
/// an event kept in memory): within the decompression budget (64x the file, which a 1 MiB
/// attachment of random bytes makes large enough), beyond what the reader keeps (16x the file
/// + 16 MiB). The worst case of memory per file byte.
pub fn compressible_events_log() -> Vec<u8> {
    let mut channel = 1u16.to_le_bytes().to_vec();
    channel.extend_from_slice(&0u16.to_le_bytes());
    channel.extend(string("/beam/contact"));
    channel.extend(string("protobuf"));
    channel.extend_from_slice(&0u32.to_le_bytes());
    let mut records = record(op::CHANNEL, &channel);
    let one = message(1, 0, b"");
    while records.len() + one.len() <= 60 << 20 {
        records.extend_from_slice(&one);
    }
    let mut b = start();
    let mut rng = Rng(60);
    let noise: Vec<u8> = (0..1 << 20).map(|_| rng.next_u64() as u8).collect();
    let mut attachment = vec![0u8; 16];
    attachment.extend(string("noise.bin"));
    attachment.extend(string("application/octet-stream"));
    attachment.extend_from_slice(&(noise.len() as u64).to_le_bytes());
    attachment.extend_from_slice(&noise);
    attachment.extend_from_slice(&0u32.to_le_bytes());
    b.extend(record(op::ATTACHMENT, &attachment));
    b.extend(chunk(&records, true, None));
    end(&mut b);
    b
}

/// The id of the channel on `topic` in `log` (uncompressed: its channel record, at the top level
/// or in a chunk, is found by its topic string).
pub fn channel_id(log: &[u8], topic: &str) -> Option<u16> {
    let mut pattern = (topic.len() as u32).to_le_bytes().to_vec();
    pattern.extend_from_slice(topic.as_bytes());
    let at = log.windows(pattern.len()).position(|w| w == pattern.as_slice())?;
    // The channel record's body: id (u16), schema id (u16), then the topic.
    Some(u16::from_le_bytes(log.get(at.checked_sub(4)?..at.checked_sub(2)?)?.try_into().ok()?))
}

/// `log` (our writer's, uncompressed or zstd) with the data of every message on `topic` replaced by
/// `edit(k, data)` (k counts those messages), behind correct lengths and CRCs.
pub fn rewrite_messages(log: &[u8], topic: &str, edit: &mut dyn FnMut(usize, &[u8]) -> Vec<u8>) -> Vec<u8> {
    let channel = channel_id(log, topic).unwrap_or_else(|| panic!("no channel {topic}"));
    let mut count = 0;
    edit_chunks(log, &mut |_, records| {
        let mut out = Vec::with_capacity(records.len());
        let mut pos = 0;
        while pos + 9 <= records.len() {
            let len = u64::from_le_bytes(records[pos + 1..pos + 9].try_into().unwrap()) as usize;
            let body = &records[pos + 9..pos + 9 + len];
            if records[pos] == op::MESSAGE && u16::from_le_bytes([body[0], body[1]]) == channel {
                let mut new = body[..22].to_vec();
                new.extend(edit(count, &body[22..]));
                count += 1;
                out.extend(record(op::MESSAGE, &new));
            } else {
                out.extend_from_slice(&records[pos..pos + 9 + len]);
            }
            pos += 9 + len;
        }
        out.extend_from_slice(&records[pos..]);
        out
    })
}

/// One structure-aware mutation of the TOML text `text` (scenario files and packed resources
/// alike): one to three edits, each a key's value set to one of `literals`, a line removed,
/// repeated or swapped, one of `extras` inserted, or `other` (the caller's own edit at line `i`).
pub fn mutate_toml(
    text: &str,
    rng: &mut Rng,
    literals: &[&str],
    extras: &[&str],
    other: &dyn Fn(&mut Rng, &mut Vec<String>, usize),
) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            lines.push("x = 1".into());
        }
        let i = rng.below(lines.len());
        match rng.below(8) {
            0..=2 => {
                if let Some((key, _)) = lines[i].split_once('=') {
                    lines[i] = format!("{key}= {}", rng.pick(literals));
                }
            }
            3 => {
                lines.remove(i);
            }
            4 => {
                // A whole table header, or any line, repeated elsewhere.
                let line = lines[i].clone();
                lines.insert(rng.below(lines.len() + 1), line);
            }
            5 => {
                let j = rng.below(lines.len());
                lines.swap(i, j);
            }
            6 => {
                let extra = rng.pick(extras);
                lines.insert(i, extra.to_string());
            }
            _ => other(rng, &mut lines, i),
        }
    }
    lines.join("\n")
}

/// One structure-aware mutation of CSV text (1 to 3 of: a cell replaced by one of `literals`, a
/// line deleted, duplicated or swapped), shared by the CSV readers' fuzz tests.
pub fn mutate_csv(text: &str, literals: &[&str], rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            lines.push("time".into());
        }
        let i = rng.below(lines.len());
        match rng.below(6) {
            0..=2 => {
                let mut cells: Vec<String> = lines[i].split(',').map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = rng.pick(literals).to_string();
                lines[i] = cells.join(",");
            }
            3 => {
                lines.remove(i);
            }
            4 => {
                let line = lines[i].clone();
                lines.insert(rng.below(lines.len() + 1), line);
            }
            _ => {
                let j = rng.below(lines.len());
                lines.swap(i, j);
            }
        }
    }
    lines.join("\n")
}
