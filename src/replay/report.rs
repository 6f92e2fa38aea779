//! `beam-impact report`: reads a log written by [`crate::record::mcap::McapRecorder`], rebuilds the run's
//! [`Summary`] from it and writes Figures 6-9 and the mode shapes of Figures 10-12.
//!
//! The log is read linearly, chunk by chunk, with chunk CRCs checked, so a file cut short by a
//! killed process still yields every complete chunk; the report then says that it was cut short
//! and reports what it holds. The modes and the energy approach are recomputed from the scenario
//! stored in the log (they are functions of it); everything else comes from the messages.
//!
//! Nothing in a log is trusted (issue 9): the bytes are framed by [`super::safe_read`], which
//! checks every length before allocating or decompressing; what is kept is bounded by
//! [`RETAINED_RATIO`] times the file; a rollback drops the superseded tail of the steps in
//! time linear in the log; the stored scenario is validated (its limits bound the model) before
//! a model is built from it; values the figures cannot scale are reported instead of drawn.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

use prost::Message;

use super::safe_read::{read_records, Ending, Limits, Place, Record};
use crate::error::{Error, Result};
use crate::model::motion_table::MotionTable;
use crate::model::Scenario;
use crate::record::mcap::{
    ANSWER_ATTACHMENT, CONTACT_TOPIC, ENVELOPE_ATTACHMENT, LOG_FORMAT, LOG_FORMAT_KEY, LOG_TOPIC, MODEL_TOPIC,
    MODES_TOPIC, MOTION_ATTACHMENT, SCENARIO_ATTACHMENT, SCENARIO_METADATA, STATIONS_TOPIC, STEP_TOPIC,
};
use crate::record::schema::{
    ContactEventMessage, LogMessage, ModalCoordinatesMessage, ModelMessage, StationGroupMessage,
    StationStressesMessage, StepMessage,
};
use crate::record::stations::{StationGroup, StationLayout};
use crate::results::{
    seconds, ContactEvent, ContactWindow, FirstContact, Peaks, Quality, StationEnvelope, StepResult, StressEnvelope,
    Summary, TimeSteps,
};
use crate::simulation::Simulation;

/// Everything a log holds, decoded.
#[derive(Clone, Debug, Default)]
pub struct LogData {
    /// The scenario's TOML (from the attachment, else from the model message).
    pub scenario_toml: Option<String>,
    /// The scenario's Metadata record, flattened keys.
    pub metadata: BTreeMap<String, String>,
    /// The one-off model message (nodes and nodal shapes).
    pub model: Option<ModelMessage>,
    /// Every step, in order.
    pub steps: Vec<StepResult>,
    /// Whether each of `steps` is a sample of the dense output inside its step (issue 41), not
    /// a step's end.
    pub samples: Vec<bool>,
    /// Modal coordinates of the row at which the arrestor's deflection peaked (a log that lacks
    /// that row's: the first of its step's, as logs before the row's own were read).
    pub peak_deflection_coordinates: Vec<f64>,
    /// Step index of `peak_deflection_coordinates`.
    pub peak_deflection_step: u64,
    /// Time of the row at which the arrestor's deflection peaked, ns.
    pub peak_deflection_time_ns: u64,
    /// The run's bridge strain energy at that row as it printed it, J, when the log holds it
    /// (`ModalCoordinates.upper_strain_at_peak` of the row's own message).
    pub peak_deflection_strain: Option<f64>,
    /// How often the run was rolled back (an FMU state restored): each time, the steps and
    /// events after the restored step are superseded and dropped here.
    pub rollbacks: u64,
    /// Contact events, in order.
    pub events: Vec<ContactEvent>,
    /// The `foxglove.Log` lines.
    pub log_lines: Vec<String>,
    /// Attachments: (name, media type, size in bytes).
    pub attachments: Vec<(String, String, usize)>,
    /// The run's answer with its checks as the CLI stored it (`answer.json`: `quality`,
    /// `design`, `discretisation`), if the log holds it (CLI runs from this version on).
    pub answer_json: Option<String>,
    /// The support-motion table the run used (`motion.csv`: its rows as CSV), if the run had one
    /// and the log holds it (CLI runs from issue 27 on).
    pub motion_csv: Option<String>,
    /// The run's stress envelope as stored when the log was finished (`envelope.json`, issue 30),
    /// if the log holds it: read by [`replay_envelope`], which checks it.
    pub envelope_json: Option<String>,
    /// The bending stations' stress histories as turning points (`fatigue.json`, issue 44), if
    /// the log holds them: read by [`crate::replay::fatigue`], which checks them.
    pub fatigue_json: Option<String>,
    /// The stress stations (from the model message) and their stresses at every recorded step
    /// (`/beam/stations`), issue 30; empty for logs written before them.
    pub stations: StationRecord,
    /// Messages per topic.
    pub messages: BTreeMap<String, u64>,
    /// Whether log times never decreased, across all channels in file order.
    pub monotonic: bool,
    /// Whether the file ended with its summary and footer (a finished log).
    pub complete: bool,
    /// Why reading stopped early, one line naming the record and its byte offset: for a log cut
    /// short (a killed writer) or one that holds damaged or invalid records.
    pub problem: Option<String>,
    /// Whether reading stopped at bytes that are not a valid log (a bad CRC, a length beyond its
    /// record, a chunk that does not decompress, a message that does not decode), rather than at
    /// the end of a file cut short.
    pub damaged: bool,
    /// Size of the file, bytes.
    pub file_size: u64,
    /// Why the recorder stopped before the run's end (the log reached its size cap: its last
    /// `/beam/log` line says so), if it did. The file is complete; the run went on unrecorded.
    pub stopped_early: Option<String>,
    /// The log's format: 1 (modal coordinates in every step message; no `log_format` metadata) or
    /// 2 (modal coordinates on `/beam/modes`).
    pub log_format: u32,
    /// Every row of modal coordinates and every message's log time, when read with
    /// [`ReadOptions::history`] (empty otherwise).
    pub history: History,
}

/// The stress stations of a log and the stresses recorded at them (issue 30).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StationRecord {
    /// Where the stations are (the model message's groups), if the log says.
    pub layout: Option<StationLayout>,
    /// The step of each recorded row (increasing: the rows a rollback superseded are dropped).
    pub steps: Vec<u64>,
    /// The time of each row, ns.
    pub times_ns: Vec<u64>,
    /// The rows one after the other, signed, Pa, single precision as stored: row k is
    /// `values[k * width..(k + 1) * width]`, width the layout's station count.
    pub values: Vec<f32>,
    /// The latest row that carried the run's envelope so far (issue 41), its index in the rows,
    /// the largest |stress| at every station (Pa) and when each was reached (s); None for logs
    /// written before the rows carried it.
    pub envelope: Option<(usize, Vec<f32>, Vec<f32>)>,
}

impl StationRecord {
    /// Stations per row.
    pub fn width(&self) -> usize {
        self.layout.as_ref().map_or(0, StationLayout::len)
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.steps.len()
    }

