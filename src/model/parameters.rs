//! The scenario's parameters as a flat, named table: the one place the FMU's parameter
//! variables and the CLI's messages take names, units and descriptions from.

use super::contact_law::LawKind;
use super::discretisation::Method;
use super::scenario::{
    ImpactorKind, Scenario, SupportKind, MAX_ELEMENTS, SMALLEST_CONTACT_STIFFNESS, SMALLEST_STRESS,
    SMALLEST_YIELD_STRESS,
};
use super::stress_recovery::StressRecovery;
use super::supports::Supports;
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
    Parameter {
        name: "impact_angular_velocity",
        unit: "rad/s",
        description: "The bridge's angular velocity about its hinge at first contact, free end moving down; 0: not \
                      given (from drop_height, Eqs. 20-22; with a speed, set drop_height = 0)",
        kind: Kind::Real,
        get: |s| s.impact_angular_velocity.unwrap_or(0.0),
        put: |s, v| {
            s.impact_angular_velocity = if v == 0.0 { None } else { Some(v) };
            Ok(())
        },
    },
    Parameter {
        name: "lower.kind",
        unit: "",
        description: "What the bridge strikes: 0 the arrestor beam, 1 a rigid point (the contact element alone is the \
                      support's spring)",
        kind: Kind::Integer,
        get: |s| f64::from(s.lower.kind.index()),
        put: |s, v| {
            s.lower.kind =
                SupportKind::from_index(v).ok_or_else(|| Error::invalid("lower.kind", "0 (beam) or 1 (rigid)", v))?;
            Ok(())
        },
    },
    Parameter {
        name: "contact.stiffness",
        unit: "N/m",
        description: "The contact's rate k given directly; 0: the bar's E A_c / l_c",
        kind: Kind::Real,
        get: |s| s.contact.given_stiffness.unwrap_or(0.0),
        put: |s, v| {
            s.contact.given_stiffness = if v == 0.0 { None } else { Some(v) };
            Ok(())
        },
    },
    real!(
        "contact.clearance",
        "m",
        "A gap the bodies close after first touching before the contact acts",
        contact.clearance
    ),
    Parameter {
        name: "contact.law",
        unit: "",
        description: "The contact law: 0 linear (F = k delta, the paper's bar), 1 power (F = k delta^n, n = \
                      contact.exponent; contact.stiffness then in N/m^n), 2 hertz (a sphere of upper.radius on a \
                      flat face: k = 4/3 E* sqrt(R), n = 3/2)",
        kind: Kind::Integer,
        get: |s| f64::from(s.contact.law.index()),
        put: |s, v| {
            s.contact.law = LawKind::from_index(v)
                .ok_or_else(|| Error::invalid("contact.law", "0 (linear), 1 (power) or 2 (hertz)", v))?;
            Ok(())
        },
    },
    real!(
        "contact.exponent",
        "1",
        "The power law's exponent n; 0: not given (the power law's 1.5, Hertz; the linear law's own is 1)",
        contact.exponent
    ),
    real!(
        "contact.damping",
        "s/m",
        "Hunt and Crossley's damping c: F = k delta^n (1 + c delta'), for either law; 0: none",
        contact.damping
    ),
    real!(
        "upper.shear_area",
        "m2",
        "Bridge shear area for Q/A_s; 0: none given (the paper gives none): no shear stress for the bridge",
        upper.shear_area
    ),
    real!(
        "upper.allowable_shear_stress",
        "Pa",
        "Bridge allowable shear stress; 0: none given (the bridge's shear is not checked)",
        upper.allowable_shear_stress
    ),
    // issue 45: supports
    Parameter {
        name: "lower.supports",
        unit: "",
        description: "How the struck beam is held at its two ends (first at x = 0): 0 clamped-free (the paper's \
                      cantilever), 1 pinned-pinned, 2 clamped-clamped, 3 clamped-pinned",
        kind: Kind::Integer,
        get: |s| f64::from(s.lower.supports.index()),
        put: |s, v| {
            s.lower.supports = Supports::from_index(v).ok_or_else(|| {
                Error::invalid(
                    "lower.supports",
                    "0 (clamped-free), 1 (pinned-pinned), 2 (clamped-clamped) or 3 (clamped-pinned)",
                    v,
                )
            })?;
            Ok(())
        },
    },
    real!(
        "lower.contact_position",
        "m",
        "Where the bridge strikes the arrestor, from its first support; 0: not given (the free end of a clamped-free \
         beam, the midspan of a beam on two supports)",
        lower.contact_position
    ),
    // issue 45: rigid impactor
    Parameter {
        name: "upper.kind",
        unit: "",
        description: "What strikes: 0 the bridge (a hinged beam), 1 a rigid mass of upper.mass moving vertically (the \
                      bridge's beam fields do not apply)",
        kind: Kind::Integer,
        get: |s| f64::from(s.upper.kind.index()),
        put: |s, v| {
            s.upper.kind =
                ImpactorKind::from_index(v).ok_or_else(|| Error::invalid("upper.kind", "0 (beam) or 1 (mass)", v))?;
            Ok(())
        },
    },
    real!(
        "impact_speed",
        "m/s",
        "A rigid mass's downward speed at first contact; 0: not given (from drop_height, v = sqrt(2 g h); with a \
         speed, set drop_height = 0)",
        impact_speed
    ),
    real!(
        "upper.radius",
        "m",
        "The striking body's radius at the contact, for contact.law = hertz (a sphere on a flat face); 0: not given",
        upper.radius
    ),
    real!(
        "upper.poisson_ratio",
        "1",
        "Poisson's ratio of the striking body, for contact.law = hertz (default 0.3)",
        upper.poisson_ratio
    ),
    real!(
        "lower.poisson_ratio",
        "1",
        "Poisson's ratio of the struck beam, for contact.law = hertz (default 0.3)",
        lower.poisson_ratio
    ),
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

