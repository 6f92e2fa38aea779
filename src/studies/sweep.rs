//! Design sweeps: a scenario varied over a full factorial grid of its fields, every scenario run
//! unrecorded in parallel, one row of results per scenario (CSV and JSON); and the `KEY=VALUE`
//! overrides of `beam-impact run --set`.
//!
//! Names are the scenario's dotted field names ([`crate::model::parameters::PARAMETERS`], plus the
//! constant tip forces [`TIP_FORCES`]); values are read per field: reals, whole numbers, `"auto"`
//! for the time steps (0 in the FMU's form), `mean` / `left` / `right` for `stress_recovery`.
//!
//! A grid is the product of its axes in the order given, the last axis varying fastest (as
//! Python's `itertools.product`). An axis is `start:stop:count` (inclusive, linear: value i is
//! `start + (stop - start) * i / (count - 1)` to 15 significant digits, the last one `stop`
//! exactly; count 1 is `start`) or a comma list; an integer field's values are rounded and its
//! duplicates dropped (first kept).
//! The Python package `beam_impact` parses the same specs with the same arithmetic, so both give
//! the same bits.
//!
//! A row is the run's [`crate::answer::Answer`] reduced to what a design envelope needs: the four
//! Table 1 peaks and the contact force peak, when each was reached, the energy approach, the
//! largest energy residual, the checks' figures, the design's utilisations and verdict, and the
//! trust verdict, and the row's wall time. Each run is the `run` command's
//! ([`crate::answer::run_with`] into a [`NullRecorder`]), so a row equals the single run of its
//! scenario to the bit. A scenario that fails validation, or whose run fails, gives a row with the error.
//!
//! The rows share one [`ModalCache`]: the rungs of rows that differ only in the
//! [`PER_RUN_FIELDS`] (drop height, impact speed, damping, steps, checks) take their modes from
//! the first of them, and [`Sweep::execution_order`] runs the rows of one geometry together (the
//! rows are still written in grid order). The setup it saves is about 4 % of a converged row's
//! time (issue 29's measurement); the stepping is the rest.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use crate::error::{Error, Result};
use crate::model::parameters::{self, Kind, Parameter};
use crate::model::Scenario;
use crate::record::NullRecorder;
use crate::results::{Peaks, ENVELOPE_PEAK_NAMES};
use crate::solver::modal_cache::PER_RUN_FIELDS;
use crate::solver::{EnergyMethod, ModalCache};

/// Scenario fields beyond [`parameters::PARAMETERS`] that `--set` and `--vary` accept: the constant tip
/// forces (the FMU's inputs, so not among its parameters).
pub static TIP_FORCES: [Parameter; 2] = [
    Parameter {
        name: "upper.tip_force",
        unit: "N",
        description: "Constant vertical force at the bridge's free end, up positive",
        kind: Kind::Real,
        get: |s| s.upper.tip_force,
        put: |s, v| {
            s.upper.tip_force = v;
            Ok(())
        },
    },
    Parameter {
        name: "lower.tip_force",
        unit: "N",
        description: "Constant vertical force at the arrestor's free end, up positive",
        kind: Kind::Real,
        get: |s| s.lower.tip_force,
        put: |s, v| {
            s.lower.tip_force = v;
            Ok(())
        },
    },
];

/// The support motion's time shift (issue 17): a scenario field of the CLI (the FMU takes the
/// motion as inputs), which `--vary` sweeps over a wave period.
pub static MOTION_FIELDS: [Parameter; 1] = [Parameter {
    name: "motion.time_shift",
    unit: "s",
    description: "The motion file's time at the run's t = 0 (the impact)",
    kind: Kind::Real,
    get: |s| s.motion.time_shift,
    put: |s, v| {
        s.motion.time_shift = v;
        Ok(())
    },
}];

/// The field named `name` (the dotted names of `beam-impact scenario`).
pub fn field(name: &str) -> Result<&'static Parameter> {
    parameters::find(name).or_else(|_| {
        TIP_FORCES
            .iter()
            .chain(&MOTION_FIELDS)
            .chain(&crate::model::sea::fields::SEA_FIELDS)
            .chain(&crate::model::fatigue_fields::FATIGUE_FIELDS)
            .find(|p| p.name == name)
            .ok_or_else(|| {
                Error::Other(format!(
                    "unknown parameter `{name}`: the names are those of `beam-impact scenario`, dotted ({})",
                    "drop_height, damping_ratio, upper.mass, lower.elements, ..."
                ))
            })
    })
}

/// Fields whose 0 is `"auto"`: the time steps, the element counts and the modal cut-off.
fn is_time_step(field: &Parameter) -> bool {
    matches!(
        field.name,
        "step_free"
            | "step_contact"
            | "lower.elements"
            | "upper.elements_to_contact"
            | "upper.elements_beyond_contact"
            | "modal_cutoff"
            | "sea.peak_enhancement"
            | "sea.frequency_min"
            | "sea.frequency_max"
    )
}

/// The names of a symbolic field's values (their index is the parameter's value), if it has them.
fn symbolic_names(field: &Parameter) -> Option<&'static [&'static str]> {
    match field.name {
        "stress_recovery" => Some(&RECOVERY_NAMES),
        "method" => Some(&METHOD_NAMES),
        "lower.kind" => Some(&SUPPORT_NAMES),
        "upper.kind" => Some(&IMPACTOR_NAMES),
        "contact.law" => Some(&LAW_NAMES),
        "sea.spectrum" => Some(&SPECTRUM_NAMES),
        "fatigue.curve" => Some(crate::model::fatigue_settings::curve_names()),
        "lower.supports" => Some(&crate::model::supports::SUPPORTS_NAMES),
        _ => None,
    }
}

fn is_stress_recovery(field: &Parameter) -> bool {
    symbolic_names(field).is_some()
}

const RECOVERY_NAMES: [&str; 3] = ["mean", "left", "right"];
/// `lower.kind`'s names, by FMU index.
const SUPPORT_NAMES: [&str; 2] = ["beam", "rigid"];
/// `contact.law`'s names, by FMU index.
const LAW_NAMES: [&str; 3] = ["linear", "power", "hertz"];
/// `upper.kind`'s names, by FMU index (issue 45).
const IMPACTOR_NAMES: [&str; 2] = ["beam", "mass"];

const METHOD_NAMES: [&str; 2] = ["converged", "paper"];
/// `sea.spectrum`'s names, by index.
const SPECTRUM_NAMES: [&str; 2] = ["jonswap", "pierson-moskowitz"];

/// What a value of `field` looks like, for messages.
fn expected(field: &Parameter) -> String {
    if matches!(field.name, "step_free" | "step_contact") {
        "a time step in s or \"auto\"".into()
    } else if is_time_step(field) {
        format!("{} or \"auto\"", if field.kind == Kind::Integer { "a whole number" } else { "a number" })
    } else if let Some(names) = symbolic_names(field) {
        let (last, rest) = names.split_last().unwrap_or((&"", &[]));
        format!("{} or {last}", rest.join(", "))
    } else if field.kind == Kind::Integer {
        "a whole number".into()
    } else if field.unit.is_empty() || field.unit == "1" {
        "a number".into()
    } else {
        format!("a number in {}", field.unit)
    }
}

/// Reads one value of `field` in its parameter form: a number; `auto` (0) for the time steps;
/// `mean`, `left`, `right` (0, 1, 2) for `stress_recovery`.
pub fn parse_value(field: &Parameter, text: &str) -> Result<f64> {
    let text = text.trim();
    if is_time_step(field) && text == "auto" {
        return Ok(0.0);
    }
    if let Some(names) = symbolic_names(field) {
        if let Some(k) = names.iter().position(|&n| n == text) {
            return Ok(k as f64);
        }
    }
    text.parse::<f64>().map_err(|_| Error::Other(format!("{} takes {}, got `{text}`", field.name, expected(field))))
}

/// A value of `field` as the CSV writes it (and as `parse_value` reads it back): `auto`, a stress
/// recovery's name, a whole number, or the shortest decimal that gives the same f64.
pub fn format_value(field: &Parameter, value: f64) -> String {
    if is_time_step(field) && value == 0.0 {
        "auto".into()
    } else if let Some(names) = symbolic_names(field) {
        let index = value as usize;
        if value.fract() == 0.0 && value >= 0.0 && index < names.len() {
            names[index].into()
        } else {
            format!("{value}")
        }
    } else {
        format!("{value}")
    }
}

