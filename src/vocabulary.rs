//! One name per quantity. The FMU's dotted variable names (`lower.clamp_bending_stress`,
//! `peak.contact.force`, `quality.trusted`) and the scenario keys (`drop_height`, `upper.mass`)
//! are the names; the CSV columns of `sweep` and `report --csv`, the keys of `sweep --json` and
//! the columns of the Python `Log.dataframe()` use them. The former underscore names
//! (`lower_clamp_bending_stress`, `peaks.contact_force`, `trusted`) stay as duplicate columns,
//! after the named ones, until version [`FORMER_NAMES_REMOVED_IN`].
//!
//! Units travel beside a CSV in a sidecar, `FILE.units.json` ([`units_path`],
//! [`units_document`]), so that `pandas.read_csv` reads the CSV as it is.

use std::path::{Path, PathBuf};

/// The version whose CSV and JSON drop the former names.
pub const FORMER_NAMES_REMOVED_IN: &str = "0.2.0";

/// The five peaked quantities by their FMU names, in the order of
/// [`crate::results::Peaks::as_array`]; the FMU's peak outputs are `peak.<name>`.
pub const PEAK_QUANTITIES: [&str; 5] = [
    "lower.tip_deflection",
    "lower.clamp_bending_stress",
    "lower.clamp_shear_stress",
    "upper.contact_bending_stress",
    "contact.force",
];

/// The five peaks' former names, the field names of [`crate::results::Peaks`] (serde keys of
/// `run --json`'s peak objects), in the order of [`PEAK_QUANTITIES`].
pub const PEAK_FIELDS: [&str; 5] = [
    "lower_tip_deflection",
    "lower_clamp_bending_stress",
    "lower_clamp_shear_stress",
    "upper_contact_bending_stress",
    "contact_force",
];

/// The SI units of [`PEAK_QUANTITIES`], in their order.
pub const PEAK_UNITS: [&str; 5] = ["m", "Pa", "Pa", "Pa", "N"];

/// The step channel's former column names (the `beam_impact.Step` field paths) and their names,
/// for `report --csv` and the Python `Log.dataframe()`; fields whose path is already the name
/// (`step`, `time`, `energy.kinetic`, ...) are not listed.
pub const STEP_RENAMES: [(&str, &str); 21] = [
    ("contact", "contact.active"),
    ("lower_tip_deflection", "lower.tip_deflection"),
    ("upper_contact_deflection", "upper.contact_deflection"),
    ("upper_tip_deflection", "upper.tip_deflection"),
    ("lower_clamp_bending_stress", "lower.clamp_bending_stress"),
    ("lower_clamp_shear_stress", "lower.clamp_shear_stress"),
    ("upper_contact_bending_stress", "upper.contact_bending_stress"),
    ("contact_force", "contact.force"),
    ("contact_stress", "contact.stress"),
    ("lower_clamp_reaction_force", "lower.clamp_reaction_force"),
    ("lower_clamp_reaction_moment", "lower.clamp_reaction_moment"),
    ("upper_hinge_reaction_force", "upper.hinge_reaction_force"),
    ("lower_tip_velocity", "lower.tip_velocity"),
    ("upper_tip_velocity", "upper.tip_velocity"),
    ("lower_far_reaction_force", "lower.far_reaction_force"),
    ("lower_far_reaction_moment", "lower.far_reaction_moment"),
    ("peaks.lower_tip_deflection", "peak.lower.tip_deflection"),
    ("peaks.lower_clamp_bending_stress", "peak.lower.clamp_bending_stress"),
    ("peaks.lower_clamp_shear_stress", "peak.lower.clamp_shear_stress"),
    ("peaks.upper_contact_bending_stress", "peak.upper.contact_bending_stress"),
    ("peaks.contact_force", "peak.contact.force"),
];

/// The sweep's former column names (and `sweep --json` keys) and their names; the peaks and
/// their times follow from [`PEAK_QUANTITIES`] ([`sweep_former_names`]).
pub const SWEEP_RENAMES: [(&str, &str); 7] = [
    ("discretisation_error", "quality.discretisation_error"),
    ("sensitivity_spread", "quality.sensitivity_spread"),
    ("utilisation.lower_clamp_bending_stress", "utilisation.lower.clamp_bending_stress"),
    ("utilisation.lower_clamp_shear_stress", "utilisation.lower.clamp_shear_stress"),
    ("utilisation.upper_contact_bending_stress", "utilisation.upper.contact_bending_stress"),
    ("design_pass", "design.pass"),
    ("trusted", "quality.trusted"),
];

/// Every former sweep column with its name: `<peak>` -> `peak.<name>`, `<peak>_time` ->
/// `peak_time.<name>`, then [`SWEEP_RENAMES`].
pub fn sweep_former_names() -> Vec<(String, String)> {
    let former = PEAK_FIELDS;
    let mut pairs: Vec<(String, String)> =
        former.iter().zip(PEAK_QUANTITIES).map(|(f, n)| (f.to_string(), format!("peak.{n}"))).collect();
    pairs.extend(former.iter().zip(PEAK_QUANTITIES).map(|(f, n)| (format!("{f}_time"), format!("peak_time.{n}"))));
    pairs.extend(SWEEP_RENAMES.iter().map(|(f, n)| (f.to_string(), n.to_string())));
    pairs
}