    /// Drops the rows of step `step` and later (a rollback to it).
    fn roll_back(&mut self, step: u64) {
        let keep = self.steps.partition_point(|&s| s < step);
        let width = self.width();
        self.steps.truncate(keep);
        self.times_ns.truncate(keep);
        self.values.truncate(keep * width);
        // The envelope of a superseded row is superseded too; an earlier one is not kept (the
        // rebuild then starts from the rows alone).
        if self.envelope.as_ref().is_some_and(|(row, _, _)| *row >= keep) {
            self.envelope = None;
        }
    }
}

/// The model message's station group, as the layout holds it.
fn station_group(message: Option<&StationGroupMessage>) -> StationGroup {
    message.map_or_else(StationGroup::default, |g| StationGroup {
        positions: g.positions.clone(),
        allowable: g.allowable.clone(),
        nodes: g.nodes.clone(),
    })
}

/// The stations of a model message (None for a log written before them).
fn station_layout(m: &ModelMessage) -> Option<StationLayout> {
    let groups =
        [&m.lower_bending_stations, &m.lower_shear_stations, &m.upper_bending_stations, &m.upper_shear_stations];
    if groups.iter().all(|g| g.is_none()) {
        return None;
    }
    Some(StationLayout {
        lower_bending: station_group(m.lower_bending_stations.as_ref()),
        lower_shear: station_group(m.lower_shear_stations.as_ref()),
        upper_bending: station_group(m.upper_bending_stations.as_ref()),
        upper_shear: station_group(m.upper_shear_stations.as_ref()),
        sampled_every: m.stations_sampled_every.max(1),
    })
}

/// What [`read_log_with`] keeps beyond what `report` needs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Keep every row of modal coordinates and every message's log time ([`LogData::history`]).
    pub history: bool,
}

/// Every row of modal coordinates (format 2's `/beam/modes` messages, format 1's step
/// messages), without the rows a rollback superseded, and every message's log time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// The step of each row.
    pub modal_steps: Vec<u64>,
    /// The time of each row, ns.
    pub modal_times_ns: Vec<u64>,
    /// The rows, one after the other (row k is `coordinates[k * width..(k + 1) * width]`).
    pub coordinates: Vec<f64>,
    /// Coordinates per row (every row has as many as the first).
    pub width: usize,
    /// Every message's log time, in file order.
    pub log_times: Vec<u64>,
    /// (rows appended before it, step) of each rollback, to drop the rows it superseded.
    rollbacks: Vec<(usize, u64)>,
}

impl History {
    /// Appends one row of coordinates; a row of another width stops reading.
    fn push(
        &mut self,
        step: u64,
        time_ns: u64,
        row: impl ExactSizeIterator<Item = f64>,
    ) -> std::result::Result<(), String> {
        if self.modal_steps.is_empty() {
            self.width = row.len();
        } else if row.len() != self.width {
            return Err(format!("{} modal coordinates where the first row had {}", row.len(), self.width));
        }
        self.modal_steps.push(step);
        self.modal_times_ns.push(time_ns);
        self.coordinates.extend(row);
        Ok(())
    }

    /// Drops the rows superseded by a rollback: a row is superseded by any later rollback to its
    /// step or an earlier one. One pass from the last row back, keeping the smallest step rolled
    /// back to after the row: linear in the log, however many rollbacks it holds.
    fn settle(&mut self) {
        if self.rollbacks.is_empty() {
            return;
        }
        let rows = self.modal_steps.len();
        let mut keep = vec![true; rows];
        let mut later = self.rollbacks.iter().rev().peekable();
        let mut smallest = u64::MAX;
        for k in (0..rows).rev() {
            while let Some(&&(appended, step)) = later.peek() {
                if appended > k {
                    smallest = smallest.min(step);
                    later.next();
                } else {
                    break;
                }
            }
            keep[k] = self.modal_steps[k] < smallest;
        }
        let width = self.width;
        let mut next = 0;
        for (k, _) in keep.iter().enumerate().filter(|(_, kept)| **kept) {
            self.modal_steps[next] = self.modal_steps[k];
            self.modal_times_ns[next] = self.modal_times_ns[k];
            self.coordinates.copy_within(k * width..(k + 1) * width, next * width);
            next += 1;
        }
        self.modal_steps.truncate(next);
        self.modal_times_ns.truncate(next);
        self.coordinates.truncate(next * width);
        self.rollbacks.clear();
    }
}

impl LogData {
    /// The scenario stored in the log.
    /// The motion table comes from the log's `motion.csv` attachment, never from the file the
    /// scenario names (a log replays by itself); a log written before the attachment existed
    /// replays with fixed supports (see [`LogData::notes`]).
    pub fn scenario(&self) -> Result<Scenario> {
        let text = self.scenario_toml.as_deref().ok_or_else(|| Error::Other("the log holds no scenario".into()))?;
        let mut scenario = Scenario::from_toml(text, SCENARIO_ATTACHMENT)?;
        if !scenario.motion.file.is_empty() {
            match &self.motion_csv {
                Some(csv) => {
                    let table = MotionTable::parse(csv).map_err(|e| {
                        Error::Other(format!("the log's motion table ({MOTION_ATTACHMENT}) is refused: {e}"))
                    })?;
                    scenario.motion.table = Some(std::sync::Arc::new(table));
                }
                None => scenario.motion = Default::default(),
            }
        }
        // A sea's record is the log's motion table (issue 42): replayed without the RAO file.
        let duration = scenario.duration;
        if let Some(sea) = &mut scenario.sea {
            let csv = self.motion_csv.as_ref().ok_or_else(|| {
                Error::Other(format!(
                    "the log's [sea] run holds no record ({MOTION_ATTACHMENT}): it cannot be replayed"
                ))
            })?;
            let table = MotionTable::parse(csv)
                .map_err(|e| Error::Other(format!("the log's sea record ({MOTION_ATTACHMENT}) is refused: {e}")))?;
            sea.recorded = Some((sea.key(duration), std::sync::Arc::new(table)));
        }
        Ok(scenario)
    }

    /// What a reader should know about how the log is replayed (one line each): today, a run
    /// with moving supports whose log holds no motion table.
    pub fn notes(&self) -> Vec<String> {
        let file = self
            .scenario_toml
            .as_deref()
            .and_then(|t| Scenario::from_toml(t, SCENARIO_ATTACHMENT).ok())
            .map(|s| s.motion.file)
            .unwrap_or_default();
        if file.is_empty() || self.motion_csv.is_some() {
            return Vec::new();
        }
        vec![format!(
            "note: the run's supports moved ({}), but the log holds no motion table (written before logs carried \
             {MOTION_ATTACHMENT}): the steps are reported as recorded; the modes and the energy approach are those of \
             fixed supports",
            crate::model::motion_table::quote_cell(&file)
        )]
    }
}

fn mcap_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Mcap { path: path.display().to_string(), message: e.to_string() }
}

