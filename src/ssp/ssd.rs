//! `SystemStructure.ssd` of GangwayOnVessel.ssp (SSP 1.0): the vessel-motion FMU and the
//! BeamImpact FMU as two components, each with the connectors a tool exchanges or records
//! (a tool exchanges only variables declared as connectors; Ecos refuses a connection naming an
//! undeclared one), the connections both ways, the parameter bindings of each component (inline
//! parameter sets: the scenario's main fields, the vessel's wave and response), the units of
//! every connector and binding, and the default experiment (with libcosim's fixed-step
//! annotation: the master's 1 ms). Elements stand in the order the SSP 1.0 schema requires
//! (System, Units, DefaultExperiment; in a component Connectors before ParameterBindings).

use std::fmt::Write;

use super::vessel::{self, RealVariable};
use crate::fmi::variables::{base_units, Causality, Type, Variable};
use crate::model::support_motion::MOTION_NAMES;
use crate::{Error, Result};

/// The system's (and the archive's) name.
pub const SYSTEM_NAME: &str = "GangwayOnVessel";
/// The BeamImpact component's name.
pub const BEAM_COMPONENT: &str = "gangway";
/// The vessel-motion component's name.
pub const VESSEL_COMPONENT: &str = "vessel";
/// Where the archive holds the BeamImpact FMU (FMI 2.0).
pub const BEAM_SOURCE: &str = "resources/BeamImpact.fmu";
/// Where the archive holds the vessel-motion FMU.
pub const VESSEL_SOURCE: &str = "resources/VesselMotion.fmu";
/// The name of each component's parameter set: one name across the components, so that a tool
/// that applies sets by name (Ecos: `init(parameter_set=...)`) applies both with one call.
pub const PARAMETER_SET: &str = "GangwayOnVessel";
/// The communication step of the default experiment, s: the Python master's
/// (`tests/python/vessel_master.py`), so that a tool's run and the master's exchange the same values.
pub const COMMUNICATION_STEP: f64 = 1e-3;

/// The reactions BeamImpact sends the vessel as its deck load: (BeamImpact output, vessel input).
pub const REACTIONS: [(&str, &str); 3] = [
    ("upper.hinge_reaction_force", "hinge_force"),
    ("lower.clamp_reaction_force", "clamp_force"),
    ("lower.clamp_reaction_moment", "clamp_moment"),
];

/// BeamImpact's outputs declared as connectors besides the reactions: what a tool records (the
/// running peaks the README's tables give, the contact force, the stresses at the critical points,
/// the tips' absolute positions and the energy check).
pub const BEAM_OUTPUTS: [&str; 12] = [
    "peak.lower.clamp_bending_stress",
    "peak.upper.contact_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.contact.force",
    "contact.force",
    "lower.clamp_bending_stress",
    "upper.contact_bending_stress",
    "lower.clamp_shear_stress",
    "upper.tip_position",
    "lower.tip_position",
    "energy.residual",
    "energy.external_work",
];

/// The scenario's main fields, bound as BeamImpact's parameters (the geometry, masses, contact,
/// drop and allowables; the rest keep the FMU's start values, which are the same scenario's),
/// each one the packed description has as a Real parameter.
pub const BEAM_PARAMETERS: [&str; 14] = [
    "lower.length",
    "lower.mass",
    "lower.tip_mass",
    "upper.length",
    "upper.mass",
    "contact_position",
    "contact.area",
    "contact.length",
    "contact.elastic_modulus",
    "gravity",
    "drop_height",
    "lower.allowable_bending_stress",
    "lower.allowable_shear_stress",
    "upper.allowable_bending_stress",
];

/// The vessel's outputs declared as connectors besides the nine motions: the wave, the vessel's
/// own motion and the deck load.
pub const VESSEL_OUTPUTS: [&str; 7] = [
    "wave.elevation",
    "vessel.heave",
    "vessel.pitch",
    "deck.force",
    "deck.pitch_moment",
    "deck.heave_acceleration",
    "deck.pitch_acceleration",
];

/// One connector: name, kind (`input`, `output`, `parameter`), unit.
struct Connector {
    name: String,
    kind: &'static str,
    unit: Option<String>,
}

