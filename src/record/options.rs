//! How a log is written ([`RecorderOptions`], [`LogCompression`]) and what writing it cost
//! ([`RecorderTiming`]): set by the caller of [`super::mcap::McapRecorder`], read by it and by its
//! writer thread ([`super::writer`]).

use std::time::Duration;

/// How the log's chunks are compressed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LogCompression {
    /// None, the default: the solver's results are doubles that compress poorly (LZ4 saves
    /// about 20 %, zstd 35 %) while compressing takes the writer thread longer than the solver's
    /// step takes (see `beam-impact bench`); without it recording keeps pace with the solver.
    #[default]
    None,
    /// LZ4 frames: a 20 % smaller file, at about twice the writer thread's work.
    Lz4,
    /// zstd at [`RecorderOptions::compression_level`]: the smallest file, the slowest writer.
    Zstd,
}

impl std::str::FromStr for LogCompression {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "lz4" => Ok(LogCompression::Lz4),
            "zstd" => Ok(LogCompression::Zstd),
            "none" => Ok(LogCompression::None),
            other => Err(format!("log compression must be lz4, zstd or none, got \"{other}\"")),
        }
    }
}

impl std::fmt::Display for LogCompression {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LogCompression::Lz4 => "lz4",
            LogCompression::Zstd => "zstd",
            LogCompression::None => "none",
        })
    }
}

/// How the log is written. The defaults: no compression, chunks up to 256 KiB, a flush every 1000 steps and
/// at contact events, a scene and modal coordinates every 1 ms of simulated time, every step with
/// its stations' stresses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecorderOptions {
    /// Target uncompressed chunk size, bytes (64-256 KiB: a killed run loses at most one).
    pub chunk_size: u64,
    /// Chunk compression.
    pub compression: LogCompression,
    /// zstd level (1 is the fastest; 0 means zstd's default, 3); LZ4 ignores it.
    pub compression_level: u32,
    /// Steps between flushes (each flush closes the chunk and hands it to the OS).
    pub flush_every: u64,
    /// Simulated time between two scene updates, ns (0: no scene).
    pub scene_interval_ns: u64,
    /// Simulated time between two regular `/beam/modes` messages, ns (0: only at step 0, peaks,
    /// contact changes and the last step).
    pub modes_interval_ns: u64,
    /// Write `/beam/modes` at all (the scene is drawn either way).
    pub modal_coordinates: bool,
    /// Write `/beam/stations`, the stress at every station of each recorded step (issue 30; the
    /// envelope attachment and the scene's utilisation colours stay either way).
    pub station_stresses: bool,
    /// Record every Nth step (1: every step); see the module's decimation rule.
    pub record_every: u64,
    /// Clock every message's encoding and writing (for the benchmark's breakdown: the clock
    /// reads, four a message, slow the writer noticeably). The writer thread's CPU time and the
    /// solver's wait for the queue are measured either way.
    pub timing: bool,
    /// Accept a device as the log (the CLI's `/dev/null`); the FMU wants a regular file.
    pub allow_devices: bool,
    /// Size at which the log stops (checked at every flush), bytes: the run goes on unrecorded
    /// and [`McapRecorder::capped`](super::mcap::McapRecorder::capped) says so. [`MAX_LOG_BYTES`] by default.
    pub max_bytes: u64,
}

/// Default size cap of a log: 2 GiB, about 7.7 million steps of the paper's model (278 B each).
pub const MAX_LOG_BYTES: u64 = 2 << 30;

impl Default for RecorderOptions {
    fn default() -> Self {
        RecorderOptions {
            // A chunk closes once it passes this size, so it ends at most one message (< 1 KiB)
            // above it: 255 KiB keeps every chunk within 256 KiB.
            chunk_size: 255 * 1024,
            compression: LogCompression::default(),
            compression_level: 1,
            flush_every: 1000,
            scene_interval_ns: 1_000_000,
            modes_interval_ns: 1_000_000,
            modal_coordinates: true,
            station_stresses: true,
            record_every: 1,
            timing: false,
            allow_devices: false,
            max_bytes: MAX_LOG_BYTES,
        }
    }
}

/// Time spent in the recorder: `encode` and `write` when [`RecorderOptions::timing`] is on, the
/// rest always.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RecorderTiming {
    /// Building and protobuf-encoding messages (writer thread).
    pub encode: Duration,
    /// Handing messages to the MCAP writer: chunking, compression, CRCs, file writes, flushes,
    /// finish (writer thread).
    pub write: Duration,
    /// Time the solver's thread waited for room in the queue (the writer was behind).
    pub queue_wait: Duration,
    /// CPU time of the writer thread, start to finish (what it costs a second core).
    pub writer_cpu: Duration,
    /// Messages written.
    pub messages: u64,
}
