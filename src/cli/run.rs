//! `beam-impact run`: one scenario with its answer, tables and checks; the log with the answer
//! attached; `--json` for scripts.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use beam_impact::model::TimeStep;
use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::output::{check_distinct, OutputFile};
use beam_impact::record::{NullRecorder, Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{compare, Error, Result, Scenario, Simulation};

use super::args::RunArgs;
use super::common::{emit, io, read_scenario};

/// Runs a scenario; returns whether its numbers are trusted.
pub fn run(args: &RunArgs) -> Result<bool> {
    let settings = beam_impact::studies::sweep::parse_settings(&args.set)?;
    // Only a bare `beam-impact` runs the paper's method; a file or `--set` starts from the defaults.
    let mut scenario = match &args.file {
        Some(path) => read_scenario(path)?,
        None if settings.is_empty() => Scenario::paper(),
        None => Scenario::default(),
    };
    if let Some(motion) = &args.motion {
        super::common::load_motion(&mut scenario, motion)?;
    }
    beam_impact::studies::sweep::apply_settings(&mut scenario, &settings)?;
    let mcap = args
        .mcap
        .clone()
        .unwrap_or_else(|| beam_impact::studies::sweep::default_log(args.file.as_deref(), &settings, &scenario));
    let paper = scenario.is_paper();
    let started = Instant::now();
    let simulation = Simulation::new(&scenario)?;
    simulation.check_step_count(scenario.duration_ns(), args.max_steps)?;
    drop(simulation);
    // No two of the files name one (device and inode, or folder and name for a new file), and
    // every output is open before the run, so that a bad path fails at once, not after it; the
    // JSON is written beside and renamed into place at the end, so a failed run leaves the user's
    // earlier file as it was.
    let mut files: Vec<(&str, &Path)> = Vec::new();
    if let Some(file) = args.file.as_deref() {
        files.push(("the scenario file", file));
    }
    if !scenario.motion.file.is_empty() {
        files.push(("the motion file", Path::new(&scenario.motion.file)));
    }
    if let Some(json) = args.json.as_deref() {
        files.push(("--json", json));
    }
    if !args.no_mcap {
        if mcap.as_os_str() == "-" {
            return Err(beam_impact::Error::Other(
                "--mcap -: an MCAP log cannot go to standard output (the writer goes back to finish its summary); \
                 give a file name, or --no-mcap"
                    .into(),
            ));
        }
        files.push(("--mcap", &mcap));
    }
    check_distinct(&files)?;
    let json_file = match &args.json {
        Some(path) if path.as_os_str() == "-" => Some((path, None)),
        Some(path) => Some((path, Some(OutputFile::create(path, true, "cannot create JSON")?))),
        None => None,
    };
    let mut recorder: Box<dyn Recorder + Send> = if args.no_mcap {
        Box::new(NullRecorder)
    } else {
        let options = RecorderOptions {
            allow_devices: true,
            max_bytes: args.max_log_bytes,
            record_every: args.record_every,
            modal_coordinates: !args.no_modal_coordinates,
            station_stresses: !args.no_station_stresses,
            compression: args.log_compression,
            ..RecorderOptions::default()
        };
        Box::new(McapRecorder::with_options(&mcap, options)?)
    };
    let mut progress = Progress::new(recorder.as_mut(), scenario.duration_ns());
    let options = beam_impact::answer::Options { max_steps: args.max_steps, ..Default::default() };
    let answer = beam_impact::answer::run(&scenario, &mut progress, options)?;
    progress.complete(&answer)?;
    progress.bar.finish_and_clear();
    if let Some(reason) = progress.stopped_early() {
        super::common::warn(reason);
    }
    let wall = started.elapsed();
    let summary = &answer.summary;
    let resolved = &answer.resolved;

    let mut text = format!(
        "beam-impact: {} scenario, method {}, {} + {}/{} elements (arrestor + bridge to/beyond the contact), {:.3} s \
         simulated\n\n",
        if paper { "paper" } else { "user" },
        if resolved.method == beam_impact::model::Method::Paper { "paper" } else { "converged" },
        resolved.lower.elements,
        resolved.upper.elements_to_contact,
        resolved.upper.elements_beyond_contact,
        scenario.duration
    );
    let impact = summary.impact;
    text += &format!(
        "impact: the bridge turns at {:.6} rad/s about its hinge ({}), its contact point closing at {:.6} m/s\n\n",
        impact.angular_velocity,
        match scenario.impact_angular_velocity {
            Some(_) => "as stated: impact_angular_velocity".to_string(),
            None => format!(
                "from drop_height = {} m: omega_0 = sqrt(3 g alpha_0 / l_u), alpha_0 = atan(2 h / l_u), Eqs. 20-22",
                scenario.drop_height
            ),
        },
        impact.closing_speed
    );
    if let Some(table) = &scenario.motion.table {
        text += &format!(
            "supports moving: {} ({} rows of {}, each with its velocity and acceleration), from its time {} s; \
             deflections are relative to the supports, the energy approach's column assumes fixed ones\n\n",
            scenario.motion.file,
            table.times.len(),
            table
                .columns
                .iter()
                .filter(|c| !c.ends_with("_velocity") && !c.ends_with("_acceleration"))
                .copied()
                .collect::<Vec<_>>()
                .join(", "),
            scenario.motion.time_shift
        );
    }
    text += &compare::comparison(summary, paper);
    if paper {
        text += "(Table 1's FEM column is bound to the paper's 7 + 7/7 mesh; the converged answer follows.)\n";
    }
    text += "\n";
    text += &beam_impact::answer::table(&answer);
    let quality = &answer.quality;
    text += &format!(
        "time steps: {:e} s out of contact, {:e} s in contact{}\n",
        summary.time_steps.free,
        summary.time_steps.contact,
        if scenario.step_free == TimeStep::Auto || scenario.step_contact == TimeStep::Auto {
            " (auto: energy-safe)"
        } else {
            ""
        },
    );
    for line in quality.advisories.iter() {
        super::common::note(&format!("beam-impact: note: {}", super::common::bounded_line(line)));
    }
    for line in quality.reasons.iter() {
        super::common::warn(&format!("results not trusted: {line}"));
    }
    text += &format!("wall time: {:.1} ms (assembly, modes and stepping", wall.as_secs_f64() * 1e3);
    if !args.no_mcap {
        text += &format!(", recorded to {}", mcap.display());
    }
    text += ")\n";
    if let Some((path, file)) = json_file {
        let mut summary_json = serde_json::to_value(summary).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        summary_json["converged_peaks"] = serde_json::json!(answer.converged_peaks);
        summary_json["converged_first_contact_peaks"] = serde_json::json!(answer.converged_first_contact_peaks);
        summary_json["quality"] = serde_json::json!(answer.quality);
        envelope_json(&mut summary_json, &answer);
        let doc = serde_json::json!({
            "scenario": resolved,
            "scenario_as_given": scenario,
            "summary": summary_json,
            "quality": answer.quality,
            "design": answer.design,
            "discretisation": discretisation_json(&answer),
            "impact": summary.impact,
            "merged_contact_windows": compare::merged_windows(&summary.contact_windows, beam_impact::results::BOUNCE_GAP),
            "units": json_units(),
            "wall_time_s": wall.as_secs_f64(),
        });
        let mut doc = doc;
        beam_impact::vocabulary::add_quantity_names(&mut doc);
        let json = serde_json::to_string_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        match file {
            Some(mut file) => {
                writeln!(file, "{json}").map_err(|source| io("cannot write JSON", path, source))?;
                file.commit()?;
                text += &format!("results written to {}\n", path.display());
            }
            // `--json -`: the JSON is the standard output, without the tables.
            None => return emit(&format!("{json}\n")).map(|()| answer.quality.trusted),
        }
    }
    emit(&text)?;
    Ok(answer.quality.trusted)
}

/// Each beam's worst stress along it (issue 30) in `summary.peaks` beside the paper's five
/// (`upper.bending_stress`, `upper.shear_stress`, `lower.bending_stress`, `lower.shear_stress`;
/// null without a shear area), their positions (m from the hinge or the clamp) in
/// `summary.peak_positions` and their times in `summary.peak_times`.
pub fn envelope_json(summary: &mut serde_json::Value, answer: &beam_impact::answer::Answer) {
    let mut positions = serde_json::Map::new();
    for (name, peak) in beam_impact::results::ENVELOPE_PEAK_NAMES.iter().zip(answer.envelope_peaks) {
        summary["peaks"][*name] = serde_json::json!(peak.map(|p| p.value));
        summary["peak_times"][*name] = serde_json::json!(peak.map(|p| p.time));
        positions.insert(name.to_string(), serde_json::json!(peak.map(|p| p.position)));
    }
    summary["peak_positions"] = serde_json::Value::Object(positions);
}

/// The `discretisation` block of `--json` and of the log's `answer.json`: each peak's figure, the
/// twin's spreads (whole run and first contact), the late peaks not vouched for, and the runs (rungs) behind the answer.
pub fn discretisation_json(answer: &beam_impact::answer::Answer) -> serde_json::Value {
    serde_json::json!({
        "peaks": answer.discretisation_error,
        "first_contact_peaks": answer.first_contact_discretisation_error,
        "sensitivity_spread": answer.sensitivity_spread,
        "first_contact_sensitivity_spread": answer.first_contact_sensitivity_spread,
        "unvouched_late_peaks": answer.unvouched_late_peaks,
        "envelope_peaks": envelope_figures(&answer.envelope_discretisation_error),
        "envelope_sensitivity_spread": answer.envelope_sensitivity_spread.as_ref().map(envelope_figures),
        "runs": answer.runs,
    })
}

/// The envelope peaks' figures by name (null where not defined).
fn envelope_figures(values: &[Option<f64>; 4]) -> serde_json::Value {
    let mut map = serde_json::Map::new();
    for (name, v) in beam_impact::results::ENVELOPE_PEAK_NAMES.iter().zip(values) {
        map.insert(name.to_string(), serde_json::json!(v));
    }
    serde_json::Value::Object(map)
}

/// The SI units of the `--json` fields (by name; nested names with dots).
pub fn json_units() -> serde_json::Value {
    serde_json::json!({
        "time, times, contact windows, time_steps, first_contact_end": "s",
        "peak_positions, envelope positions": "m from the beam's support (the hinge, the clamp)",
        "lower_tip_deflection, tip_deflection": "m",
        "*_stress (peaks, first_contact_peaks, energy_method)": "Pa",
        "contact_force, energy_method.force": "N",
        "energies, residuals, strain_energy, bridge_strain_energy, upper_strain_at_peak_deflection": "J",
        "energy_method.flexion_stiffness": "N/m",
        "energy_method.bridge_deceleration": "rad/s^2",
        "energy_method.bridge_contact_moment": "N m",
        "modes": "rad/s",
        "energy_residual_fraction, energy_tolerance, bridge_strain_ratio": "1 (fraction)",
        "scenario": "SI, as in `beam-impact scenario`",
        "wall_time_s": "s"
    })
}

/// Shows a progress bar (on a terminal) while passing every step on to the real recorder.
pub struct Progress<'a> {
    inner: &'a mut (dyn Recorder + Send),
    bar: ProgressBar,
    /// The run asked to finish the record: deferred until its answer is attached.
    finish_requested: bool,
}

