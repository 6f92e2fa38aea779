//! `beam_impact.run` through the crate, without an FMU: the scenario read as `beam-impact run`
//! reads it (a file, a TOML text, the paper's or the defaults, then the dotted fields as
//! `--set`), the answer of [`beam_impact::one_run::run`] (the CLI's very path: converged peaks,
//! checks, design, the log with `answer.json`), the `run --json` document, and, when asked, every
//! recorded step kept in memory for a DataFrame. The GIL is released while the scenario's modes
//! are computed and while it steps; the calling thread watches for Ctrl-C meanwhile.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use beam_impact::answer::{Answer, Options};
use beam_impact::record::mcap::{LogChannels, McapRecorder, RecorderOptions};
use beam_impact::record::{Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::studies::sweep::{self, Axis, Row, RowResults, Setting};
use beam_impact::{scenario_file, Error, Scenario};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{columns, guard, value_error};

/// Bumped by [`cancel_running`]: every run started before stops at its next step.
static EPOCH: AtomicU64 = AtomicU64::new(0);

/// How often the calling thread looks for Ctrl-C while a run steps: short against a person's
/// patience, long against the cost of taking the GIL (microseconds).
const WATCH_INTERVAL: Duration = Duration::from_millis(50);

/// How often the calling thread looks for a [`cancel_running`] (an atomic load, no GIL): a sweep's
/// pool threads each step on for up to this long after Ctrl-C reached the main thread.
const EPOCH_INTERVAL: Duration = Duration::from_millis(5);

/// Stack of the thread that runs the answer (the size of a main thread's: the printed run steps
/// on it, as on the CLI's main thread).
const RUN_STACK_BYTES: usize = 8 << 20;

/// One field of `fields`: its dotted name and its value, a number or text read as `--set` reads it.
#[derive(FromPyObject)]
pub enum FieldValue {
    /// A Python float or int (a bool is refused before it gets here).
    Number(f64),
    /// Text: `auto`, `mean`, `converged`, a number in Rust's grammar.
    Text(String),
}

/// Where the scenario comes from.
fn base_scenario(
    path: Option<&Path>,
    text: Option<&str>,
    has_fields: bool,
    warnings: &mut Vec<String>,
) -> beam_impact::Result<Scenario> {
    match (path, text) {
        (Some(p), _) => scenario_file::read_file(p, warnings),
        // A text names its motion file relative to the current folder, as standard input does.
        (None, Some(t)) => scenario_file::from_text(t, "text", Path::new(""), warnings),
        // As a bare `beam-impact run` runs the paper's method and `--set` starts from the defaults.
        (None, None) if !has_fields => Ok(Scenario::paper()),
        (None, None) => Ok(Scenario::default()),
    }
}

/// The fields as `--set` settings (a name `sweep::field` does not know, or a value its parser
/// refuses: the CLI's message, naming the field).
fn settings(fields: Vec<(String, FieldValue)>) -> beam_impact::Result<Vec<Setting>> {
    fields
        .into_iter()
        .map(|(name, value)| {
            let field = sweep::field(&name)?;
            let value = match value {
                FieldValue::Number(v) => v,
                FieldValue::Text(t) => sweep::parse_value(field, &t)?,
            };
            Ok(Setting { field, value })
        })
        .collect()
}

/// Every `every`-th step kept (and the last), for the run's DataFrame.
struct Series {
    every: u64,
    steps: Vec<StepResult>,
    last: Option<StepResult>,
}

/// The log (if asked), the series (if asked), or neither (a recorder that keeps nothing, so the
/// steps skip the details no one reads, as `run --no-mcap`).
struct Outputs {
    log: Option<McapRecorder>,
    series: Option<Series>,
    /// The printed run's simulated time, ns, for the progress line the watching thread writes.
    reached_ns: std::sync::Arc<AtomicU64>,
}

impl Recorder for Outputs {
    fn start(&mut self, info: &RunInfo<'_>) -> beam_impact::Result<()> {
        self.log.as_mut().map_or(Ok(()), |l| l.start(info))
    }
    fn step(&mut self, result: &StepResult, q: &[f64]) -> beam_impact::Result<()> {
        self.reached_ns.store(result.time_ns, Ordering::Relaxed);
        if let Some(s) = &mut self.series {
            if result.step.is_multiple_of(s.every) {
                s.steps.push(*result);
                s.last = None;
            } else {
                s.last = Some(*result);
            }
        }
        self.log.as_mut().map_or(Ok(()), |l| l.step(result, q))
    }
    fn sample_interval_ns(&self) -> u64 {
        self.log.as_ref().map_or(0, Recorder::sample_interval_ns)
    }
    /// The dense output goes to the log; the series keeps the internal steps.
    fn sample(&mut self, result: &StepResult, q: &[f64]) -> beam_impact::Result<()> {
        self.log.as_mut().map_or(Ok(()), |l| l.sample(result, q))
    }
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> beam_impact::Result<()> {
        self.log.as_mut().map_or(Ok(()), |l| l.deflection_peak_strain(upper_strain))
    }
    fn contact_event(&mut self, event: &ContactEvent) -> beam_impact::Result<()> {
        self.log.as_mut().map_or(Ok(()), |l| l.contact_event(event))
    }
    /// A rolled-back run (an FMU's; never here) supersedes the steps after `result`.
    fn rollback(&mut self, result: &StepResult) -> beam_impact::Result<()> {
        if let Some(s) = &mut self.series {
            s.steps.retain(|r| r.step <= result.step);
            s.last = None;
        }
        self.log.as_mut().map_or(Ok(()), |l| l.rollback(result))
    }
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> beam_impact::Result<()> {
        self.log.as_mut().map_or(Ok(()), |l| l.attach(name, media_type, data))
    }
    fn finish(&mut self) -> beam_impact::Result<()> {
        if let Some(s) = &mut self.series {
            s.steps.extend(s.last.take());
        }
        self.log.as_mut().map_or(Ok(()), |l| l.finish())
    }
    fn wants_details(&self) -> bool {
        self.series.is_some() || self.log.as_ref().is_some_and(|l| l.wants_details())
    }
    fn keeps(&self, result: &StepResult) -> bool {
        self.series.is_some() || self.log.as_ref().is_some_and(|l| l.keeps(result))
    }
    fn stopped_early(&self) -> Option<&str> {
        self.log.as_ref().and_then(|l| l.stopped_early())
    }
}

/// What Python gets back: the `run --json` document as text, the series' columns (None unless
/// asked), the warnings (motion rows, the log stopped early), the log's path (None without one).
type RunOutput<'py> = (String, Option<Bound<'py, PyDict>>, Vec<String>, Option<String>);

