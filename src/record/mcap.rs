//! The MCAP recorder: every internal step of a run as one protobuf message, readable by
//! Foxglove, by Python's `mcap` package and by [`crate::replay::report`].
//!
//! Channels (all with log_time = publish_time = simulated time in ns since the impact, one time
//! base; for the FMU that is the time since its startTime; after a rollback of an FMU state the
//! time goes back, marked by a `rolled back to` line on `/beam/log`):
//!
//! | topic | schema | what |
//! |---|---|---|
//! | `/beam/model` | `beam_impact.Model` | once at t = 0: scenario, nodes, nodal shape matrix |
//! | `/beam/step` | `beam_impact.Step` | every internal step (or every Nth, see below), step 0 = initial state |
//! | `/beam/modes` | `beam_impact.ModalCoordinates` | modal coordinates: see [`RecorderOptions::modes_interval_ns`] |
//! | `/beam/contact` | `beam_impact.ContactEvent` | contact starts and ends |
//! | `/beam/log` | `foxglove.Log` | the same events as text lines |
//! | `/beam/scene` | `foxglove.SceneUpdate` | both beams, each element coloured by its utilisation, every [`RecorderOptions::scene_interval_ns`] |
//! | `/beam/stations` | `beam_impact.StationStresses` | the stress at every station (issue 30; the stations in `/beam/model`): at the first recorded row of every [`RecorderOptions::stations_interval_ns`], where contact starts or ends, and at the last row |
//!
//! **The stress envelope** (issue 30): the run's [`crate::results::StressEnvelope`] is attached as
//! [`ENVELOPE_ATTACHMENT`] when the log is finished (the CLI's and the FMU's alike: the simulation
//! hands it over through the stations' feed, see [`super::stations`]); `/beam/stations` holds the
//! stresses along both beams, and the run's envelope so far, every 1 ms of simulated time by
//! default (the scene's rate: the stresses at the paper's points, the peaks and the dense output
//! are in every `/beam/step` row; evaluating and compressing some thirty stresses for every row
//! was a third of the writer's time), at the rows where contact starts or ends and at the last
//! row, so that a log without the attachment (a killed run) rebuilds it from its last such row;
//! with `stations_interval_ns` 0 at every recorded row. On a basis so large that the envelope is
//! evaluated every k-th step, only those steps carry stations. The stresses are evaluated on the
//! writer thread from the step's modal coordinates and the static correction's load
//! coefficients; the envelope so far comes from the simulation through the feed.
//!
//! The scenario is also an MCAP Metadata record (`scenario`, flattened dotted keys, with
//! `log_format` = [`LOG_FORMAT`]) and a TOML attachment (`scenario.toml`).
//!
//! **Log format 2** (this one): the modal coordinates left the step message (in format 1 they were
//! 43 single-precision floats in every step, most of the log's bytes and of its compression time)
//! for `/beam/modes`; a step message whose running peaks equal the previous one's leaves them out
//! (they change in few steps; a reader carries them forward), and every step message leaves out
//! `time` (it is `time_ns` / 1e9; the MCAP log time is the same). `/beam/modes` is written at step 0, every [`RecorderOptions::modes_interval_ns`] of simulated
//! time, at the steps where contact starts or ends, at the last step, and at the latest step of
//! each interval at which the arrestor's deflection reached a new peak (so the shape at the peak
//! deflection is in the log; that message is written, and stamped, when its interval ends: its
//! `step` and `time` fields say which step it belongs to). Every step's results stay in
//! `/beam/step`; [`crate::replay::report`] reads both formats.
//!
//! **Threads.** The solver's thread only copies each step's results into a batch; a writer thread
//! owned by the recorder ([`super::writer`]) encodes, compresses and writes them. The queue holds
//! [`QUEUE_BATCHES`] batches of [`BATCH_STEPS`] steps, so memory stays flat and a slow disk holds
//! the solver back. The writer flushes at contact events and every [`RecorderOptions::flush_every`]
//! steps: a killed process loses at most the open chunk, the queue and the batch being gathered,
//! [`UNFLUSHED_STEPS_BOUND`] steps with the defaults. An error of the writer (a full disk) is
//! returned by the recorder's next call.
//!
//! **Decimation** ([`RecorderOptions::record_every`] = N > 1, for long runs): step 0, every Nth
//! step, every step at which a running peak changes, the steps where contact starts or ends and
//! the last step are recorded; the others are not.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{sync_channel, SyncSender};
use std::sync::{Arc, OnceLock};
use std::thread::JoinHandle;
use std::time::Instant;