/// What the reader may keep from a log, as a multiple of the file's size (plus
/// [`RETAINED_SLACK`]): the decoded steps, events, log lines, topics, metadata and scenario.
/// A step message of ours is ~280 bytes in the file (format 2, uncompressed; ~330 compressed in
/// format 1) and 216 bytes decoded, so real logs keep under 1x; the bound stops a crafted log of highly compressible messages from growing the
/// reader's memory to the 64x its chunks may decompress to (see [`super::safe_read::Limits`]).
pub const RETAINED_RATIO: u64 = 16;

/// What the reader may keep from any log regardless of its size, bytes.
pub const RETAINED_SLACK: u64 = 16 << 20;

/// Reads every complete chunk of the log at `path`; a log cut short is not an error (see
/// [`LogData::complete`] and [`LogData::problem`]), an unreadable or foreign file is.
pub fn read_log(path: &Path) -> Result<LogData> {
    read_log_with(path, ReadOptions::default())
}

/// [`read_log`], keeping what `options` asks for besides.
pub fn read_log_with(path: &Path, options: ReadOptions) -> Result<LogData> {
    // A FIFO or socket is refused rather than waited on.
    let mut file = crate::record::output::open_regular_input(path, "cannot read MCAP log")?;
    let mut bytes = Vec::new();
    std::io::Read::read_to_end(&mut file, &mut bytes).map_err(|source| Error::Io {
        action: "cannot read MCAP log",
        path: path.display().to_string(),
        source,
    })?;
    read_log_bytes_with(&bytes, path, options)
}

/// What [`read_log`] does with the bytes of the file: every length is checked against what the
/// bytes hold before anything is allocated or decompressed ([`super::safe_read`]), and what is
/// kept is bounded by [`RETAINED_RATIO`] times their size. `path` names the log in errors.
///
/// Reading stops at the first record that is not valid (a file cut short, a bad CRC, a chunk
/// that does not decompress, a message that does not decode); what was read before it is kept,
/// and [`LogData::problem`] says what stopped it, with the record's kind and byte offset. A file
/// in which nothing could be read is an error.
pub fn read_log_bytes(bytes: &[u8], path: &Path) -> Result<LogData> {
    read_log_bytes_with(bytes, path, ReadOptions::default())
}

/// [`read_log_bytes`], keeping what `options` asks for besides (within the same bound).
pub fn read_log_bytes_with(bytes: &[u8], path: &Path, options: ReadOptions) -> Result<LogData> {
    let mut data = LogData { monotonic: true, file_size: bytes.len() as u64, ..LogData::default() };
    let mut state = ReadState {
        retained_limit: RETAINED_RATIO.saturating_mul(bytes.len() as u64).saturating_add(RETAINED_SLACK),
        history: options.history,
        ..ReadState::default()
    };
    let ending = read_records(bytes, Limits::default(), &mut |at, record| state.visit(&mut data, at, record));
    let stop = match ending {
        Ok(Ending::Complete) => None,
        Ok(Ending::Stopped(e)) => Some((e.is_cut_short(), e.to_string())),
        Err(problem) => Some((false, problem)),
    };
    if let Some((cut_short, problem)) = stop {
        // Nothing readable at all: not a log (or not even its header), an error.
        if state.topics.is_empty() && data.messages.is_empty() {
            return Err(mcap_err(path, format!("not a readable MCAP log: {problem}")));
        }
        data.damaged = !cut_short;
        data.problem = Some(problem);
    }
    data.complete = data.problem.is_none();
    data.log_format = match data.metadata.get(LOG_FORMAT_KEY) {
        None => 1,
        Some(text) => match text.parse::<u32>() {
            Ok(format) if (1..=LOG_FORMAT).contains(&format) => format,
            _ => {
                let known = format!(
                    "log format {} is not one this reader knows (1 to {LOG_FORMAT})",
                    super::safe_read::quoted(text)
                );
                let why = match (&data.problem, data.damaged) {
                    // The metadata itself may be what changed.
                    (Some(problem), true) => format!("the file is damaged: {problem}"),
                    _ => format!(
                        "written by a newer beam-impact? (its version: {})",
                        data.metadata
                            .get("beam_impact_version")
                            .map_or("not recorded".to_string(), |v| super::safe_read::quoted(v))
                    ),
                };
                return Err(mcap_err(path, format!("{known}: {why}")));
            }
        },
    };
    if data.scenario_toml.is_none() {
        data.scenario_toml = state.model_toml;
    }
    data.history.settle();
    Ok(data)
}

/// What reading a log carries from one record to the next.
#[derive(Default)]
struct ReadState {
    topics: BTreeMap<u16, String>,
    step: StepMessage,
    /// Whether the last step message was a sample of the dense output (issue 41).
    last_sample: bool,
    last_time: u64,
    model_toml: Option<String>,
    retained: u64,
    retained_limit: u64,
    history: bool,
}

impl ReadState {
    /// Counts `bytes` more kept from the log; past the limit, reading stops.
    fn keep(&mut self, bytes: usize, at: Place, what: &str) -> std::result::Result<(), String> {
        self.retained = self.retained.saturating_add(bytes as u64);
        if self.retained > self.retained_limit {
            return Err(format!(
                "{what} at {at}: the log decodes to more than {} bytes ({RETAINED_RATIO}x its size + {} MiB), \
                 more than any log of this program holds",
                self.retained_limit,
                RETAINED_SLACK >> 20
            ));
        }
        Ok(())
    }

