//! The `[fatigue]` section's fields as parameters (issue 44: `--set fatigue.FIELD=VALUE`,
//! `--vary`, `beam-impact scenario`), apart from the section itself
//! ([`super::fatigue_settings`]) so that the scenario holding it needs none of them.

use super::fatigue_settings::{curve_names, FatigueSettings, DEFAULT_CURVE, MAX_EVENTS_PER_YEAR, MIN_EVENTS_PER_YEAR};
use crate::error::Error;
use crate::model::parameters::{Kind, Parameter};
use crate::model::Scenario;

/// The fatigue section of `scenario`, added with the defaults when missing.
fn section(scenario: &mut Scenario) -> &mut FatigueSettings {
    scenario.fatigue.get_or_insert_with(FatigueSettings::default)
}

/// The fatigue settings `scenario` is assessed with (the defaults without a section).
pub fn of(scenario: &Scenario) -> FatigueSettings {
    scenario.fatigue.clone().unwrap_or_default()
}

/// Every `[fatigue]` field a setting or a sweep can change. 0 is "absent" for the thickness and
/// the events per year.
pub static FATIGUE_FIELDS: [Parameter; 5] = [
    Parameter {
        name: "fatigue.curve",
        unit: "",
        description: "The S-N curve of DNV-RP-C203 (beam-impact fatigue --help lists them; default D in air)",
        kind: Kind::Integer,
        get: |s| {
            let name = of(s).curve;
            curve_names().iter().position(|n| n.eq_ignore_ascii_case(&name)).map_or(f64::NAN, |k| k as f64)
        },
        put: |s, v| {
            let names = curve_names();
            let name = (v.fract() == 0.0 && v >= 0.0 && (v as usize) < names.len())
                .then(|| names[v as usize])
                .ok_or_else(|| Error::invalid("fatigue.curve", format!("a curve's name ({})", names.join(", ")), v))?;
            section(s).curve = name.into();
            Ok(())
        },
    },
    Parameter {
        name: "fatigue.scf",
        unit: "1",
        description: "Stress concentration factor on the nominal stress range",
        kind: Kind::Real,
        get: |s| of(s).scf,
        put: |s, v| {
            section(s).scf = v;
            Ok(())
        },
    },
    Parameter {
        name: "fatigue.thickness",
        unit: "m",
        description: "The detail's thickness for the thickness correction; 0: none",
        kind: Kind::Real,
        get: |s| of(s).thickness.unwrap_or(0.0),
        put: |s, v| {
            section(s).thickness = (v != 0.0).then_some(v);
            Ok(())
        },
    },
    Parameter {
        name: "fatigue.design_fatigue_factor",
        unit: "1",
        description: "Design fatigue factor on the damage",
        kind: Kind::Real,
        get: |s| of(s).design_fatigue_factor,
        put: |s, v| {
            section(s).design_fatigue_factor = v;
            Ok(())
        },
    },
    Parameter {
        name: "fatigue.events_per_year",
        unit: "1/year",
        description: "Impacts per year, for the fatigue life; 0: none given",
        kind: Kind::Real,
        get: |s| of(s).events_per_year.unwrap_or(0.0),
        put: |s, v| {
            section(s).events_per_year = (v != 0.0).then_some(v);
            Ok(())
        },
    },
];

/// The `[fatigue]` section commented out with its defaults, each field's unit, description and
/// range, as `beam-impact scenario` shows it after the annotated fields
/// ([`crate::model::parameters::annotate_toml`]): a scenario without it is assessed on these.
pub fn section_comment() -> String {
    let examples: [(&str, String); 5] = [
        ("curve", format!("\"{DEFAULT_CURVE}\"")),
        ("scf", "1.0".into()),
        ("thickness", "0.025".into()),
        ("design_fatigue_factor", "1.0".into()),
        ("events_per_year", "1000.0".into()),
    ];
    let ranges = [
        "a name of `beam-impact fatigue --curve`".to_string(),
        "1 to 20".into(),
        "absent (no correction), or > 0 to 1".into(),
        "1 to 10".into(),
        format!("absent (no life), or {MIN_EVENTS_PER_YEAR:e} to {MAX_EVENTS_PER_YEAR:e}"),
    ];
    let mut out = String::from("\n# [fatigue]  # a run's fatigue (docs/fatigue-run.md); absent: the defaults below\n");
    for ((p, (key, example)), range) in FATIGUE_FIELDS.iter().zip(examples).zip(ranges) {
        let unit = if p.unit.is_empty() { "-" } else { p.unit };
        out.push_str(&format!("# {key} = {example}  # [{unit}] {}; range {range}\n", p.description));
    }
    out
}
