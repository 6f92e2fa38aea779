//! `beam_impact._native`: the Rust log reader of `beam-impact report` for the Python package, so
//! that `beam_impact.load_log` inherits every bound of `replay::safe_read` (time linear in the
//! file, memory the file plus one chunk plus at most 16x the file kept) and no log is read by two
//! codes. The Python side (`beam_impact/log.py`) turns the flat buffers into numpy arrays.
//! `check_run` holds `beam_impact.simulate` to the CLI's limits before the FMU steps.

use std::collections::HashMap;
use std::path::PathBuf;

use beam_impact::model::parameters;
use beam_impact::replay::report::{read_log_with, LogData, ReadOptions};
use beam_impact::results::StepResult;
use beam_impact::{Scenario, Simulation};
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
fn columns<'py>(py: Python<'py>, steps: &[StepResult]) -> PyResult<Bound<'py, PyDict>> {
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
        PyValueError::new_err(format!("no /beam/model message{why}"))
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
    out.set_item("log_format", data.log_format)?;
    out.set_item("answer_json", data.answer_json.clone())?;
    Ok(out)
}

/// Reads the log at `path` with the Rust reader (every modal coordinate row and log time kept):
/// a dict of buffers and values, or ValueError with one line saying why the file is not a
/// readable beam-impact log. The GIL is released while the file is read.
#[pyfunction]
fn load_log<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let data = py
        .detach(|| read_log_with(&path, ReadOptions { history: true }))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    to_python(py, &data)
}

/// Checks a run as the CLI checks it before stepping: `values` (the scenario's parameters by
/// their FMU names; names that are not scenario parameters, such as `check_sensitivity` or
/// `log.path`, are left to the FMU) on the default scenario, validated, and the internal steps
/// to `stop_time` s at most `max_steps`. Returns the steps it needs; ValueError with the CLI's
/// one-line message otherwise. Builds the model and its modes (tens of ms), steps nothing.
#[pyfunction]
fn check_run(py: Python<'_>, values: HashMap<String, f64>, stop_time: f64, max_steps: u64) -> PyResult<u64> {
    let error = |e: beam_impact::Error| PyValueError::new_err(e.to_string());
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

/// The module `beam_impact._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load_log, m)?)?;
    m.add_function(wrap_pyfunction!(check_run, m)?)?;
    m.add("MAX_STEPS", beam_impact::model::scenario::MAX_STEPS)?;
    // One name per quantity: the step channel's columns as `report --csv` names them.
    m.add("STEP_COLUMNS", beam_impact::replay::csv::names())?;
    m.add("STEP_RENAMES", beam_impact::vocabulary::STEP_RENAMES.to_vec())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