/// Each field's accepted range (`min`, `max`), declared as the FMU parameters' `min` and `max`
/// and printed by `beam-impact scenario`: exactly the ranges
/// [`Scenario::validate`] accepts (checked at and beyond each bound by
/// `tests/fmi_description.rs`), so an importer that honours them never meets an
/// initialization error for a value out of range. Where the rule depends on another parameter
/// the declared bound is the widest one and the rest is checked at initialization:
/// `drop_height` is at most half of `upper.length` (500 m at its largest),
/// `contact_position` is below `upper.length` (a bound FMI cannot express: no `max`). The step
/// sizes' range 0..1 s holds a gap: 0 is "automatic", otherwise at least 1e-9 s; so do the
/// bridge's shear area and allowable shear stress (issue 30): 0 is "none given", otherwise at
/// least 1e-12 m^2 and 1e-3 Pa.
pub const RANGES: &[(&str, Option<f64>, Option<f64>)] = &[
    ("drop_height", Some(0.0), Some(500.0)),
    ("contact_position", Some(SMALLEST_POSITIVE), None),
    ("damping_ratio", Some(0.0), Some(0.999)),
    ("rayleigh_alpha", Some(0.0), Some(1e4)),
    ("rayleigh_beta", Some(0.0), Some(1.0)),
    ("step_free", Some(0.0), Some(1.0)),
    ("step_contact", Some(0.0), Some(1.0)),
    ("gravity", Some(0.0), Some(100.0)),
    ("upper.length", Some(0.01), Some(1e3)),
    ("upper.mass", Some(1e-3), Some(1e9)),
    ("upper.elastic_modulus", Some(1e6), Some(1e13)),
    ("upper.second_moment", Some(1e-12), Some(1e3)),
    ("upper.section_modulus", Some(1e-12), Some(1e3)),
    ("upper.elements_to_contact", Some(0.0), Some(MAX_ELEMENTS as f64)),
    ("upper.elements_beyond_contact", Some(0.0), Some(MAX_ELEMENTS as f64)),
    ("lower.length", Some(0.01), Some(1e3)),
    ("lower.mass", Some(1e-3), Some(1e9)),
    ("lower.tip_mass", Some(0.0), Some(1e9)),
    ("lower.elastic_modulus", Some(1e6), Some(1e13)),
    ("lower.second_moment", Some(1e-12), Some(1e3)),
    ("lower.section_modulus", Some(1e-12), Some(1e3)),
    ("lower.shear_area", Some(1e-12), Some(1e3)),
    ("lower.elements", Some(0.0), Some(MAX_ELEMENTS as f64)),
    ("contact.area", Some(1e-12), Some(1e3)),
    ("contact.length", Some(1e-6), Some(1e3)),
    ("contact.elastic_modulus", Some(1e6), Some(1e13)),
    ("energy_tolerance", Some(SMALLEST_POSITIVE), Some(1.0)),
    ("stress_recovery", Some(0.0), Some(2.0)),
    ("method", Some(0.0), Some(1.0)),
    ("modal_cutoff", Some(0.0), Some(1e12)),
    ("discretisation_tolerance", Some(SMALLEST_POSITIVE), Some(1.0)),
    ("lower.allowable_bending_stress", Some(1e-3), Some(1e12)),
    ("lower.allowable_shear_stress", Some(1e-3), Some(1e12)),
    ("upper.allowable_bending_stress", Some(1e-3), Some(1e12)),
    ("lower.yield_stress", Some(0.0), Some(1e12)),
    ("upper.yield_stress", Some(0.0), Some(1e12)),
    ("impact_angular_velocity", Some(0.0), Some(crate::model::scenario::MAX_IMPACT_ANGULAR_VELOCITY)),
    ("lower.kind", Some(0.0), Some(1.0)),
    ("contact.stiffness", Some(0.0), Some(crate::model::scenario::MAX_POWER_LAW_STIFFNESS)),
    ("contact.clearance", Some(0.0), Some(10.0)),
    ("contact.law", Some(0.0), Some(2.0)),
    ("contact.exponent", Some(0.0), Some(3.0)),
    ("contact.damping", Some(0.0), Some(1e3)),
    ("upper.shear_area", Some(0.0), Some(1e3)),
    ("upper.allowable_shear_stress", Some(0.0), Some(1e12)),
    ("lower.supports", Some(0.0), Some(3.0)),
    ("lower.contact_position", Some(0.0), Some(1e3)),
    // issue 45: rigid impactor
    ("upper.kind", Some(0.0), Some(1.0)),
    ("impact_speed", Some(0.0), Some(crate::model::rigid_impactor::MAX_IMPACT_SPEED)),
    ("upper.radius", Some(0.0), Some(crate::model::rigid_impactor::RADIUS_RANGE.1)),
    ("upper.poisson_ratio", Some(0.0), Some(crate::model::rigid_impactor::MAX_POISSON_RATIO)),
    ("lower.poisson_ratio", Some(0.0), Some(crate::model::rigid_impactor::MAX_POISSON_RATIO)),
];

