//! The two modelDescription.xml files, generated from the variable table ([`super::variables`]).
//! The committed copies (`modelDescription.xml` for FMI 2.0, `fmu/modelDescription.xml` for
//! FMI 3.0) are checked against these by `tests/fmi_drift.rs`.

use std::collections::BTreeSet;
use std::fmt::Write;

/// The starting scenario's file name in the FMU's `resources/` (issue 30).
pub const SCENARIO_RESOURCE: &str = "scenario.toml";

use super::variables::{
    affects_values, base_units, declared_type, display_unit, format_real, table, table_for, Causality, Source, Type,
    Variable,
};
use crate::Scenario;

/// The `modelIdentifier`: the binary is `BeamImpact.so`.
pub const MODEL_IDENTIFIER: &str = "BeamImpact";

/// Start, stop and communication step of the DefaultExperiment, s (the paper's 3 s run).
pub const DEFAULT_EXPERIMENT: (f64, f64, f64) = (0.0, 3.0, 1e-3);

/// `generationDateAndTime` of both descriptions: when the variable table last changed (set by
/// hand with it; a constant, not the clock, so that the generated files are reproducible and the
/// drift test holds).
pub const GENERATION_DATE_AND_TIME: &str = "2026-11-26T00:00:00Z";

const DESCRIPTION: &str = "Elastic impact of two beams (Catipovic, Vladimir, Reljic 2008): a hinged bridge dropped \
                           on a cantilever arrestor through a contact bar, Euler-Bernoulli FEM with the modified linear \
                           acceleration method";

const CATEGORIES: &[(&str, &str)] = &[
    ("logEvents", "Contact starts and ends, early returns"),
    ("logStatusWarning", "Warnings"),
    ("logStatusDiscard", "Discarded calls"),
    ("logStatusError", "Errors: invalid parameters, illegal call sequences, bad arguments"),
    ("logStatusFatal", "Internal errors (the instance can only be freed)"),
];

/// The instantiation token (FMI 2 `guid`): a GUID-shaped FNV-1a hash of the variable table, so a
/// description from another build of the table is refused at instantiation.
pub fn token() -> String {
    token_for(None)
}

/// The instantiation token of an FMU that starts from `packed` (its `resources/scenario.toml`,
/// issue 30; `None`: the paper scenario, [`token`]): the hash of the variable table with that
/// scenario's start values and, for beams of sections, of the sections, which no variable holds.
/// A description and a resource scenario that do not belong together are refused at
/// instantiation.
pub fn token_for(packed: Option<&Scenario>) -> String {
    let mut hash: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    let mut feed = |line: &str| {
        for b in line.bytes() {
            hash ^= u128::from(b);
            hash = hash.wrapping_mul(0x0000_0000_0100_0000_0000_0000_0000_013b);
        }
    };
    for v in packed.map_or_else(table, table_for) {
        feed(&format!(
            "{}|{}|{}|{}|{}|{:?}|{:?}\n",
            v.name,
            v.vr,
            v.ty.fmi2_name(),
            v.causality.name(),
            v.variability.name(),
            v.unit,
            v.start
        ));
    }
    // Uniform beams (every FMU before issue 30) add nothing: their tokens stay as they were.
    for (beam, sections) in packed.iter().flat_map(|s| [("upper", &s.upper.sections), ("lower", &s.lower.sections)]) {
        for (k, section) in sections.iter().enumerate() {
            feed(&format!("{beam}.sections[{}]|{}\n", k + 1, serde_json::to_string(section).unwrap_or_default()));
        }
    }
    let h = format!("{hash:032x}");
    format!("{{{}-{}-{}-{}-{}}}", &h[0..8], &h[8..12], &h[12..16], &h[16..20], &h[20..32])
}

/// Escapes text for an XML attribute.
fn esc(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn units(variables: &[Variable]) -> BTreeSet<&'static str> {
    variables.iter().filter_map(|v| v.unit).collect()
}