use ::mcap::{Compression, WriteOptions};

pub use super::log_format::{
    ANSWER_ATTACHMENT, CONTACT_TOPIC, ENVELOPE_ATTACHMENT, LOG_FORMAT, LOG_FORMAT_KEY, LOG_TOPIC, MODEL_TOPIC,
    MODES_TOPIC, MOTION_ATTACHMENT, MOTION_MEDIA_TYPE, ROLLBACK_LINE, SCENARIO_ATTACHMENT, SCENARIO_METADATA,
    SCENE_TOPIC, SIZE_CAP_LINE, STATIONS_TOPIC, STEP_TOPIC,
};
pub use super::options::{
    LogChannels, LogCompression, RecorderOptions, RecorderTiming, DEFAULT_ZSTD_LEVEL, MAX_LOG_BYTES,
};
use super::scene::SceneBuilder;
use super::schema::{self, ModelMessage, StationGroupMessage};
use super::stations::{StationFeed, StationGroup};
use super::writer::{error_chain, Batch, Channels, Item, LogWriter, StartRecord};
pub use super::writer::{BATCH_STEPS, QUEUE_BATCHES};
use super::{Recorder, RunInfo};
use crate::error::{Error, Result};
use crate::results::{ContactEvent, StepResult};

/// Steps a killed process may lose with the default options: the writer's open chunk (a flush
/// every 1000 steps), the queue and the batch the writer is on, and the batch being gathered.
pub const UNFLUSHED_STEPS_BOUND: u64 = 1000 + ((QUEUE_BATCHES + 2) * BATCH_STEPS) as u64;

/// Writes the steps of a run to an MCAP file, on a writer thread of its own.
pub struct McapRecorder {
    path: PathBuf,
    /// The file being written, renamed to `path` when the log is complete (`None`: a device,
    /// written in place).
    partial: Option<PathBuf>,
    options: RecorderOptions,
    queue: Option<SyncSender<Batch>>,
    thread: Option<JoinHandle<Result<RecorderTiming>>>,
    batch: Batch,
    capped: Arc<OnceLock<String>>,
    timing: RecorderTiming,
    finished: bool,
    /// The latest step seen, and whether it was left out by decimation (not yet recorded).
    previous: Option<StepResult>,
    pending: bool,
    /// Modal coordinates of `previous`, and whether they were sent.
    coordinates: Vec<f64>,
    coordinates_sent: bool,
    /// The step (number, time) at which the arrestor's deflection last reached a new peak, with
    /// its modal coordinates, while they wait to be written (at the next modes tick, contact
    /// change or the end: one message per tick, not one per rising step).
    peak: Option<(u64, u64)>,
    peak_coordinates: Vec<f64>,
    /// The run's bridge strain energy at the latest deflection peak (`peak`'s row), J, and as of
    /// the next row ([`Recorder::deflection_peak_strain`]).
    peak_strain: f64,
    next_peak_strain: f64,
    next_scene_ns: u64,
    next_modes_ns: u64,
    /// The next multiple of the sample interval at or after which an internal step's end is
    /// recorded (when no sample came since), ns.
    next_sample_ns: u64,
    has_scene: bool,
    /// The next multiple of the stations' interval at or after which a recorded row carries its
    /// stations' stresses, ns; and the step whose stresses were queued last.
    next_stations_ns: u64,
    stations_step: Option<(u64, u64)>,
    /// The stations' feed (issue 30), held while the run has stations.
    feed: Option<Arc<StationFeed>>,
    /// The stations are evaluated at every this many steps.
    station_stride: u64,
    /// The correction's load coefficients of `previous`, from the feed.
    loads: Option<[f64; crate::solver::static_correction::LOADS]>,
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

impl McapRecorder {
    /// Creates (truncates) the file at `path`; the error names the path.
    pub fn create(path: &Path) -> Result<Self> {
        Self::with_options(path, RecorderOptions::default())
    }