/// A value of `field` as JSON: a string for `auto` and the stress recoveries, else a number.
fn json_value(field: &Parameter, value: f64) -> String {
    if (is_time_step(field) && value == 0.0) || is_stress_recovery(field) {
        json_string(&format_value(field, value))
    } else if field.kind == Kind::Integer && value.fract() == 0.0 && value.abs() < 9e15 {
        format!("{}", value as i64)
    } else {
        json_number(value)
    }
}

/// One `KEY=VALUE` override.
#[derive(Clone, Copy, Debug)]
pub struct Setting {
    /// The field.
    pub field: &'static Parameter,
    /// Its value in the parameter form (see [`parse_value`]).
    pub value: f64,
}

fn split_assignment<'a>(option: &str, text: &'a str, what: &str) -> Result<(&'a str, &'a str)> {
    match text.split_once('=') {
        Some((key, value)) if !key.trim().is_empty() => Ok((key.trim(), value)),
        _ => Err(Error::Other(format!("{option} expects KEY={what}, got `{text}`"))),
    }
}

/// Reads `--set KEY=VALUE`.
pub fn parse_setting(text: &str) -> Result<Setting> {
    let (key, value) = split_assignment("--set", text, "VALUE")?;
    let field = field(key).map_err(|e| Error::Other(format!("--set {text}: {e}")))?;
    let value = parse_value(field, value).map_err(|e| Error::Other(format!("--set {text}: {e}")))?;
    Ok(Setting { field, value })
}

/// Reads every `--set`.
pub fn parse_settings(texts: &[String]) -> Result<Vec<Setting>> {
    texts.iter().map(|t| parse_setting(t)).collect()
}

/// Sets one field (integers must be whole), without validating the scenario.
pub fn set(scenario: &mut Scenario, field: &Parameter, value: f64) -> Result<()> {
    parameters::set(scenario, field, value)
}

/// Validates a whole scenario: every invalid field, each named, in one error.
pub fn validate(scenario: &Scenario) -> Result<()> {
    let mut errors = scenario.validation_errors();
    match errors.len() {
        0 => Ok(()),
        1 => Err(errors.remove(0)),
        _ => Err(Error::Invalid(errors)),
    }
}

/// Applies a reference fixture row's settings, a JSON object of field names and values (numbers,
/// or the words `--set` takes: `"rigid"`, `"power"`), as `--set KEY=VALUE` would, and validates
/// the result ([`apply_settings`]). The key `file`, the scenario file a row starts from, is the
/// caller's.
pub fn apply_fixture_settings(scenario: &mut Scenario, settings: &serde_json::Value) -> Result<()> {
    let mut parsed = Vec::new();
    for (key, value) in settings.as_object().into_iter().flatten().filter(|(k, _)| *k != "file") {
        let text = match value {
            serde_json::Value::String(word) => word.clone(),
            other => other.to_string(),
        };
        parsed.push(parse_setting(&format!("{key}={text}"))?);
    }
    apply_settings(scenario, &parsed)
}

/// Applies the settings in order (a later one wins) and validates the result.
pub fn apply_settings(scenario: &mut Scenario, settings: &[Setting]) -> Result<()> {
    for s in settings {
        set(scenario, s.field, s.value)?;
    }
    // The impact is stated one way: a speed set here replaces the drop height it would otherwise
    // come from, and a drop height set here the speed (both set here: refused by validation).
    let given = |name: &str| settings.iter().any(|s| s.field.name == name);
    // A rigid support has no arrestor beam: its fields set here are a contradiction (as in a file).
    if scenario.lower.kind == crate::model::scenario::SupportKind::Rigid {
        let beam: Vec<&str> = settings
            .iter()
            .map(|s| s.field.name)
            .filter(|n| n.starts_with("lower.") && *n != "lower.kind" && *n != "lower.tip_force")
            .collect();
        if !beam.is_empty() {
            return Err(Error::Other(format!(
                "lower.kind = \"rigid\" has no arrestor beam, but {} {} set: leave them out",
                beam.join(", "),
                if beam.len() == 1 { "is" } else { "are" }
            )));
        }
    }
    match (given("impact_angular_velocity"), given("drop_height")) {
        (true, false) if scenario.impact_angular_velocity.is_some() => scenario.drop_height = 0.0,
        (false, true) => scenario.impact_angular_velocity = None,
        _ => {}
    }
    // The same for a rigid impactor's speed (issue 45).
    match (given("impact_speed"), given("drop_height")) {
        (true, false) if scenario.impact_speed != 0.0 => scenario.drop_height = 0.0,
        (false, true) => scenario.impact_speed = 0.0,
        _ => {}
    }
    // The contact moved to the bridge's free end here, where the scenario (the paper's, a file's)
    // keeps elements beyond it: the field set here is at fault, named with its value (issue 40:
    // `modes --set contact_position=29` blamed upper.elements_beyond_contact, never set).
    let u = &scenario.upper;
    if scenario.contact_at_free_end() && u.elements_beyond_contact != 0 && !given("upper.elements_beyond_contact") {
        let keeps = format!(
            "while the scenario has upper.elements_beyond_contact = {} (not set here); for the contact at the \
             bridge's free end also set upper.elements_beyond_contact=auto",
            u.elements_beyond_contact
        );
        if given("contact_position") {
            let rule = format!("below upper.length = {} m {keeps}", u.length);
            return Err(Error::invalid("contact_position", rule, scenario.contact_position));
        }
        if given("upper.length") {
            let rule = format!("above contact_position = {} m {keeps}", scenario.contact_position);
            return Err(Error::invalid("upper.length", rule, u.length));
        }
    }
    validate(scenario)
}

/// The scenario a case runs: `scenario` with the case's fields set as `--set` sets them, its
/// load cases removed. Errors name the case.
pub fn case_scenario(scenario: &Scenario, case: &crate::model::load_case::LoadCase) -> Result<Scenario> {
    let mut s = scenario.clone();
    s.load_cases.clear();
    if case.set.is_empty() {
        return Ok(s);
    }
    let settings = serde_json::Value::Object(
        case.set
            .iter()
            .map(|(k, v)| {
                let value = match v {
                    crate::model::load_case::SetValue::Number(x) => serde_json::json!(x),
                    crate::model::load_case::SetValue::Word(w) => serde_json::json!(w),
                };
                (k.clone(), value)
            })
            .collect(),
    );
    apply_fixture_settings(&mut s, &settings)
        .map_err(|e| Error::Other(format!("load case {:?}: {}", case.name, e.to_string().replace("--set ", "set "))))?;
    Ok(s)
}

/// Checks every case's fields before any run: the first error names the case and the field.
pub fn check_cases(scenario: &Scenario) -> Result<()> {
    for case in &scenario.load_cases {
        case_scenario(scenario, case)?;
    }
    Ok(())
}

/// The converged answer of `scenario` as [`crate::answer::run_cancellable`] gives it, with the
/// scenario's load cases judged (issue 44, [`crate::load_cases`]): each case that changes fields
/// is a converged answer of its own (unrecorded, with `options` less the station envelope), and
/// with cases `design.pass` is every case's verdict; a case whose answer is not trusted makes the
/// answer not trusted, the case named in the reasons. Without cases: the answer alone.
pub fn answer_with_cases(
    scenario: &Scenario,
    recorder: &mut (dyn crate::record::Recorder + Send),
    options: crate::answer::Options,
    cache: &ModalCache,
    cancel: &std::sync::atomic::AtomicBool,
) -> Result<crate::answer::Answer> {
    check_cases(scenario)?;
    let mut answer = crate::answer::run_cancellable(scenario, recorder, options, cache, cancel)?;
    let case_options = crate::answer::Options { station_envelope: false, ..options };
    let mut answer_of = |case: &crate::model::load_case::LoadCase| {
        let s = case_scenario(scenario, case)?;
        crate::answer::run_cancellable(&s, &mut NullRecorder, case_options, cache, cancel)
    };
    if let Some(cases) = crate::load_cases::judge(scenario, &answer, &mut answer_of, &crate::load_cases::static_values)?
    {
        answer.design.pass = cases.pass;
        if !cases.trusted {
            answer.quality.trusted = false;
            for case in cases.cases.iter().filter(|c| !c.trusted) {
                answer.quality.reasons.push(format!(
                    "load case {:?}: its own converged answer is not trusted, so its verdict is not vouched for",
                    case.name
                ));
            }
        }
        answer.load_cases = Some(cases);
    }
    Ok(answer)
}

