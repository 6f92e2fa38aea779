//! How a log is written ([`RecorderOptions`], [`LogCompression`]) and what writing it cost
//! ([`RecorderTiming`]): set by the caller of [`super::mcap::McapRecorder`], read by it and by its
//! writer thread ([`super::writer`]).

use std::time::Duration;

/// How the log's chunks are compressed (every MCAP reader reads all three: the `mcap` crate,
/// Foxglove, Python's `mcap`, `@mcap/core` with `@mcap/support`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LogCompression {
    /// Uncompressed chunks: the cheapest writer, the largest file (the paper log 45.9 MB).
    None,
    /// LZ4 frames: about 24 % smaller than none on the paper log, at about twice the writer
    /// thread's work; zstd at its fast levels is both smaller and cheaper (measured in
    /// `docs/logs.md`).
    Lz4,
    /// zstd at [`RecorderOptions::compression_level`], the default: at level -1 about a third
    /// smaller than none on the paper log (30.5 MB) and half on the arrestor example's, for about
    /// the writer work LZ4 costs.
    #[default]
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

/// zstd level of the default compression: -1, one of zstd's fast levels. Measured on the paper
/// log (`docs/logs.md`, 2026-11-29): level 1 is 2 % smaller (29.8 MB against 30.5 MB) for 18 %
/// more writer CPU; level -5 8 % larger for 13 % less.
pub const DEFAULT_ZSTD_LEVEL: i32 = -1;

/// The topics a log can leave out (`log.channels`, `run --log-channels`): the modal
/// coordinates (`/beam/modes`), the 3D scene (`/beam/scene`) and the stations' stresses
/// (`/beam/stations`). The model, the steps, the contact events and the log lines are always
/// written: they are what [`crate::replay`] reads a run from (a log without its steps would not
/// replay), and they are a small part of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LogChannels {
    /// `/beam/modes`: without it `report` cannot give the bridge's strain energy at the peak
    /// deflection, and `load_log` has no modal coordinates (no deflected shapes).
    pub modes: bool,
    /// `/beam/scene`: Foxglove's 3D panel; neither `report` nor `load_log` reads it.
    pub scene: bool,
    /// `/beam/stations`: without it a killed run's log cannot rebuild the stress envelope (a
    /// finished log carries it as an attachment), and `load_log`'s `station_stresses` is empty.
    pub stations: bool,
}

impl Default for LogChannels {
    fn default() -> Self {
        LogChannels::ALL
    }
}

/// The topics by their short names, in the order [`LogChannels`]' `Display` writes them; the
/// first four are always written.
pub const CHANNEL_NAMES: [&str; 7] = ["model", "step", "contact", "log", "modes", "scene", "stations"];

/// The longest `log.channels` text accepted, bytes (every name once with its `/beam/` prefix
/// and a space after each comma is 82).
pub const MAX_CHANNELS_TEXT: usize = 256;

impl LogChannels {
    /// Every topic (the default).
    pub const ALL: LogChannels = LogChannels { modes: true, scene: true, stations: true };
    /// The topics always written only.
    pub const REQUIRED: LogChannels = LogChannels { modes: false, scene: false, stations: false };

    /// Parses a comma list of topics, each by its short name (`modes`) or its topic
    /// (`/beam/modes`), spaces around a name ignored, or `all`. The always-written topics may be
    /// named or not. Every problem is one line naming the bad value: `log.channels: unknown topic
    /// "foo"; known: ...`.
    pub fn parse(text: &str) -> std::result::Result<LogChannels, String> {
        let known = || format!("{}, or all", CHANNEL_NAMES.join(", "));
        if text.len() > MAX_CHANNELS_TEXT {
            return Err(format!(
                "log.channels: {} bytes, at most {MAX_CHANNELS_TEXT}: give a comma list of {}",
                text.len(),
                known()
            ));
        }
        if text.trim().is_empty() {
            return Err(format!(
                "log.channels: empty; give a comma list of {} (model, step, contact and log are always written)",
                known()
            ));
        }
        let mut channels = LogChannels::REQUIRED;
        for (k, item) in text.split(',').enumerate() {
            let name = item.trim();
            let short = name.strip_prefix("/beam/").unwrap_or(name);
            match short {
                "all" if name == "all" => channels = LogChannels::ALL,
                "model" | "step" | "contact" | "log" => {}
                "modes" => channels.modes = true,
                "scene" => channels.scene = true,
                "stations" => channels.stations = true,
                "" => {
                    return Err(format!(
                        "log.channels: empty topic at position {} of {}; known: {}",
                        k + 1,
                        shown(text),
                        known()
                    ))
                }
                _ => return Err(format!("log.channels: unknown topic {}; known: {}", shown(name), known())),
            }
        }
        Ok(channels)
    }
}

/// `text` quoted for an error line: at most 40 characters, control characters and quotes escaped.
fn shown(text: &str) -> String {
    let mut cut: String = text.chars().take(40).collect();
    if cut.len() < text.len() {
        cut.push_str("...");
    }
    format!("{cut:?}")
}

impl std::str::FromStr for LogChannels {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        LogChannels::parse(s)
    }
}

impl std::fmt::Display for LogChannels {
    /// The topics written, by their short names (`model,step,contact,log,modes,scene,stations`);
    /// parses back to the same set.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let on = [true, true, true, true, self.modes, self.scene, self.stations];
        let names: Vec<&str> = CHANNEL_NAMES.iter().zip(on).filter(|(_, on)| *on).map(|(n, _)| *n).collect();
        f.write_str(&names.join(","))
    }
}

