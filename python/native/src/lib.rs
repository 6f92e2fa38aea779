//! `beam_impact._native`: the Rust log reader of `beam-impact report` for the Python package, so
//! that `beam_impact.load_log` inherits every bound of `replay::safe_read` (time linear in the
//! file, memory the file plus one chunk plus at most 16x the file kept) and no log is read by two
//! codes. The Python side (`beam_impact/log.py`) turns the flat buffers into numpy arrays.
//! `check_run` holds `beam_impact.simulate` to the CLI's limits before the FMU steps.
//! `parse_vary` and `parse_value` are the CLI's `--vary` and value parsers (one grammar of numbers).
//! Every file the package writes goes through the CLI's output guard (`write_file`,
//! `check_output`), and an FMU is read only if it is a regular file under `MAX_FMU_BYTES` (1 GiB)
//! (`fmu_key`, `read_fmu`), issue 27. `run` runs the solver itself, as `beam-impact run` does
//! (`run.rs`), for `beam_impact.run`; `sweep_row` and `sweep_columns` give the sweeps' native
//! engine the rows and the columns of `beam-impact sweep`, from the CLI's own row code.
//! `Campaign` and `campaign_sources` are `beam-impact campaign`'s plan, rows and statistics for
//! `beam_impact.campaign` (`campaign.rs`).

mod campaign;
mod run;

use std::collections::HashMap;
use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use beam_impact::model::motion_table::MotionTable;
use beam_impact::model::parameters;
use beam_impact::model::support_motion::MOTION_NAMES;
use beam_impact::record::output::{
    check_distinct, check_size, open_output, open_regular_input, partial_for, shown, OutputFile,
};
use beam_impact::replay::report::{envelope_of_log, read_log_with, EnvelopeSource, LogData, ReadOptions};
use beam_impact::results::StepResult;
use beam_impact::studies::sweep;
use beam_impact::{Error, Scenario, Simulation};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

/// One float column of the step channel: its name and how to read it from a step.
type Column = (&'static str, fn(&StepResult) -> f64);

/// The step channel's float columns, as in `beam_impact.log.SCALARS` (dotted for nested fields).
const FLOAT_COLUMNS: &[Column] = &[
    ("time", |r| r.time),
    ("step_size", |r| r.step_size),
    ("lower_tip_deflection", |r| r.lower_tip_deflection),
    ("upper_contact_deflection", |r| r.upper_contact_deflection),
    ("upper_tip_deflection", |r| r.upper_tip_deflection),
    ("lower_clamp_bending_stress", |r| r.lower_clamp_bending_stress),
    ("lower_clamp_shear_stress", |r| r.lower_clamp_shear_stress),
    ("upper_contact_bending_stress", |r| r.upper_contact_bending_stress),
    ("contact_force", |r| r.contact_force),
    ("contact_stress", |r| r.contact_stress),
    ("lower_clamp_reaction_force", |r| r.lower_clamp_reaction_force),
    ("lower_clamp_reaction_moment", |r| r.lower_clamp_reaction_moment),
    ("upper_hinge_reaction_force", |r| r.upper_hinge_reaction_force),
    ("lower_tip_velocity", |r| r.lower_tip_velocity),
    ("upper_tip_velocity", |r| r.upper_tip_velocity),
    ("lower_far_reaction_force", |r| r.lower_far_reaction_force),
    ("lower_far_reaction_moment", |r| r.lower_far_reaction_moment),
    ("energy.kinetic", |r| r.energy.kinetic),
    ("energy.strain", |r| r.energy.strain),
    ("energy.gravity_potential", |r| r.energy.gravity_potential),
    ("energy.external_work", |r| r.energy.external_work),
    ("energy.damping_dissipation", |r| r.energy.damping_dissipation),
    ("energy.residual", |r| r.energy.residual),
    ("peaks.lower_tip_deflection", |r| r.peaks.lower_tip_deflection),
    ("peaks.lower_clamp_bending_stress", |r| r.peaks.lower_clamp_bending_stress),
    ("peaks.lower_clamp_shear_stress", |r| r.peaks.lower_clamp_shear_stress),
    ("peaks.upper_contact_bending_stress", |r| r.peaks.upper_contact_bending_stress),
    ("peaks.contact_force", |r| r.peaks.contact_force),
];

/// `values` as native-endian bytes (numpy's `frombuffer` reads them without a copy per value).
fn f64_bytes<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.flat_map(f64::to_ne_bytes).collect();
    PyBytes::new(py, &bytes)
}