/// The default log of a `run` with `--set`: `<stem>-set-<hash>.mcap` in the working directory,
/// the stem the scenario file's (`paper` without one) and the hash the resolved scenario's
/// (FNV-1a of its TOML, 32 bits in hex), so that it never overwrites the unmodified run's
/// `paper.mcap` and the same overrides find the same file. Without settings: `FILE.mcap` beside the scenario file, `paper.mcap` for the paper run.
pub fn default_log(file: Option<&Path>, settings: &[Setting], scenario: &Scenario) -> PathBuf {
    // A scenario file's log sits beside it under its name (rerunning the file replaces its own
    // log): FILE.toml logs to FILE.mcap, any other name to NAME.mcap with its extension kept
    // (`s.mcap` to `s.mcap.mcap`, never onto the scenario itself); the paper run's is paper.mcap;
    // standard input's stdin.mcap.
    let base = match file {
        Some(f) if f.as_os_str() == "-" => PathBuf::from("stdin"),
        Some(f) if f.extension().is_some_and(|e| e == "toml") => f.with_extension(""),
        Some(f) => f.to_path_buf(),
        None => PathBuf::from("paper"),
    };
    let with_mcap = |base: &Path| {
        let mut name = base.as_os_str().to_owned();
        name.push(".mcap");
        PathBuf::from(name)
    };
    if settings.is_empty() {
        return with_mcap(&base);
    }
    let hash = fnv1a(scenario.to_toml().as_bytes());
    PathBuf::from(format!("{}-set-{:08x}.mcap", base.display(), (hash ^ (hash >> 32)) as u32))
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// One varied field and its values, in order.
#[derive(Clone, Debug)]
pub struct Axis {
    /// The field.
    pub field: &'static Parameter,
    /// Its values in the parameter form.
    pub values: Vec<f64>,
}

/// `count` values from `start` to `stop` inclusive: `start + (stop - start) * i / (count - 1)`
/// rounded to 15 significant digits (so that 0.2:1:3 gives 0.6, not 0.6000000000000001), the
/// last exactly `stop`; one value is `start`. Where `stop - start` overflows (endpoints near
/// +-1.8e308 of opposite signs) the same point as `start (1 - t) + stop t`, t = i / (count - 1),
/// which cannot. Python's `float(f"{x:.14e}")` rounds the same way (both correctly rounded), so
/// the package's grids are these bits. Endpoints are finite ([`parse_axis`] refuses others).
pub fn linspace(start: f64, stop: f64, count: usize) -> Vec<f64> {
    let snap = |x: f64| format!("{x:.14e}").parse::<f64>().unwrap_or(x);
    let span = stop - start;
    (0..count)
        .map(|i| match i {
            0 => start,
            i if i + 1 == count => stop,
            i if span.is_finite() => snap(start + span * i as f64 / (count - 1) as f64),
            i => {
                let t = i as f64 / (count - 1) as f64;
                snap(start * (1.0 - t) + stop * t)
            }
        })
        .collect()
}

/// Reads `--vary KEY=SPEC`: `start:stop:count` (inclusive, linear) or a comma list. Integer
/// fields are rounded (half away from zero) and their duplicates dropped, the first kept.
pub fn parse_axis(text: &str) -> Result<Axis> {
    let context = |e: Error| Error::Other(format!("--vary {text}: {e}"));
    let (key, spec) = split_assignment("--vary", text, "SPEC")?;
    let field = field(key).map_err(context)?;
    let values = if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        let [start, stop, count] = parts[..] else {
            return Err(context(Error::Other(format!(
                "SPEC is start:stop:count (inclusive, linear) or a comma list, got `{spec}`"
            ))));
        };
        let count: usize = count.trim().parse().ok().filter(|&n| n >= 1).ok_or_else(|| {
            context(Error::Other(format!(
                "the count of start:stop:count must be a whole number from 1 to {MAX_SCENARIOS}, got `{}`",
                quoted(count)
            )))
        })?;
        if count > MAX_SCENARIOS {
            return Err(context(Error::Other(format!(
                "the count {count} is more than a sweep runs ({MAX_SCENARIOS} scenarios): split the sweep"
            ))));
        }
        let (start, stop) = (parse_value(field, start).map_err(context)?, parse_value(field, stop).map_err(context)?);
        if let Some(bad) = [start, stop].into_iter().find(|v| !v.is_finite()) {
            return Err(context(Error::Other(format!(
                "start and stop of start:stop:count must be finite numbers, got {bad}"
            ))));
        }
        linspace(start, stop, count)
    } else {
        spec.split(',').map(|v| parse_value(field, v).map_err(context)).collect::<Result<Vec<f64>>>()?
    };
    Ok(Axis { field, values: normalize(field, values) })
}

/// Integer fields: rounded, duplicates dropped (the first kept). Reals: as given.
pub fn normalize(field: &Parameter, values: Vec<f64>) -> Vec<f64> {
    if field.kind != Kind::Integer {
        return values;
    }
    let mut seen = std::collections::HashSet::with_capacity(values.len());
    let mut out: Vec<f64> = Vec::with_capacity(values.len());
    for v in values.into_iter().map(f64::round) {
        // By bits, with -0 and 0 one value (linear in the count: a million values in milliseconds).
        if seen.insert((v + 0.0).to_bits()) {
            out.push(v);
        }
    }
    out
}

/// Reads every `--vary`; a field given twice is an error.
pub fn parse_axes(texts: &[String]) -> Result<Vec<Axis>> {
    let axes = texts.iter().map(|t| parse_axis(t)).collect::<Result<Vec<Axis>>>()?;
    for (k, a) in axes.iter().enumerate() {
        if axes[..k].iter().any(|b| b.field.name == a.field.name) {
            return Err(Error::Other(format!("--vary {} is given twice", a.field.name)));
        }
    }
    Ok(axes)
}

/// Scenarios in the grid: the product of the axes' lengths (1 without axes).
pub fn grid_len(axes: &[Axis]) -> Result<usize> {
    axes.iter()
        .try_fold(1usize, |n, a| n.checked_mul(a.values.len()))
        .filter(|&n| n <= MAX_SCENARIOS)
        .ok_or_else(|| Error::Other(format!("the grid has more than {MAX_SCENARIOS} scenarios: split the sweep")))
}

/// Grid points within which [`Sweep::execution_order`] groups rows by geometry: the rows a sweep
/// holds, finished but not yet written, stay below about this many (a row is about 0.5 kB).
pub const GROUP_WINDOW: usize = 4096;

/// Largest grid a sweep runs, checked before any value is built: a million converged scenarios
/// is about ten days of CPU (0.86 s each, docs/cli.md).
pub const MAX_SCENARIOS: usize = 1_000_000;

/// At most 200 characters of user text for a one-line message (an ellipsis marks the cut).
fn quoted(text: &str) -> String {
    match text.char_indices().nth(200) {
        Some((cut, _)) => format!("{}...", &text[..cut]),
        None => text.to_string(),
    }
}

/// The values of grid point `index` (0-based, grid order: the last axis fastest), one per axis.
pub fn grid_point(axes: &[Axis], mut index: usize) -> Vec<f64> {
    let mut point = vec![0.0; axes.len()];
    for (value, axis) in point.iter_mut().zip(axes).rev() {
        let n = axis.values.len();
        *value = axis.values[index % n];
        index /= n;
    }
    point
}

/// The whole grid in order (as `itertools.product(*values)`).
pub fn expand(axes: &[Axis]) -> Vec<Vec<f64>> {
    let n = axes.iter().map(|a| a.values.len()).product();
    (0..n).map(|i| grid_point(axes, i)).collect()
}

/// The names of the five peaks, as in `summary.peaks` and in [`Peaks::as_array`]'s order.
pub use crate::answer::PEAK_NAMES;
use crate::vocabulary::{sweep_former_names, PEAK_QUANTITIES, PEAK_UNITS};

