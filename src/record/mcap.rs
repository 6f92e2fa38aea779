//! The MCAP recorder: every internal step of a run as one protobuf message, readable by
//! Foxglove, by Python's `mcap` package and by [`super::report`].
//!
//! Channels (all with log_time = publish_time = simulated time in ns since the impact, one time
//! base; for the FMU that is the time since its startTime; after a rollback of an FMU state the
//! time goes back, marked by a `rolled back to` line on `/beam/log`):
//!
//! | topic | schema | what |
//! |---|---|---|
//! | `/beam/model` | `beam_impact.Model` | once at t = 0: scenario, nodes, nodal shape matrix |
//! | `/beam/step` | `beam_impact.Step` | every internal step, step 0 = initial state |
//! | `/beam/contact` | `beam_impact.ContactEvent` | contact starts and ends |
//! | `/beam/log` | `foxglove.Log` | the same events as text lines |
//! | `/beam/scene` | `foxglove.SceneUpdate` | both beams as line strips, every [`RecorderOptions::scene_interval_ns`] |
//!
//! The scenario is also an MCAP Metadata record (`scenario`, flattened dotted keys) and a TOML
//! attachment (`scenario.toml`). Chunks are zstd-compressed without worker threads (this runs
//! inside FMI hosts too); the writer flushes at contact events and every
//! [`RecorderOptions::flush_every`] steps, so a killed process loses at most the open chunk.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use ::mcap::records::{MessageHeader, Metadata};
use ::mcap::{Attachment, Compression, WriteOptions, Writer};
use prost::Message;

use super::scene::SceneBuilder;
use super::schema::{self, ContactEventMessage, LogMessage, ModelMessage, StepMessage, TimeMessage};
use super::{Recorder, RunInfo};
use crate::error::{Error, Result};
use crate::results::{ContactEvent, StepResult};

/// Topic of the step messages.
pub const STEP_TOPIC: &str = "/beam/step";
/// Topic of the contact events.
pub const CONTACT_TOPIC: &str = "/beam/contact";
/// Topic of the one-off model message.
pub const MODEL_TOPIC: &str = "/beam/model";
/// Topic of the 3D scene.
pub const SCENE_TOPIC: &str = "/beam/scene";
/// Topic of the log lines.
pub const LOG_TOPIC: &str = "/beam/log";
/// Name of the scenario's Metadata record.
pub const SCENARIO_METADATA: &str = "scenario";
/// Name of the scenario's TOML attachment.
pub const SCENARIO_ATTACHMENT: &str = "scenario.toml";

/// How the log is written. The defaults are the issue's: zstd, chunks up to 256 KiB, a flush every
/// 1000 steps and at contact events, a scene every 1 ms of simulated time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecorderOptions {
    /// Target uncompressed chunk size, bytes (64-256 KiB: a killed run loses at most one).
    pub chunk_size: u64,
    /// zstd level (1 is the fastest; 0 means zstd's default, 3).
    pub compression_level: u32,
    /// Steps between flushes (each flush closes the chunk and hands it to the OS).
    pub flush_every: u64,
    /// Simulated time between two scene updates, ns (0: no scene).
    pub scene_interval_ns: u64,
    /// Measure the time spent encoding and writing (for the benchmark).
    pub timing: bool,
    /// Accept a device as the log (the CLI's `/dev/null`); the FMU wants a regular file.
    pub allow_devices: bool,
    /// Size at which the log stops (checked at every flush), bytes: the run goes on unrecorded
    /// and [`McapRecorder::capped`] says so. [`MAX_LOG_BYTES`] by default.
    pub max_bytes: u64,
}

/// Default size cap of a log: 2 GiB, about 7 million steps of the paper's model (300 B each).
pub const MAX_LOG_BYTES: u64 = 2 << 30;

impl Default for RecorderOptions {
    fn default() -> Self {
        RecorderOptions {
            // A chunk closes once it passes this size, so it ends at most one message (< 1 KiB)
            // above it: 255 KiB keeps every chunk within 256 KiB.
            chunk_size: 255 * 1024,
            compression_level: 1,
            flush_every: 1000,
            scene_interval_ns: 1_000_000,
            timing: false,
            allow_devices: false,
            max_bytes: MAX_LOG_BYTES,
        }
    }
}

/// Time spent in the recorder, filled when [`RecorderOptions::timing`] is on.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RecorderTiming {
    /// Building and protobuf-encoding messages.
    pub encode: Duration,
    /// Handing messages to the writer: chunking, zstd, CRCs, file writes, flushes, finish.
    pub write: Duration,
    /// Messages written.
    pub messages: u64,
}

