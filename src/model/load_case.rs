//! A load case (issue 44: `[[load_cases]]`): the factors a design code puts on the impact's
//! static and dynamic parts and on the allowable stress, and the scenario fields the case changes
//! (a heavier tip, a higher drop, wind on the bridge as a tip force).
//!
//! A case's factored utilisation of a stress quantity with converged dynamic peak P, static value
//! S (the bridge resting on the arrestor under gravity, the same model and mesh) and allowable A:
//!
//!   u = (static_factor * S + dynamic_factor * max(P - S, 0)) / (A * allowable_factor / material_factor)
//!
//! Allowable-stress design states `allowable_factor` (an increase of the allowable for a rare
//! case, 1 for the normal one); limit-state design states partial factors, the load factors on
//! the two parts and `material_factor` (gamma_M) on the resistance. No factor here is a code's:
//! the examples in `docs/sign-off.md` are labelled as examples.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// Load cases a scenario may hold: each case is a converged answer of its own when it changes a
/// field, so the count bounds a run's cost.
pub const MAX_LOAD_CASES: usize = 16;

/// Fields one case may change.
pub const MAX_CASE_FIELDS: usize = 32;

/// The longest case name, in characters (names head table columns and sweep columns).
pub const MAX_NAME_CHARS: usize = 48;

/// The largest factor on a load part or the allowable: codes' factors lie within 0.5-2; 10 keeps a
/// typo (`13` for `1.3`) from passing as a factor while leaving room for a deliberate study.
pub const MAX_FACTOR: f64 = 10.0;

/// One load case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadCase {
    /// The case's name (letters, digits, `-`, `_`, `.`, spaces; at most [`MAX_NAME_CHARS`]).
    pub name: String,
    /// Factor on the static part S, 1 by default.
    #[serde(default = "one")]
    pub static_factor: f64,
    /// Factor on the dynamic part max(P - S, 0), 1 by default.
    #[serde(default = "one")]
    pub dynamic_factor: f64,
    /// Factor on the allowable stress (allowable-stress design: above 1 for a rare case), 1 by default.
    #[serde(default = "one")]
    pub allowable_factor: f64,
    /// Partial factor gamma_M dividing the allowable (limit-state design), 1 by default.
    #[serde(default = "one")]
    pub material_factor: f64,
    /// The scenario fields the case changes, by the names `--set` takes, with a number or the
    /// word `--set` would take (`"rigid"`, `"auto"`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub set: BTreeMap<String, SetValue>,
}

/// A value a case sets: a number or a word (`"rigid"`, `"auto"`, `"power"`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SetValue {
    /// A number, in the field's unit.
    Number(f64),
    /// A word the field takes.
    Word(String),
}

impl SetValue {
    /// The value as `--set KEY=VALUE` writes it.
    pub fn text(&self) -> String {
        match self {
            SetValue::Number(v) => format!("{v}"),
            SetValue::Word(w) => w.clone(),
        }
    }
}

fn one() -> f64 {
    1.0
}

impl LoadCase {
    /// A case that changes nothing and factors nothing (the plain design check).
    pub fn named(name: &str) -> LoadCase {
        LoadCase {
            name: name.into(),
            static_factor: 1.0,
            dynamic_factor: 1.0,
            allowable_factor: 1.0,
            material_factor: 1.0,
            set: BTreeMap::new(),
        }
    }

    /// The factored utilisation of a quantity with converged peak `peak`, static value `static_value`
    /// (0 where the bridge cannot rest on the arrestor) and allowable `allowable` (same unit).
    pub fn utilisation(&self, peak: f64, static_value: f64, allowable: f64) -> f64 {
        let dynamic = (peak - static_value).max(0.0);
        (self.static_factor * static_value + self.dynamic_factor * dynamic) * self.material_factor
            / (allowable * self.allowable_factor)
    }
}