    /// Like [`McapRecorder::create`], with explicit options. The file is created, locked and given
    /// its header and channels here, on the caller's thread; then the writer thread starts.
    pub fn with_options(path: &Path, options: RecorderOptions) -> Result<Self> {
        // The channel filter (`log.channels`): a topic left out is switched off here.
        let options = options.effective();
        let io_error = |action, source| Error::Io { action, path: path.display().to_string(), source };
        let mcap_error =
            |e: ::mcap::McapError| Error::Mcap { path: path.display().to_string(), message: error_chain(&e) };
        // The log is written to `NAME.partial` and renamed to NAME when it is complete (a device
        // such as /dev/null is written in place): a killed run leaves `NAME.partial`, which
        // `report` reads as a log cut short, and never a half-written NAME over an earlier log.
        // The target must not be a link, a FIFO or a folder (checked before anything is written).
        let partial = super::output::partial_for(path).map_err(|e| io_error("cannot create MCAP log", e))?;
        if let Some(partial) = &partial {
            // A leftover at NAME.partial: a link (symbolic, or a hard link to another file) is
            // removed, never written through; a plain file (a killed run's, or the FMU's
            // reservation of a unique name) is taken over below once its lock is free.
            if let Ok(m) = std::fs::symlink_metadata(partial) {
                if m.file_type().is_symlink() || (m.is_file() && super::output::has_other_links(&m)) {
                    std::fs::remove_file(partial).map_err(|e| io_error("cannot create MCAP log", e))?;
                }
            }
        }
        let written = partial.as_deref().unwrap_or(path);
        // Open without truncating, take an exclusive lock, then truncate: two writers given the same
        // path (two FMU instances with the default log.path) get an error, not an interleaved file.
        let file = super::output::open_output(written, options.allow_devices, "cannot create MCAP log")?;
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
        let compression = match options.compression {
            LogCompression::Lz4 => Some(Compression::Lz4),
            LogCompression::Zstd => Some(Compression::Zstd),
            LogCompression::None => None,
        };
        let write_options = WriteOptions::new()
            .profile("beam-impact")
            .compression(compression)
            // The crate hands the level to zstd as an i32: a fast level (-1) goes through as its
            // two's complement (tests/mcap_channels.rs checks that it takes effect).
            .compression_level(options.compression_level.cast_unsigned())
            .compression_threads(0)
            // Every chunk has its own CRC; the data section's CRC covers what lies outside the
            // chunks (the top-level metadata record has no CRC of its own), checked by the
            // readers. Hashing the file once more costs about 1 ms per 10 MB.
            .calculate_data_section_crc(true)
            .chunk_size(Some(options.chunk_size));
        // The size cap counts what the open file holds (its descriptor, not its path: a log renamed
        // mid-run keeps its cap).
        let sized = file.try_clone().map_err(|source| io_error("cannot write MCAP log", source))?;
        let mut writer =
            write_options.create(std::io::BufWriter::with_capacity(128 * 1024, file)).map_err(mcap_error)?;
        let channels = add_channels(&mut writer).map_err(mcap_error)?;
        let capped = Arc::new(OnceLock::new());
        let log_writer = LogWriter::new(path.to_path_buf(), options, writer, sized, channels, Arc::clone(&capped));
        let (queue, receiver) = sync_channel(QUEUE_BATCHES);
        let thread = std::thread::Builder::new()
            .name("beam-impact-mcap".into())
            .spawn(move || log_writer.run(receiver))
            .map_err(|source| io_error("cannot start the MCAP writer thread for", source))?;
        Ok(McapRecorder {
            path: path.to_path_buf(),
            partial,
            options,
            queue: Some(queue),
            thread: Some(thread),
            batch: Batch::new(),
            capped,
            timing: RecorderTiming::default(),
            finished: false,
            previous: None,
            pending: false,
            coordinates: Vec::new(),
            coordinates_sent: false,
            peak: None,
            peak_coordinates: Vec::new(),
            peak_strain: f64::NAN,
            next_peak_strain: f64::NAN,
            next_scene_ns: 0,
            next_modes_ns: 0,
            next_sample_ns: 0,
            has_scene: false,
            next_stations_ns: 0,
            stations_step: None,
            feed: None,
            station_stride: 1,
            loads: None,
        })
    }

    fn err(&self, e: impl std::fmt::Display) -> Error {
        Error::Mcap { path: self.path.display().to_string(), message: e.to_string() }
    }

