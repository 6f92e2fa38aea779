//! The JSON of one run: the document `beam-impact run --json` prints and the Python package's
//! `beam_impact.run` returns (one builder, so both hold the same keys and numbers), and the
//! answer with its checks that the log keeps as `answer.json`.

use crate::answer::Answer;
use crate::error::{Error, Result};
use crate::model::Scenario;

/// The `run --json` document of `answer` (the run of `as_given`, before `"auto"` was resolved),
/// its wall time `wall_time_s` (s), with the FMU's names beside the former keys.
pub fn document(as_given: &Scenario, answer: &Answer, wall_time_s: f64) -> Result<serde_json::Value> {
    let summary = &answer.summary;
    let mut summary_json = serde_json::to_value(summary).map_err(|e| Error::Other(format!("JSON: {e}")))?;
    summary_json["converged_peaks"] = serde_json::json!(answer.converged_peaks);
    summary_json["converged_first_contact_peaks"] = serde_json::json!(answer.converged_first_contact_peaks);
    summary_json["quality"] = serde_json::json!(answer.quality);
    envelope_json(&mut summary_json, answer);
    let mut doc = serde_json::json!({
        "scenario": answer.resolved,
        "scenario_as_given": as_given,
        "summary": summary_json,
        "quality": answer.quality,
        "design": answer.design,
        "discretisation": discretisation_json(answer),
        "impact": summary.impact,
        "load_cases": answer.load_cases,
        "merged_contact_windows": crate::compare::merged_windows(&summary.contact_windows, crate::results::BOUNCE_GAP),
        "units": json_units(),
        "wall_time_s": wall_time_s,
    });
    doc["dynamic_amplification"] = amplification_json(answer);
    crate::vocabulary::add_quantity_names(&mut doc);
    doc["fatigue"] = fatigue_json(answer)?;
    crate::sub_impacts::add_to(&mut doc, &summary.sub_impacts);
    Ok(doc)
}

/// The log's `answer.json`: the answer's quality, design, converged peaks and discretisation,
/// with the FMU's names beside the former keys.
pub fn answer_attachment(answer: &Answer) -> serde_json::Value {
    let mut doc = serde_json::json!({
        "quality": answer.quality,
        "design": answer.design,
        "converged_peaks": answer.converged_peaks,
        "converged_first_contact_peaks": answer.converged_first_contact_peaks,
        "discretisation": discretisation_json(answer),
        "load_cases": answer.load_cases,
    });
    doc["dynamic_amplification"] = amplification_json(answer);
    // The printed run's fatigue on the scenario's curve (the log keeps its histories too, as
    // `fatigue.json`, for `report --fatigue` on any curve): null without them.
    doc["fatigue"] = fatigue_json(answer).unwrap_or_else(|e| serde_json::json!({ "error": e.to_string() }));
    crate::vocabulary::add_quantity_names(&mut doc);
    // Each contact window as an impact (issue 45): `report LOG` and `load_log().answer` read them here.
    crate::sub_impacts::add_to(&mut doc, &answer.summary.sub_impacts);
    doc
}

/// Each beam's worst stress along it (issue 30) in `summary.peaks` beside the paper's five
/// (`upper.bending_stress`, `upper.shear_stress`, `lower.bending_stress`, `lower.shear_stress`;
/// null without a shear area), their positions (m from the hinge or the clamp) in
/// `summary.peak_positions` and their times in `summary.peak_times`.
pub fn envelope_json(summary: &mut serde_json::Value, answer: &Answer) {
    let mut positions = serde_json::Map::new();
    for (name, peak) in crate::results::ENVELOPE_PEAK_NAMES.iter().zip(answer.envelope_peaks) {
        summary["peaks"][*name] = serde_json::json!(peak.map(|p| p.value));
        summary["peak_times"][*name] = serde_json::json!(peak.map(|p| p.time));
        positions.insert(name.to_string(), serde_json::json!(peak.map(|p| p.position)));
    }
    summary["peak_positions"] = serde_json::Value::Object(positions);
}

/// The `discretisation` block of `--json` and of the log's `answer.json`: each peak's figure, the
/// twin's spreads (whole run and first contact), the late peaks not vouched for, and the runs (rungs) behind the answer.
pub fn discretisation_json(answer: &Answer) -> serde_json::Value {
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
    for (name, v) in crate::results::ENVELOPE_PEAK_NAMES.iter().zip(values) {
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

/// The `dynamic_amplification` block (issue 44, [`crate::amplification`]): the static values, the
/// DAF per design quantity, the energy method's and the crane-style psi; `{"error": ...}` where
/// the static solution fails.
pub fn amplification_json(answer: &Answer) -> serde_json::Value {
    match crate::amplification::amplification(answer) {
        Ok(a) => a.to_json(),
        Err(e) => serde_json::json!({ "error": e.to_string() }),
    }
}

/// The `fatigue` block of `run --json` (issue 44): the printed run's fatigue on the scenario's
/// curve and factors ([`crate::run_fatigue::assess`]); null without the stations' histories (a
/// run without every station's envelope).
pub fn fatigue_json(answer: &Answer) -> Result<serde_json::Value> {
    let Some(histories) = &answer.station_histories else { return Ok(serde_json::Value::Null) };
    let settings = crate::model::fatigue_fields::of(&answer.resolved);
    let fatigue = crate::run_fatigue::assess(histories, &settings)?;
    serde_json::to_value(&fatigue).map_err(|e| Error::Other(format!("JSON: {e}")))
}

/// The log's `fatigue.json` of `answer`: every bending station's turning points (None without
/// them), from which `report --fatigue` applies any curve.
pub fn fatigue_attachment(answer: &Answer) -> Result<Option<Vec<u8>>> {
    answer
        .station_histories
        .as_ref()
        .map(|h| serde_json::to_vec(h).map_err(|e| Error::Other(format!("JSON: {e}"))))
        .transpose()
}