/// One run done: the scenario as given, its answer, what it recorded, its warnings, its start.
struct Ran {
    as_given: Scenario,
    answer: Answer,
    outputs: Outputs,
    warnings: Vec<String>,
    started: Instant,
}

/// Runs one scenario as `beam-impact run` does. `scenario`: a scenario file's path; else
/// `scenario_text`: its TOML; else the paper's scenario (no fields) or the defaults. `fields`:
/// (dotted name, value) pairs applied as `--set`. `log`: the MCAP log's path (through the output
/// guard; never the scenario or motion file), None for none; `log_channels`: its topics, as
/// `run --log-channels` (ValueError naming a bad one). `series_every`: keep every N-th
/// step (and the last) for a DataFrame, 0 for none. `sensitivity`, `observed_order`: the twin
/// and the coarsest rung (a sweep's row leaves the latter out, as `beam-impact sweep`).
/// ValueError with the CLI's one-line message for a scenario, field, path or step count it
/// refuses; KeyboardInterrupt when Ctrl-C (or [`cancel_running`]) stops the run between steps;
/// RuntimeError when the run fails.
#[pyfunction]
#[pyo3(signature = (scenario=None, scenario_text=None, fields=Vec::new(), log=None, series_every=0,
    max_steps=beam_impact::model::scenario::MAX_STEPS, sensitivity=true, observed_order=true,
    log_sample_interval=None, log_channels=None))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    scenario: Option<PathBuf>,
    scenario_text: Option<String>,
    fields: Vec<(String, FieldValue)>,
    log: Option<PathBuf>,
    series_every: u64,
    max_steps: u64,
    sensitivity: bool,
    observed_order: bool,
    log_sample_interval: Option<f64>,
    log_channels: Option<String>,
) -> PyResult<RunOutput<'py>> {
    let channels = match log_channels.as_deref() {
        None => LogChannels::ALL,
        Some(text) => LogChannels::parse(text).map_err(pyo3::exceptions::PyValueError::new_err)?,
    };
    let options = RunOptions {
        series_every,
        max_steps,
        sensitivity,
        observed_order,
        log_sample_interval,
        channels,
        fatigue: false,
    };
    let ran = answer_of(py, scenario, scenario_text, fields, log.clone(), options)?;
    let doc = beam_impact::run_document::document(&ran.as_given, &ran.answer, ran.started.elapsed().as_secs_f64())
        .and_then(|d| serde_json::to_string(&d).map_err(|e| Error::Other(format!("JSON: {e}"))))
        .map_err(|e| PyRuntimeError::new_err(crate::one_line(&e.to_string())))?;
    let series = match &ran.outputs.series {
        Some(s) => Some(columns(py, &s.steps)?),
        None => None,
    };
    Ok((doc, series, ran.warnings, log.map(|p| p.display().to_string())))
}