fn u64_bytes<'py>(py: Python<'py>, values: impl Iterator<Item = u64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.flat_map(u64::to_ne_bytes).collect();
    PyBytes::new(py, &bytes)
}

/// The step channel, column by column: name -> bytes (u64 for `step` and `time_ns`, one byte
/// per step for `contact`, f64 otherwise).
pub(crate) fn columns<'py>(py: Python<'py>, steps: &[StepResult]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("step", u64_bytes(py, steps.iter().map(|r| r.step)))?;
    out.set_item("time_ns", u64_bytes(py, steps.iter().map(|r| r.time_ns)))?;
    let contact: Vec<u8> = steps.iter().map(|r| u8::from(r.contact)).collect();
    out.set_item("contact", PyBytes::new(py, &contact))?;
    for (name, get) in FLOAT_COLUMNS {
        out.set_item(*name, f64_bytes(py, steps.iter().map(get)))?;
    }
    Ok(out)
}

/// Everything `beam_impact.load_log` needs from `data`, as plain Python objects and buffers.
fn to_python<'py>(py: Python<'py>, data: &LogData) -> PyResult<Bound<'py, PyDict>> {
    let model = data.model.as_ref().ok_or_else(|| {
        let why = data.problem.as_deref().map_or(String::new(), |p| format!(" ({p})"));
        value_error(format!("no /beam/model message{why}"))
    })?;
    let (rows, cols) = (model.shape_rows as usize, model.shape_cols as usize);
    if rows.checked_mul(cols) != Some(model.nodal_shapes.len()) {
        return Err(PyValueError::new_err(format!(
            "the model message's nodal shapes hold {} values, not {rows} x {cols}",
            model.nodal_shapes.len()
        )));
    }
    let history = &data.history;
    if !history.modal_steps.is_empty() && history.width != cols {
        return Err(PyValueError::new_err(format!(
            "modal coordinate rows hold {} values where the model has {cols} modes",
            history.width
        )));
    }
    let out = PyDict::new(py);
    out.set_item("steps", columns(py, &data.steps)?)?;
    out.set_item("modal_steps", u64_bytes(py, history.modal_steps.iter().copied()))?;
    out.set_item("modal_times_ns", u64_bytes(py, history.modal_times_ns.iter().copied()))?;
    out.set_item("modal_coordinates", f64_bytes(py, history.coordinates.iter().copied()))?;
    out.set_item("shape_rows", rows)?;
    out.set_item("shape_cols", cols)?;
    out.set_item("nodal_shapes", f64_bytes(py, model.nodal_shapes.iter().copied()))?;
    out.set_item("lower_nodes", f64_bytes(py, model.lower_nodes.iter().copied()))?;
    out.set_item("upper_nodes", f64_bytes(py, model.upper_nodes.iter().copied()))?;
    let events = PyList::empty(py);
    for e in &data.events {
        events.append((e.start, e.time_ns, e.step, e.relative_velocity))?;
    }
    out.set_item("events", events)?;
    out.set_item("scenario_toml", &model.scenario_toml)?;
    out.set_item("metadata", data.metadata.clone())?;
    out.set_item("log_times", u64_bytes(py, history.log_times.iter().copied()))?;
    out.set_item("counts", data.messages.clone())?;
    out.set_item("complete", data.complete)?;
    out.set_item("damaged", data.damaged)?;
    out.set_item("problem", data.problem.clone().unwrap_or_default())?;
    out.set_item("stopped_early", data.stopped_early.clone().unwrap_or_default())?;
    out.set_item("rollbacks", data.rollbacks)?;
    out.set_item("upper_strain_at_peak_deflection", data.peak_deflection_strain)?;
    out.set_item("log_format", data.log_format)?;
    out.set_item("answer_json", data.answer_json.clone())?;
    out.set_item("motion_csv", data.motion_csv.clone())?;
    stations_to_python(py, data, &out)?;
    fatigue_to_python(data, &out)?;
    Ok(out)
}