    fn visit(&mut self, data: &mut LogData, at: Place, record: Record<'_>) -> std::result::Result<(), String> {
        match record {
            Record::Channel { id, topic, .. } => {
                // The topic is kept twice: here and as a key of the message counts.
                self.keep(2 * topic.len() + 64, at, "channel record")?;
                self.topics.insert(id, topic.to_string());
            }
            Record::Message { channel_id, log_time, publish_time, data: bytes, .. } => {
                if self.history {
                    self.keep(8, at, "message")?;
                    data.history.log_times.push(log_time);
                }
                let topic = self.topics.get(&channel_id).map(String::as_str).unwrap_or("?");
                match data.messages.get_mut(topic) {
                    Some(n) => *n += 1,
                    None => {
                        data.messages.insert(topic.to_string(), 1);
                    }
                }
                // Time runs backwards only at a rollback: its log line and the steps after it.
                let decreasing = log_time < self.last_time;
                if publish_time != log_time {
                    data.monotonic = false;
                }
                self.last_time = log_time;
                let bad = |what: &str, e: prost::DecodeError| format!("{what} message at {at} does not decode: {e}");
                match topic {
                    STEP_TOPIC => {
                        self.keep(std::mem::size_of::<StepResult>(), at, "step message")?;
                        self.step.clear();
                        self.step.merge(bytes).map_err(|e| bad("step", e))?;
                        let mut result = self.step.result();
                        // Format 2 leaves out the time in seconds: it is time_ns / 1e9 (format 1's).
                        result.time = seconds(result.time_ns);
                        // Rows of one step: its dense output's samples (issue 41), in time order, then
                        // its end. Any other row of a step not after the last one's is a rollback's.
                        let sample = self.step.sample;
                        let follows = |last: &StepResult| {
                            result.step > last.step
                                || (result.step == last.step && self.last_sample && result.time_ns > last.time_ns)
                        };
                        let rollback = data.steps.last().is_some_and(|last| !follows(last));
                        self.last_sample = sample;
                        data.monotonic &= !decreasing || rollback;
                        if rollback && self.history {
                            data.history.rollbacks.push((data.history.modal_steps.len(), result.step));
                        }
                        if rollback {
                            // A rollback: this step continues from step result.step - 1. Steps are
                            // kept in increasing step order, so the superseded ones are a tail
                            // (found by binary search); so are the events, which follow the steps.
                            // Each step and event is dropped at most once: linear in the log.
                            data.rollbacks += 1;
                            let keep = data.steps.partition_point(|r| r.step < result.step);
                            data.steps.truncate(keep);
                            data.samples.truncate(keep);
                            while data.events.last().is_some_and(|e| e.step > result.step) {
                                data.events.pop();
                            }
                            if data.peak_deflection_step >= result.step {
                                data.peak_deflection_coordinates.clear();
                                data.peak_deflection_strain = None;
                            }
                            data.stations.roll_back(result.step);
                        }
                        // Format 2 leaves out peaks equal to the previous step's.
                        if self.step.peaks.is_none() {
                            result.peaks = data.steps.last().map(|r| r.peaks).unwrap_or_default();
                        }
                        let previous = data.steps.last().map(|r| r.peaks.lower_tip_deflection);
                        if previous.is_none_or(|p| result.peaks.lower_tip_deflection != p) {
                            data.peak_deflection_coordinates.clear();
                            data.peak_deflection_coordinates
                                .extend(self.step.modal_coordinates.iter().map(|&q| f64::from(q)));
                            data.peak_deflection_step = result.step;
                            data.peak_deflection_time_ns = result.time_ns;
                            data.peak_deflection_strain = None;
                        }
                        if self.history && !self.step.modal_coordinates.is_empty() {
                            self.keep(8 * self.step.modal_coordinates.len() + 16, at, "step message")?;
                            let (step, time_ns) = (result.step, result.time_ns);
                            let row = self.step.modal_coordinates.iter().map(|&q| f64::from(q));
                            data.history.push(step, time_ns, row).map_err(|e| format!("step message at {at}: {e}"))?;
                        }
                        data.steps.push(result);
                        data.samples.push(sample);
                    }
                    MODES_TOPIC => {
                        data.monotonic &= !decreasing;
                        let m = ModalCoordinatesMessage::decode(bytes).map_err(|e| bad("modes", e))?;
                        if self.history {
                            self.keep(8 * m.coordinates.len() + 16, at, "modes message")?;
                            let row = m.coordinates.iter().copied();
                            data.history
                                .push(m.step, m.time_ns, row)
                                .map_err(|e| format!("modes message at {at}: {e}"))?;
                        }
                        // Kept only at the arrestor's peak deflection (the summary's E_def,b): the
                        // row's own message (its step and time: a step's samples share its number),
                        // else, until it comes, the first of its step.
                        let own = (m.step, m.time_ns) == (data.peak_deflection_step, data.peak_deflection_time_ns);
                        let same_step =
                            data.peak_deflection_coordinates.is_empty() && m.step == data.peak_deflection_step;
                        if own || same_step {
                            self.keep(8 * m.coordinates.len(), at, "modes message")?;
                            data.peak_deflection_coordinates = m.coordinates;
                            // A strain energy is finite and not negative: a log's other value is
                            // not taken (the kept modes' sum stands for it).
                            data.peak_deflection_strain =
                                m.upper_strain_at_peak.filter(|e| own && e.is_finite() && *e >= 0.0);
                        }
                    }
                    STATIONS_TOPIC => {
                        data.monotonic &= !decreasing;
                        let m = StationStressesMessage::decode(bytes).map_err(|e| bad("stations", e))?;
                        let width = data.stations.width();
                        let given =
                            m.lower_bending.len() + m.lower_shear.len() + m.upper_bending.len() + m.upper_shear.len();
                        let Some(layout) = &data.stations.layout else {
                            return Err(format!("stations message at {at}: the log's model message has no stations"));
                        };
                        let counts = [&m.lower_bending, &m.lower_shear, &m.upper_bending, &m.upper_shear].map(Vec::len);
                        if counts != layout.groups().map(StationGroup::len) {
                            return Err(format!(
                                "stations message at {at} holds {given} stresses ({counts:?}) where the model has {width} \
                                 stations ({:?})",
                                layout.groups().map(StationGroup::len)
                            ));
                        }
                        // Rows in step order: a row of an earlier step (a rollback's) replaces the tail.
                        let last_time = data.stations.times_ns.last().copied().unwrap_or(0);
                        let follows = |last: u64| m.step > last || (m.step == last && m.time_ns > last_time);
                        if data.stations.steps.last().is_some_and(|&last| !follows(last)) {
                            data.stations.roll_back(m.step);
                        }
                        self.keep(4 * given + 16, at, "stations message")?;
                        data.stations.steps.push(m.step);
                        data.stations.times_ns.push(m.time_ns);
                        for values in [&m.lower_bending, &m.lower_shear, &m.upper_bending, &m.upper_shear] {
                            data.stations.values.extend_from_slice(values);
                        }
                        // The running envelope, when the message holds one per station (else it is
                        // not the model's, or the log predates it: the rows alone are used).
                        if m.envelope.len() == width && m.envelope_time.len() == width && width > 0 {
                            let row = data.stations.steps.len() - 1;
                            data.stations.envelope = Some((row, m.envelope, m.envelope_time));
                        }
                    }
                    CONTACT_TOPIC => {
                        self.keep(std::mem::size_of::<ContactEvent>(), at, "contact message")?;
                        data.monotonic &= !decreasing;
                        let m = ContactEventMessage::decode(bytes).map_err(|e| bad("contact", e))?;
                        data.events.push(ContactEvent::from(&m));
                    }
                    LOG_TOPIC => {
                        let m = LogMessage::decode(bytes).map_err(|e| bad("log", e))?;
                        self.keep(m.message.len() + std::mem::size_of::<String>(), at, "log message")?;
                        data.monotonic &= !decreasing || m.message.starts_with(crate::record::mcap::ROLLBACK_LINE);
                        if m.message.contains(crate::record::mcap::SIZE_CAP_LINE) {
                            data.stopped_early = Some(m.message.clone());
                        }
                        data.log_lines.push(m.message);
                    }
                    MODEL_TOPIC => {
                        data.monotonic &= !decreasing;
                        let m = ModelMessage::decode(bytes).map_err(|e| bad("model", e))?;
                        let layout = station_layout(&m);
                        let stations = layout.as_ref().map_or(0, |l| 2 * 20 * l.len());
                        let size = 2 * m.scenario_toml.len()
                            + 8 * (m.lower_nodes.len() + m.upper_nodes.len() + m.nodal_shapes.len())
                            + stations;
                        self.keep(size, at, "model message")?;
                        if let Some(l) = &layout {
                            if let Some(k) = l.groups().iter().position(|g| !g.is_consistent()) {
                                return Err(format!(
                                    "model message at {at}: station group {k} holds {} positions, {} allowables and \
                                     {} nodes (or a value that is not finite)",
                                    l.groups()[k].positions.len(),
                                    l.groups()[k].allowable.len(),
                                    l.groups()[k].nodes.len()
                                ));
                            }
                        }
                        // A second model message (a record started again) must describe the same stations.
                        match (&data.stations.layout, layout) {
                            (None, layout) => data.stations.layout = layout,
                            (Some(known), Some(layout)) if *known != layout => {
                                return Err(format!(
                                    "model message at {at}: its stations are not those of the log's first model message"
                                ))
                            }
                            _ => {}
                        }
                        self.model_toml = Some(m.scenario_toml.clone());
                        data.model = Some(m);
                    }
                    _ => {}
                }
            }
            Record::Attachment { name, media_type, data: bytes, .. } => {
                let scenario = name == SCENARIO_ATTACHMENT;
                let answer = name == ANSWER_ATTACHMENT;
                let motion = name == MOTION_ATTACHMENT;
                let envelope = name == ENVELOPE_ATTACHMENT;
                let fatigue = name == crate::record::log_format::FATIGUE_ATTACHMENT;
                let kept = scenario || answer || motion || envelope || fatigue;
                let size = name.len() + media_type.len() + 64 + if kept { bytes.len() } else { 0 };
                self.keep(size, at, "attachment record")?;
                if scenario {
                    data.scenario_toml = Some(String::from_utf8_lossy(bytes).into_owned());
                }
                if answer {
                    data.answer_json = Some(String::from_utf8_lossy(bytes).into_owned());
                }
                if motion {
                    data.motion_csv = Some(String::from_utf8_lossy(bytes).into_owned());
                }
                if envelope {
                    data.envelope_json = Some(String::from_utf8_lossy(bytes).into_owned());
                }
                if fatigue {
                    data.fatigue_json = Some(String::from_utf8_lossy(bytes).into_owned());
                }
                data.attachments.push((name.to_string(), media_type.to_string(), bytes.len()));
            }
            Record::Metadata { name, entries } if name == SCENARIO_METADATA => {
                let size: usize = entries.iter().map(|(k, v)| k.len() + v.len() + 64).sum();
                self.keep(size, at, "metadata record")?;
                data.metadata = entries.into_iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
            }
            _ => {}
        }
        Ok(())
    }
}