/// The smallest positive f64: a lower bound "> 0" in the FMU's `min` (FMI has no exclusive bound).
pub const SMALLEST_POSITIVE: f64 = f64::from_bits(1);

/// The accepted range of a field, (`min`, `max`), `None` where unbounded or not listed.
pub fn range(name: &str) -> (Option<f64>, Option<f64>) {
    RANGES.iter().find(|(n, _, _)| *n == name).map_or((None, None), |&(_, min, max)| (min, max))
}

/// Fields whose accepted values are 0, a setting of its own ("auto", none given, the bar's own
/// rate, not given), or from a smallest nonzero value up to the range's `max`: a gap FMI's
/// `min` / `max` cannot declare, so the FMU's description of each states it (see [`range_note`]);
/// the numbers are the constants [`Scenario::validate`] checks with (`MIN_STEP`, `SMALLEST_*`).
pub const NONZERO_MINIMA: &[(&str, f64)] = &[
    ("step_free", crate::model::scenario::MIN_STEP),
    ("step_contact", crate::model::scenario::MIN_STEP),
    ("upper.elements_to_contact", 1.0),
    ("upper.elements_beyond_contact", 1.0),
    ("lower.elements", 1.0),
    ("upper.shear_area", 1e-12),
    ("upper.allowable_shear_stress", SMALLEST_STRESS),
    ("lower.yield_stress", SMALLEST_YIELD_STRESS),
    ("upper.yield_stress", SMALLEST_YIELD_STRESS),
    ("contact.stiffness", SMALLEST_CONTACT_STIFFNESS),
    ("contact.exponent", crate::model::contact_law::EXPONENT_RANGE.0),
    ("upper.radius", crate::model::rigid_impactor::RADIUS_RANGE.0),
];

/// The smallest nonzero value a field accepts where 0 is a setting of its own
/// ([`NONZERO_MINIMA`]).
pub fn nonzero_minimum(name: &str) -> Option<f64> {
    NONZERO_MINIMA.iter().find(|(n, _)| *n == name).map(|&(_, m)| m)
}