/// The run's fatigue (issue 44: as `report --fatigue` has it, from the log's `fatigue.json` or
/// rebuilt from its stations' rows) as the `run --json` block's JSON text, or None with the
/// reason in `fatigue_note`.
fn fatigue_to_python(data: &LogData, out: &Bound<'_, PyDict>) -> PyResult<()> {
    let fatigue = beam_impact::replay::fatigue::fatigue_of_log(data, None)
        .and_then(|f| serde_json::to_string(&f).map_err(|e| beam_impact::Error::Other(format!("JSON: {e}"))));
    match fatigue {
        Ok(text) => {
            out.set_item("fatigue_json", Some(text))?;
            out.set_item("fatigue_note", "")?;
        }
        Err(e) => {
            out.set_item("fatigue_json", None::<String>)?;
            out.set_item("fatigue_note", e.to_string())?;
        }
    }
    Ok(())
}

/// The stress envelope (issue 30: the log's `envelope.json` when sound, else rebuilt from the
/// recorded stresses, as `report` does; per beam and stress its stations' buffers, None when the
/// log holds neither), where it came from, and the stations with their recorded stresses.
fn stations_to_python<'py>(py: Python<'py>, data: &LogData, out: &Bound<'py, PyDict>) -> PyResult<()> {
    let (envelope, source) = envelope_of_log(data);
    let origin = match source {
        EnvelopeSource::Attachment => Some("attachment"),
        EnvelopeSource::Rebuilt { .. } => Some("rebuilt"),
        EnvelopeSource::Absent { .. } => None,
    };
    let envelope = match origin {
        None => None,
        Some(_) => {
            let beams = PyDict::new(py);
            for (name, beam) in [("lower", &envelope.lower), ("upper", &envelope.upper)] {
                let stresses = PyDict::new(py);
                for (stress, e) in [("bending", &beam.bending), ("shear", &beam.shear)] {
                    let group = PyDict::new(py);
                    group.set_item("position", f64_bytes(py, e.positions.iter().copied()))?;
                    group.set_item("max", f64_bytes(py, e.max.iter().copied()))?;
                    group.set_item("time", f64_bytes(py, e.times.iter().copied()))?;
                    group.set_item("allowable", f64_bytes(py, e.allowable.iter().copied()))?;
                    stresses.set_item(stress, group)?;
                }
                beams.set_item(name, stresses)?;
            }
            beams.set_item("sampled_every", envelope.sampled_every)?;
            Some(beams)
        }
    };
    out.set_item("envelope", envelope)?;
    out.set_item("envelope_source", origin)?;
    out.set_item("envelope_note", source.describe())?;
    let record = &data.stations;
    let layout = match &record.layout {
        None => None,
        Some(l) => {
            let groups = PyDict::new(py);
            let names = ["lower.bending", "lower.shear", "upper.bending", "upper.shear"];
            for (name, g) in names.iter().zip(l.groups()) {
                let group = PyDict::new(py);
                group.set_item("positions", f64_bytes(py, g.positions.iter().copied()))?;
                group.set_item("allowable", f64_bytes(py, g.allowable.iter().copied()))?;
                group.set_item("nodes", u64_bytes(py, g.nodes.iter().map(|&n| u64::from(n))))?;
                groups.set_item(*name, group)?;
            }
            groups.set_item("sampled_every", l.sampled_every)?;
            Some(groups)
        }
    };
    out.set_item("station_layout", layout)?;
    out.set_item("station_steps", u64_bytes(py, record.steps.iter().copied()))?;
    out.set_item("station_times_ns", u64_bytes(py, record.times_ns.iter().copied()))?;
    out.set_item("station_values", f64_bytes(py, record.values.iter().map(|&v| f64::from(v))))?;
    Ok(())
}

/// Reads the log at `path` with the Rust reader (every modal coordinate row and log time kept):
/// a dict of buffers and values, or ValueError with one line saying why the file is not a
/// readable beam-impact log. The GIL is released while the file is read.
#[pyfunction]
fn load_log<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let data = py.detach(|| read_log_with(&path, ReadOptions { history: true })).map_err(value_error)?;
    to_python(py, &data)
}