/// The run's [`Summary`] rebuilt from the log: peaks and when they were reached from the step
/// messages, contact windows from the events, residuals from the energy account; modes and
/// the energy approach recomputed from the stored scenario by `simulation`.
pub fn summary_from_log(data: &LogData, simulation: &Simulation) -> Result<Summary> {
    let last = data.steps.last().ok_or_else(|| Error::Other("the log holds no step message".into()))?;
    let peak_times = peak_times(&data.steps);
    let mut max_residual = 0.0f64;
    let (mut max_strain, mut max_work) = (0.0f64, 0.0f64);
    let mut first_contact = FirstContact::default();
    for (k, r) in data.steps.iter().enumerate() {
        first_contact.observe(r);
        // The run's energy check is over its steps' ends: a sample books the damping's work as a
        // trapezoid, not the exact advance's, and its residual is not the run's.
        if data.samples.get(k) == Some(&true) {
            continue;
        }
        max_strain = max_strain.max(r.energy.strain);
        max_work = max_work.max(r.energy.external_work.abs());
        max_residual = max_residual.max(r.energy.residual.abs());
    }
    let mut windows: Vec<ContactWindow> = Vec::new();
    for e in &data.events {
        let t = crate::results::seconds(e.time_ns);
        if e.start {
            windows.push(ContactWindow { start: t, end: last.time });
        } else if let Some(w) = windows.last_mut() {
            w.end = t;
        }
    }
    // A window still open when the log ends closes at the last step taken in contact.
    if let (Some(w), Some(e)) = (windows.last_mut(), data.events.last()) {
        if e.start {
            w.end = data.steps.iter().rev().find(|r| r.contact).map_or(w.start, |r| r.time);
        }
    }
    let modal = simulation.modal();
    let upper_strain = data
        .peak_deflection_coordinates
        .iter()
        .enumerate()
        .skip(modal.lower_dofs)
        .map(|(i, q)| 0.5 * modal.omega2.get(i).copied().unwrap_or(0.0) * q * q)
        .sum();
    // After a rollback past the peak the shape at the peak is no longer in the log. The run's own
    // value where the log holds it (the kept modes' sum leaves out a truncated basis's correction).
    let upper_strain = match data.peak_deflection_strain {
        Some(printed) => printed,
        None if data.peak_deflection_coordinates.is_empty() => f64::NAN,
        None => upper_strain,
    };
    Ok(Summary {
        steps: last.step,
        time: last.time,
        peaks: last.peaks,
        peak_times,
        upper_strain_at_peak_deflection: upper_strain,
        contact_windows: windows,
        // The log's `answer.json` carries them (issue 45).
        sub_impacts: Vec::new(),
        final_energy_residual: last.energy.residual,
        max_energy_residual: max_residual,
        energy_method: *simulation.energy_method(),
        modes: simulation.mode_table(5),
        quality: {
            let s = simulation.scenario();
            Quality::assess(
                max_residual,
                s.impact_energy(),
                max_work,
                max_strain,
                s.energy_tolerance,
                simulation.step_plan().advisories(s, simulation.modal()),
            )
        },
        first_contact_peaks: first_contact.peaks,
        first_contact_end: first_contact.end(),
        time_steps: {
            let plan = simulation.step_plan();
            TimeSteps { free: seconds(plan.free_ns), contact: seconds(plan.contact_ns) }
        },
        impact: simulation.impact(),
        envelope: replay_envelope(data, &last.peaks, &peak_times, simulation.scenario().contact_position).0,
        model_range: Default::default(),
    })
}

/// When each running peak of `steps` was last raised, s (the step messages' peaks).
pub fn peak_times(steps: &[StepResult]) -> Peaks {
    let mut peak_times = Peaks::default();
    let mut previous: Option<Peaks> = None;
    for r in steps {
        let now = r.peaks.as_array();
        let before = previous.map(|p| p.as_array());
        for (k, when) in peak_times.as_mut_array().into_iter().enumerate() {
            if before.is_none_or(|b| b[k] != now[k]) {
                *when = r.time;
            }
        }
        previous = Some(r.peaks);
    }
    peak_times
}

/// [`replay_envelope`] of a log by itself (no model built): the peaks of its last step message,
/// their times, and the contact point of its stored scenario (none raised there if the scenario
/// does not parse). For readers other than `report` (the Python package).
pub fn envelope_of_log(data: &LogData) -> (StressEnvelope, EnvelopeSource) {
    let peaks = data.steps.last().map(|r| r.peaks).unwrap_or_default();
    let contact = data
        .scenario_toml
        .as_deref()
        .and_then(|t| Scenario::from_toml(t, SCENARIO_ATTACHMENT).ok())
        .map_or(f64::NAN, |s| s.contact_position);
    replay_envelope(data, &peaks, &peak_times(&data.steps), contact)
}