/// How [`answer_of`] runs: see [`run`]'s arguments of the same names.
#[derive(Clone, Copy)]
struct RunOptions {
    series_every: u64,
    max_steps: u64,
    sensitivity: bool,
    observed_order: bool,
    /// The log's dense output, s (None: the default).
    log_sample_interval: Option<f64>,
    /// The log's topics.
    channels: LogChannels,
    /// Keep the printed run's stations' turning points for its fatigue (a sweep's row with
    /// `fatigue=True`; a run with a log or the observed order keeps them anyway).
    fatigue: bool,
}

/// The run of [`run`] up to its answer (the scenario read, checked, run with the GIL released
/// and Ctrl-C watched), with [`run`]'s errors.
fn answer_of(
    py: Python<'_>,
    scenario: Option<PathBuf>,
    scenario_text: Option<String>,
    fields: Vec<(String, FieldValue)>,
    log: Option<PathBuf>,
    options: RunOptions,
) -> PyResult<Ran> {
    let RunOptions { series_every, max_steps, sensitivity, observed_order, log_sample_interval, channels, fatigue } =
        options;
    let epoch = EPOCH.load(Ordering::SeqCst);
    let started = Instant::now();
    let mut warnings = Vec::new();
    let has_fields = !fields.is_empty();
    if let Some(path) = &scenario {
        crate::refuse_nul("the scenario file", path)?;
    }
    // Reading the scenario (and its motion file) and building the modes for the step check take
    // tens of ms: the GIL is released meanwhile.
    let prepared = py.detach(|| -> beam_impact::Result<(Scenario, u64)> {
        let mut s = base_scenario(scenario.as_deref(), scenario_text.as_deref(), has_fields, &mut warnings)?;
        sweep::apply_settings(&mut s, &settings(fields)?)?;
        let planned = beam_impact::one_run::check(&s, max_steps)?;
        Ok((s, planned))
    });
    let (as_given, planned_steps) = prepared.map_err(value_error)?;
    // The CLI says it before the run (issue 40): a plan of many steps is long. Written to
    // sys.stderr now, as the CLI writes it, and among the warnings at the end.
    if let Some(note) = beam_impact::one_run::large_run_note(planned_steps, as_given.duration) {
        say(py, &format!("beam_impact.run: note: {note}"));
        warnings.push(format!("note: {note}"));
    }
    let mut inputs: Vec<(String, PathBuf)> = Vec::new();
    if let Some(path) = &scenario {
        inputs.push(("the scenario file".into(), path.clone()));
    }
    if !as_given.motion.file.is_empty() {
        inputs.push(("the motion file".into(), PathBuf::from(&as_given.motion.file)));
    }
    let log_recorder = match &log {
        None => None,
        Some(path) => {
            guard("log", path, &inputs, &Vec::new(), true)?;
            let sample_interval_ns = match log_sample_interval {
                None => beam_impact::record::options::DEFAULT_SAMPLE_INTERVAL_NS,
                Some(s) => beam_impact::record::options::sample_interval_ns("log_sample_interval", s)
                    .map_err(pyo3::exceptions::PyValueError::new_err)?,
            };
            let options =
                RecorderOptions { allow_devices: true, sample_interval_ns, channels, ..RecorderOptions::default() };
            Some(McapRecorder::with_options(path, options).map_err(value_error)?)
        }
    };
    let series = (series_every > 0).then(|| Series { every: series_every, steps: Vec::new(), last: None });
    let reached_ns = std::sync::Arc::new(AtomicU64::new(0));
    let mut outputs = Outputs { log: log_recorder, series, reached_ns: reached_ns.clone() };
    let mut progress = Progress { started, said: None, end_ns: as_given.duration_ns() };
    // A sweep's row (no observed order, no log) keeps each envelope's peak only, as the CLI's
    // sweep does: the same row values for a fraction of the envelope's work.
    let station_envelope = observed_order || log.is_some() || fatigue;
    let options = Options { sensitivity, max_steps, observed_order, station_envelope, linearised_twin: true };
    let cancel = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let answer = py.detach(|| {
        std::thread::scope(|scope| {
            let worker = std::thread::Builder::new()
                .name("beam_impact.run".into())
                .stack_size(RUN_STACK_BYTES)
                .spawn_scoped(scope, || beam_impact::one_run::run(&as_given, &mut outputs, options, &cancel));
            let worker = match worker {
                Ok(w) => w,
                Err(e) => return Err(Error::Other(format!("cannot start the run's thread: {e}"))),
            };
            let mut signals_checked = Instant::now();
            while !worker.is_finished() {
                std::thread::park_timeout(EPOCH_INTERVAL);
                if interrupt.is_none() && signals_checked.elapsed() >= WATCH_INTERVAL {
                    signals_checked = Instant::now();
                    // Signal handlers run on the main thread only; elsewhere this returns Ok.
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        interrupt = Some(e);
                        cancel.store(true, Ordering::SeqCst);
                    }
                }
                if EPOCH.load(Ordering::SeqCst) != epoch {
                    cancel.store(true, Ordering::SeqCst);
                }
                if let Some(line) = progress.due(reached_ns.load(Ordering::Relaxed)) {
                    Python::attach(|py| say(py, &line));
                }
            }
            worker.join().unwrap_or_else(|_| Err(Error::Other("internal error: the run panicked".into())))
        })
    });
    if let Some(e) = interrupt {
        return Err(e);
    }
    let answer = match answer {
        Ok(a) => a,
        Err(e @ Error::Cancelled { .. }) => return Err(PyKeyboardInterrupt::new_err(crate::one_line(&e.to_string()))),
        Err(e) => return Err(PyRuntimeError::new_err(crate::one_line(&e.to_string()))),
    };
    if let Some(reason) = outputs.stopped_early() {
        warnings.push(reason.to_string());
    }
    // The CLI's warnings of an untrusted run, one line per reason (issue 41).
    warnings.extend(answer.quality.reasons.iter().map(|r| format!("results not trusted: {r}")));
    Ok(Ran { as_given, answer, outputs, warnings, started })
}