fn unit_definitions(out: &mut String, variables: &[Variable]) {
    out.push_str("  <UnitDefinitions>\n");
    for unit in units(variables) {
        let exponents = base_units(unit).unwrap_or([0; 4]);
        let base: String = ["kg", "m", "s", "rad"]
            .iter()
            .zip(exponents)
            .filter(|(_, e)| *e != 0)
            .map(|(name, e)| format!(" {name}=\"{e}\""))
            .collect();
        let _ = write!(out, "    <Unit name=\"{}\">\n      <BaseUnit{base}/>\n", esc(unit));
        if unit == "Pa" {
            out.push_str("      <DisplayUnit name=\"MPa\" factor=\"1e-06\"/>\n");
        }
        out.push_str("    </Unit>\n");
    }
    out.push_str("  </UnitDefinitions>\n");
}

/// `<TypeDefinitions>`: one type per unit the variables use, which declares the unit (and the
/// display unit) for every variable of that unit through `declaredType`.
fn type_definitions(out: &mut String, variables: &[Variable], fmi3: bool) {
    out.push_str("  <TypeDefinitions>\n");
    let mut types: Vec<(&str, &str, &str)> = units(variables)
        .into_iter()
        .filter_map(|u| declared_type(u).map(|(name, quantity)| (name, quantity, u)))
        .collect();
    types.sort_unstable();
    for (name, quantity, unit) in types {
        let mut attributes = format!("quantity=\"{}\" unit=\"{}\"", esc(quantity), esc(unit));
        if let Some(display) = display_unit(unit) {
            let _ = write!(attributes, " displayUnit=\"{display}\"");
        }
        if fmi3 {
            let _ = writeln!(out, "    <Float64Type name=\"{}\" {attributes}/>", esc(name));
        } else {
            let _ =
                writeln!(out, "    <SimpleType name=\"{}\">\n      <Real {attributes}/>\n    </SimpleType>", esc(name));
        }
    }
    out.push_str("  </TypeDefinitions>\n");
}

/// `declaredType`, `min` and `max` of a variable's type element, each with a leading space.
fn type_attributes(v: &Variable) -> String {
    let mut a = String::new();
    if let Some(name) = v.declared_type() {
        let _ = write!(a, " declaredType=\"{}\"", esc(name));
    }
    let bound = |x: f64| if v.ty == Type::Integer { format!("{}", x as i64) } else { format_real(x) };
    if let Some(min) = v.min {
        let _ = write!(a, " min=\"{}\"", bound(min));
    }
    if let Some(max) = v.max {
        let _ = write!(a, " max=\"{}\"", bound(max));
    }
    a
}

/// What an initial unknown depends on in Initialization Mode: every parameter the computed
/// values depend on and, for an output, the inputs (the initial state is the static deflection
/// under the tip forces). After initialization an output depends on no input: an input set at a
/// communication point acts from that point on, and the outputs there were computed before it;
/// so every output declares `dependencies=""`. FMI 2 lists 1-based indices, FMI 3 value
/// references (both are the value reference + 1 / the value reference here).
fn initial_dependencies(v: &Variable, variables: &[Variable]) -> Vec<u32> {
    variables
        .iter()
        .filter(|k| match k.source {
            Source::Parameter(p) => affects_values(p),
            Source::Input(_) | Source::Motion(_) => v.causality == Causality::Output,
            _ => false,
        })
        .map(|k| k.vr)
        .collect()
}

fn list(values: impl IntoIterator<Item = u32>) -> String {
    values.into_iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ")
}

fn log_categories(out: &mut String) {
    out.push_str("  <LogCategories>\n");
    for (name, description) in CATEGORIES {
        let _ = writeln!(out, "    <Category name=\"{name}\" description=\"{}\"/>", esc(description));
    }
    out.push_str("  </LogCategories>\n");
}