/// Where a replayed stress envelope comes from (issue 30).
#[derive(Clone, Debug, PartialEq)]
pub enum EnvelopeSource {
    /// The log's `envelope.json`, stored when the log was finished.
    Attachment,
    /// Rebuilt from the stresses of the `/beam/stations` messages (`rows` recorded steps),
    /// because `why` (no attachment: a killed run; or one that was refused).
    Rebuilt {
        /// Recorded steps it was rebuilt from.
        rows: usize,
        /// Why the attachment was not used.
        why: String,
    },
    /// Neither: the log holds no stations (written before issue 30) or no stresses at them.
    Absent {
        /// Why.
        why: String,
    },
}

impl EnvelopeSource {
    /// One line for a report.
    pub fn describe(&self) -> String {
        match self {
            EnvelopeSource::Attachment => format!("from the log's {ENVELOPE_ATTACHMENT} (stored with the run)"),
            EnvelopeSource::Rebuilt { rows, why } => format!(
                "REBUILT from the {rows} rows of /beam/stations (the run's envelope so far, which the rows carry \
                 every 1 ms by default, from the last that does, raised by the stresses after it; single \
                 precision; a log written before the rows carried it: from their stresses alone, a lower bound; \
                 the paper's three points raised by the steps' running peaks): {why}"
            ),
            EnvelopeSource::Absent { why } => format!("not in this log: {why}"),
        }
    }
}

/// A stored envelope's problem with the log's stations, if any: every list of each station
/// envelope one entry per station, every value finite and no stress negative; the stations those
/// of the model message, when it has them.
fn envelope_problem(envelope: &StressEnvelope, layout: Option<&StationLayout>) -> Option<String> {
    let groups = [
        ("lower.bending", &envelope.lower.bending),
        ("lower.shear", &envelope.lower.shear),
        ("upper.bending", &envelope.upper.bending),
        ("upper.shear", &envelope.upper.shear),
    ];
    for (k, (name, e)) in groups.iter().enumerate() {
        let n = e.positions.len();
        if e.max.len() != n || e.times.len() != n || e.allowable.len() != n {
            return Some(format!(
                "{name} has {n} positions, {} values, {} times and {} allowables",
                e.max.len(),
                e.times.len(),
                e.allowable.len()
            ));
        }
        let values = e.positions.iter().chain(&e.max).chain(&e.times).chain(&e.allowable);
        if let Some(v) = values.copied().find(|v| !v.is_finite()) {
            return Some(format!("{name} holds {v}, not a finite value"));
        }
        if let Some(v) = e.max.iter().chain(&e.allowable).copied().find(|v| *v < 0.0) {
            return Some(format!("{name} holds the stress {v} Pa below zero"));
        }
        if let Some(layout) = layout {
            if layout.groups()[k].len() != n {
                return Some(format!("{name} has {n} stations where the log's model has {}", layout.groups()[k].len()));
            }
        }
    }
    None
}

/// The run's stress envelope from a log (issue 30): its `envelope.json` when it holds a sound one,
/// else rebuilt from the stations' rows: the run's envelope so far that the last of them to carry it
/// holds (issue 41), raised by the stresses of the rows from it on (a log written before the rows
/// carried it: the largest |value| of the rows, a lower bound of the run's own, which takes every
/// step and each station's cubic inside the exact advance's contact steps; raised at the paper's three points by the steps' running peaks
/// `peaks`, reached at `peak_times`; the bridge's contact point at `contact_position` m), else
/// empty; with where it came from.
pub fn replay_envelope(
    data: &LogData,
    peaks: &Peaks,
    peak_times: &Peaks,
    contact_position: f64,
) -> (StressEnvelope, EnvelopeSource) {
    let layout = data.stations.layout.as_ref();
    let why = match data.envelope_json.as_deref() {
        None => format!("the log holds no {ENVELOPE_ATTACHMENT} (a run killed before its log was finished?)"),
        Some(text) => match serde_json::from_str::<StressEnvelope>(text) {
            Err(e) => {
                // The parser's message may quote the file: one line, bounded.
                let text = e.to_string();
                let cut: String = text.chars().map(|c| if c.is_control() { ' ' } else { c }).take(160).collect();
                let more = if cut.len() < text.len() { "..." } else { "" };
                format!("the stored {ENVELOPE_ATTACHMENT} does not parse: {cut}{more}")
            }
            Ok(envelope) => match envelope_problem(&envelope, layout) {
                None => return (envelope, EnvelopeSource::Attachment),
                Some(problem) => format!("the stored {ENVELOPE_ATTACHMENT} is refused: {problem}"),
            },
        },
    };
    let Some(layout) = layout else {
        let why = match data.envelope_json {
            None => "the log has no stress stations (written before logs carried the envelope)".to_string(),
            Some(_) => format!("{why}, and the log has no stress stations to rebuild it from"),
        };
        return (StressEnvelope::default(), EnvelopeSource::Absent { why });
    };
    let record = &data.stations;
    if record.rows() == 0 {
        let why = format!("{why}, and it holds no stresses at its stations (/beam/stations)");
        return (StressEnvelope::default(), EnvelopeSource::Absent { why });
    }
    let width = layout.len();
    let (mut max, mut times) = (vec![0.0f64; width], vec![0.0f64; width]);
    // From the latest running envelope the rows carried (every step's and the crests within
    // them, to that row), raised by the stresses of the rows from it on; else from the rows alone.
    let mut first = 0;
    if let Some((row, envelope, envelope_times)) = &record.envelope {
        let sound = |v: &f32| v.is_finite() && *v >= 0.0;
        if envelope.len() == width && envelope.iter().all(sound) && envelope_times.iter().all(sound) {
            for k in 0..width {
                (max[k], times[k]) = (f64::from(envelope[k]), f64::from(envelope_times[k]));
            }
            first = *row;
        }
    }
    for (row, values) in record.values.chunks_exact(width.max(1)).enumerate().skip(first) {
        for (k, &v) in values.iter().enumerate() {
            let v = f64::from(v).abs();
            if v > max[k] {
                (max[k], times[k]) = (v, seconds(record.times_ns[row]));
            }
        }
    }
    let mut offset = 0;
    let mut take = |g: &StationGroup| {
        let range = offset..offset + g.len();
        offset += g.len();
        StationEnvelope {
            positions: g.positions.clone(),
            max: max[range.clone()].to_vec(),
            times: times[range].to_vec(),
            allowable: g.allowable.clone(),
        }
    };
    let mut envelope = StressEnvelope {
        lower: crate::results::BeamEnvelope { bending: take(&layout.lower_bending), shear: take(&layout.lower_shear) },
        upper: crate::results::BeamEnvelope { bending: take(&layout.upper_bending), shear: take(&layout.upper_shear) },
        sampled_every: layout.sampled_every,
    };
    // The paper's three points, as the run raises them: the clamp's first station of each stress
    // and the bridge's one bending station at the contact point.
    let raise = |e: &mut StationEnvelope, k: usize, value: f64, time: f64| {
        if k < e.max.len() && value.is_finite() && value > e.max[k] {
            (e.max[k], e.times[k]) = (value, time);
        }
    };
    raise(&mut envelope.lower.bending, 0, peaks.lower_clamp_bending_stress, peak_times.lower_clamp_bending_stress);
    raise(&mut envelope.lower.shear, 0, peaks.lower_clamp_shear_stress, peak_times.lower_clamp_shear_stress);
    let tolerance = 1e-9 * contact_position.abs().max(1.0);
    let at_contact: Vec<usize> = (0..envelope.upper.bending.positions.len())
        .filter(|&k| (envelope.upper.bending.positions[k] - contact_position).abs() <= tolerance)
        .collect();
    if let [k] = at_contact[..] {
        raise(
            &mut envelope.upper.bending,
            k,
            peaks.upper_contact_bending_stress,
            peak_times.upper_contact_bending_stress,
        );
    }
    (envelope, EnvelopeSource::Rebuilt { rows: record.rows(), why })
}

