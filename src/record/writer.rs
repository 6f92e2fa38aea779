//! The MCAP recorder's writer thread: encodes the batches the solver's thread hands over
//! (protobuf), and writes them (chunking, compression, CRCs, file writes, flushes, size cap).
//!
//! The thread owns the `mcap::Writer`; [`super::mcap::McapRecorder`] owns the thread. The queue
//! between them is bounded ([`QUEUE_BATCHES`] batches of [`BATCH_STEPS`] steps), so memory stays
//! flat and a slow disk holds the solver back instead of piling up steps. The thread ends when
//! the recorder drops its end of the queue: it then writes the summary and footer and returns
//! what it measured, or the first error, which the recorder reports at its next call.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::mpsc::Receiver;
use std::sync::{Arc, OnceLock};
use std::time::Instant;

use ::mcap::records::{MessageHeader, Metadata};
use ::mcap::{Attachment, Writer};
use prost::Message;

use super::log_format::{ROLLBACK_LINE, SCENARIO_ATTACHMENT, SCENARIO_METADATA, SIZE_CAP_LINE};
use super::options::{RecorderOptions, RecorderTiming};
use super::scene::SceneBuilder;
use super::schema::{
    self, ContactEventMessage, LogMessage, ModalCoordinatesMessage, ModelMessage, StationStressesMessage, TimeMessage,
};
use super::stations::StationLayout;
use crate::error::{Error, Result};
use crate::results::{ContactEvent, StepResult};
use crate::solver::envelope::StationRows;
use crate::solver::static_correction::LOADS;

/// Steps the solver's thread gathers before it hands a batch to the writer.
pub const BATCH_STEPS: usize = 256;
/// Batches the queue holds before the solver's thread waits for the writer.
pub const QUEUE_BATCHES: usize = 4;

/// An error with its causes, one line: the mcap crate's I/O error says "I/O error from writing"
/// and keeps the reason ("No space left on device") as its source.
pub(super) fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        let cause_text = cause.to_string();
        if !text.contains(&cause_text) {
            text = format!("{text}: {cause_text}");
        }
        source = cause.source();
    }
    text
}

/// Adds the time since `started` to `total` (when the recorder clocks its messages).
fn lap(started: Option<Instant>, total: &mut std::time::Duration) {
    if let Some(t) = started {
        *total += t.elapsed();
    }
}

/// Encodes `message` into the cleared `buffer`. Encoding into a Vec cannot fail: it grows.
fn encode_into(buffer: &mut Vec<u8>, message: &impl Message) {
    buffer.clear();
    message.encode(buffer).expect("encoding into a Vec cannot run out of space");
}

/// What the recorder writes once, at the start of a run.
#[derive(Debug)]
pub(super) struct StartRecord {
    pub model: ModelMessage,
    pub metadata: BTreeMap<String, String>,
    pub scenario_toml: String,
    pub scene: Option<SceneBuilder>,
    /// The stress stations, evaluated here (off the solver's thread) for the recorded steps and
    /// the scene's colours.
    pub stations: Option<(StationLayout, std::sync::Arc<StationRows>)>,
}

/// One thing to write, in order.
#[derive(Debug)]
pub(super) enum Item {
    Start(Box<StartRecord>),
    /// A row of `/beam/step`: an internal step's end, or (true) a sample of the dense output.
    Step(StepResult, bool),
    /// The modal coordinates `batch.coordinates[offset..offset + len]` of `step` at `time_ns`:
    /// logged on the modes topic at log time `log_time_ns` (`log`; later than `time_ns` for a
    /// peak's coordinates written at the end of their interval, so log times never decrease)
    /// and/or drawn as a scene (`scene`, coloured by the stations' utilisation under the
    /// correction's `loads`); at a row that raised the arrestor's deflection peak, with the run's
    /// bridge strain energy there (`strain`, J).
    Modes {
        step: u64,
        time_ns: u64,
        log_time_ns: u64,
        offset: usize,
        len: usize,
        log: bool,
        scene: bool,
        loads: Option<[f64; LOADS]>,
        strain: Option<f64>,
    },
    /// The stresses at every station of `step` at `time_ns`, from the modal coordinates
    /// `batch.coordinates[offset..offset + len]` and the correction's `loads` (`/beam/stations`).
    Stations {
        step: u64,
        time_ns: u64,
        offset: usize,
        len: usize,
        loads: Option<[f64; LOADS]>,
        /// The run's envelope so far, after the coordinates (0: none).
        maxima: usize,
    },
    Contact(ContactEvent),
    Rollback(StepResult),
    Attach {
        name: String,
        media_type: String,
        data: Vec<u8>,
    },
}