/// How the log is written. The defaults: zstd chunks at level [`DEFAULT_ZSTD_LEVEL`], chunks up to 256 KiB, a flush every 1000 steps and
/// at contact events, a scene, modal coordinates and the stations' stresses every 1 ms of
/// simulated time, the dense output every 0.1 ms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecorderOptions {
    /// Target uncompressed chunk size, bytes (64-256 KiB: a killed run loses at most one).
    pub chunk_size: u64,
    /// Chunk compression.
    pub compression: LogCompression,
    /// zstd level: 1 to 22, 0 for zstd's default (3), or a fast level, -1 to -131072 (the faster,
    /// the larger); LZ4 ignores it.
    pub compression_level: i32,
    /// Steps between flushes (each flush closes the chunk and hands it to the OS).
    pub flush_every: u64,
    /// Simulated time between two scene updates, ns (0: no scene).
    pub scene_interval_ns: u64,
    /// Simulated time between two regular `/beam/modes` messages, ns (0: only at step 0, peaks,
    /// contact changes and the last step).
    pub modes_interval_ns: u64,
    /// The topics written besides the always-written ones: a topic left out here is left out
    /// whatever the switches below say ([`RecorderOptions::effective`]).
    pub channels: LogChannels,
    /// Write `/beam/modes` at all (the scene is drawn either way).
    pub modal_coordinates: bool,
    /// Write `/beam/stations`, the stress at every station (issue 30; the envelope attachment and
    /// the scene's utilisation colours stay either way).
    pub station_stresses: bool,
    /// Simulated time between two rows that carry `/beam/stations`, ns: the first recorded row at
    /// or after each multiple, besides the rows where contact starts or ends and the last row.
    /// 0: every recorded row (so in a log of every internal step, see
    /// [`RecorderOptions::effective`]). 1 ms by default, the scene's rate.
    pub stations_interval_ns: u64,
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
            compression_level: DEFAULT_ZSTD_LEVEL,
            flush_every: 1000,
            scene_interval_ns: 1_000_000,
            modes_interval_ns: 1_000_000,
            channels: LogChannels::ALL,
            modal_coordinates: true,
            station_stresses: true,
            stations_interval_ns: 1_000_000,
            record_every: 1,
            sample_interval_ns: DEFAULT_SAMPLE_INTERVAL_NS,
            timing: false,
            allow_devices: false,
            max_bytes: MAX_LOG_BYTES,
        }
    }
}

impl RecorderOptions {
    /// The options as the recorder applies them: a topic is written when `channels` names it and
    /// its older switch ([`RecorderOptions::modal_coordinates`], [`RecorderOptions::station_stresses`],
    /// a non-zero [`RecorderOptions::scene_interval_ns`]) leaves it on; `channels` then says
    /// exactly what the log holds. A log of every internal step (`sample_interval_ns` 0) carries
    /// the stations at every recorded row too.
    pub fn effective(self) -> RecorderOptions {
        let channels = LogChannels {
            modes: self.channels.modes && self.modal_coordinates,
            scene: self.channels.scene && self.scene_interval_ns > 0,
            stations: self.channels.stations && self.station_stresses,
        };
        RecorderOptions {
            channels,
            modal_coordinates: channels.modes,
            station_stresses: channels.stations,
            scene_interval_ns: if channels.scene { self.scene_interval_ns } else { 0 },
            stations_interval_ns: if self.sample_interval_ns == 0 { 0 } else { self.stations_interval_ns },
            ..self
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn channels_parse_short_names_topics_and_all_and_print_back() {
        assert_eq!(LogChannels::parse("all").unwrap(), LogChannels::ALL);
        assert_eq!(LogChannels::parse("step").unwrap(), LogChannels::REQUIRED);
        let some = LogChannels::parse(" step, /beam/modes ,scene").unwrap();
        assert_eq!(some, LogChannels { modes: true, scene: true, stations: false });
        assert_eq!(some.to_string(), "model,step,contact,log,modes,scene");
        assert_eq!(LogChannels::ALL.to_string().parse::<LogChannels>().unwrap(), LogChannels::ALL);
        assert_eq!(LogChannels::REQUIRED.to_string(), "model,step,contact,log");
    }

    #[test]
    fn channels_errors_name_the_bad_value_on_one_line() {
        let e = LogChannels::parse("step,foo").unwrap_err();
        assert_eq!(
            e,
            "log.channels: unknown topic \"foo\"; known: model, step, contact, log, modes, scene, stations, or all"
        );
        assert!(LogChannels::parse("").unwrap_err().starts_with("log.channels: empty;"));
        assert!(LogChannels::parse("step,,modes")
            .unwrap_err()
            .contains("empty topic at position 2 of \"step,,modes\""));
        assert!(LogChannels::parse("/beam/all").unwrap_err().contains("unknown topic \"/beam/all\""));
        assert!(LogChannels::parse(&"x".repeat(300)).unwrap_err().starts_with("log.channels: 300 bytes, at most 256"));
        assert!(!LogChannels::parse("a\nb").unwrap_err().contains('\n'));
    }

    #[test]
    fn effective_options_follow_the_channels_and_the_older_switches() {
        let o = RecorderOptions { channels: LogChannels::parse("scene").unwrap(), ..RecorderOptions::default() }
            .effective();
        assert!(!o.modal_coordinates && !o.station_stresses && o.scene_interval_ns > 0);
        let o = RecorderOptions { modal_coordinates: false, scene_interval_ns: 0, ..RecorderOptions::default() }
            .effective();
        assert_eq!(o.channels, LogChannels { modes: false, scene: false, stations: true });
    }
}