/// The axes of a sweep's grid point: one axis per varied field, holding the point's value.
fn axes_of(point: &[(String, f64)]) -> PyResult<Vec<Axis>> {
    point
        .iter()
        .map(|(name, value)| Ok(Axis { field: sweep::field(name).map_err(value_error)?, values: vec![*value] }))
        .collect()
}

/// The columns of `beam-impact sweep --out` for a grid varying `fields` (in that order): the
/// CLI's header, names and order, which the native engine's rows follow; with `fatigue`, those of
/// `sweep --fatigue`.
#[pyfunction]
#[pyo3(signature = (fields, fatigue=false))]
pub fn sweep_columns(fields: Vec<String>, fatigue: bool) -> PyResult<Vec<String>> {
    let point: Vec<(String, f64)> = fields.into_iter().map(|f| (f, 0.0)).collect();
    Ok(sweep::columns_with(&axes_of(&point)?, fatigue))
}

/// One row of `beam-impact sweep` for the grid point `point` ((dotted name, value in the
/// parameter form) per varied field), through the CLI's own row (`sweep::json_object`: its
/// columns, in its order, `sweep_columns`' names) as JSON text. The scenario is `scenario` /
/// `scenario_text` as [`run`] takes them (both None: the defaults), with `duration` set unless
/// None (a varied `duration` wins) and `point` applied; the run is a sweep's (no coarsest rung,
/// no log, the twin with `sensitivity`). A refused scenario, or a failed run, is the row of its
/// error (the CLI's message), as the CLI writes it; KeyboardInterrupt when Ctrl-C (or
/// [`cancel_running`]) stops it. With `fatigue`, the row of `sweep --fatigue` (the printed run
/// keeps its stations' turning points; the fatigue columns).
#[pyfunction]
#[pyo3(signature = (point, scenario=None, scenario_text=None, duration=None, sensitivity=false, fatigue=false))]
pub fn sweep_row(
    py: Python<'_>,
    point: Vec<(String, f64)>,
    scenario: Option<PathBuf>,
    scenario_text: Option<String>,
    duration: Option<f64>,
    sensitivity: bool,
    fatigue: bool,
) -> PyResult<String> {
    let started = Instant::now();
    let axes = axes_of(&point)?;
    let mut fields: Vec<(String, FieldValue)> =
        point.iter().map(|(name, value)| (name.clone(), FieldValue::Number(*value))).collect();
    if let Some(d) = duration.filter(|_| !point.iter().any(|(name, _)| name == "duration")) {
        fields.push(("duration".into(), FieldValue::Number(d)));
    }
    // Without a base scenario the defaults, as `beam-impact sweep` without a file and the FMU
    // start from them (not the paper's scenario a bare `run` takes).
    let text = if scenario.is_none() && scenario_text.is_none() { Some(String::new()) } else { scenario_text };
    let options = RunOptions {
        series_every: 0,
        max_steps: beam_impact::model::scenario::MAX_STEPS,
        sensitivity,
        observed_order: false,
        log_sample_interval: None,
        channels: LogChannels::ALL,
        fatigue,
    };
    let outcome = match answer_of(py, scenario, text, fields, None, options) {
        // With `fatigue`, the row's fatigue as `beam-impact sweep --fatigue` assesses it.
        Ok(ran) if fatigue => RowResults::with_fatigue(&ran.answer).map_err(|e| e.to_string()),
        Ok(ran) => Ok(RowResults::from(&ran.answer)),
        Err(e) if e.is_instance_of::<PyKeyboardInterrupt>(py) => return Err(e),
        Err(e) if e.is_instance_of::<PyValueError>(py) || e.is_instance_of::<PyRuntimeError>(py) => {
            Err(e.value(py).to_string())
        }
        Err(e) => return Err(e),
    };
    let values = point.iter().map(|(_, v)| *v).collect();
    let row = Row { values, outcome, wall_time: started.elapsed().as_secs_f64() };
    Ok(sweep::json_object_with(&axes, &row, fatigue))
}