/// Checks a run as the CLI checks it before stepping: `values` (the scenario's parameters by
/// their FMU names; names that are not scenario parameters, such as `check_sensitivity` or
/// `log.path`, are left to the FMU) on the default scenario, validated, and the internal steps
/// to `stop_time` s at most `max_steps`. Returns the steps it needs; ValueError with the CLI's
/// one-line message otherwise. Builds the model and its modes (tens of ms), steps nothing.
#[pyfunction]
fn check_run(py: Python<'_>, values: HashMap<String, f64>, stop_time: f64, max_steps: u64) -> PyResult<u64> {
    let error = |e: beam_impact::Error| value_error(e);
    let mut scenario = Scenario::default();
    for (name, value) in &values {
        if let Ok(parameter) = parameters::find(name) {
            parameters::set(&mut scenario, parameter, *value).map_err(error)?;
        }
    }
    scenario.duration = stop_time;
    scenario.validate().map_err(error)?;
    py.detach(|| {
        let simulation = Simulation::new(&scenario)?;
        simulation.check_step_count(scenario.duration_ns(), max_steps)?;
        let plan = simulation.step_plan();
        Ok(scenario.duration_ns().div_ceil(plan.free_ns.min(plan.contact_ns).max(1)))
    })
    .map_err(error)
}

/// Largest FMU file the package opens, bytes (1 GiB): the FMU is held in memory whole (read
/// once, scattered to a cluster's workers), and `beam-impact pack` refuses a binary over 1 GiB;
/// the FMU of this project is about 2 MB.
const MAX_FMU_BYTES: u64 = 1 << 30;

/// The one-line ValueError of a library error, as the CLI prints it (`bounded_line` of
/// `src/cli/common.rs`): line breaks and tabs as spaces, other control characters (a terminal's
/// escape sequences from a hostile value) as U+FFFD, and a line over 600 characters cut to its
/// first 400 and last 150 with the count cut between.
pub(crate) fn value_error(e: impl ToString) -> PyErr {
    PyValueError::new_err(one_line(&e.to_string()))
}

pub(crate) fn one_line(message: &str) -> String {
    let chars: Vec<char> = message
        .chars()
        .map(|c| match c {
            '\n' | '\r' | '\t' => ' ',
            c if c.is_control() => '\u{FFFD}',
            c => c,
        })
        .collect();
    if chars.len() <= 600 {
        return chars.into_iter().collect();
    }
    let head: String = chars[..400].iter().collect();
    let tail: String = chars[chars.len() - 150..].iter().collect();
    format!("{head} [... {} characters cut ...] {tail}", chars.len() - 550)
}

/// Refuses a path holding a NUL character: the operating system (and fmpy's C strings) would cut
/// the name there, so `results.csv\0.mcap` would write `results.csv`.
pub(crate) fn refuse_nul(role: &str, path: &Path) -> PyResult<()> {
    if path.as_os_str().as_encoded_bytes().contains(&0) {
        return Err(value_error(format!(
            "{role} {}: a path holding a NUL character is refused (the file's name would be cut there)",
            shown(path)
        )));
    }
    Ok(())
}

/// Files a call names, each with its role in messages ("the FMU", "--out").
pub(crate) type Named = Vec<(String, PathBuf)>;

/// The output guard's checks of `path` (`role` in messages), before anything is written: no NUL
/// in any path; not one file (device and inode) with an input or another output, nor the
/// `NAME.partial` of one; not a symbolic link, a folder, a FIFO or a socket; a device only
/// where `allow_devices`, and then only the null device.
pub(crate) fn guard(role: &str, path: &Path, inputs: &Named, others: &Named, allow_devices: bool) -> PyResult<()> {
    if path.as_os_str().is_empty() {
        return Err(value_error(format!("{role}: an empty path is refused (give a file name)")));
    }
    refuse_nul(role, path)?;
    for (r, p) in inputs.iter().chain(others) {
        refuse_nul(r, p)?;
    }
    let mut files: Vec<(&str, &Path)> = inputs.iter().map(|(r, p)| (r.as_str(), p.as_path())).collect();
    files.push((role, path));
    files.extend(others.iter().map(|(r, p)| (r.as_str(), p.as_path())));
    check_distinct(&files).map_err(value_error)?;
    let refused =
        |source| value_error(Error::Io { action: "cannot create", path: format!("{role} {}", shown(path)), source });
    match partial_for(path) {
        Err(e) => Err(refused(e)),
        Ok(Some(_)) => Ok(()),
        Ok(None) if !allow_devices => Err(refused(std::io::Error::other("it is a device, not a regular file"))),
        // Opening checks that the device is the null device (never blocks, writes nothing).
        Ok(None) => open_output(path, true, "cannot create").map(drop).map_err(value_error),
    }
}