/// What the solver's thread hands over at once.
#[derive(Debug, Default)]
pub(super) struct Batch {
    pub items: Vec<Item>,
    pub coordinates: Vec<f64>,
    /// Steps seen (recorded or decimated) since the batch began.
    pub steps: usize,
}

impl Batch {
    pub fn new() -> Self {
        Batch { items: Vec::with_capacity(BATCH_STEPS + 16), coordinates: Vec::new(), steps: 0 }
    }

    /// Queues the modal coordinates `q` of `step` (see [`Item::Modes`]).
    #[allow(clippy::too_many_arguments)]
    pub fn push_modes(
        &mut self,
        q: &[f64],
        step: u64,
        time_ns: u64,
        log_time_ns: u64,
        log: bool,
        scene: bool,
        loads: Option<[f64; LOADS]>,
        strain: Option<f64>,
    ) {
        let offset = self.coordinates.len();
        let len = q.len();
        self.coordinates.extend_from_slice(q);
        self.items.push(Item::Modes { step, time_ns, log_time_ns, offset, len, log, scene, loads, strain });
    }

    /// Queues the stations' stresses of `step` from its modal coordinates `q` (see [`Item::Stations`]).
    /// `maxima` appends the run's envelope so far after the coordinates (nothing: none given).
    pub fn push_stations(
        &mut self,
        q: &[f64],
        step: u64,
        time_ns: u64,
        loads: Option<[f64; LOADS]>,
        maxima: impl FnOnce(&mut Vec<f64>),
    ) {
        let offset = self.coordinates.len();
        self.coordinates.extend_from_slice(q);
        maxima(&mut self.coordinates);
        let maxima = self.coordinates.len() - offset - q.len();
        self.items.push(Item::Stations { step, time_ns, offset, len: q.len(), loads, maxima });
    }
}

/// Channel ids of the log's topics.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Channels {
    pub model: u16,
    pub step: u16,
    pub contact: u16,
    pub log: u16,
    pub scene: u16,
    pub modes: u16,
    pub stations: u16,
}

/// The writer thread's state.
pub(super) struct LogWriter {
    pub path: PathBuf,
    pub options: RecorderOptions,
    pub writer: Writer<BufWriter<File>>,
    /// The same open file (a second descriptor): its size is what the cap counts.
    sized: File,
    pub channels: Channels,
    /// Per-channel sequence numbers, indexed like [`LogWriter::sequence_slot`].
    sequences: [u32; 7],
    /// The running peaks of the latest step message: a step whose peaks are the same leaves them
    /// out (log format 2; the reader carries them forward).
    peaks: Option<crate::results::Peaks>,
    modes: ModalCoordinatesMessage,
    buffer: Vec<u8>,
    scene: Option<SceneBuilder>,
    stations: Option<(StationLayout, std::sync::Arc<StationRows>)>,
    /// The latest stresses evaluated (every station, signed, Pa) and their step.
    station_values: Vec<f64>,
    station_step: Option<(u64, u64)>,
    station_message: StationStressesMessage,
    steps_since_flush: u64,
    timing: RecorderTiming,
    /// Set once when the log reaches its size cap; read by the recorder.
    capped: Arc<OnceLock<String>>,
    last_time_ns: u64,
}

