//! A scenario's load cases judged (issue 44): each case's factored utilisation of every stress
//! quantity the design check holds, the governing case of each quantity, and the verdict of all
//! cases ([`crate::model::load_case`] for the factors and the formula).
//!
//! A case that changes no field shares the scenario's own converged answer; a case that changes
//! fields is a converged answer of its own (its scenario without load cases), with its own static
//! solution. A case whose answer is not trusted is flagged as such beside its verdict.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::answer::{Answer, DesignUtilisation};
use crate::error::{Error, Result};
use crate::model::load_case::LoadCase;
use crate::model::Scenario;
use crate::results::ENVELOPE_PEAK_NAMES;

/// One quantity under one case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseQuantity {
    /// The case's converged dynamic peak, Pa.
    pub peak: f64,
    /// Its static value (the bridge resting on the arrestor under gravity), Pa; 0 where it cannot rest.
    pub static_value: f64,
    /// The allowable the plain design check holds it to, Pa.
    pub allowable: f64,
    /// The factored utilisation ([`LoadCase::utilisation`]).
    pub utilisation: f64,
}

/// One case's judgement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    /// The case's name.
    pub name: String,
    /// Its factors, as stated.
    pub static_factor: f64,
    /// See [`LoadCase::dynamic_factor`].
    pub dynamic_factor: f64,
    /// See [`LoadCase::allowable_factor`].
    pub allowable_factor: f64,
    /// See [`LoadCase::material_factor`].
    pub material_factor: f64,
    /// The fields it changes, as `--set` writes them.
    pub set: BTreeMap<String, String>,
    /// Each stress quantity with an allowable, by the design check's names.
    pub quantities: BTreeMap<String, CaseQuantity>,
    /// The quantity with the largest factored utilisation.
    pub worst: Option<String>,
    /// That utilisation.
    pub utilisation: f64,
    /// True when every factored utilisation is <= 1.
    pub pass: bool,
    /// Whether the case's answer is trusted (a case that changes nothing: the scenario's own).
    pub trusted: bool,
    /// Whether a static solution exists (the bridge rests on the arrestor); without one the
    /// static part is 0 and the dynamic factor takes the whole peak.
    pub static_solution: bool,
}

/// The governing case of a quantity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Governing {
    /// The case's name.
    pub case: String,
    /// Its factored utilisation.
    pub utilisation: f64,
}

/// Every case judged.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LoadCaseResults {
    /// Each case in the scenario's order.
    pub cases: Vec<CaseResult>,
    /// Each quantity's governing case (the largest factored utilisation).
    pub governing: BTreeMap<String, Governing>,
    /// True when every case passes.
    pub pass: bool,
    /// True when every case's answer is trusted.
    pub trusted: bool,
}

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

/// The scenario a case runs: `scenario` with the case's fields set as `--set` sets them, its
/// load cases removed. Errors name the case.
pub fn case_scenario(scenario: &Scenario, case: &LoadCase) -> Result<Scenario> {
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
    crate::studies::sweep::apply_fixture_settings(&mut s, &settings)
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

/// The static values of a case's scenario by quantity name, Pa (None: the bridge cannot rest).
pub type StaticValues = Option<BTreeMap<String, f64>>;

/// Judges every case of `scenario` whose own answer is `answer`: `answer_of` gives the answer of
/// a case's scenario (called only for cases that change fields), `static_of` its static values.
pub fn judge(
    scenario: &Scenario,
    answer: &Answer,
    answer_of: &mut dyn FnMut(&Scenario) -> Result<Answer>,
    static_of: &dyn Fn(&Scenario, &Answer) -> Result<StaticValues>,
) -> Result<Option<LoadCaseResults>> {
    if scenario.load_cases.is_empty() {
        return Ok(None);
    }
    let own_static = static_of(scenario, answer)?;
    let mut cases = Vec::new();
    for case in &scenario.load_cases {
        let (case_answer, statics) = if case.set.is_empty() {
            (None, own_static.clone())
        } else {
            let s = case_scenario(scenario, case)?;
            let a = answer_of(&s)?;
            let statics = static_of(&s, &a)?;
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

/// `text` as printed: control characters escaped and cut to [`crate::model::load_case::MAX_NAME_CHARS`]
/// characters (a log's stored cases are not trusted text).
fn printable(text: &str) -> String {
    let cut: String = text.chars().take(crate::model::load_case::MAX_NAME_CHARS).collect();
    let more = if cut.len() < text.len() { "..." } else { "" };
    cut.chars()
        .flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] })
        .collect::<String>()
        + more
}

/// The cases as printed lines: one per case (its worst utilisation, verdict, trust) and the
/// governing case of each quantity.
pub fn text(results: &LoadCaseResults) -> String {
    let mut out = String::from("Load cases (factored: static S and dynamic max(P - S, 0) parts, allowable):\n");
    let width = results.cases.iter().map(|c| printable(&c.name).chars().count()).max().unwrap_or(4).max(4);
    for c in &results.cases {
        let worst = c.worst.as_deref().unwrap_or("-");
        let verdict = if c.pass { "PASS" } else { "FAIL" };
        let trust = if c.trusted { "" } else { "  (its answer is not trusted)" };
        let statics = if c.static_solution { "" } else { "  (no static rest: S = 0)" };
        let changes = if c.set.is_empty() {
            String::new()
        } else {
            let changes: Vec<String> =
                c.set.iter().map(|(k, v)| format!("{}={}", printable(k), printable(v))).collect();
            format!("  [{}]", changes.join(", "))
        };
        out += &format!(
            "  {:<width$}  gS {:.2} gD {:.2} fA {:.2} gM {:.2}  worst {:.3} ({worst})  {verdict}{trust}{statics}{changes}\n",
            printable(&c.name), c.static_factor, c.dynamic_factor, c.allowable_factor, c.material_factor, c.utilisation
        );
    }
    for (name, g) in &results.governing {
        out += &format!("  governing {}: {} ({:.3})\n", printable(name), printable(&g.case), g.utilisation);
    }
    out += &format!("  all cases: {}\n", if results.pass { "PASS" } else { "FAIL" });
    out
}

/// The static values of `answer`'s scenario by quantity name, Pa (the bridge resting on the
/// arrestor on the mesh its converged peaks come from: [`crate::amplification::amplification`]),
/// None where it cannot rest.
pub fn static_values(_scenario: &Scenario, answer: &Answer) -> Result<StaticValues> {
    Ok(crate::amplification::amplification(answer)?
        .static_response
        .map(|r| r.values().into_iter().map(|(name, value)| (name.to_string(), value)).collect()))
}
