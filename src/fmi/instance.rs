//! One FMU instance: the scenario being parameterized, the running simulation, the MCAP log and
//! the FMI state machine. `fmi2.rs` and `fmi3.rs` only translate C arguments and call in here
//! through [`Instance::guard`], which checks the allowed states, catches panics and logs errors
//! before the error status is returned.

use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use super::boundary::panic_message;
use super::description;
use super::logger::{c_string, log_with, number, significant, Logger};
use super::resource::SCENARIO_RESOURCE;
use super::state::{parameters_of, scenario_of, sections_of, Snapshot};
use super::status::{Mask, State, Status};
pub use super::variables::DEFAULT_LOG_CHANNELS;
use super::variables::{table, Column, Source, Tip, Type, Variable};
use crate::error::Error;
use crate::model::parameters::{self, find};
use crate::model::scenario::MAX_TIP_FORCE;
use crate::model::support_motion::{check_motion_value, MOTION_NAMES};
use crate::model::SupportMotion;
use crate::record::mcap::{LogChannels, McapRecorder, RecorderOptions};
use crate::record::{Recorder, RunInfo};
use crate::results::{seconds, ContactEvent, StepResult};
use crate::simulation::Advance;
use crate::solver::TipForces;
use crate::{Scenario, Simulation};

/// Which standard the instance was created through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    /// FMI 2.0 (`fmi2Instantiate`).
    Fmi2,
    /// FMI 3.0 (`fmi3InstantiateCoSimulation`).
    Fmi3,
}

/// The result of one `DoStep`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepOutcome {
    /// The step stopped at a contact change before the communication point (FMI 3 only).
    pub early_return: bool,
    /// FMU time reached, s.
    pub last_successful_time: f64,
    /// In this step the run's results stopped being trusted, its log reached its size cap or was
    /// dropped (a full disk), or a support motion disagreed with the one before (logged; return
    /// a warning).
    pub warned: bool,
}

/// Internal result: the error message is logged by [`Instance::guard`].
pub type Outcome<T> = std::result::Result<T, String>;

/// Largest |start time| and stop time the FMU accepts, s: beyond it a time step of microseconds
/// is lost in the absolute time's rounding (at 1e300 s `doStep` would return OK without
/// advancing); 1e6 s is 11.6 days of simulated impact, far beyond any run of this model.
pub const MAX_ABSOLUTE_TIME: f64 = 1e6;

/// Whether `t` is a time the FMU accepts: |t| <= [`MAX_ABSOLUTE_TIME`] (NaN is not).
fn within_time_limit(t: f64) -> bool {
    t.abs() <= MAX_ABSOLUTE_TIME
}

/// An FMU instance (the opaque `fmi2Component` / `fmi3Instance`).
pub struct Instance {
    name: String,
    version: Version,
    logger: Logger,
    logging_on: bool,
    log_events: bool,
    state: State,
    variables: Vec<Variable>,
    /// The scenario packed into the FMU's resources (`resources/scenario.toml`, issue 30) that the
    /// instance starts from; `None`: the paper scenario.
    packed: Option<Scenario>,
    scenario: Scenario,
    log_path: String,
    /// `log.channels`: the topics of the log (checked when set).
    log_channels: String,
    /// `log.sample_interval`: the log's dense output, ns (checked when set).
    log_sample_interval_ns: u64,
    simulation: Option<Simulation>,
    /// The discretisation check's runs, stepped in lockstep with `simulation` (the coarser rungs
    /// of the converged method, or the converged answer beside the paper method); `None` once a
    /// state has been restored (they hold no state of their own): not checked from there on.
    checks: Option<Vec<Simulation>>,
    /// Whether `checks` ends with the reproducibility twin (the `check_sensitivity` parameter).
    check_sensitivity: bool,
    /// The most internal steps of the run and each check run (`solver.max_steps`).
    max_steps: u64,
    recorder: Option<McapRecorder>,
    start_time: f64,
    stop_time: Option<f64>,
    event_mode_used: bool,
    early_return_allowed: bool,
    last_successful_time: f64,
    strings: Vec<CString>,
    /// The state a failed `DoStep`, `Terminate` or `ExitInitializationMode` was called in: where a
    /// successful `SetFMUState` returns to from [`State::Error`].
    before_error: State,
    /// Whether the energy residual's crossing of `energy_tolerance` has been reported (once).
    untrusted_reported: bool,
    /// Whether the MCAP log's size cap has been reported (once).
    log_cap_reported: bool,
    /// The support-motion inputs as last set (issue 17).
    motion: SupportMotion,
    /// Support-motion inputs that disagreed with the motion before them, so far.
    motion_mismatches: u64,
}

/// How many support-motion mismatches are logged one by one (the rest are counted).
const LOGGED_MISMATCHES: u64 = 10;

/// `log.path`'s start value, which stands for the default log: a new file per instance and run in
/// the user's log folder ([`default_log_dir`]), `BeamImpact-<instance>-<UTC date and time>-<n>.mcap`
/// (see [`unique_log`]). Any other path is the user's file (`./BeamImpact.mcap` for that very name).
pub const DEFAULT_LOG_PATH: &str = "BeamImpact.mcap";

/// The folder of the default logs: `$XDG_STATE_HOME/beam-impact/logs` when `XDG_STATE_HOME` is
/// an absolute path, else on Windows `%LOCALAPPDATA%\beam-impact\logs`, elsewhere
/// `$HOME/.local/state/beam-impact/logs` (the XDG base directories' place for logs). Not the working
/// directory: an SSP tool's or a test's run would litter it (and some tools run the FMU in a
/// temporary folder that is deleted afterwards). Relative values are ignored, as the XDG
/// specification says. Err says which variables were missing.
pub fn default_log_dir() -> Result<PathBuf, String> {
    let absolute = |name: &str| std::env::var_os(name).map(PathBuf::from).filter(|p| p.is_absolute());
    let tail = |base: PathBuf| base.join("beam-impact").join("logs");
    if let Some(state) = absolute("XDG_STATE_HOME") {
        return Ok(tail(state));
    }
    if cfg!(windows) {
        return absolute("LOCALAPPDATA")
            .map(tail)
            .ok_or_else(|| "neither XDG_STATE_HOME nor LOCALAPPDATA is an absolute folder".to_string());
    }
    absolute("HOME")
        .map(|home| tail(home.join(".local").join("state")))
        .ok_or_else(|| "neither XDG_STATE_HOME nor HOME is an absolute folder".to_string())
}

/// Creates the folder of the default logs with its parents (on Unix, those it creates readable
/// by the user alone, as the XDG specification asks of the state folder).
pub fn create_log_dir(dir: &Path) -> std::io::Result<()> {
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    #[cfg(unix)]
    std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
    builder.create(dir)
}

/// The instance name as it goes into a default log's name: an instance name that is a path (Ecos
/// names its instances after the FMU's file in a temporary folder) gives its last component, a
/// `.fmu` extension left off, then [`file_name_part`]: never a temporary folder's name.
pub fn log_name_part(instance_name: &str) -> String {
    let last = instance_name.rsplit(['/', '\\']).find(|s| !s.trim().is_empty()).unwrap_or("");
    file_name_part(last.strip_suffix(".fmu").unwrap_or(last))
}

/// The highest `<n>` tried for a default log name in one second before giving up (a warning).
const MAX_LOG_COUNTER: u32 = 10_000;