type MethodField = (&'static str, fn(&EnergyMethod) -> f64);

/// Every field of [`EnergyMethod`], in declaration order (a unit test checks it against serde).
pub const ENERGY_METHOD_FIELDS: [MethodField; 11] = [
    ("flexion_stiffness", |e| e.flexion_stiffness),
    ("tip_deflection", |e| e.tip_deflection),
    ("force", |e| e.force),
    ("clamp_bending_stress", |e| e.clamp_bending_stress),
    ("clamp_shear_stress", |e| e.clamp_shear_stress),
    ("strain_energy", |e| e.strain_energy),
    ("bridge_deceleration", |e| e.bridge_deceleration),
    ("bridge_contact_moment", |e| e.bridge_contact_moment),
    ("bridge_bending_stress", |e| e.bridge_bending_stress),
    ("bridge_strain_energy", |e| e.bridge_strain_energy),
    ("bridge_strain_ratio", |e| e.bridge_strain_ratio),
];

/// What a row keeps of a run: no histories, no windows, no modes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowResults {
    /// Peaks max |.| over the run (Table 1 and the contact force), SI units.
    pub peaks: Peaks,
    /// When each peak was reached, s.
    pub peak_times: Peaks,
    /// The energy approach of Section 3.
    pub energy_method: EnergyMethod,
    /// Largest |energy residual| of the run, J.
    pub max_energy_residual: f64,
    /// The largest discretisation figure of the peaks (a fraction; see [`crate::answer`]).
    pub discretisation_error: f64,
    /// The largest spread against the twin run (a fraction).
    pub sensitivity_spread: f64,
    /// The largest stress as a fraction of the yield stress (NaN, an empty cell: none given).
    pub yield_utilisation: f64,
    /// Each stress peak's utilisation, converged peak / allowable.
    pub utilisation: crate::answer::DesignUtilisation,
    /// Whether every utilisation is <= 1 (with load cases: every case passes).
    pub design_pass: bool,
    /// The largest factored utilisation over the scenario's load cases (NaN: none given).
    pub load_case_utilisation: f64,
    /// Each beam's worst stress along it (issue 30), in the order of
    /// [`crate::results::ENVELOPE_PEAK_NAMES`].
    pub envelope_peaks: [Option<crate::results::EnvelopePeak>; 4],
    /// The run's verdict: every check that ran passes (`quality.trusted` of `run --json`).
    pub trusted: bool,
    /// The run's fatigue at its worst station, when the sweep asks for it ([`Sweep::fatigue`]).
    pub fatigue: Option<RowFatigue>,
    /// Each design quantity's governing load case, in [`GOVERNING_QUANTITIES`]' order: the case's
    /// index in the scenario's `[[load_cases]]` and its factored utilisation (None: no cases, or
    /// the quantity has no allowable).
    pub governing: [Option<(usize, f64)>; GOVERNING_QUANTITIES.len()],
}

impl From<&crate::answer::Answer> for RowResults {
    fn from(a: &crate::answer::Answer) -> Self {
        let s = &a.summary;
        let c = &a.quality.checks;
        RowResults {
            peaks: s.peaks,
            peak_times: s.peak_times,
            energy_method: s.energy_method,
            max_energy_residual: s.max_energy_residual,
            discretisation_error: c.discretisation.map_or(f64::NAN, |c| c.value),
            sensitivity_spread: c.sensitivity.map_or(f64::NAN, |c| c.value),
            yield_utilisation: c.yield_stress.map_or(f64::NAN, |c| c.value),
            utilisation: a.design.utilisation,
            design_pass: a.design.pass,
            load_case_utilisation: a
                .load_cases
                .as_ref()
                .map_or(f64::NAN, |c| c.cases.iter().map(|c| c.utilisation).fold(f64::NEG_INFINITY, f64::max)),
            envelope_peaks: a.envelope_peaks,
            trusted: a.quality.trusted,
            fatigue: None,
            governing: governing_cases(a),
        }
    }
}

/// The columns of the checks and the design, between `max_energy_residual` and `quality.trusted`,
/// with their units.
pub const CHECK_COLUMNS: [(&str, &str); 8] = [
    ("quality.discretisation_error", "1"),
    ("quality.sensitivity_spread", "1"),
    ("yield_utilisation", "1"),
    ("utilisation.lower.clamp_bending_stress", "1"),
    ("utilisation.lower.clamp_shear_stress", "1"),
    ("utilisation.upper.contact_bending_stress", "1"),
    ("design.pass", "true/false"),
    ("load_cases.utilisation", "1"),
];

/// The fatigue columns of a sweep with [`Sweep::fatigue`] (issue 44), after the checks', with
/// their units: the worst station's Miner sum of one impact, its life at `fatigue.events_per_year`
/// (empty without it), and where that station is (`lower`: the arrestor from its clamp, `upper`:
/// the bridge from its hinge; m).
pub const FATIGUE_COLUMNS: [(&str, &str); 4] =
    [("fatigue.damage", "1"), ("fatigue.life", "years"), ("fatigue.beam", "text"), ("fatigue.position", "m")];

/// A row's fatigue: the worst bending station of both beams ([`crate::run_fatigue::RunFatigue::worst`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowFatigue {
    /// Miner's sum of one event at the worst station (with the SCF, thickness and DFF).
    pub damage: f64,
    /// The life at the scenario's `fatigue.events_per_year`, years (None: no events a year, or
    /// no damage).
    pub life: Option<f64>,
    /// The worst station's beam: `"lower"` or `"upper"`.
    pub beam: &'static str,
    /// Its position along the beam, m from its support.
    pub position: f64,
}

impl RowFatigue {
    /// The worst station of `fatigue` (None: no bending station).
    pub fn of(fatigue: &crate::run_fatigue::RunFatigue) -> Option<RowFatigue> {
        fatigue.worst().map(|w| RowFatigue {
            damage: w.damage,
            life: fatigue.life_years,
            beam: if w.beam == "upper" { "upper" } else { "lower" },
            position: w.position,
        })
    }
}

fn fatigue_cells(f: Option<&RowFatigue>) -> [Cell; 4] {
    match f {
        Some(f) => [
            Cell::Number(f.damage),
            f.life.map_or(Cell::Empty, Cell::Number),
            Cell::Text(f.beam.into()),
            Cell::Number(f.position),
        ],
        None => [Cell::Empty, Cell::Empty, Cell::Empty, Cell::Empty],
    }
}

impl RowResults {
    /// The row of `answer` with its fatigue assessed on the resolved scenario's `[fatigue]` curve
    /// and factors ([`crate::run_fatigue::assess`]); an answer without the stations' histories
    /// (a run without every station's envelope) has none.
    pub fn with_fatigue(answer: &crate::answer::Answer) -> Result<RowResults> {
        let mut row = RowResults::from(answer);
        if let Some(histories) = &answer.station_histories {
            let settings = crate::model::fatigue_fields::of(&answer.resolved);
            row.fatigue = RowFatigue::of(&crate::run_fatigue::assess(histories, &settings)?);
        }
        Ok(row)
    }
}

/// The design quantities a load case is judged on ([`crate::load_cases::design_quantities`]'s
/// names): the three stress peaks of Table 1, then each beam's envelope.
pub const GOVERNING_QUANTITIES: [&str; 7] = [
    "lower.clamp_bending_stress",
    "lower.clamp_shear_stress",
    "upper.contact_bending_stress",
    ENVELOPE_PEAK_NAMES[0],
    ENVELOPE_PEAK_NAMES[1],
    ENVELOPE_PEAK_NAMES[2],
    ENVELOPE_PEAK_NAMES[3],
];

/// Each of [`GOVERNING_QUANTITIES`]' governing case in `answer` (its index among the cases and
/// its factored utilisation), None without load cases.
fn governing_cases(answer: &crate::answer::Answer) -> [Option<(usize, f64)>; GOVERNING_QUANTITIES.len()] {
    let Some(cases) = &answer.load_cases else { return [None; GOVERNING_QUANTITIES.len()] };
    GOVERNING_QUANTITIES.map(|q| {
        let g = cases.governing.get(q)?;
        let index = cases.cases.iter().position(|c| c.name == g.case)?;
        Some((index, g.utilisation))
    })
}