/// Every rule the cases break, each naming the case by its index and name. The fields a case
/// sets are checked by name and value where the case is applied (the scenario's own rules).
pub fn validation_errors(cases: &[LoadCase]) -> Vec<Error> {
    let mut errors = Vec::new();
    if cases.len() > MAX_LOAD_CASES {
        errors.push(Error::Other(format!(
            "load_cases holds {} cases, at most {MAX_LOAD_CASES} (each that changes a field is a converged answer of its own)",
            cases.len()
        )));
        return errors;
    }
    for (k, case) in cases.iter().enumerate() {
        let at = format!("load_cases[{k}]");
        let name = &case.name;
        let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.' | ' ');
        if name.trim().is_empty() || name.chars().count() > MAX_NAME_CHARS || !name.chars().all(allowed) {
            errors.push(Error::Other(format!(
                "{at}.name must be 1 to {MAX_NAME_CHARS} letters, digits, spaces, '-', '_' or '.', got {:?}",
                name.chars().take(MAX_NAME_CHARS + 8).collect::<String>()
            )));
        } else if cases[..k].iter().any(|c| c.name == *name) {
            errors.push(Error::Other(format!("{at}.name {name:?} names an earlier case too: names must differ")));
        }
        let label = format!("{at} ({})", name.chars().take(MAX_NAME_CHARS).collect::<String>());
        let factors = [
            ("static_factor", case.static_factor, 0.0),
            ("dynamic_factor", case.dynamic_factor, 0.0),
            ("allowable_factor", case.allowable_factor, f64::MIN_POSITIVE),
            ("material_factor", case.material_factor, f64::MIN_POSITIVE),
        ];
        for (field, value, low) in factors {
            if !(value.is_finite() && value >= low && value <= MAX_FACTOR) {
                let rule = if low == 0.0 { ">= 0" } else { "> 0" };
                errors.push(Error::Other(format!(
                    "{label}: {field} must be {rule} and at most {MAX_FACTOR}, got {value}"
                )));
            }
        }
        if case.set.len() > MAX_CASE_FIELDS {
            errors.push(Error::Other(format!(
                "{label}: set changes {} fields, at most {MAX_CASE_FIELDS}",
                case.set.len()
            )));
        }
        for (key, value) in &case.set {
            if key == "duration" || key.starts_with("load_cases") {
                errors.push(Error::Other(format!(
                    "{label}: set.{key} cannot differ between cases (every case is judged over the same run length)"
                )));
            }
            if let SetValue::Number(v) = value {
                if !v.is_finite() {
                    errors.push(Error::Other(format!("{label}: set.{key} must be finite, got {v}")));
                }
            }
        }
    }
    errors
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_factors_give_the_plain_utilisation() {
        let case = LoadCase::named("plain");
        // Peak over allowable exactly: the factored sum S + (P - S) = P.
        assert_eq!(case.utilisation(300e6, 100e6, 400e6), 0.75);
    }

    #[test]
    fn factors_act_on_their_own_parts() {
        let case = LoadCase {
            static_factor: 1.2,
            dynamic_factor: 1.5,
            allowable_factor: 1.25,
            material_factor: 1.1,
            ..LoadCase::named("factored")
        };
        // (1.2 * 100 + 1.5 * 200) * 1.1 / (400 * 1.25) = 420 * 1.1 / 500 = 0.924.
        let u = case.utilisation(300e6, 100e6, 400e6);
        assert!((u - 0.924).abs() < 1e-12, "{u}");
        // A peak below the static value (the bridge never fully loading the arrestor) has no
        // dynamic part: the static part alone.
        let u = case.utilisation(50e6, 100e6, 400e6);
        assert!((u - 1.2 * 100.0 * 1.1 / 500.0).abs() < 1e-12, "{u}");
    }

    #[test]
    fn bad_cases_are_named_with_their_values() {
        let mut bad = LoadCase::named("emergency");
        bad.dynamic_factor = -1.0;
        bad.set.insert("duration".into(), SetValue::Number(5.0));
        let cases = vec![LoadCase::named("emergency"), bad, LoadCase::named("<script>")];
        let text: Vec<String> = validation_errors(&cases).iter().map(|e| e.to_string()).collect();
        assert!(text.iter().any(|t| t.contains("load_cases[1].name \"emergency\" names an earlier case")), "{text:?}");
        assert!(text.iter().any(|t| t.contains("dynamic_factor must be >= 0 and at most 10, got -1")), "{text:?}");
        assert!(text.iter().any(|t| t.contains("set.duration cannot differ")), "{text:?}");
        assert!(text.iter().any(|t| t.contains("load_cases[2].name must be")), "{text:?}");
        let many = vec![LoadCase::named("a"); MAX_LOAD_CASES + 1];
        assert!(validation_errors(&many)[0].to_string().contains("at most 16"));
    }
}
