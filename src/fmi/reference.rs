//! The FMU's reference results: its starting scenario (the paper's, or the one packed into its
//! resources, issue 30; every parameter at its start value, the DefaultExperiment's 0 to 3 s) run
//! through an [`Instance`], the very code behind the C functions, with one communication point
//! per millisecond. `beam-impact pack` puts them into the FMU as `extra/` CSV and draws the
//! documentation's figures and Table 1 from them, so what the FMU documents is what it computes.

use std::fmt::Write;

use super::description::DEFAULT_EXPERIMENT;
use super::instance::{Instance, Version};
use super::logger::Logger;
use super::variables::{format_real, table, Causality, Type, Variable};
use crate::Scenario;

/// Where the reference results go inside the FMU: `extra/` in reverse-domain form (FMI 3.0
/// section 2.5), the file named after the model like the Reference FMUs' `<model>_ref.csv`.
pub const REFERENCE_CSV: &str = "extra/org.beam-impact.reference/BeamImpact_ref.csv";

/// The communication step of the reference results, s.
pub const REFERENCE_STEP: f64 = 1e-3;

/// The outputs of the paper scenario at every millisecond.
#[derive(Clone, Debug)]
pub struct ReferenceRun {
    /// The output variables, in value-reference order (the columns after `time`).
    pub outputs: Vec<Variable>,
    /// One row per communication point: time (s), then the outputs (Booleans as 0 or 1).
    pub rows: Vec<Vec<f64>>,
}

impl ReferenceRun {
    /// The column of output `name` as (time, value) points; `None` if there is no such output.
    pub fn series(&self, name: &str) -> Option<Vec<(f64, f64)>> {
        let column = self.outputs.iter().position(|v| v.name == name)? + 1;
        Some(self.rows.iter().map(|row| (row[0], row[column])).collect())
    }

    /// The last value of output `name` (the running peaks at the stop time).
    pub fn last(&self, name: &str) -> Option<f64> {
        self.series(name)?.last().map(|p| p.1)
    }

    /// The CSV: a header of quoted names (`"time","lower.tip_deflection",...`), then one row per
    /// millisecond, numbers that parse back to the same bits.
    pub fn csv(&self) -> String {
        let mut out = String::from("\"time\"");
        for v in &self.outputs {
            let _ = write!(out, ",\"{}\"", v.name);
        }
        out.push('\n');
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(|&x| format_real(x)).collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }
}

/// Runs the paper scenario through an FMI 3 instance (no log file, no logger) from the
/// DefaultExperiment's start to its stop time in [`REFERENCE_STEP`] communication steps and reads
/// every output at every point. An error names the FMU call that failed.
pub fn reference_run() -> Result<ReferenceRun, String> {
    reference_run_with(&[])
}

/// [`reference_run`] with Integer parameters set first (`("method", 1)`: the paper's method).
pub fn reference_run_with(integers: &[(&str, i32)]) -> Result<ReferenceRun, String> {
    reference_run_from(None, integers)
}

/// [`reference_run_with`] of an FMU that starts from `packed` (its `resources/scenario.toml`,
/// issue 30; `None`: the paper scenario): every parameter at that scenario's start value.
pub fn reference_run_from(packed: Option<&Scenario>, integers: &[(&str, i32)]) -> Result<ReferenceRun, String> {
    let logger = Logger::Fmi3 { callback: None, environment: std::ptr::null_mut() };
    let mut instance = Instance::starting_from("reference", Version::Fmi3, logger, false, packed.cloned());
    let variables = table();
    let outputs: Vec<Variable> = variables.iter().filter(|v| v.causality == Causality::Output).cloned().collect();
    let vr =
        |name: &str| variables.iter().find(|v| v.name == name).map(|v| v.vr).ok_or(format!("no variable `{name}`"));
    let (start, stop, _) = DEFAULT_EXPERIMENT;
    let points = ((stop - start) / REFERENCE_STEP).round() as u64;
    let failed = |call: &str, why: String| format!("the reference run's {call} failed: {why}");
    instance.set_string(vr("log.path")?, String::new()).map_err(|e| failed("setting log.path", e))?;
    for &(name, value) in integers {
        instance.set_integer(vr(name)?, value).map_err(|e| failed(&format!("setting {name}"), e))?;
    }
    instance.setup_experiment(start, Some(stop)).map_err(|e| failed("setup", e))?;
    instance.enter_initialization().map_err(|e| failed("EnterInitializationMode", e))?;
    instance.exit_initialization().map_err(|e| failed("ExitInitializationMode", e))?;
    let mut rows = Vec::with_capacity(points as usize + 1);
    for k in 0..=points {
        // Communication points as an importer computes them: start + k h, not a running sum.
        let time = start + k as f64 * REFERENCE_STEP;
        if k > 0 {
            let previous = start + (k - 1) as f64 * REFERENCE_STEP;
            instance.do_step(previous, time - previous).map_err(|e| failed(&format!("DoStep to {time} s"), e))?;
        }
        let mut row = Vec::with_capacity(outputs.len() + 1);
        row.push(time);
        for v in &outputs {
            let value = match v.ty {
                Type::Real => instance.get_real(v.vr),
                Type::Integer => instance.get_integer(v.vr).map(f64::from),
                Type::Boolean => instance.get_boolean(v.vr).map(|b| if b { 1.0 } else { 0.0 }),
                Type::String => Err(format!("`{}` is a String output: not in the reference CSV", v.name)),
            };
            row.push(value.map_err(|e| failed(&format!("reading {}", v.name), e))?);
        }
        rows.push(row);
    }
    instance.terminate().map_err(|e| failed("Terminate", e))?;
    instance.free();
    Ok(ReferenceRun { outputs, rows })
}