    /// Hands the gathered batch to the writer thread (waiting while the queue is full). If the
    /// writer stopped at an error, that error.
    fn send(&mut self) -> Result<()> {
        if self.batch.items.is_empty() {
            self.batch.steps = 0;
            return Ok(());
        }
        let batch = std::mem::replace(&mut self.batch, Batch::new());
        let Some(queue) = self.queue.as_ref() else {
            return Err(self.err("the log is already finished"));
        };
        // Two clock reads a batch of 256 steps: always measured.
        let started = Instant::now();
        if queue.send(batch).is_err() {
            // The writer ended early: its error says why.
            self.queue = None;
            return Err(match self.join() {
                Err(e) => e,
                Ok(_) => self.err("the MCAP writer thread ended early"),
            });
        }
        self.timing.queue_wait += started.elapsed();
        Ok(())
    }

    /// Waits for the writer thread and takes what it measured (or its error).
    fn join(&mut self) -> Result<RecorderTiming> {
        match self.thread.take() {
            Some(thread) => thread.join().map_err(|_| self.err("the MCAP writer thread panicked"))?,
            None => Err(self.err("the log is already finished")),
        }
    }

    /// A row for `/beam/step`: an internal step's end (`sample` false: recorded or left out by
    /// the decimation rule, see the module's documentation) or a sample of the dense output
    /// (always recorded); the scene's and the modes' ticks follow either.
    fn observe(&mut self, result: &StepResult, modal_coordinates: &[f64], sample: bool) -> Result<()> {
        if self.finished {
            return Err(self.err("the log is already finished"));
        }
        if self.capped.get().is_some() {
            return Ok(());
        }
        let (peaks_changed, stage_changed, deflection_peak) = match &self.previous {
            None => (true, true, true),
            Some(p) => (
                p.peaks != result.peaks,
                p.contact != result.contact,
                p.peaks.lower_tip_deflection != result.peaks.lower_tip_deflection,
            ),
        };
        let interval = self.options.sample_interval_ns;
        let regular = self.regular(result, sample);
        if let (Some(ticks), true) = (result.time_ns.checked_div(interval), regular) {
            self.next_sample_ns = ticks.saturating_add(1).saturating_mul(interval);
        }
        let keep = peaks_changed || stage_changed || regular;
        self.previous = Some(*result);
        self.coordinates.clear();
        self.coordinates.extend_from_slice(modal_coordinates);
        self.coordinates_sent = false;
        self.pending = !keep;
        if let Some(feed) = &self.feed {
            self.loads = feed.loads();
        }
        if keep {
            self.push(Item::Step(*result, sample));
            self.push_stations(result, false);
        }
        if deflection_peak && self.options.modal_coordinates {
            self.peak = Some((result.step, result.time_ns));
            self.peak_coordinates.clear();
            self.peak_coordinates.extend_from_slice(modal_coordinates);
            self.peak_strain = self.next_peak_strain;
        }
        let scene = self.has_scene && result.time_ns >= self.next_scene_ns;
        if scene {
            let interval = self.options.scene_interval_ns;
            self.next_scene_ns = (result.time_ns / interval + 1) * interval;
        }
        let mut modes = stage_changed;
        if self.options.modes_interval_ns > 0 && result.time_ns >= self.next_modes_ns {
            let interval = self.options.modes_interval_ns;
            self.next_modes_ns = (result.time_ns / interval + 1) * interval;
            modes = true;
        }
        let log = modes && self.options.modal_coordinates;
        if log || scene {
            self.push_modes(log, scene);
        }
        if log {
            // The peak's shape from an earlier step of this tick.
            self.push_peak();
        }
        self.batch.steps += 1;
        if self.batch.steps >= BATCH_STEPS {
            self.send()?;
        }
        Ok(())
    }

    /// Whether `result` is a row by the clock: a sample of the dense output, the first step end
    /// at or after a multiple of the sample interval, or (interval 0) every `record_every`-th step.
    fn regular(&self, result: &StepResult, sample: bool) -> bool {
        match self.options.sample_interval_ns {
            0 => result.step.is_multiple_of(self.options.record_every.max(1)),
            _ => sample || result.time_ns >= self.next_sample_ns,
        }
    }

    fn push(&mut self, item: Item) {
        self.batch.items.push(item);
    }

