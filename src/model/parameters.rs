//! The scenario's parameters as a flat, named table: the one place the FMU's parameter
//! variables and the CLI's messages take names, units and descriptions from.

use super::discretisation::Method;
use super::scenario::Scenario;
use super::stress_recovery::StressRecovery;
use super::time_step::TimeStep;
use crate::error::{Error, Result};

/// Whether a parameter is a real number or a count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A real value in the given unit.
    Real,
    /// A whole number (element counts).
    Integer,
}

/// One scenario parameter with its accessors.
#[derive(Clone, Copy)]
pub struct Parameter {
    /// Dotted name, as in the TOML file and the FMU (`upper.length`).
    pub name: &'static str,
    /// SI unit ("" for dimensionless).
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Real or integer.
    pub kind: Kind,
    /// Reads the value (integers as exact f64).
    pub get: fn(&Scenario) -> f64,
    /// Writes the value (integers are checked by [`set`]; a value the field cannot hold, such
    /// as an unknown stress recovery index, is an error naming the parameter).
    pub put: fn(&mut Scenario, f64) -> Result<()>,
}

impl std::fmt::Debug for Parameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Parameter").field("name", &self.name).field("unit", &self.unit).finish()
    }
}

macro_rules! real {
    ($name:literal, $unit:literal, $desc:literal, $($field:ident).+) => {
        Parameter {
            name: $name,
            unit: $unit,
            description: $desc,
            kind: Kind::Real,
            get: |s| s.$($field).+,
            put: |s, v| {
                s.$($field).+ = v;
                Ok(())
            },
        }
    };
}

macro_rules! integer {
    ($name:literal, $desc:literal, $($field:ident).+) => {
        Parameter {
            name: $name,
            unit: "",
            description: $desc,
            kind: Kind::Integer,
            get: |s| f64::from(s.$($field).+),
            put: |s, v| {
                s.$($field).+ = v as u32;
                Ok(())
            },
        }
    };
}