/// The name of a peaked quantity given by its former name (`lower_clamp_bending_stress` ->
/// `lower.clamp_bending_stress`), for the printed tables and verdict lines; other names as given.
pub fn quantity_name(former: &str) -> &str {
    PEAK_FIELDS.iter().position(|n| *n == former).map_or(former, |k| PEAK_QUANTITIES[k])
}

/// Adds, in every object of a JSON document that holds a peak under its former name
/// (`"lower_clamp_bending_stress": 4.7e8`), the same value under the quantity's name
/// (`"lower.clamp_bending_stress"`): `run --json` and the log's `answer.json` keep their nested
/// structure and speak the FMU's names too, the former keys kept until
/// [`FORMER_NAMES_REMOVED_IN`].
pub fn add_quantity_names(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            for v in map.values_mut() {
                add_quantity_names(v);
            }
            for (former, name) in PEAK_FIELDS.iter().zip(PEAK_QUANTITIES) {
                if let Some(v) = map.get(*former).cloned() {
                    map.entry(name.to_string()).or_insert(v);
                }
            }
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(add_quantity_names),
        _ => {}
    }
}

/// The sidecar of a CSV (or JSON) file: `sweep.csv` -> `sweep.units.json`.
pub fn units_path(file: &Path) -> PathBuf {
    file.with_extension("units.json")
}

/// The sidecar's content: the columns in order, each with its unit and, for a former name, the
/// name it duplicates. `describes` names the data files it describes.
///
/// ```json
/// {"describes": ["sweep.csv"], "former_names_removed_in": "0.2.0",
///  "columns": [{"name": "drop_height", "unit": "m"}, ...,
///              {"name": "lower_tip_deflection", "unit": "m", "same_as": "peak.lower.tip_deflection"}]}
/// ```
///
/// In pandas: `units = {c["name"]: c["unit"] for c in json.load(f)["columns"]}`.
pub fn units_document(describes: &[String], columns: &[(String, &str)], former: &[(String, String)]) -> String {
    let entries: Vec<serde_json::Value> = columns
        .iter()
        .map(|(name, unit)| match former.iter().find(|(f, _)| f == name) {
            Some((_, same_as)) => serde_json::json!({"name": name, "unit": unit, "same_as": same_as}),
            None => serde_json::json!({"name": name, "unit": unit}),
        })
        .collect();
    let doc = serde_json::json!({
        "describes": describes,
        "units": "SI; \"1\" a dimensionless number or fraction, \"true/false\" a flag, \"text\" a message",
        "former_names_removed_in": FORMER_NAMES_REMOVED_IN,
        "columns": entries,
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every renamed step field is a name the FMU declares (or `contact.active`, its contact
    /// flag), so the CSV and the FMU speak of the same quantity by the same name.
    #[test]
    fn step_names_are_fmu_variable_names() {
        let table = crate::fmi::variables::table();
        let fmu: Vec<&str> = table.iter().map(|v| v.name.as_ref()).collect();
        for (_, name) in STEP_RENAMES {
            assert!(fmu.contains(&name), "{name} is not an FMU variable");
        }
        for (_, name) in SWEEP_RENAMES {
            assert!(fmu.contains(&name), "{name} is not an FMU variable");
        }
        for name in PEAK_QUANTITIES {
            assert!(fmu.contains(&name), "{name}");
            assert!(fmu.contains(&format!("peak.{name}").as_str()), "peak.{name}");
        }
    }

    #[test]
    fn printed_names_are_the_fmu_quantities() {
        assert_eq!(quantity_name("lower_clamp_bending_stress"), "lower.clamp_bending_stress");
        assert_eq!(quantity_name("contact_force"), "contact.force");
        assert_eq!(quantity_name("something_else"), "something_else");
    }

    #[test]
    fn json_peaks_gain_their_quantity_names() {
        let mut doc = serde_json::json!({"summary": {"peaks": {"contact_force": 5.0, "lower_tip_deflection": 0.6}},
                                         "runs": [{"peaks": {"contact_force": 1.0}}], "time": 3.0});
        add_quantity_names(&mut doc);
        assert_eq!(doc["summary"]["peaks"]["contact.force"], 5.0);
        assert_eq!(doc["summary"]["peaks"]["contact_force"], 5.0);
        assert_eq!(doc["summary"]["peaks"]["lower.tip_deflection"], 0.6);
        assert_eq!(doc["runs"][0]["peaks"]["contact.force"], 1.0);
        assert_eq!(doc["time"], 3.0);
    }

    #[test]
    fn the_sidecar_sits_beside_its_file_and_marks_former_names() {
        assert_eq!(units_path(Path::new("out/sweep.csv")), Path::new("out/sweep.units.json"));
        assert_eq!(units_path(Path::new("rows")), Path::new("rows.units.json"));
        let text = units_document(
            &["a.csv".into()],
            &[("peak.contact.force".into(), "N"), ("contact_force".into(), "N")],
            &[("contact_force".into(), "peak.contact.force".into())],
        );
        let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(doc["describes"][0], "a.csv");
        assert_eq!(doc["columns"][0]["name"], "peak.contact.force");
        assert_eq!(doc["columns"][0]["unit"], "N");
        assert!(doc["columns"][0].get("same_as").is_none());
        assert_eq!(doc["columns"][1]["same_as"], "peak.contact.force");
    }
}