    /// Queues the modal coordinates of `previous` (held in `self.coordinates`); when it is the
    /// latest deflection peak's row (its step and time: a step's samples share its number), they
    /// are the peak's, with its strain energy.
    fn push_modes(&mut self, log: bool, scene: bool) {
        let Some(r) = self.previous else { return };
        let at_peak = log && self.peak == Some((r.step, r.time_ns));
        let strain = at_peak.then_some(self.peak_strain);
        self.batch.push_modes(&self.coordinates, r.step, r.time_ns, r.time_ns, log, scene, self.loads, strain);
        self.coordinates_sent |= log;
        if at_peak {
            self.peak = None;
        }
    }

    /// Queues the modal coordinates at the latest peak of the arrestor's deflection, if they
    /// are still owed.
    fn push_peak(&mut self) {
        if let Some((step, time_ns)) = self.peak.take() {
            // Written now, stamped now: log times never decrease; the message says its step.
            let log_time_ns = self.previous.map_or(time_ns, |p| p.time_ns.max(time_ns));
            let strain = Some(self.peak_strain);
            self.batch.push_modes(&self.peak_coordinates, step, time_ns, log_time_ns, true, false, None, strain);
            if self.previous.is_some_and(|p| (p.step, p.time_ns) == (step, time_ns)) {
                self.coordinates_sent = true;
            }
        }
    }

    /// Records the latest step if decimation left it out, with its modal coordinates, and the
    /// coordinates of the latest deflection peak.
    fn record_pending(&mut self) {
        if let (true, Some(r)) = (self.pending, self.previous) {
            self.push(Item::Step(r, false));
            self.pending = false;
        }
        if let Some(r) = self.previous {
            self.push_stations(&r, true);
        }
        self.push_peak();
        if !self.coordinates_sent && self.options.modal_coordinates {
            self.push_modes(true, false);
        }
    }

    /// Queues the stations' stresses of the recorded step `r` (its coordinates in
    /// `self.coordinates`), if the run has stations evaluated at that step, the log keeps them, and
    /// the row is the first at or after a multiple of [`RecorderOptions::stations_interval_ns`]
    /// (every recorded row with 0) or `always` (the rows where contact starts or ends, the last).
    fn push_stations(&mut self, r: &StepResult, always: bool) {
        if self.feed.is_none() || !self.options.station_stresses || !r.step.is_multiple_of(self.station_stride) {
            return;
        }
        if self.stations_step == Some((r.step, r.time_ns)) {
            return;
        }
        let interval = self.options.stations_interval_ns;
        let due = interval == 0 || r.time_ns >= self.next_stations_ns;
        if !(due || always) {
            return;
        }
        if let (Some(ticks), true) = (r.time_ns.checked_div(interval), due) {
            self.next_stations_ns = ticks.saturating_add(1).saturating_mul(interval);
        }
        self.stations_step = Some((r.step, r.time_ns));
        let feed = self.feed.as_deref();
        self.batch.push_stations(&self.coordinates, r.step, r.time_ns, self.loads, |out| {
            if let Some(feed) = feed {
                feed.append_maxima(out);
            }
        });
    }

    /// Why the log stopped before the run's end (it reached its size cap), if it did.
    pub fn capped(&self) -> Option<&str> {
        self.capped.get().map(String::as_str)
    }

    /// The file being written now: `NAME.partial` until the log is finished, then NAME.
    pub fn file_being_written(&self) -> &Path {
        self.partial.as_deref().unwrap_or(&self.path)
    }

    /// Adds an attachment (the FMU's modelDescription.xml, for example).
    pub fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        if self.finished {
            return Err(self.err("the log is already finished"));
        }
        self.push(Item::Attach { name: name.into(), media_type: media_type.into(), data: data.to_vec() });
        Ok(())
    }

    /// The file being written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The options in use.
    pub fn options(&self) -> &RecorderOptions {
        &self.options
    }

    /// Time spent encoding and writing (see [`RecorderTiming`]; the writer thread's share is
    /// known once [`Recorder::finish`] returned).
    pub fn timing(&self) -> RecorderTiming {
        self.timing
    }
}