/// The SI units of [`ENERGY_METHOD_FIELDS`], in their order.
const ENERGY_METHOD_UNITS: [&str; 11] = ["N/m", "m", "N", "Pa", "Pa", "J", "rad/s^2", "N m", "Pa", "J", "1"];

/// One scenario of the grid: its values (one per axis), its results or error message, and the
/// wall time it took.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The varied fields' values, parameter form, in the order of the axes.
    pub values: Vec<f64>,
    /// The results, or the one-line error.
    pub outcome: std::result::Result<RowResults, String>,
    /// Wall time of the scenario's answer (its rungs and twin, in parallel), s: shorter for a row
    /// whose modes an earlier row of its geometry computed.
    pub wall_time: f64,
}

/// The named columns with their units: the varied fields, `peak.<quantity>`,
/// `peak_time.<quantity>`, `energy_method.<field>`, `max_energy_residual`, the checks and the
/// design, `quality.trusted`, `wall_time`, `error`; then the former names, duplicates of named columns, until
/// [`crate::vocabulary::FORMER_NAMES_REMOVED_IN`].
pub fn column_units(axes: &[Axis]) -> Vec<(String, &'static str)> {
    column_units_with(axes, false)
}

/// [`column_units`], with the [`FATIGUE_COLUMNS`] after the checks' when `fatigue` (a sweep
/// with [`Sweep::fatigue`]).
pub fn column_units_with(axes: &[Axis], fatigue: bool) -> Vec<(String, &'static str)> {
    let mut c: Vec<(String, &'static str)> = axes.iter().map(|a| (a.field.name.to_string(), a.field.unit)).collect();
    c.extend(PEAK_QUANTITIES.iter().zip(PEAK_UNITS).map(|(n, u)| (format!("peak.{n}"), u)));
    c.extend(PEAK_QUANTITIES.iter().map(|n| (format!("peak_time.{n}"), "s")));
    c.extend(ENVELOPE_PEAK_NAMES.iter().map(|n| (format!("peak.{n}"), "Pa")));
    c.extend(ENVELOPE_PEAK_NAMES.iter().map(|n| (format!("peak_position.{n}"), "m")));
    c.extend(ENVELOPE_PEAK_NAMES.iter().map(|n| (format!("utilisation.{n}"), "1")));
    c.extend(ENERGY_METHOD_FIELDS.iter().zip(ENERGY_METHOD_UNITS).map(|((n, _), u)| (format!("energy_method.{n}"), u)));
    c.push(("max_energy_residual".into(), "J"));
    c.extend(CHECK_COLUMNS.iter().map(|(n, u)| (n.to_string(), *u)));
    if fatigue {
        c.extend(FATIGUE_COLUMNS.iter().map(|(n, u)| (n.to_string(), *u)));
    }
    c.extend([("quality.trusted".into(), "true/false"), ("wall_time".into(), "s"), ("error".into(), "text")]);
    let named = c.len();
    for (former, name) in sweep_former_names() {
        let unit = c[..named].iter().find(|(n, _)| *n == name).map_or("", |(_, u)| *u);
        c.push((former, unit));
    }
    c
}

/// The column names of [`column_units`].
pub fn columns(axes: &[Axis]) -> Vec<String> {
    columns_with(axes, false)
}

/// The column names of [`column_units_with`].
pub fn columns_with(axes: &[Axis], fatigue: bool) -> Vec<String> {
    column_units_with(axes, fatigue).into_iter().map(|(name, _)| name).collect()
}

/// A cell before formatting.
#[derive(Clone)]
enum Cell {
    Value(&'static Parameter, f64),
    Number(f64),
    Bool(bool),
    Text(String),
    Empty,
}

fn cells(axes: &[Axis], row: &Row, fatigue: bool) -> Vec<Cell> {
    let mut c: Vec<Cell> = axes.iter().zip(&row.values).map(|(a, &v)| Cell::Value(a.field, v)).collect();
    match &row.outcome {
        Ok(r) => {
            c.extend(r.peaks.as_array().map(Cell::Number));
            c.extend(r.peak_times.as_array().map(Cell::Number));
            let given = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Number);
            c.extend(r.envelope_peaks.map(|p| given(p.map(|p| p.value))));
            c.extend(r.envelope_peaks.map(|p| given(p.map(|p| p.position))));
            c.extend(r.utilisation.envelope().map(given));
            c.extend(ENERGY_METHOD_FIELDS.iter().map(|(_, get)| Cell::Number(get(&r.energy_method))));
            c.push(Cell::Number(r.max_energy_residual));
            let optional = |v: f64| if v.is_nan() { Cell::Empty } else { Cell::Number(v) };
            c.extend([optional(r.discretisation_error), optional(r.sensitivity_spread), optional(r.yield_utilisation)]);
            c.extend(r.utilisation.as_array().map(Cell::Number));
            c.extend([Cell::Bool(r.design_pass), optional(r.load_case_utilisation)]);
            if fatigue {
                c.extend(fatigue_cells(r.fatigue.as_ref()));
            }
            c.extend([Cell::Bool(r.trusted), Cell::Number(row.wall_time)]);
            c.push(Cell::Text(String::new()));
        }
        Err(message) => {
            c.extend(
                (0..2 * PEAK_NAMES.len()
                    + 3 * ENVELOPE_PEAK_NAMES.len()
                    + ENERGY_METHOD_FIELDS.len()
                    + 2
                    + CHECK_COLUMNS.len()
                    + if fatigue { FATIGUE_COLUMNS.len() } else { 0 })
                    .map(|_| Cell::Empty),
            );
            c.push(Cell::Number(row.wall_time));
            c.push(Cell::Text(one_line(message)));
        }
    }
    // The former names repeat their named columns' cells.
    let names = columns_with(axes, fatigue);
    for (_, name) in sweep_former_names() {
        let i = names.iter().position(|n| *n == name).unwrap_or(0);
        c.push(c.get(i).cloned().unwrap_or(Cell::Empty));
    }
    c
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The CSV header line (with its line break).
pub fn csv_header(axes: &[Axis]) -> String {
    csv_header_with(axes, false)
}

/// [`csv_header`] of [`columns_with`].
pub fn csv_header_with(axes: &[Axis], fatigue: bool) -> String {
    columns_with(axes, fatigue).iter().map(|c| csv_field(c)).collect::<Vec<_>>().join(",") + "\n"
}

/// One CSV line: numbers as the shortest decimal that gives the same f64, `true`/`false`, and
/// empty cells for the results of a failed scenario.
pub fn csv_line(axes: &[Axis], row: &Row) -> String {
    csv_line_with(axes, row, false)
}

/// [`csv_line`] of [`columns_with`].
pub fn csv_line_with(axes: &[Axis], row: &Row, fatigue: bool) -> String {
    let text: Vec<String> = cells(axes, row, fatigue)
        .into_iter()
        .map(|cell| match cell {
            Cell::Value(field, v) => csv_field(&format_value(field, v)),
            Cell::Number(x) => format!("{x}"),
            Cell::Bool(b) => format!("{b}"),
            Cell::Text(t) => csv_field(&t),
            Cell::Empty => String::new(),
        })
        .collect();
    text.join(",") + "\n"
}

fn json_string(text: &str) -> String {
    serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into())
}

fn json_number(x: f64) -> String {
    // serde_json writes the shortest round-trip decimal, and null for NaN and infinities.
    serde_json::to_string(&x).unwrap_or_else(|_| "null".into())
}

/// One row as a JSON object, the keys in column order; a failed scenario's results are null and
/// `error` is its message (an empty string when fine).
pub fn json_object(axes: &[Axis], row: &Row) -> String {
    json_object_with(axes, row, false)
}

/// [`json_object`] of [`columns_with`].
pub fn json_object_with(axes: &[Axis], row: &Row, fatigue: bool) -> String {
    let mut s = String::from("{");
    for (k, (name, cell)) in columns_with(axes, fatigue).iter().zip(cells(axes, row, fatigue)).enumerate() {
        let value = match cell {
            Cell::Value(field, v) => json_value(field, v),
            Cell::Number(x) => json_number(x),
            Cell::Bool(b) => format!("{b}"),
            Cell::Text(t) => json_string(&t),
            Cell::Empty => "null".into(),
        };
        let _ = write!(s, "{}{}: {value}", if k == 0 { "" } else { ", " }, json_string(name));
    }
    s + "}"
}

/// A sweep: the base scenario, the grid and the step limit of each run.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The scenario every grid point starts from (a file or the paper's, with `--set` applied).
    pub base: Scenario,
    /// The varied fields, outermost first.
    pub axes: Vec<Axis>,
    /// Largest number of internal steps a run may need (as `run --max-steps`).
    pub max_steps: u64,
    /// The points to run, one value per axis each, when they are not the axes' product (a
    /// campaign's events, issue 43); empty: the product grid.
    pub points: Vec<Vec<f64>>,
    /// Assess each row's fatigue (`sweep --fatigue`, issue 44): the printed run keeps every
    /// station's turning points (about 1.6 times a row's work) and the row gets the
    /// [`FATIGUE_COLUMNS`].
    pub fatigue: bool,
}

