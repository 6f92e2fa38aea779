//! A scenario's load cases as judged (issue 44): each case's factored utilisations, the governing
//! case of each quantity, the verdict of all cases, and their printed lines. Types only, so that
//! the answer that carries them needs nothing of how they are judged ([`super`]).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// One quantity under one case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseQuantity {
    /// The case's converged dynamic peak, Pa.
    pub peak: f64,
    /// Its static value (the bridge resting on the arrestor under gravity), Pa; 0 where it cannot rest.
    pub static_value: f64,
    /// The allowable the plain design check holds it to, Pa.
    pub allowable: f64,
    /// The factored utilisation ([`crate::model::load_case::LoadCase::utilisation`]).
    pub utilisation: f64,
}

/// One case's judgement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    /// The case's name.
    pub name: String,
    /// Its factors, as stated.
    pub static_factor: f64,
    /// See [`crate::model::load_case::LoadCase::dynamic_factor`].
    pub dynamic_factor: f64,
    /// See [`crate::model::load_case::LoadCase::allowable_factor`].
    pub allowable_factor: f64,
    /// See [`crate::model::load_case::LoadCase::material_factor`].
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