impl LogWriter {
    pub fn new(
        path: PathBuf,
        options: RecorderOptions,
        writer: Writer<BufWriter<File>>,
        sized: File,
        channels: Channels,
        capped: Arc<OnceLock<String>>,
    ) -> Self {
        LogWriter {
            path,
            options,
            writer,
            sized,
            channels,
            sequences: [0; 7],
            peaks: None,
            modes: ModalCoordinatesMessage::default(),
            buffer: Vec::with_capacity(4096),
            scene: None,
            stations: None,
            station_values: Vec::new(),
            station_step: None,
            station_message: StationStressesMessage::default(),
            steps_since_flush: 0,
            timing: RecorderTiming::default(),
            capped,
            last_time_ns: 0,
        }
    }

    /// The thread's body: writes every batch until the queue closes, then finishes the file.
    pub fn run(mut self, queue: Receiver<Batch>) -> Result<RecorderTiming> {
        // Two clock reads a run: always measured.
        let cpu = cpu_time::ThreadTime::now();
        for batch in queue {
            self.write_batch(&batch)?;
        }
        let mut timing = self.finish()?;
        timing.writer_cpu = cpu.elapsed();
        Ok(timing)
    }

    fn err(&self, e: ::mcap::McapError) -> Error {
        Error::Mcap { path: self.path.display().to_string(), message: error_chain(&e) }
    }

    fn sequence_slot(&self, channel: u16) -> usize {
        let c = &self.channels;
        match channel {
            x if x == c.model => 0,
            x if x == c.step => 1,
            x if x == c.contact => 2,
            x if x == c.log => 3,
            x if x == c.scene => 4,
            x if x == c.modes => 5,
            _ => 6,
        }
    }

    fn write_batch(&mut self, batch: &Batch) -> Result<()> {
        for item in &batch.items {
            // A log at its cap keeps nothing more (the run goes on; the recorder says why).
            if self.capped.get().is_some() {
                return Ok(());
            }
            match item {
                Item::Start(start) => self.start(start)?,
                &Item::Step(ref result, sample) => self.write_step(result, sample)?,
                &Item::Modes { step, time_ns, log_time_ns, offset, len, log, scene, loads, strain } => {
                    let q = &batch.coordinates[offset..offset + len];
                    self.write_modes((step, time_ns, log_time_ns), q, strain, log, scene.then_some(loads))?;
                }
                &Item::Stations { step, time_ns, offset, len, loads, maxima } => {
                    let q = &batch.coordinates[offset..offset + len];
                    let maxima = &batch.coordinates[offset + len..offset + len + maxima];
                    self.write_stations(step, time_ns, q, loads, maxima)?;
                }
                Item::Contact(event) => self.contact(event)?,
                Item::Rollback(result) => self.rollback(result)?,
                Item::Attach { name, media_type, data } => self.attach(name, media_type, data)?,
            }
        }
        Ok(())
    }

    /// Writes the encoded `self.buffer` on `channel` at `time_ns`.
    fn write_buffer(&mut self, channel: u16, time_ns: u64) -> Result<()> {
        let slot = self.sequence_slot(channel);
        let header = MessageHeader {
            channel_id: channel,
            sequence: self.sequences[slot],
            log_time: time_ns,
            publish_time: time_ns,
        };
        self.sequences[slot] = self.sequences[slot].wrapping_add(1);
        let started = self.options.timing.then(Instant::now);
        let result = self.writer.write_to_known_channel(&header, &self.buffer);
        result.map_err(|e| self.err(e))?;
        lap(started, &mut self.timing.write);
        self.timing.messages += 1;
        Ok(())
    }

    fn encode(&mut self, message: &impl Message) {
        let started = self.options.timing.then(Instant::now);
        encode_into(&mut self.buffer, message);
        lap(started, &mut self.timing.encode);
    }