/// Every scenario parameter, in the order of the FMU's value references.
pub const PARAMETERS: &[Parameter] = &[
    real!("drop_height", "m", "Drop height h of the bridge's centre of gravity before impact (Eq. 20)", drop_height),
    real!("contact_position", "m", "Distance d from the hinge to the bridge's contact point", contact_position),
    real!("damping_ratio", "1", "Modal damping ratio on every mode of each beam (Eq. 34)", damping_ratio),
    real!("rayleigh_alpha", "1/s", "Rayleigh mass-proportional damping added per beam", rayleigh_alpha),
    real!("rayleigh_beta", "s", "Rayleigh stiffness-proportional damping added per beam", rayleigh_beta),
    Parameter {
        name: "step_free",
        unit: "s",
        description: "Time step out of contact; 0: automatic (the largest stable, energy-safe step, at most 5e-5 s)",
        kind: Kind::Real,
        get: |s| s.step_free.as_parameter(),
        put: |s, v| {
            s.step_free = TimeStep::from_parameter(v);
            Ok(())
        },
    },
    Parameter {
        name: "step_contact",
        unit: "s",
        description: "Time step in contact; 0: automatic (the largest stable, energy-safe step, at most 2.5e-5 s)",
        kind: Kind::Real,
        get: |s| s.step_contact.as_parameter(),
        put: |s, v| {
            s.step_contact = TimeStep::from_parameter(v);
            Ok(())
        },
    },
    real!("duration", "s", "Simulated time of a CLI run", duration),
    real!("gravity", "m/s2", "Acceleration of gravity", gravity),
    real!("upper.length", "m", "Bridge length l_u", upper.length),
    real!("upper.mass", "kg", "Bridge mass m_u, uniformly distributed", upper.mass),
    real!("upper.elastic_modulus", "Pa", "Bridge Young's modulus", upper.elastic_modulus),
    real!("upper.second_moment", "m4", "Bridge second moment of area", upper.second_moment),
    real!("upper.section_modulus", "m3", "Bridge section modulus for M/W", upper.section_modulus),
    integer!(
        "upper.elements_to_contact",
        "Bridge elements from the hinge to the contact node; 0: automatic",
        upper.elements_to_contact
    ),
    integer!(
        "upper.elements_beyond_contact",
        "Bridge elements from the contact node to the free end; 0: automatic",
        upper.elements_beyond_contact
    ),
    real!("lower.length", "m", "Arrestor length l_l", lower.length),
    real!("lower.mass", "kg", "Arrestor distributed mass m_l", lower.mass),
    real!("lower.tip_mass", "kg", "Lumped mass at the arrestor's free end", lower.tip_mass),
    real!("lower.elastic_modulus", "Pa", "Arrestor Young's modulus", lower.elastic_modulus),
    real!("lower.second_moment", "m4", "Arrestor second moment of area", lower.second_moment),
    real!("lower.section_modulus", "m3", "Arrestor section modulus for M/W", lower.section_modulus),
    real!("lower.shear_area", "m2", "Arrestor shear area for Q/A_s", lower.shear_area),
    integer!("lower.elements", "Arrestor elements from the clamp to the free end; 0: automatic", lower.elements),
    real!("contact.area", "m2", "Contact bar cross-section A_c", contact.area),
    real!("contact.length", "m", "Contact bar length l_c", contact.length),
    real!("contact.elastic_modulus", "Pa", "Contact bar Young's modulus", contact.elastic_modulus),
    real!(
        "energy_tolerance",
        "1",
        "Largest energy residual of a trusted run, as a fraction of the energy that flows in it",
        energy_tolerance
    ),
    Parameter {
        name: "stress_recovery",
        unit: "",
        description:
            "Bridge moment at the contact node: 0 mean of the two adjacent elements, 1 left (hinge side), 2 right",
        kind: Kind::Integer,
        get: |s| f64::from(s.stress_recovery.index()),
        put: |s, v| {
            s.stress_recovery = StressRecovery::from_index(v)
                .ok_or_else(|| Error::invalid("stress_recovery", "0 (mean), 1 (left) or 2 (right)", v))?;
            Ok(())
        },
    },
    Parameter {
        name: "method",
        unit: "",
        description: "Solution method: 0 converged (fine mesh, truncated modal basis with static correction, \
                      checked against a coarser rung), 1 paper (7 + 7/7 elements, full modal basis)",
        kind: Kind::Integer,
        get: |s| f64::from(s.method.index()),
        put: |s, v| {
            s.method =
                Method::from_index(v).ok_or_else(|| Error::invalid("method", "0 (converged) or 1 (paper)", v))?;
            Ok(())
        },
    },
    real!(
        "modal_cutoff",
        "rad/s",
        "Modal cut-off of the converged method; 0: automatic (the ladder's rung)",
        modal_cutoff
    ),
    real!(
        "discretisation_tolerance",
        "1",
        "Largest change of a peak against the coarser discretisation, and largest spread against the run's twin",
        discretisation_tolerance
    ),
    real!(
        "lower.allowable_bending_stress",
        "Pa",
        "Arrestor allowable bending stress (paper: 533 MPa)",
        lower.allowable_bending_stress
    ),
    real!(
        "lower.allowable_shear_stress",
        "Pa",
        "Arrestor allowable shear stress (paper: 355 MPa)",
        lower.allowable_shear_stress
    ),
    real!(
        "upper.allowable_bending_stress",
        "Pa",
        "Bridge allowable bending stress (paper: 533 MPa)",
        upper.allowable_bending_stress
    ),
    real!("lower.yield_stress", "Pa", "Arrestor yield stress; 0: none given", lower.yield_stress),
    real!("upper.yield_stress", "Pa", "Bridge yield stress; 0: none given", upper.yield_stress),
];

/// Looks a parameter up by name.
pub fn find(name: &str) -> Result<&'static Parameter> {
    PARAMETERS.iter().find(|p| p.name == name).ok_or_else(|| Error::UnknownParameter(name.to_string()))
}

/// Sets a parameter, checking that integers are whole and in range (the rest is checked by
/// [`Scenario::validate`]).
pub fn set(scenario: &mut Scenario, parameter: &Parameter, value: f64) -> Result<()> {
    if parameter.kind == Kind::Integer && !(value.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&value)) {
        return Err(Error::invalid(parameter.name, "a whole number >= 0", value));
    }
    (parameter.put)(scenario, value)
}

/// `toml` (a scenario as [`Scenario::to_toml`] writes it) with each field's unit and description
/// as a comment on its line, from this table (what `beam-impact scenario` prints; a TOML reader
/// skips the comments). In TOML an automatic value is `"auto"`, where the FMU takes 0.
pub fn annotate_toml(toml: &str) -> String {
    let mut section = String::new();
    let mut out = String::new();
    for line in toml.lines() {
        let trimmed = line.trim();
        if let Some(name) = trimmed.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
            section = format!("{name}.");
        }
        let key = trimmed.split_once(" = ").map(|(k, _)| format!("{section}{}", k.trim()));
        match key.as_deref().and_then(|k| find(k).ok()) {
            Some(p) => {
                let unit = if p.unit.is_empty() { "-" } else { p.unit };
                let description = p.description.replace("0: automatic", "\"auto\": automatic");
                out.push_str(&format!("{line}  # [{unit}] {description}\n"));
            }
            None if key.as_deref().is_some_and(|k| k.ends_with(".tip_force")) => {
                out.push_str(&format!(
                    "{line}  # [N] Constant vertical force at the free end, up positive (an FMU input)\n"
                ));
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    out
}