fn summary_text(data: &LogData, scenario: &Scenario, summary: &Summary, out: &mut String) {
    use std::fmt::Write as _;
    let _ = writeln!(
        out,
        "scenario: {}",
        if scenario.is_paper() { "the paper's (Catipovic, Vladimir, Reljic 2008)" } else { "user" }
    );
    if !scenario.is_paper() {
        for line in scenario.to_toml().lines().filter(|l| !l.trim().is_empty()) {
            let _ = writeln!(out, "  {line}");
        }
    }
    let _ = writeln!(
        out,
        "steps: {} internal steps to t = {:.6} s of {:.3} s ({} step messages)",
        summary.steps,
        summary.time,
        scenario.duration,
        data.steps.len()
    );
    // Issue 45: w_din,a at the contact point on two supports or struck inside the span, a pin's
    // stresses at a pinned first support, no bridge for a rigid impactor.
    let words = crate::wording::Wording::of(scenario);
    let deflection =
        if words.at_contact { "contact-point deflection w_din,a" } else { "arrestor end deflection  w_din,a" };
    let pin = words.first_support == "pin";
    let names = [
        (deflection, 1.0, "m  "),
        (if pin { "pin bending stress       s_din,a" } else { "clamp bending stress     s_din,a" }, 1e-6, "MPa"),
        (if pin { "pin shear stress         t_din,a" } else { "clamp shear stress       t_din,a" }, 1e-6, "MPa"),
        ("bridge contact bending   s_din,b", 1e-6, "MPa"),
        ("contact bar force        F_c    ", 1e-3, "kN "),
    ];
    let _ = writeln!(out, "peaks max |.| and when reached:");
    for (k, (name, scale, unit)) in names.iter().enumerate() {
        if k == 3 && words.rigid_impactor {
            continue;
        }
        let _ = writeln!(
            out,
            "  {name} {:10.4} {unit} at t = {:.5} s",
            summary.peaks.as_array()[k] * scale,
            summary.peak_times.as_array()[k]
        );
    }
    let _ = writeln!(
        out,
        "contact: {} events -> {} windows (merged below); {} log lines",
        data.events.len(),
        summary.contact_windows.len(),
        data.log_lines.len()
    );
}

/// The envelope's lines of a report: where it comes from, then each beam's worst bending and
/// shear stress with where and when, its utilisation, and the paper's point beside it.
pub fn envelope_text(summary: &Summary, source: &EnvelopeSource) -> String {
    envelope_text_worded(summary, source, &crate::wording::Wording::default())
}

/// [`envelope_text`] in the words of `w` (issue 45): the first support a clamp or a pin; the
/// paper's point beside it only on the paper's scenario's words.
pub fn envelope_text_worded(summary: &Summary, source: &EnvelopeSource, w: &crate::wording::Wording) -> String {
    use std::fmt::Write as _;
    let mut out = format!("stress envelope: {}\n", source.describe());
    let e = &summary.envelope;
    let p = &summary.peaks;
    let (bending_at, shear_at) = if w.first_support == "pin" {
        ("s_din,a at the pin", "t_din,a at the pin")
    } else {
        ("s_din,a at the clamp", "t_din,a at the clamp")
    };
    let rows = [
        ("arrestor bending", &e.lower.bending, Some((bending_at, p.lower_clamp_bending_stress))),
        ("arrestor shear  ", &e.lower.shear, Some((shear_at, p.lower_clamp_shear_stress))),
        ("bridge bending  ", &e.upper.bending, Some(("s_din,b at contact", p.upper_contact_bending_stress))),
        ("bridge shear    ", &e.upper.shear, None),
    ];
    for (name, envelope, paper) in rows {
        let Some(peak) = envelope.peak() else { continue };
        let utilisation = match (peak.utilisation, peak.utilisation_position) {
            (Some(u), Some(x)) => format!("utilisation {u:.3} at x = {x:.3} m"),
            _ => "no allowable".to_string(),
        };
        let owner = if *w == crate::wording::Wording::default() { "paper's " } else { "the run's " };
        let beside = paper.map_or(String::new(), |(point, v)| format!("; {owner}{point} {:.1} MPa", v * 1e-6));
        let _ = writeln!(
            out,
            "  {name} {:10.1} MPa at x = {:7.3} m, t = {:.5} s; {utilisation}{beside}",
            peak.value * 1e-6,
            peak.position,
            peak.time
        );
    }
    out
}

/// The run's verdict as the log stores it (the CLI's `answer.json`): trusted or not with the
/// reasons, and the design check; one line. Nothing in a log is trusted: a document that does not
/// parse is said to, and quoted text is cut.
pub fn stored_verdict(answer_json: Option<&str>) -> String {
    let Some(text) = answer_json else {
        return "verdict: not stored in this log (written by the FMU or an earlier version; `beam-impact run` \
                stores its checks)"
            .to_string();
    };
    let Ok(doc) = serde_json::from_str::<serde_json::Value>(text) else {
        return "verdict: the stored answer.json does not parse".to_string();
    };
    let quality = &doc["quality"];
    let trust = match quality["trusted"].as_bool() {
        Some(true) => "trusted (every check that ran passed)".to_string(),
        Some(false) => {
            let reasons: Vec<&str> =
                quality["reasons"].as_array().map_or(Vec::new(), |r| r.iter().filter_map(|v| v.as_str()).collect());
            let joined = reasons.join("; ");
            let cut: String = joined.chars().take(400).collect();
            let more = if cut.len() < joined.len() { "..." } else { "" };
            format!("NOT TRUSTED: {cut}{more}")
        }
        None => "unknown (no quality.trusted)".to_string(),
    };
    let design = match doc["design"]["pass"].as_bool() {
        Some(true) => "PASS",
        Some(false) => "FAIL",
        None => "unknown",
    };
    let cases = serde_json::from_value::<crate::load_cases::results::LoadCaseResults>(doc["load_cases"].clone())
        .map(|cases| format!("\n{}", crate::load_cases::results::text(&cases).trim_end()))
        .unwrap_or_default();
    format!("verdict stored with the run: {trust}; design: {design}{cases}{}", stored_amplification(&doc))
}