#[derive(Clone, Copy, Debug, Default)]
struct Channels {
    model: u16,
    step: u16,
    contact: u16,
    log: u16,
    scene: u16,
}

/// Writes every step of a run to an MCAP file.
pub struct McapRecorder {
    path: PathBuf,
    options: RecorderOptions,
    writer: Option<Writer<BufWriter<File>>>,
    channels: Channels,
    sequences: [u32; 5],
    message: StepMessage,
    buffer: Vec<u8>,
    scene: Option<SceneBuilder>,
    next_scene_ns: u64,
    steps_since_flush: u64,
    timing: RecorderTiming,
    finished: bool,
    /// Why the log stopped early (its size cap), if it did.
    capped: Option<String>,
    /// Time of the latest step recorded, ns.
    last_time_ns: u64,
}

impl std::fmt::Debug for McapRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder")
            .field("path", &self.path)
            .field("options", &self.options)
            .field("finished", &self.finished)
            .finish_non_exhaustive()
    }
}

fn channel_index(channel: u16, c: &Channels) -> usize {
    match channel {
        x if x == c.model => 0,
        x if x == c.step => 1,
        x if x == c.contact => 2,
        x if x == c.log => 3,
        _ => 4,
    }
}

impl McapRecorder {
    /// Creates (truncates) the file at `path`; the error names the path.
    pub fn create(path: &Path) -> Result<Self> {
        Self::with_options(path, RecorderOptions::default())
    }

    /// Like [`McapRecorder::create`], with explicit options.
    pub fn with_options(path: &Path, options: RecorderOptions) -> Result<Self> {
        let io_error = |action, source| Error::Io { action, path: path.display().to_string(), source };
        // Open without truncating, take an exclusive lock, then truncate: two writers given the same
        // path (two FMU instances with the default log.path) get an error, not an interleaved file.
        let file = super::output::open_output(path, options.allow_devices, "cannot create MCAP log")?;
        file.try_lock().map_err(|e| {
            io_error(
                "cannot write MCAP log",
                std::io::Error::other(format!("the file is being written by another run or instance ({e})")),
            )
        })?;
        // A device (the CLI's /dev/null) has no length to cut.
        if file.metadata().is_ok_and(|m| m.is_file()) {
            file.set_len(0).map_err(|source| io_error("cannot truncate MCAP log", source))?;
        }
        let write_options = WriteOptions::new()
            .profile("beam-impact")
            .compression(Some(Compression::Zstd))
            .compression_level(options.compression_level)
            .compression_threads(0)
            .chunk_size(Some(options.chunk_size));
        let mut recorder = McapRecorder {
            path: path.to_path_buf(),
            options,
            writer: None,
            channels: Channels::default(),
            sequences: [0; 5],
            message: StepMessage::default(),
            buffer: Vec::with_capacity(4096),
            scene: None,
            next_scene_ns: 0,
            steps_since_flush: 0,
            timing: RecorderTiming::default(),
            finished: false,
            capped: None,
            last_time_ns: 0,
        };
        let writer = write_options.create(BufWriter::with_capacity(128 * 1024, file)).map_err(|e| recorder.err(e))?;
        recorder.writer = Some(writer);
        recorder.add_channels()?;
        Ok(recorder)
    }

    fn err(&self, e: impl std::fmt::Display) -> Error {
        Error::Mcap { path: self.path.display().to_string(), message: e.to_string() }
    }

    fn writer(&mut self) -> Result<&mut Writer<BufWriter<File>>> {
        let path = self.path.display().to_string();
        self.writer.as_mut().ok_or(Error::Mcap { path, message: "the log is already finished".into() })
    }

    fn add_channels(&mut self) -> Result<()> {
        let beam = schema::beam_impact_descriptor();
        let none = BTreeMap::new();
        let path = self.path.display().to_string();
        let w = self.writer()?;
        let err = |e: ::mcap::McapError| Error::Mcap { path: path.clone(), message: e.to_string() };
        let step_schema = w.add_schema(schema::STEP_SCHEMA, "protobuf", &beam).map_err(err)?;
        let contact_schema = w.add_schema(schema::CONTACT_SCHEMA, "protobuf", &beam).map_err(err)?;
        let model_schema = w.add_schema(schema::MODEL_SCHEMA, "protobuf", &beam).map_err(err)?;
        let scene_schema =
            w.add_schema(schema::SCENE_SCHEMA, "protobuf", &schema::scene_update_descriptor()).map_err(err)?;
        let log_schema = w.add_schema(schema::LOG_SCHEMA, "protobuf", &schema::log_descriptor()).map_err(err)?;
        let channels = Channels {
            model: w.add_channel(model_schema, MODEL_TOPIC, "protobuf", &none).map_err(err)?,
            step: w.add_channel(step_schema, STEP_TOPIC, "protobuf", &none).map_err(err)?,
            contact: w.add_channel(contact_schema, CONTACT_TOPIC, "protobuf", &none).map_err(err)?,
            log: w.add_channel(log_schema, LOG_TOPIC, "protobuf", &none).map_err(err)?,
            scene: w.add_channel(scene_schema, SCENE_TOPIC, "protobuf", &none).map_err(err)?,
        };
        self.channels = channels;
        Ok(())
    }