/// Adds the log's schemas and channels (the same for every log).
fn add_channels<W: std::io::Write + std::io::Seek>(w: &mut ::mcap::Writer<W>) -> ::mcap::McapResult<Channels> {
    let beam = schema::beam_impact_descriptor();
    let none = BTreeMap::new();
    let step_schema = w.add_schema(schema::STEP_SCHEMA, "protobuf", &beam)?;
    let contact_schema = w.add_schema(schema::CONTACT_SCHEMA, "protobuf", &beam)?;
    let model_schema = w.add_schema(schema::MODEL_SCHEMA, "protobuf", &beam)?;
    let modes_schema = w.add_schema(schema::MODES_SCHEMA, "protobuf", &beam)?;
    let scene_schema = w.add_schema(schema::SCENE_SCHEMA, "protobuf", &schema::scene_update_descriptor())?;
    let log_schema = w.add_schema(schema::LOG_SCHEMA, "protobuf", &schema::log_descriptor())?;
    let stations_schema = w.add_schema(schema::STATIONS_SCHEMA, "protobuf", &beam)?;
    Ok(Channels {
        model: w.add_channel(model_schema, MODEL_TOPIC, "protobuf", &none)?,
        step: w.add_channel(step_schema, STEP_TOPIC, "protobuf", &none)?,
        contact: w.add_channel(contact_schema, CONTACT_TOPIC, "protobuf", &none)?,
        log: w.add_channel(log_schema, LOG_TOPIC, "protobuf", &none)?,
        scene: w.add_channel(scene_schema, SCENE_TOPIC, "protobuf", &none)?,
        modes: w.add_channel(modes_schema, MODES_TOPIC, "protobuf", &none)?,
        stations: w.add_channel(stations_schema, STATIONS_TOPIC, "protobuf", &none)?,
    })
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
        let group = |g: &StationGroup| {
            Some(StationGroupMessage {
                positions: g.positions.clone(),
                allowable: g.allowable.clone(),
                nodes: g.nodes.clone(),
            })
        };
        let layout = info.stations.map(|p| &p.layout);
        let model = ModelMessage {
            scenario_toml: toml.clone(),
            lower_nodes: info.lower_nodes.to_vec(),
            upper_nodes: info.upper_nodes.to_vec(),
            shape_rows: shapes.nrows() as u32,
            shape_cols: shapes.ncols() as u32,
            nodal_shapes: (0..shapes.nrows()).flat_map(|r| (0..shapes.ncols()).map(move |c| shapes[(r, c)])).collect(),
            lower_bending_stations: layout.and_then(|l| group(&l.lower_bending)),
            lower_shear_stations: layout.and_then(|l| group(&l.lower_shear)),
            upper_bending_stations: layout.and_then(|l| group(&l.upper_bending)),
            upper_shear_stations: layout.and_then(|l| group(&l.upper_shear)),
            stations_sampled_every: layout.map_or(0, |l| l.sampled_every),
        };
        self.feed = info.stations.map(|p| Arc::clone(&p.feed));
        self.station_stride = layout.map_or(1, |l| l.sampled_every.max(1));
        self.loads = None;
        let mut metadata = flatten_toml(&toml);
        metadata.insert("paper".into(), info.scenario.is_paper().to_string());
        metadata.insert("beam_impact_version".into(), env!("CARGO_PKG_VERSION").into());
        metadata.insert(LOG_FORMAT_KEY.into(), LOG_FORMAT.to_string());
        // A sea's RAO file by its hash (issue 42); its seed and sea state are among the fields.
        if let Some(sea) = &info.scenario.sea {
            metadata.insert("sea.raos_sha256".into(), sea.rao_sha256.clone());
        }
        self.has_scene = self.options.scene_interval_ns > 0;
        let scene = self.has_scene.then(|| SceneBuilder::new(info));
        let stations = info.stations.map(|p| (p.layout.clone(), Arc::clone(&p.rows)));
        self.push(Item::Start(Box::new(StartRecord { model, metadata, scenario_toml: toml, scene, stations })));
        // The motion table travels with the log, so that it replays without the file (issue 27).
        // A sea's record too (issue 42): the log replays without the RAO file.
        if let Ok(Some((table, _))) = info.scenario.motion_source() {
            self.push(Item::Attach {
                name: MOTION_ATTACHMENT.into(),
                media_type: MOTION_MEDIA_TYPE.into(),
                data: table.to_csv().into_bytes(),
            });
        }
        self.next_scene_ns = 0;
        self.next_modes_ns = 0;
        self.next_sample_ns = 0;
        self.previous = None;
        self.pending = false;
        Ok(())
    }

    fn sample_interval_ns(&self) -> u64 {
        self.options.sample_interval_ns
    }

    fn keeps(&self, result: &StepResult) -> bool {
        if self.finished || self.capped.get().is_some() {
            return false;
        }
        let Some(p) = &self.previous else { return true };
        p.peaks != result.peaks
            || p.contact != result.contact
            || self.regular(result, false)
            || (self.has_scene && result.time_ns >= self.next_scene_ns)
            || (self.options.modes_interval_ns > 0 && result.time_ns >= self.next_modes_ns)
    }

    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.observe(result, modal_coordinates, true)
    }

    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.observe(result, modal_coordinates, false)
    }

    fn deflection_peak_strain(&mut self, upper_strain: f64) -> Result<()> {
        self.next_peak_strain = upper_strain;
        Ok(())
    }

    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        McapRecorder::attach(self, name, media_type, data)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.capped()
    }

    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        if self.finished {
            return Err(self.err("the log is already finished"));
        }
        if self.capped.get().is_some() {
            return Ok(());
        }
        // The step the event follows is recorded, whatever the decimation.
        self.record_pending();
        self.push(Item::Contact(*event));
        // The writer flushes at events; hand it what it has so the event reaches the file.
        self.send()
    }

    fn rollback(&mut self, result: &StepResult) -> Result<()> {
        // A step left out by decimation is recorded if it is the one restored; the later ones
        // are superseded anyway.
        if self.previous.is_some_and(|p| p.step == result.step) {
            self.record_pending();
        }
        if self.peak.is_some_and(|(step, _)| step <= result.step) {
            self.push_peak();
        }
        self.peak = None;
        self.push(Item::Rollback(*result));
        // The dense output goes on from the restored time.
        let interval = self.options.sample_interval_ns;
        if let Some(ticks) = result.time_ns.checked_div(interval) {
            self.next_sample_ns = ticks.saturating_add(1).saturating_mul(interval);
        }
        // The stations likewise; the restored step's are in the log already or superseded.
        let interval = self.options.stations_interval_ns;
        if let Some(ticks) = result.time_ns.checked_div(interval) {
            self.next_stations_ns = ticks.saturating_add(1).saturating_mul(interval);
        }
        self.stations_step = Some((result.step, result.time_ns));
        self.previous = Some(*result);
        self.pending = false;
        // The restored step's coordinates are not known here: none are owed for it.
        self.coordinates_sent = true;
        self.send()
    }

    fn finish(&mut self) -> Result<()> {
        if self.finished {
            return Ok(());
        }
        self.finished = true;
        // The last step is always recorded, with its modal coordinates; then the run's envelope.
        let mut encoded = Ok(());
        if self.capped.get().is_none() {
            self.record_pending();
            if let Some(envelope) = self.feed.as_ref().and_then(|f| f.envelope()) {
                match serde_json::to_vec(&envelope) {
                    Ok(data) => self.push(Item::Attach {
                        name: ENVELOPE_ATTACHMENT.into(),
                        media_type: "application/json".into(),
                        data,
                    }),
                    Err(e) => encoded = Err(self.err(format!("cannot encode {ENVELOPE_ATTACHMENT}: {e}"))),
                }
            }
        }
        let sent = self.send().and(encoded);
        // Closing the queue ends the writer thread, which then writes the summary and footer.
        self.queue = None;
        let joined = self.join();
        // A finished log takes its name; one that failed on the way (a full disk) stays
        // NAME.partial, as a killed run's does, and an earlier NAME is left as it was.
        if let Some(partial) = self.partial.take().filter(|_| sent.is_ok() && joined.is_ok()) {
            std::fs::rename(&partial, &self.path).map_err(|source| Error::Io {
                action: "cannot rename the finished MCAP log to",
                path: self.path.display().to_string(),
                source,
            })?;
        }
        sent?;
        let writer = joined?;
        self.timing = RecorderTiming { queue_wait: self.timing.queue_wait, ..writer };
        Ok(())
    }
}

impl Drop for McapRecorder {
    /// A recorder dropped unfinished (an FMU freed without Terminate, an error on the way) still
    /// ends its thread and completes the file: nothing keeps running after the owner is gone.
    fn drop(&mut self) {
        if !self.finished {
            let _ = self.finish();
        }
    }
}