/// The dynamic amplification the log's `answer.json` stores (issue 44), one line: each quantity's
/// DAF (names escaped and cut, as everything read from a log), or nothing where none is stored.
fn stored_amplification(doc: &serde_json::Value) -> String {
    let Some(daf) = doc["dynamic_amplification"]["daf"].as_object() else {
        return String::new();
    };
    let shown: Vec<String> = daf
        .iter()
        .take(16)
        .filter_map(|(name, v)| v.as_f64().map(|v| (name, v)))
        .map(|(name, v)| {
            let name: String = name.chars().take(48).map(|c| if c.is_control() { '?' } else { c }).collect();
            format!("{name} {v:.3}")
        })
        .collect();
    if shown.is_empty() {
        return "\ndynamic amplification stored with the run: none (the bridge does not rest on the arrestor)".into();
    }
    format!("\ndynamic amplification stored with the run (peak / static): {}", shown.join(", "))
}

/// Reads the log at `mcap`, prints the summary to `out` and writes Figures 6-12 (SVG and PNG)
/// into `out_dir` (created if missing).
pub fn report(mcap: &Path, out_dir: &Path, out: &mut dyn Write) -> Result<()> {
    let data = read_log(mcap)?;
    let io = |source| Error::Io { action: "cannot write report to", path: "output".into(), source };
    let mut text = String::new();
    {
        use std::fmt::Write as _;
        let _ = writeln!(text, "MCAP log {} ({} bytes)", crate::record::output::shown(mcap), data.file_size);
        if let (true, Some(reason)) = (data.complete, &data.stopped_early) {
            let _ = writeln!(
                text,
                "status: STOPPED EARLY: {reason}; reporting the {} step messages before it (the peaks and figures \
                 cover only them)",
                data.steps.len()
            );
        } else if data.complete {
            let _ = writeln!(text, "status: complete (finished file, every chunk CRC checked)");
        } else {
            let _ = writeln!(
                text,
                "status: {}: {}; reporting the {} complete step messages before it",
                if data.damaged { "DAMAGED" } else { "CUT SHORT" },
                data.problem.as_deref().unwrap_or("unknown"),
                data.steps.len()
            );
        }
        let _ = writeln!(text, "{}", stored_verdict(data.answer_json.as_deref()));
        text += &crate::sub_impacts::stored_lines(data.scenario_toml.as_deref(), data.answer_json.as_deref());
        for note in data.notes() {
            let _ = writeln!(text, "{note}");
        }
        let counts: Vec<String> = data.messages.iter().map(|(t, n)| format!("{t} {n}")).collect();
        let _ = writeln!(text, "messages: {}", counts.join(", "));
        if !data.monotonic {
            let _ = writeln!(text, "WARNING: log times decrease somewhere in the file");
        }
        if data.rollbacks > 0 {
            let _ = writeln!(
                text,
                "rollbacks: {} (FMU states restored); the steps they superseded are left out below",
                data.rollbacks
            );
        }
    }
    // Nothing in a log is trusted: the stored scenario is parsed and validated (every field within
    // the scenario limits, which bound the model's size) before anything is built from it.
    if data.scenario_toml.is_none() {
        let problem = data.problem.as_deref().map(|p| format!(" (reading stopped: {p})")).unwrap_or_default();
        return Err(mcap_err(mcap, format!("the log holds no scenario{problem}")));
    }
    let refused = |e: Error| mcap_err(mcap, format!("the scenario stored in the log is refused: {e}"));
    let scenario = data.scenario().map_err(refused)?;
    scenario.validate().map_err(refused)?;
    let simulation = Simulation::new(&scenario).map_err(refused)?;
    let summary = summary_from_log(&data, &simulation).map_err(|e| mcap_err(mcap, e))?;
    summary_text(&data, &scenario, &summary, &mut text);
    let (_, source) = replay_envelope(&data, &summary.peaks, &summary.peak_times, scenario.contact_position);
    text.push_str(&envelope_text_worded(&summary, &source, &crate::wording::Wording::of(&scenario)));
    text.push('\n');
    text.push_str(&crate::compare::comparison_for(&summary, &scenario));
    out.write_all(text.as_bytes()).map_err(io)?;
    super::figures::create_dir(out_dir)?;
    // A value the figures cannot scale (a damaged or forged log: a run's results are finite) would
    // make the axes infinite: say so instead of drawing.
    if let Some(reason) = unplottable(&data.steps, &summary) {
        let note = format!("\nfigures: not drawn: {reason}\n");
        return out.write_all(note.as_bytes()).map_err(io);
    }
    let mut files = super::figures::write_figures(&data.steps, &summary, &scenario, out_dir, !data.complete)?;
    if !matches!(source, EnvelopeSource::Absent { .. }) {
        let subtitle = super::figures::scenario_subtitle(&scenario, Some(summary.time_steps));
        let figure = super::envelope_figure::envelope_figure(
            &summary.envelope,
            &summary.peaks,
            &scenario,
            &subtitle,
            &source.describe(),
        );
        files.extend(super::envelope_figure::write_envelope_figure(&figure, out_dir)?);
    }
    files.extend(super::mode_figures::write_mode_figures(simulation.model(), simulation.modal(), out_dir)?);
    let mut listing = String::from("\nfigures:\n");
    for f in files {
        listing.push_str(&format!("  {}\n", crate::record::output::shown(&f)));
    }
    out.write_all(listing.as_bytes()).map_err(io)?;
    Ok(())
}

pub use super::figures::PLOTTABLE;

/// The first time or plotted value (Figures 6-9) that is not finite or not within
/// [`PLOTTABLE`], with its step, or the end of a contact window that is not.
fn unplottable(steps: &[StepResult], summary: &Summary) -> Option<String> {
    let fine = |v: f64| v.abs() <= PLOTTABLE;
    for r in steps {
        let values = [
            ("time", r.time),
            ("lower_tip_deflection", r.lower_tip_deflection),
            ("upper_contact_deflection", r.upper_contact_deflection),
            ("lower_clamp_bending_stress", r.lower_clamp_bending_stress),
            ("upper_contact_bending_stress", r.upper_contact_bending_stress),
            ("lower_clamp_shear_stress", r.lower_clamp_shear_stress),
            ("contact_stress", r.contact_stress),
        ];
        if let Some((name, v)) = values.into_iter().find(|&(_, v)| !fine(v)) {
            return Some(format!("step {} holds {name} = {v:e}, not a finite value within {PLOTTABLE:e}", r.step));
        }
    }
    summary
        .contact_windows
        .iter()
        .find(|w| !(fine(w.start) && fine(w.end)))
        .map(|w| format!("a contact window runs from {:e} s to {:e} s", w.start, w.end))
}

/// The default figure directory: `<stem>-figures` next to the log.
pub fn default_out_dir(mcap: &Path) -> std::path::PathBuf {
    let stem = mcap.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "log".into());
    mcap.with_file_name(format!("{stem}-figures"))
}