/// The instance name as it goes into a file name: `[A-Za-z0-9._-]` kept, anything else `_`, at most
/// 64 characters, `instance` if nothing is left.
pub fn file_name_part(instance_name: &str) -> String {
    let cleaned: String = instance_name
        .chars()
        .take(64)
        .map(|c| if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') { c } else { '_' })
        .collect();
    if cleaned.is_empty() {
        "instance".to_string()
    } else {
        cleaned
    }
}

/// `YYYYMMDDTHHMMSSZ` (UTC) of `time`.
pub fn timestamp(time: SystemTime) -> String {
    let seconds = time.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, second_of_day) = (seconds.div_euclid(86_400), seconds.rem_euclid(86_400));
    // Days since 1970-01-01 to the civil (proleptic Gregorian) date, in 400-year eras.
    let z = days + 719_468;
    let (era, day_of_era) = (z.div_euclid(146_097), z.rem_euclid(146_097));
    let year_of_era = (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_from_march = (5 * day_of_year + 2) / 153;
    let day = day_of_year - (153 * month_from_march + 2) / 5 + 1;
    let month = if month_from_march < 10 { month_from_march + 3 } else { month_from_march - 9 };
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    let (hour, minute, second) = (second_of_day / 3600, second_of_day / 60 % 60, second_of_day % 60);
    format!("{year:04}{month:02}{day:02}T{hour:02}{minute:02}{second:02}Z")
}

/// Reserves a new log name `BeamImpact-<instance>-<timestamp>-<n>.mcap` in `dir` (`<instance>`:
/// [`log_name_part`]), `n` = 1, 2, ...
/// the first name that does not exist yet, by creating its empty `NAME.partial` with
/// `create_new`: two instances or processes never get the same one and no file is overwritten.
pub fn unique_log(dir: &Path, instance_name: &str, now: SystemTime) -> std::io::Result<PathBuf> {
    let stem = format!("BeamImpact-{}-{}", log_name_part(instance_name), timestamp(now));
    for n in 1..=MAX_LOG_COUNTER {
        let path = dir.join(format!("{stem}-{n}.mcap"));
        if path.exists() {
            continue;
        }
        // The reservation is the log's partial file (renamed to the name when the log is
        // finished), so a killed instance leaves no empty NAME behind.
        match std::fs::OpenOptions::new().write(true).create_new(true).open(crate::record::output::partial_path(&path))
        {
            Ok(_) => return Ok(path),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other(format!("{stem}-1.mcap to {stem}-{MAX_LOG_COUNTER}.mcap all exist")))
}

/// The longest run the scenario's `duration` accepts, s (it only labels the MCAP log here).
const MAX_DURATION: f64 = 1e6;

/// Communication points closer than this to the FMU's time are the same point, s (time is kept
/// in integer nanoseconds; importers accumulate rounding, e.g. steps of 0.009999999999999998).
pub const TIME_TOLERANCE: f64 = 1e-9;

fn time_tolerance(t: f64) -> f64 {
    TIME_TOLERANCE + 1e-12 * t.abs()
}

/// Forwards every step to the MCAP log (if any) and keeps the contact events for `logEvents`.
/// An error of the log (a full disk) never reaches the simulation: it is kept in `failed`, nothing
/// more is sent to the log, and the instance drops the log after the call ([`Instance::drop_log`]):
/// the co-simulation goes on without it (issue 27).
struct Tap<'a> {
    inner: Option<&'a mut McapRecorder>,
    events: Vec<ContactEvent>,
    failed: Option<Error>,
}

impl<'a> Tap<'a> {
    fn new(inner: Option<&'a mut McapRecorder>) -> Self {
        Tap { inner, events: Vec::new(), failed: None }
    }

    /// Sends one call to the log while it is written; its first error stops the log, not the run.
    fn send(&mut self, call: impl FnOnce(&mut McapRecorder) -> crate::Result<()>) -> crate::Result<()> {
        if let Some(recorder) = self.inner.as_deref_mut() {
            if let Err(e) = call(recorder) {
                self.failed = Some(e);
                self.inner = None;
            }
        }
        Ok(())
    }
}

impl Recorder for Tap<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> crate::Result<()> {
        self.send(|r| r.start(info))
    }
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> crate::Result<()> {
        self.send(|r| r.step(result, modal_coordinates))
    }
    fn sample_interval_ns(&self) -> u64 {
        self.inner.as_deref().map_or(0, Recorder::sample_interval_ns)
    }
    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> crate::Result<()> {
        self.send(|r| r.sample(result, modal_coordinates))
    }
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> crate::Result<()> {
        self.send(|r| r.deflection_peak_strain(upper_strain))
    }
    fn contact_event(&mut self, event: &ContactEvent) -> crate::Result<()> {
        self.events.push(*event);
        self.send(|r| r.contact_event(event))
    }
    fn rollback(&mut self, result: &StepResult) -> crate::Result<()> {
        self.send(|r| r.rollback(result))
    }
    fn wants_details(&self) -> bool {
        self.inner.is_some()
    }
    fn keeps(&self, result: &StepResult) -> bool {
        self.inner.as_deref().is_some_and(|r| r.keeps(result))
    }
    fn finish(&mut self) -> crate::Result<()> {
        self.send(|r| r.finish())
    }
}

/// Two optional warnings as one.
fn both(a: Option<String>, b: Option<String>) -> Option<String> {
    match (a, b) {
        (Some(a), Some(b)) => Some(format!("{a}; {b}")),
        (a, b) => a.or(b),
    }
}

impl Instance {
    /// A new instance in state Instantiated with the paper scenario.
    pub fn new(name: &str, version: Version, logger: Logger, logging_on: bool) -> Self {
        Self::starting_from(name, version, logger, logging_on, None)
    }

    /// A new instance in state Instantiated with `packed`, the scenario of the FMU's
    /// `resources/scenario.toml` (issue 30), as its starting scenario (`None`: the paper's): the
    /// parameters and inputs start at its values, and the importer's parameters override them.
    pub fn starting_from(
        name: &str,
        version: Version,
        logger: Logger,
        logging_on: bool,
        packed: Option<Scenario>,
    ) -> Self {
        let scenario = packed.clone().unwrap_or_default();
        Instance {
            name: name.to_string(),
            version,
            logger,
            logging_on,
            log_events: true,
            state: State::Instantiated,
            variables: table(),
            packed,
            scenario,
            log_path: DEFAULT_LOG_PATH.to_string(),
            log_channels: DEFAULT_LOG_CHANNELS.to_string(),
            log_sample_interval_ns: crate::record::options::DEFAULT_SAMPLE_INTERVAL_NS,
            simulation: None,
            checks: None,
            check_sensitivity: false,
            max_steps: crate::model::scenario::MAX_STEPS,
            recorder: None,
            start_time: 0.0,
            stop_time: None,
            event_mode_used: false,
            early_return_allowed: false,
            last_successful_time: 0.0,
            strings: Vec::new(),
            before_error: State::Instantiated,
            untrusted_reported: false,
            log_cap_reported: false,
            motion: SupportMotion::default(),
            motion_mismatches: 0,
        }
    }

    /// FMI 3 co-simulation options given at instantiation.
    pub fn set_cosimulation_options(&mut self, event_mode_used: bool, early_return_allowed: bool) {
        self.event_mode_used = event_mode_used;
        self.early_return_allowed = early_return_allowed;
    }

    /// Logs (category `logEvents`, with logging on) where the importer unpacked the resources and
    /// which scenario the instance starts from: the one of `resources/scenario.toml` (issue 30),
    /// or the paper's when there is none.
    pub fn log_resources(&self, given: Option<&str>, parsed: Option<PathBuf>) {
        let start = match &self.packed {
            Some(s) => {
                let count = |n: usize| if n == 1 { "1 section".to_string() } else { format!("{n} sections") };
                format!(
                    "the FMU starts from its packed scenario resources/{SCENARIO_RESOURCE} (bridge: {}, arrestor: {})",
                    if s.upper.sections.is_empty() { "uniform".to_string() } else { count(s.upper.sections.len()) },
                    if s.lower.sections.is_empty() { "uniform".to_string() } else { count(s.lower.sections.len()) },
                )
            }
            None => format!("no {SCENARIO_RESOURCE} there: the FMU starts from the paper scenario"),
        };
        let message = match (given, parsed) {
            (None, _) => "no resource location given (the FMU starts from the paper scenario)".to_string(),
            (Some(given), Some(dir)) => {
                format!("resource location \"{given}\" is the directory {} ({start})", dir.display())
            }
            (Some(given), None) => format!(
                "resource location \"{given}\" is not a local directory (the FMU starts from the paper scenario)"
            ),
        };
        self.log(Status::Ok, "logEvents", &message);
    }