fn default_experiment(out: &mut String) {
    let (start, stop, step) = DEFAULT_EXPERIMENT;
    let _ = writeln!(out, "  <DefaultExperiment startTime=\"{start:?}\" stopTime=\"{stop:?}\" stepSize=\"{step:?}\"/>");
}

/// The attributes every variable element shares (name .. initial).
fn common_attributes(v: &Variable) -> String {
    let mut a = format!(
        "name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{}\" variability=\"{}\"",
        esc(&v.name),
        v.vr,
        esc(&v.description),
        v.causality.name(),
        v.variability.name()
    );
    if v.causality != Causality::Input {
        match v.exact {
            Some(true) => a.push_str(" initial=\"exact\""),
            Some(false) => a.push_str(" initial=\"calculated\""),
            None => {}
        }
    }
    a
}

fn is_initial_unknown(v: &Variable) -> bool {
    v.causality == Causality::CalculatedParameter || (v.causality == Causality::Output && v.exact == Some(false))
}

/// `generationTool`: the crate and its version; `commit` (the packed FMU's git commit) is added
/// only when given, so that the committed descriptions stay free of drift.
pub fn generation_tool(commit: Option<&str>) -> String {
    let tool = format!("beam-impact {}", env!("CARGO_PKG_VERSION"));
    match commit {
        Some(commit) => format!("{tool} (git {commit})"),
        None => tool,
    }
}

/// The model's `description`: the model, and for an FMU packed with a scenario of its own (issue
/// 30) where that scenario is and what its start values are.
fn model_description(packed: Option<&Scenario>) -> String {
    let Some(s) = packed else { return DESCRIPTION.to_string() };
    let sections = |n: usize, beam: &str| match n {
        0 => None,
        1 => Some(format!("1 section for the {beam}")),
        n => Some(format!("{n} sections for the {beam}")),
    };
    let listed: Vec<String> =
        [sections(s.upper.sections.len(), "bridge"), sections(s.lower.sections.len(), "arrestor")]
            .into_iter()
            .flatten()
            .collect();
    let beams = if listed.is_empty() { String::new() } else { format!(", with {}", listed.join(" and ")) };
    format!(
        "{DESCRIPTION}. Packed with a starting scenario of its own, resources/{SCENARIO_RESOURCE}{beams}: the start \
         values are that scenario's, and parameters set by the importer override its uniform fields"
    )
}

/// The FMI 2.0 modelDescription.xml (as committed: no commit in `generationTool`).
pub fn fmi2() -> String {
    fmi2_by(&generation_tool(None))
}

/// The FMI 2.0 modelDescription.xml with `generation_tool` ([`generation_tool`]).
pub fn fmi2_by(generation_tool: &str) -> String {
    fmi2_for(None, generation_tool)
}

/// The FMI 2.0 modelDescription.xml of an FMU that starts from `packed` (its
/// `resources/scenario.toml`; `None`: the paper scenario) with `generation_tool`.
pub fn fmi2_for(packed: Option<&Scenario>, generation_tool: &str) -> String {
    let variables = packed.map_or_else(table, table_for);
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{MODEL_IDENTIFIER}\" guid=\"{}\"\n  \
         description=\"{}\"\n  generationTool=\"{}\" generationDateAndTime=\"{GENERATION_DATE_AND_TIME}\"\n  \
         variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">",
        token_for(packed),
        esc(&model_description(packed)),
        esc(generation_tool)
    );
    let _ = writeln!(
        out,
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" canHandleVariableCommunicationStepSize=\"true\" \
         canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" canNotUseMemoryManagementFunctions=\"true\"/>"
    );
    unit_definitions(&mut out, &variables);
    type_definitions(&mut out, &variables, false);
    log_categories(&mut out);
    default_experiment(&mut out);
    out.push_str("  <ModelVariables>\n");
    for (index, v) in variables.iter().enumerate() {
        let _ = writeln!(out, "    <!-- index {} -->", index + 1);
        let _ = writeln!(out, "    <ScalarVariable {}>", common_attributes(v));
        let mut t = format!("      <{}{}", v.ty.fmi2_name(), type_attributes(v));
        if let Some(start) = &v.start {
            let _ = write!(t, " start=\"{}\"", esc(start));
        }
        let _ = writeln!(out, "{t}/>\n    </ScalarVariable>");
    }
    out.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    for (index, v) in variables.iter().enumerate() {
        if v.causality == Causality::Output {
            let _ = writeln!(out, "      <Unknown index=\"{}\" dependencies=\"\"/>", index + 1);
        }
    }
    out.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for (index, v) in variables.iter().enumerate() {
        if is_initial_unknown(v) {
            let dependencies = list(initial_dependencies(v, &variables).into_iter().map(|vr| vr + 1));
            let _ = writeln!(out, "      <Unknown index=\"{}\" dependencies=\"{dependencies}\"/>", index + 1);
        }
    }
    out.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    out
}

