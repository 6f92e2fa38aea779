//! A scenario's load cases judged (issue 44): each case's factored utilisation of every stress
//! quantity the design check holds, the governing case of each quantity, and the verdict of all
//! cases ([`crate::model::load_case`] for the factors and the formula).
//!
//! A case that changes no field shares the scenario's own converged answer; a case that changes
//! fields is a converged answer of its own (its scenario without load cases), with its own static
//! solution. A case whose answer is not trusted is flagged as such beside its verdict. The runs
//! are the caller's ([`crate::studies::sweep::answer_with_cases`]: the CLI's `run`, Python's
//! `run`, a sweep's rows and a campaign's events), so that the answer knows nothing of the cases.

use std::collections::BTreeMap;

use crate::answer::{Answer, DesignUtilisation};
use crate::error::Result;
use crate::model::load_case::LoadCase;
use crate::model::Scenario;
use crate::results::ENVELOPE_PEAK_NAMES;

pub mod results;

pub use results::{text, CaseQuantity, CaseResult, Governing, LoadCaseResults};

/// Each stress quantity of the design check with its converged peak and allowable, Pa, by the
/// FMU's names (`lower.clamp_bending_stress`) of [`DesignUtilisation::NAMES`] and [`ENVELOPE_PEAK_NAMES`] (an envelope without an
/// allowable is left out; a beam of sections: the allowable where its worst utilisation sits,
/// peak / utilisation).
pub fn design_quantities(answer: &Answer) -> Vec<(&'static str, f64, f64)> {
    let mut out = Vec::new();
    let peaks = &answer.converged_peaks;
    let values = [peaks.lower_clamp_bending_stress, peaks.lower_clamp_shear_stress, peaks.upper_contact_bending_stress];
    for ((name, value), allowable) in
        DesignUtilisation::NAMES.iter().zip(values).zip(answer.resolved.paper_allowables())
    {
        if value.is_finite() && allowable > 0.0 {
            out.push((crate::vocabulary::quantity_name(name), value, allowable));
        }
    }
    for (name, peak) in ENVELOPE_PEAK_NAMES.iter().zip(answer.envelope_peaks) {
        if let Some(p) = peak {
            if let Some(u) = p.utilisation.filter(|u| *u > 0.0 && u.is_finite()) {
                out.push((*name, p.value, p.value / u));
            }
        }
    }
    out
}

/// The static values of a case's scenario by quantity name, Pa (None: the bridge cannot rest).
pub type StaticValues = Option<BTreeMap<String, f64>>;

/// Judges every case of `scenario` whose own answer is `answer`: `answer_of` gives the converged
/// answer of a case (called only for cases that change fields; the caller builds the case's
/// scenario, [`crate::studies::sweep::case_scenario`]), `static_of` an answer's static values.
pub fn judge(
    scenario: &Scenario,
    answer: &Answer,
    answer_of: &mut dyn FnMut(&LoadCase) -> Result<Answer>,
    static_of: &dyn Fn(&Answer) -> Result<StaticValues>,
) -> Result<Option<LoadCaseResults>> {
    if scenario.load_cases.is_empty() {
        return Ok(None);
    }
    let own_static = static_of(answer)?;
    let mut cases = Vec::new();
    for case in &scenario.load_cases {
        let (case_answer, statics) = if case.set.is_empty() {
            (None, own_static.clone())
        } else {
            let a = answer_of(case)?;
            let statics = static_of(&a)?;
            (Some(a), statics)
        };
        let judged = case_answer.as_ref().unwrap_or(answer);
        cases.push(judge_case(case, judged, statics.as_ref()));
    }
    let mut governing: BTreeMap<String, Governing> = BTreeMap::new();
    for case in &cases {
        for (name, q) in &case.quantities {
            let better = governing.get(name).is_none_or(|g| q.utilisation > g.utilisation);
            if better {
                governing.insert(name.clone(), Governing { case: case.name.clone(), utilisation: q.utilisation });
            }
        }
    }
    let pass = cases.iter().all(|c| c.pass);
    let trusted = cases.iter().all(|c| c.trusted);
    Ok(Some(LoadCaseResults { cases, governing, pass, trusted }))
}

fn judge_case(case: &LoadCase, answer: &Answer, statics: Option<&BTreeMap<String, f64>>) -> CaseResult {
    let mut quantities = BTreeMap::new();
    for (name, peak, allowable) in design_quantities(answer) {
        let static_value = statics.and_then(|s| s.get(name)).copied().filter(|v| v.is_finite()).unwrap_or(0.0).abs();
        let utilisation = case.utilisation(peak, static_value, allowable);
        quantities.insert(name.to_string(), CaseQuantity { peak, static_value, allowable, utilisation });
    }
    let worst = quantities
        .iter()
        .max_by(|a, b| a.1.utilisation.total_cmp(&b.1.utilisation))
        .map(|(n, q)| (n.clone(), q.utilisation));
    let pass = quantities.values().all(|q| q.utilisation <= 1.0);
    CaseResult {
        name: case.name.clone(),
        static_factor: case.static_factor,
        dynamic_factor: case.dynamic_factor,
        allowable_factor: case.allowable_factor,
        material_factor: case.material_factor,
        set: case.set.iter().map(|(k, v)| (k.clone(), v.text())).collect(),
        worst: worst.as_ref().map(|w| w.0.clone()),
        utilisation: worst.map_or(0.0, |w| w.1),
        pass,
        trusted: answer.quality.trusted,
        static_solution: statics.is_some(),
        quantities,
    }
}

/// The static values of `answer`'s scenario by quantity name, Pa (the bridge resting on the
/// arrestor on the mesh its converged peaks come from: [`crate::amplification::amplification`]),
/// None where it cannot rest.
pub fn static_values(answer: &Answer) -> Result<StaticValues> {
    Ok(crate::amplification::amplification(answer)?
        .static_response
        .map(|r| r.values().into_iter().map(|(name, value)| (name.to_string(), value)).collect()))
}