/// Checks an output that another writes (the FMU's `log.path`) as the guard would, creating
/// nothing: ValueError with one line if `path` holds a NUL, names one of `inputs` or
/// `other_outputs` (lists of (role, path), compared by device and inode), or is a symbolic link,
/// a folder, a FIFO, a socket or a device (`allow_devices`: the null device is allowed).
#[pyfunction]
#[pyo3(signature = (path, role = "output", inputs = Vec::new(), other_outputs = Vec::new(), allow_devices = false))]
fn check_output(path: PathBuf, role: &str, inputs: Named, other_outputs: Named, allow_devices: bool) -> PyResult<()> {
    guard(role, &path, &inputs, &other_outputs, allow_devices)
}

/// Writes `data` to `path` through the CLI's output guard: the checks of `check_output` (the
/// null device allowed, as the CLI's outputs), then written to `NAME.partial` beside it (created
/// exclusively, never through a link) and renamed over NAME when complete, so an earlier NAME
/// stays whole until then. ValueError with one line otherwise. The GIL is released while writing.
#[pyfunction]
#[pyo3(signature = (path, data, role = "output", inputs = Vec::new(), other_outputs = Vec::new()))]
fn write_file(
    py: Python<'_>,
    path: PathBuf,
    data: &[u8],
    role: &str,
    inputs: Named,
    other_outputs: Named,
) -> PyResult<()> {
    guard(role, &path, &inputs, &other_outputs, true)?;
    py.detach(|| {
        let mut file = OutputFile::create(&path, true, "cannot create")?;
        file.write_all(data).map_err(|source| Error::Io { action: "cannot write", path: shown(&path), source })?;
        file.commit()
    })
    .map_err(value_error)
}

/// Opens the FMU at `path`: a regular file (never a FIFO, a device or a folder: opening never
/// blocks) of at most [`MAX_FMU_BYTES`], its size read from its metadata.
fn open_fmu(path: &Path) -> PyResult<File> {
    refuse_nul("the FMU", path)?;
    let file = open_regular_input(path, "cannot read FMU").map_err(value_error)?;
    check_size(&file, MAX_FMU_BYTES, "the FMU")
        .map_err(|source| value_error(Error::Io { action: "cannot read FMU", path: shown(path), source }))?;
    Ok(file)
}

/// What identifies the FMU file's content for a cache, read from the opened file (after the
/// checks of `read_fmu`): its size, modification time and, on Unix, device and inode.
#[pyfunction]
fn fmu_key(path: PathBuf) -> PyResult<String> {
    let m = open_fmu(&path)?.metadata().map_err(value_error)?;
    let modified = m.modified().ok().and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok());
    let key = format!("{}:{}", m.len(), modified.map_or(0, |d| d.as_nanos()));
    // Not `mut` + `+=`: the Windows build has no Unix part and warned of an unused `mut`.
    #[cfg(unix)]
    let key = {
        use std::os::unix::fs::MetadataExt;
        format!("{key}:{}:{}", m.dev(), m.ino())
    };
    Ok(key)
}

/// The FMU file's bytes: a regular file of at most [`MAX_FMU_BYTES`] (checked before a byte is
/// read, and again while reading), else ValueError with one line. The GIL is released.
#[pyfunction]
fn read_fmu<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyBytes>> {
    let file = open_fmu(&path)?;
    let bytes = py
        .detach(|| {
            let mut bytes = Vec::new();
            file.take(MAX_FMU_BYTES + 1).read_to_end(&mut bytes)?;
            if bytes.len() as u64 > MAX_FMU_BYTES {
                return Err(std::io::Error::other(format!("the FMU is larger than {MAX_FMU_BYTES} bytes (the limit)")));
            }
            Ok(bytes)
        })
        .map_err(|source| value_error(Error::Io { action: "cannot read FMU", path: shown(&path), source }))?;
    Ok(PyBytes::new(py, &bytes))
}