/// Stops every run of this process at its next step (each raises KeyboardInterrupt): what a
/// sweep calls when Ctrl-C reaches its main thread while worker threads run.
#[pyfunction]
pub fn cancel_running() {
    EPOCH.fetch_add(1, Ordering::SeqCst);
}

/// How long a run goes without a word, and how often its progress line repeats: the CLI's.
const QUIET_FOR: Duration = Duration::from_secs(2);
const PROGRESS_EVERY: Duration = Duration::from_secs(10);

/// A long run's progress line, as the CLI's (issue 40 item 3: progress after two seconds).
struct Progress {
    started: Instant,
    said: Option<Instant>,
    end_ns: u64,
}

impl Progress {
    /// The line to write now, with the printed run at `reached_ns`, if one is due.
    fn due(&mut self, reached_ns: u64) -> Option<String> {
        let now = Instant::now();
        let due = match self.said {
            None => now.duration_since(self.started) >= QUIET_FOR,
            Some(at) => now.duration_since(at) >= PROGRESS_EVERY,
        };
        due.then(|| {
            self.said = Some(now);
            format!(
                "beam_impact.run: {:.4} of {:.4} s simulated, {:.0} s elapsed",
                reached_ns as f64 * 1e-9,
                self.end_ns as f64 * 1e-9,
                now.duration_since(self.started).as_secs_f64()
            )
        })
    }
}

/// Writes `line` to Python's sys.stderr (a notebook shows it; a failure to write is ignored).
fn say(py: Python<'_>, line: &str) {
    if let Ok(stderr) = py.import("sys").and_then(|sys| sys.getattr("stderr")) {
        let _ = stderr.call_method1("write", (format!("{line}\n"),));
        let _ = stderr.call_method0("flush");
    }
}