/// How a sweep went.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Scenarios run.
    pub scenarios: usize,
    /// Scenarios with an error (invalid, or the run failed).
    pub failed: usize,
    /// Scenarios that ran but are not trusted by their energy balance.
    pub untrusted: usize,
}

impl Sweep {
    /// A sweep of `base` over `axes`; checks the grid's size.
    pub fn new(base: Scenario, axes: Vec<Axis>, max_steps: u64) -> Result<Sweep> {
        grid_len(&axes)?;
        Ok(Sweep { base, axes, max_steps, points: Vec::new(), fatigue: false })
    }

    /// A sweep of `base` over the given `points` (each one value per axis, in the axes' order),
    /// run and written in their order; the axes name the columns.
    pub fn of_points(base: Scenario, axes: Vec<Axis>, points: Vec<Vec<f64>>, max_steps: u64) -> Result<Sweep> {
        if points.len() > MAX_SCENARIOS {
            return Err(Error::Other(format!("{} scenarios, more than {MAX_SCENARIOS}", points.len())));
        }
        if let Some(p) = points.iter().find(|p| p.len() != axes.len()) {
            return Err(Error::Other(format!("a point of {} values for {} axes", p.len(), axes.len())));
        }
        Ok(Sweep { base, axes, max_steps, points, fatigue: false })
    }

    /// Scenarios in the grid.
    pub fn len(&self) -> usize {
        if self.points.is_empty() {
            self.axes.iter().map(|a| a.values.len()).product()
        } else {
            self.points.len()
        }
    }

    /// The values of scenario `index`, one per axis.
    pub fn point(&self, index: usize) -> Vec<f64> {
        match self.points.get(index) {
            Some(point) => point.clone(),
            None => grid_point(&self.axes, index),
        }
    }

    /// Whether the grid is empty (never: an axis has at least one value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The scenario of grid point `values`, validated (every invalid field in one error).
    pub fn scenario(&self, values: &[f64]) -> Result<Scenario> {
        let mut scenario = self.base.clone();
        let settings: Vec<Setting> =
            self.axes.iter().zip(values).map(|(axis, &value)| Setting { field: axis.field, value }).collect();
        apply_settings(&mut scenario, &settings)?;
        Ok(scenario)
    }

    /// Runs grid point `index` as `beam-impact run --no-mcap` does, with the modes of its rungs
    /// from `cache` (the same numbers to the bit); an error or a panic becomes the row's message.
    pub fn run_one(&self, index: usize, cache: &ModalCache) -> Row {
        let started = std::time::Instant::now();
        let values = self.point(index);
        let run = || -> Result<RowResults> {
            let scenario = self.scenario(&values)?;
            let options = crate::answer::Options {
                max_steps: self.max_steps,
                observed_order: false,
                station_envelope: self.fatigue,
                ..Default::default()
            };
            let answer = answer_with_cases(&scenario, &mut NullRecorder, options, cache, &Default::default())?;
            if self.fatigue {
                RowResults::with_fatigue(&answer)
            } else {
                Ok(RowResults::from(&answer))
            }
        };
        let outcome = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(run)) {
            Ok(result) => result.map_err(|e| e.to_string()),
            Err(panic) => Err(format!(
                "internal error: {}",
                panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("panic")
            )),
        };
        Row { values, outcome, wall_time: started.elapsed().as_secs_f64() }
    }

    /// The order the grid points run in: within each [`GROUP_WINDOW`] consecutive points, those of
    /// one geometry together (the values of the axes outside
    /// [`crate::solver::modal_cache::PER_RUN_FIELDS`], in grid order), so that a row finds its
    /// modes in the cache while at most a window of finished rows waits for its turn to be written.
    pub fn execution_order(&self) -> Vec<usize> {
        // A sea's fields move the supports, never the modes (issue 42): per run, as the motion's shift.
        let geometry: Vec<bool> = self
            .axes
            .iter()
            .map(|a| !PER_RUN_FIELDS.contains(&a.field.name) && !a.field.name.starts_with("sea."))
            .collect();
        let positions = |mut index: usize| -> Vec<usize> {
            let mut key = vec![0; self.axes.len()];
            for ((k, axis), shape) in key.iter_mut().zip(&self.axes).zip(&geometry).rev() {
                let n = axis.values.len();
                if *shape {
                    *k = index % n;
                }
                index /= n;
            }
            key
        };
        let mut order: Vec<usize> = (0..self.len()).collect();
        if self.points.is_empty() && geometry.iter().any(|g| *g) {
            for window in order.chunks_mut(GROUP_WINDOW) {
                window.sort_by_cached_key(|&i| positions(i));
            }
        }
        order
    }

    /// Runs every scenario on `jobs` threads (each takes the next grid point of
    /// [`Sweep::execution_order`] when it is free; the rows share one [`ModalCache`]) and
    /// hands the rows to `write` in grid order as soon as they and all before them are done, so
    /// that only the rows finished out of order are held. `done` is called after each scenario
    /// with the number finished so far. A `write` error stops the sweep (the running scenarios
    /// finish, no new one starts) and is returned.
    pub fn run(
        &self,
        jobs: usize,
        done: &mut dyn FnMut(usize),
        write: &mut dyn FnMut(&Row) -> Result<()>,
    ) -> Result<Tally> {
        self.run_until(jobs, &AtomicBool::new(false), done, write)
    }

    /// [`Sweep::run`] until `cancel` is set: then no new scenario starts, the running ones finish
    /// and the rows before the first not run are written (in order); the tally counts them.
    pub fn run_until(
        &self,
        jobs: usize,
        cancel: &AtomicBool,
        done: &mut dyn FnMut(usize),
        write: &mut dyn FnMut(&Row) -> Result<()>,
    ) -> Result<Tally> {
        let n = self.len();
        let jobs = jobs.clamp(1, n.max(1));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .thread_name(|k| format!("sweep-{k}"))
            .build()
            .map_err(|e| Error::Other(format!("cannot start {jobs} sweep threads: {e}")))?;
        let next = AtomicUsize::new(0);
        let stop = AtomicBool::new(false);
        let order = self.execution_order();
        let cache = ModalCache::default();
        let (sender, receiver) = mpsc::channel::<(usize, Row)>();
        let mut tally = Tally::default();
        std::thread::scope(|scope| {
            let (next, stop, order, cache) = (&next, &stop, &order, &cache);
            scope.spawn(move || {
                pool.broadcast(|_| loop {
                    if stop.load(Ordering::Relaxed) || cancel.load(Ordering::Relaxed) {
                        break;
                    }
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= n {
                        break;
                    }
                    let index = order[k];
                    if sender.send((index, self.run_one(index, cache))).is_err() {
                        break;
                    }
                });
                // `sender` drops here: the receiving loop ends once every row is in.
            });
            let mut pending: BTreeMap<usize, Row> = BTreeMap::new();
            let mut expected = 0;
            for (finished, (index, row)) in receiver.iter().enumerate() {
                done(finished + 1);
                pending.insert(index, row);
                while let Some(row) = pending.remove(&expected) {
                    tally.scenarios += 1;
                    match &row.outcome {
                        Err(_) => tally.failed += 1,
                        Ok(r) if !r.trusted => tally.untrusted += 1,
                        Ok(_) => {}
                    }
                    if let Err(e) = write(&row) {
                        stop.store(true, Ordering::Relaxed);
                        return Err(e);
                    }
                    expected += 1;
                }
            }
            Ok(())
        })?;
        Ok(tally)
    }

    /// Runs the sweep into `csv` (and `json`, an array of row objects, one per line), writing each
    /// row as soon as it is in grid order; `done` as in [`Sweep::run`].
    pub fn write(
        &self,
        jobs: usize,
        csv: &mut dyn Write,
        json: Option<&mut dyn Write>,
        done: &mut dyn FnMut(usize),
    ) -> std::result::Result<Tally, SweepWriteError> {
        self.write_observed(jobs, csv, json, done, &mut |_| {})
    }

    /// [`Sweep::write`], handing each row to `observe` too once written (the governing load
    /// cases and the worst fatigue row the CLI prints: [`crate::studies::sweep_governing`]).
    pub fn write_observed(
        &self,
        jobs: usize,
        csv: &mut dyn Write,
        mut json: Option<&mut dyn Write>,
        done: &mut dyn FnMut(usize),
        observe: &mut dyn FnMut(&Row),
    ) -> std::result::Result<Tally, SweepWriteError> {
        csv.write_all(csv_header_with(&self.axes, self.fatigue).as_bytes()).map_err(SweepWriteError::Csv)?;
        if let Some(j) = json.as_deref_mut() {
            j.write_all(b"[").map_err(SweepWriteError::Json)?;
        }
        let mut first = true;
        let mut failure = None;
        let result = self.run(jobs, done, &mut |row| {
            let fatigue = self.fatigue;
            let outcome = csv
                .write_all(csv_line_with(&self.axes, row, fatigue).as_bytes())
                .map_err(SweepWriteError::Csv)
                .and_then(|()| match json.as_deref_mut() {
                    Some(j) => {
                        let separator = if first { "\n" } else { ",\n" };
                        j.write_all(format!("{separator}{}", json_object_with(&self.axes, row, fatigue)).as_bytes())
                            .map_err(SweepWriteError::Json)
                    }
                    None => Ok(()),
                });
            first = false;
            if outcome.is_ok() {
                observe(row);
            }
            outcome.map_err(|e| {
                let message = e.to_string();
                failure = Some(e);
                Error::Other(message)
            })
        });
        let tally = match result {
            Ok(tally) => tally,
            Err(e) => return Err(failure.unwrap_or(SweepWriteError::Run(e))),
        };
        csv.flush().map_err(SweepWriteError::Csv)?;
        if let Some(j) = json {
            j.write_all(b"\n]\n").and_then(|()| j.flush()).map_err(SweepWriteError::Json)?;
        }
        Ok(tally)
    }
}