/// `--vary KEY=SPEC` options read by the CLI's parser (`beam-impact sweep --vary`): a list of
/// (field, values) in order, values in parameter form (integer fields rounded, duplicates
/// dropped); ValueError with the CLI's one-line message for anything the CLI refuses.
#[pyfunction]
fn parse_vary(texts: Vec<String>) -> PyResult<Vec<(String, Vec<f64>)>> {
    let axes = sweep::parse_axes(&texts).map_err(value_error)?;
    Ok(axes.into_iter().map(|a| (a.field.name.to_string(), a.values)).collect())
}

/// One value of `field` as the CLI reads it (`--set`, `--vary`): a number in Rust's grammar
/// (no `1_0`, ASCII digits only), `auto` (0) where the field has it, a symbolic field's names.
/// A name the CLI does not know (an FMU-only variable) takes a number. ValueError otherwise.
#[pyfunction]
fn parse_value(field: &str, text: &str) -> PyResult<f64> {
    match sweep::field(field) {
        Ok(parameter) => sweep::parse_value(parameter, text).map_err(value_error),
        Err(_) => text
            .trim()
            .parse::<f64>()
            .map_err(|_| value_error(format!("{field} takes a number, got `{}`", text.trim()))),
    }
}

/// The log's motion table (`motion.csv`, `Log.motion_csv`) read by the CLI's parser: (columns,
/// rows as f64 bytes, row-major, `time` first then the columns); ValueError with the parser's
/// one-line message for a table it refuses.
#[pyfunction]
fn parse_motion<'py>(py: Python<'py>, text: &str) -> PyResult<(Vec<&'static str>, Bound<'py, PyBytes>)> {
    let table = py.detach(|| MotionTable::parse(text)).map_err(value_error)?;
    let slots: Vec<usize> =
        table.columns.iter().map(|c| MOTION_NAMES.iter().position(|n| n == c).unwrap_or(0)).collect();
    let rows = table.times.iter().zip(&table.motions).flat_map(|(&time, motion)| {
        let values = motion.values();
        std::iter::once(time).chain(slots.iter().map(move |&k| values[k]))
    });
    let bytes = f64_bytes(py, rows);
    Ok((table.columns, bytes))
}

/// The module `beam_impact._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load_log, m)?)?;
    m.add_function(wrap_pyfunction!(check_run, m)?)?;
    m.add_function(wrap_pyfunction!(check_output, m)?)?;
    m.add_function(wrap_pyfunction!(write_file, m)?)?;
    m.add_function(wrap_pyfunction!(fmu_key, m)?)?;
    m.add_function(wrap_pyfunction!(read_fmu, m)?)?;
    m.add_function(wrap_pyfunction!(parse_vary, m)?)?;
    m.add_function(wrap_pyfunction!(parse_value, m)?)?;
    m.add_function(wrap_pyfunction!(parse_motion, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(run::cancel_running, m)?)?;
    m.add_function(wrap_pyfunction!(run::sweep_columns, m)?)?;
    m.add_function(wrap_pyfunction!(run::sweep_row, m)?)?;
    m.add_function(wrap_pyfunction!(campaign::campaign_sources, m)?)?;
    m.add_function(wrap_pyfunction!(campaign::occurrence_text, m)?)?;
    m.add_class::<campaign::Campaign>()?;
    m.add("CAMPAIGN_MAX_EVENTS", beam_impact::studies::campaign::DEFAULT_MAX_EVENTS)?;
    m.add("CAMPAIGN_DEFAULT_SEEDS", beam_impact::studies::campaign::DEFAULT_SEEDS)?;
    m.add("MAX_FMU_BYTES", MAX_FMU_BYTES)?;
    m.add("MAX_STEPS", beam_impact::model::scenario::MAX_STEPS)?;
    // One name per quantity: the step channel's columns as `report --csv` names them.
    m.add("STEP_COLUMNS", beam_impact::replay::csv::names())?;
    m.add("STEP_RENAMES", beam_impact::vocabulary::STEP_RENAMES.to_vec())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