    /// Writes the encoded `self.buffer` on `channel` at `time_ns`.
    fn write_buffer(&mut self, channel: u16, time_ns: u64) -> Result<()> {
        let index = channel_index(channel, &self.channels);
        let header = MessageHeader {
            channel_id: channel,
            sequence: self.sequences[index],
            log_time: time_ns,
            publish_time: time_ns,
        };
        self.sequences[index] = self.sequences[index].wrapping_add(1);
        let started = self.options.timing.then(Instant::now);
        let writer = self.writer.as_mut();
        let result = match writer {
            Some(w) => w.write_to_known_channel(&header, &self.buffer),
            None => return Err(self.err("the log is already finished")),
        };
        result.map_err(|e| self.err(e))?;
        if let Some(t) = started {
            self.timing.write += t.elapsed();
        }
        self.timing.messages += 1;
        Ok(())
    }

    fn encode(&mut self, message: &impl Message) {
        encode_into(&mut self.buffer, message);
    }

    fn flush(&mut self) -> Result<()> {
        let started = self.options.timing.then(Instant::now);
        let result = self.writer()?.flush();
        result.map_err(|e| self.err(e))?;
        if let Some(t) = started {
            self.timing.write += t.elapsed();
        }
        self.steps_since_flush = 0;
        let written = std::fs::metadata(&self.path).map_or(0, |m| m.len());
        if self.capped.is_none() && written >= self.options.max_bytes {
            let reason = format!(
                "the MCAP log {} reached its size cap of {} bytes at {written} bytes: it ends here, the run goes on \
                 unrecorded",
                self.path.display(),
                self.options.max_bytes
            );
            // The log itself says why it ends early.
            let log = LogMessage {
                timestamp: Some(TimeMessage::from_ns(self.last_time_ns)),
                level: schema::LOG_LEVEL_WARNING,
                message: reason.clone(),
                name: "beam-impact".into(),
                file: String::new(),
                line: 0,
            };
            self.encode(&log);
            self.write_buffer(self.channels.log, self.last_time_ns)?;
            self.capped = Some(reason);
        }
        Ok(())
    }

    /// Why the log stopped before the run's end (it reached its size cap), if it did.
    pub fn capped(&self) -> Option<&str> {
        self.capped.as_deref()
    }

    /// Adds an attachment (the FMU's modelDescription.xml, for example).
    pub fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        let attachment = Attachment {
            log_time: 0,
            create_time: 0,
            name: name.to_string(),
            media_type: media_type.to_string(),
            data: Cow::Borrowed(data),
        };
        let result = self.writer()?.attach(&attachment);
        result.map_err(|e| self.err(e))
    }

    /// The file being written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The options in use.
    pub fn options(&self) -> &RecorderOptions {
        &self.options
    }

    /// Time spent encoding and writing so far (zero unless [`RecorderOptions::timing`]).
    pub fn timing(&self) -> RecorderTiming {
        self.timing
    }
}

/// How the log line of a rollback starts (the reader recognises it).
pub const ROLLBACK_LINE: &str = "rolled back to";

/// Encodes `message` into the cleared `buffer`. Encoding into a Vec cannot fail: it grows.
fn encode_into(buffer: &mut Vec<u8>, message: &impl Message) {
    buffer.clear();
    message.encode(buffer).expect("encoding into a Vec cannot run out of space");
}

/// The scenario's TOML flattened to dotted keys (`upper.length` -> `29.0`).
pub fn flatten_toml(text: &str) -> BTreeMap<String, String> {
    fn walk(prefix: &str, value: &toml::Value, out: &mut BTreeMap<String, String>) {
        match value {
            toml::Value::Table(table) => {
                for (k, v) in table {
                    let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                    walk(&key, v, out);
                }
            }
            toml::Value::String(s) => {
                out.insert(prefix.to_string(), s.clone());
            }
            other => {
                out.insert(prefix.to_string(), other.to_string());
            }
        }
    }
    let mut out = BTreeMap::new();
    if let Ok(value) = text.parse::<toml::Table>() {
        walk("", &toml::Value::Table(value), &mut out);
    }
    out
}