/// Why [`Sweep::write`] stopped: which output failed, or the sweep itself.
#[derive(Debug, thiserror::Error)]
pub enum SweepWriteError {
    /// Writing the CSV failed.
    #[error("CSV: {0}")]
    Csv(std::io::Error),
    /// Writing the JSON failed.
    #[error("JSON: {0}")]
    Json(std::io::Error),
    /// The sweep could not start.
    #[error("{0}")]
    Run(Error),
}

/// Threads a sweep uses by default: every core.
pub fn default_jobs() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(text: &str) -> Axis {
        parse_axis(text).unwrap()
    }

    /// The grid is `itertools.product` of the axes: the first axis outermost, the last fastest.
    /// Source: the Python documentation of itertools.product, whose example
    /// product('AB', 'xy') is Ax Ay Bx By.
    #[test]
    fn grid_is_the_product_with_the_last_axis_fastest() {
        let axes = [axis("drop_height=1,2"), axis("damping_ratio=0.1,0.2,0.3")];
        let grid = expand(&axes);
        let expected: Vec<Vec<f64>> =
            [1.0, 2.0].iter().flat_map(|&h| [0.1, 0.2, 0.3].iter().map(move |&g| vec![h, g])).collect();
        assert_eq!(grid, expected);
        assert_eq!(grid_len(&axes).unwrap(), 6);
        for (i, point) in grid.iter().enumerate() {
            assert_eq!(&grid_point(&axes, i), point);
        }
        // No axis: one scenario, the base (product() yields one empty tuple).
        assert_eq!(expand(&[]), vec![Vec::<f64>::new()]);
    }

    /// start:stop:count is inclusive and linear, to 15 significant digits (Python's
    /// `float(f"{start + (stop - start) * i / (count - 1):.14e}")`, the same bits).
    #[test]
    fn ranges_are_inclusive_and_linear() {
        assert_eq!(axis("drop_height=0.1:0.5:5").values, vec![0.1, 0.2, 0.3, 0.4, 0.5]);
        assert_eq!(axis("drop_height=0.2:1:3").values, vec![0.2, 0.6, 1.0]);
        assert_eq!(axis("drop_height=0.7:2:1").values, vec![0.7]);
        assert_eq!(axis("drop_height=1:0:3").values, vec![1.0, 0.5, 0.0]);
        let v = axis("damping_ratio=0.005:0.05:10").values;
        assert_eq!(v.len(), 10);
        assert_eq!((v[0], v[9]), (0.005, 0.05));
    }

    /// A range's endpoints are finite (issue 40's re-test: `nan:1:3` ran rows that all failed,
    /// `1e308:-1e308:3` put -inf in the middle row), and a span that overflows still gives the
    /// points between: 1e308 (1 - 1/2) - 1e308 / 2 = 0 exactly.
    #[test]
    fn ranges_refuse_non_finite_endpoints_and_never_overflow() {
        for spec in ["nan:1:3", "0:inf:3", "-inf:0:2", "1:NaN:1"] {
            let e = parse_axis(&format!("drop_height={spec}")).unwrap_err().to_string();
            assert!(e.contains("must be finite numbers") && e.contains("drop_height"), "{spec}: {e}");
        }
        assert_eq!(axis("upper.tip_force=1e308:-1e308:3").values, vec![1e308, 0.0, -1e308]);
        let wide = linspace(-1.7e308, 1.7e308, 5);
        assert!(wide.iter().all(|v| v.is_finite()), "{wide:?}");
        assert!(wide.windows(2).all(|w| w[0] < w[1]), "{wide:?}");
    }

    /// Integer fields: rounded half away from zero, duplicates dropped with the first kept.
    #[test]
    fn integer_fields_are_rounded_and_deduplicated() {
        assert_eq!(axis("lower.elements=4:8:9").values, vec![4.0, 5.0, 6.0, 7.0, 8.0]);
        assert_eq!(axis("lower.elements=7,3,7,2.5").values, vec![7.0, 3.0]);
        // Reals are kept as given, repeats too.
        assert_eq!(axis("drop_height=0.5,0.5").values, vec![0.5, 0.5]);
    }

    /// Names per field: `auto` for the time steps, the stress recoveries by name (a range too).
    #[test]
    fn values_are_read_per_field_and_written_back() {
        let steps = axis("step_free=auto,5e-5");
        assert_eq!(steps.values, vec![0.0, 5e-5]);
        assert_eq!(format_value(steps.field, 0.0), "auto");
        let recovery = axis("stress_recovery=mean:right:3");
        assert_eq!(recovery.values, vec![0.0, 1.0, 2.0]);
        assert_eq!(format_value(recovery.field, 2.0), "right");
        assert_eq!(axis("upper.tip_force=-1000,0").values, vec![-1000.0, 0.0]);
        for (field, text) in [("drop_height", "0.30000000000000004"), ("lower.elements", "7"), ("step_free", "auto")] {
            let f = super::field(field).unwrap();
            assert_eq!(format_value(f, parse_value(f, text).unwrap()), text);
        }
    }

    /// Bad options are one-line errors naming the key.
    #[test]
    fn bad_specs_name_the_key() {
        for (text, needle) in [
            ("nonsense=1,2", "unknown parameter `nonsense`"),
            ("drop_height", "--vary expects KEY=SPEC"),
            ("drop_height=1:2", "start:stop:count"),
            ("drop_height=1:2:0", "count"),
            ("drop_height=1,,2", "drop_height takes a number in m, got ``"),
            ("stress_recovery=middle", "stress_recovery takes mean, left or right, got `middle`"),
            ("step_free=fast", "step_free takes a time step in s or \"auto\""),
        ] {
            let e = parse_axis(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text}: {e}");
            assert_eq!(e.lines().count(), 1);
        }
        let twice = parse_axes(&["drop_height=1".into(), "drop_height=2".into()]).unwrap_err().to_string();
        assert!(twice.contains("drop_height is given twice"), "{twice}");
        let e = parse_setting("upper.mass").unwrap_err().to_string();
        assert!(e.contains("--set expects KEY=VALUE"), "{e}");
    }

    /// `--set` changes the named fields and validates the whole scenario; the default log is the
    /// scenario's own and never `paper.mcap`.
    #[test]
    fn settings_apply_validate_and_name_their_log() {
        let settings =
            parse_settings(&["upper.mass=14000".into(), "drop_height=0.8".into(), "step_contact=auto".into()]).unwrap();
        let mut s = Scenario::paper();
        apply_settings(&mut s, &settings).unwrap();
        assert_eq!((s.upper.mass, s.drop_height, s.step_contact), (14000.0, 0.8, crate::model::TimeStep::Auto));
        let log = default_log(None, &settings, &s);
        assert_ne!(log, PathBuf::from("paper.mcap"));
        assert!(log.to_string_lossy().starts_with("paper-set-"), "{}", log.display());
        assert_eq!(default_log(None, &settings, &s), log, "the same settings, the same log");
        let other = default_log(Some(Path::new("dir/arrestor.toml")), &settings[..1], &Scenario::paper());
        assert!(other.to_string_lossy().starts_with("dir/arrestor-set-"), "{}", other.display());
        assert_eq!(default_log(None, &[], &s), PathBuf::from("paper.mcap"));

        let mut bad = Scenario::paper();
        let e = apply_settings(&mut bad, &parse_settings(&["drop_height=-1".into()]).unwrap()).unwrap_err();
        assert!(e.to_string().starts_with("drop_height must be"), "{e}");
        let e = apply_settings(&mut Scenario::paper(), &parse_settings(&["lower.elements=2.5".into()]).unwrap())
            .unwrap_err();
        assert!(e.to_string().contains("lower.elements"), "{e}");
    }

    /// One name per quantity: every former column duplicates a named column (same cells in CSV
    /// and JSON), every column has a unit, and the named ones come first.
    #[test]
    fn former_columns_duplicate_named_ones_and_every_column_has_a_unit() {
        let axes = vec![axis("drop_height=0.5")];
        let units = column_units(&axes);
        let names = columns(&axes);
        let former = sweep_former_names();
        assert_eq!(names.len(), units.len());
        let first_former = names.len() - former.len();
        assert_eq!(names[first_former - 1], "error");
        for (name, unit) in &units {
            assert!(!unit.is_empty() || name == "drop_height", "{name} has no unit");
        }
        assert_eq!(units[0].1, "m");
        let row = Row {
            values: vec![0.5],
            outcome: Ok(RowResults::from(
                &crate::answer::run(
                    &Scenario { duration: 0.05, ..Scenario::default() },
                    &mut crate::record::NullRecorder,
                    crate::answer::Options::default(),
                )
                .unwrap(),
            )),
            wall_time: 1.5,
        };
        let line = csv_line(&axes, &row);
        let cells: Vec<&str> = line.trim_end().split(',').collect();
        assert_eq!(cells.len(), names.len());
        let json: serde_json::Value = serde_json::from_str(&json_object(&axes, &row)).unwrap();
        for (f, n) in &former {
            let (i, j) = (names.iter().position(|c| c == f).unwrap(), names.iter().position(|c| c == n).unwrap());
            assert!(j < first_former && i >= first_former, "{f} -> {n}");
            assert_eq!(cells[i], cells[j], "{f} vs {n}");
            assert_eq!(json[f], json[n], "{f} vs {n}");
            assert_eq!(units[i].1, units[j].1);
        }
        assert_eq!(json["quality.trusted"], json["trusted"]);
        assert!(json["peak.lower.clamp_bending_stress"].as_f64().unwrap() > 1e6);
    }

    /// The column list names every peak of `summary.peaks` and every field of EnergyMethod, by
    /// their serde names (so a new field cannot be left out silently).
    #[test]
    fn columns_cover_every_peak_and_energy_method_field() {
        let keys = |v: serde_json::Value| -> Vec<String> {
            let mut k: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
            k.sort();
            k
        };
        let mut peaks: Vec<String> = PEAK_NAMES.iter().map(|s| s.to_string()).collect();
        peaks.sort();
        assert_eq!(keys(serde_json::to_value(Peaks::default()).unwrap()), peaks);
        let method = EnergyMethod::new(&Scenario::default());
        let mut names: Vec<String> = ENERGY_METHOD_FIELDS.iter().map(|(n, _)| n.to_string()).collect();
        names.sort();
        assert_eq!(keys(serde_json::to_value(method).unwrap()), names);
        let json = serde_json::to_value(method).unwrap();
        for (name, get) in ENERGY_METHOD_FIELDS {
            assert_eq!(json[name].as_f64().unwrap(), get(&method), "{name}");
        }
        // Peaks::as_array's order is PEAK_NAMES's.
        let p = Peaks {
            lower_tip_deflection: 1.0,
            lower_clamp_bending_stress: 2.0,
            lower_clamp_shear_stress: 3.0,
            upper_contact_bending_stress: 4.0,
            contact_force: 5.0,
        };
        let json = serde_json::to_value(p).unwrap();
        for (name, value) in PEAK_NAMES.iter().zip(p.as_array()) {
            assert_eq!(json[name].as_f64().unwrap(), value, "{name}");
        }
    }

    /// Rows arrive in grid order whatever the thread count; a failing writer stops the sweep with
    /// its error (no hang, no further scenarios started).
    #[test]
    fn rows_come_in_grid_order_and_a_write_error_stops_the_sweep() {
        // The paper's method: its mesh is flagged against the converged answer (not trusted).
        let base = Scenario { duration: 0.002, ..Scenario::paper() };
        let axes = vec![axis("drop_height=0.2:0.8:4"), axis("contact_position=13,40")];
        let sweep = Sweep::new(base, axes, crate::model::scenario::MAX_STEPS).unwrap();
        let mut seen = Vec::new();
        let mut finished = 0;
        let tally = sweep
            .run(3, &mut |n| finished = n, &mut |row| {
                seen.push(row.values.clone());
                Ok(())
            })
            .unwrap();
        assert_eq!(seen, expand(&sweep.axes));
        assert_eq!((finished, tally), (8, Tally { scenarios: 8, failed: 4, untrusted: 4 }));

        struct Failing(usize);
        impl Write for Failing {
            fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
                if self.0 == 0 {
                    return Err(std::io::Error::other("disk full"));
                }
                self.0 -= 1;
                Ok(buf.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let e = sweep.write(2, &mut Failing(3), None, &mut |_| {}).unwrap_err();
        assert!(matches!(e, SweepWriteError::Csv(_)), "{e}");
        assert_eq!(e.to_string(), "CSV: disk full");
    }

    /// Rows: an error is quoted in CSV when it holds a comma, results are empty there; JSON rows
    /// parse, with null results.
    #[test]
    fn csv_and_json_rows() {
        let axes = vec![axis("drop_height=0.5"), axis("step_free=auto")];
        let failed = Row { values: vec![0.5, 0.0], outcome: Err("a, \"b\"\nc".into()), wall_time: 0.25 };
        let line = csv_line(&axes, &failed);
        assert!(line.starts_with("0.5,auto,,"), "{line}");
        // `error` is the last named column; the former names (all empty here) follow it.
        let former = ",".repeat(sweep_former_names().len());
        assert!(line.ends_with(&format!(",\"a, \"\"b\"\" c\"{former}\n")), "{line}");
        assert_eq!(csv_header(&axes).split(',').count(), columns(&axes).len());
        let doc: serde_json::Value = serde_json::from_str(&json_object(&axes, &failed)).unwrap();
        assert_eq!(doc["step_free"], "auto");
        assert!(doc["peak.lower.tip_deflection"].is_null());
        assert!(doc["lower_tip_deflection"].is_null());
        assert_eq!(doc["error"], "a, \"b\" c");
    }
}