impl<'a> Progress<'a> {
    fn new(inner: &'a mut (dyn Recorder + Send), end_ns: u64) -> Self {
        let bar = ProgressBar::new(end_ns / 1_000_000);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} ms simulated, {elapsed} ({eta} left)")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress { inner, bar, finish_requested: false }
    }
}

impl Progress<'_> {
    /// Stores the answer with its checks in the record (`answer.json`) and finishes it.
    fn complete(&mut self, answer: &beam_impact::answer::Answer) -> Result<()> {
        if self.finish_requested {
            let doc = serde_json::json!({
                "quality": answer.quality,
                "design": answer.design,
                "converged_peaks": answer.converged_peaks,
                "converged_first_contact_peaks": answer.converged_first_contact_peaks,
                "discretisation": discretisation_json(answer),
            });
            let mut doc = doc;
            beam_impact::vocabulary::add_quantity_names(&mut doc);
            let bytes = serde_json::to_vec_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
            self.inner.attach(beam_impact::record::mcap::ANSWER_ATTACHMENT, "application/json", &bytes)?;
        }
        self.inner.finish()
    }
}

impl Recorder for Progress<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        self.inner.start(info)
    }
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        if result.step.is_multiple_of(1000) {
            self.bar.set_position(result.time_ns / 1_000_000);
        }
        self.inner.step(result, modal_coordinates)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.inner.contact_event(event)
    }
    /// Deferred: the answer with its checks is attached first ([`Progress::complete`]).
    fn finish(&mut self) -> Result<()> {
        self.finish_requested = true;
        Ok(())
    }
    fn wants_details(&self) -> bool {
        self.inner.wants_details()
    }
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        self.inner.attach(name, media_type, data)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.inner.stopped_early()
    }
}
