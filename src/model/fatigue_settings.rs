//! The `[fatigue]` section of a scenario (issue 44): the S-N curve and the designer's factors a
//! run's fatigue is assessed with ([`crate::run_fatigue`]), and its fields as parameters
//! (`--set fatigue.FIELD=VALUE`, `--vary`). Setting a field on a scenario without `[fatigue]`
//! adds the section with the defaults for the others. None of them changes a run's motion: the
//! fatigue is read from the run's stress histories afterwards.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::fatigue::{SnCurve, SnOptions};

/// The default S-N curve: DNV-RP-C203 (2016) Table 2-1's D curve in air. The RP's hot-spot
/// stress method for welded plated details (2016 Sec. 4.3) reads the hot-spot stress range on the
/// D curve, and a beam station's nominal stress times an SCF is such a hot-spot stress; D is also
/// the class of common transverse butt and fillet-welded details (the RP's Appendix A tables).
/// A gangway stands above the sea: air. A designer with a classified detail names its curve;
/// the choice is the designer's to justify (docs/fatigue-run.md).
pub const DEFAULT_CURVE: &str = "D";

/// The `[fatigue]` section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FatigueSettings {
    /// The S-N curve's name, as `beam-impact fatigue --curve` takes it ([`SnCurve::names`]):
    /// `"D"` by default ([`DEFAULT_CURVE`]).
    pub curve: String,
    /// Stress concentration factor on the stations' nominal stress ranges, 1 to 20 (1: the
    /// nominal stress is the hot-spot stress).
    pub scf: f64,
    /// The detail's thickness, m, for the RP's thickness correction (t / t_ref)^k where thicker
    /// than the curve's reference (25 mm for welded details); absent: no correction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
    /// Design fatigue factor multiplying the damage, 1 to 10 (DNV-OS-C101: 1, 2, 3 by access and
    /// consequence).
    pub design_fatigue_factor: f64,
    /// Impacts per year, for the fatigue life 1 / (damage x events); absent: no life.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub events_per_year: Option<f64>,
}

impl Default for FatigueSettings {
    fn default() -> Self {
        FatigueSettings {
            curve: DEFAULT_CURVE.into(),
            scf: 1.0,
            thickness: None,
            design_fatigue_factor: 1.0,
            events_per_year: None,
        }
    }
}

/// Most impacts a year the life takes: one a second all year (3.2e7) is far beyond any
/// gangway's landings; the bound keeps the life a finite, printable number.
pub const MAX_EVENTS_PER_YEAR: f64 = 1e9;

/// Fewest impacts a year the life takes: one in a million years; fewer would only print lives
/// beyond any structure's (and at 1e-320 an infinite one).
pub const MIN_EVENTS_PER_YEAR: f64 = 1e-6;

impl FatigueSettings {
    /// The curve and the factors, as the fatigue library takes them.
    pub fn options(&self) -> SnOptions {
        SnOptions { scf: self.scf, thickness_m: self.thickness, design_fatigue_factor: self.design_fatigue_factor }
    }

    /// The named curve.
    pub fn curve(&self) -> Result<SnCurve> {
        SnCurve::by_name(&self.curve).map_err(|e| Error::Other(format!("fatigue.curve: {e}")))
    }

    /// Every field out of its bounds, each one line naming it.
    pub fn validation_errors(&self) -> Vec<Error> {
        let mut errors = Vec::new();
        if let Err(e) = self.curve() {
            errors.push(e);
        }
        match self.options().validate() {
            Ok(()) => {}
            Err(Error::Invalid(list)) => errors.extend(list),
            Err(e) => errors.push(e),
        }
        if let Some(n) = self.events_per_year {
            if !(MIN_EVENTS_PER_YEAR..=MAX_EVENTS_PER_YEAR).contains(&n) {
                errors.push(Error::invalid(
                    "fatigue.events_per_year",
                    format!(">= {MIN_EVENTS_PER_YEAR:e} and <= {MAX_EVENTS_PER_YEAR:e}"),
                    n,
                ));
            }
        }
        errors
    }
}

/// The names of the curves in the order of [`SnCurve::names`], as `'static` text for the
/// parameters' symbolic values (`--set fatigue.curve=D`: its index in this list).
pub fn curve_names() -> &'static [&'static str] {
    static NAMES: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
    NAMES.get_or_init(|| SnCurve::names().into_iter().map(|n| &*Box::leak(n.into_boxed_str())).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The defaults are valid, and each bound is refused with one line naming the field.
    #[test]
    fn each_fatigue_bound_is_refused_by_name() {
        assert!(FatigueSettings::default().validation_errors().is_empty());
        type Change = fn(&mut FatigueSettings);
        let cases: [(Change, &str); 6] = [
            (|f| f.curve = "Z9".into(), "fatigue.curve"),
            (|f| f.scf = 0.5, "fatigue.scf"),
            (|f| f.thickness = Some(-0.01), "fatigue.thickness"),
            (|f| f.design_fatigue_factor = f64::NAN, "fatigue.design_fatigue_factor"),
            (|f| f.events_per_year = Some(-3.0), "fatigue.events_per_year"),
            (|f| f.events_per_year = Some(f64::INFINITY), "fatigue.events_per_year"),
        ];
        for (change, name) in cases {
            let mut f = FatigueSettings::default();
            change(&mut f);
            let errors = f.validation_errors();
            assert_eq!(errors.len(), 1, "{name}: {errors:?}");
            let text = errors[0].to_string();
            assert!(text.contains(name) && !text.contains('\n'), "{text}");
        }
    }
}