/// The rules a field's range involves another field in, which FMI's `min` / `max` cannot say:
/// each as [`range_text`] adds it, and in the FMU parameter's description.
pub const CONDITIONS: &[(&str, &str)] = &[
    ("drop_height", "at most upper.length / 2 (a mass: 500)"),
    ("contact_position", "at most upper.length (its free end)"),
    ("gravity", "0 only with impact_angular_velocity (a mass: impact_speed) given"),
    ("contact.exponent", "only 0 or 1 with contact.law = \"linear\""),
    (
        "contact.stiffness",
        "at most 4e10 N/m with contact.law = \"linear\" (1e13 N/m^n: the power law's, whose tangent at 4 times the \
         impact's energy is at most 4e10 N/m)",
    ),
    ("upper.radius", "with contact.law = \"hertz\", Hertz's tangent at 4 times the impact's energy at most 4e10 N/m"),
    ("contact.area", "with contact.law = \"linear\" and no contact.stiffness, E A_c / l_c at most 4e10 N/m"),
    ("contact.length", "with contact.law = \"linear\" and no contact.stiffness, E A_c / l_c at most 4e10 N/m"),
    ("contact.elastic_modulus", "with contact.law = \"linear\" and no contact.stiffness, E A_c / l_c at most 4e10 N/m"),
    ("lower.contact_position", "at most lower.length; below it on two supports"),
];