    /// The current state.
    pub fn state(&self) -> State {
        self.state
    }

    /// Logs a message (errors and warnings always; events only with logging on and the category enabled).
    pub fn log(&self, status: Status, category: &str, message: &str) {
        if status == Status::Ok && !(self.logging_on && self.log_events) {
            return;
        }
        log_with(self.logger, &self.name, status, category, message);
    }

    /// Logs an error and returns [`Status::Error`].
    pub fn error(&self, message: &str) -> Status {
        self.log(Status::Error, Status::Error.category(), message);
        Status::Error
    }

    /// Runs `work` if the instance is in one of `allowed`'s states; logs an illegal call sequence,
    /// an error message or a caught panic (which makes the instance Fatal) before returning the status.
    pub fn guard(&mut self, function: &str, allowed: Mask, work: impl FnOnce(&mut Self) -> Outcome<Status>) -> Status {
        self.guarded(function, allowed, false, work)
    }

    /// [`Instance::guard`] for a setter (issue 40): called in a state where it is not allowed,
    /// the refusal also names what the call was to set, `refused(self)` (see
    /// [`Instance::to_be_set`]), not only the function.
    pub fn guard_set(
        &mut self,
        function: &str,
        allowed: Mask,
        refused: impl FnOnce(&Self) -> String,
        work: impl FnOnce(&mut Self) -> Outcome<Status>,
    ) -> Status {
        if !allowed.contains(self.state) {
            let what = refused(self);
            return self.error(&format!(
                "{function} is not allowed in state {} (illegal call sequence): {what}",
                self.state.name()
            ));
        }
        self.guard(function, allowed, work)
    }

    /// What a refused setter call was to set, for its message: the first of `vrs` by name and
    /// value reference with `first`, its value as shown ([`Shown`]), and how many more.
    pub fn to_be_set(&self, vrs: &[u32], first: Option<String>) -> String {
        let (Some(&vr), Some(value)) = (vrs.first(), first) else {
            return "no value reference was given".into();
        };
        let variable = match self.variables.get(vr as usize) {
            Some(v) => format!("`{}` (value reference {vr})", v.name),
            None => format!("unknown value reference {vr}"),
        };
        let more = match vrs.len() - 1 {
            0 => String::new(),
            n => format!(", nor {n} more value reference(s)"),
        };
        format!("{variable} = {value} is not set{more}")
    }

    /// [`Instance::guard`] for `DoStep`, `Terminate` and `ExitInitializationMode`: an error (not an
    /// illegal call sequence, which changes nothing) puts the instance in [`State::Error`].
    pub fn guard_run(
        &mut self,
        function: &str,
        allowed: Mask,
        work: impl FnOnce(&mut Self) -> Outcome<Status>,
    ) -> Status {
        self.guarded(function, allowed, true, work)
    }

    fn guarded(
        &mut self,
        function: &str,
        allowed: Mask,
        failure_is_error_state: bool,
        work: impl FnOnce(&mut Self) -> Outcome<Status>,
    ) -> Status {
        if !allowed.contains(self.state) {
            let why = if allowed == Mask::NONE {
                "is not supported by this FMU".to_string()
            } else {
                format!("is not allowed in state {} (illegal call sequence)", self.state.name())
            };
            return self.error(&format!("{function} {why}"));
        }
        let before = self.state;
        let status = match catch_unwind(AssertUnwindSafe(|| work(self))) {
            Ok(Ok(status)) => status,
            Ok(Err(message)) => self.error(&format!("{function}: {message}")),
            Err(payload) => {
                self.state = State::Fatal;
                let message = format!("{function}: internal error: {}", panic_message(payload.as_ref()));
                self.log(Status::Fatal, Status::Fatal.category(), &message);
                return Status::Fatal;
            }
        };
        if failure_is_error_state && status == Status::Error {
            self.before_error = before;
            self.state = State::Error;
        }
        status
    }