    fn start(&mut self, start: &StartRecord) -> Result<()> {
        self.encode(&start.model);
        self.write_buffer(self.channels.model, 0)?;
        let metadata = Metadata { name: SCENARIO_METADATA.into(), metadata: start.metadata.clone() };
        let result = self.writer.write_metadata(&metadata);
        result.map_err(|e| self.err(e))?;
        self.attach(SCENARIO_ATTACHMENT, "application/toml", start.scenario_toml.as_bytes())?;
        self.scene = start.scene.clone();
        self.stations = start.stations.clone();
        self.station_values = vec![0.0; self.stations.as_ref().map_or(0, |(layout, _)| layout.len())];
        self.station_step = None;
        Ok(())
    }

    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        let attachment = Attachment {
            log_time: 0,
            create_time: 0,
            name: name.to_string(),
            media_type: media_type.to_string(),
            data: std::borrow::Cow::Borrowed(data),
        };
        let result = self.writer.attach(&attachment);
        result.map_err(|e| self.err(e))
    }

    fn write_step(&mut self, result: &StepResult, sample: bool) -> Result<()> {
        self.last_time_ns = result.time_ns;
        let started = self.options.timing.then(Instant::now);
        // Format 2: no `time` (it is time_ns / 1e9), and no peaks when they are the previous
        // step message's.
        let with_peaks = self.peaks != Some(result.peaks);
        self.peaks = Some(result.peaks);
        super::step_encoding::encode_step(&mut self.buffer, result, with_peaks, sample);
        lap(started, &mut self.timing.encode);
        self.write_buffer(self.channels.step, result.time_ns)?;
        self.steps_since_flush += 1;
        if self.steps_since_flush >= self.options.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    /// Evaluates every station's stress at `step` from `q` and `loads` into `station_values`
    /// (once per step: the stations message and the scene of one step share it). False without
    /// stations.
    fn evaluate_stations(&mut self, (step, time_ns): (u64, u64), q: &[f64], loads: Option<[f64; LOADS]>) -> bool {
        let Some((_, rows)) = &self.stations else { return false };
        if self.station_step != Some((step, time_ns)) {
            let started = self.options.timing.then(Instant::now);
            rows.stresses(q, loads.as_ref(), &mut self.station_values);
            lap(started, &mut self.timing.encode);
            self.station_step = Some((step, time_ns));
        }
        true
    }

    /// Writes the stresses at every station of `step` (`/beam/stations`).
    fn write_stations(
        &mut self,
        step: u64,
        time_ns: u64,
        q: &[f64],
        loads: Option<[f64; LOADS]>,
        maxima: &[f64],
    ) -> Result<()> {
        if !self.evaluate_stations((step, time_ns), q, loads) {
            return Ok(());
        }
        let Some((layout, _)) = &self.stations else { return Ok(()) };
        let Some(groups) = super::stations::split(layout, &self.station_values) else { return Ok(()) };
        let started = self.options.timing.then(Instant::now);
        let m = &mut self.station_message;
        m.step = step;
        m.time_ns = time_ns;
        for (field, values) in
            [&mut m.lower_bending, &mut m.lower_shear, &mut m.upper_bending, &mut m.upper_shear].into_iter().zip(groups)
        {
            field.clear();
            field.extend(values.iter().map(|&v| v as f32));
        }
        // The running envelope, one value per station (a feed that gave none, or another count:
        // left out).
        m.envelope.clear();
        m.envelope_time.clear();
        let width = self.station_values.len();
        if maxima.len() == 2 * width {
            m.envelope.extend(maxima[..width].iter().map(|&v| v as f32));
            m.envelope_time.extend(maxima[width..].iter().map(|&v| v as f32));
        }
        encode_into(&mut self.buffer, &self.station_message);
        lap(started, &mut self.timing.encode);
        self.write_buffer(self.channels.stations, time_ns)
    }

    /// Writes the modal coordinates `q` of `step` at `time_ns` (`log`, at `log_time_ns`, with the
    /// bridge's `strain` at a deflection peak) and/or the scene of them (`scene`: Some with the
    /// correction's loads, from which the stations' utilisation colours follow).
    fn write_modes(
        &mut self,
        (step, time_ns, log_time_ns): (u64, u64, u64),
        q: &[f64],
        strain: Option<f64>,
        log: bool,
        scene: Option<Option<[f64; LOADS]>>,
    ) -> Result<()> {
        if log {
            self.modes.step = step;
            self.modes.time_ns = time_ns;
            self.modes.time = crate::results::seconds(time_ns);
            self.modes.coordinates.clear();
            self.modes.coordinates.extend_from_slice(q);
            self.modes.upper_strain_at_peak = strain;
            let started = self.options.timing.then(Instant::now);
            encode_into(&mut self.buffer, &self.modes);
            lap(started, &mut self.timing.encode);
            self.write_buffer(self.channels.modes, log_time_ns)?;
        }
        if let (Some(loads), true) = (scene, self.scene.is_some()) {
            let stresses = self.evaluate_stations((step, time_ns), q, loads);
            if let Some(builder) = self.scene.as_mut() {
                let started = self.options.timing.then(Instant::now);
                let stresses = stresses.then_some(self.station_values.as_slice());
                encode_into(&mut self.buffer, builder.update(time_ns, q, stresses));
                lap(started, &mut self.timing.encode);
                self.write_buffer(self.channels.scene, time_ns)?;
            }
        }
        Ok(())
    }

    fn log_line(&mut self, time_ns: u64, level: i32, message: String) -> Result<()> {
        let log = LogMessage {
            timestamp: Some(TimeMessage::from_ns(time_ns)),
            level,
            message,
            name: "beam-impact".into(),
            file: String::new(),
            line: 0,
        };
        self.encode(&log);
        self.write_buffer(self.channels.log, time_ns)
    }

    fn contact(&mut self, event: &ContactEvent) -> Result<()> {
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
        self.log_line(event.time_ns, schema::LOG_LEVEL_INFO, text)?;
        self.flush()
    }

    fn rollback(&mut self, result: &StepResult) -> Result<()> {
        let text = format!(
            "{ROLLBACK_LINE} t = {:.6} s (step {}): the steps recorded after it are superseded",
            result.time, result.step
        );
        self.log_line(result.time_ns, schema::LOG_LEVEL_WARNING, text)?;
        // The next step message carries its peaks in full; a step number may come again.
        self.peaks = None;
        self.station_step = None;
        self.flush()
    }

    /// Closes the open chunk and hands it to the OS; stops the log at its size cap.
    fn flush(&mut self) -> Result<()> {
        let started = self.options.timing.then(Instant::now);
        let result = self.writer.flush();
        result.map_err(|e| self.err(e))?;
        lap(started, &mut self.timing.write);
        self.steps_since_flush = 0;
        let written = self.sized.metadata().map_or(0, |m| m.len());
        if self.capped.get().is_none() && written >= self.options.max_bytes {
            let reason = format!(
                "the MCAP log {} {SIZE_CAP_LINE} of {} bytes at {written} bytes: it ends here, the run goes on \
                 unrecorded",
                self.path.display(),
                self.options.max_bytes
            );
            // The log itself says why it ends early.
            self.log_line(self.last_time_ns, schema::LOG_LEVEL_WARNING, reason.clone())?;
            let _ = self.capped.set(reason);
        }
        Ok(())
    }

    fn finish(mut self) -> Result<RecorderTiming> {
        let started = self.options.timing.then(Instant::now);
        self.writer.finish().map_err(|e| self.err(e))?;
        let path = self.path.display().to_string();
        let mut timing = self.timing;
        let mut file = self.writer.into_inner();
        file.flush().map_err(|source| Error::Io { action: "cannot write MCAP log", path, source })?;
        lap(started, &mut timing.write);
        Ok(timing)
    }
}