/// The FMI 3.0 modelDescription.xml (as committed: no commit in `generationTool`).
pub fn fmi3() -> String {
    fmi3_by(&generation_tool(None))
}

/// The FMI 3.0 modelDescription.xml with `generation_tool` ([`generation_tool`]).
pub fn fmi3_by(generation_tool: &str) -> String {
    fmi3_for(None, generation_tool)
}

/// The FMI 3.0 modelDescription.xml of an FMU that starts from `packed` (see [`fmi2_for`]).
pub fn fmi3_for(packed: Option<&Scenario>, generation_tool: &str) -> String {
    let variables = packed.map_or_else(table, table_for);
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"{MODEL_IDENTIFIER}\" instantiationToken=\"{}\"\n  \
         description=\"{}\"\n  generationTool=\"{}\" generationDateAndTime=\"{GENERATION_DATE_AND_TIME}\"\n  \
         variableNamingConvention=\"structured\">",
        token_for(packed),
        esc(&model_description(packed)),
        esc(generation_tool)
    );
    let _ = writeln!(
        out,
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" canHandleVariableCommunicationStepSize=\"true\" \
         canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\" hasEventMode=\"true\" \
         mightReturnEarlyFromDoStep=\"true\"/>"
    );
    unit_definitions(&mut out, &variables);
    type_definitions(&mut out, &variables, true);
    log_categories(&mut out);
    default_experiment(&mut out);
    out.push_str("  <ModelVariables>\n");
    for v in &variables {
        let mut element = format!("    <{} {}{}", v.ty.fmi3_name(), common_attributes(v), type_attributes(v));
        match (&v.start, v.ty) {
            (Some(start), Type::String) => {
                let _ = write!(element, ">\n      <Start value=\"{}\"/>\n    </String>", esc(start));
            }
            (Some(start), _) => {
                let _ = write!(element, " start=\"{}\"/>", esc(start));
            }
            (None, _) => element.push_str("/>"),
        }
        out.push_str(&element);
        out.push('\n');
    }
    out.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    for v in &variables {
        if v.causality == Causality::Output {
            let _ = writeln!(out, "    <Output valueReference=\"{}\" dependencies=\"\"/>", v.vr);
        }
    }
    for v in &variables {
        if is_initial_unknown(v) {
            let dependencies = list(initial_dependencies(v, &variables));
            let _ = writeln!(out, "    <InitialUnknown valueReference=\"{}\" dependencies=\"{dependencies}\"/>", v.vr);
        }
    }
    out.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn token_is_guid_shaped_and_in_both_descriptions() {
        let t = token();
        assert_eq!(t.len(), 38, "{t}");
        assert!(fmi2().contains(&format!("guid=\"{t}\"")));
        assert!(fmi3().contains(&format!("instantiationToken=\"{t}\"")));
    }

    #[test]
    fn stresses_display_in_mpa() {
        assert!(fmi2().contains("<DisplayUnit name=\"MPa\" factor=\"1e-06\"/>"));
        assert!(fmi3().contains("name=\"peak.lower.clamp_bending_stress\""));
    }
}