/// A bound as the ranges print it: "1e-12", "1e6", "0.01", "1000" ("0" for the smallest
/// positive f64, the bound of "> 0").
fn bound_text(x: f64) -> String {
    if x == SMALLEST_POSITIVE {
        "0".to_string()
    } else if x != 0.0 && (x.abs() >= 1e6 || x.abs() < 1e-3) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// A range as a comment reads it: "0 to 500", "> 0", "0 (none), or 1e3 to 1e12", with the rules
/// that involve another field ([`CONDITIONS`]); none for the named choices (`method`,
/// `stress_recovery`, `lower.kind`, `contact.law`), whose description lists them. Built from
/// [`RANGES`], [`NONZERO_MINIMA`] and [`CONDITIONS`], the numbers validation takes.
pub fn range_text(name: &str) -> Option<String> {
    let zero = |name: &str| match name {
        "step_free" | "step_contact" | "modal_cutoff" => "\"auto\"",
        _ if name.contains("elements") => "\"auto\"",
        "contact.stiffness" => "0 (the bar's E A_c / l_c)",
        "contact.exponent" => "0 (not given: 1.5 with the power law)",
        _ => "0 (none)",
    };
    let base = match name {
        "method" | "stress_recovery" | "lower.kind" | "contact.law" | "lower.supports" | "upper.kind" => return None,
        "modal_cutoff" => "\"auto\", or > 0 up to 1e12".to_string(),
        // A CLI field (the FMU's stop time is the importer's): Scenario::validate's bound.
        "duration" => "> 0, at most 1e6".to_string(),
        _ => match (range(name), nonzero_minimum(name)) {
            ((Some(_), Some(max)), Some(gap)) => {
                format!("{}, or {} to {}", zero(name), bound_text(gap), bound_text(max))
            }
            ((Some(min), Some(max)), None) if min == SMALLEST_POSITIVE => format!("> 0, at most {}", bound_text(max)),
            ((Some(min), Some(max)), None) => format!("{} to {}", bound_text(min), bound_text(max)),
            ((Some(min), None), _) if min == SMALLEST_POSITIVE => "> 0".into(),
            ((Some(min), None), _) => format!(">= {}", bound_text(min)),
            ((None, Some(max)), _) => format!("<= {}", bound_text(max)),
            ((None, None), _) => return None,
        },
    };
    Some(match CONDITIONS.iter().find(|(n, _)| *n == name) {
        Some((_, rule)) => format!("{base}; {rule}"),
        None => base,
    })
}

/// What an FMU parameter's description adds to its declared `min` / `max`: its [`range_text`]
/// where a gap ([`NONZERO_MINIMA`]) or a rule ([`CONDITIONS`]) makes it more than they say, with
/// the FMU's 0 for TOML's "auto".
pub fn range_note(name: &str) -> Option<String> {
    let more = nonzero_minimum(name).is_some() || CONDITIONS.iter().any(|(n, _)| *n == name);
    more.then(|| range_text(name)).flatten().map(|r| format!("; range {}", r.replace("\"auto\"", "0 (automatic)")))
}

/// A field's comment in `beam-impact scenario`: its unit, description and range.
fn annotation(p: &Parameter) -> String {
    let unit = if p.unit.is_empty() { "-" } else { p.unit };
    let description = p.description.replace("0: automatic", "\"auto\": automatic");
    let range = range_text(p.name).map_or_else(String::new, |r| format!("; range {r}"));
    format!("[{unit}] {description}{range}")
}

/// Fields of a section that a scenario leaves out unless given, with an example value.
const OPTIONAL_FIELDS: [(&str, &str); 14] = [
    ("upper.kind", "\"mass\""),
    ("upper.radius", "0.035"),
    ("upper.poisson_ratio", "0.3"),
    ("upper.shear_area", "0.012"),
    ("upper.allowable_shear_stress", "355e6"),
    ("lower.poisson_ratio", "0.3"),
    ("lower.kind", "\"rigid\""),
    ("contact.stiffness", "2.8e10"),
    ("contact.clearance", "0.001"),
    ("contact.law", "\"power\""),
    ("contact.exponent", "1.5"),
    ("contact.damping", "0.2"),
    ("lower.supports", "\"pinned-pinned\""),
    ("lower.contact_position", "6.0"),
];

/// Whether section `[name]` of `toml` sets `key`.
fn section_has(toml: &str, name: &str, key: &str) -> bool {
    toml.parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get(name).and_then(|s| s.as_table()).map(|s| s.contains_key(key)))
        .unwrap_or(false)
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
            out.push_str(line);
            out.push('\n');
            // Optional fields (absent when not given) are shown commented out, with an example.
            for (field, example) in OPTIONAL_FIELDS {
                let key = field.strip_prefix(section.as_str());
                let given = |k: &str| section_has(toml, name, k);
                if let (Some(key), Ok(p)) = (key, find(field)) {
                    if !given(key) {
                        out.push_str(&format!("# {key} = {example}  # {}\n", annotation(p)));
                    }
                }
            }
            continue;
        }
        let key = trimmed.split_once(" = ").map(|(k, _)| format!("{section}{}", k.trim()));
        match key.as_deref().and_then(|k| find(k).ok()) {
            Some(p) => {
                out.push_str(&format!("{line}  # {}\n", annotation(p)));
                // The impact's speed, an alternative to the drop height, is shown commented out.
                if p.name == "drop_height" && !toml.lines().any(|l| l.starts_with("impact_angular_velocity = ")) {
                    let speed = find("impact_angular_velocity").expect("a parameter");
                    out.push_str(&format!("# impact_angular_velocity = 0.2  # {}\n", annotation(speed)));
                }
                // A rigid impactor's speed (issue 45), too.
                if p.name == "drop_height" && !toml.lines().any(|l| l.starts_with("impact_speed = ")) {
                    let speed = find("impact_speed").expect("a parameter");
                    out.push_str(&format!("# impact_speed = 1.0  # {}\n", annotation(speed)));
                }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `beam-impact scenario`: every field's line carries its unit and, where the scenario limits
    /// it, its range, and the annotated text still reads back to the same scenario.
    #[test]
    fn annotated_scenario_states_units_and_ranges_and_reads_back() {
        let text = annotate_toml(&Scenario::default().to_toml());
        for (name, _, _) in RANGES {
            let key = name.rsplit('.').next().unwrap_or(name);
            let line = text
                .lines()
                .find(|l| l.starts_with(&format!("{key} = ")) || l.starts_with(&format!("# {key} = ")))
                .unwrap_or_else(|| panic!("{name}"));
            assert!(line.contains("  # ["), "{name}: no unit: {line}");
            let named_choice = matches!(
                *name,
                "method" | "stress_recovery" | "lower.kind" | "contact.law" | "lower.supports" | "upper.kind"
            );
            assert_eq!(line.contains("; range "), !named_choice, "{name}: {line}");
        }
        assert!(
            text.contains("drop_height = 0.567  # [m] ") && text.contains("range 0 to 500; at most upper.length / 2")
        );
        assert!(text.contains("range 0.01 to 1000\n"), "upper.length's range");
        assert_eq!(Scenario::from_toml(&text, "annotated").unwrap(), Scenario::default());
    }
}