/// XML text with `&`, `<`, `>` and `"` escaped.
fn esc(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A number as `xs:double` reads it back to the same bits (Rust's shortest round-trip form).
fn number(value: f64) -> String {
    format!("{value:?}")
}

/// The text of `SystemStructure.ssd` for BeamImpact's variables `beam` (its description's table:
/// the packed scenario's start values) and the embedded vessel description; `generation_tool`
/// names this build; `vessel_values` binds those vessel parameters to other values than their start
/// values (a scenario's `[sea]`: [`vessel::sea_bindings`]). Errors name a variable the SSD needs
/// that a description lacks.
pub fn system_structure(beam: &[Variable], generation_tool: &str, vessel_values: &[(&str, f64)]) -> Result<String> {
    let vessel_vars = vessel::real_variables()?;
    let find_beam = |name: &str| -> Result<&Variable> {
        beam.iter().find(|v| v.name == name).ok_or_else(|| {
            Error::Other(format!("cannot write the SSP: BeamImpact's description has no variable {name}"))
        })
    };
    let find_vessel = |name: &str| -> Result<&RealVariable> {
        vessel_vars
            .iter()
            .find(|v| v.name == name)
            .ok_or_else(|| Error::Other(format!("cannot write the SSP: VesselMotion.xml has no Real variable {name}")))
    };
    let beam_unit = |v: &Variable| v.unit.map(str::to_string);

    // The vessel: the nine motions and its other outputs, the reactions as inputs, its Real
    // parameters (bound to their start values: the wave and the response a user changes here).
    let mut vessel_connectors = Vec::new();
    for name in MOTION_NAMES.iter().chain(VESSEL_OUTPUTS.iter()) {
        let v = find_vessel(name)?;
        vessel_connectors.push(Connector { name: v.name.clone(), kind: "output", unit: Some(v.unit.clone()) });
    }
    for (_, input) in REACTIONS {
        let v = find_vessel(input)?;
        vessel_connectors.push(Connector { name: v.name.clone(), kind: "input", unit: Some(v.unit.clone()) });
    }
    let vessel_parameters: Vec<&RealVariable> = vessel_vars.iter().filter(|v| v.causality == "parameter").collect();
    let mut vessel_bindings = Vec::new();
    if let Some((name, _)) = vessel_values.iter().find(|(n, _)| !vessel_parameters.iter().any(|v| v.name == *n)) {
        return Err(Error::Other(format!("cannot write the SSP: VesselMotion.xml has no Real parameter {name}")));
    }
    for v in &vessel_parameters {
        if let Some((_, value)) = vessel_values.iter().find(|(n, _)| *n == v.name) {
            vessel_connectors.push(Connector { name: v.name.clone(), kind: "parameter", unit: Some(v.unit.clone()) });
            vessel_bindings.push((v.name.clone(), number(*value), v.unit.clone()));
            continue;
        }
        let start = v.start.ok_or_else(|| {
            Error::Other(format!("cannot write the SSP: VesselMotion.xml gives the parameter {} no start", v.name))
        })?;
        vessel_connectors.push(Connector { name: v.name.clone(), kind: "parameter", unit: Some(v.unit.clone()) });
        vessel_bindings.push((v.name.clone(), number(start), v.unit.clone()));
    }

    // BeamImpact: the nine motions as inputs, the reactions and the recorded outputs, the
    // scenario's main fields as parameters (bound to the packed scenario's values).
    let mut beam_connectors = Vec::new();
    for name in MOTION_NAMES {
        let v = find_beam(name)?;
        beam_connectors.push(Connector { name: v.name.clone(), kind: "input", unit: beam_unit(v) });
    }
    for name in REACTIONS.iter().map(|r| r.0).chain(BEAM_OUTPUTS) {
        let v = find_beam(name)?;
        beam_connectors.push(Connector { name: v.name.clone(), kind: "output", unit: beam_unit(v) });
    }
    // A packed scenario with beams of sections has no uniform mass or length parameter for such a
    // beam (its sections come from resources/scenario.toml): those fields are left out.
    let mut beam_bindings = Vec::new();
    for name in BEAM_PARAMETERS {
        let Some(v) = beam.iter().find(|v| v.name == name) else { continue };
        let (Some(start), Causality::Parameter, Type::Real) = (&v.start, v.causality, v.ty) else { continue };
        beam_connectors.push(Connector { name: v.name.clone(), kind: "parameter", unit: beam_unit(v) });
        beam_bindings.push((v.name.clone(), start.clone(), v.unit.unwrap_or("1").to_string()));
    }

    // Every unit a connector or binding names, with its base units (BeamImpact's table, else the
    // vessel's description).
    let vessel_units = vessel::units();
    let mut units: Vec<(String, [i32; 4], f64)> = Vec::new();
    let named = vessel_connectors.iter().chain(&beam_connectors).filter_map(|c| c.unit.clone());
    for unit in named.chain(beam_bindings.iter().map(|b| b.2.clone())) {
        if units.iter().any(|u| u.0 == unit) {
            continue;
        }
        let (exponents, factor) = base_units(&unit)
            .map(|e| (e, 1.0))
            .or_else(|| vessel_units.iter().find(|u| u.0 == unit).map(|u| (u.1, u.2)))
            .ok_or_else(|| Error::Other(format!("cannot write the SSP: no base units known for the unit `{unit}`")))?;
        units.push((unit, exponents, factor));
    }

    let (start, stop, _) = crate::fmi::description::DEFAULT_EXPERIMENT;
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<ssd:SystemStructureDescription xmlns:ssc=\"http://ssp-standard.org/SSP1/SystemStructureCommon\" \
         xmlns:ssd=\"http://ssp-standard.org/SSP1/SystemStructureDescription\" \
         xmlns:ssv=\"http://ssp-standard.org/SSP1/SystemStructureParameterValues\" \
         xmlns:osp=\"http://opensimulationplatform.com/SSP/OSPAnnotations\" version=\"1.0\" \
         name=\"{SYSTEM_NAME}\" generationTool=\"{}\">",
        esc(generation_tool)
    );
    let _ = writeln!(
        out,
        "  <ssd:System name=\"{SYSTEM_NAME}\" description=\"BeamImpact's gangway and arrestor on a vessel in a regular \
         head sea (or, with sea.significant_wave_height > 0, an irregular sea through the vessel's RAO table): the \
         vessel's motion drives the supports, the support reactions load its deck\">"
    );
    out.push_str("    <ssd:Elements>\n");
    component(&mut out, VESSEL_COMPONENT, VESSEL_SOURCE, &vessel_connectors, &vessel_bindings);
    component(&mut out, BEAM_COMPONENT, BEAM_SOURCE, &beam_connectors, &beam_bindings);
    out.push_str("    </ssd:Elements>\n");
    out.push_str("    <ssd:Connections>\n");
    for name in MOTION_NAMES {
        connection(&mut out, (VESSEL_COMPONENT, name), (BEAM_COMPONENT, name));
    }
    for (output, input) in REACTIONS {
        connection(&mut out, (BEAM_COMPONENT, output), (VESSEL_COMPONENT, input));
    }
    out.push_str("    </ssd:Connections>\n");
    out.push_str("  </ssd:System>\n");
    out.push_str("  <ssd:Units>\n");
    for (name, exponents, factor) in &units {
        let mut attributes = String::new();
        for (base, e) in ["kg", "m", "s", "rad"].iter().zip(exponents) {
            if *e != 0 {
                let _ = write!(attributes, " {base}=\"{e}\"");
            }
        }
        if *factor != 1.0 {
            let _ = write!(attributes, " factor=\"{}\"", number(*factor));
        }
        let _ =
            writeln!(out, "    <ssc:Unit name=\"{}\">\n      <ssc:BaseUnit{attributes}/>\n    </ssc:Unit>", esc(name));
    }
    out.push_str("  </ssd:Units>\n");
    let _ = writeln!(out, "  <ssd:DefaultExperiment startTime=\"{}\" stopTime=\"{}\">", number(start), number(stop));
    out.push_str("    <ssd:Annotations>\n      <ssc:Annotation type=\"com.opensimulationplatform\">\n");
    let _ = writeln!(
        out,
        "        <osp:Algorithm>\n          <osp:FixedStepAlgorithm baseStepSize=\"{}\"/>\n        </osp:Algorithm>",
        number(COMMUNICATION_STEP)
    );
    out.push_str("      </ssc:Annotation>\n    </ssd:Annotations>\n  </ssd:DefaultExperiment>\n");
    out.push_str("</ssd:SystemStructureDescription>\n");
    Ok(out)
}

/// One component: its connectors, then its parameter binding (one inline parameter set,
/// [`PARAMETER_SET`]).
fn component(
    out: &mut String,
    name: &str,
    source: &str,
    connectors: &[Connector],
    bindings: &[(String, String, String)],
) {
    let _ = writeln!(
        out,
        "      <ssd:Component name=\"{name}\" type=\"application/x-fmu-sharedlibrary\" source=\"{source}\">"
    );
    out.push_str("        <ssd:Connectors>\n");
    for c in connectors {
        let unit = c.unit.as_deref().map(|u| format!(" unit=\"{}\"", esc(u))).unwrap_or_default();
        let _ = writeln!(
            out,
            "          <ssd:Connector name=\"{}\" kind=\"{}\">\n            <ssc:Real{unit}/>\n          </ssd:Connector>",
            esc(&c.name),
            c.kind
        );
    }
    out.push_str("        </ssd:Connectors>\n");
    out.push_str(
        "        <ssd:ParameterBindings>\n          <ssd:ParameterBinding>\n            <ssd:ParameterValues>\n",
    );
    let _ = writeln!(
        out,
        "              <ssv:ParameterSet version=\"1.0\" name=\"{PARAMETER_SET}\">\n                <ssv:Parameters>"
    );
    for (parameter, value, unit) in bindings {
        let _ = writeln!(
            out,
            "                  <ssv:Parameter name=\"{}\">\n                    <ssv:Real value=\"{}\" unit=\"{}\"/>\n                  </ssv:Parameter>",
            esc(parameter),
            esc(value),
            esc(unit)
        );
    }
    out.push_str("                </ssv:Parameters>\n              </ssv:ParameterSet>\n");
    out.push_str(
        "            </ssd:ParameterValues>\n          </ssd:ParameterBinding>\n        </ssd:ParameterBindings>\n",
    );
    out.push_str("      </ssd:Component>\n");
}

/// One connection from `(element, connector)` to `(element, connector)`.
fn connection(out: &mut String, from: (&str, &str), to: (&str, &str)) {
    let _ = writeln!(
        out,
        "      <ssd:Connection startElement=\"{}\" startConnector=\"{}\" endElement=\"{}\" endConnector=\"{}\"/>",
        from.0,
        esc(from.1),
        to.0,
        esc(to.1)
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every connection names declared connectors of the right kinds, and every connector's unit
    /// is defined (what Ecos and libcosim check when they load the file).
    #[test]
    fn connections_name_declared_connectors_and_units_are_defined() {
        let text = system_structure(&crate::fmi::variables::table(), "test", &[]).unwrap();
        for name in MOTION_NAMES {
            assert!(text.contains(&format!(
                "startElement=\"vessel\" startConnector=\"{name}\" endElement=\"gangway\" endConnector=\"{name}\""
            )));
        }
        assert_eq!(text.matches("<ssd:Connection ").count(), 12);
        for unit in ["m", "m/s2", "rad/s", "N", "N.m", "Pa", "kg", "deg"] {
            assert!(text.contains(&format!("<ssc:Unit name=\"{unit}\">")), "{unit}");
        }
        assert!(
            text.contains("<ssc:Unit name=\"deg\">\n      <ssc:BaseUnit rad=\"1\" factor=\"0.017453292519943295\"/>")
        );
        // The irregular sea's parameters are bound, the regular wave (Hs 0) the default.
        assert!(text.contains(
            "<ssv:Parameter name=\"sea.significant_wave_height\">\n                    <ssv:Real value=\"0.0\" unit=\"m\"/>"
        ));
        assert!(text.contains(
            "<ssv:Parameter name=\"wave.period\">\n                    <ssv:Real value=\"9.0\" unit=\"s\"/>"
        ));
        assert!(text.contains("<ssv:Parameter name=\"drop_height\">"));
    }
}
