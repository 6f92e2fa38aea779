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
    /// Record every Nth step (1: every step); see the module's decimation rule. Only for a log
    /// without the dense output (`sample_interval_ns` 0).
    pub record_every: u64,
    /// The dense output's interval, ns (issue 41): the converged method's log holds the exact
    /// state at every multiple of it and at every instant where a running peak was reached,
    /// besides its internal steps' ends where contact starts or ends or a peak rises; the paper
    /// method's log its own step ends, one at least every interval (and those where contact
    /// changes or a peak rises). 0: every internal step (thinned by `record_every`).
    /// [`DEFAULT_SAMPLE_INTERVAL_NS`] by default.
    pub sample_interval_ns: u64,
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

/// The dense output's default interval: 0.1 ms, 10 kHz (issue 41). Thirty samples or more in the
/// shortest contact of the paper scenario (3.4 ms), ten a period up to 1 kHz, beyond the bridge's
/// and the arrestor's modes that carry the stresses (the paper scenario's fifth mode is below
/// 500 Hz): a plot of the log looks like the physics. The paper method's 2.5-5e-5 s steps are
/// thinned to one at least every interval, as the paper plotted its figures.
pub const DEFAULT_SAMPLE_INTERVAL_NS: u64 = 100_000;

/// Bounds of the dense output's interval (besides 0, every internal step): 1 us to 1 s (the
/// error message of [`sample_interval_ns`] spells them). Below a
/// microsecond a 3 s run's log would pass its 2 GiB cap; above a second it holds no dynamics.
pub const SAMPLE_INTERVAL_BOUNDS_NS: (u64, u64) = (1_000, 1_000_000_000);

/// The dense output's interval of a log, ns, from `seconds` as a user gives it (`--log-sample-interval`,
/// the FMU's `log.sample_interval`, Python's `log_sample_interval`): 0 (every internal step) or
/// within [`SAMPLE_INTERVAL_BOUNDS_NS`]; anything else is refused in one line naming `name`.
pub fn sample_interval_ns(name: &str, seconds: f64) -> std::result::Result<u64, String> {
    let (low, high) = SAMPLE_INTERVAL_BOUNDS_NS;
    let ns = seconds * 1e9;
    if seconds == 0.0 {
        return Ok(0);
    }
    if !(ns >= low as f64 - 0.5 && ns <= high as f64 + 0.5) {
        // Short either way: 1e-300 and 1e300 as such, not as 300 digits.
        let given = if (1e-4..1e6).contains(&seconds.abs()) { format!("{seconds}") } else { format!("{seconds:e}") };
        return Err(format!("{name} must be 0 (every internal step) or between 1e-6 and 1 s, got {given}"));
    }
    Ok(ns.round() as u64)
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
            sample_interval_ns: DEFAULT_SAMPLE_INTERVAL_NS,
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