impl Recorder for McapRecorder {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        let toml = info.scenario.to_toml();
        let shapes = info.nodal_shapes;
        let model = ModelMessage {
            scenario_toml: toml.clone(),
            lower_nodes: info.lower_nodes.to_vec(),
            upper_nodes: info.upper_nodes.to_vec(),
            shape_rows: shapes.nrows() as u32,
            shape_cols: shapes.ncols() as u32,
            nodal_shapes: (0..shapes.nrows()).flat_map(|r| (0..shapes.ncols()).map(move |c| shapes[(r, c)])).collect(),
        };
        self.encode(&model);
        self.write_buffer(self.channels.model, 0)?;
        let mut metadata = flatten_toml(&toml);
        metadata.insert("paper".into(), info.scenario.is_paper().to_string());
        metadata.insert("beam_impact_version".into(), env!("CARGO_PKG_VERSION").into());
        let result = self.writer()?.write_metadata(&Metadata { name: SCENARIO_METADATA.into(), metadata });
        result.map_err(|e| self.err(e))?;
        self.attach(SCENARIO_ATTACHMENT, "application/toml", toml.as_bytes())?;
        if self.options.scene_interval_ns > 0 {
            self.scene = Some(SceneBuilder::new(info));
        }
        self.next_scene_ns = 0;
        Ok(())
    }

    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        if self.capped.is_some() {
            return Ok(());
        }
        self.last_time_ns = result.time_ns;
        let started = self.options.timing.then(Instant::now);
        self.message.fill(result, modal_coordinates);
        encode_into(&mut self.buffer, &self.message);
        if let Some(t) = started {
            self.timing.encode += t.elapsed();
        }
        self.write_buffer(self.channels.step, result.time_ns)?;
        if self.scene.is_some() && result.time_ns >= self.next_scene_ns {
            let started = self.options.timing.then(Instant::now);
            let interval = self.options.scene_interval_ns;
            self.next_scene_ns = (result.time_ns / interval + 1) * interval;
            if let Some(scene) = self.scene.as_mut() {
                encode_into(&mut self.buffer, scene.update(result.time_ns, modal_coordinates));
            }
            if let Some(t) = started {
                self.timing.encode += t.elapsed();
            }
            self.write_buffer(self.channels.scene, result.time_ns)?;
        }
        self.steps_since_flush += 1;
        if self.steps_since_flush >= self.options.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    fn stopped_early(&self) -> Option<&str> {
        self.capped()
    }

    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        if self.capped.is_some() {
            return Ok(());
        }
        let message = ContactEventMessage::from(event);
        self.encode(&message);
        self.write_buffer(self.channels.contact, event.time_ns)?;
        let text = format!(
            "contact {} at t = {:.6} s (step {}), relative velocity {:.4} m/s",
            if event.start { "starts" } else { "ends" },
            message.time,
            event.step,
            event.relative_velocity
        );
        let log = LogMessage {
            timestamp: Some(TimeMessage::from_ns(event.time_ns)),
            level: schema::LOG_LEVEL_INFO,
            message: text,
            name: "beam-impact".into(),
            file: String::new(),
            line: 0,
        };
        self.encode(&log);
        self.write_buffer(self.channels.log, event.time_ns)?;
        self.flush()
    }

    fn rollback(&mut self, result: &StepResult) -> Result<()> {
        let log = LogMessage {
            timestamp: Some(TimeMessage::from_ns(result.time_ns)),
            level: schema::LOG_LEVEL_WARNING,
            message: format!(
                "{ROLLBACK_LINE} t = {:.6} s (step {}): the steps recorded after it are superseded",
                result.time, result.step
            ),
            name: "beam-impact".into(),
            file: String::new(),
            line: 0,
        };
        self.encode(&log);
        self.write_buffer(self.channels.log, result.time_ns)?;
        self.flush()
    }

    fn finish(&mut self) -> Result<()> {
        if self.finished {
            return Ok(());
        }
        let started = self.options.timing.then(Instant::now);
        let mut writer = self.writer.take().ok_or_else(|| self.err("the log was never opened"))?;
        self.finished = true;
        writer.finish().map_err(|e| self.err(e))?;
        let mut file = writer.into_inner();
        file.flush().map_err(|source| Error::Io {
            action: "cannot write MCAP log",
            path: self.path.display().to_string(),
            source,
        })?;
        if let Some(t) = started {
            self.timing.write += t.elapsed();
        }
        Ok(())
    }
}