    /// `SetDebugLogging`: an empty category list switches every category.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Outcome<Status> {
        self.logging_on = on;
        for c in categories {
            match c.as_str() {
                "logEvents" => self.log_events = on,
                "logStatusWarning" | "logStatusDiscard" | "logStatusError" | "logStatusFatal" => {}
                other => {
                    return Err(format!(
                        "unknown log category `{other}` (this FMU has logEvents, logStatusWarning, \
                         logStatusDiscard, logStatusError, logStatusFatal)"
                    ))
                }
            }
        }
        if categories.is_empty() {
            self.log_events = on;
        }
        Ok(Status::Ok)
    }

    /// `SetupExperiment` / the time arguments of FMI 3's `EnterInitializationMode`.
    pub fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Outcome<Status> {
        if !within_time_limit(start_time) {
            return Err(format!("startTime must be within +-{MAX_ABSOLUTE_TIME:e} s, got {}", number(start_time)));
        }
        if let Some(stop) = stop_time {
            if !(within_time_limit(stop) && stop >= start_time) {
                return Err(format!(
                    "stopTime must be >= startTime = {} and within +-{MAX_ABSOLUTE_TIME:e} s, got {}",
                    number(start_time),
                    number(stop)
                ));
            }
        }
        self.start_time = start_time;
        self.stop_time = stop_time;
        // The run's length only labels the scenario recorded in the MCAP log (`duration` is not an
        // FMU parameter): taken from the stop time when the scenario accepts it.
        if let Some(length) = stop_time.map(|stop| stop - start_time).filter(|&l| l > 0.0 && l <= MAX_DURATION) {
            self.scenario.duration = length;
        }
        self.last_successful_time = start_time;
        Ok(Status::Ok)
    }

    /// `EnterInitializationMode`.
    pub fn enter_initialization(&mut self) -> Outcome<Status> {
        self.state = State::Initialization;
        Ok(Status::Ok)
    }

    /// Every invalid parameter, each named with [`Scenario::validate`]'s message: validate, set the
    /// offending parameter back to its start value (the starting scenario's) in a scratch copy, repeat.
    fn invalid_parameters(&self) -> Vec<String> {
        let mut scratch = self.scenario.clone();
        let defaults = self.packed.clone().unwrap_or_default();
        let mut messages = Vec::new();
        let mut named: Vec<std::borrow::Cow<'static, str>> = Vec::new();
        while let Err(e) = scratch.validate() {
            messages.push(e.to_string());
            let Error::InvalidParameter { name, .. } = e else { break };
            if named.contains(&name) {
                break;
            }
            named.push(name.clone());
            match find(&name) {
                Ok(p) => {
                    if (p.put)(&mut scratch, (p.get)(&defaults)).is_err() {
                        break;
                    }
                }
                Err(_) if name == "upper.tip_force" => scratch.upper.tip_force = 0.0,
                Err(_) if name == "lower.tip_force" => scratch.lower.tip_force = 0.0,
                Err(_) => break,
            }
        }
        messages
    }

    /// The simulation, built from the parameters on first use (validating them).
    fn simulation(&mut self) -> Outcome<&mut Simulation> {
        if self.simulation.is_none() {
            let invalid = self.invalid_parameters();
            if let Some((last, others)) = invalid.split_last() {
                for message in others {
                    self.error(&format!("invalid parameter: {message}"));
                }
                return Err(format!("invalid parameter: {last}"));
            }
            let mut simulation = Simulation::starting_with(&self.scenario, self.motion)
                .map_err(|e| format!("invalid parameters: {e}"))?;
            simulation.set_max_steps(self.max_steps);
            let checks = self
                .check_runs(&self.scenario)
                .map_err(|e| format!("invalid parameters (discretisation check): {e}"))?;
            self.simulation = Some(simulation);
            self.checks = Some(checks);
        }
        self.simulation.as_mut().ok_or_else(|| "no simulation".to_string())
    }

    /// Whether the instance went through `ExitInitializationMode` (or restored a state taken after
    /// it): Event, Step or Terminated, or Error after a failure in one of them.
    fn initialized(&self) -> bool {
        let state = if self.state == State::Error { self.before_error } else { self.state };
        matches!(state, State::Event | State::Step | State::Terminated)
    }

    /// The MCAP log of a run that starts now (initialization, or a state restored into an instance
    /// that was not initialized). `log.path` = `""`: none. [`DEFAULT_LOG_PATH`]: a new file with a
    /// unique name in the user's log folder ([`default_log_dir`], [`unique_log`]); a folder that
    /// cannot take it is a warning (returned, to be logged) and no log. Any other path is the user's
    /// file, created or truncated (an error if that fails, or if another run writes it). The topics
    /// are `log.channels`'. The model description is attached, and where the log goes is logged
    /// (logEvents), its full path.
    fn open_log(&self) -> Outcome<(Option<McapRecorder>, Option<String>)> {
        if self.log_path.is_empty() {
            return Ok((None, None));
        }
        let channels = LogChannels::parse(&self.log_channels)?;
        let options =
            RecorderOptions { channels, sample_interval_ns: self.log_sample_interval_ns, ..RecorderOptions::default() };
        let tool = description::generation_tool(None);
        let xml = match self.version {
            Version::Fmi2 => description::fmi2_for(self.packed.as_ref(), &tool),
            Version::Fmi3 => description::fmi3_for(self.packed.as_ref(), &tool),
        };
        let attach = |mut recorder: McapRecorder| {
            recorder.attach("modelDescription.xml", "application/xml", xml.as_bytes()).map(|()| recorder)
        };
        let topics = if channels == LogChannels::ALL { String::new() } else { format!(", topics {channels}") };
        if self.log_path != DEFAULT_LOG_PATH {
            let path = Path::new(&self.log_path);
            let recorder = McapRecorder::with_options(path, options)
                .and_then(attach)
                .map_err(|e| format!("log.path = \"{}\": {e}", self.log_path))?;
            let full = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
            self.log(Status::Ok, "logEvents", &format!("MCAP log of the run: {}{topics}", full.display()));
            return Ok((Some(recorder), None));
        }
        let no_log = |why: String| {
            format!(
                "log.path = \"{DEFAULT_LOG_PATH}\" (the default, a new file per instance and run in the user's log \
                 folder): {why}; the run goes on without an MCAP log (set log.path to a writable file, or \"\" for no \
                 log)"
            )
        };
        let dir = match default_log_dir() {
            Ok(dir) => dir,
            Err(why) => return Ok((None, Some(no_log(format!("no log folder: {why}"))))),
        };
        let reserved = create_log_dir(&dir).and_then(|()| unique_log(&dir, &self.name, SystemTime::now()));
        let path = match reserved {
            Ok(path) => path,
            Err(e) => return Ok((None, Some(no_log(format!("cannot create a log in {}: {e}", dir.display()))))),
        };
        match McapRecorder::with_options(&path, options).and_then(attach) {
            Ok(recorder) => {
                self.log(
                    Status::Ok,
                    "logEvents",
                    &format!(
                        "MCAP log of the run: {}{topics} (log.path is the default \"{DEFAULT_LOG_PATH}\": a \
                         new file per instance and run)",
                        path.display()
                    ),
                );
                Ok((Some(recorder), None))
            }
            Err(e) => {
                // The reservation is ours (created empty by unique_log): do not leave it behind.
                let _ = std::fs::remove_file(crate::record::output::partial_path(&path));
                Ok((None, Some(no_log(e.to_string()))))
            }
        }
    }

    /// Sends the run's description and its latest step (step 0 after initialization, the restored
    /// step after a restore) to the MCAP log, if any; a log that fails is dropped (the warning
    /// returned, to be logged).
    fn start_log(&mut self) -> Outcome<Option<String>> {
        let simulation = self.simulation.as_mut().ok_or("no simulation")?;
        let mut tap = Tap::new(self.recorder.as_mut());
        simulation.start_recording(&mut tap).map_err(|e| format!("MCAP log: {e}"))?;
        let failed = tap.failed.take();
        Ok(failed.map(|e| self.drop_log(&e)))
    }

    /// Drops the MCAP log after its error `e` (a full disk, issue 27): the log is finished as the
    /// recorder's rules say (one that failed stays `NAME.partial`, which `report` reads as a log
    /// cut short; an earlier NAME is left as it was), and the run goes on without a log. Returns
    /// the warning to log, naming the file, the reason and what is left of it.
    fn drop_log(&mut self, e: &Error) -> String {
        let Some(mut recorder) = self.recorder.take() else {
            return format!("the MCAP log failed ({e}); the run goes on without a log");
        };
        let (path, written) = (recorder.path().to_path_buf(), recorder.file_being_written().to_path_buf());
        let left = match recorder.finish() {
            Ok(()) => format!("what it holds is complete in {}", path.display()),
            Err(_) if written != path && written.exists() => {
                format!("what was written stays in {} (a log cut short)", written.display())
            }
            Err(_) => "what was written is left as it is".to_string(),
        };
        format!(
            "the MCAP log {} cannot be written ({e}): it is dropped, {left}; the run goes on without a log",
            path.display()
        )
    }

    /// `ExitInitializationMode`: builds the model, opens the MCAP log and records the initial state.
    /// A default log that cannot be created is a warning (the run goes on without it).
    pub fn exit_initialization(&mut self) -> Outcome<Status> {
        let (duration, duration_ns) = (self.scenario.duration, self.scenario.duration_ns());
        let planned_steps = self.simulation()?.step_estimate(duration_ns);
        // What may make the run long is said before the first doStep, as the CLI says it (issue 40):
        // the steps its plan takes over the run's duration (stopTime - startTime when given).
        if let Some(note) = crate::one_run::large_run_note(planned_steps, duration) {
            self.log(Status::Warning, Status::Warning.category(), &format!("note: {note}"));
        }
        // A resource scenario's load cases (issue 44) need a converged answer per case, which
        // `beam-impact run` gives; the FMU's design.pass is the plain check, and says so.
        if !self.scenario.load_cases.is_empty() {
            self.log(
                Status::Warning,
                Status::Warning.category(),
                &format!(
                    "note: the scenario's {} load case(s) are not judged by the FMU: design.pass and utilisation.* \
                     are the plain design check; `beam-impact run` judges the cases",
                    self.scenario.load_cases.len()
                ),
            );
        }
        let (recorder, warning) = self.open_log()?;
        self.recorder = recorder;
        let dropped = self.start_log()?;
        self.last_successful_time = self.time();
        self.state = if self.event_mode_used { State::Event } else { State::Step };
        Ok(self.warn(both(warning, dropped)))
    }

    /// FMI 3 `EnterEventMode`.
    pub fn enter_event_mode(&mut self) -> Outcome<Status> {
        if !self.event_mode_used {
            return Err("the instance was created with eventModeUsed = false".into());
        }
        self.state = State::Event;
        Ok(Status::Ok)
    }

    /// FMI 3 `EnterStepMode`.
    pub fn enter_step_mode(&mut self) -> Outcome<Status> {
        self.state = State::Step;
        Ok(Status::Ok)
    }

    /// The FMU's time, s.
    pub fn time(&self) -> f64 {
        self.start_time + seconds(self.simulation.as_ref().map_or(0, |s| s.output().time_ns))
    }

    /// `fmi2LastSuccessfulTime` / FMI 3's `lastSuccessfulTime`, s.
    pub fn last_successful_time(&self) -> f64 {
        self.last_successful_time
    }

    /// `DoStep`: advances to `current + step` in internal steps, landing exactly on it; with
    /// `early_return` (FMI 3, if allowed) stops at a contact change.
    pub fn do_step(&mut self, current: f64, step: f64) -> Outcome<StepOutcome> {
        let now = self.time();
        if !(current.is_finite() && step.is_finite() && step > 0.0) {
            return Err(format!(
                "the communication step must be finite and > 0 s, got currentCommunicationPoint = {}, \
                 communicationStepSize = {}",
                number(current),
                number(step)
            ));
        }
        if (current - now).abs() > time_tolerance(now) {
            return Err(format!(
                "currentCommunicationPoint = {} s is not the FMU's time {} s (tolerance {:e} s)",
                number(current),
                number(now),
                time_tolerance(now)
            ));
        }
        let end = current + step;
        if let Some(stop) = self.stop_time {
            if end > stop + time_tolerance(stop) {
                return Err(format!("the step ends at {} s, after stopTime = {} s", number(end), number(stop)));
            }
        }
        let target_ns = ((end - self.start_time) * 1e9).round();
        if !(0.0..=1.8e19).contains(&target_ns) {
            return Err(format!("the step ends at {} s, outside the FMU's time range", number(end)));
        }
        let target_ns = target_ns as u64;
        let early = self.version == Version::Fmi3 && self.early_return_allowed;
        let mismatch = self.simulation.as_ref().ok_or("no simulation")?.motion_mismatch();
        let mut mismatched = false;
        if let Some(m) = mismatch {
            self.motion_mismatches += 1;
            mismatched = true;
            if self.motion_mismatches <= LOGGED_MISMATCHES {
                let more = if self.motion_mismatches == LOGGED_MISMATCHES {
                    " (further mismatches are counted, not logged)"
                } else {
                    ""
                };
                self.log(
                    Status::Warning,
                    Status::Warning.category(),
                    &format!("support motion at t = {} s: {m}; the values are used as given{more}", number(current)),
                );
            }
        }
        let simulation = self.simulation.as_mut().ok_or("no simulation")?;
        let mut tap = Tap::new(self.recorder.as_mut());
        // The stop time ends the run as the CLI's does (`finish_at`: the converged method records
        // the stop point inside its step grid); elsewhere the outputs are interpolated.
        let at_stop = self.stop_time.is_some_and(|stop| (end - stop).abs() <= time_tolerance(stop));
        let advance = if at_stop {
            simulation.finish_at(target_ns, &mut tap, early)
        } else {
            simulation.advance_outputs_to(target_ns, &mut tap, early)
        };
        if advance.is_ok() {
            let reached = simulation.output().time_ns;
            let forces = simulation.state().forces;
            let motion = simulation.state().input_motion;
            for check in self.checks.iter_mut().flatten() {
                check.set_tip_forces(forces);
                check.set_support_motion(motion);
                let moved = if at_stop {
                    check.finish_at(reached, &mut crate::record::NullRecorder, false)
                } else {
                    check.advance_outputs_to(reached, &mut crate::record::NullRecorder, false)
                };
                if let Err(e) = moved {
                    return Err(format!("the discretisation check's run: {e}"));
                }
            }
        }
        let events = std::mem::take(&mut tap.events);
        // A log that failed (a full disk) is dropped with a warning; the step stands (issue 27).
        let log_dropped = tap.failed.take().map(|e| self.drop_log(&e));
        if let Some(warning) = &log_dropped {
            self.log(Status::Warning, Status::Warning.category(), warning);
        }
        for e in &events {
            self.log(
                Status::Ok,
                "logEvents",
                &format!(
                    "t = {:.9} s (step {}): contact {} (relative velocity {} m/s)",
                    self.start_time + seconds(e.time_ns),
                    e.step,
                    if e.start { "starts" } else { "ends" },
                    significant(e.relative_velocity, 5)
                ),
            );
        }
        let time = self.time();
        self.last_successful_time = time;
        let advance = advance.map_err(|e| e.to_string())?;
        let early_return = advance == Advance::ContactChanged && time < end - time_tolerance(end);
        if early_return {
            self.log(Status::Ok, "logEvents", &format!("early return at t = {time:.9} s (contact change)"));
        }
        let mut capped_now = false;
        if let Some(reason) = self.recorder.as_ref().and_then(|r| r.capped()).map(str::to_owned) {
            if !self.log_cap_reported {
                self.log_cap_reported = true;
                capped_now = true;
                self.log(Status::Warning, Status::Warning.category(), &reason);
            }
        }
        let quality = self.simulation.as_ref().ok_or("no simulation")?.quality();
        let mut reasons = quality.reasons.clone();
        // The discretisation figure speaks of the whole run's peaks (the early running peaks of
        // the first contact transients differ between rungs by far more): judged at the stop time.
        let (figure, tolerance) = (self.discretisation_error(), self.scenario.discretisation_tolerance);
        if at_stop && figure > tolerance {
            reasons.push(format!(
                "a running peak changes by {} against the discretisation check (> discretisation_tolerance = {})",
                crate::answer::percent(figure),
                crate::answer::percent(tolerance)
            ));
        }
        let spread = self.sensitivity_spread();
        if at_stop && spread > tolerance {
            reasons.push(format!(
                "a drop height changed by 1e-9 moves a running peak by {} (> discretisation_tolerance = {}): not \
                 reproducible",
                crate::answer::percent(spread),
                crate::answer::percent(tolerance)
            ));
        }
        if let Some(c) = self.yield_check() {
            if !c.pass {
                reasons.push(format!(
                    "the stresses reach {} of the yield stress: the elastic model is out of its range",
                    crate::answer::percent(c.value)
                ));
            }
        }
        let untrusted = !reasons.is_empty() && !self.untrusted_reported;
        if untrusted {
            self.untrusted_reported = true;
            self.log(
                Status::Warning,
                Status::Warning.category(),
                &format!("at t = {} s the results are no longer trusted: {}", number(time), reasons.join("; ")),
            );
        }
        Ok(StepOutcome {
            early_return,
            last_successful_time: time,
            warned: untrusted || capped_now || mismatched || log_dropped.is_some(),
        })
    }

    /// Completes the MCAP log. A log that cannot be completed (a full disk) is a warning, returned
    /// to be logged: the run's results stand, and the part written stays `NAME.partial`.
    fn finish_log(&mut self) -> Option<String> {
        let mut recorder = self.recorder.take()?;
        let written = recorder.file_being_written().to_path_buf();
        let e = recorder.finish().err()?;
        let path = recorder.path();
        let left = if written != path && written.exists() {
            format!("what was written stays in {} (a log cut short)", written.display())
        } else {
            "what was written is left as it is".to_string()
        };
        Some(format!("the MCAP log {} cannot be completed ({e}): {left}", path.display()))
    }

    /// `Terminate`: completes the MCAP log (a log that cannot be completed is a warning).
    pub fn terminate(&mut self) -> Outcome<Status> {
        self.state = State::Terminated;
        let warning = self.finish_log();
        Ok(self.warn(warning))
    }

    /// `Reset`: back to Instantiated with the starting scenario (the packed one, or the paper's;
    /// completing an open log first; one that cannot be completed is a warning).
    pub fn reset(&mut self) -> Outcome<Status> {
        let warning = self.finish_log();
        let (name, version, logger, logging_on) = (self.name.clone(), self.version, self.logger, self.logging_on);
        let (event_mode_used, early_return_allowed) = (self.event_mode_used, self.early_return_allowed);
        *self = Instance::starting_from(&name, version, logger, logging_on, self.packed.take());
        self.set_cosimulation_options(event_mode_used, early_return_allowed);
        Ok(self.warn(warning))
    }

    /// Called by `FreeInstance`: completes the log if `Terminate` was not called, logging a log
    /// that cannot be completed as a warning.
    pub fn free(&mut self) {
        if let Some(warning) = self.finish_log() {
            self.log(Status::Warning, Status::Warning.category(), &format!("FreeInstance: {warning}"));
        }
    }

    fn variable(&self, vr: u32, ty: Type) -> Outcome<Variable> {
        let v = self
            .variables
            .get(vr as usize)
            .ok_or_else(|| format!("unknown value reference {vr} (this FMU has 0..{})", self.variables.len() - 1))?;
        if v.ty != ty {
            let name = |t: Type| if self.version == Version::Fmi2 { t.fmi2_name() } else { t.fmi3_name() };
            return Err(format!("value reference {vr} is `{}`, a {} variable, not {}", v.name, name(v.ty), name(ty)));
        }
        Ok(v.clone())
    }

    fn forces(&self) -> TipForces {
        match &self.simulation {
            Some(s) if self.state != State::Instantiated && self.state != State::Initialization => s.state().forces,
            _ => TipForces { upper: self.scenario.upper.tip_force, lower: self.scenario.lower.tip_force },
        }
    }

    /// The simulation behind an output or a calculated parameter: built from the parameters from
    /// initialization mode on, never before (FMI 3 allows reads in Instantiated, where only the
    /// parameters and inputs have values).
    fn computed(&mut self, name: &str) -> Outcome<&mut Simulation> {
        match self.state {
            State::Instantiated => Err(format!(
                "`{name}` is available after initialization (from EnterInitializationMode on); \
                 in state Instantiated only parameters and inputs have values"
            )),
            State::Error | State::Fatal if self.simulation.is_none() => {
                Err(format!("`{name}` is not available: the model could not be built (see the error before)"))
            }
            _ => self.simulation(),
        }
    }

    /// Reads a Real / Float64 variable.
    pub fn get_real(&mut self, vr: u32) -> Outcome<f64> {
        let v = self.variable(vr, Type::Real)?;
        Ok(match v.source {
            Source::Time => self.time(),
            Source::Parameter(p) => (p.get)(&self.scenario),
            Source::LogSampleInterval => self.log_sample_interval_ns as f64 * 1e-9,
            Source::Input(Tip::Upper) => self.forces().upper,
            Source::Input(Tip::Lower) => self.forces().lower,
            Source::Motion(k) => self.motion.values()[k],
            Source::Output(get) => get(self.computed(&v.name)?.output()),
            Source::Mode(column, k) => {
                let table = self.computed(&v.name)?.mode_table(super::variables::MODES);
                let (list, what) = match column {
                    Column::Lower => (table.lower, "the arrestor"),
                    Column::Upper => (table.upper, "the bridge"),
                    Column::Coupled => (table.coupled, "the coupled system"),
                };
                *list
                    .get(k)
                    .ok_or_else(|| format!("{}: {what} has only {} modes with this mesh", v.name, list.len()))?
            }
            Source::EnergyMethod(get) => get(self.computed(&v.name)?.energy_method()),
            Source::Utilisation(k) => {
                let simulation = self.computed(&v.name)?;
                let (peaks, envelope) = (simulation.output().peaks, simulation.envelope());
                crate::answer::Design::assess(&self.scenario, &peaks, &envelope).utilisation.as_array()[k]
            }
            Source::DiscretisationError => {
                self.computed(&v.name)?;
                self.discretisation_error()
            }
            Source::SensitivitySpread => {
                self.computed(&v.name)?;
                self.sensitivity_spread()
            }
            Source::Impact(get) => get(&self.computed(&v.name)?.impact()),
            // A beam without such a stress (the bridge without a shear area, a rigid support) or
            // without an allowable: 0, as the descriptions say.
            Source::EnvelopePeak(k) => self.computed(&v.name)?.envelope().peaks()[k].map_or(0.0, |p| p.value),
            Source::EnvelopePosition(k) => self.computed(&v.name)?.envelope().peaks()[k].map_or(0.0, |p| p.position),
            Source::EnvelopeUtilisation(k) => {
                self.computed(&v.name)?.envelope().peaks()[k].and_then(|p| p.utilisation).unwrap_or(0.0)
            }
            Source::LogPath
            | Source::LogChannels
            | Source::ContactActive
            | Source::DesignPass
            | Source::Trusted
            | Source::MaxSteps
            | Source::CheckSensitivity => return Err(format!("`{}` is not Real", v.name)),
        })
    }

    /// Reads an Integer / Int32 variable.
    pub fn get_integer(&mut self, vr: u32) -> Outcome<i32> {
        let v = self.variable(vr, Type::Integer)?;
        match v.source {
            Source::Parameter(p) => Ok((p.get)(&self.scenario) as i32),
            Source::MaxSteps => Ok(i32::try_from(self.max_steps).unwrap_or(i32::MAX)),
            _ => Err(format!("`{}` is not an Integer", v.name)),
        }
    }

    /// Reads a Boolean variable.
    pub fn get_boolean(&mut self, vr: u32) -> Outcome<bool> {
        let v = self.variable(vr, Type::Boolean)?;
        match v.source {
            Source::ContactActive => Ok(self.computed(&v.name)?.output().contact),
            Source::DesignPass => {
                let simulation = self.computed(&v.name)?;
                let (peaks, envelope) = (simulation.output().peaks, simulation.envelope());
                Ok(crate::answer::Design::assess(&self.scenario, &peaks, &envelope).pass)
            }
            Source::Trusted => {
                let energy = self.computed(&v.name)?.quality().trusted;
                let figure = self.discretisation_error();
                Ok(energy
                    && figure <= self.scenario.discretisation_tolerance
                    && self.sensitivity_spread() <= self.scenario.discretisation_tolerance
                    && self.yield_check().is_none_or(|c| c.pass))
            }
            Source::CheckSensitivity => Ok(self.check_sensitivity),
            _ => Err(format!("`{}` is not a Boolean", v.name)),
        }
    }

    /// Reads String variables; the returned pointers stay valid until the next string read.
    pub fn get_strings(&mut self, vrs: &[u32]) -> Outcome<Vec<*const c_char>> {
        let mut strings = Vec::with_capacity(vrs.len());
        for &vr in vrs {
            let v = self.variable(vr, Type::String)?;
            match v.source {
                Source::LogPath => strings.push(c_string(&self.log_path)),
                Source::LogChannels => strings.push(c_string(&self.log_channels)),
                _ => return Err(format!("`{}` is not a String", v.name)),
            }
        }
        self.strings = strings;
        Ok(self.strings.iter().map(|s| s.as_ptr()).collect())
    }

    /// The per-variable rule inside a setter's allowed states: parameters before
    /// `ExitInitializationMode`, inputs until `Terminate`, nothing else ever.
    fn check_settable(&self, v: &Variable, value: &dyn Shown) -> Outcome<()> {
        let (allowed, rule) = match v.source {
            Source::Parameter(_)
            | Source::LogPath
            | Source::LogChannels
            | Source::LogSampleInterval
            | Source::MaxSteps
            | Source::CheckSensitivity => {
                (super::status::allowed::SET_PARAMETER, "parameters are fixed at ExitInitializationMode")
            }
            Source::Input(_) | Source::Motion(_) => {
                (super::status::allowed::SET_INPUT, "inputs are set until Terminate")
            }
            _ => {
                let kind = v.causality.name();
                let article = if kind.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
                return Err(format!(
                    "`{}` is {article} {kind} and cannot be set: value reference {} = {} is not set",
                    v.name,
                    v.vr,
                    value.shown()
                ));
            }
        };
        if !allowed.contains(self.state) {
            return Err(format!(
                "setting `{}` ({}) is not allowed in state {} (illegal call sequence: {rule}): value reference {} = \
                 {} is not set",
                v.name,
                v.causality.name(),
                self.state.name(),
                v.vr,
                value.shown()
            ));
        }
        Ok(())
    }

    /// Writes a Real / Float64 variable (parameters: finite values only; the rest is checked at
    /// initialization, where each invalid parameter is named). The inputs' bounds hold in every
    /// state: |F| <= [`MAX_TIP_FORCE`] for the tip forces, [`check_motion_value`]'s range for the
    /// support motion (issue 27).
    pub fn set_real(&mut self, vr: u32, value: f64) -> Outcome<()> {
        let v = self.variable(vr, Type::Real)?;
        self.check_settable(&v, &value)?;
        match v.source {
            // Its own message names the bound, NaN and inf included.
            Source::Motion(k) => check_motion_value(k, value)?,
            _ if !value.is_finite() => return Err(format!("{} must be a finite number, got {value}", v.name)),
            _ => {}
        }
        match v.source {
            Source::Parameter(p) => {
                parameters::set(&mut self.scenario, p, value).map_err(|e| e.to_string())?;
                self.simulation = None;
            }
            Source::LogSampleInterval => {
                self.log_sample_interval_ns = crate::record::options::sample_interval_ns("log.sample_interval", value)?;
            }
            Source::Input(tip) => {
                // The bound holds in every state, not only before initialization.
                if value.abs() > MAX_TIP_FORCE {
                    return Err(format!("{} must be finite with |F| <= {MAX_TIP_FORCE:e} N, got {value:e}", v.name));
                }
                let mut forces = self.forces();
                match tip {
                    Tip::Upper => forces.upper = value,
                    Tip::Lower => forces.lower = value,
                }
                match self.state {
                    State::Instantiated | State::Initialization => {
                        self.scenario.upper.tip_force = forces.upper;
                        self.scenario.lower.tip_force = forces.lower;
                        self.simulation = None;
                    }
                    _ => self.simulation()?.set_tip_forces(forces),
                }
            }
            Source::Motion(k) => {
                let mut values = self.motion.values();
                values[k] = value;
                let motion = SupportMotion::from_values(values);
                match self.state {
                    State::Instantiated | State::Initialization => {
                        // The fall before t = 0 happened under the accelerations at t = 0.
                        self.motion = motion;
                        self.simulation = None;
                    }
                    _ => {
                        self.simulation()?.set_support_motion(motion);
                        self.motion = motion;
                    }
                }
            }
            _ => {
                return Err(format!("`{}` cannot be set: value reference {vr} = {} is not set", v.name, number(value)))
            }
        }
        Ok(())
    }

    /// Writes an Integer / Int32 variable.
    pub fn set_integer(&mut self, vr: u32, value: i32) -> Outcome<()> {
        let v = self.variable(vr, Type::Integer)?;
        self.check_settable(&v, &value)?;
        if let Source::MaxSteps = v.source {
            if value < 1 {
                return Err(format!("{} must be a whole number >= 1 (internal steps), got {value}", v.name));
            }
            self.max_steps = value as u64;
            self.simulation = None;
            self.checks = None;
            return Ok(());
        }
        let Source::Parameter(p) = v.source else {
            return Err(format!("`{}` cannot be set: value reference {vr} = {value} is not set", v.name));
        };
        parameters::set(&mut self.scenario, p, f64::from(value)).map_err(|e| e.to_string())?;
        self.simulation = None;
        Ok(())
    }

    /// Writes a Boolean variable (there is no settable one).
    pub fn set_boolean(&mut self, vr: u32, value: bool) -> Outcome<()> {
        let v = self.variable(vr, Type::Boolean)?;
        self.check_settable(&v, &value)?;
        match v.source {
            Source::CheckSensitivity => {
                self.check_sensitivity = value;
                self.simulation = None;
                self.checks = None;
                Ok(())
            }
            _ => Err(format!("`{}` cannot be set: value reference {vr} = {} is not set", v.name, value.shown())),
        }
    }

    /// Writes a String variable.
    pub fn set_string(&mut self, vr: u32, value: String) -> Outcome<()> {
        let v = self.variable(vr, Type::String)?;
        self.check_settable(&v, &value)?;
        match v.source {
            Source::LogPath => {
                self.log_path = value;
                Ok(())
            }
            Source::LogChannels => {
                // Checked here, so that a bad list is the setter's error, naming the value.
                LogChannels::parse(&value)?;
                self.log_channels = value;
                Ok(())
            }
            _ => Err(format!("`{}` cannot be set: value reference {vr} = {} is not set", v.name, value.shown())),
        }
    }

    /// Error for a type this FMU has no variable of (FMI 3 Float32, Int8, ..., Binary, Clock).
    pub fn no_variables_of(&self, type_name: &str, vrs: &[u32]) -> Outcome<Status> {
        match vrs.first() {
            None => Ok(Status::Ok),
            Some(vr) => Err(format!("value reference {vr}: this FMU has no {type_name} variables")),
        }
    }

    /// `GetFMUState`: the FMI state: the simulation's state, the FMU parameters, the absolute
    /// start time and whether the instance is initialized (not the stop time, not `log.path`).
    pub fn snapshot(&mut self) -> Outcome<Snapshot> {
        let run = self.simulation()?.state().clone();
        let checks = self.checks.iter().flatten().map(|c| c.state().clone()).collect();
        Ok(Snapshot {
            start_time: self.start_time,
            initialized: self.initialized(),
            parameters: parameters_of(&self.scenario),
            run,
            checks,
            sections: sections_of(&self.scenario),
        })
    }

    /// `SetFMUState`: restores the FMI state of a snapshot, after checking it (the scenario within
    /// the scenario limits, [`crate::simulation::RunState::validate`]); a refused state changes
    /// nothing. The snapshot's parameters win: a state of another scenario rebuilds the model for
    /// it. The time is the snapshot's (absolute); the stop time stays the instance's.
    ///
    /// - Into an instance that is not initialized (Instantiated, Initialization Mode; fmpy's
    ///   `simulate_fmu(fmu_state=...)`, fmusim's `--initial-fmu-state-file`): a snapshot taken after
    ///   initialization puts the instance in Step Mode, ready for `DoStep` and the getters, with
    ///   its MCAP log (`log.path` of this instance; the default one is a new file) starting at the
    ///   restored step. A snapshot taken before initialization only sets the parameters and the
    ///   inputs; `ExitInitializationMode` follows as usual.
    /// - Into an initialized instance (rollback): the MCAP log records the rollback. If the
    ///   scenario changes, the log (which describes the old one) is completed; a default log goes
    ///   on in a new file, an explicit one stops (a warning).
    /// - In state Error it returns the instance to the state the failed call was made in.
    pub fn restore(&mut self, snapshot: &Snapshot) -> Outcome<Status> {
        if !within_time_limit(snapshot.start_time) {
            return Err(Error::StateInvalid {
                field: "start_time".into(),
                detail: format!("= {} s is not within +-{MAX_ABSOLUTE_TIME:e} s", number(snapshot.start_time)),
            }
            .to_string());
        }
        // The support motion within the inputs' range, as the setters hold it (issue 27).
        for (k, run) in std::iter::once(&snapshot.run).chain(&snapshot.checks).enumerate() {
            let which = if k == 0 { String::new() } else { format!("checks[{}].", k - 1) };
            for (field, motion) in [("input_motion", run.input_motion), ("motion", run.motion)] {
                for (j, value) in motion.values().into_iter().enumerate() {
                    check_motion_value(j, value).map_err(|detail| {
                        Error::StateInvalid {
                            field: format!("{which}{field}.{}", MOTION_NAMES[j]),
                            detail: format!("is out of range: {detail}"),
                        }
                        .to_string()
                    })?;
                }
            }
        }
        let fresh = !self.initialized();
        let mut base = self.scenario.clone();
        if fresh {
            base.upper.tip_force = snapshot.run.forces.upper;
            base.lower.tip_force = snapshot.run.forces.lower;
        }
        let scenario = scenario_of(&base, snapshot).map_err(|e| e.to_string())?;
        let same_model = self.simulation.is_some()
            && parameters_of(&scenario) == parameters_of(&self.scenario)
            && sections_of(&scenario) == sections_of(&self.scenario);
        if same_model {
            let simulation = self.simulation.as_mut().ok_or("no simulation")?;
            simulation.restore(snapshot.run.clone()).map_err(|e| e.to_string())?;
        } else {
            let mut simulation = Simulation::new(&scenario).map_err(|e| format!("the state's scenario: {e}"))?;
            simulation.set_max_steps(self.max_steps);
            simulation.restore(snapshot.run.clone()).map_err(|e| e.to_string())?;
            self.simulation = Some(simulation);
        }
        // The discretisation check's runs, restored from the snapshot's states (a state without
        // them, or whose check runs do not fit, leaves the check off: not checked from there on).
        let mut checks = match (same_model, self.checks.take()) {
            (true, Some(checks)) => Some(checks),
            _ => self.check_runs(&scenario).ok(),
        };
        if let Some(runs) = checks.as_mut() {
            let fits = runs.len() == snapshot.checks.len()
                && runs.iter_mut().zip(&snapshot.checks).all(|(run, state)| run.restore(state.clone()).is_ok());
            if !fits {
                checks = None;
            }
        }
        self.scenario = scenario;
        self.checks = checks;
        self.motion = snapshot.run.input_motion;
        self.start_time = snapshot.start_time;
        self.last_successful_time = self.time();
        if self.state == State::Error {
            self.state = self.before_error;
        }
        let result = *self.simulation.as_ref().ok_or("no simulation")?.result();
        let restored = format!("t = {} s, step {}", number(self.time()), result.step);
        if fresh {
            if !snapshot.initialized {
                return Ok(Status::Ok);
            }
            if let Some(mut left) = self.recorder.take() {
                // A log left open by a failed initialization: complete it before the run starts anew.
                let _ = left.finish();
            }
            let (recorder, warning) = self.open_log()?;
            self.recorder = recorder;
            let dropped = self.start_log()?;
            self.state = State::Step;
            self.log(Status::Ok, "logEvents", &format!("restored a state into Step Mode ({restored})"));
            return Ok(self.warn(both(warning, dropped)));
        }
        if !same_model {
            let Some(mut old) = self.recorder.take() else { return Ok(Status::Ok) };
            let finished = old.finish().err().map(|e| format!("; completing it failed: {e}"));
            let old = old.path().display().to_string();
            let warning = if self.log_path == DEFAULT_LOG_PATH {
                let (recorder, warning) = self.open_log()?;
                self.recorder = recorder;
                let dropped = self.start_log()?;
                both(warning, dropped)
            } else {
                Some(format!(
                    "the state restored ({restored}) belongs to another scenario: the MCAP log {old} describes the \
                     previous one and is complete; no log from here on (log.path is not the default)"
                ))
            };
            let warning = match (warning, finished) {
                (Some(w), Some(f)) => Some(format!("{w} (the previous log {old}{f})")),
                (None, Some(f)) => Some(format!("the previous log {old}{f}")),
                (w, None) => w,
            };
            return Ok(self.warn(warning));
        }
        let rollback = self.recorder.as_mut().map_or(Ok(()), |recorder| recorder.rollback(&result));
        if let Err(e) = rollback {
            let dropped = self.drop_log(&e);
            return Ok(self.warn(Some(format!(
                "the state is restored ({restored}), but the MCAP log cannot record the rollback: {dropped}"
            ))));
        }
        Ok(Status::Ok)
    }

    /// The runs stepped in lockstep with the simulation: the discretisation check's, then the
    /// reproducibility twin when `check_sensitivity` is on.
    fn check_runs(&self, scenario: &Scenario) -> crate::Result<Vec<Simulation>> {
        let mut scenarios = crate::answer::check_scenarios(scenario)?;
        if self.check_sensitivity {
            scenarios.push(crate::answer::twin_scenario(scenario));
        }
        scenarios
            .iter()
            .map(|s| {
                let mut run = Simulation::starting_with(s, self.motion)?;
                run.set_max_steps(self.max_steps);
                Ok(run)
            })
            .collect()
    }

    /// The discretisation check's runs and the twin (when run), apart.
    fn split_checks(&self) -> Option<(&[Simulation], Option<&Simulation>)> {
        let checks = self.checks.as_deref()?;
        Some(match (self.check_sensitivity, checks.split_last()) {
            (true, Some((twin, rungs))) => (rungs, Some(twin)),
            _ => (checks, None),
        })
    }

    /// The largest spread of the running peaks, whole-run and first-contact, against the twin's
    /// (see [`crate::answer`]); -1 when not checked (`check_sensitivity` off, or after a state
    /// without the twin).
    fn sensitivity_spread(&self) -> f64 {
        let (Some(simulation), Some((_, Some(twin)))) = (&self.simulation, self.split_checks()) else { return -1.0 };
        let spread = |a: [f64; 5], b: [f64; 5]| (0..5).map(|k| crate::answer::relative(b[k], a[k])).fold(0.0, f64::max);
        let whole = spread(simulation.output().peaks.as_array(), twin.output().peaks.as_array());
        let first =
            spread(simulation.state().first_contact.peaks.as_array(), twin.state().first_contact.peaks.as_array());
        whole.max(first)
    }

    /// The largest discretisation figure of the running peaks so far (whole-run and first-contact)
    /// against the checks' runs (see [`crate::answer`]); -1 when not checked (no simulation, or
    /// after a state without the check runs).
    fn discretisation_error(&self) -> f64 {
        let (Some(simulation), Some((checks, _))) = (&self.simulation, self.split_checks()) else { return -1.0 };
        let Some(check) = checks.first() else { return -1.0 };
        let paper = self.scenario.method == crate::model::Method::Paper;
        let peaks = |s: &Simulation| (s.output().peaks, s.state().first_contact.peaks);
        let ((fine_whole, fine_first), (medium_whole, medium_first)) = (peaks(simulation), peaks(check));
        let (whole, first) = crate::answer::peak_figures(
            paper,
            self.scenario.damping_ratio,
            [&fine_whole, &fine_first],
            [&medium_whole, &medium_first],
        );
        whole.as_array().into_iter().chain(first.as_array()).fold(-1.0, f64::max)
    }

    /// The yield check of the running peaks (`None` without a yield stress).
    fn yield_check(&self) -> Option<crate::answer::Check> {
        let simulation = self.simulation.as_ref()?;
        let envelope = simulation.envelope().peaks().map(|p| p.map(|p| p.value));
        crate::answer::yield_check(&self.scenario, &simulation.output().peaks, &envelope)
    }

    /// Logs `warning` (if any) and returns its status.
    fn warn(&self, warning: Option<String>) -> Status {
        match warning {
            Some(message) => {
                self.log(Status::Warning, Status::Warning.category(), &message);
                Status::Warning
            }
            None => Status::Ok,
        }
    }
}

/// A value as the refusal of a setter shows it ([`Instance::to_be_set`]): numbers as the logger
/// prints them, a string quoted with its control characters escaped and cut at 100 characters.
pub trait Shown {
    /// The value for a message.
    fn shown(&self) -> String;
}

impl Shown for f64 {
    fn shown(&self) -> String {
        number(*self)
    }
}

impl Shown for i32 {
    fn shown(&self) -> String {
        self.to_string()
    }
}

impl Shown for bool {
    fn shown(&self) -> String {
        self.to_string()
    }
}

impl Shown for String {
    fn shown(&self) -> String {
        const MAX: usize = 100;
        let cut: String = self.chars().take(MAX).collect();
        let more = if self.chars().nth(MAX).is_some() { "..." } else { "" };
        format!("{cut:?}{more}")
    }
}
